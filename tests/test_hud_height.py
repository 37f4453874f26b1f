"""The HUD shows the cared-for tree's height: the top of its wood, the definition the postcard and the export
share (engine.geometry.tree.tree_height)."""

from __future__ import annotations

import pygame
import pytest

from arbor.engine.base.units import METRE
from arbor.engine.life.keep.away import tree_height
from arbor.game.render.ui import HudInfo, draw_hud
from arbor.game.screens.game import Game, GameConfig
from arbor.game.strings import text
from tests.conftest import FakeClock


def _hud(info: HudInfo) -> pygame.Surface:
    """The HUD drawn for ``info`` on a clear 640 x 400 surface."""
    pygame.font.init()
    surface = pygame.Surface((640, 400), pygame.SRCALPHA)
    draw_hud(surface, pygame.font.Font(None, 24), info)
    return surface


def test_the_hud_shows_the_height_the_postcard_and_export_use(gl_ctx, tmp_path):
    clock = FakeClock()
    game = Game(gl_ctx, (640, 400), GameConfig(saves=tmp_path, seed=4), clock=clock,
                wall_clock=lambda: 1.7e9 + clock.t)
    for _ in range(40):
        game.world.step(0.5)
    game.world.tree.light_scene(game.world.clocks())  # a light reading: the tree measures its wood's top
    shown = game.hud_info().height_m
    assert shown > 0 and shown == pytest.approx(tree_height(game.world) / METRE, rel=0.02)
    assert text("hud.tall", metres=shown).endswith(" m tall")
    pictures = [pygame.image.tobytes(_hud(HudInfo(0.5, 0.5, "", 600.0, 1.0, height_m=height)), "RGBA")
                for height in (0.0, shown)]
    assert pictures[0] != pictures[1]  # the line with the height is drawn


def test_the_meters_show_the_need_line_where_the_hints_and_the_stops_begin(gl_ctx, tmp_path):
    from arbor.engine.life.world.status import need_line

    clock = FakeClock()
    game = Game(gl_ctx, (640, 400), GameConfig(saves=tmp_path, seed=4), clock=clock)
    need = game.hud_info().need
    assert need == need_line(game.rules) > game.rules.growth.threshold  # (a little above the half mark)
    x = 20 + 90 + int(200 * need)  # under each bar, where the line is
    notch = [[_hud(HudInfo(0.9, 0.9, "", 600.0, 1.0, need=line)).get_at((x, y))[3] > 200 for y in (20 + 36, 68 + 36)]
             for line in (0.0, need)]
    assert notch == [[False, False], [True, True]]
