"""Issue 46: what a warm start spends its CPU on. numba's first use must not import scipy.linalg (about
150 ms: engine/base/jit.py), and the garbage collector rests while the game's modules and kernels load,
then keeps them out of its scans (game/first_start.py _settle_garbage)."""

import gc
import subprocess
import sys

import pygame

from arbor.game import first_start

_FIRST_USE = """
import sys
from arbor.game import first_start
first_start.kernel_dispatchers()
first_start.STAGES[1][1]()  # plain rules: numba loads (or compiles) a kernel, its first use in this process
import numba.np.arraymath
print('scipy.linalg' in sys.modules, numba.np.arraymath._HAVE_BLAS)
import numba, numpy as np
dot = numba.njit(lambda a, b: np.dot(a, b))  # BLAS still there for a kernel that asks for it
print(float(dot(np.ones((2, 3)), np.ones((3, 2)))[0, 0]), 'scipy.linalg' in sys.modules)
"""


def test_numba_first_use_leaves_scipy_linalg_unimported_and_blas_usable():
    run = subprocess.run([sys.executable, "-c", _FIRST_USE], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    first, second = run.stdout.split("\n")[:2]
    assert first == "False True"  # no scipy.linalg for the kernels; numba still knows BLAS is there
    assert second == "3.0 True"  # np.dot compiles and runs (importing scipy.linalg then)


class _Screen:
    def __init__(self, ctx, size):
        pass

    def draw(self, progress, line):
        pass


class _Warmup:
    """A warm start's warm-up (nothing to compile), done once the loop has looked twice; records whether
    the collector ran while it worked."""

    def __init__(self, extra=None):
        self.cold, self.progress, self.looks, self.collecting = False, 0.5, 0, []

    @property
    def done(self):
        self.collecting.append(gc.isenabled())
        self.looks += 1
        return self.looks > 2

    def result(self):
        return None


def test_the_collector_rests_during_a_warm_start_then_keeps_the_loaded_modules_out(gl_ctx, monkeypatch):
    monkeypatch.setattr(first_start, "TitleScreen", _Screen)
    made = []
    monkeypatch.setattr(first_start, "Warmup", lambda extra=None: made.append(_Warmup(extra)) or made[-1])
    pygame.event.clear()
    try:
        assert first_start.show_until_ready(None, (64, 64))
        assert made[0].collecting == [False, False, False]
        assert gc.isenabled() and gc.get_freeze_count() > 0
    finally:
        gc.unfreeze()
        gc.enable()


def test_a_window_closed_during_the_start_leaves_the_collector_running(gl_ctx, monkeypatch):
    monkeypatch.setattr(first_start, "TitleScreen", _Screen)
    monkeypatch.setattr(first_start, "Warmup", _Warmup)
    pygame.event.clear()
    pygame.event.post(pygame.event.Event(pygame.QUIT))
    try:
        assert not first_start.show_until_ready(None, (64, 64))
        assert gc.isenabled()
    finally:
        gc.enable()
