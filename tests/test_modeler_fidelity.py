"""Modeler fidelity (seeds 000, 002, 004): region growth that stays in the region, a bend toward the
ground in world terms, growth points that keep what was drawn, lobes that are consistent."""

import copy
from pathlib import Path

import numpy as np
import pytest

from arbor.engine.geometry.turtle import TurtleConfig, module_positions
from arbor.engine.life.form.interpret import Clocks, render_view
from arbor.engine.life.plant.growth import new_axis_text
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.engine.modeling.edits import apply_edit, load_edit_sets
from arbor.engine.modeling.regions import Sphere

ASSETS = Path(__file__).resolve().parent.parent / "assets"


@pytest.fixture(scope="module")
def grown():
    rules = load_rules(ASSETS / "rules.toml", pace="demo")
    rules.seasons.enabled = False
    world = World(load_lsystem(ASSETS / "lsystems" / "game_tree.lsys"), rules, seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(2500):  # (10 game days: a crown wide enough that a region holds only part of it)
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)
    return world


def positions(world: World) -> np.ndarray:
    view = render_view(world.tree.lstring, Clocks(world.sim.state.length_time, world.sim.state.girth_time, 0.0),
                       world.tree.geometry_constants)
    return module_positions(view, TurtleConfig(pipe_model=False, leaves_at_tips=0))


def grow_steps(world: World, rewrites: int) -> None:
    target = world.tree.last_rewrite_T + rewrites * world.rules.growth.rewrite_step
    while world.tree.last_rewrite_T < target - 1e-9:
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(0.5)


@pytest.mark.parametrize("confined", [True, False])
def test_region_grow_keeps_new_growth_inside_the_region(grown, confined):
    """Seed 000 Fig. 11: rules applied only inside the region, for as long as it is active."""
    world = copy.deepcopy(grown)
    pos = positions(world)
    ls = world.tree.lstring
    internodes = np.flatnonzero(ls.sym == ord("I"))
    side = internodes[np.argmax(pos[internodes, 0])]  # the crown's far side: a branch, not the leader
    region = Sphere(tuple(pos[side]), 2.5)
    grow = load_edit_sets(ASSETS / "edits")["grow"]
    now = world.sim.state.length_time
    new, _, _ = apply_edit(ls, pos, region, grow, {"NOW": now, "P": 4.0, "IL": 1.0, "IO": 0.75, "MAXO": 4.0},
                                 new_axis=new_axis_text(world.system, now, world.sim.state.girth_time))
    world.tree.lstring = new
    if confined:
        world.tree.confine, world.tree.confine_left = region, 20
    t0 = world.sim.state.length_time
    grow_steps(world, 20)
    ls, pos = world.tree.lstring, positions(world)
    born = np.flatnonzero((ls.sym == ord("I")) & (ls.nparams == 5))
    born = born[ls.params[ls.offsets[born]] > t0]
    inside = region.contains(pos[born]).mean()
    assert len(born) >= 5
    if confined:
        assert (inside >= 0.95 and world.tree.confine is None) or world.tree.confine_left == 0
    else:
        assert inside < 0.6  # without the region's hold, the tree grows everywhere


def drawn_tree(rng):
    """A hand-drawn trunk and two branches, one curving in its own turn plane (jittered strokes)."""
    from arbor.engine.modeling.modeler import Modeler
    from arbor.engine.modeling.strokes import Stroke

    modeler = Modeler()
    u = np.linspace(0, 1, 120)
    # (the trunk leans a little towards the viewer, as drawn: a bend then turns it down that way, not
    # towards whichever side its jitter happened to lean, since jitter no longer reads as a lean)
    modeler.add_stroke(Stroke(np.stack([0 * u, 3 * u, 0.15 * u], 1) + rng.normal(0, 0.02, (120, 3)),
                              np.linspace(0, 1, 120)))
    for side in (-1, 1):
        path = np.stack([side * 2.2 * u, 2.0 + 1.2 * np.sin(np.pi * u), 0.4 * u], 1) + rng.normal(0, 0.02, (120, 3))
        modeler.add_stroke(Stroke(path, np.linspace(0, 1, 120)))
    return modeler


