"""From an L-string to the geometry of a tree: the one pipeline the game, render and export share."""

from __future__ import annotations

from dataclasses import dataclass

from arbor.engine.geometry.mesh import TreeMesh, lod_level, tree_mesh
from arbor.engine.geometry.turtle import TurtleConfig, TurtleResult, interpret
from arbor.engine.lsystem.lstring import LString
from arbor.engine.lsystem.lsys import LSystem


@dataclass
class TreeGeometry:
    """A tree's turtle output (for picking and overlays) and its meshes at one LOD level."""

    turtle: TurtleResult
    mesh: TreeMesh


def tree_height(geometry: TreeGeometry) -> float:
    """The tree's height (scene units): the top of its wood above its base (the ground, y = 0). The one
    definition the HUD, the postcard and exports share; leaf cards may reach a little higher."""
    ends = geometry.turtle.segments.end
    return float(ends[:, 1].max()) if len(ends) else 0.0


def build_geometry(ls: LString, system: LSystem, lod: int = 0, **turtle_overrides) -> TreeGeometry:
    """Interpret ``ls`` with the defaults of ``system`` and mesh it at LOD level ``lod``."""
    turtle = interpret(ls, TurtleConfig.from_system(system, **turtle_overrides))
    return TreeGeometry(turtle, tree_mesh(turtle, lod_level(lod)))
