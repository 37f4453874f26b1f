"""Shared test fixtures: paths and a headless environment for pygame/moderngl."""

import os
from pathlib import Path

import pytest

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")
os.environ.setdefault("ARBOR_PACE", "demo")  # the tests run at the thesis's pace (20 s / 40 s, 2-minute days)

ROOT = Path(__file__).resolve().parent.parent
LSYSTEMS = ROOT / "assets" / "lsystems"


@pytest.fixture(scope="session")
def lsys_dir() -> Path:
    return LSYSTEMS


@pytest.fixture(scope="session")
def gl_ctx():
    """One headless EGL context for the whole run, with a (dummy-driver) pygame display for events."""
    import pygame

    from arbor.game.render.renderer import headless_context

    pygame.init()
    pygame.display.set_mode((64, 64))
    context = headless_context()
    yield context
    context.release()


class FakeClock:
    """A settable clock for code that takes ``clock=`` (seconds; call it to read, set ``t`` to move it)."""

    def __init__(self, t: float = 1000.0) -> None:
        self.t = t

    def __call__(self) -> float:
        return self.t


MODELER_SIZE = (1280, 720)


@pytest.fixture
def modeler_game(gl_ctx, tmp_path):
    """Make the real Game, headless at 1280x720, for driving the modeler through its input path: a
    settable clock (``game.clock_box[0]``, seconds) and an off-screen frame (``game.fbo``), drawn once."""
    from arbor.game.screens.game import Game, GameConfig

    def make(seed: int):
        clock = [0.0]
        game = Game(gl_ctx, MODELER_SIZE, GameConfig(saves=tmp_path, seed=seed, resume=False), clock=lambda: clock[0])
        game.clock_box = clock
        game.fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(MODELER_SIZE)],
                                      depth_attachment=gl_ctx.depth_renderbuffer(MODELER_SIZE))
        game.draw(game.fbo)
        return game
    return make
