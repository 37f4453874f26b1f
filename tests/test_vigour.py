"""The Borchert-Honda vigour sharing (Palubicki et al. 2009): the vectorised prefix-sum form against a plain
recursive one on random bracketed trees, conservation, and what apical control does to a grown tree."""

from __future__ import annotations

import re

import numpy as np
import pytest

from arbor.engine.life.plant.vigour import borchert_honda
from arbor.engine.lsystem.lstring import parse_lstring


def _random_tree(rng: np.random.Generator, depth: int = 0) -> str:
    """A random axis: internodes, laterals (nested to depth 4, some with no apex at all) and an apex."""
    out = []
    for _ in range(int(rng.integers(1, 5))):
        out.append("I")
        for _ in range(int(rng.integers(0, 3))):
            out.append("[+L]" if rng.random() < 0.3 or depth >= 4 else "[+" + _random_tree(rng, depth + 1) + "]")
    return "".join(out) + ("A" if rng.random() < 0.9 or depth == 0 else "")


def _reference(text: str, light: dict[int, float], lam: float) -> dict[int, float]:
    """Borchert-Honda by recursion over the parsed axes: Q up, then v down, branch point by branch point."""
    pos = 0

    def axis():  # [("apex", index) | ("lateral", subtree)] in order
        nonlocal pos
        items = []
        while pos < len(text) and text[pos] != "]":
            c = text[pos]
            if c == "[":
                pos += 1
                items.append(("lateral", axis()))
                pos += 1  # the ']'
            else:
                if c == "A":
                    items.append(("apex", pos))
                pos += 1
        return items

    def q(items):
        return sum(light[x] if kind == "apex" else q(x) for kind, x in items)

    out: dict[int, float] = {}

    def share(items, v):
        for k, (kind, x) in enumerate(items):
            if kind == "apex":
                out[x] = v  # an apex ends its axis: what reached it is its vigour
                continue
            q_l, q_m = q(x), q(items[k + 1:])
            den = (1 - lam) * q_l + lam * q_m
            if den > 0:
                share(x, v * (1 - lam) * q_l / den)
                v = v * lam * q_m / den
            else:
                share(x, 0.0)

    tree = axis()
    share(tree, q(tree))
    return out


@pytest.mark.parametrize("seed", range(12))
@pytest.mark.parametrize("lam", [0.35, 0.5, 0.58])
def test_prefix_sums_give_the_recursive_borchert_honda_shares(seed, lam):
    rng = np.random.default_rng(seed)
    text = _random_tree(rng)
    ls = parse_lstring(text)
    apex = np.flatnonzero(ls.sym == ord("A"))
    light = rng.random(len(apex)) * (rng.random(len(apex)) > 0.15)  # some apices in full shade
    got = borchert_honda(ls.sym, apex, light, lam)
    # parse_lstring keeps one module per character here, so string positions are character positions
    want = _reference(text, dict(zip(apex.tolist(), light.tolist(), strict=True)), lam)
    np.testing.assert_allclose(got, [want[int(i)] for i in apex], rtol=1e-9, atol=1e-12)
    assert got.sum() == pytest.approx(light.sum())  # vigour is shared, never made


def test_apical_control_feeds_the_leader_at_the_laterals_cost():
    ls = parse_lstring("I[+IA]I[+IA]I[+IA]IA")
    apex = np.flatnonzero(ls.sym == ord("A"))
    light = np.full(4, 0.6)
    even, leader_first, laterals_first = (borchert_honda(ls.sym, apex, light, lam) for lam in (0.5, 0.6, 0.4))
    np.testing.assert_allclose(even, light)
    assert leader_first[-1] > 0.6 > leader_first[0]  # the leader's tip gains, the lowest lateral loses
    assert laterals_first[-1] < 0.6 < laterals_first[0]


def test_a_species_with_strong_apical_control_grows_taller_on_the_same_light(lsys_dir, tmp_path):
    from arbor.engine.life.keep.away import tree_height
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.actions import Action
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem

    source = (lsys_dir / "game_tree.lsys").read_text()
    heights = []
    for lam in (0.5, 0.7):
        path = tmp_path / f"bhl_{lam}.lsys"
        path.write_text(re.sub(r"#define BHL [0-9.]+ ", f"#define BHL {lam} ", source, count=1))
        world = World(load_lsystem(path), load_rules(lsys_dir.parent / "rules.toml", pace="demo"), seed=4)
        assert world.tree.geometry_constants["BHL"] == lam
        world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
        for _ in range(4000):
            world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
            world.step(0.5)
        heights.append(tree_height(world))
    assert heights[1] > 1.1 * heights[0], heights  # the leader drew vigour from the laterals


def test_apical_control_weakens_as_the_tree_grows():
    from arbor.engine.life.plant.vigour import apical_control

    assert apical_control(0.6, 0.0, 4.0) == pytest.approx(0.6)  # a sapling: its species' own
    assert apical_control(0.6, 4.0, 4.0) == pytest.approx(0.55)  # half its lead at the fade height
    assert apical_control(0.6, 40.0, 4.0) == pytest.approx(0.5 + 0.1 / 11)  # an old crown: nearly even sharing
    assert apical_control(0.45, 40.0, 4.0) > 0.45  # (a decurrent species' laterals' lead fades alike)


def test_a_tall_tree_feeds_its_leader_less_than_a_sapling_would(lsys_dir):
    """The tree's own height sets its lambda (GrowingTree.sense through apical_control): the same crown read as
    a sapling's (a fade height far above it) sends its leader more of the light than read as an old tree's."""
    from arbor.engine.life.form.interpret import APEX, Clocks
    from arbor.engine.life.plant.growth import GrowingTree
    from arbor.engine.lsystem.lsys import load_lsystem

    system = load_lsystem(lsys_dir / "game_tree.lsys")
    assert system.constants["BHL"] > 0.5  # the game tree's sapling has a leader that leads
    leader = {}
    for fade in (1e3, 0.1):
        tree = GrowingTree(system, seed=1)
        tree.apical_fade = fade
        for k in range(1, 61):
            clocks = Clocks(float(k), float(k))
            scene = tree.light_scene(clocks)
            tree.sense(scene, np.full(len(scene.queries), 0.5), clocks, 1.0, np.array([0.0, 1.0, 0.0]), 4.0)
            tree.rewrite(float(k), float(k), resources=1.0)
        ls = tree.lstring
        apex = np.flatnonzero((ls.sym == APEX) & (ls.nparams == 6))
        order, light = ls.params[ls.offsets[apex] + 1], ls.params[ls.offsets[apex] + 3]
        assert len(apex) > 4
        leader[fade] = light[order == 0][0] / light[order > 0].mean()
    assert leader[1e3] > 1.2 * leader[0.1], leader


def test_a_species_sets_how_soon_its_apical_control_fades(lsys_dir, tmp_path):
    from arbor.engine.life.rules.rules import load_rules
    from arbor.engine.life.world.world import World
    from arbor.engine.lsystem.lsys import load_lsystem

    rules = load_rules(lsys_dir.parent / "rules.toml", pace="demo")
    source = (lsys_dir / "game_tree.lsys").read_text()
    assert World(load_lsystem(lsys_dir / "game_tree.lsys"), rules, seed=1).tree.apical_fade == rules.growth.apical_fade
    path = tmp_path / "slow_fade.lsys"
    path.write_text(source.replace("#define BHL", "#define BHF 30\n#define BHL", 1))
    assert World(load_lsystem(path), rules, seed=1).tree.apical_fade == 30.0
