"""Hostile input, generated: saves, .lsys sources and TUIO packets never escape as anything but the error
meant for users; and whatever state the game can be in, it can save it and load it back.

A short version of `python -m benchmarks.fuzz` (same mutators, a few hundred cases, well under a minute).
"""

import logging
import random

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.keep.save_check import SIM_FIELDS
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.input.tuio import TuioParser
from benchmarks.fuzz import (
    mutate_text,
    random_packet,
    sample_garden_text,
    sample_sources,
    try_packet,
    try_save,
    try_source,
)

FAST = settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


@pytest.fixture(scope="module")
def base_save():
    return sample_garden_text()


@FAST
@given(seed=st.integers(0, 2**32 - 1))
def test_mutated_saves_load_or_say_why(base_save, tmp_path, seed):
    try_save(mutate_text(base_save, random.Random(seed)), tmp_path)


@FAST
@given(seed=st.integers(0, 2**32 - 1))
def test_mutated_sources_parse_or_say_why(seed):
    rng = random.Random(seed)
    with np.errstate(all="ignore"):
        try_source(mutate_text(rng.choice(SOURCES), rng))


SOURCES = sample_sources()


@settings(max_examples=400, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_tuio_packets_never_raise(seed):
    logging.disable(logging.WARNING)
    try:
        parser = TuioParser((1280, 720))
        rng = random.Random(seed)
        for _ in range(3):
            try_packet(parser, random_packet(rng))
    finally:
        logging.disable(logging.NOTSET)


def test_a_hostile_nesting_is_refused_not_a_crash():
    from arbor.engine.base.errors import LSysError
    from arbor.engine.lsystem.lsys import parse_lsystem

    for text in ("w: F(" + "-" * 495 + "1)", "w: F(" + "(" * 600 + "1" + ")" * 600 + ")",
                 "#extern x\nw: A(1)\np1: A(a) -> A(" + "+".join(["a"] * 3000) + ")"):
        with pytest.raises(LSysError) as info:
            parse_lsystem(text, "hostile.lsys")
        assert "nested too deeply" in info.value.message or "too long" in info.value.message


@pytest.fixture(scope="module")
def system(lsys_dir):
    return load_lsystem(lsys_dir / "game_tree.lsys")


def _bounded(name):
    kind, low, high = SIM_FIELDS[name]
    if kind == "bool":
        return st.booleans()
    if kind == "int":
        return st.integers(int(low), int(min(high, 2**62)))
    return st.floats(max(low, -1e9), min(high, 1e9), allow_nan=False, allow_infinity=False)


SIM_STATES = st.fixed_dictionaries({name: _bounded(name) for name in SIM_FIELDS})


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(values=SIM_STATES, trees=st.integers(1, 6), position=st.tuples(st.floats(-1e4, 1e4), st.floats(-1e4, 1e4)))
def test_whatever_the_game_saves_it_loads(system, tmp_path, values, trees, position):
    rules = load_rules("assets/rules.toml", pace="demo")
    worlds = []
    for k in range(trees):
        world = World(system, rules, seed=k)
        for name, value in values.items():
            setattr(world.sim.state, name, value)
        world.position = position
        worlds.append(world)
    path = tmp_path / "garden.arbor"
    write_garden(SavedGarden(worlds, trees - 1), path)
    saved = read_garden(path, rules)
    back, current = saved.worlds, saved.current
    assert current == trees - 1 and len(back) == trees
    for a, b in zip(worlds, back, strict=True):
        for name in ("sun_meter", "water_meter", "wilt", "length_time", "girth_time", "time", "alive"):
            assert getattr(a.sim.state, name) == getattr(b.sim.state, name)
        assert b.tree.lstring.equals(a.tree.lstring) and b.position == a.position
    write_garden(SavedGarden(back, current), path)  # and what was loaded saves again
    read_garden(path, rules)


def test_every_kind_of_user_file_reads_or_says_why(tmp_path):
    """Issue 45's classes, a short run: settings, kiosk, experiment, sweep, devices, species, recording,
    save, card and .lsys files, mutated, nested deep or not plain files, each read or refused in its
    own error within FILE_HANG_SECONDS (`python -m benchmarks.fuzz 0 0 0 10000` runs 10,000)."""
    import signal
    import time

    from benchmarks.fuzz import FILE_HANG_SECONDS, _alarm, _file_maker

    rng = random.Random(45)
    make, run = _file_maker(rng, sample_garden_text(1), tmp_path)
    old = signal.signal(signal.SIGALRM, _alarm)
    try:
        outcomes = []
        for _ in range(150):
            case = make()
            if case[0] == "derive":
                continue  # (the heavy derivations are the benchmark's: seconds each)
            started = time.perf_counter()
            signal.setitimer(signal.ITIMER_REAL, FILE_HANG_SECONDS)
            with np.errstate(all="ignore"):
                outcomes.append(run(case))
            signal.setitimer(signal.ITIMER_REAL, 0)
            assert time.perf_counter() - started < FILE_HANG_SECONDS
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    assert "read" in outcomes and "refused" in outcomes
