import numpy as np
import pytest

from arbor.engine.life.form.interpret import Clocks
from arbor.engine.life.plant.growth import GrowingTree
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.lsys import load_lsystem

FPS = 60


@pytest.fixture(scope="module")
def system(lsys_dir):
    return load_lsystem(lsys_dir / "game_tree.lsys")


def grown_world(system, seconds, seed=3, dt=0.5):
    rules = load_rules("assets/rules.toml", pace="demo")
    rules.seasons.enabled = False
    world = World(system, rules, seed=seed)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for _ in range(round(seconds / dt)):
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(dt)
    return world


def internode_ends(tree, clocks):
    geo = tree.geometry(clocks)
    segs = geo.turtle.segments
    birth = tree.lstring.params[tree.lstring.offsets[segs.module]]
    return segs.end, birth, segs


def test_no_visible_jumps_at_1x_even_across_rewrites(system):
    world = grown_world(system, 900)
    tree, rate = world.tree, world.rules.growth.length_rate
    now = world.sim.state.length_time
    step = rate / FPS  # physiological time that passes in one frame at 1x
    worst, height = 0.0, 0.0
    for frame in range(240):
        before, _, segs = internode_ends(tree, Clocks(now, now))
        height = max(height, float(np.ptp(segs.end[:, 1])))
        if frame % 60 == 59:  # a rewrite every second of frames: new modules are born
            tree.rewrite(now + step, now + step, 1.0)
        after, birth, segs_after = internode_ends(tree, Clocks(now + step, now + step))
        old = birth < tree.last_rewrite_T if frame % 60 == 59 else np.ones(len(after), bool)
        assert old.sum() == len(before)
        worst = max(worst, float(np.linalg.norm(after[old] - before, axis=1).max()))
        new_len = np.linalg.norm(segs_after.end[~old] - segs_after.start[~old], axis=1)
        assert np.all(new_len < 0.01 * height)  # new internodes appear at (almost) zero size
        now += step
    assert worst < 0.01 * height, (worst, height)


def test_growth_saturates_and_trunk_tapers(system):
    world = grown_world(system, 1500)
    clocks = world.clocks()
    _, _, segs = internode_ends(world.tree, clocks)
    lengths = np.linalg.norm(segs.end - segs.start, axis=1)
    assert lengths.max() <= 1.0 + 1e-9  # saturating: old internodes never exceed their full length
    trunk = np.flatnonzero(segs.order == 0)
    radii = segs.radius[trunk][np.argsort(segs.start[trunk, 1])]
    assert np.all(np.diff(radii) <= 1e-12) and radii[0] > 4 * radii[-1]  # tapers, base thickest


def test_buds_wait_for_resources(system):
    tree = GrowingTree(system, seed=1)
    apices = []
    for k in range(1, 120):
        tree.rewrite(k * 1.0, k * 1.0, resources=0.0)
        apices.append(tree.lstring.count("A"))
    assert max(apices) == 1  # no resources: only the leader grows; every dormant bud stays asleep
    rich = GrowingTree(system, seed=1)
    for k in range(1, 120):
        rich.rewrite(k * 1.0, k * 1.0, resources=1.0)
    assert rich.lstring.count("A") > 3


def test_stays_in_budget_forever_and_never_freezes(system):
    sizes, heights = [], []
    rules = load_rules("assets/rules.toml", pace="demo")
    rules.seasons.enabled = False  # (winter rest would pause the height it checks)
    world = World(system, rules, seed=3)
    world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
    for i in range(round(2 * 3600 / 2.0)):  # two hours: 57 simulated days
        world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
        world.step(2.0)
        if i % 300 == 299:
            sizes.append(len(world.tree.lstring))
            heights.append(float(world.tree.geometry(world.clocks()).turtle.segments.end[:, 1].max()))
    assert max(sizes) <= system.budget
    assert heights[-1] > heights[-3] > heights[-5]  # still growing at the end: no wall
    assert np.isfinite(world.tree.lstring.params).all()


def test_world_is_deterministic(system):
    def run():
        world = World(system, load_rules("assets/rules.toml", pace="demo"), seed=11)
        for i in range(3000):
            if i % 500 == 0:
                world.apply(Action.WATER, 1.0)
            if i % 500 == 100:
                world.apply(Action.WATER, 0.0)
            if i == 1500:
                world.apply(Action.ORBIT_HEIGHT, 0.8)
            world.step(0.2)
        return world

    a, b = run(), run()
    assert a.tree.lstring.to_text() == b.tree.lstring.to_text()
    assert a.sim.state == b.sim.state
    assert len(a.tree.lstring) > 10
