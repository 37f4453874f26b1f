"""The game a player comes back to: time away, first-run hints, garden care by tapping a tree, fruit
picked by a tap and sown, the journal, the menu's pages, seasons on screen and a steady light at 100x."""

import copy
import itertools
import math
import re
from pathlib import Path

import numpy as np
import pygame
import pytest

from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.input.events import DOWN, UP, InputEvent
from arbor.game.screens.game import Game, GameConfig
from tests.conftest import FakeClock
from tests.test_game import tap
from tests.test_seasons import careful

SIZE = (1280, 720)
ASSETS = Path(__file__).resolve().parent.parent / "assets"
NOW = 1.7e9


@pytest.fixture(scope="module")
def fruiting():
    """A tree in its second spring with ripe fruit (demo pace, about 5 s to grow; its fruit set on day 29 and
    ripen by day 31 under the clear-sky sun)."""
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), load_rules(ASSETS / "rules.toml", pace="demo"),
                  seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    careful(world, 31.5)
    return world


def framebuffer(ctx):
    return ctx.framebuffer(color_attachments=[ctx.renderbuffer(SIZE)], depth_attachment=ctx.depth_renderbuffer(SIZE))


def new_game(ctx, saves, pace="demo", seed=4, now=NOW) -> Game:
    clock = FakeClock()
    game = Game(ctx, SIZE, GameConfig(saves=saves, seed=seed, pace=pace), clock=clock, wall_clock=lambda: now + clock.t)
    game.fake_clock = clock
    pygame.event.clear()
    return game


def _turn_to(game, fbo, other, here) -> tuple[float, float]:
    """Turn the camera (close in) until the tree at ``other`` is in view from the one at ``here``;
    returns where it is on the screen."""
    dx, dz = np.array(other) - np.array(here)
    game.control.distance = 5.0
    for _ in range(12):
        x, y = game.hud.project(game.camera(), (dx, 1.0, dz))
        if 100 <= x < SIZE[0] - 100 and 100 <= y < SIZE[1] - 100:
            break
        game.control.turn(30.0)
    game.draw(fbo)
    return x, y


def test_three_days_away_at_home_pace_the_tree_lived_on(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path, pace="home", now=NOW - 3 * 86400)
    game.world.sim.state.water_meter = 0.95
    game.world.sim.state.sun_meter = 0.8
    time0, length0 = game.world.sim.state.time, game.world.sim.state.length_time
    game.quit()  # saved three days ago
    again = new_game(gl_ctx, tmp_path, pace="home")
    s = again.world.sim.state
    assert s.alive and s.time == pytest.approx(time0 + 3 * 86400, rel=0.01)
    assert s.length_time > length0  # it grew meanwhile
    message = again.hud_info().message
    assert message.startswith("While you were away (3.0 days) your tree") and "grew" in message
    assert not again.coach.hints  # a returning player gets no first-run hints


@pytest.mark.parametrize("saved_at", ["1.8e9", "nan", "1e308", "inf", '"yesterday"'])
def test_a_save_from_the_future_or_without_a_clock_loads_without_growth(gl_ctx, tmp_path, saved_at):
    game = new_game(gl_ctx, tmp_path)
    game.quit()
    path = tmp_path / "autosave.arbor"
    path.write_text(re.sub(r"saved_at = \S+", f"saved_at = {saved_at}", path.read_text()))
    before = copy.deepcopy(game.world.sim.state)
    again = new_game(gl_ctx, tmp_path)
    assert again.world.sim.state == before  # no time away, no error, the same tree
    assert "away" not in again.hud_info().message and "Could not" not in again.hud_info().message


