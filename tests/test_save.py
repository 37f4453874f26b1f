import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

from arbor.engine.life.keep.save import SavedGarden, SaveError, read_garden, save_text, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.commands import Water
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem


@pytest.fixture(scope="module")
def world(lsys_dir):
    w = World(load_lsystem(lsys_dir / "game_tree.lsys"), load_rules("assets/rules.toml", pace="demo"), seed=5)
    w.sim.state.sun_meter = w.sim.state.water_meter = 0.9
    for _ in range(2400):
        w.apply(Water(w.sim.state.water_meter < 0.6))
        w.step(0.5)
    return w


def test_round_trip_is_exact_and_continues_identically(world, tmp_path):
    path = tmp_path / "tree.arbor"
    write_garden(SavedGarden([world]), path)
    saved = read_garden(path, world.rules)
    back, saved_at = saved.world, saved.saved_at
    assert abs(saved_at - time.time()) < 60
    assert back.tree.lstring.equals(world.tree.lstring)
    assert back.sim.state == world.sim.state
    assert back.tree.height == world.tree.height > 0  # (apical control and the HUD read it before the next reading)
    write_garden(SavedGarden([back]), tmp_path / "again.arbor")
    for w in (world, back):
        for _ in range(300):
            w.step(0.5)
    assert back.tree.lstring.to_text() == world.tree.lstring.to_text()


def test_save_is_readable_text(world):
    text = save_text(world, "game_tree.lsys")
    assert text.startswith("# Arbor save file")
    assert "\nlstring = '''\nI(0,0,0," in text  # a literal block: read without unescaping (the trunk's foot)
    tail = text[text.index("lstring = "):].splitlines()[1:]
    assert max(len(line) for line in tail) <= 100 + 200 and np.median([len(x) for x in tail]) <= 130  # wrapped
    assert all(re.match(r"[!-'*+\--~]", line) for line in tail if line and line != "'''")  # between modules
    assert "#extern T G DT R" in text  # the rules that grew it travel with it


def write(path, text):
    path.write_text(text)
    return path.read_bytes()


