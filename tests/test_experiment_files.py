"""Every bad experiment or sweep file a teacher can write is one line naming the file, the key's line and
column, and the fix (issue 30's cases, one test each)."""

from __future__ import annotations

import pytest

from arbor.engine.base.errors import ExperimentError, SweepError
from arbor.engine.life.experiment.lab import load_experiment
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.game.paths import ASSETS

LSYS = ASSETS / "lsystems"
SWEEP = """title = "Sun"
duration = 300
sample_every = 60
seeds = 3

[base]
watering = { below = 0.5, until = 0.7 }

[[factor]]
name = "Sun orbit height"
key = "orbit_height"
levels = [0.0, 1.0]
"""
LAB = """title = "Two trees"
seed = 5
duration = 300
sample_every = 30

[[tree]]
name = "Watered"
orbit_height = 0.6
watering = { below = 0.55, until = 0.75 }

[[tree]]
name = "Dry"
orbit_height = 0.6
"""

SWEEP_CASES = [  # (what is replaced, by what, line, column, words of the message)
    ("seeds = 3", "seed = 2", 4, 1, "unknown key 'seed' in the sweep (did you mean 'seeds'?)"),
    ("sample_every = 60", "sample_evry = 60", 3, 1, "did you mean 'sample_every'?"),
    ('key = "orbit_height"', 'key = "watering.every"', 12, 11, "'levels' must be above 0"),
    ("watering = { below = 0.5, until = 0.7 }", "watering = { below = 0.5, until = 0.7 }\norbit_hieght = 0.5",
     8, 1, "did you mean 'orbit_height'?"),
    ("levels = [0.0, 1.0]", "levels = [0.0, 5]", 12, 16, "'levels' must be from -1 to 1 orbit radii (it is 5)"),
    ('key = "orbit_height"\nlevels = [0.0, 1.0]', 'key = "water.drain_rate"\nlevels = [-0.004, 0.01]', 12, 11,
     "'drain_rate' in [water] must be from 0"),
    ("watering = { below = 0.5, until = 0.7 }", "watering = { below = 1.5, until = 0.2 }", 7, 22,
     "'below' must be from 0 to 1"),
    ("seeds = 3", "seeds = [1, 2.7]", 4, 13, "'seeds' must be a whole number, not 2.7"),
    ("seeds = 3", "seeds = [1, -3]", 4, 13, "'seeds' must be from 0 to"),
    ('title = "Sun"', 'title = "Sun"\nspecies = "game_oak.lsys"', 2, 11, "no species 'game_oak.lsys'"),
    ('key = "orbit_height"\nlevels = [0.0, 1.0]', 'key = "prune.every_days"\nlevels = [3, 7]', 11, 1,
     "needs what to cut: give [base] a prune"),
    ('key = "orbit_height"\nlevels = [0.0, 1.0]', 'key = "prune.lowest"\nlevels = [0, 2]', 12, 14,
     "'levels' must be from 0 to 1 share, 0..1 (it is 2)"),
    ("watering = { below = 0.5, until = 0.7 }", "prune = { every_days = 7, keep_hight = 2 }", 7, 27,
     "unknown key 'keep_hight' in 'prune' (did you mean 'keep_height'?)"),
    ('key = "orbit_height"', 'key = "orbit_hieght"', 11, 7,
     "unknown factor key 'orbit_hieght' (did you mean 'orbit_height'?)"),
    ('key = "orbit_height"\nlevels = [0.0, 1.0]', 'key = "water.drain_rat"\nlevels = [0.004, 0.01]', 11, 7,
     "unknown factor key 'water.drain_rat' (did you mean 'water.drain_rate'?)"),
    ("watering = { below = 0.5, until = 0.7 }", 'rules = { "watr.drain_rate" = 0.01 }', 7, 11,
     "unknown rule 'watr.drain_rate' (did you mean 'water.drain_rate'?)"),
    ('key = "orbit_height"\nlevels = [0.0, 1.0]', 'key = "day_of_year"\nlevels = [172, 355]', 11, 1,
     "a factor 'day_of_year' needs 'latitude': give it in [base] or vary it too"),
    ('[base]\nwatering = { below = 0.5, until = 0.7 }\n\n[[factor]]\nname = "Sun orbit height"\n'
     'key = "orbit_height"\nlevels = [0.0, 1.0]', '[base]\nlatitude = 52\n\n[[factor]]\nname = "Date"\n'
     'key = "day_of_year"\nlevels = [172, 355]', 12, 16, "at latitude 52 on day 355 the noon sun stands 14.6 degrees"),
    ('watering = { below', 'latitude = 52\nday_of_year = 172\nwatering = { below', 13, 1,
     "a factor 'orbit_height' with a place and date (latitude, day_of_year): vary 'latitude' or 'day_of_year'"),
    ('title = "Sun"', 'title = "Sun"\nresponses = ["hieght"]', 2, 14,
     "unknown response 'hieght' (did you mean 'height'?)"),
]


