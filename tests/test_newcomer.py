"""A newcomer's first minutes: a window that cannot be seen is refused with one line, the first start says
what it compiles, and a tree shared as a postcard PNG comes back as the same tree."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from arbor.game.errors import UserError


def _no_display_env() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")}
    env.update(SDL_AUDIODRIVER="dummy", ARBOR_MAX_FRAMES="2")  # a window that did open ends at once
    return env


@pytest.mark.parametrize("args", [[], ["view", "assets/lsystems/abop_1_24a.lsys"]])
def test_windowed_command_without_display_is_refused_in_one_line(args):
    """No DISPLAY: SDL would fall back to its invisible offscreen driver; arbor says how to fix it, exit 1."""
    from arbor.game.paths import ROOT

    run = subprocess.run([sys.executable, "-m", "arbor.game.cli", *args], env=_no_display_env(), cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 1, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1, run.stderr
    assert "no display" in lines[0] and "xvfb-run -a arbor" in lines[0]


def test_a_driver_asked_for_by_name_is_kept(monkeypatch):
    """SDL_VIDEODRIVER=offscreen set on purpose (EGL screenshots) is the user's choice; a fallback is not."""
    from arbor.game.app import _refuse_invisible_window

    monkeypatch.setenv("SDL_VIDEODRIVER", "offscreen")
    _refuse_invisible_window("offscreen")
    _refuse_invisible_window("x11")
    monkeypatch.delenv("SDL_VIDEODRIVER")
    with pytest.raises(UserError, match="xvfb-run -a arbor"):
        _refuse_invisible_window("offscreen")


@pytest.mark.parametrize("progress", [0.25, 0.75])
def test_title_screen_bar_fills_with_the_kernels_progress(progress):
    """The first start's progress bar is green over `progress` of its width and dark over the rest."""
    import pygame

    from arbor.game.first_start import FIRST_START, TitleScreen

    pygame.display.init()
    pygame.font.init()
    screen = TitleScreen.__new__(TitleScreen)  # the drawing alone: no GL context needed
    screen.size = (800, 480)
    screen.title, screen.small = pygame.font.Font(None, 68), pygame.font.Font(None, 20)
    surf = screen.surface(progress, FIRST_START)
    row = int(480 * 0.62) + 5
    green = [x for x in range(800) if surf.get_at((x, row))[1] > 180]
    assert green, "no bar drawn"
    assert abs((max(green) - 200) / 400 - progress) < 0.03  # the bar spans the middle half: x 200..600
    assert surf.get_at((590, row))[1] < 60 if progress < 0.9 else True


def test_the_first_start_builds_every_compiled_kernel():
    """Every engine module with a numba kernel is in the first start's list (a kernel left out compiled
    silently the first time it ran, after the notice had said the machine was ready)."""
    from arbor.game.first_start import KERNEL_MODULES

    root = Path(__file__).resolve().parents[1]
    compiled = {"arbor." + ".".join(path.relative_to(root).with_suffix("").parts)
                for path in (root / "engine").rglob("*.py") if "numba.njit" in path.read_text(encoding="utf-8")}
    assert compiled and compiled <= set(KERNEL_MODULES), sorted(compiled - set(KERNEL_MODULES))


def test_the_warm_up_reaches_every_kernel_the_cold_check_reads():
    """warm_kernels() builds (or loads) exactly the kernels kernels_cold() checks: run in a fresh process,
    every dispatcher kernels_cold() reads is used by the warm-up itself or called from a kernel it used
    (a kernel called from another is built and cached with it). The light grid's kernel was left out once:
    every headless command said "first start" again."""
    code = """
from arbor.game.first_start import kernel_dispatchers, warm_kernels
warm_kernels()
found = kernel_dispatchers()
by_name = {(d.py_func.__module__, d.__name__): d for d in found}
reached = {key for key, d in by_name.items() if d.overloads}
todo = list(reached)
while todo:
    d = by_name[todo.pop()]
    for name in d.py_func.__code__.co_names:
        key = (d.py_func.__module__, name)
        if key in by_name and key not in reached:
            reached.add(key)
            todo.append(key)
print(sorted(n for key, n in ((k, k[1]) for k in by_name) if key not in reached))
"""
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "[]"


def test_the_first_start_notice_is_true(tmp_path, capsys, monkeypatch, gl_ctx):
    """A warm machine prints no notice after render, export and card; a cold one prints it once, after the
    arguments and files are checked (a mistyped name costs no compile), and never under -q."""
    from arbor.engine.life.keep.save import SavedGarden, write_garden
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem
    from arbor.game import first_start
    from arbor.game.cli import main
    from arbor.game.paths import ASSETS

    first_start.warm_kernels()
    source = tmp_path / "t.lsys"
    source.write_text("n: 3\nw: A\np1: A -> F[+A L][-A L]F A\n")
    save = tmp_path / "g.arbor"
    write_garden(SavedGarden([World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), load_rules(
        ASSETS / "rules.toml"), seed=1)]), save)
    for line in (["render", str(source), "--size", "64x64", "--out", str(tmp_path / "r.png")],
                 ["export", str(source), "--out", str(tmp_path / "e.glb")],
                 ["card", str(save), "--out", str(tmp_path / "c.png")]):
        assert main(line) == 0
        assert first_start.FIRST_START not in capsys.readouterr().err
    warmed = []
    monkeypatch.setattr(first_start, "kernels_cold", lambda: True)  # as on a fresh install
    monkeypatch.setattr(first_start, "warm_kernels", lambda progress=None: warmed.append(1))
    assert main(["render", str(tmp_path / "mistyped.lsys")]) == 1
    assert warmed == [] and first_start.FIRST_START not in capsys.readouterr().err
    assert main(["export", str(source), "--out", str(tmp_path / "f.glb"), "-q"]) == 0
    assert warmed == [1] and capsys.readouterr().err == ""
    assert main(["export", str(source), "--out", str(tmp_path / "g.glb")]) == 0
    assert warmed == [1, 1] and first_start.FIRST_START in capsys.readouterr().err


def test_the_title_screens_bar_moves_by_measured_work_not_by_kernel_count(monkeypatch):
    """The first start's bar follows the stages' measured compile seconds: after a stage weighing a tenth, it
    stands near a tenth (times the 0.9 kept for the imports after), and it moves with the clock inside a
    long stage instead of sitting still."""
    import threading
    import time

    from arbor.game import first_start

    release = threading.Event()
    monkeypatch.setattr(first_start, "STAGES", (("short", lambda: None, 1.0),
                                                ("long", lambda: release.wait(5), 9.0)))
    warm = first_start.Warmup()
    time.sleep(0.3)
    early = warm.progress
    time.sleep(0.6)
    later = warm.progress
    release.set()
    warm.result()
    assert 0.09 <= early < later < 0.9 and warm.progress == 1.0
