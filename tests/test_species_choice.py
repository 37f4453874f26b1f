"""Garden -> Species (issue 47): the player chooses which species of the collection Plant a tree plants; the
button and a line say which; the planted tree is of that species (its lineage and its form's defines)."""

from arbor.engine.life.world.actions import Action
from tests.test_game_life import new_game


def test_the_player_chooses_the_species_plant_a_tree_plants(gl_ctx, tmp_path):
    game = new_game(gl_ctx, tmp_path)
    assert game.menu.widget("species").label == "Species: its own"
    game.act(Action.SPECIES, 1.0)  # the game tree's next: the poplar
    game.act(Action.SPECIES, 1.0)  # then the spruce
    assert game.menu.widget("species").label == "Species: Spruce"
    assert "plants a Spruce now" in game.state.shown_message()
    game.act(Action.PLANT, 1.0)
    tree = game.world
    assert len(game.garden.worlds) == 2 and tree.lineage.species == "spruce"
    assert tree.system.constants["BA"] == 80.0  # (level whorls: the spruce's branching angle; each seedling varies it)
    for _ in range(4):  # birch, willow, oak, and round to the maple
        game.act(Action.SPECIES, 1.0)
    game.act(Action.PLANT, 1.0)
    assert game.world.lineage.species == "game_tree" and game.world.system is game.system
