import numpy as np
import pytest
import trimesh

from arbor.engine.geometry.mesh import LOD_LEVELS, leaf_mesh, lod_level, tree_mesh, wood_mesh
from arbor.engine.geometry.turtle import TurtleConfig, interpret
from arbor.engine.lsystem.derive import derive
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem


def segs_of(text, **cfg):
    return interpret(parse_lstring(text), TurtleConfig(**cfg)).segments


def test_rings_are_shared_along_an_axis_and_caps_only_at_tips():
    segs = segs_of("!(1)FFF[+F]F", leaves_at_tips=0)
    n_surf = 6
    mesh = wood_mesh(segs, n_surf=n_surf, n_div=1)
    # 5 segments: 5 end rings + 2 axis-start rings (trunk, branch), n_surf+1 vertices each, + 2 tip vertices
    assert len(mesh.positions) == (5 + 2) * (n_surf + 1) + 2
    # tubes: 5 segments x n_surf quads; caps: 2 tips x n_surf triangles
    assert mesh.n_triangles == 5 * n_surf * 2 + 2 * n_surf
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-5)


def test_tube_is_closed_except_the_base():
    mesh = wood_mesh(segs_of("!(1)F+(20)F-(35)F/(90)F"), n_surf=8, n_div=3)
    tm = trimesh.Trimesh(mesh.positions, mesh.indices, process=True, merge_tex=True, merge_norm=True)
    assert tm.is_winding_consistent
    # the only open boundary is the bottom ring of the trunk
    edges = tm.edges_sorted
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert (counts == 1).sum() == 8


def test_no_twist_when_the_turtle_rolls():
    mesh = wood_mesh(segs_of("!(1)F/(120)F/(120)F/(77)F"), n_surf=8, n_div=1)
    second = mesh.indices[1 : 4 * 8 * 2 : 2]  # triangles (a, b+1, b): a and b are one side edge
    a, b = mesh.positions[second[:, 0]], mesh.positions[second[:, 2]]
    turn = np.degrees(np.arctan2(a[:, 0] * b[:, 2] - a[:, 2] * b[:, 0], a[:, 0] * b[:, 0] + a[:, 2] * b[:, 2]))
    # side edges of the straight tube stay at the same angle around it: rings are transported, not rolled
    assert np.max(np.abs(turn)) < 1.0


def test_uv_v_counts_growth_steps():
    mesh = wood_mesh(segs_of("!(1)F(3)F(1)F(2)"), n_surf=4, n_div=1)
    ring_vertices = slice(0, len(mesh.positions) - 1)  # the last vertex is the tip of the cap
    top = mesh.uvs[ring_vertices][mesh.positions[ring_vertices, 1] > 5.5]
    assert top[:, 1].max() == pytest.approx(3.0)
    assert mesh.uvs[:, 0].min() == 0.0 and mesh.uvs[:, 0].max() == pytest.approx(1.0)


def test_face_module_maps_geometry_back_to_the_string():
    ls = parse_lstring("!(1)F[+F]A F")
    mesh = wood_mesh(interpret(ls).segments, n_surf=5)
    assert set(np.unique(mesh.face_module)) == {1, 4, 7}


def test_leaf_quads():
    result = interpret(parse_lstring("F[+L(2)][-L(2)]"), TurtleConfig(leaves_at_tips=0))
    mesh = leaf_mesh(result.leaves)
    assert mesh.n_triangles == 4 and len(mesh.positions) == 8
    assert np.linalg.norm(mesh.positions[2] - mesh.positions[1]) == pytest.approx(2.0)


def test_a_level_number_becomes_a_mesh_level_in_one_place(lsys_dir):
    """lod_level clamps to the levels there are; build_geometry and grow_geometry mesh at it; no other code
    indexes LOD_LEVELS (issue 42: the LOD choice was made in two places)."""
    import ast
    from pathlib import Path

    from arbor.engine.geometry.tree import build_geometry
    from arbor.engine.life.rules.rules import Rules
    from arbor.engine.life.world.world import World

    last = len(LOD_LEVELS) - 1
    assert [lod_level(k) for k in (-2, 0, 1, last, last + 5)] == [LOD_LEVELS[0], LOD_LEVELS[0], LOD_LEVELS[1],
                                                                 LOD_LEVELS[last], LOD_LEVELS[last]]
    system = load_lsystem(lsys_dir / "abop_2_8_tree.lsys")
    ls = derive(system, 4)
    clamped = [build_geometry(ls, system, lod=k).mesh.n_triangles for k in (last, last + 3, 0, -1)]
    assert clamped[0] == clamped[1] < clamped[2] == clamped[3]
    world = World(load_lsystem(lsys_dir / "game_tree.lsys"), Rules(), seed=1)  # (grow_geometry)
    grown = [world.tree.geometry(world.clocks(), lod=k).mesh.n_triangles for k in (last + 3, last, 0)]
    assert grown[0] == grown[1] < grown[2]
    root = Path(__file__).resolve().parent.parent
    for path in [*(root / "engine").rglob("*.py"), *(root / "game").rglob("*.py")]:
        if path.name == "mesh.py" and path.parent.name == "geometry":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Subscript) and "LOD_LEVELS" in (getattr(node.value, "id", ""),
                                                                     getattr(node.value, "attr", "")):
                raise AssertionError(f"{path.relative_to(root)}:{node.lineno} picks a LOD level: use lod_level")


def test_lod_levels_reduce_triangles_and_keep_silhouette(lsys_dir):
    system = load_lsystem(lsys_dir / "abop_2_8_tree.lsys")
    result = interpret(derive(system, 6), TurtleConfig.from_system(system))
    counts, boxes = [], []
    for level in LOD_LEVELS:
        tm = tree_mesh(result, level)
        counts.append(tm.n_triangles)
        pts = np.concatenate([tm.wood.positions, tm.leaves.positions])
        boxes.append((pts.min(axis=0), pts.max(axis=0)))
    assert counts == sorted(counts, reverse=True) and counts[-1] < counts[0] / 8
    size = boxes[0][1] - boxes[0][0]
    for lo, hi in boxes[1:]:
        assert np.all(np.abs(lo - boxes[0][0]) < 0.08 * size) and np.all(np.abs(hi - boxes[0][1]) < 0.08 * size)
