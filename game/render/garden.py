"""The game's scene: the garden's trees (instanced, each at its own level of detail), the ground with
their shadows, the sky with the sun, antialiased.

Costs are kept where they must be: the shadow map (1024 texels) is redrawn only when the sun moved or a
tree changed enough; trees far away or small on screen use fewer sides per ring, leave out sub-pixel
twigs and draw fewer, larger leaves; the sky is a dome of vertices. Multisampling (4x) is resolved into
the target framebuffer. On a software GL (no multisampling) each tree keeps to a vertex budget, sky and
ground are drawn once and copied while nothing they show changes, and trees costly to draw (LAYER_COST:
their leaves' pixels and their segments) are drawn as a layer's picture, a share of their leaves a frame
while the camera holds still, and smoothed once per picture: at the frame's resolution, or lower for a
crown whose leaves would cover the screen many times over (game/render/layer.py).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace

import moderngl
import numpy as np

from arbor.game.render.backdrop import CLOUD_DRIFT, CLOUD_STEP, Backdrop, lamp, sky_colors
from arbor.game.render.camera import OrbitCamera, look_at, orthographic
from arbor.game.render.fxaa import Fxaa
from arbor.game.render.grass import Grass
from arbor.game.render.instanced import (
    LEAF_KEPT,
    SIDES,
    TEMPLATE_VERTICES,
    WHOLE,
    Detail,
    InstancedTrees,
    Piece,
    TreeBuffers,
    cover_grow,
)
from arbor.game.render.layer import MIN_SCALE, REUSE_PIXELS, Pictures, Step, moved, screen_rect
from arbor.game.render.renderer import _gl, _load_texture
from arbor.game.render.shadows import SHADOW_SIZE, ShadowMaps
from arbor.game.render.species import CLUSTERS, GAME_TREE, SpeciesLook
from arbor.game.render.stage import Scene, Stage

LOD_PIXELS = (520, 260, 120)  # on-screen height (px) above which a tree gets level 0, 1, 2 (else 3)
TWIG_PIXELS = (0.0, 0.1, 0.2, 0.35)  # per level: grown segments of a smaller radius (px) are left out
FINE_PIXELS = 2.5  # grown segments at least this thick (radius, px) keep level 0's sides at any level
LEAF_PIXELS = 1_000_000  # leaf area (pixels, all layers) above which a software GL draws trees smaller
SEGMENT_PIXELS = 130  # a grown segment costs a software GL about as much as this many pixels of leaves
LAYER_COST = 100_000  # cost (leaf pixels, all layers, and segments) above which a software GL draws trees as a picture
STEP_COST = 120_000  # a picture drawn over frames draws its leaves in shares of about this many pixels
LEAF_STEPS = (2, 6)  # and in at least, at most so many shares
WOOD_STEPS = 4  # and its wood in shares of about STEP_COST too (grown segments at SEGMENT_PIXELS), at most so many
LEAVES = Piece(frozenset({"leaf", "leaf_young", "blossom", "fruit"}))
WOOD = Piece(frozenset({"tube", "tube_young", "stone"}))
BARK = (1.4, 1.36, 1.3)  # (near grey: the sun's warm light does the rest)
BLOSSOM = (1.2, 0.9, 1.0)
SHADOW_WAIT = 4  # frames a due shadow map waits at most for a frame the backdrop is not being drawn in
FALLING = -1  # Placed.version of a shed branch falling: new records every frame, and no shadow
SCENERY = -4  # Placed.version of the garden's stones and shrubs (scenery.py): no box in the shadows' or smoothing's


def software_gl(ctx: moderngl.Context) -> bool:
    """True on a CPU renderer (Mesa llvmpipe/softpipe, SwiftShader), where multisampling costs a frame."""
    name = str(ctx.info.get("GL_RENDERER", "")).lower()
    return any(word in name for word in ("llvmpipe", "softpipe", "swiftshader", "software"))


@dataclass
class Placed:
    """A tree in the scene: its buffers and where it stands (x, 0, z)."""

    buffers: TreeBuffers
    offset: np.ndarray
    version: int = 0  # changes when the tree changed enough to need new shadows (FALLING: casts none)
    look: SpeciesLook = GAME_TREE  # its species' bark tint and leaf cards (game/render/species.py)


class GardenRenderer:
    """Draws placed trees with backdrop and shadows (see module docstring)."""

    def __init__(self, ctx: moderngl.Context, samples: int | None = None) -> None:
        self.ctx = ctx
        self.backdrop = Backdrop(ctx)
        self.trees = InstancedTrees(ctx)
        self.grass = Grass(ctx)
        self.textures = {name: _load_texture(ctx, name, name.startswith(("bark", "rock")))
                         for name in ("bark", "bark_normal", *CLUSTERS, "blossom", "rock", "rock_normal")}
        self.shadows = ShadowMaps(ctx)
        self.samples = samples if samples is not None else (1 if software_gl(ctx) else 4)
        self.vertex_budget = 60_000 if software_gl(ctx) else 10_000_000  # shaded per tree and frame
        self.stage = Stage(ctx, self.backdrop, self.shadows, self.samples)
        self.placed: list[Placed] = []
        self.lo, self.hi = -np.ones(3), np.ones(3)
        self.leaf_tint, self.bark_tint, self.blossom_tint = (1.0, 1.0, 1.0), BARK, BLOSSOM
        self.autumn, self.leaf_keep = 0.0, 1.0  # autumn colour (0..1) and share of leaves still on
        self.relief, self.translucency = 1.0, 1.0  # bark normal map and light through leaves (0: left out)
        # smoothed edges where there is no multisampling (see fxaa.py); ARBOR_FXAA=0 leaves them out (a slow CPU)
        self.fxaa = self.samples <= 1 and os.environ.get("ARBOR_FXAA", "1") != "0"
        self.soft_shadows = 1.0  # shadow edges filtered over this many texels (0: one bilinear tap)
        self.post = Fxaa(ctx)
        self.wind = np.zeros(3)  # direction x strength (scene units at the outermost twigs)
        self.time = 0.0
        self.last_details: list[Detail] = []
        self.pictures = Pictures(ctx)
        self.last_scale = 1.0
        self.last_layered = False  # whether the last frame showed the trees as a layer's picture (layer.py)
        self.last_vp: np.ndarray | None = None  # the last frame's view-projection (did the camera move?)
        self.leaf_steps = LEAF_STEPS[0]  # shares of the leaves a picture drawn over frames draws them in
        self.wood_steps = 1  # and of its wood
        self.shadow_waited = 0  # frames a due shadow map has waited (see SHADOW_WAIT)

    def place(self, placed: list[Placed], lo: np.ndarray, hi: np.ndarray) -> None:
        """The trees to draw this frame and the bounds of the one in the middle (for framing)."""
        self.placed = placed
        self.lo, self.hi = np.asarray(lo, float), np.asarray(hi, float)

    def _scene_bounds(self) -> tuple[np.ndarray, float]:
        centres, radius = [], 1.0
        for p in self.placed:
            view = p.buffers.view
            if view is None:
                continue
            lo, hi = np.asarray(view.lo) + p.offset, np.asarray(view.hi) + p.offset
            centres.append((lo + hi) / 2)
            radius = max(radius, float(np.linalg.norm(hi - lo)) / 2)
        if not centres:
            return np.zeros(3), radius
        centre = np.mean(centres, axis=0)
        spread = max(float(np.linalg.norm(c - centre)) for c in centres)
        return centre, radius + spread

    def light_matrix(self, sun: np.ndarray) -> np.ndarray:
        """Orthographic sun view covering every tree and the shadows it casts."""
        centre, radius = self._scene_bounds()
        reach = radius * (1.2 + 1.0 / max(float(sun[1]), 0.35))
        focus = np.array([centre[0], centre[1] * 0.5, centre[2]])
        return orthographic(reach, 0.01, reach * 4) @ look_at(focus + sun * reach * 2, focus)

    def _detail(self, buffers: TreeBuffers, offset: np.ndarray, camera: OrbitCamera, height_px: int) -> Detail:
        """The level of detail by the tree's size on screen (sides per ring, and grown twigs under a
        fraction of a pixel left out), coarser while the vertices it would shade exceed the budget;
        at the coarsest level the thinnest segments and a share of the leaves go until it fits."""
        view = buffers.view
        size = float(np.linalg.norm(np.asarray(view.hi) - np.asarray(view.lo)))
        per_pixel = pixel_size(buffers, offset, camera, height_px)
        lod = next((k for k, limit in enumerate(LOD_PIXELS) if size / per_pixel >= limit), len(SIDES) - 1)
        detail = Detail.of(buffers, lod, TWIG_PIXELS[lod] * per_pixel, LEAF_KEPT[lod])
        while detail.vertices(buffers) > self.vertex_budget and detail.lod < len(SIDES) - 1:
            lod = detail.lod + 1
            detail = Detail.of(buffers, lod, TWIG_PIXELS[lod] * per_pixel, LEAF_KEPT[lod])
        if detail.vertices(buffers) > self.vertex_budget:
            detail = squeezed(buffers, detail, self.vertex_budget)
        # (a coarse level's few thick segments, trunk and limbs, stay round: a 3-sided trunk is a prism;
        # within the budget's room)
        room = (self.vertex_budget - detail.vertices(buffers)) // max(TEMPLATE_VERTICES[0] - TEMPLATE_VERTICES[
            detail.lod], 1)
        detail = replace(detail, fine=min(buffers.tubes_at_least(FINE_PIXELS * per_pixel), max(room, 0)))
        if self.samples > 1:
            return detail
        natural = buffers.leaf_area * detail.leaf_share / per_pixel**2  # pixels of the drawn leaves, life size
        cap = math.sqrt(LEAF_PIXELS / MIN_SCALE**2 / max(natural, 1.0))  # (all their layers together)
        return replace(detail, leaf_grow=min(detail.leaf_grow, max(cap, 1.0)))

    def render(self, fbo: moderngl.Framebuffer, camera: OrbitCamera, sun_dir: np.ndarray,
               size: tuple[int, int], stream: bool = False) -> None:
        """Draw the scene into ``fbo`` (``size`` pixels). ``stream``: one of a stream of frames (the
        game's), which on a software GL may show a change of the backdrop the camera did not make a few
        frames late, drawn a part a frame (kept.py); else (a picture alone) everything is drawn as it is."""
        sun = np.asarray(sun_dir, float) / np.linalg.norm(sun_dir)
        light = self.light_matrix(lamp(sun)[0])  # (by night the moon casts the shadows)
        vp = camera.projection(size[0] / size[1]) @ camera.view()
        details = [self._detail(p.buffers, p.offset, camera, size[1]) if p.buffers.view else Detail(3)
                   for p in self.placed]
        self.last_details = details
        leaf_pixels = drawn_leaf_pixels(self.placed, details, camera, size[1])
        self.last_scale = scale = draw_scale(self.samples, leaf_pixels)
        cost = sum(leaf_pixels) + SEGMENT_PIXELS * sum(d.tubes for d in details)
        # (a camera that moves gets no picture drawn over frames: the trees are drawn whole, and without
        # the layer's composite and copies, unless they must be drawn smaller)
        seen = _corners(placed_boxes(self.placed, scenery=True) or [(np.zeros(3), np.zeros(3))])
        still = self.last_vp is not None and moved(self.last_vp, vp, seen, size) <= REUSE_PIXELS
        self.last_vp = vp
        layered = self.samples <= 1 and (scale < 1.0 or (cost > LAYER_COST and still))
        self.last_layered = layered
        self.leaf_steps = min(max(math.ceil(sum(leaf_pixels) * scale**2 / STEP_COST), LEAF_STEPS[0]), LEAF_STEPS[1])
        self.wood_steps = min(max(math.ceil(SEGMENT_PIXELS * sum(d.tubes for d in details) / STEP_COST), 1),
                              WOOD_STEPS)
        grow_grass(self.grass, self.placed)
        self.backdrop.drift = int(self.time * CLOUD_DRIFT / CLOUD_STEP)
        self.backdrop.soft = (self.soft_shadows, 1.0 / SHADOW_SIZE)
        self.shadows.age += 1
        smooth = self.fxaa and self.samples <= 1 and scale >= 1.0  # (a layer's picture is soft already)
        target = self.stage.target(fbo, size)
        pixel = 2.0 * math.tan(math.radians(camera.fov_y) / 2) / size[1]
        uniforms = self._lit_uniforms(_gl(vp), _gl(light), sun, sky_colors(sun)[2])
        uniforms.update(u_eye=tuple(camera.eye), u_pixel=pixel / scale, u_soft=self.soft_shadows)
        if self.samples <= 1:  # a software GL: the grass and the scenery stand still in the backdrop's picture
            still = {**uniforms, "u_wind": (0.0, 0.0, 0.0, 0.0)}  # (the same blades at every redraw: no jumps)
            self.stage.cover = lambda: draw_cover(self, still, details)
            self.stage.cover_version = (self.grass.version,
                                        *(id(p.buffers.view) for p in self.placed if p.version == SCENERY))
            self.stage.cover_look = self.grass.look(uniforms)
        boxes = placed_boxes(self.placed)
        if not layered:
            # a software GL draws a changed backdrop a part a frame (kept.py): the shadow map waits
            # for a frame without one (a few frames at most), so that no frame pays for both
            steps = self._shadow_steps(light, sun, details, [WHOLE])
            if steps and stream and self.stage.busy and self.shadow_waited < SHADOW_WAIT:
                self.shadow_waited, steps = self.shadow_waited + 1, []
            else:
                self.shadow_waited = 0
            for step in steps:
                step()
            self.stage.draw(target, size, Scene(camera, vp, sun, light, boxes, self._scene_bounds()[1]),
                            spread=stream, wait=bool(steps))
            self.ctx.enable(moderngl.DEPTH_TEST)
            self._trees_step(details, uniforms, WHOLE)[0]()
        else:
            self._render_layered(target, size, Scene(camera, vp, sun, light, boxes, self._scene_bounds()[1]),
                                 details, uniforms, scale, smooth)
        if smooth and not layered:
            self.post.smooth(fbo, size, screen_rect(camera, size, boxes, margin=0.15))
        elif target is not fbo:
            self.ctx.copy_framebuffer(fbo, target)

    def _render_layered(self, target: moderngl.Framebuffer, size: tuple[int, int], scene: Scene,
                        details: list[Detail], uniforms: dict, scale: float, smooth: bool = False) -> None:
        """The trees as a layer's picture (drawn over frames while the camera holds still, see
        layer.Pictures) over the backdrop, all as they were when the picture shown was begun; with
        ``smooth``, FXAA over them once per picture shown (a picture at the frame's resolution)."""
        corners = _corners(scene.boxes)
        # the trees a picture shows (falling branches are new buffers every frame: counted only)
        views = (len(self.placed), tuple(id(p.buffers.view) for p in self.placed if p.version >= 0))
        look = (self.autumn, self.leaf_keep, *self.leaf_tint, *self.bark_tint)
        self.pictures.draw(size, scale, scene.vp, corners, views,
                           lambda whole: self._picture_steps(scene, details, uniforms, size, whole), scene, look)
        post = (lambda into, rect: self.post.smooth(into, size, rect)) if smooth else None
        self.stage.layered(target, size, self.pictures.shown.scene, self.pictures, post)

    def _picture_steps(self, scene: Scene, details: list[Detail], uniforms: dict, size: tuple[int, int],
                       whole: bool) -> list[Step]:
        """What a picture of the trees takes, frame by frame (see layer.Pictures): the shadow map when it
        is due, then shares of the grown leaves (``leaf_steps`` of them, the last with the young leaves,
        blossoms and fruit), then of the wood (``wood_steps``, the last with the young segments and the
        rocks), and a frame for showing it (the backdrop keeps itself up to
        date, a part a frame: stage.Stage.layered)."""
        n, m = self.leaf_steps, self.wood_steps
        leaves = [Piece(frozenset({"leaf"}), k / n, (k + 1) / n) for k in range(n - 1)]
        wood = [*(Piece(frozenset({"tube"}), k / m, (k + 1) / m) for k in range(m - 1)), Piece(WOOD.names, (m - 1) / m)]
        halves = [Piece(frozenset({"leaf"}), 0.0, 0.5), Piece(LEAVES.names, 0.5), *wood]  # (the shadow map's)
        shadows = self._shadow_steps(scene.light, scene.sun, details, [WHOLE] if whole else halves)
        last = [Piece(LEAVES.names, (n - 1) / n), *wood]
        pieces = [WHOLE] if whole else [*leaves, *last]
        trees = [self._trees_step(details, dict(uniforms), p) for p in pieces]
        show = [] if whole else [(lambda: None, False)]  # the new picture is shown in a frame of its own
        return [(step, False) for step in shadows] + trees + show

    def _trees_step(self, details: list[Detail], uniforms: dict, piece: Piece) -> Step:
        """Drawing ``piece`` of every tree, lit, into whatever framebuffer is bound."""
        def run() -> None:
            self.ctx.enable(moderngl.DEPTH_TEST)
            self.shadows.texture.use(location=1)
            bark, leaf, blossom = uniforms["tints"]
            for placed, detail in zip(self.placed, details, strict=True):
                if placed.version == SCENERY and self.samples <= 1:
                    continue  # (in the backdrop's picture: draw_cover)
                look = placed.look
                tints = (tuple(a * b for a, b in zip(bark, look.bark, strict=True)),
                         tuple(a * b for a, b in zip(leaf, look.leaf, strict=True)), blossom)
                season = {"u_autumn": 0.0, "u_keep": 1.0} if look.evergreen else {}  # (needles kept green)
                self.trees.draw(placed.buffers, "lit", detail, {**uniforms, "u_offset": tuple(placed.offset),
                                                                "tints": tints, **season}, self._textures(look), piece)
            if self.samples > 1 and "tube" in piece.names and not self.stage.backdrop.cutaway:  # (with the wood)
                self.grass.draw(uniforms)
        return run, True

    def _textures(self, look: SpeciesLook) -> dict:
        """The textures a tree of ``look`` is drawn with: its species' leaf cards."""
        if look.cluster == "leaf_cluster":
            return self.textures
        return {**self.textures, "leaf_cluster": self.textures[look.cluster]}

    def _lit_uniforms(self, mvp: bytes, light: bytes, sun: np.ndarray, day: float) -> dict:
        zenith, _, _ = sky_colors(sun)
        toward, sun_color = lamp(sun)  # (the sun by day, the moon by night: backdrop.lamp)
        centre, radius = self._scene_bounds()
        return {"u_mvp": mvp, "u_light_mvp": light, "u_shadow": 1, "u_shadow_texel": 1.0 / SHADOW_SIZE,
                "u_sun_dir": tuple(toward), "u_sun_color": sun_color,
                "u_sky_color": tuple(c * (1.0 + 1.2 * (1.0 - day)) for c in zenith),  # moonlit: always visible
                "u_ground_color": tuple(c * max(day, 0.35) for c in (0.30, 0.28, 0.18)),
                "u_crown_center": tuple(centre + np.array([0.0, radius * 0.25, 0.0])), "u_crown_radius": radius,
                "u_wind": (*self.wind, self.time), "u_autumn": self.autumn, "u_keep": self.leaf_keep,
                "u_relief": self.relief, "u_translucency": self.translucency * (0.35 + 0.65 * day),  # (moon: less)
                "tints": (self.bark_tint, self.leaf_tint, self.blossom_tint)}

    def _shadow_steps(self, light: np.ndarray, sun: np.ndarray, details: list[Detail],
                      pieces: list[Piece]) -> list:
        """The shadow map's redraw as steps (none when it is not due); the trees one level coarser. A falling
        branch casts no shadow (its records are new every frame: counted, they made the map due every frame
        of its fall, which on a software GL also kept the backdrop from following the sun, see stage.py)."""
        versions = (*((id(p.buffers.view), p.version) for p in self.placed if p.version != FALLING),
                    round(self.leaf_keep, 2))
        if not self.shadows.due(sun, versions):
            return []
        uniforms = {"u_mvp": _gl(light), "u_light_mvp": _gl(light), "u_wind": (*self.wind, self.time),
                    "u_eye": (0.0, 0.0, 0.0), "u_pixel": 0.0, "u_keep": self.leaf_keep}
        def draw(piece: Piece) -> None:  # (the trees placed when it runs: the same ones, see render)
            for tree, detail in zip(self.placed, details, strict=True):
                if tree.version == FALLING:
                    continue
                uniforms["u_offset"] = tuple(tree.offset)
                uniforms["u_keep"] = 1.0 if tree.look.evergreen else self.leaf_keep  # (needles kept all winter)
                coarser = replace(detail, lod=min(detail.lod + 1, len(SIDES) - 1))
                self.trees.draw(tree.buffers, "shadow", coarser, uniforms, self._textures(tree.look), piece)
        return self.shadows.steps(sun, versions, draw, pieces)

    def release(self) -> None:
        """Free the trees' buffers (GL objects of the renderer itself live with the context)."""
        for placed in self.placed:
            placed.buffers.release()
        self.placed = []


def placed_boxes(placed: list[Placed], scenery: bool = False) -> list[tuple[np.ndarray, np.ndarray]]:
    """The placed trees' boxes (scene units), which bound the ground's shadow tests and the smoothing; with
    ``scenery``, the scenery's too, which spans the garden's ground (a shadow test and smoothing over all of it
    doubled a software GL's frame of a sapling; its stones and low shrubs need neither)."""
    return [(np.asarray(p.buffers.view.lo) + p.offset, np.asarray(p.buffers.view.hi) + p.offset)
            for p in placed if p.buffers.view is not None and (scenery or p.version != SCENERY)]


def _corners(boxes: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """The corners of ``boxes`` (scene units; 8 a box), for how far the camera moved."""
    return np.array([[x, y, z] for lo, hi in boxes for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                     for z in (lo[2], hi[2])]).reshape(-1, 3)


def draw_cover(renderer: GardenRenderer, uniforms: dict, details: list[Detail]) -> None:
    """What covers the ground in a software GL's picture of the backdrop (redrawn only when the camera, the
    light or they change): the grass, and the scenery's stones and shrubs, lit (a stone's lumpy rock shading
    is costly per pixel: 15 stones by a sapling cost its every frame about 5 ms on llvmpipe)."""
    renderer.grass.draw(uniforms, shadowed=False)
    # unshadowed, as the grass (the picture's shade pass darkens the ground's shadows over both): a light
    # matrix that puts every point off the shadow map
    unshadowed = {**uniforms, "u_light_mvp": _gl(np.array([[0, 0, 0, 4.0], [0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1]]))}
    for placed, detail in zip(renderer.placed, details, strict=True):
        if placed.version == SCENERY:
            renderer.trees.draw(placed.buffers, "lit", detail, {**unshadowed, "u_offset": tuple(placed.offset)},
                                renderer._textures(placed.look))


def drawn_leaf_pixels(placed: list[Placed], details: list[Detail], camera: OrbitCamera, height_px: int) -> list[float]:
    """Each placed tree's drawn leaves in pixels at the frame's resolution (all their layers together)."""
    return [p.buffers.leaf_area * d.leaf_share * d.leaf_grow**2
            / pixel_size(p.buffers, p.offset, camera, height_px) ** 2 if p.buffers.view is not None else 0.0
            for p, d in zip(placed, details, strict=True)]


def draw_scale(samples: int, leaf_pixels: list[float]) -> float:
    """The resolution the trees are drawn at: the whole frame's (always with multisampling: ``samples`` > 1),
    or on a software GL less when their leaves (``leaf_pixels``, see :func:`drawn_leaf_pixels`) would cover the
    screen many times over (their pixels are the frame's cost)."""
    if samples > 1:
        return 1.0
    return min(max(math.sqrt(LEAF_PIXELS / max(sum(leaf_pixels), 1.0)), MIN_SCALE), 1.0)


def squeezed(buffers: TreeBuffers, detail: Detail, budget: int) -> Detail:
    """``detail`` at the coarsest level and still over the vertex ``budget``: the thinnest grown segments and
    a share of the grown leaves left out until it fits."""
    lod = detail.lod
    fixed = Detail(lod).vertices(buffers)  # young parts, blossoms, fruit: always drawn
    leaves = min(detail.leaves, max(budget - fixed, 0) // 8)  # half the rest for leaves
    share = float(buffers.hashes[leaves]) if leaves < len(buffers.hashes) else detail.leaf_share
    room = (budget - fixed - 4 * leaves) // TEMPLATE_VERTICES[lod]  # the rest for wood
    share, tubes = min(share, detail.leaf_share), min(detail.tubes, max(room, 0))
    thinnest = float(buffers.radii[tubes - 1]) if 0 < tubes < len(buffers.radii) else detail.thinnest
    return Detail(lod, tubes, leaves, share, cover_grow(share), max(thinnest, detail.thinnest))


def pixel_size(buffers: TreeBuffers, offset: np.ndarray, camera: OrbitCamera, height_px: int) -> float:
    """The size of a pixel (scene units) at the distance of the tree standing at ``offset``."""
    view = buffers.view
    centre = (np.asarray(view.lo) + np.asarray(view.hi)) / 2 + offset
    distance = max(float(np.linalg.norm(centre - camera.eye)), 1e-3)
    return 2 * distance * math.tan(math.radians(camera.fov_y) / 2) / height_px


def grow_grass(grass: Grass, placed: list[Placed]) -> None:
    """The grass around the grown trees (not the falling branches), as big as the trees are."""
    standing = [p for p in placed if p.version >= 0 and p.buffers.view is not None]
    if not standing:
        return
    heights = [float(np.asarray(p.buffers.view.hi)[1]) for p in standing]
    radius = max(float(np.linalg.norm(np.asarray(p.buffers.view.hi) - np.asarray(p.buffers.view.lo))) / 2
                 for p in standing)
    grass.update([p.offset for p in standing], radius, max(max(heights), 4.0))
