"""Hostile saves at the game's start (issue 33): an L-string of just `F`, an `F(1e12)`, NaN from the
tree's own .lsys; what the game writes it reads back (byte for byte); every unreadable save kept under
a name of its own."""

import math
import re
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.keep.save_check import BIG, CARBON_FIELDS, SIM_FIELDS
from arbor.engine.life.plant.journal import MAX_METRES, Journal
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem
from arbor.game.screens.game import Game, GameConfig
from benchmarks.fuzz import sample_garden_text
from tests.conftest import FakeClock

SIZE = (1280, 720)


@pytest.fixture(scope="module")
def base_save():
    return sample_garden_text(1)


@pytest.fixture(scope="module")
def rules():
    return load_rules("assets/rules.toml", pace="demo")


def with_lstring(save: str, lstring: str) -> str:
    """The save with its tree's L-string replaced (and its module count to match)."""
    out = re.sub(r"lstring = '''\n.*?'''", lambda _: "lstring = '''\n" + lstring + "'''", save, flags=re.S)
    return re.sub(r"(?m)^modules = \d+$", "modules = 1", out)


def start(gl_ctx, folder):
    clock = FakeClock()
    return Game(gl_ctx, SIZE, GameConfig(saves=folder, seed=3), clock=clock, wall_clock=lambda: 1.7e9 + clock.t)


def play(game, ctx, frames=30):
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))
    for _ in range(frames):
        game.update(1 / 10)
    game.draw(fbo)


def test_a_save_of_one_bare_f_starts_draws_and_saves(gl_ctx, tmp_path, base_save, rules):
    (tmp_path / "autosave.arbor").write_text(with_lstring(base_save, "F"))
    game = start(gl_ctx, tmp_path)
    assert game.world.tree.lstring.to_text() == "F"  # loaded, not set aside
    play(game, gl_ctx)
    game.quit()
    assert read_garden(tmp_path / "autosave.arbor", rules).world.tree.lstring.to_text() == "F"
    assert not list(tmp_path.glob("*.broken"))


def test_a_tree_of_1e12_units_starts_in_time_and_writes_a_bounded_journal(gl_ctx, tmp_path, base_save):
    (tmp_path / "autosave.arbor").write_text(with_lstring(base_save, "F(1e12)"))
    t0 = time.perf_counter()
    game = start(gl_ctx, tmp_path)
    play(game, gl_ctx, 5)
    assert time.perf_counter() - t0 < 20
    heights = [v for _, k, v in game.world.journal.entries if k == "height"]
    assert 0 < len(heights) <= MAX_METRES and max(heights) == MAX_METRES


def test_the_metre_milestones_stop_at_the_bound():
    system = load_lsystem("assets/lsystems/game_tree.lsys")
    world = World(system, load_rules("assets/rules.toml", pace="demo"), seed=1)
    journal = Journal()
    t0 = time.perf_counter()
    for height in (1e13, float("inf"), float("nan"), 1e13):
        journal.observe(world, height)
    assert time.perf_counter() - t0 < 1.0
    assert sum(k == "height" for _, k, _ in journal.entries) == MAX_METRES


def test_nan_from_the_trees_own_lsys_is_never_written(tmp_path, rules):
    """QG = 1 makes the game tree divide by zero in every apex's growth (the issue's embedded .lsys)."""
    source = load_lsystem("assets/lsystems/game_tree.lsys").source.replace("#define QG 0.12", "#define QG 1")
    world = World(parse_lsystem(source, "div0.lsys"), rules, seed=5)
    for _ in range(200):
        world.step(0.5)
    assert not np.isfinite(world.tree.lstring.params).all()  # the tree really holds NaN
    world.carbon.pool = float("nan")
    world.sim.state.time = float("inf")
    path = tmp_path / "autosave.arbor"
    write_garden(SavedGarden([world], saved_at=1.7e9), path)
    text = path.read_text()
    assert not re.search(r"\b(nan|inf)\b", text.split("lsystem_source")[0] + text.split('"""', 2)[-1])
    first = path.read_bytes()
    write_garden(read_garden(path, rules), path)
    assert path.read_bytes() == first


def test_each_broken_save_is_kept_under_its_own_name(gl_ctx, tmp_path):
    for k in range(3):
        (tmp_path / "autosave.arbor").write_text(f"format = 2\nbad {k} [[[")
        game = start(gl_ctx, tmp_path)
        assert "Could not load autosave.arbor" in game.hud_info().message
    kept = sorted(p.name for p in tmp_path.glob("*.broken"))
    assert kept == ["autosave.arbor.2.broken", "autosave.arbor.3.broken", "autosave.arbor.broken"]
    assert (tmp_path / "autosave.arbor.2.broken").read_text() == "format = 2\nbad 1 [[["


def test_a_bug_while_loading_sets_the_save_aside_in_one_line(gl_ctx, tmp_path, base_save, monkeypatch):
    import arbor.game.screens.saves as saves

    (tmp_path / "autosave.arbor").write_text(base_save)
    monkeypatch.setattr(saves, "live_away", lambda garden, seconds, **_: [][1])
    game = start(gl_ctx, tmp_path)
    message = game.hud_info().message
    assert "IndexError" in message and "\n" not in message and (tmp_path / "autosave.arbor.broken").exists()


def _hostile(kind, low, high):
    if kind == "bool":
        return st.booleans()
    if kind == "int":
        return st.sampled_from([int(low), int(high), int(high) + 1, 2**63 - 1])
    return st.sampled_from([low, high, high * 10, -BIG * 10, math.nan, math.inf, -math.inf, 0.5])


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(sim=st.fixed_dictionaries({k: _hostile(*v) for k, v in SIM_FIELDS.items()}),
       carbon=st.fixed_dictionaries({k: _hostile(*v) for k, v in CARBON_FIELDS.items()}),
       param=st.sampled_from([math.nan, math.inf, -math.inf, 1e300, -1e13, 2.5]),
       position=st.sampled_from([(math.nan, 0.0), (1e9, -1e9), (3.0, 4.0)]))
def test_whatever_state_the_game_is_in_saves_loads_and_saves_the_same_bytes(tmp_path, rules, sim, carbon, param,
                                                                            position):
    system = load_lsystem("assets/lsystems/game_tree.lsys")
    world = World(system, rules, seed=2)
    for name, v in sim.items():
        setattr(world.sim.state, name, v)
    for name, v in carbon.items():
        setattr(world.carbon, name, v)
    world.tree.lstring.params[:] = param
    world.position, world.steps, world.tree.shed_total = position, 2**60, -4
    world.tree.mean_light, world.tree.last_rewrite_T, world.last_light = math.nan, math.inf, math.nan
    world.journal.entries += [(math.inf, "height", 1.0), (1.0, "branch", math.nan), (2.0, "flower", 0.0)]
    path = tmp_path / "g.arbor"
    write_garden(SavedGarden([world], saved_at=1.7e9), path)
    first = path.read_bytes()
    write_garden(read_garden(path, rules), path)
    assert path.read_bytes() == first
