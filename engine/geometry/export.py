"""Export a tree as GLB (binary glTF 2.0) or OBJ+MTL through trimesh.

Wood, leaves and blossoms are separate primitives with their own materials: bark is opaque, leaves
and blossoms use alpha masking (cutoff 0.5) and are double-sided, as glTF allows.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh
from PIL import Image

from engine.base.files import atomic_write
from engine.geometry.mesh import Mesh, TreeMesh

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


def _trimesh(mesh: Mesh, material) -> trimesh.Trimesh:
    visual = trimesh.visual.TextureVisuals(uv=mesh.uvs.astype(np.float64), material=material)
    return trimesh.Trimesh(
        vertices=mesh.positions.astype(np.float64),
        faces=mesh.indices.astype(np.int64),
        vertex_normals=mesh.normals.astype(np.float64),
        visual=visual,
        process=False,
    )


def tree_scene(tree: TreeMesh, textures: Path) -> trimesh.Scene:
    """A trimesh scene with one textured geometry per non-empty part of the tree."""
    scene = trimesh.Scene()
    for attr, tex, masked in PARTS:
        mesh: Mesh = getattr(tree, attr)
        if mesh.n_triangles:
            material = _material(textures / f"{tex}.png", masked, tex)
            scene.add_geometry(_trimesh(mesh, material), node_name=attr, geom_name=attr)
    return scene


def export_tree(tree: TreeMesh, path: str | Path, textures: Path, file_format: str | None = None) -> list[Path]:
    """Write ``tree`` to ``path`` as 'glb' or 'obj' (OBJ also writes .mtl and texture files beside it).

    Returns the files written. The main file is written to a temp name and renamed, so an existing
    export is never left half-written.
    """
    path = Path(path)
    fmt = (file_format or path.suffix.lstrip(".")).lower()
    scene = tree_scene(tree, textures)
    if fmt == "glb":
        data = trimesh.exchange.gltf.export_glb(scene, include_normals=True)
        atomic_write(path, data)
        return [path]
    if fmt == "obj":
        text, extras = trimesh.exchange.obj.export_obj(
            scene, include_normals=True, include_texture=True, return_texture=True, mtl_name=path.stem + ".mtl"
        )
        written = []
        for name, blob in extras.items():
            atomic_write(path.parent / name, blob)
            written.append(path.parent / name)
        atomic_write(path, text.encode("utf-8"))
        return [path, *written]
    raise ValueError(f"unknown export format {fmt!r}: use glb or obj")


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
