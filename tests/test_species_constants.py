"""The .lsys #defines are the one source of the interpretation constants (lengths, radii, leaf sizes,
tropisms, the modeler's lambda): the engine names them and reads their values from the species' file."""

from __future__ import annotations

import re
from pathlib import Path

from arbor.engine.life.form.interpret import (
    CONSTANT_NAMES,
    REFERENCE_SPECIES,
    interpretation_constants,
    reference_constants,
)
from arbor.engine.life.plant.growth import GrowingTree
from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem

ROOT = Path(__file__).resolve().parent.parent
LSYSTEMS = ROOT / "assets" / "lsystems"


def test_the_reference_species_defines_every_constant():
    system = load_lsystem(LSYSTEMS / REFERENCE_SPECIES)
    assert [k for k in CONSTANT_NAMES if k not in system.constants] == []
    assert reference_constants() == {k: float(system.constants[k]) for k in CONSTANT_NAMES}


def test_each_game_species_is_drawn_with_its_own_defines():
    reference = reference_constants()
    for name in ("game_tree.lsys", "game_poplar.lsys"):
        system = load_lsystem(LSYSTEMS / name)
        tree = GrowingTree(system)
        expected = {k: float(system.constants.get(k, reference[k])) for k in CONSTANT_NAMES}
        assert tree.geometry_constants == expected, name


def test_a_define_changed_in_the_lsys_changes_what_the_tree_is_drawn_with():
    path = LSYSTEMS / REFERENCE_SPECIES
    base = load_lsystem(path)
    changed = parse_lsystem(path.read_text(encoding="utf-8"), str(path),
                            overrides={"IO": base.constants["IO"] * 0.5, "GMAX": 7.0})
    const = GrowingTree(changed).geometry_constants
    assert const["IO"] == base.constants["IO"] * 0.5 and const["GMAX"] == 7.0


def test_an_lsys_without_them_takes_the_reference_species_values():
    system = load_lsystem(LSYSTEMS / "abop_2_8_tree.lsys")
    own = {k for k in CONSTANT_NAMES if k in system.constants}
    const = interpretation_constants(system.constants)
    assert {k: v for k, v in const.items() if k not in own} == {k: v for k, v in reference_constants().items()
                                                               if k not in own}


PENDING = {  # a fallback value still written in code, in a file another change owns today
    "engine/life/plant/carbon.py",  # QG and P in the cost of growing apices: the same
}


def test_no_copy_of_a_define_in_code():
    """No ``"IO": 0.72`` or ``.get("P", 4.0)`` value for a constant the host reads, in engine/ or game/."""
    names = "|".join(CONSTANT_NAMES)
    copy = re.compile(rf"""["']({names})["']\s*[:,]\s*[-+]?\.?\d""")
    found = [f"{path.relative_to(ROOT)}:{n}" for top in ("engine", "game") for path in (ROOT / top).rglob("*.py")
             if str(path.relative_to(ROOT)) not in PENDING
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if copy.search(line)]
    assert found == [], f"values of .lsys #defines copied into code: {found}"
