"""Shared test fixtures: paths and a headless environment for pygame/moderngl."""

import os
from pathlib import Path

import pytest

os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

ROOT = Path(__file__).resolve().parent.parent
LSYSTEMS = ROOT / "assets" / "lsystems"


@pytest.fixture(scope="session")
def lsys_dir() -> Path:
    return LSYSTEMS
