"""The tamagotchi game: world + fixed-step loop + touch/mouse/keyboard + menu/HUD + renderer + saves.

`Game` does not own a window: the app gives it pygame events and a framebuffer, so tests drive the real
game headless (SDL dummy video for events, an EGL context for pixels).
"""

from __future__ import annotations

import copy
import math
import time
from dataclasses import dataclass
from pathlib import Path

import moderngl
import numpy as np
import pygame

from engine.errors import LSysError
from engine.growth import Clocks, grow_geometry
from engine.lsys import load_lsystem
from engine.mesh import merge_trees
from engine.save import load_world, save_world
from engine.sim import load_rules
from engine.world import World
from game.camera import OrbitCamera, project_points
from game.gestures import CameraControl, Gestures
from game.input import (
    DEVICE,
    DOWN,
    FOCUS_LOST,
    KEY_DOWN,
    KEY_UP,
    MOVE,
    QUIT,
    ROTATE,
    UP,
    WHEEL,
    InputEvent,
    PygameTranslator,
)
from game.loop import SPEEDS, FixedStepLoop
from game.modeling import TOOLS, ModelingMode
from game.render import ASSETS, Overlay, TreeRenderer
from game.strings import text
from game.ui import HudInfo, Menu, draw_hud, draw_rain_cloud, range_to_slider, slider_to_range

ROOT = Path(__file__).resolve().parent.parent
KEY_YAW, KEY_TILT = 4.0, 3.0  # degrees per key press
MAX_GARDEN = 6  # trees in one garden
GARDEN_SPACING = 7.0  # scene units between neighbouring trees
BASE_PITCH = 8.0
HEALTHY_LEAF, WILTED_LEAF = np.array([1.0, 1.0, 1.0]), np.array([2.6, 0.85, 0.45])  # green -> yellow-brown


@dataclass
class GameConfig:
    """Where the game finds its data and keeps its saves."""

    lsystem: Path = ASSETS / "lsystems" / "game_tree.lsys"
    rules: Path = ASSETS / "rules.toml"
    saves: Path = ROOT / "saves"
    autosave_seconds: float = 60.0  # real seconds between autosaves
    resume: bool = True
    seed: int | None = None


