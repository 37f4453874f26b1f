"""An artist's whole modeler session (issue 48's list), replayed in the real game headless with a shaky hand:
a trunk from the sapling's foot, two branches, three crown outlines, a moved lobe, a supertoroid region,
prune and grow in it, undo and redo, a branch made wider, a crown preset, Done, save, restart, load, a
lobe edited after the restart and an export. Every step says what the game told the player and checks
what an artist expects (no surprise); a step that does not hold is printed as SURPRISE.

Run: python -m benchmarks.artist_session [--out DIR]  (DIR: a screenshot after the crown, the branch edit
and the restart, and the exported GLB; default a temporary folder). tests/test_artist_session.py runs it.
"""

from __future__ import annotations

import os
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import numpy as np

SIZE = (1280, 720)
JITTER = 1.5  # pixels: a shaky hand on a mouse


@dataclass
class Step:
    """One step of the session: what was done, what the game said, and what did not hold ('' when all did)."""

    name: str
    said: str
    surprise: str = ""


class Session:
    """The real game, headless, driven by touch events as a player's hand gives them."""

    def __init__(self, ctx, saves: Path, resume: bool = False) -> None:
        from arbor.game.screens.game import Game, GameConfig

        self.clock = [0.0]
        self.game = Game(ctx, SIZE, GameConfig(saves=saves, seed=3, resume=resume), clock=lambda: self.clock[0])
        self.fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)],
                                   depth_attachment=ctx.depth_renderbuffer(SIZE))
        self.game.draw(self.fbo)
        self.rng = np.random.default_rng(48)

    def touch(self, kind: str, x: float, y: float, finger: int = 0) -> None:
        from arbor.game.input.events import InputEvent

        self.game.handle_input(InputEvent(kind, self.clock[0], "touch:1", finger, float(x), float(y)))

    def stroke(self, points, dt: float = 0.02, shaky: bool = True) -> None:
        """A drag through ``points`` (pixels), with the hand's jitter."""
        from arbor.game.input.events import DOWN, MOVE, UP

        points = np.asarray(points, float)
        if shaky:
            points = points + self.rng.normal(0.0, JITTER, points.shape)
        self.touch(DOWN, *points[0])
        for p in points[1:]:
            self.clock[0] += dt
            self.touch(MOVE, *p)
        self.clock[0] += dt
        self.touch(UP, *points[-1])

    def tap(self, x: float, y: float) -> None:
        from arbor.game.input.events import DOWN, UP

        self.touch(DOWN, x, y)
        self.clock[0] += 0.05
        self.touch(UP, x, y)

    def bar(self, name: str) -> None:
        """A press on the tool bar's button ``name``."""
        self.tap(*self.game.modeling.bar.widgets[name].rect.center)

    def menu(self, name: str) -> None:
        """The tap menu's button ``name`` (the menu opened by a tap on the sky)."""
        game = self.game
        game.tap(100, 100)
        self.tap(*game.menu.reveal(name).rect.center)
        if game.menu.visible:
            game.tap(1000, 700)

    def pixel(self, point) -> tuple[float, float]:
        return self.game.hud.project(self.game.camera(), tuple(float(v) for v in point))

    def said(self) -> str:
        return self.game.hud_info().message

    def shot(self, path: Path) -> None:
        from arbor.game.render.renderer import save_png

        self.game.draw(self.fbo)
        pixels = np.frombuffer(self.fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1]
        save_png(pixels, str(path))


def ellipse(cx: float, cy: float, rx: float, ry: float, n: int = 48) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi, n)
    return np.stack([cx + rx * np.cos(a), cy + ry * np.sin(a)], 1)


def check(steps: list[Step], name: str, said: str, **conditions: bool) -> None:
    """Record a step; the conditions that do not hold are its surprise."""
    failed = [what.replace("_", " ") for what, ok in conditions.items() if not ok]
    steps.append(Step(name, said, "; ".join(failed)))


