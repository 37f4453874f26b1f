"""Load-time budgets (issue 33): a save is refused in one line, before the expensive part, when reading
it would take too long (the TOML outside its L-strings, the embedded .lsys sources, the trees' module
counts); the biggest garden the game itself writes stays well inside every budget."""

import hashlib
import re

import pytest

from arbor.engine.life.keep import save, save_blocks
from arbor.engine.life.keep.save import MAX_SAVED_BUDGET, SavedGarden, _toml_text, read_garden, write_garden
from arbor.engine.life.keep.save_check import SaveError
from arbor.engine.life.lineage.lineage import Family, new_lineage
from arbor.engine.life.plant.journal import MAX_ENTRIES
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from benchmarks.fuzz import sample_garden_text

SOURCE = re.compile(r'lsystem_source = """\n.*?"""', re.S)


@pytest.fixture(scope="module")
def base_save():
    return sample_garden_text(2)


@pytest.fixture(scope="module")
def rules():
    return load_rules("assets/rules.toml", pace="demo")


def with_lstring(text: str, lstring: str, modules: int) -> str:
    """Every tree's L-string replaced (and its module count to match)."""
    text = re.sub(r"lstring = '''\n.*?'''", lambda _: "lstring = '''\n" + lstring + "'''", text, flags=re.S)
    return re.sub(r"(?m)^modules = \d+$", f"modules = {modules}", text)


def with_source(text: str, edit) -> str:
    """Every tree's embedded .lsys changed by ``edit`` (and its hash to match: a hostile file can)."""
    source = read_garden_source(text)
    changed = edit(source)
    text = SOURCE.sub(lambda _: "lsystem_source = " + _toml_text(changed), text)
    return re.sub(r'lsystem_sha256 = "[0-9a-f]+"', f'lsystem_sha256 = "{hashlib.sha256(changed.encode()).hexdigest()}"',
                  text)


def read_garden_source(text: str) -> str:
    import tomllib

    return tomllib.loads(text)["trees"][0]["lsystem_source"]


def refused(tmp_path, text: str, rules) -> str:
    path = tmp_path / "hostile.arbor"
    path.write_text(text)
    with pytest.raises(SaveError) as info:
        read_garden(path, rules)
    assert "\n" not in str(info.value)
    return info.value.message


def test_a_journal_too_long_to_read_is_refused_before_toml_reads_it(tmp_path, base_save, rules, monkeypatch):
    rows = '[1.0, "height", 2.0], ' * 20_000  # 460 KB: 2.6 M units of reading work (a 33 MB one took 65 s)
    text = base_save.replace("entries = [", "entries = [" + rows, 1)

    def never(*args):
        raise AssertionError("TOML was asked to read it")

    monkeypatch.setattr(save_blocks.tomllib, "loads", never)
    message = refused(tmp_path, text, rules)
    assert message.startswith("too complex to load in time: reading it outside its L-strings is ")
    assert f"at most {save_blocks.MAX_WORK:,}" in message


def test_embedded_sources_too_long_to_parse_are_refused_before_parsing(tmp_path, base_save, rules, monkeypatch):
    axiom = " F(1,2)[+(3)A(4)]" * 700  # 11,200 characters of rules a tree: 2 trees are over 20,000
    text = with_source(base_save, lambda s: re.sub(r"(?m)^w: .*$", lambda m: m.group(0) + axiom, s, count=1))

    def never(*args, **kwargs):
        raise AssertionError("an embedded source was parsed")

    monkeypatch.setattr(save, "parse_lsystem", never)
    save._parsed.cache_clear()
    message = refused(tmp_path, text, rules)
    assert message.startswith("too complex to load in time: its trees' embedded .lsys sources hold ")
    assert "at most 20,000" in message


def test_an_embedded_budget_past_the_cap_does_not_let_a_huge_tree_in(tmp_path, base_save, rules):
    text = with_source(base_save, lambda s: re.sub(r"(?m)^budget: \d+", "budget: 20000000", s))
    modules = 2 * MAX_SAVED_BUDGET + 4
    message = refused(tmp_path, with_lstring(text, "F(1)" * modules, modules), rules)
    assert message == f"the tree is larger than this L-system's budget allows ({2 * MAX_SAVED_BUDGET:,} modules)"
    within = tmp_path / "within.arbor"
    within.write_text(with_lstring(text, "F(1)" * 1000, 1000))
    assert read_garden(within, rules).world.tree.deriver.budget == MAX_SAVED_BUDGET  # it grows no further


def test_a_tree_of_internodes_only_loads_and_grows(tmp_path, base_save, rules):
    path = tmp_path / "internodes.arbor"
    path.write_text(with_lstring(base_save, "I(1,1,1,0,1)" * 24_000, 24_000))  # (it crashed consolidation)
    world = read_garden(path, rules).world
    world.catch_up(30.0)
    assert len(world.tree.lstring) <= 24_000


def test_the_biggest_garden_the_game_writes_is_within_every_budget(tmp_path, rules):
    system = load_lsystem("assets/lsystems/game_tree.lsys")
    worlds = []
    for k in range(save.MAX_TREES):
        world = World(system, rules, seed=k + 1)
        for i in range(MAX_ENTRIES):
            world.journal.entries.append((float(i), "height", 12.345678 + i))
        worlds.append(world)
    family = Family()
    for k in range(600):  # more than it keeps
        family.add(new_lineage(k, 1.7e9 + k, "game_tree", (worlds[0].lineage,)))
    path = tmp_path / "big.arbor"
    write_garden(SavedGarden(worlds, family=family), path)
    lifted, _ = save_blocks._lift(path.read_bytes())
    assert save_blocks.reading_work(lifted) < save_blocks.MAX_WORK / 2
    assert len(read_garden(path, rules).worlds) == save.MAX_TREES


def test_a_genome_value_no_float_can_hold_is_dropped(tmp_path, base_save, rules):
    path = tmp_path / "genome.arbor"
    text = re.sub(r"(?m)^(\[trees\.genome\]\n\w+ = ).*$", lambda m: m.group(1) + "10000000000000000000000000",
                  base_save, count=1)
    assert "= 10000000000000000000000000" in text
    path.write_text(text)
    world = read_garden(path, rules).worlds[0]  # (it was a TypeError from numpy)
    assert all(abs(v) < 1e6 for v in world.genome.values())
