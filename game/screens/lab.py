"""The lab screen: 2-4 trees side by side, grown in lock-step, with live charts underneath; trees that share
a plot (an experiment with ``spacing``: the competition lesson) stand together in one scene, lit from the
front (the Light button, or L, shows them under the simulation's own sun), each one's name and state beneath it.

Large touch buttons choose the speed (pause, 1x, 10x, 100x) and export the run (CSV, a PNG of the
screen and of the charts, and a save of every tree) into results/<experiment>-<time>/. The lab's window
runs it as the one screen of a screen stack (game/screens/stack.py, game/app.py).
"""

from __future__ import annotations

import time
from pathlib import Path

import moderngl
import numpy as np
import pygame

from arbor.engine.life.experiment.lab import Lab, save_stem
from arbor.engine.life.keep.save import SavedGarden, write_garden
from arbor.game.input.events import DOWN, KEY_DOWN, InputEvent
from arbor.game.loop import SPEEDS, FixedStepLoop
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.charts import COLORS, draw_charts
from arbor.game.render.figures import lab_charts
from arbor.game.render.plot_scene import PlotScene, tree_state
from arbor.game.render.renderer import Overlay, TreeRenderer, save_png
from arbor.game.screens.stack import Screen, quit_asked

SCENE_FRACTION = 0.55
BUTTON_H = 56
LABEL_W = 130  # pixels a tree's label in the plot's scene needs at least (its state on lines of their own)