def test_bend_turns_every_branch_down_in_world_terms_and_keeps_stored_frames(grown):
    from arbor.engine.geometry.turtle import interpret
    from arbor.engine.modeling.bend import bend_region

    cfg = TurtleConfig(pipe_model=False, leaves_at_tips=0)
    ls = drawn_tree(np.random.default_rng(1)).lstring
    segs = interpret(ls, cfg).segments
    tips = np.setdiff1d(np.arange(len(segs)), segs.parent)
    side = tips[np.abs(segs.end[tips, 0]) > 1.0]  # the two branch tips
    new, count = bend_region(ls, ls, Sphere((0.0, 2.5, 0.0), 3.5))
    bent = interpret(new, cfg).segments
    order = np.argsort(bent.module)  # (the turns added shift the modules; the pieces keep their order)
    assert count == len(segs) > 60 and len(bent) == len(segs)  # every piece (jitter no longer adds pieces)
    assert np.all(bent.end[order][side, 1] < segs.end[side, 1] - 0.2)  # every branch tip goes down
    drawn = np.flatnonzero((new.sym == ord("F")) & (new.nparams == 11))
    row = np.full(len(new), -1)
    row[bent.module] = np.arange(len(bent))
    off = new.offsets[drawn]
    stored = np.stack([new.params[off + k] for k in range(1, 10)], 1)
    actual = np.concatenate([bent.start[row[drawn]], bent.frame[row[drawn], :, 0], bent.frame[row[drawn], :, 2]], 1)
    assert np.abs(stored - actual).max() < 1e-6  # V, H, U of every piece as the turtle draws it
    world = copy.deepcopy(grown)  # the game tree's grown internodes bend too
    view = render_view(world.tree.lstring, world.clocks(), world.tree.geometry_constants)
    before = interpret(view, cfg).segments
    crown = Sphere(tuple(before.end[np.argmax(before.end[:, 0])]), 3.0)
    new, count = bend_region(world.tree.lstring, view, crown)
    after = interpret(render_view(new, world.clocks(), world.tree.geometry_constants), cfg).segments
    moved = crown.contains(before.start)
    assert count > 0 and after.end[:, 1][np.argsort(after.module)][moved].mean() < before.end[moved, 1].mean()


def test_growth_points_wake_keeping_the_length_they_were_drawn_with(grown):
    """A growth point A(l, x, y, z, d) becomes an apex whose internodes are as long as its piece."""
    from arbor.engine.lsystem.derive import Deriver
    from arbor.engine.lsystem.lstring import parse_lstring

    const = grown.tree.geometry_constants
    for length in (1.0, 0.75, 0.5625, 0.3):
        ls = parse_lstring(f"I(0,0,0,0,0)[A({length},0,1,0,0.05)]A(0,0,0,1,0,0)")
        extern = {"T": 10.0, "G": 1.0, "DT": 50.0, "R": 1.0, "B": 0.0, "WL": 1.0, "SF": 1.0, "AF": 0.0, "SP": 0.0,
                  "SL": 0.0, "C": 1.0, "LG": 1.0}
        woken = Deriver(grown.tree.system, seed=1).step(ls, extern)[0]  # (the tree's own genome)
        apex = woken.module(int(np.flatnonzero(woken.sym == ord("A"))[0]))[1]
        order = apex[1]
        expected = min(max(np.log(length / const["IL"]) / np.log(const["IO"]), 1.0), 4.0)
        assert order == pytest.approx(expected)
        drawn = max(min(length, const["IL"] * const["IO"]), const["IO"] ** 4)  # within the orders that grow
        assert const["IL"] * const["IO"] ** order == pytest.approx(drawn)


