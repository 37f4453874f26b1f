"""Denser, layered foliage at no more triangles (issue 47, looks): each leaf card a full, layered clump
(a darker second layer of leaves behind the spray), each card its own green, and the crown lighter on its
sunlit side than on its far side."""

import numpy as np
import pytest
from PIL import Image

from arbor.engine.geometry.instances import LEAF_FLOATS, LeafInstances, TubeInstances
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.falling import StaticView
from arbor.game.render.garden import GardenRenderer
from arbor.game.render.textures import TEXTURES, leaf_cluster_rgba
from tests.test_look import SIZE, drawer

# a card's leaf cover (share of its texels) at least: the single sprays covered 0.375, 0.223, 0.230, 0.105 (the
# needles, 0.16 as a sparse spray, read as a bare twig: a bottle-brush now, 0.49)
FULL = {"leaf_cluster": 0.48, "leaf_cluster_deltoid": 0.32, "leaf_cluster_lance": 0.28, "leaf_cluster_needle": 0.45,
        "leaf_cluster_lobed": 0.5}


def draw_once(gl_ctx, view: StaticView, camera: OrbitCamera, sun: np.ndarray) -> np.ndarray:
    """One picture of ``view`` by a renderer of its own (a renderer keeps a still camera's picture of the
    trees over frames: a second picture from the same camera may be the first one's)."""
    renderer = GardenRenderer(gl_ctx)
    try:
        return drawer(gl_ctx, renderer)(view, camera, sun)
    finally:
        renderer.release()


@pytest.mark.parametrize("name", sorted(FULL))
def test_every_leaf_card_is_a_full_clump(name):
    cover = (np.asarray(Image.open(TEXTURES / f"{name}.png").convert("RGBA"))[..., 3] > 127).mean()
    assert cover >= FULL[name]


def test_a_card_is_layered_darker_behind_and_at_its_twig():
    card = leaf_cluster_rgba().astype(float)  # (rows: v from 0, the twig, to 1, the tip)
    leaf = card[..., 3] > 127
    green = card[..., 1]
    assert green[:40][leaf[:40]].mean() < 0.92 * green[-50:][leaf[-50:]].mean()  # the twig's end darker
    # the back layer shows between the front leaves: darker greens than the front's darkest tones
    assert np.percentile(green[leaf], 15) < 0.74 * np.percentile(green[leaf], 70)  # (one layer: 0.78)


def crown(eye_dir: np.ndarray, n: int = 500, seed: int = 4) -> StaticView:
    """``n`` leaf cards filling a ball of radius 3 round (0, 5, 0), each facing ``eye_dir``."""
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(n, 3))
    points *= (3.0 * rng.random(n) ** (1 / 3) / np.linalg.norm(points, axis=1))[:, None]
    data = np.zeros((n, LEAF_FLOATS), np.float32)
    data[:, 0:3] = points + np.array([0.0, 4.6, 0.0])
    data[:, 3:6], data[:, 6:9] = (0.0, 1.0, 0.0), eye_dir
    data[:, 9], data[:, 10], data[:, 12] = 0.9, 0.45, rng.random(n)
    return StaticView(TubeInstances.empty(), LeafInstances(data), LeafInstances.empty(),
                      np.array([-3.0, 1.6, -3.0]), np.array([3.0, 7.6, 3.0]))


def leaf_pixels(gl_ctx, image: np.ndarray, camera: OrbitCamera, sun: np.ndarray) -> np.ndarray:
    """Where the picture is leaf: where it differs from the same picture without the crown."""
    bare = crown(np.array([0.0, 0.0, 1.0]))
    bare.leaves = LeafInstances.empty()
    leaf = np.abs(image - draw_once(gl_ctx, bare, camera, sun)).sum(axis=2) > 30
    leaf[SIZE[1] // 2:] = False  # (over the sky only: not the crown's shadow on the ground)
    return leaf


def test_the_crown_is_lighter_on_its_sunlit_side(gl_ctx):
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=14.0, target=np.array([0.0, 4.6, 0.0]))
    to_eye = (camera.eye - camera.target) / np.linalg.norm(camera.eye - camera.target)
    across = np.cross(to_eye, [0.0, 1.0, 0.0])  # the sun from one side: edge-on to every card (no direct
    view = crown(to_eye)  # light, nothing through), so only where in the crown a card is can light it
    ratios = []
    for sun in (across, -across):
        image = draw_once(gl_ctx, view, camera, sun + np.array([0.0, 0.5, 0.0]))
        leaf, luma = leaf_pixels(gl_ctx, image, camera, sun + np.array([0.0, 0.5, 0.0])), image.sum(axis=2)
        halves = [(luma[:, cols][leaf[:, cols]]) for cols in (slice(0, SIZE[0] // 2), slice(SIZE[0] // 2, None))]
        assert min(len(h) for h in halves) > 1500  # (the crown is drawn, on both sides)
        ratios.append(halves[1].mean() / halves[0].mean())
    # the half toward the sun lighter, whichever side it is (the ratio of ratios: the crown's own
    # left-right differences cancel; 1.01 with the sunlit side's term left out of tree.frag)
    assert max(ratios) / min(ratios) > 1.25, ratios


def test_each_card_has_its_own_green(gl_ctx):
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=14.0, target=np.array([0.0, 4.6, 0.0]))
    to_eye = (camera.eye - camera.target) / np.linalg.norm(camera.eye - camera.target)
    sun = to_eye + np.array([0.0, 0.6, 0.0])
    image = draw_once(gl_ctx, crown(to_eye, 60), camera, sun)
    leaf = image[leaf_pixels(gl_ctx, image, camera, sun)]
    assert len(leaf) > 1500
    hue = (leaf[:, 0] + 1.0) / (leaf[:, 2] + 1.0)  # yellow-greens to blue-greens: red over blue
    assert np.percentile(hue, 85) > 1.35 * np.percentile(hue, 15)
