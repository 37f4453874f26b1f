"""Save files: a readable TOML text holding a garden: every tree's L-string, rules, sim and RNG state.

A player can open a save in any text editor and read the L-strings (wrapped at 100 characters). A
garden is one file written atomically (temp file, fsync, rename), so a crash never leaves a garden
of mixed generations. Saves are shared between players, so loading treats them as hostile: only a
regular file of bounded size is read, TOML is parsed by the standard library (no eval), the embedded
.lsys source by our own parser, the L-string by ``parse_lstring``, and every field is checked for type,
range and finiteness (keep/save_check.py); every problem is a :class:`SaveError` naming the
file, line and column. Format 3 adds each tree's crown lobes (keep/save_crown.py); formats 2 (no lobes)
and 1 (one tree per file) still load.
"""

from __future__ import annotations

import codecs
import functools
import hashlib
import json
import math
import re
import time
import tomllib
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.base.files import atomic_write
from arbor.engine.base.reader import read_user_bytes
from arbor.engine.life.keep import save_blocks
from arbor.engine.life.keep.save_check import (
    BIG,
    CARBON_FIELDS,
    CYCLE_FIELDS,
    GROWTH_FIELDS,
    POSITION_LIMIT,
    SIM_FIELDS,
    TREE_FIELDS,
    SaveError,
    Where,
    carbon_budget,
    fit,
    fitted,
    fitted_params,
    lstring_sane,
    restore_rng,
    sim_state,
    table,
    text_value,
    value,
    vector,
)
from arbor.engine.life.keep.save_confine import confine_lines, read_confine
from arbor.engine.life.keep.save_crown import crown_lines, read_crown
from arbor.engine.life.lineage.lineage import Family, Lineage, lineage_from_row, new_lineage, species_of
from arbor.engine.life.plant import genome
from arbor.engine.life.plant.growth import GrowingTree
from arbor.engine.life.plant.journal import Journal
from arbor.engine.life.plant.roots import Roots
from arbor.engine.life.plant.sim import Rules, SimState, Simulation
from arbor.engine.life.rules.rules import clamp_orbit
from arbor.engine.life.world.garden import MAX_ROCKS, MAX_SEEDS, Garden, Seed
from arbor.engine.life.world.world import Parts, World
from arbor.engine.lsystem.lstring import LString, parse_lstring
from arbor.engine.lsystem.lsys import parse_lsystem
from arbor.engine.lsystem.text import format_number

FORMAT = 3
WRAP = 100
MAX_BYTES = 64 * 1024 * 1024
MAX_TREES = 6
MAX_SOURCE = 256 * 1024  # characters of an embedded .lsys source
MAX_RULE_CHARACTERS = 20_000  # of all the trees' sources, comments aside (parsed 3 times: at most about 2.4 s)
MAX_SAVED_BUDGET = 16_000  # an embedded .lsys's module budget at most (the game's species: 12,000)
_LSYS_COMMENTS = re.compile(r"//[^\n]*|^[ \t]*#(?:[ \t#][^\n]*)?$", re.M)
_CONTROLS = re.compile(r"[\x00-\x08\x0b-\x1f\x7f]")
_CONTROLS_AND_NEWLINE = re.compile(r"[\x00-\x08\x0a-\x1f\x7f]")


def _escape(text: str, keep_newlines: bool = False) -> str:
    out = text.replace("\\", "\\\\").replace('"', '\\"')
    pattern = _CONTROLS if keep_newlines else _CONTROLS_AND_NEWLINE
    return pattern.sub(lambda m: f"\\u{ord(m.group()):04x}", out)


def _toml_string(text: str) -> str:
    return '"' + _escape(text) + '"'


def _toml_text(text: str) -> str:
    """A multi-line basic string keeping the text's own lines (for the embedded .lsys source)."""
    return '"""\n' + _escape(text, keep_newlines=True) + '"""'


def _toml_lstring(ls: LString) -> str:
    """An L-string as a multi-line literal string, broken into lines of about WRAP characters between
    modules (the L-string reader skips the line breaks; TOML reads a literal string without unescaping,
    fast). Text a literal string cannot hold (three quotes in a row, control characters) is wrapped
    with line-ending backslashes in a basic string instead, as older saves were."""
    printable = bool(((ls.sym > 32) & (ls.sym < 127)).all())
    text = ls.to_text(WRAP if printable else 0)
    if printable and "'''" not in text and not text.endswith("'"):
        return "'''\n" + text + "'''"
    return _toml_basic_block(ls.to_text() if printable else text)


