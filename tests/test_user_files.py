"""Every file a user hands us goes through one reader (engine/base/reader.py): FIFOs, devices and links
are refused without blocking, sizes are capped, and TOML nested deeper than any of our files is refused
before tomllib runs out of stack (issue 45: a 2 KB settings.toml crashed every start with RecursionError;
experiments, sweeps, kiosk.toml, device profiles, species presets and recordings likewise)."""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path

import pytest

from arbor.engine.base.errors import ExperimentError, LSysError, SettingsError, SweepError
from arbor.engine.base.reader import MAX_DEPTH, loads_toml, read_user_toml
from arbor.engine.forest.geomatree import load_species
from arbor.engine.life.experiment.lab import load_experiment
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.input.events import load_recording
from arbor.game.input.hid import DevicesError, load_profiles
from arbor.game.paths import ASSETS
from arbor.game.screens.config import PREFERENCES, read_preferences
from arbor.game.screens.kiosk import KioskConfig, kiosk_config_or_defaults, load_kiosk_config

LSYS = ASSETS / "lsystems"
DEEP = "x = " + "[" * 3000 + "]" * 3000 + "\n"  # 6 KB: RecursionError in tomllib


def _lab(path):
    return load_experiment(path, LSYS)


def _sweep(path):
    return load_sweep(path, LSYS)


READERS = [  # (reader, its error type)
    (read_preferences, SettingsError), (load_kiosk_config, SettingsError), (_lab, ExperimentError),
    (_sweep, SweepError), (load_profiles, DevicesError), (load_species, SettingsError),
]


@pytest.mark.parametrize(("read", "error"), READERS)
def test_deep_nesting_in_every_toml_file_is_one_line_with_its_place(tmp_path, read, error):
    path = tmp_path / "deep.toml"
    path.write_text('title = "a"\n' + DEEP)
    with pytest.raises(error) as info:
        read(path)
    assert str(info.value).startswith(f"{path}:2:{5 + MAX_DEPTH}: nested too deeply"), str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(("read", "error"), READERS)
def test_a_fifo_a_device_and_a_link_are_refused_at_once(tmp_path, read, error):
    os.mkfifo(tmp_path / "fifo.toml")
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    (outside / "real.toml").write_text('title = "a"\n')
    (tmp_path / "link.toml").symlink_to(outside / "real.toml")
    def blocked(signum, frame):
        raise TimeoutError(f"{read} blocked on a file that is not plain")

    old = signal.signal(signal.SIGALRM, blocked)  # (a reader that waits on the FIFO fails, not hangs)
    try:
        for path, says in [(tmp_path / "fifo.toml", "not a regular file"), (Path("/dev/zero"), "not a regular file"),
                           (tmp_path / "link.toml", "it is a link")]:
            started = time.monotonic()
            signal.alarm(5)
            with pytest.raises(error) as info:
                read(path)
            signal.alarm(0)
            assert time.monotonic() - started < 2.0 and says in str(info.value), str(info.value)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def test_a_huge_file_is_refused_before_it_is_read(tmp_path):
    path = tmp_path / "big.toml"
    path.write_bytes(b"# " + b"x" * 2_000_000 + b"\n")
    with pytest.raises(SweepError, match="too large"):
        _sweep(path)


def test_brackets_in_strings_and_comments_are_not_nesting():
    text = 'a = "' + "[" * 500 + '"\nb = \'' + "{" * 500 + "'\n# " + "[" * 500 + '\nc = """\n' + "[" * 99 + '\n"""\n'
    assert loads_toml(text, "t.toml")["a"] == "[" * 500
    assert loads_toml("x = " + "[" * MAX_DEPTH + "]" * MAX_DEPTH, "t.toml")["x"]


def test_a_long_dotted_key_is_refused_too():
    with pytest.raises(LSysError, match="dotted key"):
        loads_toml(".".join(["a"] * 5000) + " = 1\n", "t.toml")


