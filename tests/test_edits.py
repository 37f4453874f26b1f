"""Region edits: built-in production sets applied only inside a region (Onishi et al. 2003, 4.2, 5.2)."""

from pathlib import Path

import numpy as np

from arbor.engine.geometry.turtle import TurtleConfig, interpret, module_positions
from arbor.engine.life.form.interpret import Clocks, grow_geometry, render_view
from arbor.engine.lsystem.lstring import parse_lstring
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.engine.modeling.edits import apply_edit, load_edit_sets
from arbor.engine.modeling.regions import Sphere

ASSETS = Path(__file__).resolve().parents[1] / "assets"
SETS = load_edit_sets(ASSETS / "edits")


def game_tree(steps: int = 40):
    from arbor.engine.life.plant.growth import GrowingTree

    system = load_lsystem(ASSETS / "lsystems" / "game_tree.lsys")
    tree = GrowingTree(system)
    for k in range(1, steps + 1):
        tree.rewrite(float(k), float(k), 1.0)
    return tree, Clocks(length_time=float(steps) + 20, girth_time=float(steps) + 20, wilt=0.0)


def positions_of(tree, clocks):
    return module_positions(render_view(tree.lstring, clocks, tree.geometry_constants), TurtleConfig(pipe_model=False))


def test_erase_leaves_removes_only_the_leaves_inside():
    tree, clocks = game_tree()
    ls, pos = tree.lstring, positions_of(tree, clocks)
    leaf = ls.sym == ord("L")
    region = Sphere(tuple(pos[leaf][len(pos[leaf]) // 2]), 1.5)
    inside = region.contains(pos) & leaf
    assert 0 < inside.sum() < leaf.sum()
    new, changed, _ = apply_edit(ls, pos, region, SETS["erase_leaves"])
    assert changed == inside.sum()
    assert (new.sym == ord("L")).sum() == leaf.sum() - inside.sum()
    assert (new.sym != ord("L")).sum() == (ls.sym != ord("L")).sum()  # nothing else changed


def test_added_blossoms_grow_in_and_show_only_inside():
    tree, clocks = game_tree()
    ls, pos = tree.lstring, positions_of(tree, clocks)
    region = Sphere(tuple(pos[ls.sym == ord("I")].mean(axis=0)), 1.0)
    new, changed, _ = apply_edit(ls, pos, region, SETS["add_blossoms"], {"T": clocks.length_time, "G": 0.0})
    assert changed > 0 and new.count("K") == changed
    geometry = grow_geometry(new, clocks, tree.geometry_constants).turtle
    assert len(geometry.blossoms.position) == 0 or geometry.blossoms.size.max() == 0  # born now: zero size
    later = Clocks(clocks.length_time + 8, clocks.girth_time, 0.0)
    opened = grow_geometry(new, later, tree.geometry_constants).turtle.blossoms
    assert len(opened.position) == changed and opened.size.min() > 0.2
    assert np.linalg.norm(opened.position - region.center, axis=1).max() < 1.0 + 1.5  # on wood inside the ball


def test_bend_turns_branches_down_only_inside():
    from arbor.engine.modeling.bend import bend_region

    ls = parse_lstring("F(1)[&(30)F(1)F(1)]F(1)[&(30)F(1)F(1)]F(1)")
    pos = module_positions(ls)
    second = np.flatnonzero(ls.sym == ord("F"))[5]  # the upper branch's second piece
    new, changed = bend_region(ls, ls, Sphere(tuple(pos[second]), 0.2), degrees=20.0)
    assert changed == 1
    before, after = interpret(ls).segments.end, interpret(new).segments.end
    moved = np.linalg.norm(after - before, axis=1) > 1e-9
    assert moved.sum() == 1 and after[moved][0, 1] < before[moved][0, 1]


def test_grow_in_an_empty_region_starts_a_new_axis_there():
    ls = parse_lstring("F(1)F(1)")
    pos = module_positions(ls)
    new, changed, _ = apply_edit(ls, pos, Sphere((2.0, 0.5, 1.0), 0.3), SETS["grow"], new_axis="F(1)")
    assert changed == -1
    segs = interpret(new).segments
    assert np.isclose(np.linalg.norm(segs.start - [2.0, 0.5, 1.0], axis=1).min(), 0.0, atol=1e-6)


def test_a_budget_holds_back_growing_edits_but_not_erasing():
    tree, clocks = game_tree()
    ls, pos = tree.lstring, positions_of(tree, clocks)
    everywhere = Sphere(tuple(pos.mean(axis=0)), 1e6)
    full, changed, held = apply_edit(ls, pos, everywhere, SETS["add_leaves"], {"T": 1.0}, budget=len(ls) + 40)
    assert len(full) <= len(ls) + 40 and held > 0 and changed > 0
    bare, erased, held = apply_edit(ls, pos, everywhere, SETS["erase_leaves"], budget=len(ls) - 1000)
    assert held == 0 and erased == ls.count("L") and bare.count("L") == 0


def test_prune_region_removes_the_subtrees_that_start_inside_and_nothing_else():
    from arbor.engine.modeling.edits import prune_region

    tree, clocks = game_tree(60)
    ls, pos = tree.lstring, positions_of(tree, clocks)
    wood = np.flatnonzero(ls.sym == ord("I"))
    region = Sphere(tuple(pos[wood[len(wood) // 2]] + [0.0, 0.0, 0.0]), 0.8)
    new, removed = prune_region(ls, pos, region)
    assert 0 < removed < len(ls) and len(new) == len(ls) - removed
    new_pos = positions_of(type(tree)(tree.system, lstring=new), clocks)
    kept_wood = new_pos[new.sym == ord("I")]
    starts = np.array([pos[i] for i in wood[1:] if region.contains(pos[i][None])[0]])
    assert len(starts) and not region.contains(kept_wood[1:]).any()  # no piece starts in the region any more
    assert {round(float(y), 6) for y in kept_wood[:, 1]} <= {round(float(y), 6) for y in pos[wood][:, 1]}
    assert prune_region(new, new_pos, region)[1] == 0  # nothing left to cut there
    everything = Sphere((0.0, 0.0, 0.0), 1e6)
    stump, _ = prune_region(ls, pos, everything)
    assert stump.count("I") == 1  # the trunk's first piece always stays


def test_added_leaves_grow_round_the_branch_in_varied_sizes_not_a_comb():
    ls = parse_lstring("".join(f"F({0.3},0,{0.3 * k},0,0,1,0,0,0,1,0)" for k in range(20)))
    pos = module_positions(ls)
    new, changed, _ = apply_edit(ls, pos, Sphere((0.0, 3.0, 0.0), 5.0), SETS["add_leaves"], {"T": 0.0})
    assert changed == 20
    leaves = interpret(new).leaves
    side = leaves.frame[:, :, 0][:, [0, 2]]  # where each leaf points, seen from above
    azimuth = np.arctan2(side[:, 1], side[:, 0])
    spread = 1 - np.hypot(np.cos(azimuth).mean(), np.sin(azimuth).mean())  # circular variance
    assert spread > 0.5  # all round the branch
    vigour = np.array([new.module(i)[1][1] for i in np.flatnonzero(new.sym == ord("L"))])
    assert vigour.std() > 0.1 and vigour.min() >= 0.7 and vigour.max() <= 1.3  # sizes vary