def _toml_basic_block(text: str) -> str:
    """Whitespace-free text wrapped with line-ending backslashes (TOML joins the lines on reading)."""
    pieces = [text[i : i + WRAP] for i in range(0, len(text), WRAP)] or [""]
    escaped = [_escape(p) for p in pieces]
    return '"""\\\n' + "\\\n".join(escaped) + '\\\n"""'


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    return _toml_string(str(value))


def _table(name: str, data: dict) -> list[str]:
    lines = [f"[{name}]"]
    nested = []
    for key, item in data.items():
        if isinstance(item, dict):
            nested.append((f"{name}.{key}", item))
        else:
            lines.append(f"{key} = {_toml_value(item)}")
    for sub, values in nested:
        lines += ["", *_table(sub, values)]
    return lines


def _rng_text(rng: np.random.Generator) -> str:
    return json.dumps(rng.bit_generator.state, separators=(",", ":"))


def _numbers(values) -> str:
    return "[" + ", ".join(format_number(float(v)) for v in values) + "]"


def _tree_lines(world: World, lsystem_name: str) -> list[str]:
    """One tree's part of a save: its identity and rules, [trees.sim], then [trees.growth] with the
    L-string last. Every number is first fitted to the range the reader accepts (save_check.fit)."""
    tree = world.tree
    ls, roots = _fitted_lstring(tree.lstring), _fitted_lstring(world.roots.lstring)
    growth = fitted({"last_rewrite_T": tree.last_rewrite_T, "mean_light": tree.mean_light,
                     "shed_total": tree.shed_total, "last_light": world.last_light,
                     "last_sense_length": tree.last_sense_length, "last_sense_girth": tree.last_sense_girth,
                     "roots_rewrite": world.roots.last_rewrite, "height": tree.height}, GROWTH_FIELDS)
    journal, _ = Journal.from_rows(world.journal.to_rows())  # what the reader keeps, nothing else
    journal.read_sizes(world.journal.size_rows())
    lines = [
        "[[trees]]",
        f"seed = {fit(world.seed, *TREE_FIELDS['seed'])}",
        f"steps = {fit(world.steps, *TREE_FIELDS['steps'])}",
        f"position = {_numbers(np.clip(np.nan_to_num(world.position), -POSITION_LIMIT, POSITION_LIMIT))}",
        f"lsystem = {_toml_string(lsystem_name)}",
        f"lsystem_sha256 = {_toml_string(world.system.sha256)}",
        f"lsystem_source = {_toml_text(world.system.source)}",
        "",
        *_table("trees.sim", _fitted_sim(world)),
        "",
        "[trees.lineage]",
        *_lineage_pairs(world.lineage),
        "",
        *_table("trees.carbon", fitted(asdict(world.carbon), CARBON_FIELDS)),
        "",
        *_table("trees.genome", world.genome),
        "",
        "[trees.journal]",
        "entries = [" + ", ".join(f"[{format_number(tm)}, {_toml_string(k)}, {format_number(v)}]"
                                  for tm, k, v in journal.entries) + "]",
        "sizes = [" + ", ".join(f"[{', '.join(format_number(x) for x in row)}]" for row in journal.size_rows()) + "]",
        "",
        "[trees.growth]",
        *(f"{key} = {format_number(growth[key])}" for key in ("last_rewrite_T", "mean_light", "height")),
        f"light_dir = {_numbers(_direction(tree.light_dir))}",
        f"shed_total = {growth['shed_total']}",
    ]
    if world.last_light > -BIG:  # never measured: -inf, not written
        lines.append(f"last_light = {format_number(growth['last_light'])}")
    if tree.last_sense_length is not None and tree.last_sense_girth is not None:
        lines += [f"last_sense_length = {format_number(growth['last_sense_length'])}",
                  f"last_sense_girth = {format_number(growth['last_sense_girth'])}"]
    lines += [
        f"rng_world = {_toml_string(_rng_text(world.rng))}",
        f"rng_roots = {_toml_string(_rng_text(world.roots.deriver.rng))}",
        f"roots_rewrite = {format_number(growth['roots_rewrite'])}",
        f"roots = {_toml_lstring(roots)}",
        f"rng_tree = {_toml_string(_rng_text(tree.deriver.rng))}",
        f"modules = {len(ls)}",
        f"lstring = {_toml_lstring(ls)}",
        "",
        *crown_lines(world.crown, tree.lstring, _toml_lstring),
        *confine_lines(tree.confine, tree.confine_left),
    ]
    return lines


