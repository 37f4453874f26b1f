"""The Borchert-Honda vigour sharing (Palubicki et al. 2009): the vectorised prefix-sum form against a plain
recursive one on random bracketed trees, conservation, and what apical control does to a grown tree."""

from __future__ import annotations

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
    for lam in (0.5, 0.62):
        path = tmp_path / f"bhl_{lam}.lsys"
        path.write_text(source.replace("#define BHL 0.5 ", f"#define BHL {lam} ", 1))
        world = World(load_lsystem(path), load_rules(lsys_dir.parent / "rules.toml", pace="demo"), seed=4)
        assert world.tree.geometry_constants["BHL"] == lam
        world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
        for _ in range(4000):
            world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
            world.step(0.5)
        heights.append(tree_height(world))
    assert heights[1] > 1.1 * heights[0], heights  # the leader drew vigour from the laterals