def test_a_table_as_a_sweep_factor_key_is_one_line_not_a_type_error(tmp_path):
    path = tmp_path / "sweep.toml"
    path.write_text('title = "x"\nduration = 600\n[[factor]]\nkey = {a = 1}\nlevels = [1, 2]\n')
    with pytest.raises(SweepError, match=r"sweep.toml:4:\d+: 'key' must be a text"):
        _sweep(path)
    path.write_text('title = "x"\nduration = 600\n[[factor]]\nkey = ["latitude"]\nlevels = [1, 2]\n')
    with pytest.raises(SweepError, match=r"sweep.toml:4:\d+: 'key' must be a text"):
        _sweep(path)


def test_a_deep_settings_file_is_set_aside_and_the_game_keeps_its_defaults(tmp_path):
    from arbor.game.screens.config import PlayerSettings

    class Audio:
        def set_volume(self, volume, muted):
            self.volume = volume

    (tmp_path / PREFERENCES).write_text(DEEP)
    settings = PlayerSettings(Audio(), tmp_path, time.monotonic)
    assert settings.prefs.volume == 0.7 and "nested too deeply" in settings.problem
    assert "set aside as settings.toml.broken" in settings.problem and "\n" not in settings.problem
    assert not (tmp_path / PREFERENCES).exists() and (tmp_path / f"{PREFERENCES}.broken").read_text() == DEEP


def test_a_bad_kiosk_file_runs_the_kiosk_on_its_defaults(tmp_path):
    path = tmp_path / "kiosk.toml"
    path.write_text(DEEP)
    config, line = kiosk_config_or_defaults(path)
    assert config == KioskConfig() and "nested too deeply" in line and "default settings" in line
    path.write_text('pin = "1357"\n')
    assert kiosk_config_or_defaults(path) == (KioskConfig(pin="1357"), "")


def test_lsys_sources_and_recordings_come_through_the_same_reader(tmp_path):
    os.mkfifo(tmp_path / "fifo.lsys")
    with pytest.raises(LSysError, match="not a regular file"):
        load_lsystem(tmp_path / "fifo.lsys")
    (tmp_path / "link.lsys").symlink_to(LSYS / "game_tree.lsys")
    with pytest.raises(LSysError, match="it is a link"):
        load_lsystem(tmp_path / "link.lsys")
    deep = tmp_path / "deep.jsonl"
    deep.write_text('{"kind": "down", "t": 0.5, "x": ' + "[" * 5000 + "]" * 5000 + "}\n")
    with pytest.raises(ValueError, match=r"deep.jsonl:1:1: not an input event"):
        load_recording(deep)


def test_a_good_file_reads_as_before(tmp_path):
    path = tmp_path / "ok.toml"
    path.write_text('a = [[1, 2], {b = "]"}]  # ]]\n[t]\nc = 1\n')
    text, data = read_user_toml(path)
    assert data == {"a": [[1, 2], {"b": "]"}], "t": {"c": 1}} and text.startswith("a = ")


def test_a_fifo_planted_in_a_sweeps_out_folder_is_refused_not_waited_on(tmp_path):
    """The --out folder is the user's: a run's CSV that is a FIFO is refused in one line (reading it back
    for the table blocked)."""
    from types import SimpleNamespace

    from arbor.game.commands.sweep_runs import RunStore

    sweep = SimpleNamespace(source="title = 'x'\n", file="sweep.toml", factors=[], responses=[], stop=None)
    store = RunStore(tmp_path, sweep)
    os.mkfifo(store.runs_dir / "run0001.csv")
    with pytest.raises(SweepError, match="not a regular file"):
        store.table([SimpleNamespace(name="run0001")])