class Game:
    """One running game; see module docstring."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], config: GameConfig | None = None,
                 clock=time.monotonic, wall_clock=time.time) -> None:
        self.config = config or GameConfig()
        self.size = size
        self.clock, self.wall_clock = clock, wall_clock
        self.rules = load_rules(self.config.rules)
        self.system = load_lsystem(self.config.lsystem)
        self.loop = FixedStepLoop(dt=0.1)
        self.control = CameraControl(distance=1.0, min_distance=0.25, max_distance=6.0)
        self.gestures = Gestures(self.control)
        self.menu = Menu(size)
        self.renderer = TreeRenderer(ctx)
        self.overlay = Overlay(ctx, size)
        pygame.font.init()
        self.font = pygame.font.Font(None, 32)
        self.small_font = pygame.font.Font(None, 24)
        self.surface = pygame.Surface(size, pygame.SRCALPHA)
        self.message, self.message_until = "", 0.0
        self.input_log: list[tuple[int, str, float]] = []
        self.menu_pointers: set[int] = set()
        self.translator = PygameTranslator(size)
        self._right_y: float | None = None
        self.cursor3d: tuple[float, float, float] | None = None
        self.devices: dict[str, str] = {}
        self.overlay_hooks: list = []  # extra overlay layers (kiosk attract text, PIN pad)
        self.modeling = ModelingMode(self)
        self.stroke_pointer: int | None = None
        self.stroke_start: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self.keys_water = False
        self.last_autosave = clock()
        self._built: tuple | None = None
        self.triangles = 0
        self.others: list[World] = []  # the rest of the garden (the cared-for tree is self.world)
        self.world = self._start_world()
        self.previous = copy.deepcopy(self.world.sim.state)
        self.alpha = 1.0
        self._sync_sliders()

    # ----- world, saves -------------------------------------------------------------------------
    @property
    def autosave_path(self) -> Path:
        """Where autosaves go (and where the game resumes from)."""
        return self.config.saves / "autosave.arbor"

    def _new_world(self) -> World:
        seed = self.config.seed if self.config.seed is not None else int(self.wall_clock() * 1000) % 2**31
        world = World(self.system, self.rules, seed=seed)
        world.apply("replant", 1.0)  # a sapling with meters at a random 25-100 %
        self.input_log = [(0, "replant", 1.0)]
        return world

    def _start_world(self) -> World:
        if self.config.resume and self.autosave_path.exists():
            world = self._load(self.autosave_path)
            if world is not None:
                for path in sorted(self.config.saves.glob("garden-*.arbor")):
                    other = self._load(path)
                    if other is not None:
                        self.others.append(other)
                return world
        return self._new_world()

    def _load(self, path: Path) -> World | None:
        try:
            world, saved_at = load_world(path, self.rules)
        except LSysError as err:
            kept = path.with_name(path.name + ".broken")
            path.replace(kept)
            self.say(text("messages.load_failed", name=path.name, error=err.message, kept=kept.name), 12)
            return None
        away = max(self.wall_clock() - saved_at, 0.0)
        day = 2 * math.pi / max(world.sim.state.sun_speed, 1e-6)
        grown = min(away, day)
        world.catch_up(grown)
        if grown > 1:
            self.say(text("messages.welcome_back", minutes=grown / 60), 6)
        return world

    def save(self, path: Path | None = None) -> bool:
        """Save the cared-for tree (atomically) and, with the autosave, the rest of the garden."""
        path = path or self.autosave_path
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            save_world(self.world, path, self.config.lsystem.name, self.wall_clock())
            if path == self.autosave_path:
                for k, other in enumerate(self.others):
                    save_world(other, path.parent / f"garden-{k}.arbor", self.config.lsystem.name, self.wall_clock())
                for stale in sorted(path.parent.glob("garden-*.arbor"))[len(self.others):]:
                    stale.unlink()
        except OSError as exc:
            self.say(text("messages.save_failed", error=exc.strerror), 6)
            return False
        self.last_autosave = self.clock()
        return True

    def say(self, text: str, seconds: float = 3.0) -> None:
        """Show a message at the bottom of the screen for a while."""
        self.message, self.message_until = text, self.clock() + seconds

    # ----- actions -------------------------------------------------------------------------------
    def act(self, action: str, value: float = 0.0) -> None:
        """Apply a player action; world actions are logged against the sim step (replayable)."""
        if action in ("water", "orbit_height", "sun_speed", "replant"):
            if action == "replant" and value == 0.0:
                return
            sim_value = self._slider_value(action, value)
            self.input_log.append((self.world.steps, action, sim_value))
            self.world.apply(action, sim_value)
            if action in ("orbit_height", "sun_speed"):  # one sun over the whole garden
                for other in self.others:
                    other.apply(action, sim_value)
            if action == "replant":
                self.previous = copy.deepcopy(self.world.sim.state)
                self.say(text("messages.planted"))
        elif action == "speed" and value:
            i = SPEEDS.index(self.loop.speed) if self.loop.speed in SPEEDS else 1
            self.set_speed(SPEEDS[(i + 1) % len(SPEEDS)])
        elif action == "save" and value:
            if self.save():
                self.say(text("messages.saved"))
        elif action == "plant" and value:
            self.plant()
        elif action == "next" and value and self.others:
            self.others.append(self.world)
            self.world = self.others.pop(0)
            self.previous = copy.deepcopy(self.world.sim.state)
            self._sync_sliders()
        elif action in TOOLS and value:
            TOOLS[action](self.modeling)
            self.menu.widget("edit").label = self.modeling.option_label()
        elif action == "edit" and value:
            self.menu.widget("edit").label = self.modeling.next_option()
        elif action == "undo" and value:
            self.modeling.undo()
        elif action == "redo" and value:
            self.modeling.redo()
        elif action == "devices" and value:
            names = sorted(self.devices) or [text("messages.no_devices")]
            self.say(text("messages.devices", names=", ".join(names)), 8)
        elif action == "load" and value:
            world = self._load(self.autosave_path) if self.autosave_path.exists() else None
            if world is not None:
                self.world, self.previous = world, copy.deepcopy(world.sim.state)
                self.say(text("messages.loaded"))

    def plant(self) -> None:
        """A new sapling in the garden, beside the others; it becomes the tree you care for."""
        if len(self.others) + 1 >= MAX_GARDEN:
            self.say(text("messages.garden_full", count=MAX_GARDEN), 5)
            return
        k = len(self.others) + 1
        angle = k * 2.39996  # golden angle: the garden spirals outwards without crowding
        radius = GARDEN_SPACING * math.sqrt(k)
        seed = (self.world.seed * 7919 + k * 104729) % 2**31
        world = World(self.system, self.rules, seed=seed)
        world.apply("replant", 1.0)
        world.apply("orbit_height", self.world.sim.state.orbit_height)
        world.apply("sun_speed", self.world.sim.state.sun_speed)
        world.position = (radius * math.cos(angle), radius * math.sin(angle))
        self.others.append(self.world)
        self.world, self.previous = world, copy.deepcopy(world.sim.state)
        self.say(text("messages.garden_planted", count=k + 1), 4)

    def _slider_value(self, action: str, value: float) -> float:
        r = self.rules.sun
        if action == "orbit_height":
            return slider_to_range(value, r.orbit_height_min, r.orbit_height_max)
        if action == "sun_speed":
            return slider_to_range(value, r.speed_min, r.speed_max, log=True)
        return value

    def _sync_sliders(self) -> None:
        r, s = self.rules.sun, self.world.sim.state
        self.menu.widget("orbit_height").value = range_to_slider(s.orbit_height, r.orbit_height_min,
                                                                 r.orbit_height_max)
        self.menu.widget("sun_speed").value = range_to_slider(s.sun_speed, r.speed_min, r.speed_max, log=True)
        speed = self.loop.speed
        self.menu.widget("speed").label = text("menu.paused") if speed == 0 else text("menu.speed", speed=f"{speed:g}")

    def set_speed(self, speed: float) -> None:
        """Time speed: 0 (pause), 1, 10 or 100."""
        self.loop.speed = speed
        self._sync_sliders()

    # ----- input ---------------------------------------------------------------------------------
    def handle_event(self, e: pygame.event.Event) -> bool:
        """Handle one pygame event (through the input layer); returns False when the game should quit."""
        keep = True
        for event in self.translator.translate(e, self.clock()):
            keep = self.handle_input(event) and keep
        return keep

    def handle_input(self, e: InputEvent) -> bool:
        """Handle one device-independent input event; returns False when the game should quit."""
        if e.device not in self.devices and e.device not in ("window", "hid") and e.amount >= 0:
            self.devices[e.device] = e.device.split(":")[0]
        if e.kind == QUIT:
            return False
        if e.kind in (DOWN, MOVE, UP):
            if e.dims == 3:
                self._pointer3d(e)
            elif e.device == "mouse" and e.button == 3:
                self._right_drag(e)
            elif e.button == 1:
                self._pointer(e.kind, hash((e.device, e.pointer)) & 0x7FFFFFFF, e.x, e.y, e.t)
        elif e.kind == WHEEL and not self.menu.visible:
            self.control.zoom(0.9**e.amount)
        elif e.kind == ROTATE and not self.menu.visible:
            self.control.turn(-e.ry)
            self.control.tilt_by(e.rx)
        elif e.kind in (KEY_DOWN, KEY_UP):
            return self._key(e.key, e.kind == KEY_DOWN)
        elif e.kind == FOCUS_LOST:
            self.gestures.cancel_all()
        elif e.kind == DEVICE:
            self.devices_changed(e)
        return True

    def devices_changed(self, e: InputEvent) -> None:
        """A device came, went or misbehaved: tell the player (never crash)."""
        if e.amount < 0:
            self.devices.pop(e.device, None)
        self.say(e.text, 5)

    def _right_drag(self, e: InputEvent) -> None:
        """The mouse's tilt gesture: vertical right-button drag."""
        if e.kind == DOWN:
            self._right_y = e.y
        elif e.kind == MOVE and not self.menu.visible and self._right_y is not None:
            self.control.tilt_by((e.y - self._right_y) * 0.25)
            self._right_y = e.y
        else:
            self._right_y = None

    def _pointer3d(self, e: InputEvent) -> None:
        """A 3D tracker's cursor (shown by the HUD); in the modeler, its button draws strokes in 3D."""
        self.cursor3d = (e.x, e.y, e.z)
        if not self.modeling.active:
            return
        if e.kind == DOWN:
            self.modeling.cancel_points()
            self.stroke_pointer = -3
        if self.stroke_pointer == -3:
            self.modeling.add3d(self.cursor3d, e.t)
            if e.kind == UP:
                self.modeling.finish()
                self.stroke_pointer = None

    def _stroke(self, kind: str, pid: int, x: float, y: float, now: float) -> bool:
        """Modeler: one pointer draws; a second pointer turns the stroke into a camera gesture."""
        if not self.modeling.active or self.menu.visible:
            return False
        if kind == DOWN and self.stroke_pointer is None and not self.gestures.pointers:
            if self.menu.hit(x, y):
                return False
            self.stroke_pointer, self.stroke_start = pid, (x, y, now)
            self.modeling.begin2d(x, y, now, self.camera())
            return True
        if kind == DOWN and self.stroke_pointer is not None:  # second finger: it was a camera gesture
            sx, sy, st = self.stroke_start
            self.modeling.cancel_points()
            self.gestures.down(self.stroke_pointer, sx, sy, st)
            self.stroke_pointer = None
            return False
        if pid != self.stroke_pointer:
            return False
        if kind == MOVE:
            self.modeling.add2d(x, y, now, self.camera())
        elif kind == UP:
            sx, sy, st = self.stroke_start
            self.stroke_pointer = None
            if now - st < 0.3 and abs(x - sx) + abs(y - sy) < 12:  # a tap: a cut, or the menu as everywhere
                self.modeling.cancel_points()
                if not (self.modeling.prune_at(x, y, self.camera()) or self.modeling.edit_at(x, y, self.camera())):
                    self._tap(x, y)
            else:
                self.modeling.finish()
        return True

    def _pointer(self, kind: str, pid: int, x: float, y: float, now: float) -> None:
        if self._stroke(kind, pid, x, y, now):
            return
        if kind == DOWN:
            if self.menu.hit(x, y):
                self.menu_pointers.add(pid)
                for action in self.menu.press(x, y):
                    self.act(*action)
            else:
                self.gestures.menu_open = self.menu.visible
                self.gestures.down(pid, x, y, now)
        elif kind == MOVE:
            if pid in self.menu_pointers:
                for action in self.menu.drag(x, y):
                    self.act(*action)
            else:
                self.gestures.move(pid, x, y, now)
        elif pid in self.menu_pointers:
            self.menu_pointers.discard(pid)
            for action in self.menu.release():
                self.act(*action)
        elif self.gestures.up(pid, x, y, now):
            self._tap(x, y)

    def _tap(self, x: float, y: float) -> None:
        if self.menu.visible:
            for action in self.menu.hide():
                self.act(*action)
        else:
            self._sync_sliders()
            self.menu.show_at(x, y)
        self.gestures.menu_open = self.menu.visible

    def _key(self, key: int, down: bool) -> bool:
        if key == pygame.K_w:
            if down != self.keys_water:
                self.keys_water = down
                self.act("water", float(down))
            return True
        if not down:
            return True
        camera_keys = {pygame.K_LEFT: (KEY_YAW, 0), pygame.K_RIGHT: (-KEY_YAW, 0),
                       pygame.K_UP: (0, KEY_TILT), pygame.K_DOWN: (0, -KEY_TILT)}
        if key == pygame.K_ESCAPE:
            return False
        if key in camera_keys and not self.menu.visible:
            yaw, tilt = camera_keys[key]
            self.control.turn(yaw)
            self.control.tilt_by(tilt)
        elif key in (pygame.K_PLUS, pygame.K_EQUALS, pygame.K_KP_PLUS) and not self.menu.visible:
            self.control.zoom(0.9)
        elif key in (pygame.K_MINUS, pygame.K_KP_MINUS) and not self.menu.visible:
            self.control.zoom(1 / 0.9)
        elif key == pygame.K_m:
            self._tap(self.size[0] * 0.6, self.size[1] * 0.2)
        elif key == pygame.K_r:
            self.act("replant", 1.0)
        elif key == pygame.K_p:
            self.set_speed(0.0 if self.loop.speed else 1.0)
        elif key in (pygame.K_1, pygame.K_2, pygame.K_3):
            self.set_speed(SPEEDS[key - pygame.K_1 + 1])
        elif key == pygame.K_F5:
            self.act("save", 1.0)
        elif key == pygame.K_F9:
            self.act("load", 1.0)
        return True

    # ----- frame ---------------------------------------------------------------------------------
    def update(self, real_seconds: float) -> None:
        """Advance the simulation by one frame's worth of fixed steps; autosave when due."""
        def step(dt: float) -> None:
            self.previous = copy.copy(self.world.sim.state)
            self.world.step(dt)
            for other in self.others:
                other.step(dt)

        self.alpha = self.loop.advance(real_seconds, step)
        if self.clock() - self.last_autosave >= self.config.autosave_seconds:
            self.save()

    def clocks(self) -> Clocks:
        """Growth clocks to draw: interpolated between the last two sim states."""
        return self.world.clocks(self.previous, self.alpha)

    def camera(self) -> OrbitCamera:
        """The orbit camera for this frame: gestures applied to an auto-framed view of the tree."""
        r = self.renderer
        cam = OrbitCamera(yaw=self.control.yaw, pitch=BASE_PITCH + self.control.tilt)
        r_lo, r_hi = self.modeling.bounds if self.modeling.active and self.modeling.bounds else (r.lo, r.hi)
        height = max(float(r_hi[1]), 2.0)
        width = max(float(np.max(r_hi[[0, 2]] - r_lo[[0, 2]])), 1.0)
        lo, hi = np.array([-width / 2, 0.0, -width / 2]), np.array([width / 2, height, width / 2])
        cam.frame_bounds(lo, hi, self.size[0] / self.size[1], fill=0.8)
        cam.distance *= self.control.distance
        return cam

    def _rebuild(self) -> None:
        clocks = self.clocks()
        shown = self.modeling.lstring() if self.modeling.active else self.world.tree.lstring
        key = (id(shown), round(clocks.length_time, 6), round(clocks.girth_time, 6), round(clocks.wilt, 4),
               tuple((id(o.tree.lstring), round(o.sim.state.length_time, 3)) for o in self.others))
        if key == self._built:
            return
        geometry = grow_geometry(shown, clocks, self.world.tree.geometry_constants)
        mesh = geometry.mesh
        if self.others:  # the garden, drawn around the cared-for tree (which stays at the centre)
            here = np.array(self.world.position)
            meshes, offsets = [mesh], [np.zeros(3)]
            for other in self.others:
                meshes.append(other.tree.geometry(other.clocks()).mesh)
                dx, dz = np.array(other.position) - here
                offsets.append(np.array([dx, 0.0, dz]))
            mesh = merge_trees(meshes, offsets)
        self.renderer.set_tree(mesh)
        self.triangles = mesh.n_triangles
        wilt = 1.0 if not self.world.sim.state.alive else clocks.wilt
        self.renderer.leaf_tint = tuple(HEALTHY_LEAF + (WILTED_LEAF - HEALTHY_LEAF) * wilt)
        self.renderer.bark_tint = (1.45, 1.35, 1.25) if self.world.sim.state.alive else (1.0, 1.0, 1.0)
        self._built = key

    def draw(self, fbo: moderngl.Framebuffer) -> None:
        """Render the scene and the HUD/menu overlay into ``fbo``."""
        self._rebuild()
        camera = self.camera()
        self.renderer.render(fbo, camera, self.world.sim.sun_direction(), self.size)
        self.overlay.draw(self._overlay_pixels(camera))

    def hud_info(self) -> HudInfo:
        """What the HUD shows now."""
        s, tree = self.world.sim.state, self.world.tree
        message = self.message if self.clock() < self.message_until else ""
        if not message and tree.budget_hit:
            message = text("messages.budget")
        return HudInfo(s.sun_meter, s.water_meter, text(f"status.{self.world.sim.status()}"), s.time, self.loop.speed,
                       message,
                       s.watering)

    def _overlay_pixels(self, camera: OrbitCamera) -> bytes:
        self.surface.fill((0, 0, 0, 0))
        info = self.hud_info()
        if info.watering:
            self._draw_cloud(camera)
        draw_hud(self.surface, self.font, info)
        if self.cursor3d is not None:
            self._draw_cursor3d(camera)
        project = lambda points: self._project_many(camera, points)  # noqa: E731
        self.modeling.draw_outline(self.surface, project)
        self.modeling.draw_symbols(self.surface, camera, self.small_font, project)
        self.menu.draw(self.surface, self.font)
        for hook in self.overlay_hooks:
            hook(self.surface)
        return pygame.image.tobytes(self.surface, "RGBA", True)

    def _project(self, camera: OrbitCamera, point) -> tuple[float, float] | None:
        x, y = project_points(camera, self.size, np.asarray(point, float)[None])[0]
        return (float(x), float(y)) if np.isfinite(x) and np.isfinite(y) else None

    def _project_many(self, camera: OrbitCamera, points) -> list[tuple[float, float]]:
        """Window pixels of many 3D points at once, leaving out those behind the camera."""
        pixels = project_points(camera, self.size, np.asarray(points, float).reshape(-1, 3))
        return [(float(x), float(y)) for x, y in pixels[np.isfinite(pixels).all(axis=1)]]

    def _draw_cloud(self, camera: OrbitCamera) -> None:
        at = self._project(camera, (0.0, max(float(self.renderer.hi[1]), 1.0) * 1.25, 0.0))
        if at is not None:
            draw_rain_cloud(self.surface, (at[0], max(at[1], 60.0)), self.size[1] * 0.12, self.world.sim.state.time)

    def _draw_cursor3d(self, camera: OrbitCamera) -> None:
        """The 3D tracker's cursor (scene units, relative to the tree's base) as a ring with a drop line."""
        at = self._project(camera, self.cursor3d)
        ground = self._project(camera, (self.cursor3d[0], 0.0, self.cursor3d[2]))
        if at is None:
            return
        if ground is not None:
            pygame.draw.line(self.surface, (255, 255, 255, 120), at, ground, 1)
        pygame.draw.circle(self.surface, (255, 230, 120, 230), (int(at[0]), int(at[1])), 10, 3)

    def quit(self) -> None:
        """Save on the way out."""
        self.save()
