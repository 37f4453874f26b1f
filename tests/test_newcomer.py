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