def test_a_bad_translation_keeps_the_text_english_in_one_line(tmp_path):
    """A strings file is written by hand too (assets/strings/<language>.toml, named by kiosk.toml): nested
    too deeply, not a table of texts, or a name that is a path, it is one line and English stays."""
    from arbor.game import strings

    folder = tmp_path / "strings"
    folder.mkdir()
    (folder / "en.toml").write_text((ASSETS / "strings" / "en.toml").read_text(encoding="utf-8"))
    (folder / "fr.toml").write_text("[menu]\nreplant = " + "[" * 3000 + "]" * 3000 + "\n")
    (folder / "de.toml").write_text("[menu]\nreplant = 3\n")
    try:
        for language, says in [("fr", "nested too deeply"), ("de", "must be a table of texts"),
                               ("../../x", "is not a language's name")]:
            problem = strings.set_language(language, folder)
            assert says in problem and problem.endswith("(the text stays English)") and "\n" not in problem
            assert strings.text("menu.save") == "Save"
        (folder / "fr.toml").write_text('[menu]\nreplant = "Nouvel arbre"\n')
        assert strings.set_language("fr", folder) == "" and strings.text("menu.replant") == "Nouvel arbre"
    finally:
        strings.set_language("en")


def test_a_line_of_unclosed_quotes_is_read_in_linear_time():
    """A hostile line of open strings ('"\\' again and again): each quote's string runs to the line's end
    instead of failing and being tried again from the next quote (that took quadratic time: 1 s for 16 KB,
    45 s for a 110 KB file within the work limit)."""
    import time

    from arbor.engine.base.reader import nesting_problem

    for text in ('"\\' * 40_000, "'" * 80_000, '"""' + '"x' * 40_000, "'''" + "x'" * 40_000):
        started = time.process_time()
        assert nesting_problem(text, 32) is None
        assert time.process_time() - started < 2.0  # (linear: milliseconds; the old regex took tens of seconds)


def test_a_shared_species_with_hostile_traits_is_kept_within_the_rules_ranges():
    """A save carries its species' .lsys: FLOOD 0 divided the flooded tree's wilting by zero (a traceback),
    and AMAX, QE and RDS were taken as written. Each is kept within its rule's range."""
    from arbor.engine.life.plant.photosynthesis import leaf_traits
    from arbor.engine.life.rules.rules import Rules
    from arbor.engine.life.rules.schema import find_rule
    from arbor.engine.life.world.commands import Water
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem

    tree = load_lsystem(Path(__file__).resolve().parent.parent / "assets" / "lsystems" / "game_tree.lsys")
    hostile = parse_lsystem(tree.source, "shared.lsys", overrides={"FLOOD": 0, "AMAX": -5, "QE": 1e9, "RDS": 50})
    rules = Rules()
    traits = leaf_traits(hostile.constants, rules)
    assert traits.amax == find_rule("carbon.amax").low and traits.quantum == find_rule("carbon.quantum_efficiency").high
    assert traits.dark == traits.amax * find_rule("carbon.dark_share").high
    world = World(hostile, rules, seed=1)
    world.apply(Water(True))
    for _ in range(int(3 * rules.water.drown_time)):  # flooded long past drowning: no division by zero
        world.step(1.0)
    assert world.sim.flood_tolerance == find_rule("water.flood_tolerance").low


def test_every_users_toml_names_an_unclosed_quote_where_it_opens(tmp_path):
    """The one reader says where a one-line string was opened and not closed (the TOML reader names only
    the line's end), for settings and rules as for a teacher's experiment."""
    import pytest

    from arbor.engine.base.errors import SettingsError
    from arbor.engine.base.reader import read_user_toml

    path = tmp_path / "settings.toml"
    path.write_text('speed = 1\nlanguage = "fr\nkiosk = true\n', encoding="utf-8")
    with pytest.raises(SettingsError) as caught:
        read_user_toml(path, SettingsError)
    err = caught.value
    assert (err.line, err.col) == (2, 12) and "opened with \" at column 12 is not closed" in err.message
    path.write_text("title = 'a title\n", encoding="utf-8")  # (a literal string reads to the document's end)
    with pytest.raises(SettingsError, match="opened with ' at column 9"):
        read_user_toml(path, SettingsError)
    path.write_text('a = """two\nlines "\n"""\nb = [1,\n', encoding="utf-8")  # (inside a multi-line string: no)
    with pytest.raises(SettingsError, match="not valid TOML"):
        read_user_toml(path, SettingsError)