def _fitted_lstring(ls: LString) -> LString:
    """The L-string with its parameters as the reader accepts them (a NaN from a player's .lsys, a
    length grown past BIG): the same object when nothing needs it."""
    params = fitted_params(ls.params)
    return ls if params is ls.params else LString.from_arrays(ls.sym, ls.nparams, params)


def _fitted_sim(world: World) -> dict:
    """[trees.sim] as the reader reads it back: every field within SIM_FIELDS / CYCLE_FIELDS, the sun's
    angle on one turn and its orbit and speed within the rules' range (as loading makes them)."""
    sim = fitted(world.sim.state.to_dict(), SIM_FIELDS)
    for name in ("sun_cycle", "water_cycle"):
        sim[name] = fitted(sim[name], CYCLE_FIELDS)
    sun = world.rules.sun
    sim["sun_angle"] %= 2 * math.pi
    sim["orbit_height"], sim["sun_speed"] = clamp_orbit(sun, sim["orbit_height"], sim["sun_speed"])
    return sim


def _direction(v) -> np.ndarray:
    """A unit vector (up when ``v`` is not a usable direction), as the reader keeps it: one whose length is 1
    to within 1e-9 is kept bit for bit (dividing by its norm again would change its last bits, and a loaded
    tree would then grow apart from the one saved)."""
    v = np.asarray(v, dtype=np.float64)
    norm = float(np.linalg.norm(v)) if np.isfinite(v).all() else 0.0
    if abs(norm - 1.0) <= 1e-9:
        return v.copy()
    return v / norm if norm > 1e-9 else np.array([0.0, 1.0, 0.0])


def _lineage_pairs(lineage: Lineage) -> list[str]:
    return [f"id = {_toml_string(lineage.id)}",
            "parents = [" + ", ".join(_toml_string(p) for p in lineage.parents) + "]",
            f"generation = {lineage.generation}", f"seed = {lineage.seed}",
            f"planted = {format_number(lineage.planted)}", f"species = {_toml_string(lineage.species)}"]


def _family_lines(family: Family | None) -> list[str]:
    """The garden's family: one inline table per tree it has known."""
    if family is None or not family.members:
        return []
    return ["family = [", *("{" + ", ".join(_lineage_pairs(m)) + "}," for m in family.members.values()), "]"]


@dataclass
class SavedGarden:
    """Everything a save holds, the one value both written (:func:`write_garden`) and read
    (:func:`read_garden`): the trees, which one is cared for, when it was saved, the seed bag, the
    family, the rocks and the name of the L-system; reading also counts the lineage entries it dropped
    as malformed or hostile (told to the player, never trusted)."""

    worlds: list[World]
    current: int = 0
    saved_at: float | None = None  # wall-clock seconds; None writes "now"; NaN when read and unreadable
    seeds: list[Seed] = field(default_factory=list)
    family: Family = field(default_factory=Family)
    rocks: list[tuple[float, float, float, float]] = field(default_factory=list)
    lsystem_name: str = "game_tree.lsys"
    dropped: int = 0

    @classmethod
    def of(cls, garden: Garden, lsystem_name: str = "game_tree.lsys", saved_at: float | None = None
           ) -> SavedGarden:
        """What saving ``garden`` writes (the inverse of :meth:`garden`)."""
        return cls(garden.worlds, garden.current, saved_at, list(garden.seeds), garden.family, list(garden.rocks),
                   lsystem_name)

    @property
    def world(self) -> World:
        """The tree cared for."""
        return self.worlds[self.current]

    def garden(self) -> Garden:
        """The garden these make."""
        garden = Garden(self.worlds, self.current, self.seeds, self.family)
        garden.rocks = list(self.rocks)
        return garden


