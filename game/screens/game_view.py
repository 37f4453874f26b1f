"""What the game shows: the garden's geometry (rebuilt when the clocks or the L-strings change), framed by
the orbit camera."""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor

import moderngl
import numpy as np

from arbor.engine.life.form.growth_view import GrowthView
from arbor.engine.life.plant import seasons
from arbor.engine.life.rules.rules import Rules
from arbor.game.render import scenery
from arbor.game.render.camera import OrbitCamera, zoom_out
from arbor.game.render.falling import FALL_SECONDS, falling_view
from arbor.game.render.garden import BARK, FALLING, SCENERY, GardenRenderer, Placed
from arbor.game.render.instanced import Detail, TreeBuffers, prepare_upload
from arbor.game.render.roots import rocks_view, roots_view
from arbor.game.render.scenery import Spot, scale_of, scenery_view
from arbor.game.render.species import look_of
from arbor.game.screens.modeler import ModelingMode
from arbor.game.screens.state import GameState

BASE_PITCH = 8.0  # degrees the camera looks down on the garden before any tilt
HEALTHY_LEAF, WILTED_LEAF = np.array([1.0, 1.0, 1.0]), np.array([2.6, 0.85, 0.45])  # green -> yellow-brown
WILT_STEP = 0.02  # a change of wilt this large rebuilds the tree (drooping angles change its shape)
ASYNC_MODULES = 60_000  # trees with more modules are rebuilt on a worker thread
SMOOTH_DAY, STEADY_DAY = 20.0, 4.0  # real seconds per day of the sun: light starts to steady / is steady
FALL_FRESH = 2.0  # physiological time: a branch shed earlier than this before it is first seen does not fall


def _built(shown, clocks, const: dict) -> GrowthView:
    """A big tree's records, built and sorted for upload on the worker thread."""
    return prepare_upload(GrowthView(shown, clocks, const))


