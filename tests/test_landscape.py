import json
import struct

import numpy as np
import pytest

from arbor.engine.forest.landscape import lod_levels, scatter, terrain_height, visible
from arbor.engine.geometry.export import export_garden
from arbor.game.render.camera import OrbitCamera
from tests.conftest import ROOT


@pytest.fixture(scope="module")
def presets():
    from arbor.game.commands.landscape import build_presets

    return build_presets()


def test_scatter_is_reproducible_spread_and_on_the_ground():
    a, b = scatter(500, 3, 150.0, seed=4), scatter(500, 3, 150.0, seed=4)
    assert np.array_equal(a.position, b.position) and np.array_equal(a.preset, b.preset)
    assert set(np.unique(a.preset)) == {0, 1, 2}
    np.testing.assert_allclose(a.position[:, 1], terrain_height(a.position[:, 0], a.position[:, 2], 150.0))
    gaps = np.linalg.norm(a.position[:, None, [0, 2]] - a.position[None, :, [0, 2]], axis=2)
    np.fill_diagonal(gaps, np.inf)
    assert gaps.min() > 0.5  # jittered cells: no two trees on top of each other
    assert np.abs(a.position[:, [0, 2]]).max() <= 75.0


def test_frustum_culling_and_lod_by_distance():
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=50.0)  # at +Z, looking towards -Z
    vp = camera.projection(16 / 9) @ camera.view()
    centers = np.array([[0, 0, 0], [0, 0, 80.0], [500, 0, 0], [0, 0, -40], [0, 0, -400]], float)
    shown = visible(centers, np.full(5, 1.0), vp)
    assert shown.tolist() == [True, False, False, True, True]  # behind the camera and far aside: culled
    near_edge = visible(np.array([[30.0, 0, 0]]), np.array([40.0]), vp)
    assert near_edge[0]  # a big sphere poking into view is kept
    levels = lod_levels(centers, camera.eye, tree_height=5.0)
    assert levels.tolist() == [2, 1, 3, 2, 3]  # 10, 6, 100, 18 and 90 tree heights away
    assert (np.diff(lod_levels(np.array([[0, 0, -d] for d in range(0, 400, 10)], float), camera.eye, 5.0)) >= 0).all()


def test_landscape_renders_many_trees(gl_ctx, presets):
    from arbor.game.commands.landscape import landscape_size, overview_camera
    from arbor.game.render.landscape import LandscapeRenderer
    from arbor.game.render.renderer import sun_direction

    side = landscape_size(300)
    renderer = LandscapeRenderer(gl_ctx, presets, side)
    instances = scatter(300, len(presets), side, seed=2)
    size = (640, 360)
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(size)],
                             depth_attachment=gl_ctx.depth_renderbuffer(size))
    full = renderer.render(fbo, overview_camera(side), sun_direction(80, 40), size, instances, lod=0)
    auto = renderer.render(fbo, overview_camera(side), sun_direction(80, 40), size, instances)
    img = np.frombuffer(fbo.read(components=3), np.uint8).reshape(size[1], size[0], 3)[::-1].astype(int)
    assert 0 < auto.culled < 300 and auto.drawn == full.drawn
    assert sum(auto.per_level) == auto.drawn and len([n for n in auto.per_level if n]) >= 2
    assert auto.triangles < 0.7 * full.triangles  # distance LOD draws fewer triangles
    bark = (img[..., 0] > img[..., 1]) & (img[..., 1] >= img[..., 2]) & (img[..., 0] > 90)
    assert bark.sum() > 300  # many trunks visible


def test_garden_glb_shares_meshes_between_instances(tmp_path, presets):
    instances = scatter(25, len(presets), 40.0, seed=1)
    path = export_garden(presets, instances, tmp_path / "garden.glb", ROOT / "assets" / "textures")
    data = path.read_bytes()
    gltf = json.loads(data[20 : 20 + struct.unpack_from("<I", data, 12)[0]])
    parts_per_tree = {p: sum(1 for a in ("wood", "leaves", "blossoms")
                             if getattr(presets[p].levels[1], a).n_triangles) for p in range(len(presets))}
    assert len(gltf["meshes"]) == sum(parts_per_tree.values())
    assert len([n for n in gltf["nodes"] if "mesh" in n]) == sum(parts_per_tree[p] for p in instances.preset)
    import trimesh

    scene = trimesh.load(path, process=False)
    placed = np.array([scene.graph[n][0][:3, 3] for n in scene.graph.nodes_geometry if n.endswith("-wood")])
    assert len(placed) == 25
    assert np.allclose(np.sort(placed[:, 0]), np.sort(instances.position[:, 0]), atol=1e-4)


def test_cli_landscape_with_chosen_presets(tmp_path, capsys):
    from arbor.game.cli import main

    out, glb = tmp_path / "land.png", tmp_path / "land.glb"
    assert main(["landscape", "40", "--size", "320x180", "--presets", "broadleaf,abop_2_8_tree:3", "--out",
                 str(out), "--glb", str(glb)]) == 0
    said = capsys.readouterr().out
    assert "40 trees" in said and "sharing 2 trees' meshes" in said
    import pygame

    assert pygame.image.load(str(out)).get_size() == (320, 180) and glb.stat().st_size > 10_000
