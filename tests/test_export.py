import json
import struct
from importlib.metadata import version as installed_version
from pathlib import Path

import numpy as np
import pytest
import trimesh

from arbor.engine.base.version import DISTRIBUTION
from arbor.engine.geometry.export import export_tree
from arbor.engine.geometry.tree import build_geometry
from arbor.engine.lsystem.derive import derive
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.cli import main

TEXTURES = Path(__file__).resolve().parent.parent / "assets" / "textures"


@pytest.fixture(scope="module")
def tree(lsys_dir):
    system = load_lsystem(lsys_dir / "abop_2_8_tree.lsys")
    return build_geometry(derive(system, 4), system, lod=1).mesh


def _bounds(tree):
    pts = np.concatenate([tree.wood.positions, tree.leaves.positions]).astype(float)
    return pts.min(axis=0), pts.max(axis=0)


def test_glb_round_trip_counts_and_bounds(tree, tmp_path):
    path = tmp_path / "tree.glb"
    export_tree(tree, path, TEXTURES)
    scene = trimesh.load(path, process=False)
    geoms = scene.geometry
    assert {(len(g.vertices), len(g.faces)) for g in geoms.values()} == {
        (len(tree.wood.positions), tree.wood.n_triangles),
        (len(tree.leaves.positions), tree.leaves.n_triangles),
    }
    lo, hi = _bounds(tree)
    np.testing.assert_allclose(scene.bounds, [lo, hi], rtol=1e-5, atol=1e-4)


def test_glb_structure_follows_the_spec(tree, tmp_path):
    path = tmp_path / "tree.glb"
    export_tree(tree, path, TEXTURES)
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert (magic, version, length) == (b"glTF", 2, len(data))
    json_len, json_type = struct.unpack_from("<II", data, 12)
    assert json_type == 0x4E4F534A and json_len % 4 == 0
    gltf = json.loads(data[20 : 20 + json_len])
    bin_len, bin_type = struct.unpack_from("<II", data, 20 + json_len)
    assert bin_type == 0x004E4942 and 28 + json_len + bin_len == len(data)
    assert gltf["asset"]["version"] == "2.0"
    for view in gltf["bufferViews"]:
        assert view["byteOffset"] + view["byteLength"] <= gltf["buffers"][0]["byteLength"]
    mats = {m["name"]: m for m in gltf["materials"]}
    assert mats["leaf"]["alphaMode"] == "MASK" and mats["leaf"]["doubleSided"] is True
    assert mats["bark"].get("alphaMode", "OPAQUE") == "OPAQUE"
    for mesh in gltf["meshes"]:
        attrs = mesh["primitives"][0]["attributes"]
        assert {"POSITION", "NORMAL", "TEXCOORD_0"} <= set(attrs)
        pos = gltf["accessors"][attrs["POSITION"]]
        assert "min" in pos and "max" in pos
    assert len(gltf["images"]) == 2 and len(gltf["textures"]) == 2
    assert sorted(image["name"] for image in gltf["images"]) == ["bark", "leaf"]
    assert gltf["asset"]["generator"] == f"Arbor {installed_version(DISTRIBUTION)}"
    for mesh in gltf["meshes"]:  # vertex data and indices say which they are (the validator's hint)
        primitive = mesh["primitives"][0]
        targets = {gltf["bufferViews"][gltf["accessors"][a]["bufferView"]].get("target")
                   for a in primitive["attributes"].values()}
        assert targets == {34962}
        assert gltf["bufferViews"][gltf["accessors"][primitive["indices"]]["bufferView"]]["target"] == 34963


def test_a_glb_holds_one_tree_under_one_named_root(tree, tmp_path):
    """One root node named after the tree, wood and leaves its children: Blender imports one hierarchy."""
    path = tmp_path / "oak.glb"
    export_tree(tree, path, TEXTURES)
    gltf = _glb_json(path)
    roots = gltf["scenes"][gltf["scene"]]["nodes"]
    assert len(roots) == 1
    root = gltf["nodes"][roots[0]]
    assert root["name"] == "oak" and "mesh" not in root
    assert sorted(gltf["nodes"][c]["name"] for c in root["children"]) == ["leaves", "wood"]
    scene = trimesh.load(path, process=False)  # trimesh reads the same hierarchy: both parts below the root
    assert {scene.graph.transforms.parents[n] for n in ("wood", "leaves")} == {"oak"}


def test_obj_with_mtl_round_trip(tree, tmp_path):
    path = tmp_path / "tree.obj"
    files = export_tree(tree, path, TEXTURES)
    names = {f.name for f in files}
    assert names == {"tree.obj", "tree.mtl", "tree_bark.png", "tree_leaf.png"}  # textures named after the export
    assert "map_Kd tree_bark.png" in (tmp_path / "tree.mtl").read_text()
    scene = trimesh.load(path, process=False)
    faces = sum(len(g.faces) for g in scene.geometry.values())
    assert faces == tree.wood.n_triangles + tree.leaves.n_triangles
    lo, hi = _bounds(tree)
    np.testing.assert_allclose(scene.bounds, [lo, hi], rtol=1e-4, atol=1e-3)