def test_a_trunk_drawn_from_the_foot_of_the_sapling_becomes_its_trunk_without_a_step(grown):
    from arbor.engine.geometry.turtle import interpret
    from arbor.engine.life.form.interpret import grow_geometry
    from arbor.engine.modeling.modeler import Modeler
    from arbor.engine.modeling.strokes import Stroke

    rules = grown.rules
    world = World(grown.system, rules, seed=5)  # a fresh sapling
    const, clocks = world.tree.geometry_constants, world.clocks()
    modeler = Modeler(lstring=world.tree.lstring,
                      segments_of=lambda ls: grow_geometry(ls, clocks, const).turtle.segments)
    rng = np.random.default_rng(4)
    u = np.linspace(0, 1, 150)
    path = np.stack([0.3 * np.sin(2 * u), 4.0 * u, 0.1 * u], 1) + rng.normal(0, 0.015, (150, 3))
    path[0] = (0.05, 0.02, 0.0)  # started at the foot, by hand
    result = modeler.add_stroke(Stroke(path, np.linspace(0, 1.0, 150)))
    assert result.merged and result.snapped_to is None
    segs = grow_geometry(modeler.lstring, clocks, const).turtle.segments
    drawn = (modeler.lstring.sym[segs.module] == ord("F"))
    assert np.allclose(segs.start[0], 0.0) and drawn[0]  # the drawn trunk is the trunk
    top = np.flatnonzero(drawn)[-1]
    above = np.flatnonzero(segs.parent == top)
    assert len(above) and segs.end[:, 1].max() > 4.0  # the sapling grows on from its top
    ratio = segs.radius[above].max() / segs.radius_end[top]
    assert 0.8 < ratio < 1.25  # no step where the drawn trunk meets the sapling's stem
    roots = interpret(modeler.lstring, TurtleConfig(pipe_model=False, leaves_at_tips=0)).segments
    assert (roots.parent < 0).sum() == 1  # one trunk, not a second one beside the first


def test_a_flick_at_the_end_of_a_drawn_trunk_does_not_send_the_sapling_down(grown):
    """A hand's flick down (or sideways) over the last eighth of a trunk drawn from the sapling's foot:
    the sapling still grows on upward from the top (as the trunk leans as a whole), not along the flick."""
    from arbor.engine.life.form.interpret import grow_geometry
    from arbor.engine.modeling.modeler import Modeler
    from arbor.engine.modeling.strokes import Stroke

    world = World(grown.system, grown.rules, seed=5)
    const, clocks = world.tree.geometry_constants, world.clocks()
    for flick in ((0.0, -1.0), (1.0, -0.2)):  # down, sideways
        modeler = Modeler(lstring=world.tree.lstring,
                          segments_of=lambda ls: grow_geometry(ls, clocks, const).turtle.segments)
        u = np.linspace(0, 1, 140)
        path = np.stack([0.1 * u, 4.0 * u, 0 * u], 1)
        hook = np.linspace(0, 1, 20)[:, None] * np.array([flick[0], flick[1], 0.0]) * 0.5
        path = np.concatenate([path, path[-1] + hook[1:]])
        result = modeler.add_stroke(Stroke(path, np.linspace(0, 1.0, len(path))))
        assert result.merged
        segs = grow_geometry(modeler.lstring, clocks, const).turtle.segments
        drawn = modeler.lstring.sym[segs.module] == ord("F")
        top = np.flatnonzero(drawn)[-1]
        above = np.flatnonzero((segs.parent == top) & ~drawn)
        heading = segs.end[above] - segs.start[above]
        heading /= np.linalg.norm(heading, axis=1)[:, None]
        print(f"flick {flick}: the sapling's first piece heads {np.round(heading[0], 2)}")
        assert heading[0][1] > 0.9  # upward (without the fix: straight down along the flick)