def garden_text(saved: SavedGarden) -> str:
    """The text of a save file holding ``saved``: its trees (the cared-for one is ``current``), the seed
    bag, the rocks and the family of every tree the garden has known."""
    worlds = saved.worlds
    if not 1 <= len(worlds) <= MAX_TREES:
        raise ValueError(f"a save holds 1 to {MAX_TREES} trees")
    lines = [
        "# Arbor save file: a garden of trees, their rules and their state. Each tree's L-string ends its part.",
        f"format = {FORMAT}",
        f"saved_at = {time.time() if saved.saved_at is None else float(saved.saved_at)!r}",
        f"current = {min(max(saved.current, 0), len(worlds) - 1)}",
        "seeds = [" + ", ".join(f"[{s.parent_seed}, {_toml_string(s.parent_sha)}, {s.number}]"
                                for s in _seeds({"seeds": [[s.parent_seed, s.parent_sha, s.number]
                                                           for s in saved.seeds]})) + "]",
        "rocks = [" + ", ".join(_numbers(r) for r in _rocks({"rocks": [list(r) for r in saved.rocks]})) + "]",
        *_family_lines(Family.from_rows(saved.family.to_rows())[0] if saved.family else None),
        "",
    ]
    for world in worlds:
        lines += _tree_lines(world, saved.lsystem_name)
    return "\n".join(lines)


def save_text(world: World, lsystem_name: str, saved_at: float | None = None) -> str:
    """The text of a save file holding the one tree ``world`` (for sweeps that keep a tree as text)."""
    return garden_text(SavedGarden([world], saved_at=saved_at, lsystem_name=lsystem_name))


def write_garden(saved: SavedGarden, path: str | Path) -> None:
    """Write ``saved`` to ``path`` as one atomic unit (temp file, fsync, rename): a crash leaves the
    old save or the new one, never a mix."""
    atomic_write(path, garden_text(saved).encode("utf-8"))


def _read(path: Path) -> tuple[dict, str]:
    """The TOML of a save: only a regular file (not a link, FIFO or device), at most MAX_BYTES, UTF-8 (a BOM
    is allowed)."""
    return _decode(read_user_bytes(path, MAX_BYTES, SaveError), path)  # (the one reader of user files)


def _decode(raw: bytes, path: Path) -> tuple[dict, str]:
    """The TOML of a save's bytes (read from ``path``, or carried inside it: a postcard)."""
    if len(raw) > MAX_BYTES:
        raise SaveError(f"too large (more than {MAX_BYTES:,} bytes)", str(path))
    bom = len(codecs.BOM_UTF8) if raw.startswith(codecs.BOM_UTF8) else 0
    try:
        return save_blocks.loads(raw[bom:])
    except UnicodeDecodeError as exc:
        raise SaveError(f"not UTF-8 text (byte {exc.start + bom})", str(path)) from None
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+), column (\d+)", str(exc))
        line, col = (int(m.group(1)), int(m.group(2))) if m else (1, 1)
        raise SaveError(f"not a valid save: {exc}", str(path), line, col) from None
    except RecursionError:
        raise SaveError("not a valid save: nested too deeply", str(path)) from None
    except save_blocks.TooMuchWorkError as exc:
        raise SaveError(str(exc), str(path)) from None
    except save_blocks.TooDeepError as exc:
        raise SaveError(f"not a valid save: {exc}", str(path), exc.line, exc.col) from None


def _table_lines(text: str, header: str) -> list[int]:
    """Where each line that holds only ``header`` (blanks before it allowed) starts (str.find, not a
    regular expression over every line of a 2 MB save)."""
    out, at = [], text.find(header)
    while at >= 0:
        start = text.rfind("\n", 0, at) + 1
        if not text[start:at].strip():
            out.append(start)
        at = text.find(header, at + len(header))
    return out


def _upgraded(data: dict, where: Where) -> dict:
    """The save in today's layout, whatever format wrote it: format 1 (one tree per file, the whole file
    that tree, its growth in [tree]) becomes a garden of that one tree."""
    version = value(data, "format", "int", 0, 2**31, where)
    if version > FORMAT:
        raise where.error(f"saved by a newer Arbor (format {version}); this one reads up to {FORMAT}", "format")
    if version < 1:
        raise where.error(f"format {version} is too old to read", "format")
    if version == 1:
        return {**data, "format": FORMAT, "trees": [{**data, "growth": table(data, "tree", where)}]}
    return data