def test_cli_export(tmp_path, lsys_dir, capsys):
    out = tmp_path / "t.glb"
    assert main(["export", str(lsys_dir / "seed003_tree.lsys"), "--steps", "3", "--out", str(out)]) == 0
    assert out.stat().st_size > 1000 and [p.name for p in tmp_path.iterdir()] == ["t.glb"]
    assert "triangles" in capsys.readouterr().out


def test_cli_reports_bad_source(tmp_path, capsys):
    bad = tmp_path / "bad.lsys"
    bad.write_text("w: F\np1: F -> F(\n")
    assert main(["export", str(bad), "--out", str(tmp_path / "x.glb")]) == 1  # a runtime failure, not usage
    assert f"{bad}:2:" in capsys.readouterr().err


VALIDATOR = Path(__file__).resolve().parent.parent / ".ci" / "gltf" / "node_modules" / "gltf-validator"
VALIDATE_JS = """
const v = require(process.argv[1]); const fs = require('fs');
v.validateBytes(new Uint8Array(fs.readFileSync(process.argv[2]))).then(r => {
  console.log(JSON.stringify({errors: r.issues.numErrors, warnings: r.issues.numWarnings,
                              hints: r.issues.numHints}));
});
"""


@pytest.mark.skipif(not VALIDATOR.is_dir(), reason="Khronos glTF validator not installed (.ci/run installs it)")
def test_glb_passes_khronos_validator(tree, tmp_path):
    import shutil
    import subprocess

    path = tmp_path / "tree.glb"
    export_tree(tree, path, TEXTURES)
    node = shutil.which("node")
    assert node, "node is needed to run the validator"
    out = subprocess.run([node, "-e", VALIDATE_JS, str(VALIDATOR), str(path)], capture_output=True, timeout=120)
    report = json.loads(out.stdout.decode().strip().splitlines()[-1])
    assert report == {"errors": 0, "warnings": 0, "hints": 0}, out.stdout.decode()


def _glb_json(path: Path) -> dict:
    data = path.read_bytes()
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length])


def test_exports_arrive_at_their_height_in_metres(tmp_path, lsys_dir, capsys):
    """The source's declared unit (abop_2_8_tree.lsys: 'unit: 0.01') sets the size by default; the height is
    the top of the wood (engine.geometry.tree.tree_height), written in the asset block; --height and
    --scale override the unit."""
    from arbor.engine.geometry.tree import tree_height

    source = lsys_dir / "abop_2_8_tree.lsys"
    system = load_lsystem(source)
    assert system.unit == 0.01
    height = tree_height(build_geometry(derive(system, 4), system, lod=0))  # turtle units
    out = tmp_path / "scene.glb"
    assert main(["export", str(source), "--steps", "4", "--out", str(out)]) == 0
    wood = trimesh.load(out, process=False).geometry["wood"]
    assert wood.bounds[1][1] == pytest.approx(height * 0.01, rel=1e-3)  # the top of the wood, in metres
    out_text, err = capsys.readouterr()
    assert f"{height * 0.01:.2f} m tall (top of the wood)" in out_text and "warning" not in err  # a likely size
    asset = _glb_json(out)["asset"]
    assert asset["version"] == "2.0" and asset["extras"]["unit"] == "metre"
    assert asset["extras"]["height_m"] == pytest.approx(height * 0.01, rel=1e-3)
    for flag, value, metres in (("--height", "12", 12.0), ("--scale", "0.001", height * 0.001)):
        out = tmp_path / f"{flag[2:]}.glb"
        assert main(["export", str(source), "--steps", "4", flag, value, "--out", str(out)]) == 0
        assert trimesh.load(out, process=False).geometry["wood"].bounds[1][1] == pytest.approx(metres, rel=1e-3)
    obj = tmp_path / "tree.obj"
    assert main(["export", str(source), "--steps", "4", "--height", "3", "--out", str(obj)]) == 0
    lines = obj.read_text().splitlines()
    wood_lines = lines[:next(i for i, line in enumerate(lines) if line == "o leaves")]
    ys = [float(line.split()[2]) for line in wood_lines if line.startswith("v ")]
    assert max(ys) == pytest.approx(3.0, rel=1e-3)


def test_a_source_without_a_unit_is_in_the_scenes_and_a_tree_of_an_unlikely_size_is_warned(tmp_path, capsys):
    from arbor.engine.base.units import METRE

    source = tmp_path / "pole.lsys"
    source.write_text("w: F(30)\n")  # 30 scene units: 3 m
    assert main(["export", str(source), "--out", str(tmp_path / "p.glb")]) == 0
    out, err = capsys.readouterr()
    assert f"{30 / METRE:.2f} m tall" in out and "warning" not in err
    source.write_text("unit: 5\nw: F(30)\n")  # 150 m
    assert main(["export", str(source), "--out", str(tmp_path / "q.glb")]) == 0
    assert "150 m tall (over 100 m)" in capsys.readouterr().err
    assert main(["export", str(source), "--scale", "0.0001", "--out", str(tmp_path / "r.glb")]) == 0
    assert "(under 1 cm)" in capsys.readouterr().err


@pytest.mark.parametrize("value", ["0", "-2", "nan", "inf", "1e9", "tall"])
def test_export_sizes_are_checked(tmp_path, lsys_dir, value, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["export", str(lsys_dir / "abop_2_8_tree.lsys"), "--height", value, "--out", str(tmp_path / "x.glb")])
    assert exit_.value.code == 2 and "--height" in capsys.readouterr().err