def drawing(session: Session, steps: list[Step]) -> dict:
    """Open the modeler, draw a trunk and two branches, three outlines; returns what later steps use."""
    import pygame

    game = session.game
    session.menu("modeler")
    check(steps, "open the modeler", session.said(), draw_tool_lit=game.modeling.current_tool == "draw",
          bar_shown=game.modeling.bar.visible)
    segs = game.modeling.segments(game.world.tree.lstring)
    (x0, y0), (_, y1) = session.pixel((0, 0, 0)), session.pixel((0, 1.6 * segs.end[:, 1].max(), 0))
    session.stroke([(x0 + 1.5 * np.sin(i / 4), y0 + (y1 - y0) * i / 29) for i in range(30)], dt=0.01)
    check(steps, "a trunk from the sapling's foot", session.said(), became_the_trunk="trunk" in session.said())
    game.handle_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_f, mod=0, scancode=0, unicode="f"))  # frame
    x0, y0 = session.pixel((0, 0, 0))
    ls = game.world.tree.lstring
    top = float(game.modeling.segments(ls).end[:, 1].max())
    for side in (-1, 1):
        bx, by = session.pixel((0, 0.6 * top, 0))
        before = len(game.world.tree.lstring)
        session.stroke([(bx + side * 7 * i, by - 5 * i) for i in range(30)])
        check(steps, f"a branch to the {'left' if side < 0 else 'right'}", session.said(),
              joined_the_tree="joined" in session.said(), added_modules=len(game.world.tree.lstring) > before)
    session.bar("crown")
    _, ty = session.pixel((0, top, 0))
    outlines = [ellipse(x0 - 150, ty - 40, 100, 80), ellipse(x0 + 150, ty - 40, 100, 80),
                ellipse(x0, ty - 170, 110, 85)]
    for k, outline in enumerate(outlines):
        session.stroke(outline)
        check(steps, f"crown outline {k + 1}", session.said(), grew_a_crown="branch pieces" in session.said(),
              lobes_kept=game.world.crown is not None and len(game.world.crown.lobes) == k + 1)
    return {"outlines": outlines, "camera": game.camera()}


def crown_checks(session: Session, steps: list[Step], drawn: dict) -> None:
    """The crown fills its lobes and keeps its leaves within the outlines drawn."""
    from matplotlib.path import Path as Polygon

    from arbor.engine.life.form.interpret import LEAF_ASPECT, grown_turtle
    from arbor.engine.modeling.crown_fill import lobe_fill
    from arbor.game.render.camera import project_points

    world = session.game.world
    ls = world.tree.lstring
    fill = lobe_fill(list(world.crown.lobes), session.game.modeling.segments(ls))
    leaves = grown_turtle(ls, world.clocks(), world.tree.geometry_constants).leaves
    crown = ls.nparams[leaves.module] == 2
    h, lft = leaves.frame[crown][:, :, 0], leaves.frame[crown][:, :, 1]
    s = leaves.size[crown][:, None] / (1 - np.exp(-1))  # fully grown
    p = leaves.position[crown]
    corners = np.concatenate([p - lft * s * LEAF_ASPECT / 2, p + lft * s * LEAF_ASPECT / 2 + h * s])
    pixels = project_points(drawn["camera"], SIZE, corners)
    near = np.zeros(len(pixels), bool)
    for outline in drawn["outlines"]:  # within 10 % of an outline's size from it
        size = float(np.ptp(outline, axis=0).max())
        grown = Polygon(outline.mean(axis=0) + 1.2 * (outline - outline.mean(axis=0)))
        near |= grown.contains_points(pixels) & (np.linalg.norm(pixels - outline.mean(axis=0), axis=1) < size)
    check(steps, "the crown in its outlines", f"fill {' '.join(f'{f:.0%}' for f in fill)}; "
          f"{near.mean():.1%} of the leaf corners near an outline", every_lobe_filled=min(fill) >= 0.85,
          leaves_near_the_outlines=near.mean() >= 0.99)


def editing(session: Session, steps: list[Step]) -> None:
    """A moved lobe, a supertoroid region, prune and grow in it, undo and redo, a branch, a preset."""
    from arbor.engine.modeling.regions import Supertoroid

    game = session.game
    world = game.world
    session.bar("shape")
    lobe = world.crown.lobes[0]
    others = [len(world.crown.lobes[1].vertices)]
    x, y = session.pixel(lobe.vertices.mean(axis=0))
    session.stroke([(x - 6 * k, y) for k in range(11)], dt=0.05, shaky=False)
    check(steps, "move a lobe", session.said(), lobe_moved="Lobe move" in session.said(),
          other_lobes_kept=len(world.crown.lobes[1].vertices) == others[0] and world.crown.lobes[0] is not lobe)
    session.bar("symbols")
    x0, _ = session.pixel((0, 0, 0))
    _, ty = session.pixel((0, float(game.modeling.segments(world.tree.lstring).end[:, 1].max()), 0))
    for dx in (-250, -60):  # the left and right outlines of a region round the left lobe
        session.stroke([(x0 + dx + 3 * np.sin(i / 3), ty - 10 + 6 * i) for i in range(30)])
    region = game.modeling.region_tool.region
    check(steps, "a supertoroid region", session.said(), a_supertoroid=isinstance(region, Supertoroid))
    while game.modeling.edit != "prune":
        session.bar("edit")
    centre = session.pixel(region.center)
    before = world.tree.lstring
    session.tap(*centre)
    asked = "tap inside again" in session.said()
    if asked:
        session.tap(*centre)
    check(steps, "prune in it", session.said(), cut="modules cut" in session.said(),
          asked_before_cutting_drawn_work=asked or _drawn(before) == _drawn(world.tree.lstring))
    pruned = world.tree.lstring
    while game.modeling.edit != "grow":
        session.bar("edit")
    session.tap(*centre)
    check(steps, "grow in it", session.said(), something_grew=world.tree.lstring is not pruned,
          confined=world.tree.confine is region)
    grown = world.tree.lstring
    session.bar("undo")
    undone = world.tree.lstring is pruned
    session.bar("redo")
    check(steps, "undo and redo", session.said(), undo_back=undone, redo_again=world.tree.lstring is grown)
    session.bar("prune")
    session.bar("edit")
    segs = game.modeling.segments(world.tree.lstring)
    side = np.flatnonzero((world.tree.lstring.sym[segs.module] == ord("F")) & (segs.order == 1))
    px, py = session.pixel(0.5 * (segs.start[side[2]] + segs.end[side[2]]))
    session.tap(px, py)
    picked = "Picked a branch" in session.said()
    session.stroke([(900, 500 - 9 * k) for k in range(11)], dt=0.05, shaky=False)
    check(steps, "a branch made wider", session.said(), picked=picked, wider="Branch width x1.5" in session.said())
    session.bar("crown")
    session.bar("edit")
    panel = game.modeling.crown_panel
    session.tap(*panel.buttons[("preset", "")].rect.center)
    check(steps, "a crown preset", session.said(), regrown="Crown regrown with preset" in session.said(),
          style_kept=world.crown.style is not None and world.crown.style == panel.presets[panel.preset])