@pytest.mark.parametrize("old, new, line, col, words", SWEEP_CASES)
def test_bad_sweep_file_is_one_line_at_the_key(tmp_path, old, new, line, col, words):
    path = tmp_path / "bad_sweep.toml"
    assert old in SWEEP
    path.write_text(SWEEP.replace(old, new), encoding="utf-8")
    with pytest.raises(SweepError) as err:
        load_sweep(path, LSYS)
    text = str(err.value)
    assert "\n" not in text and text.startswith(f"{path}:{line}:{col}: "), text
    assert words in text, text


LAB_CASES = [
    ("orbit_height = 0.6\nwatering", "orbit_hieght = 0.6\nwatering", 8, 1, "did you mean 'orbit_height'?"),
    ("watering = { below = 0.55, until = 0.75 }", "waterng = { below = 0.55, until = 0.75 }", 9, 1,
     "did you mean 'watering'?"),
    ("orbit_height = 0.6\nwatering", "orbit_height = 5\nwatering", 8, 16, "must be from -1 to 1 orbit radii"),
    ("watering = { below = 0.55, until = 0.75 }", "watering = { every = -30 }", 9, 22, "'every' must be above 0"),
    ("watering = { below = 0.55, until = 0.75 }", 'rules = { "water.drain_rate" = -0.004 }', 9, 32,
     "'drain_rate' in [water] must be from 0"),
    ("watering = { below = 0.55, until = 0.75 }", 'rules = { "water.drain_rat" = 0.01 }', 9, 11,
     "unknown rule 'water.drain_rat' (did you mean 'water.drain_rate'?)"),
    ("watering = { below = 0.55, until = 0.75 }", "watering = { below = 0.8, until = 0.2 }", 9, 22,
     "'below' (0.8) must be under 'until' (0.2)"),
    ("seed = 5", "seed = -3", 2, 8, "'seed' must be from 0 to 4294967295 (it is -3)"),
    ("seed = 5", "seed = 2.7", 2, 8, "'seed' must be a whole number, not 2.7"),
    ('name = "Dry"', 'name = "Watered"', 12, 8, "two trees are named 'Watered'"),
    ('name = "Dry"', 'name = "watered!"', 12, 8,
     "trees 'Watered' and 'watered!' would both be saved as watered.arbor: give each tree a name of its own"),
    ("sample_every = 30", "sample_evry = 30", 4, 1, "did you mean 'sample_every'?"),
    ('title = "Two trees"', 'title = "Two trees"\nspecies = "../x.lsys"', 2, 11, "'species' must be a file name"),
    ("watering = { below = 0.55, until = 0.75 }", "prune = { every_dayz = 7, keep_height = 2 }", 9, 11,
     "did you mean 'every_days'?"),
    ("watering = { below = 0.55, until = 0.75 }", "prune = { keep_height = -1 }", 9, 25,
     "'keep_height' must be above 0 and at most 50 m (it is -1)"),
    ("watering = { below = 0.55, until = 0.75 }", "prune = { every_days = 7 }", 9, 1, "'prune' cuts nothing"),
    ("watering = { below = 0.55, until = 0.75 }", "prune = { lowest = 1.5 }", 9, 20, "'lowest' must be from 0 to 1"),
    ("watering = { below = 0.55, until = 0.75 }", "prune = { every_days = 0, lowest = 0.2 }", 9, 24,
     "'every_days' must be above 0"),
    ("orbit_height = 0.6\nwatering", "latitude = 52\nwatering", 8, 1, "give 'day_of_year' with 'latitude'"),
    ("orbit_height = 0.6\nwatering", "latitude = 52\nday_of_year = 172\nday_length = 12\nwatering", 10, 1,
     "give 'latitude' and 'day_of_year' or 'day_length', not both"),
    ("orbit_height = 0.6\nwatering", "latitude = 52\nday_of_year = 355\nwatering", 8, 12,
     "at latitude 52 on day 355 the noon sun stands 14.6 degrees high, below Arbor's lowest (15)"),
    ("orbit_height = 0.6\nwatering", "latitude = 80\nday_of_year = 172\nwatering", 8, 12,
     "'latitude' must be from -66 to 66 degrees north (it is 80)"),
]


