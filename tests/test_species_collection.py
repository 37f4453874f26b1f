"""The game's collection of species (issue 47): six species from assets/species.toml, each a game .lsys with
the defines it changes, a conifer among them, each with its own look; their trees carry the species'
name; grown alike they differ in form; a bad collection is refused at its line."""

import pytest

from arbor.engine.life.form.growth_view import GrowthView
from arbor.engine.life.lineage.species import SpeciesError, load_collection, species_source, species_system
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.game.render.species import look_of
from tests.test_game_life import ASSETS

LSYSTEMS = ASSETS / "lsystems"


@pytest.fixture(scope="module")
def collection():
    return load_collection(ASSETS / "species.toml", LSYSTEMS)


def test_six_species_each_with_its_defines_name_and_look(collection):
    keys = [s.key for s in collection]
    assert len(keys) == 6 == len(set(keys)) and "spruce" in keys  # (a conifer among them)
    for species in collection:
        system = species_system(species, LSYSTEMS)
        assert all(system.constants[name] == value for name, value in species.defines.items())
        world = World(system, load_rules(ASSETS / "rules.toml", "demo"), seed=1)
        assert world.lineage.species == species.key and species.name and species.about
    looks = {(look_of(k).bark, look_of(k).leaf, look_of(k).cluster) for k in keys}
    assert len(looks) == 6


def test_grown_alike_the_species_differ_in_form(collection):
    def form(key):
        species = next(s for s in collection if s.key == key)
        world = World(species_system(species, LSYSTEMS), load_rules(ASSETS / "rules.toml", "demo"), seed=3)
        world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
        while world.sim.state.sun_turns < 8:
            world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
            world.step(0.5)
        ends = world.drawn_segments(world.tree.lstring).end
        wide = max(float(ends[:, 0].max() - ends[:, 0].min()), float(ends[:, 2].max() - ends[:, 2].min()))
        return world.tree.height / max(wide, 1e-6)  # (height over crown width)

    maple, poplar, willow = form("game_tree"), form("game_poplar"), form("willow")
    assert poplar > 2 * maple and willow < maple  # columnar, rounded, weeping wide


@pytest.mark.parametrize("text, words, line", [
    ('[oak]\nbase = "game_tree.lsys"\ndefines = { BRANCHY = 3 }\n', "declares no BRANCHY", 3),
    ('[oak]\nbase = "game_tree.lsys"\ncolour = "green"\n', "has no key 'colour'", 3),
    ('[oak]\nbase = "../secret.lsys"\n', "base must name a game .lsys", 2),
    ('[oak]\nbase = "game_tree.lsys"\ndefines = { BA = nan }\n', "finite number", 3),
    ('[Oak]\nbase = "game_tree.lsys"\n', "lower-case", 1),
    ('[oak]\nbase = "game_tree.lsys"\nunlock = "never"\n', "unlock must be one of", 3),
])
def test_a_bad_collection_is_refused_at_its_line(tmp_path, text, words, line):
    path = tmp_path / "species.toml"
    path.write_text(text)
    with pytest.raises(SpeciesError) as err:
        load_collection(path, LSYSTEMS)
    assert words in err.value.message and err.value.line == line


def test_a_species_source_is_its_base_with_its_defines():
    source = "#define BA 48        // branching angle\n#define BAX 1\np1: A -> B\n"
    assert species_source(source, {"BA": 62.0}) == source.replace("BA 48", "BA 62")


def test_the_spruce_keeps_its_needles_through_winter(collection):
    """An evergreen (EVERGREEN in its .lsys): in the first winter the spruce still has its needles, drawn
    green and all there (the renderer neither turns nor hides them), while a broadleaf is bare."""
    def leaves_in_winter(key):
        species = next(s for s in collection if s.key == key)
        world = World(species_system(species, LSYSTEMS), load_rules(ASSETS / "rules.toml", "demo"), seed=3)
        world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
        while world.sim.state.sun_turns < 24.5:  # (the demo pace's first winter, after the leaf drop)
            world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
            world.step(0.5)
        assert world.sim.season().index == 3
        return len(GrowthView(world.tree.lstring, world.clocks(), world.tree.geometry_constants).leaves)

    assert leaves_in_winter("spruce") > 100 and leaves_in_winter("birch") == 0  # (leaf cards drawn)
    assert look_of("spruce").evergreen and not look_of("birch").evergreen
    assert look_of("cross", {"EVERGREEN": 1.0}).evergreen and not look_of("cross", {"EVERGREEN": 0.0}).evergreen