def _tree_parts(data: dict, path: Path, text: str) -> list[tuple[dict, Where]]:
    """Each tree's table (of an upgraded save) with where its text is."""
    where = Where(path, text)
    trees = data.get("trees")
    if not isinstance(trees, list) or not 1 <= len(trees) <= MAX_TREES:
        raise where.error(f"a save holds 1 to {MAX_TREES} [[trees]]")
    starts = _table_lines(text, "[[trees]]") or [0]
    starts += [len(text)] * (len(trees) + 1 - len(starts))
    parts = []
    for k, tree in enumerate(trees):
        part = Where(path, text, starts[k], starts[k + 1] if k + 1 < len(starts) else None)
        if not isinstance(tree, dict):
            raise part.error(f"tree #{k + 1} must be a table")
        parts.append((tree, part))
    return parts


@functools.lru_cache(maxsize=16)
def _parsed(source: str, label: str):
    """An embedded .lsys parsed once per file: the trees of a garden mostly share one (systems are
    never changed after parsing, so sharing is safe; failures are not cached). Its module budget is
    kept within MAX_SAVED_BUDGET here, so a tree grown from it never outgrows what loading accepts."""
    system = parse_lsystem(source, label)
    system.budget = min(system.budget or MAX_SAVED_BUDGET, MAX_SAVED_BUDGET)
    return system


def _rule_characters(source: str) -> int:
    """The characters of an .lsys source its parser works on (comment lines, trailing // comments and
    white space aside): what parsing it costs, up to about 50 us each (a long axiom)."""
    code = _LSYS_COMMENTS.sub("", source)
    return len(code) - sum(code.count(c) for c in " \t\r\n")


def _check_sources(parts: list[tuple[dict, Where]], path: Path) -> None:
    """Every tree's embedded .lsys is parsed up to three times while loading (the species, the empty tree,
    its genome): their rules all together within MAX_RULE_CHARACTERS, counted before any is parsed."""
    total = sum(_rule_characters(tree["lsystem_source"]) for tree, _ in parts
                if isinstance(tree.get("lsystem_source"), str))
    if total > MAX_RULE_CHARACTERS:
        raise SaveError(f"too complex to load in time: its trees' embedded .lsys sources hold {total:,} characters "
                        f"of rules in all (comments and spaces aside), at most {MAX_RULE_CHARACTERS:,} (the game's "
                        "own tree has about 2,600)", str(path))


def _system(data: dict, where: Where):
    source = text_value(data, "lsystem_source", where, MAX_SOURCE)
    digest = text_value(data, "lsystem_sha256", where, 64)
    if hashlib.sha256(source.encode("utf-8")).hexdigest() != digest:
        raise where.error("the embedded .lsys source does not match its hash", "lsystem_sha256")
    try:
        return _parsed(source, f"{where.path} (embedded .lsys)")
    except LSysError as err:
        raise SaveError(err.message, err.file, where.line("lsystem_source") + err.line, err.col) from None


def _load_tree(data: dict, where: Where, rules: Rules, budget_slack: float) -> World:
    """One checked tree (see save_check for the checks), its World built once from its parts."""
    system = _system(data, where)
    seed = value(data, "seed", *TREE_FIELDS["seed"], where)
    state = sim_state(table(data, "sim", where), where)
    state.sun_angle %= 2 * math.pi
    state.orbit_height, state.sun_speed = clamp_orbit(rules.sun, state.orbit_height, state.sun_speed)
    saved_genome = {k: v for k, v in table(data, "genome", where, required=False).items()  # (older saves: none)
                    if isinstance(v, int | float) and not isinstance(v, bool) and abs(v) <= BIG}  # (10**25: no float)
    traits = genome.checked(system, saved_genome) if "genome" in data else {}
    growth = table(data, "growth", where)
    expressed = genome.expressed(system, traits)
    tree = _restore_growth(expressed, seed, growth, where, budget_slack)
    crown = read_crown(data, where, tree.lstring, int((expressed.budget or 10**6) * 2 * budget_slack))
    tree.confine, tree.confine_left = read_confine(data, where)  # (a Grow edit's hold on the growth)
    rng = np.random.Generator(np.random.PCG64(seed))
    restore_rng(rng, text_value(growth, "rng_world", where, 4096), "rng_world", where)
    saved = data.get("lineage")
    lineage = lineage_from_row(saved) if saved is not None else None
    dropped = int(saved is not None and lineage is None)
    if lineage is None:  # an older save, or a lineage that cannot be trusted: the tree starts a line
        name = data.get("lsystem") if isinstance(data.get("lsystem"), str) else "tree"
        lineage = new_lineage(seed, 0.0, species_of(name))
    parts = Parts(sim=Simulation(rules, state), tree=tree, genome=traits, roots=_restore_roots(growth, where, seed),
                  carbon=carbon_budget(data.get("carbon") if "carbon" in data else None, where),
                  journal=_journal(table(data, "journal", where, required=False)),
                  lineage=lineage, rng=rng, steps=value(data, "steps", *TREE_FIELDS["steps"], where),
                  last_light=value(growth, "last_light", *GROWTH_FIELDS["last_light"], where, default=float("-inf")),
                  dropped_lineage=dropped, crown=crown)
    position = tuple(vector(data, "position", 2, where, [0.0, 0.0], limit=POSITION_LIMIT))
    return World(system, rules, seed=seed, position=position, parts=parts)


