"""A tree at night is lit by the moon and the sky, not a black cut-out (issue 47): by night the trees' light
comes from the moon the sky draws opposite the sun (backdrop.lamp), cool and dimmer than the sun's and
fading to nothing at the horizon as the sun's does, so day pictures are unchanged."""

import numpy as np
import pytest

from arbor.engine.geometry.instances import LeafInstances, TubeInstances
from arbor.game.render import garden
from arbor.game.render.backdrop import MOONLIGHT, lamp
from arbor.game.render.camera import OrbitCamera
from arbor.game.render.falling import StaticView
from tests.test_look import card_pixels, leaf_view, scene  # noqa: F401  (the fixture)


def test_the_lamp_is_the_sun_by_day_and_the_moon_by_night():
    day = np.array([0.3, 0.8, 0.2]) / np.linalg.norm([0.3, 0.8, 0.2])
    toward, colour = lamp(day)
    assert np.allclose(toward, day) and colour[0] > colour[2] > 0.5  # (the warm sun, as before)
    night = np.array([0.3, -0.8, 0.2]) / np.linalg.norm([0.3, -0.8, 0.2])
    toward, colour = lamp(night)
    assert np.allclose(toward, -night) and np.allclose(colour, MOONLIGHT)  # the moon high on a dark night
    for y in (1e-4, -1e-4):  # (at the horizon neither lights the trees: no jump from one to the other)
        assert max(lamp(np.array([np.sqrt(1 - y * y), y, 0.0]))[1]) < 1e-3


def test_a_leaf_at_night_is_moonlit(scene, monkeypatch):  # noqa: F811
    _, draw = scene
    camera = OrbitCamera(yaw=0.0, pitch=0.0, distance=9.0, target=np.array([0.0, 5.0, 0.0]))
    to_eye = (camera.eye - camera.target) / np.linalg.norm(camera.eye - camera.target)
    sun = -to_eye - np.array([0.0, 0.9, 0.0])  # far below the horizon before the leaf: the moon behind the viewer
    sun /= np.linalg.norm(sun)
    view = leaf_view(to_eye)
    empty = StaticView(TubeInstances.empty(), LeafInstances.empty(), LeafInstances.empty(), view.lo, view.hi)
    sky = draw(empty, camera, sun)
    moonlit = card_pixels(draw(view, camera, sun), sky)
    monkeypatch.setattr(garden, "lamp", lambda s: (np.asarray(s, float), (0.0, 0.0, 0.0)))  # (no moon: before)
    dark = card_pixels(draw(view, camera, sun), sky)
    assert len(moonlit) > 500 and len(dark) > 500
    assert moonlit.mean(axis=0)[1] > dark.mean(axis=0)[1] + 8  # (its green: 40 against 28, the sky alone)


@pytest.mark.parametrize("y", [0.2, 0.6, 0.95])
def test_by_day_the_lamp_is_the_old_sun(y):
    sun = np.array([np.sqrt(1 - y * y), y, 0.0])
    strength = min(y * 4.0, 1.0)
    old = (1.05 * (0.4 + 0.6 * y) * strength, 0.98 * (0.4 + 0.6 * y) * strength, 0.85 * strength)
    assert np.allclose(lamp(sun)[1], old) and np.allclose(lamp(sun)[0], sun)
