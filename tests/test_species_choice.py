"""Garden -> Species (issue 47): the player chooses which species of the collection Plant a tree plants; the
button and a line say which; species open with the garden's milestones (a first branch, a first fruit, a
winter lived through, a cross), stay open across restarts (settings.toml), and the journal says what is
still to find; the planted tree is of the chosen species (its lineage and its defines)."""

from arbor.engine.life.lineage.species import load_collection
from arbor.engine.life.world.actions import Action
from tests.test_game_life import ASSETS, new_game


def test_the_player_chooses_among_the_species_the_garden_has_opened(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    assert game.menu.widget("species").label == "Species: its own"
    game.act(Action.SPECIES, 1.0)  # the game tree's next open one: the poplar
    assert game.menu.widget("species").label == "Species: Poplar"
    assert "plants a Poplar now" in game.state.shown_message() and "4 more to find" in game.state.shown_message()
    game.act(Action.SPECIES, 1.0)
    assert game.menu.widget("species").label == "Species: Maple"  # (only the two open from the start)
    goals = game.care.species.goals()
    assert len(goals) == 4 and any("the Oak (a tree's first fruit)" in line for line in goals)
    game.update(1.0)
    game.world.journal.write(game.world.sim.state.time, "fruit", 1.0)  # the garden's first fruit
    game.fake_clock.t += 1.0
    game.update(1.0)
    assert "A new species to plant: the Oak!" in game.state.shown_message()  # (said once, as it opens)
    names = []
    for _ in range(3):
        game.act(Action.SPECIES, 1.0)
        names.append(game.menu.widget("species").label)
    assert names == ["Species: Poplar", "Species: Oak", "Species: Maple"]
    game.act(Action.SPECIES, 1.0)
    game.act(Action.SPECIES, 1.0)  # the oak again
    game.act(Action.PLANT, 1.0)
    oak = next(s for s in load_collection(ASSETS / "species.toml", ASSETS / "lsystems") if s.key == "oak")
    assert game.world.lineage.species == "oak" and game.world.system.constants["BA"] == oak.defines["BA"] != 58
    game.quit()
    again = new_game(gl_ctx, tmp_path)  # (the oak stays open: settings.toml keeps it)
    assert "oak" in again.sound.unlocked() and len(again.care.species.goals()) == 3


def test_a_cross_opens_the_willow(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    game.act(Action.PLANT, 1.0)
    first, second = game.garden.worlds
    game.garden.breed(first, second, 7, game.rules)
    assert any(s.key == "willow" for s in game.care.species.opened())
