"""Export a tree as GLB (binary glTF 2.0) or OBJ+MTL through trimesh.

Wood, leaves and blossoms are separate primitives with their own materials: bark is opaque, leaves
and blossoms use alpha masking (cutoff 0.5) and are double-sided, as glTF allows. In a GLB they are the
children of one root node named after the tree, so Blender or any viewer imports one object hierarchy that
moves as one; images and materials carry names (bark, leaf, blossom) and the generator is Arbor with its
version. glTF's unit is the metre: ``metres`` (metres per scene unit) scales the positions, and the GLB's
asset block records the scale and the tree's height in metres (``asset.extras``). An OBJ's textures are
named after the export (``NAME_bark.png``), so exports sharing a folder keep their own.

The tree's height is the top of its wood above its base: the one definition the HUD, the postcard and the
export share (``engine.geometry.tree.tree_height``); the export writes it in the asset block.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh
from PIL import Image

from arbor.engine.base.files import atomic_write
from arbor.engine.base.version import version
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


def lod_scene(levels: list[TreeMesh], textures: Path, metres: float, name: str) -> trimesh.Scene:
    """Every level of detail of a tree in one scene: a node ``NAME_LOD0`` (the finest), ``NAME_LOD1``, ...
    per level (the suffix engines such as Unity and Blender's LOD add-ons group by), each holding that
    level's parts (``wood_LOD1`` ...); the levels share their materials and textures."""
    scene = trimesh.Scene()
    materials = {tex: _material(textures / f"{tex}.png", masked, tex) for _, tex, masked in PARTS}
    for k, tree in enumerate(levels):
        group = f"{name}_LOD{k}"
        scene.graph.update(frame_from=scene.graph.base_frame, frame_to=group)
        for attr, tex, _ in PARTS:
            mesh: Mesh = getattr(tree, attr)
            if mesh.n_triangles:
                scene.add_geometry(_trimesh(mesh, materials[tex], metres), node_name=f"{attr}_LOD{k}",
                                   geom_name=f"{attr}_LOD{k}", parent_node_name=group)
    return scene


def wood_top(tree: TreeMesh) -> float:
    """The top of a mesh's wood (scene units; of its other parts when it has no wood): the height of a
    tree whose turtle is not at hand (the caller's ``tree_height`` is the definition)."""
    for part in (tree.wood, tree.leaves, tree.blossoms):
        if len(part.positions):
            return float(part.positions[:, 1].max())
    return 0.0


ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963  # glTF bufferView targets: vertex data, indices


def _finish(name: str, metres: float, height: float):
    """A glTF tree postprocessor: the asset block says who wrote the file, its unit and the tree's height in
    metres; the parts become children of one root node ``name``; images are named after their materials;
    every bufferView of vertex data or indices says so (its target)."""
    def write(tree: dict) -> None:
        _label(tree)
        tree["asset"]["extras"] = {"unit": "metre", "metres_per_scene_unit": metres,
                                   "height_m": round(height * metres, 4)}
        _one_root(tree, name)
    return write


def _label(tree: dict) -> None:
    """Arbor as the generator, images named after their materials, bufferView targets set."""
    tree.setdefault("asset", {})["generator"] = f"Arbor {version()}"
    for material in tree.get("materials", []):
        texture = material.get("pbrMetallicRoughness", {}).get("baseColorTexture")
        if texture is not None:
            tree["images"][tree["textures"][texture["index"]]["source"]]["name"] = material["name"]
    _targets(tree)


def _one_root(tree: dict, name: str) -> None:
    """Put the scene's top nodes under one new root node called ``name``."""
    scene = tree["scenes"][tree.get("scene", 0)]
    tree.setdefault("nodes", []).append({"name": name, "children": scene.get("nodes", [])})
    scene["nodes"] = [len(tree["nodes"]) - 1]


def _targets(tree: dict) -> None:
    """Set each mesh bufferView's target (vertex attributes, indices), as the glTF validator hints."""
    views, accessors = tree.get("bufferViews", []), tree.get("accessors", [])
    for mesh in tree.get("meshes", []):
        for primitive in mesh["primitives"]:
            for accessor in primitive["attributes"].values():
                views[accessors[accessor]["bufferView"]]["target"] = ARRAY_BUFFER
            if "indices" in primitive:
                views[accessors[primitive["indices"]]["bufferView"]]["target"] = ELEMENT_ARRAY_BUFFER


def export_tree(tree: TreeMesh, path: str | Path, textures: Path, file_format: str | None = None,
                metres: float = 1.0, name: str | None = None, height: float | None = None,
                coarser: tuple[TreeMesh, ...] = ()) -> list[Path]:
    """Write ``tree`` to ``path`` as 'glb' or 'obj' (OBJ also writes .mtl and texture files beside it),
    ``metres`` per scene unit (the game's trees: 1 / METRE, so they arrive in Blender at their height);
    ``name`` names the tree's root node (default: the file's stem); ``height`` (scene units, the top of the
    wood: engine.geometry.tree.tree_height) goes into the GLB's asset block (default: the mesh's wood top).
    ``coarser``: the tree's coarser levels of detail, written with it into one GLB (:func:`lod_scene`).

    Returns the files written. The main file is written to a temp name and renamed, so an existing
    export is never left half-written.
    """
    path = Path(path)
    fmt = (file_format or path.suffix.lstrip(".")).lower()
    if coarser and fmt != "glb":
        raise ValueError("several levels of detail go in a GLB only")
    if fmt == "glb":
        finish = _finish(name or path.stem, metres, wood_top(tree) if height is None else height)
        scene = lod_scene([tree, *coarser], textures, metres, name or path.stem) if coarser else tree_scene(
            tree, textures, metres)
        data = trimesh.exchange.gltf.export_glb(scene, include_normals=True, tree_postprocessor=finish)
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
        image = f"{path.stem}_{tex}.png"  # after the export: two exports in one folder keep their own
        atomic_write(path.parent / image, (textures / f"{tex}.png").read_bytes())
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
    atomic_write(path, trimesh.exchange.gltf.export_glb(scene, include_normals=True, tree_postprocessor=_label))
    return path
