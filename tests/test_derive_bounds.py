"""Every derivation a command runs ends in bounded time and memory (issue 45: context_plant.lsys with
--steps 100 took 271 s to reach its 2M budget; budget: 20000000 with one parametric rule peaked at
2.08 GB; arbor render derived for 204 s to 1.93 GB and only then refused)."""

from __future__ import annotations

import time

from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem
from arbor.game.commands import trees
from arbor.game.commands.trees import (
    DERIVE_MEMORY,
    DERIVE_MODULE_BYTES,
    TreeSource,
    derive_budget,
    derive_source,
    render_memory,
    render_modules,
)
from arbor.game.paths import ASSETS

CONTEXT = ASSETS / "lsystems" / "context_plant.lsys"


def test_a_time_budget_stops_derivation_before_a_step_that_would_end_late():
    deriver = Deriver(load_lsystem(CONTEXT), seed=0, seconds=0.5)
    started = time.perf_counter()
    _ls, reports = deriver.derive(steps=1000)
    assert time.perf_counter() - started < 3.0 and deriver.out_of_time and len(reports) < 1000
    unbounded = Deriver(load_lsystem(CONTEXT), seed=0)  # (the game's own steps: no time budget)
    assert unbounded.seconds is None and len(unbounded.derive(steps=3)[1]) == 3 and not unbounded.out_of_time


def test_the_derive_command_says_it_stopped_at_the_time_budget(monkeypatch, capsys):
    monkeypatch.setattr(trees, "DERIVE_SECONDS", 1.0)
    started = time.perf_counter()
    _, _ls = derive_source(TreeSource(CONTEXT, steps=1000))
    err = capsys.readouterr().err
    assert time.perf_counter() - started < 8.0 and "time budget 1 s reached at step" in err
    assert "of 1,000: derivation stopped there" in err and err.count("\n") == 1


def test_memory_is_estimated_before_the_work_and_the_budget_cut_to_fit():
    system = parse_lsystem("budget: 20000000\nw: A(1)\np1: A(x) -> A(x+1)F[A(x*2)]\n")
    budget, why = derive_budget(system, TreeSource(CONTEXT))
    assert budget * DERIVE_MODULE_BYTES <= DERIVE_MEMORY < 20_000_000 * DERIVE_MODULE_BYTES
    assert "module budget 20,000,000 would need about 2.0 GB" in why and "\n" not in why
    assert derive_budget(system, TreeSource(CONTEXT, budget=1000)) == (1000, "")


def test_a_render_derives_no_more_than_it_can_draw():
    system = load_lsystem(CONTEXT)
    most = render_modules((1024, 768), 0)
    assert render_memory((1024, 768), most, 0) <= trees.RENDER_MEMORY < render_memory((1024, 768), most + 10, 0)
    budget, why = derive_budget(system, TreeSource(CONTEXT), most)
    assert budget == most < 2_000_000 and "memory limit of 2.0 GB holds at this --lod" in why


def test_the_cut_budget_is_said_only_when_it_held_growth_back(capsys):
    small = TreeSource(CONTEXT, steps=3)  # (a few hundred modules: far below any cut)
    derive_source(small, most=render_modules((1024, 768), 0))
    assert capsys.readouterr().err == ""
    derive_source(TreeSource(CONTEXT, steps=40), most=2_000)
    err = capsys.readouterr().err
    assert "growing to 2,000 modules at most" in err and "module budget 2,000" in err
