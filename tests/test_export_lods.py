"""Every level of detail in one GLB (issue 48): arbor export --lods writes LOD 0-3 of a tree into one file,
each level a node NAME_LODk (the suffix engines group levels by) under the tree's root, holding that
level's wood and leaves; the levels share materials and textures and get coarser; an OBJ cannot hold
them (one line says so)."""

import json
import struct
from itertools import pairwise
from pathlib import Path

from arbor.game.cli import main

SOURCE = Path(__file__).resolve().parent.parent / "assets" / "lsystems" / "abop_2_8_tree.lsys"


def gltf(path: Path) -> dict:
    data = path.read_bytes()
    length = struct.unpack("<I", data[12:16])[0]
    return json.loads(data[20:20 + length])


def test_all_levels_of_detail_in_one_glb(tmp_path, capsys):
    out = tmp_path / "tree.glb"
    assert main(["export", str(SOURCE), "--steps", "6", "--out", str(out), "--lods", "-q"]) == 0
    tree = gltf(out)
    nodes = tree["nodes"]
    root = next(n for n in nodes if n.get("name") == "tree")
    levels = [nodes[k] for k in root["children"]]
    assert [n["name"] for n in levels] == ["tree_LOD0", "tree_LOD1", "tree_LOD2", "tree_LOD3"]
    triangles = []
    for k, level in enumerate(levels):
        parts = [nodes[c] for c in level["children"]]
        assert {p["name"] for p in parts} == {f"wood_LOD{k}", f"leaves_LOD{k}"}
        accessors = [tree["meshes"][p["mesh"]]["primitives"][0]["indices"] for p in parts]
        triangles.append(sum(tree["accessors"][a]["count"] // 3 for a in accessors))
    print(f"triangles per level: {triangles}")
    assert all(a > b for a, b in pairwise(triangles))  # coarser and coarser
    assert len(tree["materials"]) == 2 and len(tree["images"]) == 2  # (shared by the levels)
    assert main(["export", str(SOURCE), "--steps", "6", "--out", str(tmp_path / "tree.obj"), "--lods"]) != 0
    assert "GLB" in capsys.readouterr().err
