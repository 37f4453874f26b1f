"""How each species looks in the garden: its bark's tint and its leaf-cluster card (shape and green).

A tree's species is its lineage's (``game_tree``, ``game_poplar``: the .lsys it grows by; a cross of two
species is ``cross``). The bark's albedo and relief are shared (game/render/textures.py) and tinted per
species here; age darkens every bark alike in the shader (by the branch's radius). Unknown species (a
save from a newer game, an .lsys of the player's) look like the game tree.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace

from arbor.engine.life.plant.seasons import evergreen


@dataclass(frozen=True)
class SpeciesLook:
    """A species' look: ``bark`` and ``leaf`` multiply the renderer's tints (which carry the tree's
    health and the season), ``cluster`` names its leaf-cluster texture in assets/textures; an ``evergreen``'s
    leaves neither turn in autumn nor thin out in winter (its .lsys keeps them on: EVERGREEN)."""

    bark: tuple[float, float, float] = (1.0, 1.0, 1.0)
    leaf: tuple[float, float, float] = (1.0, 1.0, 1.0)
    cluster: str = "leaf_cluster"
    evergreen: bool = False


GAME_TREE = SpeciesLook()  # grey-brown furrowed bark, sprays of dark oval leaves
LOOKS = {
    "game_tree": GAME_TREE,
    # a poplar: pale grey-white bark, lighter yellow-green broad triangular leaves on long stalks
    "game_poplar": SpeciesLook(bark=(1.32, 1.34, 1.36), leaf=(1.08, 1.1, 0.9), cluster="leaf_cluster_deltoid"),
    "cross": SpeciesLook(bark=(1.15, 1.15, 1.16), leaf=(1.04, 1.05, 0.95)),  # between its parents
    # the collection's others (assets/species.toml): a spruce's red-brown scaly bark and blue-green needles,
    # a birch's white bark and light triangular leaves, a willow's grey-yellow bark and long narrow
    # yellow-green leaves, an oak's dark bark and deep green lobed leaves
    "spruce": SpeciesLook(bark=(0.95, 0.78, 0.68), leaf=(0.8, 0.92, 0.95), cluster="leaf_cluster_needle",
                          evergreen=True),
    "birch": SpeciesLook(bark=(1.75, 1.75, 1.7), leaf=(1.12, 1.14, 0.85), cluster="leaf_cluster_deltoid"),
    "willow": SpeciesLook(bark=(1.15, 1.08, 0.9), leaf=(1.1, 1.1, 0.85), cluster="leaf_cluster_lance"),
    "oak": SpeciesLook(bark=(0.8, 0.78, 0.74), leaf=(0.88, 1.0, 0.85), cluster="leaf_cluster_lobed"),
}
CLUSTERS = sorted({look.cluster for look in LOOKS.values()})  # the textures the renderer loads


def look_of(species: str, constants: Mapping[str, float] | None = None) -> SpeciesLook:
    """The look of ``species`` (a lineage's species name); the game tree's when it is not known. With the
    tree's .lsys ``constants``, evergreen when they say so (EVERGREEN: a cross of a spruce keeps its leaves
    in winter as the host keeps them on, whatever its look)."""
    look = LOOKS.get(species, GAME_TREE)
    if constants is not None and evergreen(constants) and not look.evergreen:
        return replace(look, evergreen=True)
    return look