@pytest.mark.parametrize(
    "mutate, words",
    [
        (lambda t: t[: len(t) // 2], "not a valid save"),  # truncated mid-file
        (lambda t: t.replace("format = 3", "format = 9"), "newer Arbor"),
        (lambda t: t.replace("format = 3", "format = 0"), "too old"),
        (lambda t: t.replace('seed = ', 'seed = "x"  # ', 1), "'seed' must be a whole number"),
        (lambda t: t.replace("#extern T G DT R", "#extern T G DT Q"), "does not match its hash"),
        (lambda t: t.replace("lstring = '''\nI(0,0,0,", "lstring = '''\nI(0,0,zz,"), "in the L-string"),
        (lambda t: re.sub(r"\nwilt = [^\n]*", "\nwilt = nan", t), "'wilt' must be a finite number"),
        (lambda t: re.sub(r"\nwater_meter = [^\n]*", "\nwater_meter = 7.5", t), "'water_meter' = 7.5 is out of range"),
        (lambda t: re.sub(r"\ntime = [^\n]*", "\ntime = 1e400", t), "'time' must be a finite number"),
        (lambda t: re.sub(r"\nseed = [^\n]*", "\nseed = -1", t, count=1), "'seed' = -1 is out of range"),
        (lambda t: t.replace("lstring = '''\nI(0,0,0,", "lstring = '''\n]I(0,0,0,"), "without a matching"),
        (lambda t: t.replace("lstring = '''\nI(0,0,0,", "lstring = '''\nI(0,0,nan,"), "finite number"),
        (lambda t: re.sub(r"PCG64", "MT19937", t), "random state"),
        (lambda t: "\x00\xff garbage", "not"),
    ],
)
def test_bad_saves_give_clear_errors_and_stay_untouched(world, tmp_path, mutate, words):
    path = tmp_path / "bad.arbor"
    before = write(path, mutate(save_text(world, "game_tree.lsys")))
    with pytest.raises(SaveError) as info:
        read_garden(path, world.rules)
    err = info.value
    assert words in err.message and err.file.startswith(str(path)) and err.line >= 1 and err.col >= 1
    assert path.read_bytes() == before


def test_error_in_lstring_points_at_its_line(world, tmp_path):
    text = save_text(world, "game_tree.lsys")
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("lstring = "))
    col = lines[start + 3].index("[")
    lines[start + 3] = lines[start + 3][:col] + "é" + lines[start + 3][col + 1 :]
    path = tmp_path / "bad.arbor"
    path.write_text("\n".join(lines))
    with pytest.raises(SaveError) as info:
        read_garden(path, world.rules)
    assert (info.value.line, info.value.col) == (start + 4, col + 1)  # 1-based line and column of the bad char


CHILD = """
import sys
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.world import World
from arbor.engine.life.keep.save import SavedGarden, write_garden
from arbor.engine.life.world.commands import Water
w = World(load_lsystem("assets/lsystems/game_tree.lsys"), load_rules("assets/rules.toml", pace="demo"), seed=1)
w.sim.state.sun_meter = w.sim.state.water_meter = 0.9
print("ready", flush=True)
while True:
    for _ in range(40):
        w.apply(Water(w.sim.state.water_meter < 0.6))
        w.step(0.5)
    write_garden(SavedGarden([w]), sys.argv[1])
"""


def test_killed_while_saving_leaves_a_loadable_save(tmp_path, world):
    path = tmp_path / "tree.arbor"
    write_garden(SavedGarden([world]), path)
    for delay in (0.05, 0.13, 0.31, 0.52, 0.77):
        proc = subprocess.Popen([sys.executable, "-c", CHILD, str(path)], stdout=subprocess.PIPE,
                                cwd=os.path.dirname(os.path.dirname(__file__)))
        assert proc.stdout.readline().strip() == b"ready"
        time.sleep(delay)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        loaded = read_garden(path, world.rules).world
        assert len(loaded.tree.lstring) >= 2
    leftovers = [p.name for p in tmp_path.iterdir() if p.name != "tree.arbor"]
    assert all(name.endswith(".tmp") for name in leftovers)  # at most a stray temp file, never a torn save


def test_saves_with_the_older_wrapped_string_still_load(world, tmp_path):
    from arbor.engine.life.keep.save import _toml_basic_block

    text = save_text(world, "game_tree.lsys")
    start = text.index("lstring = '''")
    end = text.index("'''", start + 14) + 3
    old = text[:start] + "lstring = " + _toml_basic_block(world.tree.lstring.to_text()) + text[end:]
    assert 'lstring = """\\\nI(0,0,0,' in old
    path = tmp_path / "old.arbor"
    path.write_text(old)
    back = read_garden(path, world.rules).world
    assert back.tree.lstring.equals(world.tree.lstring)


def test_lstring_blocks_read_past_toml_give_what_toml_gives(world):
    import tomllib

    from arbor.engine.life.keep import save_blocks

    text = save_text(world, "game_tree.lsys")
    assert save_blocks.loads(text.encode())[0] == tomllib.loads(text)
    # a decoy: a line like a block's start inside the embedded .lsys source (a comment there)
    decoy = text.replace("// ", "// x\nlstring = '''\n// ", 1)
    assert decoy != text and save_blocks.loads(decoy.encode())[0] == tomllib.loads(decoy)
    # a block that is not ASCII: read as TOML reads it (the L-string reader then names the problem)
    odd = text.replace("lstring = '''\n", "lstring = '''\né", 1)
    assert save_blocks.loads(odd.encode())[0] == tomllib.loads(odd)


def test_what_is_read_writes_back_the_same_file(world, tmp_path):
    from arbor.engine.life.keep.save import garden_text
    from arbor.engine.life.lineage.lineage import Family, new_lineage
    from arbor.engine.life.world.garden import Seed

    family = Family([new_lineage(3, 1.7e9, "elm")])
    saved = SavedGarden([world, World(world.system, world.rules, seed=9)], 1, 1.7e9, [Seed(5, "a" * 64, 2)],
                        family, [(1.0, 0.0, 2.0, 0.5)], "elm.lsys")
    path = tmp_path / "garden.arbor"
    write_garden(saved, path)
    back = read_garden(path, world.rules)
    assert (back.current, back.saved_at, back.seeds, back.rocks, back.lsystem_name, back.dropped) == (
        1, 1.7e9, saved.seeds, saved.rocks, "elm.lsys", 0)
    assert back.family.members == family.members and back.world.seed == 9

    def steady(text):  # the light's direction is made a unit vector again on reading (a last-digit change)
        return re.sub(r"\nlight_dir = [^\n]*", "", text)

    assert steady(garden_text(back)) == steady(path.read_text())  # every field the save holds comes back


def test_a_format_1_save_reads_as_a_garden_of_its_one_tree(world, tmp_path):
    text = save_text(world, "game_tree.lsys", saved_at=5.0).replace("format = 3", "format = 1")
    text = text.replace("[[trees]]\n", "").replace("[trees.growth]", "[tree]").replace("[trees.", "[")
    assert "\n[tree]\n" in text and "[trees" not in text  # one tree per file, its growth in [tree]
    path = tmp_path / "old.arbor"
    path.write_text(text)
    back = read_garden(path, world.rules)
    assert len(back.worlds) == 1 and back.current == 0 and back.saved_at == 5.0
    assert back.world.tree.lstring.equals(world.tree.lstring) and back.world.sim.state == world.sim.state