def _journal(data: dict) -> Journal:
    """A saved journal: its entries and its birthdays' sizes (what cannot be trusted is dropped)."""
    journal = Journal.from_rows(data.get("entries", []))[0]
    journal.read_sizes(data.get("sizes", []))
    return journal


def _restore_growth(system, seed: int, growth: dict, where: Where, budget_slack: float) -> GrowingTree:
    """The saved tree of ``system`` (its species with its genome): its L-string, clocks, light and generator."""
    limit = int((system.budget or 10**6) * 2 * budget_slack)
    modules = value(growth, "modules", "int", 0, 2**31, where)
    lstring_text = text_value(growth, "lstring", where, 64 * max(limit, 1))
    if modules > limit:
        raise where.error(f"the tree is larger than this L-system's budget allows ({limit:,} modules)", "modules")
    try:
        lstring = parse_lstring(lstring_text, str(where.path))
    except LSysError as err:
        if "\n" in lstring_text:  # a literal block: its lines are the file's lines
            line, col = where.line("lstring") + err.line, err.col
        else:  # one line once TOML has joined the wrapped lines of an older save
            line, col = where.line("lstring") + 1 + (err.col - 1) // WRAP, (err.col - 1) % WRAP + 1
        raise SaveError(f"in the L-string: {err.message}", str(where.path), line, col) from None
    if len(lstring) > limit:
        raise where.error(f"the tree is larger than this L-system's budget allows ({limit:,} modules)", "lstring")
    lstring_sane(lstring, where)
    direction = np.array(vector(growth, "light_dir", 3, where, [0.0, 1.0, 0.0], limit=10.0))
    if not 0.5 < float(np.linalg.norm(direction)) < 2.0:
        raise where.error("'light_dir' must be a direction (a vector of length 1)", "light_dir")
    sensed = "last_sense_length" in growth or "last_sense_girth" in growth
    tree = GrowingTree(system, seed=seed, lstring=lstring, light_dir=_direction(direction),
                       last_rewrite_T=value(growth, "last_rewrite_T", *GROWTH_FIELDS["last_rewrite_T"], where),
                       mean_light=value(growth, "mean_light", *GROWTH_FIELDS["mean_light"], where, default=1.0),
                       shed_total=value(growth, "shed_total", *GROWTH_FIELDS["shed_total"], where, default=0),
                       last_sense_length=value(growth, "last_sense_length", *GROWTH_FIELDS["last_sense_length"],
                                               where) if sensed else None,
                       last_sense_girth=value(growth, "last_sense_girth", *GROWTH_FIELDS["last_sense_girth"],
                                              where) if sensed else None)
    restore_rng(tree.deriver.rng, text_value(growth, "rng_tree", where, 4096), "rng_tree", where)
    if "height" in growth:  # (older saves: none until the next light reading)
        tree.height = value(growth, "height", *GROWTH_FIELDS["height"], where)
    return tree


def _restore_roots(growth: dict, where: Where, seed: int) -> Roots:
    """The roots (saves from before roots have none: the tree starts a root system)."""
    roots = Roots(seed=seed)
    if "roots" not in growth:
        return roots
    limit = 2 * (roots.system.budget or 10_000)
    text = text_value(growth, "roots", where, 64 * limit)
    try:
        lstring = parse_lstring(text, str(where.path))
    except LSysError as err:
        raise SaveError(f"in the roots: {err.message}", str(where.path), where.line("roots"), err.col) from None
    if len(lstring) > limit:
        raise where.error(f"the roots are larger than their budget allows ({limit:,} modules)", "roots")
    lstring_sane(lstring, where)
    roots = Roots(seed=seed, lstring=lstring,
                  last_rewrite=value(growth, "roots_rewrite", *GROWTH_FIELDS["roots_rewrite"], where))
    restore_rng(roots.deriver.rng, text_value(growth, "rng_roots", where, 4096), "rng_roots", where)
    return roots


