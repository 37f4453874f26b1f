"""The far ground under a low camera (issue 47, looks): aerial haze grows with the distance from the eye up
to the horizon, so the ground between the end of its near fade and the horizon is a gradient, not a flat
grey-green band, and stays ground (green), not fog, right up to a sharp horizon."""

import numpy as np

from arbor.game.render.camera import OrbitCamera
from arbor.game.render.garden import GardenRenderer
from arbor.game.render.renderer import sun_direction
from tests.test_look import drawer, trunk_view


def test_the_far_ground_hazes_on_up_to_the_horizon_not_a_flat_band(gl_ctx):
    renderer = GardenRenderer(gl_ctx)
    try:
        draw = drawer(gl_ctx, renderer)
        low = OrbitCamera(yaw=30.0, pitch=2.0, distance=24.0, target=np.array([0.0, 3.0, 0.0]))
        shot = draw(trunk_view(0.05), low, sun_direction(85.0, 40.0))
    finally:
        renderer.release()
    side = np.concatenate([shot[:, :100], shot[:, -100:]], axis=1).mean(axis=1)  # (away from the trunk)
    _, g, b = side.T
    ground = np.flatnonzero(g > b)
    horizon = int(ground[0])  # the first row of ground under the sky
    assert (b[horizon - 3:horizon] > g[horizon - 3:horizon]).all()  # sky right above it: a sharp line
    band = b[horizon:horizon + 24]  # the far ground just under the horizon, then the near fade (haze: bluish)
    assert band[0] - band[11] > 10, band  # the farthest rows hazier toward the horizon (measured 44; a flat band 0)
    assert (-np.diff(band[::4]) > 0.5).all(), band  # and a gradient all the way down, no slab in it
    assert (g[horizon:horizon + 24] > b[horizon:horizon + 24] + 8).all()  # still ground, not fog