class LabScreen(Screen):
    """Draws and drives a :class:`Lab` in a window (or headless, in tests)."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], lab: Lab, results: Path = Path("results"),
                 clock=time.monotonic) -> None:
        self.ctx, self.size, self.lab, self.results, self.clock = ctx, size, lab, results, clock
        self.loop = FixedStepLoop(dt=lab.experiment.dt, speed=10.0)
        self.plot = PlotScene(ctx) if lab.experiment.spacing else None  # (trees sharing a plot: one scene)
        self.renderers = [] if self.plot else [TreeRenderer(ctx) for _ in lab.worlds]
        self.front_lit = True  # the plot's scene lit from the front (False: the simulation's sun)
        self.overlay = Overlay(ctx, size)
        pygame.font.init()
        self.font = pygame.font.Font(None, 36)
        self.small = pygame.font.Font(None, 28)
        self.surface = pygame.Surface(size, pygame.SRCALPHA)
        self.buttons = self._layout_buttons()
        self.message = ""
        self._shown: list[tuple | None] = [None] * len(lab.worlds)  # what each renderer holds

    def _layout_buttons(self) -> dict[str, pygame.Rect]:
        labels = ["Pause", "1x", "10x", "100x", "Export", *(["Light"] if self.plot else [])]
        w = 120
        y = int(self.size[1] * SCENE_FRACTION) - BUTTON_H - 10
        return {name: pygame.Rect(self.size[0] - (len(labels) - i) * (w + 10), y, w, BUTTON_H)
                for i, name in enumerate(labels)}

    def handle(self, e: InputEvent) -> InputEvent | None:
        """Taps on the buttons, keys 0-3 and E; a quit (the window's close, or Esc) is left over."""
        if (asked := quit_asked(e)) is not None:
            return asked
        if e.kind == DOWN and e.dims == 2:
            for name, rect in self.buttons.items():
                if rect.collidepoint(e.x, e.y):
                    self.press(name)
        elif e.kind == KEY_DOWN and pygame.K_0 <= e.key <= pygame.K_3:
            self.loop.speed = SPEEDS[e.key - pygame.K_0]
        elif e.kind == KEY_DOWN and e.key == pygame.K_e:
            self.press("Export")
        elif e.kind == KEY_DOWN and e.key == pygame.K_l and self.plot:
            self.press("Light")
        return None

    def press(self, name: str) -> None:
        """A button: a speed, or export."""
        speeds = {"Pause": 0.0, "1x": 1.0, "10x": 10.0, "100x": 100.0}
        if name in speeds:
            self.loop.speed = speeds[name]
        elif name == "Export":
            folder = self.export()
            self.message = f"Exported to {folder}"
        elif name == "Light":
            self.front_lit = not self.front_lit
            self.message = "Lit from the front" if self.front_lit else "Lit by the simulation's sun"

    def update(self, real_seconds: float) -> None:
        """Advance all trees together (stops at the experiment's duration)."""
        if self.lab.time >= self.lab.experiment.duration:
            self.loop.speed = 0.0
        self.loop.advance(real_seconds, lambda dt: self.lab.step())

    def draw(self, fbo: moderngl.Framebuffer) -> None:
        """Trees side by side on top (or the plot's one scene), charts and buttons below."""
        w, h = self.size
        scene_h = int(h * SCENE_FRACTION)
        if self.plot:
            fbo.use()
            fbo.clear(0.92, 0.92, 0.89, 1.0)
            sun = None if self.front_lit else self.lab.worlds[0].sim.sun_direction()
            self.plot.render(fbo, self.lab.worlds, (w, scene_h), (0, h - scene_h, w, scene_h), sun)
            self.overlay.draw(self._overlay(scene_h, w))
            return
        n = len(self.renderers)
        tile_w = w // n
        for i, (world, renderer) in enumerate(zip(self.lab.worlds, self.renderers, strict=True)):
            clocks = world.clocks()
            key = (id(world.tree.lstring), clocks.length_time, clocks.girth_time, clocks.wilt)
            if key != self._shown[i]:  # rebuild only trees that changed (nothing, while paused)
                renderer.set_tree(world.tree.geometry(clocks).mesh)
                self._shown[i] = key
        tallest = max(2.0, *(float(r.hi[1]) for r in self.renderers))
        fbo.use()
        fbo.clear(0.92, 0.92, 0.89, 1.0)
        for i, (world, renderer) in enumerate(zip(self.lab.worlds, self.renderers, strict=True)):
            if renderer.radius < tallest * 0.6:  # one ground and shadow scale for all trees
                renderer.radius = tallest * 0.6
                renderer._make_ground()
            camera = OrbitCamera(yaw=30.0, pitch=10.0)
            half = tallest * 0.35
            camera.frame_bounds(np.array([-half, 0.0, -half]), np.array([half, tallest, half]), tile_w / scene_h)
            viewport = (i * tile_w, h - scene_h, tile_w, scene_h)
            renderer.render(fbo, camera, world.sim.sun_direction(), (tile_w, scene_h), viewport)
        self.overlay.draw(self._overlay(scene_h, tile_w))

    def _overlay(self, scene_h: int, tile_w: int) -> bytes:
        s = self.surface
        s.fill((0, 0, 0, 0))
        pygame.draw.rect(s, (235, 235, 228, 255), (0, scene_h, self.size[0], self.size[1] - scene_h))
        draw_charts(s, pygame.Rect(0, scene_h, self.size[0], self.size[1] - scene_h), self.lab.series)
        if self.plot:
            self._plot_labels(s, scene_h)
        for i, regime in enumerate([] if self.plot else self.lab.experiment.regimes):
            label = self.font.render(regime.name, True, (255, 255, 255))
            box = pygame.Rect(i * tile_w + 12, 12, label.get_width() + 24, 44)
            pygame.draw.rect(s, (*COLORS[i % len(COLORS)], 220), box, border_radius=8)
            s.blit(label, (box.left + 12, box.top + 8))
            state = self.small.render(tree_state(self.lab.worlds[i], self.lab.meters[i]), True, (255, 255, 255))
            pygame.draw.rect(s, (0, 0, 0, 150), (box.left, box.bottom + 6, state.get_width() + 24, 34), border_radius=8)
            s.blit(state, (box.left + 12, box.bottom + 12))
        days = self.lab.worlds[0].sim.state.sun_turns
        title = (f"{self.lab.experiment.title} - day {days:.1f} ({self.lab.time / 60:.1f} of "
                 f"{self.lab.experiment.duration / 60:.0f} min)")
        room = min(rect.left for rect in self.buttons.values()) - 22  # (left of the buttons, never under them)
        text = _fitting_text([self.font, self.small], title, room)
        back = pygame.Rect(12, scene_h - BUTTON_H - 10, text.get_width() + 24, BUTTON_H)
        pygame.draw.rect(s, (0, 0, 0, 140), back, border_radius=8)
        s.blit(text, (back.left + 12, back.centery - text.get_height() // 2))
        speed = {0.0: "Pause", 1.0: "1x", 10.0: "10x", 100.0: "100x"}.get(self.loop.speed)
        for name, rect in self.buttons.items():
            pygame.draw.rect(s, (70, 110, 60, 235) if name == speed else (40, 60, 38, 220), rect, border_radius=10)
            label = self.font.render(name, True, (245, 245, 240))
            s.blit(label, label.get_rect(center=rect.center))
        if self.message:
            msg = self.font.render(self.message, True, (255, 255, 255))
            pygame.draw.rect(s, (0, 0, 0, 160), msg.get_rect(topleft=(12, 70)).inflate(16, 10))
            s.blit(msg, (12, 70))
        return pygame.image.tobytes(s, "RGBA", True)

    def _plot_labels(self, s: pygame.Surface, scene_h: int) -> None:
        """Each tree's name (in its charts' colour) and state beneath it in the plot's scene (spread apart,
        in the trees' order, where the trees stand closer than their labels are wide)."""
        bases = self.plot.bases(self.lab.worlds, (self.size[0], scene_h))
        xs = _spread(bases[:, 0], min(LABEL_W, self.size[0] / max(len(bases), 1)))
        gap = float(np.min(np.diff(np.sort(xs)))) if len(xs) > 1 else float(self.size[0])
        for i, ((_, y), x, world, regime) in enumerate(zip(bases, xs, self.lab.worlds, self.lab.experiment.regimes,
                                                            strict=True)):
            label = self.font.render(regime.name, True, (255, 255, 255))
            box = label.get_rect(midtop=(int(x), min(int(y) + 10, scene_h - BUTTON_H - 110))).inflate(24, 12)
            pygame.draw.rect(s, (*COLORS[i % len(COLORS)], 220), box, border_radius=8)
            s.blit(label, label.get_rect(center=box.center))
            state = tree_state(world, self.lab.meters[i])
            lines = _fitted(state, lambda text: self.small.size(text)[0] + 24 < gap)  # (neighbours close: shorter)
            top = box.bottom + 6
            for line in lines:
                text = self.small.render(line, True, (255, 255, 255))
                under = text.get_rect(midtop=(box.centerx, top)).inflate(20, 8)
                pygame.draw.rect(s, (150, 30, 30, 200) if not world.sim.state.alive else (0, 0, 0, 150), under,
                                 border_radius=8)
                s.blit(text, text.get_rect(center=under.center))
                top = under.bottom + 2

    def export(self) -> Path:
        """CSV, a PNG of the screen, the charts (PNG and SVG) and a save of every tree."""
        stamp = time.strftime("%Y%m%d-%H%M%S")
        name = "".join(c if c.isalnum() else "_" for c in self.lab.experiment.title).strip("_").lower()
        folder = self.results / f"{name}-{stamp}"
        folder.mkdir(parents=True, exist_ok=True)
        self.lab.write_csv(folder / "results.csv")
        lab_charts(self.lab.series, folder / "charts", title=self.lab.experiment.title, colors=COLORS)
        fbo = self.ctx.simple_framebuffer(self.size)
        self.draw(fbo)
        pixels = np.frombuffer(fbo.read(components=3), np.uint8).reshape(self.size[1], self.size[0], 3)[::-1]
        save_png(pixels, folder / "screen.png")
        fbo.release()
        for world, regime in zip(self.lab.worlds, self.lab.experiment.regimes, strict=True):
            write_garden(SavedGarden([world], lsystem_name=self.lab.experiment.lsystem.name),
                         folder / f"{save_stem(regime.name)}.arbor")
        return folder


def _fitted(state: str, fits) -> list[str]:
    """``state`` ("alive, wilt 0.00, 0.58 m") on one line if it ``fits``, else its last part on a line of
    its own, else every part on its own line."""
    for lines in ([state], state.rsplit(", ", 1), state.split(", ")):
        if all(fits(line) for line in lines):
            return lines
    return lines


def _spread(xs: np.ndarray, apart: float) -> np.ndarray:
    """Label centres for trees at window columns ``xs``: their own, or, where two stand closer than
    ``apart`` pixels, all of them ``apart`` from each other in the trees' order, centred on the row."""
    if len(xs) < 2 or float(np.min(np.diff(np.sort(xs)))) >= apart:
        return np.asarray(xs, float)
    rank = np.argsort(np.argsort(xs))
    return float(np.mean(xs)) + (rank - (len(xs) - 1) / 2) * apart


def _fitting_text(fonts: list, text: str, room: int) -> pygame.Surface:
    """``text`` rendered in the first of ``fonts`` (largest first) that fits ``room`` pixels with its box's
    margins, else in the last, cut short with an ellipsis where it must be."""
    for font in fonts:
        if font.size(text)[0] + 24 <= room:
            return font.render(text, True, (255, 255, 255))
    while len(text) > 1 and fonts[-1].size(text + "…")[0] + 24 > room:
        text = text[:-1]
    return fonts[-1].render(text.rstrip() + "…", True, (255, 255, 255))