def read_garden(path: str | Path, rules: Rules | None = None, budget_slack: float = 1.0) -> SavedGarden:
    """The save at ``path``, checked (see save_check) and upgraded from any older format: every tree in
    planting order, the cared-for one, when it was saved (NaN when its clock cannot be read: the caller
    then counts no time away), seeds, rocks and family. ``budget_slack`` widens the trees' size limit."""
    path = Path(path)
    return _garden(*_read(path), path, rules, budget_slack)


@dataclass
class Glance:
    """What a save says of itself without growing its trees (a Restore's preview): when it was saved (NaN
    when unreadable), which tree is cared for and that tree's simulation state (alive, age, meters)."""

    saved_at: float
    current: int
    state: SimState


def peek_garden(path: str | Path) -> Glance:
    """A :class:`Glance` at the save ``path``: read and checked as :func:`read_garden` reads it, up to the
    cared-for tree's ``sim`` table (its species, L-string and the rest are not built: a preview of a
    30-year garden costs the file's parse alone). A save that does not load may still be glanced at."""
    path = Path(path)
    data, text = _read(path)
    data, parts, saved_at, current = _head(data, text, path)
    tree, part = parts[current]
    return Glance(saved_at, current, sim_state(table(tree, "sim", part), part))


def _head(data: dict, text: str, path: Path) -> tuple[dict, list[tuple[dict, Where]], float, int]:
    """A save's parsed TOML upgraded to today's layout, its trees' tables, when it was saved (lenient: NaN
    when unreadable, which only means no time away) and which tree is cared for."""
    where = Where(path, text)
    data = _upgraded(data, where)
    parts = _tree_parts(data, path, text)
    saved_at = data.get("saved_at")
    if isinstance(saved_at, bool) or not isinstance(saved_at, int | float) or not math.isfinite(saved_at):
        saved_at = float("nan")
    return data, parts, float(saved_at), value(data, "current", "int", 0, len(parts) - 1, where, default=0)


def read_garden_bytes(raw: bytes, label: str | Path, rules: Rules | None = None) -> SavedGarden:
    """A save carried inside another file (a postcard PNG): the same checks as :func:`read_garden`, with
    ``label`` naming the carrier in every error."""
    label = Path(label)
    return _garden(*_decode(raw, label), label, rules, 1.0)


def _garden(data: dict, text: str, path: Path, rules: Rules | None, budget_slack: float) -> SavedGarden:
    """The checked garden of a save's parsed TOML ``data`` and its ``text`` (for line numbers)."""
    data, parts, saved_at, current = _head(data, text, path)
    _check_sources(parts, path)
    worlds = [_load_tree(tree, part, rules or Rules(), budget_slack) for tree, part in parts]
    family, dropped = Family.from_rows(data.get("family", []))
    dropped += sum(w.dropped_lineage for w in worlds)
    name = parts[current][0].get("lsystem")
    return SavedGarden(worlds, current, saved_at, _seeds(data), family, _rocks(data),
                       name if isinstance(name, str) else "game_tree.lsys", dropped)


def _rocks(data: dict) -> list[tuple[float, float, float, float]]:
    """The garden's rocks; rows that are not four sane numbers are dropped."""
    out = []
    rows = data.get("rocks", [])
    for row in rows if isinstance(rows, list) else []:
        ok = (isinstance(row, list) and len(row) == 4 and len(out) < MAX_ROCKS
              and all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in row))
        if ok and all(abs(v) <= 1e4 for v in row[:3]) and 0.05 <= row[3] <= 50:
            out.append(tuple(float(v) for v in row))
    return out


def _seeds(data: dict) -> list[Seed]:
    out = []
    for row in data.get("seeds", []) if isinstance(data.get("seeds", []), list) else []:
        if (isinstance(row, list) and len(row) == 3 and isinstance(row[0], int) and isinstance(row[2], int)
                and not isinstance(row[0], bool) and isinstance(row[1], str) and len(row[1]) == 64
                and 0 <= row[0] < 2**63 and 0 <= row[2] < 2**31 and len(out) < MAX_SEEDS):
            out.append(Seed(row[0], row[1], row[2]))
    return out