def _drawn(ls) -> int:
    return int(((ls.sym == ord("F")) & (ls.nparams == 11)).sum())


def keeping(session: Session, steps: list[Step], ctx, saves: Path, out: Path) -> Session:
    """Done, save, restart, load: the tree and its lobes as they were; a lobe edited again; an export."""
    import trimesh

    from arbor.game.cli import main as arbor

    game = session.game
    tree, lobes = game.world.tree.lstring.to_text(), len(game.world.crown.lobes)
    session.bar("modeler")
    check(steps, "Done", session.said(), left_the_modeler=not game.modeling.active,
          lobes_kept=game.world.crown is not None and len(game.world.crown.lobes) == lobes)
    saved = game.save()
    check(steps, "save", session.said(), saved=saved)
    again = Session(ctx, saves, resume=True)
    world = again.game.world
    check(steps, "restart and load", again.said(), same_tree=world.tree.lstring.to_text() == tree,
          same_lobes=world.crown is not None and len(world.crown.lobes) == lobes)
    again.menu("modeler")
    again.bar("shape")
    lobe = world.crown.lobes[2]
    x, y = again.pixel(lobe.vertices.mean(axis=0))
    again.stroke([(x + 5 * k, y) for k in range(11)], dt=0.05, shaky=False)
    check(steps, "a lobe edited after the restart", again.said(), lobe_moved="Lobe move" in again.said())
    again.shot(out / "session_restart.png")
    again.bar("modeler")
    again.game.save()
    glb = out / "session_tree.glb"
    status = arbor(["export", str(saves / "autosave.arbor"), "--out", str(glb), "-q"])
    scene = trimesh.load(glb)
    height = float(scene.bounds[1][1] - scene.bounds[0][1]) if status == 0 else 0.0
    check(steps, "export", f"{glb.name}: {height:.2f} m tall", exported=status == 0 and glb.is_file(),
          a_tree_sized_height=0.5 < height < 40.0)
    return again


def run(out: Path | None = None) -> list[Step]:
    """The whole session (see module docstring); screenshots and the GLB go to ``out``."""
    import pygame

    from arbor.game.render.renderer import headless_context

    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    steps: list[Step] = []
    with tempfile.TemporaryDirectory() as tmp:
        saves, out = Path(tmp) / "saves", Path(out or tmp)
        saves.mkdir()
        out.mkdir(parents=True, exist_ok=True)
        session = Session(ctx, saves)
        drawn = drawing(session, steps)
        crown_checks(session, steps, drawn)
        session.shot(out / "session_crown.png")
        editing(session, steps)
        session.shot(out / "session_edits.png")
        keeping(session, steps, ctx, saves, out)
    return steps


def main() -> None:
    """Print every step and whether it held."""
    out = Path(sys.argv[sys.argv.index("--out") + 1]) if "--out" in sys.argv else None
    steps = run(out)
    for step in steps:
        print(f"{'SURPRISE' if step.surprise else 'ok':>8}  {step.name}: {step.said}"
              + (f"  [{step.surprise}]" if step.surprise else ""))
    print(f"{sum(bool(s.surprise) for s in steps)} surprises in {len(steps)} steps")


if __name__ == "__main__":
    main()
