"""Export a tree as GLB (binary glTF 2.0) or OBJ+MTL through trimesh.

Wood, leaves and blossoms are separate primitives with their own materials: bark is opaque, leaves
and blossoms use alpha masking (cutoff 0.5) and are double-sided, as glTF allows. glTF's unit is the metre:
``metres`` (metres per scene unit) scales the positions, and the GLB's asset block records the scale and the
tree's height in metres (``asset.extras``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh
from PIL import Image

from arbor.engine.base.files import atomic_write
from arbor.engine.geometry.mesh import Mesh, TreeMesh

PARTS = (("wood", "bark", False), ("leaves", "leaf", True), ("blossoms", "blossom", True))


def _material(texture: Path, masked: bool, name: str) -> trimesh.visual.material.PBRMaterial:
    image = Image.open(texture)
    image.load()
    return trimesh.visual.material.PBRMaterial(
        name=name,
        baseColorTexture=image,
        metallicFactor=0.0,
        roughnessFactor=0.9 if not masked else 0.6,
        alphaMode="MASK" if masked else "OPAQUE",
        alphaCutoff=0.5 if masked else None,
        doubleSided=masked,
    )


def _trimesh(mesh: Mesh, material, metres: float = 1.0) -> trimesh.Trimesh:
    visual = trimesh.visual.TextureVisuals(uv=mesh.uvs.astype(np.float64), material=material)
    return trimesh.Trimesh(
        vertices=mesh.positions.astype(np.float64) * metres,
        faces=mesh.indices.astype(np.int64),
        vertex_normals=mesh.normals.astype(np.float64),
        visual=visual,
        process=False,
    )


def tree_scene(tree: TreeMesh, textures: Path, metres: float = 1.0) -> trimesh.Scene:
    """A trimesh scene with one textured geometry per non-empty part of the tree, ``metres`` per scene unit."""
    scene = trimesh.Scene()
    for attr, tex, masked in PARTS:
        mesh: Mesh = getattr(tree, attr)
        if mesh.n_triangles:
            material = _material(textures / f"{tex}.png", masked, tex)
            scene.add_geometry(_trimesh(mesh, material, metres), node_name=attr, geom_name=attr)
    return scene


def tree_height(tree: TreeMesh) -> float:
    """Height of the tree's geometry above its base (scene units): what ``--height`` sets on export."""
    ys = [part.positions[:, 1] for part in (tree.wood, tree.leaves, tree.blossoms) if len(part.positions)]
    return float(np.concatenate(ys).max()) if ys else 0.0


def _asset_block(metres: float, height: float):
    """A glTF tree postprocessor: the asset block says the file's unit and the tree's height in metres."""
    def write(tree: dict) -> None:
        tree.setdefault("asset", {})["extras"] = {"unit": "metre", "metres_per_scene_unit": metres,
                                                  "height_m": round(height * metres, 4)}
    return write


def export_tree(tree: TreeMesh, path: str | Path, textures: Path, file_format: str | None = None,
                metres: float = 1.0) -> list[Path]:
    """Write ``tree`` to ``path`` as 'glb' or 'obj' (OBJ also writes .mtl and texture files beside it),
    ``metres`` per scene unit (the game's trees: 1 / METRE, so they arrive in Blender at their height).

    Returns the files written. The main file is written to a temp name and renamed, so an existing
    export is never left half-written.
    """
    path = Path(path)
    fmt = (file_format or path.suffix.lstrip(".")).lower()
    if fmt == "glb":
        data = trimesh.exchange.gltf.export_glb(tree_scene(tree, textures, metres), include_normals=True,
                                                tree_postprocessor=_asset_block(metres, tree_height(tree)))
        atomic_write(path, data)
        return [path]
    if fmt == "obj":
        return _export_obj(tree, path, textures, metres)
    raise ValueError(f"unknown export format {fmt!r}: use glb or obj")


def _rows(line: str, values: np.ndarray) -> str:
    """Numbers as OBJ lines, ``line`` formatting one row (one format call for all rows)."""
    return (line * len(values)) % tuple(values.ravel().tolist()) if len(values) else ""


def _export_obj(tree: TreeMesh, path: Path, textures: Path, metres: float = 1.0) -> list[Path]:
    """OBJ + MTL with our own normals and UVs, one object per part; the MTL keeps leaf and blossom
    transparency (``map_d``). Written here rather than through trimesh, whose OBJ writer drops stored
    normals and recomputes them (minutes for a big tree without scipy)."""
    mtl_name = path.stem + ".mtl"
    chunks, mtl, written, base = [f"mtllib {mtl_name}\n"], [], [], 0
    for attr, tex, masked in PARTS:
        mesh: Mesh = getattr(tree, attr)
        if not mesh.n_triangles:
            continue
        image = f"{tex}.png"
        atomic_write(path.parent / image, (textures / image).read_bytes())
        written.append(path.parent / image)
        mtl.append(f"newmtl {tex}\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nillum 1\nmap_Kd {image}\n"
                   + (f"map_d {image}\nd 1.0\n" if masked else "d 1.0\n"))
        faces = mesh.indices.astype(np.int64) + base + 1
        triples = np.repeat(faces, 3, axis=1)  # v/vt/vn share one index per vertex
        chunks += [f"o {attr}\n", _rows("v %.6g %.6g %.6g\n", mesh.positions * metres),
                   _rows("vt %.6g %.6g\n", mesh.uvs), _rows("vn %.4g %.4g %.4g\n", mesh.normals), f"usemtl {tex}\n",
                   _rows("f %d/%d/%d %d/%d/%d %d/%d/%d\n", triples)]
        base += len(mesh.positions)
    atomic_write(path.parent / mtl_name, "\n".join(mtl).encode("utf-8"))
    atomic_write(path, "".join(chunks).encode("utf-8"))
    return [path, path.parent / mtl_name, *written]


def export_garden(presets, instances, path: str | Path, textures: Path, lod: int = 1) -> Path:
    """Write many trees as one GLB: one mesh per preset part, one node per tree and part (glTF
    instancing: every node of a kind references the same mesh, so the file stays small)."""
    scene = trimesh.Scene()
    matrices = instances.matrices()
    materials = {tex: _material(textures / f"{tex}.png", masked, tex) for _, tex, masked in PARTS}
    for p, preset in enumerate(presets):
        tree: TreeMesh = preset.levels[lod]
        for attr, tex, _ in PARTS:
            mesh: Mesh = getattr(tree, attr)
            if not mesh.n_triangles:
                continue
            geom = f"{preset.name}-{attr}"
            first = True
            for i in np.flatnonzero(instances.preset == p):
                node = f"tree{i}-{attr}"
                if first:
                    scene.add_geometry(_trimesh(mesh, materials[tex]), node_name=node, geom_name=geom,
                                       transform=matrices[i])
                    first = False
                else:
                    scene.graph.update(frame_from=scene.graph.base_frame, frame_to=node, matrix=matrices[i],
                                       geometry=geom)
    path = Path(path)
    atomic_write(path, trimesh.exchange.gltf.export_glb(scene, include_normals=True))
    return path