@pytest.mark.parametrize("old, new, line, col, words", LAB_CASES)
def test_bad_lab_file_is_one_line_at_the_key(tmp_path, old, new, line, col, words):
    path = tmp_path / "bad_lab.toml"
    assert old in LAB
    path.write_text(LAB.replace(old, new, 1), encoding="utf-8")
    with pytest.raises(ExperimentError) as err:
        load_experiment(path, LSYS)
    text = str(err.value)
    assert "\n" not in text and text.startswith(f"{path}:{line}:{col}: "), text
    assert words in text, text


def test_species_is_one_key_in_lab_and_sweep_and_lsystem_is_read_with_a_note(tmp_path):
    path = tmp_path / "old.toml"
    path.write_text(LAB.replace("seed = 5", 'seed = 5\nlsystem = "game_poplar.lsys"'), encoding="utf-8")
    experiment = load_experiment(path, LSYS)
    assert experiment.lsystem.name == "game_poplar.lsys"
    assert experiment.notes == [f"{path}:3:1: note: 'lsystem' is now called 'species' (read as species)"]
    path.write_text(LAB.replace("seed = 5", 'seed = 5\nspecies = "game_poplar.lsys"'), encoding="utf-8")
    experiment = load_experiment(path, LSYS)
    assert experiment.lsystem.name == "game_poplar.lsys" and experiment.notes == []
    sweep = tmp_path / "s.toml"
    sweep.write_text(SWEEP.replace('title = "Sun"', 'title = "Sun"\nspecies = "game_poplar.lsys"'), encoding="utf-8")
    assert load_sweep(sweep, LSYS).species == "game_poplar.lsys"


def test_day_length_and_sun_elevation_set_the_sun_apart(tmp_path):
    from arbor.engine.life.experiment.lab import Lab
    from arbor.engine.life.rules.rules import load_rules

    path = tmp_path / "sun.toml"
    text = LAB.replace("orbit_height = 0.6", "day_length = 16\nsun_elevation = 45", 1)
    path.write_text(text.replace("seed = 5", "seed = 5\nseasons = false"), encoding="utf-8")  # no season offset
    lab = Lab(load_experiment(path, LSYS), load_rules(ASSETS / "rules.toml", "demo"))
    world = lab.worlds[0]
    s = world.sim
    lit = 0
    for _ in range(1000):  # one whole day of the sun, in steps
        s.state.sun_angle += 2 * 3.141592653589793 / 1000
        lit += s.sun_height() > 0
    assert abs(lit / 1000 * 24 - 16) < 0.1  # 16 of 24 hours of daylight
    s.state.sun_angle = 3.141592653589793 / 2  # noon
    direction = s.sun_direction()
    import math

    assert abs(math.degrees(math.asin(direction[1])) - 45) < 0.5


def test_a_place_and_a_date_set_the_day_length_and_the_noon_sun(tmp_path):
    import math

    from arbor.engine.life.experiment.lab import Lab
    from arbor.engine.life.experiment.schema import latitude_sun
    from arbor.engine.life.rules.rules import load_rules

    hours, noon = latitude_sun(0, 80)  # the equator at the March equinox: 12 h, the sun overhead
    assert abs(hours - 12) < 0.05 and noon > 89
    hours, noon = latitude_sun(52, 172)  # 52 deg north at midsummer (Berlin): 16.5 h, 61.4 deg (no refraction)
    assert abs(hours - 16.5) < 0.05 and abs(noon - 61.4) < 0.1
    assert latitude_sun(-52, 355) == pytest.approx(latitude_sun(52, 172), abs=0.05)  # the south's midsummer
    path = tmp_path / "place.toml"
    text = LAB.replace("orbit_height = 0.6", "latitude = 52\nday_of_year = 172", 1)
    path.write_text(text.replace("seed = 5", "seed = 5\nseasons = false"), encoding="utf-8")
    s = Lab(load_experiment(path, LSYS), load_rules(ASSETS / "rules.toml", "demo")).worlds[0].sim
    lit = 0
    for _ in range(1000):  # one whole day of the sun, in steps
        s.state.sun_angle += 2 * math.pi / 1000
        lit += s.sun_height() > 0
    assert abs(lit / 1000 * 24 - hours) < 0.1
    s.state.sun_angle = math.pi / 2  # noon
    assert abs(math.degrees(math.asin(s.sun_direction()[1])) - noon) < 0.5