def test_first_run_hints_go_one_by_one_as_the_player_finds_things(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    game.world.sim.state.water_meter, game.world.sim.state.sun_meter = 0.6, 0.9  # (water is what it needs)
    assert "watering can" in game.hud_info().hint
    tap(game, 600, 200)
    assert game.menu.visible and "watering can" in game.hud_info().hint
    water = game.menu.widget("water")
    game.handle_input(InputEvent(DOWN, 1.0, "touch:1", 1, *water.rect.center))  # (the open menu's press)
    game.handle_input(InputEvent(UP, 1.1, "touch:1", 1, *water.rect.center))
    assert "Drag to walk around" in game.hud_info().hint
    tap(game, 600, 200)  # close the menu
    game.control.turn(35.0)
    assert game.hud_info().hint == ""


def test_status_tells_a_new_player_what_the_tree_needs_in_their_pace(gl_ctx, tmp_path):
    home = new_game(gl_ctx, tmp_path / "home", pace="home")
    home.world.sim.state.sun_meter = home.world.sim.state.water_meter = 0.9
    # (a new garden's first day runs 144x at the home pace: 3.8 h of settling in are 95 s of play)
    assert home.hud_info().status.startswith("settling in") and "2 min" in home.hud_info().status
    assert home.hud_info().speed_note == "first day 144x, 10 min more"
    demo = new_game(gl_ctx, tmp_path / "demo")
    demo.world.sim.state.sun_meter = demo.world.sim.state.water_meter = 0.9
    assert "20 s" in demo.hud_info().status and demo.hud_info().speed_note == ""
    demo.world.sim.state.water_meter = 0.3
    assert "watering can" in demo.hud_info().status
    assert demo.hud_info().season.startswith("Spring, day 1")


def test_tapping_another_tree_cares_for_it_and_the_hud_says_which_needs_what(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    fbo = framebuffer(gl_ctx)
    game.act(Action.PLANT, 1.0)
    second = game.world
    game.act(Action.NEXT, 1.0)
    first = game.world
    second.sim.state.water_meter = 0.05  # the other tree is thirsty
    game.draw(fbo)
    assert game.hud_info().reminder.startswith("Tree 2: thirsty")
    x, y = _turn_to(game, fbo, second.position, first.position)
    tap(game, x + 6, y)
    assert game.world is second and not game.menu.visible
    assert "caring for tree 2" in game.hud_info().message
    game.act(Action.WATER, 1.0)
    game.update(1.0)
    assert second.sim.state.water_meter > 0.05 and not first.sim.state.watering  # water reaches that tree


def test_a_ripe_fruit_is_picked_by_a_tap_and_its_seed_sown(gl_ctx, tmp_path, fruiting):
    game = new_game(gl_ctx, tmp_path)
    game.garden.worlds[0] = copy.deepcopy(fruiting)
    game.coach.hints = []
    fbo = framebuffer(gl_ctx)
    game.draw(fbo)
    assert "Ripe fruit" in game.hud_info().reminder
    view = game.view.views[id(game.world)][1]
    ripe = np.flatnonzero(view.fruits.data[:, 10] >= 1.0)
    pixels = [game.hud.project(game.camera(), view.fruits.data[i, 0:3]) for i in ripe]
    x, y = next(p for p in pixels if p and 0 < p[0] < SIZE[0] and 0 < p[1] < SIZE[1])
    img = np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)
    red = (img[:, :, 0] > 120) & (img[:, :, 0] > img[:, :, 1] + 60) & (img[:, :, 0] > img[:, :, 2] + 60)
    assert red.sum() > 50  # ripe fruit is red on screen
    fruit_count = game.world.tree.lstring.count("O")
    tap(game, x + 3, y - 2)
    assert game.world.tree.lstring.count("O") == fruit_count - 1 and len(game.garden.seeds) == 1
    assert not game.menu.visible and "seed is in your bag" in game.hud_info().message
    game.care.sync_sliders()
    assert game.menu.widget("sow").label == "Sow a seed (1)"
    game.act(Action.SOW, 1.0)
    parent = game.garden.worlds[0]
    assert len(game.garden.worlds) == 2 and game.world.lineage.parents == (parent.lineage.id,)
    assert game.world.lineage.planted == pytest.approx(NOW + game.fake_clock.t, abs=1)
    assert not game.garden.seeds and "seed of tree 1" in game.hud_info().message
    game.act(Action.SOW, 1.0)
    assert "No seeds yet" in game.hud_info().message


def test_the_journal_page_lists_milestones_and_new_ones_are_announced(gl_ctx, tmp_path, fruiting):
    game = new_game(gl_ctx, tmp_path)
    world = copy.deepcopy(fruiting)
    world.journal.entries = [e for e in world.journal.entries if e[1] != "fruit"]
    game.garden.worlds[0] = world
    game.coach.watch()  # what was there is not news
    game.menu.show_at(600, 100, "journal")
    lines = game.menu.journal_lines
    assert any("the first branch" in line for line in lines) and any("the first blossom" in line for line in lines)
    assert lines[0].startswith("Day 1:")
    world.journal.write(world.sim.state.time, "fruit")
    game.coach.watch()
    assert game.hud_info().message == "Journal: the first fruit!"
    game.menu.show_at(600, 100, "journal")
    days = [line for line in game.menu.journal_lines if line.startswith("Day")]
    assert days[-1].endswith("the first fruit")  # (then the species still to find: test_species_choice.py)
    assert game.menu.journal_lines[len(days):] == game.care.species.goals()


def test_the_menu_puts_care_first_with_big_targets_and_tools_in_the_modeler(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    tap(game, 600, 200)
    names = {w.name for w in game.menu.shown()}
    assert names == {"orbit_height", "sun_speed", "water", "speed", "garden", "tools", "settings", "journal"}
    assert all(w.rect.height >= 48 and w.rect.width >= 48 for w in game.menu.shown())
    assert {"save", "prune", "crown"}.isdisjoint(names)  # developer and modeler buttons live elsewhere
    settings = game.menu.widget("settings")
    tap(game, *settings.rect.center)
    assert {w.name for w in game.menu.shown()} == {"save", "load", "share", "restore", "roots", "devices", "volume",
                                                   "mute", "away", "gardener", "back"}
    game.menu.hide()
    game.act(Action.MODELER, 1.0)
    assert game.modeling.active
    game.input.tap(500, 300)
    assert game.menu.page == "tools" and game.menu.widget("modeler").label == "Done"


def test_autumn_colours_the_crown_and_winter_leaves_it_bare(gl_ctx, tmp_path, fruiting):
    game = new_game(gl_ctx, tmp_path)
    game.coach.hints = []
    game.garden.worlds[0] = copy.deepcopy(fruiting)
    fbo = framebuffer(gl_ctx)
    year = game.rules.seasons.year_days

    def shot(turns):
        game.world.sim.state.sun_turns = turns
        game.world.sim.state.sun_angle = 1.2
        game.draw(fbo)
        img = np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)
        orange = (img[:, :, 0] > 110) & (img[:, :, 0] > img[:, :, 1] + 25) & (img[:, :, 1] > img[:, :, 2] + 25)
        green = (img[:, :, 1] > img[:, :, 0] + 15) & (img[:, :, 1] > img[:, :, 2] + 10)
        return orange[:430, 400:].sum(), green[:430, 400:].sum()  # (the crown against the sky, off the HUD)

    start = game.rules.seasons.start
    summer = shot(year * (1.5 - start) / 4 + year)
    autumn = shot(year * (2.4 - start) / 4 + year)  # early autumn: coloured, still on the tree
    assert autumn[0] > 20 * max(summer[0], 1) and autumn[0] > 1000
    late = shot(year * (2.97 - start) / 4 + year)
    assert late[0] < 0.1 * autumn[0] and game.renderer.leaf_keep < 0.05  # by the end the leaves have fallen
    game.world.sim.state.sun_turns = year * (3.2 - start) / 4 + year
    game.world.step(0.1)
    assert game.world.tree.lstring.count("L") == 0  # winter: bare


def test_the_light_stays_steady_when_days_fly_by(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    sim = game.world.sim
    suns = []
    game.state.autopilot = True  # (tended: the fast-forward guardian never needs to stop this day)
    game.set_speed(100.0)
    for _ in range(40):  # a day of the sun at 100x takes 1.26 s
        game.update(1 / 30)
        suns.append(game.view.scene_sun())
    turns = [float(np.dot(a, b)) for a, b in itertools.pairwise(suns)]
    assert min(turns) > math.cos(math.radians(1.0)) and min(s[1] for s in suns) > 0.3  # steady, and day
    game.set_speed(1.0)
    np.testing.assert_allclose(game.view.scene_sun(), sim.sun_direction())  # at 1x the sun is the sun


def test_crossing_two_trees_by_menu_and_tap_and_the_family_screen(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    game.coach.hints = []
    fbo = framebuffer(gl_ctx)
    game.act(Action.CROSS, 1.0)
    assert "second tree" in game.hud_info().message  # alone, no cross
    game.garden.plant(load_lsystem(ASSETS / "lsystems" / "game_poplar.lsys"), game.rules, now=NOW)
    game.act(Action.NEXT, 1.0)  # care for the first tree again: she is the mother
    mother, father = game.garden.worlds
    game.act(Action.CROSS, 1.0)
    assert game.care.crossing is mother and "Tap the other parent" in game.hud_info().message
    game.draw(fbo)
    x, y = _turn_to(game, fbo, father.position, mother.position)
    tap(game, x + 5, y)
    assert len(game.garden.worlds) == 3 and game.world.lineage.parents == (mother.lineage.id, father.lineage.id)
    assert "seedling is planted" in game.hud_info().message
    game.act(Action.FAMILY, 1.0)
    assert game.family.up and not game.menu.visible
    game.draw(fbo)
    boxes = {lin.id: box for box, lin in game.family.boxes}
    assert set(boxes) == {w.lineage.id for w in game.garden.worlds}
    assert boxes[mother.lineage.id].centery < boxes[game.world.lineage.id].centery  # parents above
    img = np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)
    box = boxes[mother.lineage.id]
    thumb = img[box.top:box.bottom, box.left:box.right]
    assert (thumb[:, :, 1] > thumb[:, :, 0] + 30).sum() > 30  # a sketch of the tree, with its leaves
    tap(game, *boxes[father.lineage.id].center)
    assert not game.family.up and game.world is father


def test_the_cut_away_view_shows_the_roots_in_the_soil(gl_ctx, tmp_path, fruiting):
    game = new_game(gl_ctx, tmp_path)
    game.coach.hints = []
    game.garden.worlds[0] = copy.deepcopy(fruiting)
    fbo = framebuffer(gl_ctx)

    def shot():
        game.draw(fbo)
        return np.frombuffer(fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)

    grass = shot()
    game.act(Action.ROOTS, 1.0)
    assert game.state.cutaway and game.menu.widget("roots").label == "Hide roots"
    soil = shot()
    low = soil[SIZE[1] - 150:, :, :]
    below = grass[SIZE[1] - 150:, :, :]
    assert (low[:, :, 0] > low[:, :, 1]).mean() > 0.5 and (below[:, :, 1] > below[:, :, 0]).mean() > 0.5
    foot = game.hud.project(game.camera(), (0.0, 0.0, 0.0))
    under = game.hud.project(game.camera(), (0.0, game.view.roots_bottom * 0.5, 0.0))
    assert foot is not None and under is not None and under[1] > foot[1] + 20  # the view reaches below the ground
    x, y = int(under[0]), int(under[1])
    column = soil[y - 40:y + 40, x - 40:x + 40]
    assert (np.abs(column - soil[y, x - 200]).sum(axis=2) > 40).sum() > 80  # roots stand out of the soil
