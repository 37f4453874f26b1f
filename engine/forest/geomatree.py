"""GeoMaTree species (Jung et al. section 4): growth-model parameters as presets, grown by an L-system.

A preset fills the #defines of assets/lsystems/geomatree.lsys; the tree's seed fixes the n_seed
random seed points of its growth space (each branch picks one; eq. 1) and, through Algorithm 2,
how many side branches each level carries. Same preset + another seed -> a similar tree with
different detail.
"""

from __future__ import annotations

import errno
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from arbor.engine.base.config import fill_dataclass
from arbor.engine.base.errors import LSysError, SettingsError
from arbor.engine.base.reader import read_user_text, read_user_toml
from arbor.engine.forest.divisors import FUNCTIONS, PropagationRule, children_function, children_table
from arbor.engine.lsystem.lsys import MAX_SOURCE_BYTES, LSystem, parse_lsystem


@dataclass
class Species:
    """Seed 001's parameters: r_bud, l_i, theta_i, phi_i, n_seed, v_ext, r_0, phi_k, l_k (+ a few).

    v_ext is the external vector of eq. 1 (gravity, phototropism, wind): each branch turns towards it
    by |v_ext| degrees (never past it).
    """

    name: str = "species"
    trunk: float = 6.0
    r_bud: float = 0.62
    l_i: float = 0.72
    theta_i: float = 40.0
    phi_i: float = 137.5
    n_seed: int = 5
    seed_spread: float = 18.0
    v_ext: list = None  # external vector [x, y, z]; its length is degrees of turn per branch
    r_0: float = 0.2
    phi_k: float = 90.0
    l_k: float = 0.08
    levels: int = 5
    branch_function: str = "sigma"
    branch_coefficient: int = 1
    max_children: int = 3

    def __post_init__(self) -> None:
        if self.v_ext is None:
            self.v_ext = [0.0, 0.0, 0.0]


def load_species(path: str | Path) -> Species:
    """A preset file; unknown keys, wrong types or out-of-range values name the file and key."""
    species = Species()
    text, data = read_user_toml(path, SettingsError, 65_536)  # (the one reader for users' files)
    fill_dataclass(species, data, str(path), "species parameter", SettingsError, text)
    if len(species.v_ext) != 3 or not all(isinstance(v, int | float) and not isinstance(v, bool)
                                          for v in species.v_ext):
        raise LSysError("v_ext must be three numbers [x, y, z]", str(path))
    species.v_ext = [float(v) for v in species.v_ext]
    if species.branch_function not in ("sigma", "sigma_alt", "sigma_star"):
        raise LSysError("branch_function must be sigma, sigma_alt or sigma_star", str(path))
    if not (0 < species.r_bud < 1 and 1 <= species.n_seed <= 64 and 1 <= species.levels <= 8
            and 1 <= species.max_children <= 4):
        raise LSysError("r_bud in (0, 1), n_seed 1-64, levels 1-8, max_children 1-4", str(path))
    return species


def seed_points(species: Species, seed: int) -> np.ndarray:
    """(n_seed, 2) pitch and roll offsets (degrees) of the growth space's seed points: uniform over a
    cone of half-angle seed_spread around the basis direction."""
    rng = np.random.default_rng([seed, 1])
    radius = species.seed_spread * np.sqrt(rng.random(species.n_seed))
    angle = rng.uniform(0, 2 * np.pi, species.n_seed)
    return np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=1)


def growth_system(species: Species, source: Path, seed: int = 0) -> LSystem:
    """The species' L-system for one tree (its seed points and branch pattern bound in)."""
    points = seed_points(species, seed)

    def lookup(column: int):
        def fn(k):
            idx = np.clip(np.asarray(k, dtype=np.int64), 0, len(points) - 1)
            return points[idx, column]

        return fn, 1, 1

    function = FUNCTIONS[species.branch_function]
    rules = [PropagationRule(lambda k, f=function: abs(f(0, k)), species.branch_coefficient)]
    # the branch pattern belongs to the species (so every seed of it branches alike); the seed varies detail
    table = children_table(rules, species.levels + 1, 0, species.max_children)
    overrides = {
        "TRUNK": species.trunk, "RBUD": species.r_bud, "LI": species.l_i, "THETA": species.theta_i,
        "PHI": species.phi_i, "NSEED": float(species.n_seed), "VEXT": float(np.linalg.norm(species.v_ext)),
        "R0": species.r_0,
        "PHIK": species.phi_k, "LK": species.l_k, "LEVELS": float(species.levels),
    }
    host = {"children": children_function(table), "seed_dt": lookup(0), "seed_dp": lookup(1)}
    system = parse_lsystem(read_user_text(source, MAX_SOURCE_BYTES, LSysError), str(source), overrides, host)
    system.iterations = 2 * species.levels
    system.seed = seed
    system.tropism_x, system.tropism_y, system.tropism_z = species.v_ext if any(species.v_ext) else (0.0, 1.0, 0.0)
    return system


SUPPLIED = ("children", "seed_dt", "seed_dp")  # the #host functions Arbor supplies (from a species)
DEFAULT_SPECIES = "broadleaf"
_HOST = re.compile(r"^\s*#host\b([^\n]*)", re.MULTILINE)


def species_file(name: str | Path | None) -> Path:
    """A species preset: a name from assets/presets (default DEFAULT_SPECIES) or a path to a .toml."""
    from arbor.engine.base.assets import assets_dir

    presets = assets_dir() / "presets"
    if name is None:
        return presets / f"{DEFAULT_SPECIES}.toml"
    if str(name).endswith(".toml"):
        return Path(name)
    path = presets / f"{name}.toml"
    if not re.fullmatch(r"[A-Za-z0-9_]+", str(name)) or not path.is_file():
        known = ", ".join(sorted(p.stem for p in presets.glob("*.toml")))
        raise FileNotFoundError(errno.ENOENT, f"no such species (the species: {known}; or a preset .toml file)",
                                f"--species {name}")
    return path


def load_grown(path: str | Path, species: str | Path | None = None, seed: int = 0) -> LSystem:
    """An .lsys source ready to derive. One that asks for GeoMaTree's functions (``#host children seed_dt
    seed_dp``, or some of them: geomatree.lsys, divisor_tree.lsys) grows as ``species`` (default
    DEFAULT_SPECIES) with this ``seed``; any other is read as it is (and ``species`` refused)."""
    from arbor.engine.lsystem.lsys import load_lsystem

    text = read_user_text(path, MAX_SOURCE_BYTES, LSysError)
    hosts = {name for line in _HOST.findall(text) for name in line.split("//")[0].split()}
    if not hosts:
        if species is not None:
            raise LSysError("--species grows sources that ask for GeoMaTree's functions (#host children seed_dt "
                            "seed_dp); this one needs none", str(path))
        return load_lsystem(path)
    unknown = sorted(hosts - set(SUPPLIED))
    if unknown:
        raise LSysError(f"this L-system needs the program to supply {', '.join(f'{n}()' for n in unknown)}; "
                        f"Arbor supplies {', '.join(f'{n}()' for n in SUPPLIED)} only", str(path))
    return growth_system(load_species(species_file(species)), Path(path), seed)
