import numpy as np
import pytest

from arbor.engine.base.errors import LSysError
from arbor.engine.forest.geomatree import Species, growth_system, load_species, seed_points
from arbor.engine.geometry.tree import build_geometry
from arbor.engine.lsystem.derive import derive
from tests.conftest import ROOT

SOURCE = ROOT / "assets" / "lsystems" / "geomatree.lsys"


def grow(species, seed):
    system = growth_system(species, SOURCE, seed)
    ls = derive(system, seed=seed)
    return ls, build_geometry(ls, system).turtle


def test_same_species_other_seed_is_similar_with_different_detail():
    species = load_species(ROOT / "assets" / "presets" / "broadleaf.toml")
    (ls1, t1), (ls2, t2) = grow(species, 1), grow(species, 2)
    assert ls1.count("F") == ls2.count("F")  # the same branching pattern
    hi1, hi2 = t1.bounds()[1], t2.bounds()[1]
    assert abs(hi1[1] - hi2[1]) < 0.25 * hi1[1]  # similar height
    assert not np.allclose(t1.segments.end, t2.segments.end)  # different detail


def test_parameters_do_what_they_say():
    base = Species(levels=3, n_seed=1, seed_spread=0.0, l_k=0.0)
    _, tree = grow(base, 0)
    trunk = tree.segments.order == 0
    assert tree.segments.radius[trunk][0] == pytest.approx(base.r_0)
    buds = tree.segments.start[tree.segments.order == 1]
    assert buds[:, 1].min() == pytest.approx(base.trunk * base.r_bud, rel=1e-6)  # eq. 1: p_i = p_pa + r_bud v_pa
    up = grow(Species(levels=3, v_ext=[0.0, 15.0, 0.0]), 0)[1].bounds()[1][1]
    down = grow(Species(levels=3, v_ext=[0.0, -15.0, 0.0]), 0)[1].bounds()[1][1]
    assert up > down  # the external vector bends branches towards the sky or the ground
    east = grow(Species(levels=3, v_ext=[12.0, 0.0, 0.0]), 0)[1].segments.end[:, 0].mean()
    west = grow(Species(levels=3, v_ext=[-12.0, 0.0, 0.0]), 0)[1].segments.end[:, 0].mean()
    assert east > west + 1.0  # and wind blows it sideways


def test_branches_follow_the_control_points_of_eq_2():
    species = Species(levels=1, n_seed=1, seed_spread=0.0, l_k=0.1, r_bud=0.5)
    _, tree = grow(species, 0)
    trunk = tree.segments.order == 0
    points = np.concatenate([tree.segments.start[trunk][:1], tree.segments.end[trunk]])
    off_axis = np.hypot(points[:, 0], points[:, 2])
    # the control points at 1/3 and 2/3 of the trunk stand l_k x its length off the axis; the ends sit on it
    assert off_axis[0] == pytest.approx(0.0, abs=1e-9) and off_axis[-1] == pytest.approx(0.0, abs=1e-9)
    np.testing.assert_allclose(np.sort(off_axis)[-2:], species.l_k * species.trunk, rtol=1e-6)


def test_seed_points_fill_the_growth_space():
    points = seed_points(Species(n_seed=400, seed_spread=20.0), seed=3)
    radius = np.hypot(points[:, 0], points[:, 1])
    assert radius.max() <= 20.0 and radius.mean() > 10.0
    assert np.allclose(points, seed_points(Species(n_seed=400, seed_spread=20.0), seed=3))


def test_bad_preset_is_a_clear_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("r_bud = 1.5\n")
    with pytest.raises(LSysError, match="r_bud"):
        load_species(bad)
    bad.write_text('leaves = "many"\n')
    with pytest.raises(LSysError, match="unknown"):
        load_species(bad)
