"""Pictures of the game's renderer for the record: one grown tree at each level of detail, in the wind
(two moments), at night and a close-up of a joint, as the game draws them headless (EGL; on this
machine Mesa llvmpipe, so with the software-GL budget).

Then the look of the scene (:func:`look`): a tree of the game's first summer in daylight, back-lit, at night,
in autumn and in blossom, a bark close-up, a garden of three trees (one a poplar) and the title screen over
the garden, each 1280x720, as docs/look_*.png beside OUT.png.

Run: python -m benchmarks.shots [OUT.png] [DAYS]   (default docs/renderer.png, a tree grown 12 days)
     python -m benchmarks.shots --look              (the look pictures only)
"""

from __future__ import annotations

import sys
from pathlib import Path
from tempfile import TemporaryDirectory

import numpy as np

PANEL = (640, 360)


def main() -> None:
    """Render the eight panels and write them as one picture (two rows of four)."""
    import pygame
    from PIL import Image, ImageDraw

    from arbor.game.render.camera import OrbitCamera
    from arbor.game.render.garden import TWIG_PIXELS, pixel_size
    from arbor.game.render.instanced import LEAF_KEPT, Detail
    from arbor.game.render.renderer import headless_context
    from arbor.game.screens.game import Game, GameConfig
    from benchmarks.game import grown_tree

    if "--look" in sys.argv:
        for path in look(Path("docs")):
            print(f"wrote {path}")
        return
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("docs/renderer.png")
    days = float(sys.argv[2]) if len(sys.argv) > 2 else 12.0
    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(PANEL)], depth_attachment=ctx.depth_renderbuffer(PANEL))
    with TemporaryDirectory() as saves:
        clock = [1000.0]
        game = Game(ctx, PANEL, GameConfig(saves=Path(saves), seed=5, resume=False), clock=lambda: clock[0])
        game.garden.worlds[0] = grown_tree(days)
        game.world.sim.state.sun_angle = 1.1  # mid-morning
        game.hud.draw = lambda camera: None  # the scene alone
        renderer = game.renderer

        def shot() -> Image.Image:
            renderer.stage.forget()  # (drawn whole: the game's frames may bring a changed sky in over a few)
            game.draw(fbo)
            pixels = np.frombuffer(fbo.read(components=3), np.uint8).reshape(PANEL[1], PANEL[0], 3)[::-1]
            return Image.fromarray(pixels.copy())

        panels = []
        game.rules.wind.strength = 0.0
        shot()
        for lod in range(4):
            placed = renderer.placed[0]
            per_pixel = pixel_size(placed.buffers, placed.offset, game.camera(), PANEL[1])
            renderer._detail = (lambda buffers, *a, lod=lod, px=per_pixel:
                                Detail.of(buffers, lod, TWIG_PIXELS[lod] * px, LEAF_KEPT[lod]))
            panels.append((shot(), f"level {lod}"))
        del renderer._detail
        game.rules.wind.strength = 3.0
        panels.append((shot(), "wind, t"))
        clock[0] += 1.3
        panels.append((shot(), "wind, t + 1.3 s"))
        game.rules.wind.strength = 0.0
        game.world.sim.state.sun_angle = 4.7
        panels.append((shot(), "night"))
        game.world.sim.state.sun_angle = 1.1
        view = renderer.placed[0].buffers.view
        tubes = view.tubes.data
        row = tubes[np.argmax((tubes[:, 25] == 1) * (1.0 / (1.0 + tubes[:, 1])))]  # the lowest first branch
        joint, reach = row[0:3].copy(), max(30.0 * float(row[18]), 0.3)  # (its start; 30 radii away)
        game.view.camera = lambda: OrbitCamera(yaw=35.0, pitch=10.0, distance=reach, target=joint)
        panels.append((shot(), "joint, close"))
    sheet = Image.new("RGB", (PANEL[0] * 4, PANEL[1] * 2))
    for k, (image, label) in enumerate(panels):
        ImageDraw.Draw(image).text((10, 10), label, fill=(255, 255, 255))
        sheet.paste(image, ((k % 4) * PANEL[0], (k // 4) * PANEL[1]))
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"wrote {out}")
    for path in look(out.parent):
        print(f"wrote {path}")
    ctx.release()



LOOK = (1280, 720)
SPRING = 28.5  # a day of the game's tree's second spring, in blossom


def _seasons():
    from arbor.engine.life.plant import seasons
    from arbor.engine.life.rules.rules import load_rules
    from arbor.game.paths import ASSETS

    return seasons, load_rules(ASSETS / "rules.toml", pace="demo")


def summer_day() -> float:
    """The last half day of the first year before the leaves begin to turn (the fullest green crown), by
    the demo pace's seasons."""
    seasons, rules = _seasons()
    day = 0.5
    while seasons.autumn_colour(day + 0.5, rules) == 0.0 and day < SPRING:
        day += 0.5
    return day


def autumn_day() -> float:
    """The half day of the first autumn with the most coloured leaves still on (colour x share kept)."""
    seasons, rules = _seasons()
    days = np.arange(summer_day(), SPRING, 0.5)
    return float(max(days, key=lambda d: seasons.autumn_colour(d, rules) * seasons.leaf_keep(d, rules)))


def _grow(days: float, seed: int, world=None, species: str = "game_tree"):
    """A world of the game's tree (or another ``species``' .lsys) grown to ``days`` simulated days by a
    careful player (or ``world`` grown on to that day)."""
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.actions import Action
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem
    from arbor.game.paths import ASSETS

    if world is None:
        rules = load_rules(ASSETS / "rules.toml", pace="demo")
        world = World(load_lsystem(ASSETS / "lsystems" / f"{species}.lsys"), rules, seed=seed)
        world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    while world.sim.state.sun_turns < days:
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
    return world


class _Looks:
    """The game's renderer drawing placed trees headless at LOOK size into PNGs."""

    def __init__(self, folder: Path) -> None:
        from arbor.game.render.garden import GardenRenderer
        from arbor.game.render.renderer import headless_context

        self.folder, self.paths = folder, []
        self.ctx = headless_context()
        self.fbo = self.ctx.framebuffer(color_attachments=[self.ctx.renderbuffer(LOOK)],
                                        depth_attachment=self.ctx.depth_renderbuffer(LOOK))
        self.renderer = GardenRenderer(self.ctx)

    def placed(self, world, offset=(0.0, 0.0, 0.0)):
        """``world``'s tree as the game draws it (records uploaded), standing at ``offset``."""
        from arbor.engine.life.form.growth_view import GrowthView
        from arbor.game.render.garden import Placed
        from arbor.game.render.instanced import TreeBuffers
        from arbor.game.render.species import look_of

        view = GrowthView(world.tree.lstring, world.clocks(), world.tree.geometry_constants)
        buffers = TreeBuffers()
        self.renderer.trees.sync(buffers, view)
        return Placed(buffers, np.array(offset, float),
                      look=look_of(world.lineage.species, world.tree.system.constants))

    def rock(self):
        """The rock Garden -> Place a rock puts second beside the tree at the origin (game/screens/care.py)."""
        from arbor.game.render.garden import Placed
        from arbor.game.render.instanced import TreeBuffers
        from arbor.game.render.roots import rocks_view

        buffers = TreeBuffers()
        self.renderer.trees.sync(buffers, rocks_view([(2.6 * np.cos(3.0), 0.5, 2.6 * np.sin(3.0), 1.4)]))
        return Placed(buffers, np.zeros(3), -3)

    def camera(self, trees: list, yaw: float, pitch: float = 8.0, fill: float = 0.8):
        """An orbit camera framing ``trees``."""
        from arbor.game.render.camera import OrbitCamera

        camera = OrbitCamera(yaw=yaw, pitch=pitch)
        lo = np.min([np.asarray(p.buffers.view.lo) + p.offset for p in trees], axis=0)
        hi = np.max([np.asarray(p.buffers.view.hi) + p.offset for p in trees], axis=0)
        camera.frame_bounds(lo, hi, LOOK[0] / LOOK[1], fill=fill)
        return camera

    def shot(self, name: str, camera, sun: np.ndarray, trees: list, world) -> None:
        """Draw ``trees`` as the game would on ``world``'s day (its season's colours) into look_NAME.png."""
        from PIL import Image

        from arbor.engine.life.plant import seasons

        r = self.renderer
        turns = world.sim.state.sun_turns
        r.autumn, r.leaf_keep = seasons.autumn_colour(turns, world.rules), seasons.leaf_keep(turns, world.rules)
        r.time = 10.0
        r.place(trees, trees[0].buffers.view.lo, trees[0].buffers.view.hi)
        r.render(self.fbo, camera, sun, LOOK)
        pixels = np.frombuffer(self.fbo.read(components=3), np.uint8).reshape(LOOK[1], LOOK[0], 3)[::-1]
        self.paths.append(self.folder / f"look_{name}.png")
        Image.fromarray(pixels.copy()).save(self.paths[-1])


def look(folder: Path) -> list[Path]:
    """The look of the game's scene at 1280x720, through the game's own renderer (headless): one tree
    in daylight, back-lit, at night, in autumn and in blossom, a bark close-up, and a garden of three
    trees. Writes look_*.png into ``folder`` and returns their paths."""
    import pygame

    from arbor.game.render.camera import OrbitCamera
    from arbor.game.render.renderer import sun_direction

    pygame.init()
    folder.mkdir(parents=True, exist_ok=True)
    looks = _Looks(folder)
    summer = summer_day()
    world = _grow(summer, 3)
    others = [_grow(summer, 8, species="game_poplar"), _grow(summer * 0.7, 12)]  # (a poplar: its own look)
    tree = looks.placed(world)
    one = [tree]
    view = tree.buffers.view
    print(f"tree after {summer:g} days: {len(view.tubes):,} segments, {len(view.leaves):,} leaf cards")
    looks.shot("day", looks.camera(one, 30.0), sun_direction(85.0, 40.0), one, world)
    looks.paths.append(edges_shot(looks, one, world))
    looks.shot("backlit", looks.camera(one, 30.0, 4.0), sun_direction(210.0, 14.0), one, world)
    looks.shot("night", looks.camera(one, 30.0, 2.0), sun_direction(40.0, -10.0), one, world)  # (the moon: opposite)
    tubes = view.tubes.data
    foot = tubes[np.argmin(tubes[:, 1])]
    reach = float(foot[18]) * 9.0
    close = OrbitCamera(yaw=30.0, pitch=12.0, distance=reach, target=foot[0:3] + np.array([0.0, reach * 0.3, 0.0]))
    looks.shot("bark", close, sun_direction(75.0, 35.0), [*one, looks.rock()], world)  # (and a rock beside it)
    garden = one + [looks.placed(w, offset) for w, offset in zip(others, ([-15.0, 0.0, 3.0], [18.0, 0.0, -16.0]),
                                                                   strict=True)]
    looks.shot("garden", looks.camera(garden, 20.0, 10.0, 0.9), sun_direction(80.0, 38.0), garden, world)
    for day, name in ((autumn_day(), "autumn"), (SPRING, "blossom")):
        world = _grow(day, 3, world)
        seen = [looks.placed(world)]
        v = seen[0].buffers.view
        print(f"day {day:g}: {len(v.leaves):,} leaf cards, {len(v.blossoms):,} blossoms, {len(v.fruits):,} fruit")
        looks.shot(name, looks.camera(seen, 30.0), sun_direction(85.0, 35.0), seen, world)
    looks.paths.append(title_shot(looks.ctx, folder, _grow(summer, 3)))
    looks.renderer.release()
    looks.ctx.release()
    return looks.paths


def edges_shot(looks: _Looks, trees: list, world) -> Path:
    """The top of the day's crown at 3x, drawn without and with the software GL's edge smoothing (left and
    right), as look_edges.png (on a multisampled GL both halves are the same)."""
    from PIL import Image

    from arbor.game.render.renderer import sun_direction

    renderer, halves = looks.renderer, []
    kept = renderer.fxaa
    for smooth in (False, True):
        renderer.fxaa = smooth
        looks.shot("edges", looks.camera(trees, 30.0), sun_direction(85.0, 40.0), trees, world)
        picture = Image.open(looks.paths.pop())
        halves.append(picture.crop((LOOK[0] // 2 - 160, 110, LOOK[0] // 2 + 40, 330)).resize((600, 660), Image.NEAREST))
    renderer.fxaa = kept
    sheet = Image.new("RGB", (1210, 660), (255, 255, 255))
    sheet.paste(halves[0], (0, 0))
    sheet.paste(halves[1], (610, 0))
    path = looks.folder / "look_edges.png"
    sheet.save(path)
    return path


def title_shot(ctx, folder: Path, world) -> Path:
    """The title screen over a garden whose tree is ``world`` (the game itself, headless), as look_title.png."""
    from PIL import Image

    from arbor.game.screens.game import Game, GameConfig

    with TemporaryDirectory() as saves:
        clock = [1000.0]
        game = Game(ctx, LOOK, GameConfig(saves=Path(saves), seed=3, resume=False, title=True),
                    clock=lambda: clock[0])
        game.garden.worlds[0] = world
        game.state.remember()
        fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(LOOK)], depth_attachment=ctx.depth_renderbuffer(LOOK))
        game.draw(fbo)
        pixels = np.frombuffer(fbo.read(components=3), np.uint8).reshape(LOOK[1], LOOK[0], 3)[::-1]
        path = folder / "look_title.png"
        Image.fromarray(pixels.copy()).save(path)
        game.renderer.release()
    return path


if __name__ == "__main__":
    main()