class GameView:
    """Keeps every tree's instance records current and draws the 3D scene."""

    def __init__(self, state: GameState, renderer: GardenRenderer, modeling: ModelingMode, rules: Rules,
                 size: tuple[int, int]) -> None:
        self.state, self.renderer, self.modeling, self.rules, self.size = state, renderer, modeling, rules, size
        self.views: dict[int, tuple[tuple, GrowthView, TreeBuffers, int]] = {}  # world id -> key, view, GPU, ver
        self.triangles = 0
        self.fall_started: dict[int, float] = {}  # shed branch -> real time its fall began
        self.falls: list[TreeBuffers] = []
        self.pending: dict[int, tuple] = {}  # world id -> (key, future) of a rebuild on the worker
        self.worker = ThreadPoolExecutor(max_workers=1, thread_name_prefix="arbor-rebuild")
        self.root_buffers: dict[int, tuple[tuple, TreeBuffers]] = {}  # world id -> (key, GPU records)
        self.roots_bottom = 0.0  # lowest root of the cared-for tree (the cut-away view frames it)
        self.rock_buffers: tuple[tuple, TreeBuffers] | None = None
        self.scenery: tuple[tuple, TreeBuffers] | None = None  # the garden's stones, shrubs and path

    def rebuild(self) -> None:
        """Bring every tree's records up to date: a full build when its L-string (or wilt) changed,
        else only its growing parts move (engine/life/form/growth_view.py)."""
        state, renderer = self.state, self.renderer
        here = np.array([state.world.position[0], 0.0, state.world.position[1]])
        placed, seen = [], set()
        for world in state.garden.worlds:
            cared = world is state.world
            shown = self.modeling.lstring() if cared and self.modeling.active else world.tree.lstring
            clocks = state.clocks() if cared else world.clocks()
            alive = world.sim.state.alive
            key = (id(shown), len(shown), round(clocks.wilt / WILT_STEP), alive)
            entry = self._view(world, shown, clocks, key)
            _, view, buffers, version = entry
            renderer.trees.sync(buffers, view)
            offset = np.array([world.position[0], 0.0, world.position[1]]) - here
            placed.append(Placed(buffers, offset, version, look_of(world.lineage.species, world.tree.system.constants)))
            seen.add(id(world))
        for gone in set(self.views) - seen:
            self.views.pop(gone)[2].release()
        placed += self._falling(here)
        placed += self._roots(here)
        placed += self._rocks(here)
        placed += self._scenery(here)
        current = self.views[id(state.world)][1]
        renderer.place(placed, current.lo, current.hi)
        self._tints()
        self._count_triangles()

    def _roots(self, here: np.ndarray) -> list[Placed]:
        """Every tree's roots, in the cut-away view only (elsewhere the ground hides them)."""
        state = self.state
        if not state.cutaway:
            for _, buffers in self.root_buffers.values():
                buffers.release()
            self.root_buffers.clear()
            return []
        out = []
        for world in state.garden.worlds:
            key = (id(world.roots.lstring), len(world.roots.lstring))
            entry = self.root_buffers.get(id(world))
            if entry is None or entry[0] != key:
                buffers = entry[1] if entry else TreeBuffers()
                self.renderer.trees.sync(buffers, roots_view(world.roots))
                entry = self.root_buffers[id(world)] = (key, buffers)
            offset = np.array([world.position[0], 0.0, world.position[1]]) - here
            out.append(Placed(entry[1], offset, -2))
            if world is state.world:
                self.roots_bottom = float(entry[1].view.lo[1])
        return out

    def _rocks(self, here: np.ndarray) -> list[Placed]:
        """The garden's rocks (grey balls; shoots grow around them)."""
        rocks = self.state.garden.rocks
        if not rocks:
            return []
        key = tuple(rocks)
        if self.rock_buffers is None or self.rock_buffers[0] != key:
            buffers = self.rock_buffers[1] if self.rock_buffers else TreeBuffers()
            self.renderer.trees.sync(buffers, rocks_view(rocks))
            self.rock_buffers = (key, buffers)
        return [Placed(self.rock_buffers[1], -here, -3)]

    def _scenery(self, here: np.ndarray) -> list[Placed]:
        """Edging stones, shrubs and a stepping-stone path placed with the trees (game/render/scenery.py),
        rebuilt only when a tree moves, comes or goes, or grows past a step of its scale; on a software GL
        only when scenery.ON_SOFTWARE_GL says so (its cost there, see game/render/scenery.py)."""
        if self.renderer.samples <= 1 and not scenery.ON_SOFTWARE_GL:
            return []
        spots = []
        for world in self.state.garden.worlds:
            view = self.views[id(world)][1]
            spots.append(Spot(float(world.position[0]), float(world.position[1]),
                              scale_of(float(view.hi[1] - view.lo[1]))))
        key = tuple(spots)
        if self.scenery is None or self.scenery[0] != key:
            buffers = self.scenery[1] if self.scenery else TreeBuffers()
            self.renderer.trees.sync(buffers, scenery_view(spots))
            self.scenery = (key, buffers)
        return [Placed(self.scenery[1], -here, SCENERY)]

    def _view(self, world, shown, clocks, key: tuple) -> tuple:
        """The records for ``world``'s tree: rebuilt when ``key`` changed, else moved to ``clocks``. A
        big tree is rebuilt on a worker thread while frames keep drawing the old records, still growing
        (new parts are born at zero size, so the few frames' delay is invisible)."""
        entry = self.views.get(id(world))
        pending = self.pending.get(id(world))
        if pending is not None and pending[1].done():
            self.pending.pop(id(world))
            entry = self._adopt(world, entry, pending[0], pending[1].result())
        const = world.tree.geometry_constants
        if entry is None or (entry[0] != key and len(shown) < ASYNC_MODULES):
            entry = self._adopt(world, entry, key, GrowthView(shown, clocks, const))
        elif entry[0] != key and id(world) not in self.pending:  # one rebuild at a time: never a backlog
            self.pending[id(world)] = (key, self.worker.submit(_built, shown, clocks, const))
        entry[1].update(clocks)  # (a stale view keeps growing until its successor is ready)
        return entry

    def _adopt(self, world, entry, key: tuple, view: GrowthView) -> tuple:
        buffers = entry[2] if entry else TreeBuffers()
        entry = (key, view, buffers, (entry[3] + 1) if entry else 0)
        self.views[id(world)] = entry
        return entry

    def _count_triangles(self) -> None:
        placed, details = self.renderer.placed, self.renderer.last_details
        if len(details) != len(placed):
            details = [Detail(0)] * len(placed)
        self.triangles = sum(d.triangles(p.buffers) for p, d in zip(placed, details, strict=True))

    def _tints(self) -> None:
        renderer = self.renderer
        alive = self.state.world.sim.state.alive
        wilt = self.state.clocks().wilt if alive else 1.0
        renderer.leaf_tint = tuple(HEALTHY_LEAF + (WILTED_LEAF - HEALTHY_LEAF) * wilt)
        renderer.bark_tint = BARK if alive else (1.0, 1.0, 1.0)

    def _falling(self, here: np.ndarray) -> list[Placed]:
        """Branches shed since they were first seen, falling (for FALL_SECONDS of real time)."""
        for old in self.falls:
            old.release()
        self.falls = []
        now, out, seen = self.state.clock(), [], set()
        for world in self.state.garden.worlds:
            offset = np.array([world.position[0], 0.0, world.position[1]]) - here
            recent = world.tree.last_rewrite_T - FALL_FRESH  # a branch shed long ago (while away) just lies there
            for fallen in world.tree.fallen:
                seen.add(id(fallen))
                started = self.fall_started.setdefault(id(fallen), now if fallen.at >= recent else -FALL_SECONDS)
                if now - started < FALL_SECONDS:
                    buffers = TreeBuffers()
                    self.renderer.trees.sync(buffers, falling_view(fallen, (now - started) / FALL_SECONDS))
                    self.falls.append(buffers)
                    out.append(Placed(buffers, offset, FALLING))
        self.fall_started = {k: v for k, v in self.fall_started.items() if k in seen}
        return out

    def camera(self) -> OrbitCamera:
        """The orbit camera for this frame: gestures applied to an auto-framed view of the tree."""
        r, control, modeling = self.renderer, self.state.control, self.modeling.active
        cam = OrbitCamera(yaw=control.yaw, pitch=BASE_PITCH + control.tilt)
        r_lo, r_hi = self.modeling.bounds if modeling and self.modeling.bounds else (r.lo, r.hi)
        height = max(float(r_hi[1]), 2.0 if modeling else 4.0)  # a sapling stands small in its garden
        width = max(float(np.max(r_hi[[0, 2]] - r_lo[[0, 2]])), 1.0)
        bottom = self.roots_bottom if self.state.cutaway and not modeling else 0.0
        lo, hi = np.array([-width / 2, bottom, -width / 2]), np.array([width / 2, height, width / 2])
        aspect = self.size[0] / self.size[1]
        cam.frame_bounds(lo, hi, aspect, fill=0.8)
        if modeling:
            cam.distance *= control.distance
        else:  # zoomed far out, the view frames the whole garden
            zoom_out(cam, *self.garden_bounds(lo, hi), control.distance, control.max_distance, aspect)
        return cam

    def garden_bounds(self, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The box round every tree of the garden (scene units, from the cared-for tree's foot, whose own
        box is [lo, hi]), each tree as tall as it is drawn."""
        state = self.state
        here = np.array(state.world.position)
        boxes_lo, boxes_hi = [lo], [hi]
        for world in state.garden.worlds:
            entry = self.views.get(id(world))
            if world is state.world or entry is None:
                continue
            dx, dz = np.array(world.position) - here
            offset = np.array([dx, 0.0, dz])
            boxes_lo.append(np.array(entry[1].lo) + offset)
            boxes_hi.append(np.maximum(np.array(entry[1].hi), (0.0, 2.0, 0.0)) + offset)
        return np.min(boxes_lo, axis=0), np.max(boxes_hi, axis=0)

    def draw(self, fbo: moderngl.Framebuffer) -> OrbitCamera:
        """Render the scene into ``fbo``; returns the camera it was seen through (the HUD projects with it)."""
        renderer = self.renderer
        self.rebuild()
        camera = self.camera()
        renderer.time = self.state.clock()
        renderer.wind = self.wind()
        renderer.backdrop.cutaway = self.state.cutaway
        self._season_look()
        renderer.render(fbo, camera, self.scene_sun(), self.size, stream=True)
        self._count_triangles()  # (again: the levels of detail of this very frame)
        return camera

    def scene_sun(self) -> np.ndarray:
        """The sun the scene is lit by. When days fly by (a day of the sun in less than SMOOTH_DAY real
        seconds) the light leans toward the noon sun, fully at a day in a few seconds: at 100x the
        screen neither strobes nor goes dark every second, while the sim keeps its real sun."""
        sim = self.state.world.sim
        sun = sim.sun_direction()
        turn = sim.state.sun_speed * self.state.time_speed()  # radians of the sun per real second
        day = 2 * math.pi / turn if turn > 0 else math.inf
        lean = min(max((SMOOTH_DAY - day) / (SMOOTH_DAY - STEADY_DAY), 0.0), 1.0)
        if lean == 0.0:
            return sun
        noon = np.array([0.0, sim.sun_height() - math.sin(sim.state.sun_angle) + 1.0, self.rules.sun.side])
        unit = lambda v: v / max(float(np.linalg.norm(v)), 1e-9)  # noqa: E731
        return unit(unit(sun) * (1.0 - lean) + unit(noon) * lean)

    def _season_look(self) -> None:
        """Autumn colours and the leaves that have fallen, for the renderer."""
        turns = self.state.world.sim.state.sun_turns
        self.renderer.autumn = seasons.autumn_colour(turns, self.rules)
        self.renderer.leaf_keep = seasons.leaf_keep(turns, self.rules)

    def wind(self) -> np.ndarray:
        """The wind vector for the shaders: the rules' direction x :meth:`wind_strength`, scaled to the
        tree's size."""
        height = max(float(self.renderer.hi[1]), 1.0)
        a = math.radians(self.rules.wind.direction)
        return np.array([math.cos(a), 0.0, math.sin(a)]) * self.wind_strength() * 0.1 * height

    def wind_strength(self) -> float:
        """How hard the wind blows now (the rule's unit): its strength with slow gusts (in real time: the
        air moves the same at every game speed), harder in a shower. The trees sway and the wind is heard
        (game/audio) by this one number."""
        rules = self.rules.wind
        t = self.state.clock()
        gust = 1.0 + rules.gusts * (0.6 * math.sin(t * 0.23) + 0.4 * math.sin(t * 0.61 + 1.3))
        shower = self.rules.weather.rain_wind if self.state.world.sim.raining() else 1.0
        return rules.strength * shower * max(gust, 0.0)
