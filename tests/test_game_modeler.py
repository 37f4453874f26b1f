"""Modeler I through the real input path: synthetic touches, mouse and a 3D tracker into the game."""

import numpy as np
import pytest

from arbor.engine.life.keep.save import SavedGarden, read_garden, write_garden
from arbor.engine.life.world.actions import Action
from arbor.game.input.events import DOWN, MOVE, UP, InputEvent

SIZE = (1280, 720)


@pytest.fixture
def game(modeler_game):
    return modeler_game(seed=3)


def touch(game, kind, fid, x, y):
    game.handle_input(InputEvent(kind, game.clock_box[0], "touch:1", fid, x, y))


def press_menu(game, name):
    game.tap(100, 100)
    center = game.menu.reveal(name).rect.center
    touch(game, DOWN, 8, *center)
    touch(game, UP, 8, *center)
    if game.menu.visible:  # (a tool pressed in the modeler closes it itself)
        game.tap(1200, 700)
    assert not game.menu.visible


def draw(game, points, fid=0, dt=0.02, check=None):
    touch(game, DOWN, fid, *points[0])
    for p in points[1:]:
        game.clock_box[0] += dt
        touch(game, MOVE, fid, *p)
        if check:
            check()
    game.clock_box[0] += dt
    touch(game, UP, fid, *points[-1])


def base_pixel(game):
    return game.hud.project(game.camera(), (0.0, 0.5, 0.0))


def test_one_finger_draws_a_branch_that_becomes_modules(game, gl_ctx):
    press_menu(game, "modeler")
    assert game.modeling.active and game.loop.speed == 0
    before = len(game.world.tree.lstring)
    x0, y0 = base_pixel(game)
    shown = []

    def check():  # what the player sees after each move: the tree plus the stroke so far
        game.view.rebuild()
        ls = game.modeling.lstring()
        drawn = [ls.module(i)[1][0] for i in range(len(ls)) if len(ls.module(i)[1]) == 11]
        shown.append((game.triangles, sum(drawn)))

    draw(game, [(x0 + 6 * i, y0 - 8 * i) for i in range(40)], check=check)
    ls = game.world.tree.lstring
    drawn = [ls.module(i) for i in range(len(ls)) if ls.module(i)[0] == "F" and len(ls.module(i)[1]) == 11]
    assert len(drawn) > 5 and len(ls) > before
    assert shown[2][0] > shown[0][0] and shown[-1][1] > 3 * shown[2][1] > 0  # it appears and lengthens as drawn
    # every drawn point lies on the plane through the tree's axis facing the camera
    point, normal = game.modeling.last_plane
    starts = np.array([p[1][1:4] for p in drawn])
    assert np.abs((starts - point) @ normal).max() < 0.05
    assert "joined the tree" in game.hud_info().message


def test_two_fingers_move_the_view_and_do_not_draw(game):
    press_menu(game, "modeler")
    text = game.world.tree.lstring.to_text()
    yaw = game.control.yaw
    touch(game, DOWN, 0, 500, 400)
    touch(game, DOWN, 1, 700, 400)
    for i in range(1, 10):
        game.clock_box[0] += 0.02
        touch(game, MOVE, 0, 500 + 20 * i, 400)
        touch(game, MOVE, 1, 700 + 20 * i, 400)
    touch(game, UP, 0, 680, 400)
    touch(game, UP, 1, 880, 400)
    assert game.world.tree.lstring.to_text() == text
    assert game.control.yaw != yaw


def test_tap_opens_the_menu_in_the_modeler_and_undo_redo(game):
    press_menu(game, "modeler")
    empty = game.world.tree.lstring.to_text()
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 5 * i, y0 - 9 * i) for i in range(30)])
    drawn = game.world.tree.lstring.to_text()
    assert drawn != empty
    press_menu(game, "undo")
    assert game.world.tree.lstring.to_text() == empty and game.hud_info().message.startswith("Undone: ")
    assert "branch pieces" in game.hud_info().message and "taken away" in game.hud_info().message
    press_menu(game, "undo")
    assert game.hud_info().message == "Nothing to undo."  # (not the undone stroke's old toast)
    press_menu(game, "redo")
    assert game.world.tree.lstring.to_text() == drawn and game.hud_info().message.startswith("Redone: ")
    press_menu(game, "redo")
    assert game.hud_info().message == "Nothing to redo."


def test_tracker_draws_in_3d(game):
    press_menu(game, "modeler")
    path = [(0.02 * i, 1.0 + 0.05 * i, 0.03 * i) for i in range(40)]
    for k, p in enumerate(path):
        kind = DOWN if k == 0 else (UP if k == len(path) - 1 else MOVE)
        game.handle_input(InputEvent(kind, 0.05 * k, "hid:SpaceMouse", 0, *p, dims=3))
    ls = game.world.tree.lstring
    drawn = np.array([ls.module(i)[1][1:4] for i in range(len(ls)) if len(ls.module(i)[1]) == 11])
    assert len(drawn) > 5
    assert np.abs(drawn[:, 2] - drawn[:, 0] * 1.5).max() < 0.05  # follows the tracker's path in depth


def test_modeled_tree_saves_reloads_and_keeps_growing(game, tmp_path):
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 7 * i, y0 - 7 * i) for i in range(40)])
    press_menu(game, "modeler")
    assert not game.modeling.active and game.loop.speed == 1.0
    path = tmp_path / "modeled.arbor"
    write_garden(SavedGarden([game.world]), path)
    back = read_garden(path, game.rules).world
    assert back.tree.lstring.equals(game.world.tree.lstring)
    apices = back.tree.lstring.count("A")
    back.sim.state.orbit_height, back.sim.state.sun_meter, back.sim.state.water_meter = 1.0, 0.9, 0.9
    for _ in range(4000):
        back.apply(Action.WATER, float(back.sim.state.water_meter < 0.6))
        back.step(0.5)
    grown = back.tree.lstring
    drawn_points = sum(1 for i in range(len(grown)) if grown.module(i)[0] == "A" and len(grown.module(i)[1]) == 5)
    assert drawn_points < apices  # growth points woke into growing apices


def test_crown_outline_grows_the_tree_into_it(game):
    press_menu(game, "crown")
    assert game.modeling.active and game.modeling.crown
    before = game.world.tree.lstring

    def trunk_radius():
        return game.world.tree.geometry(game.world.clocks()).turtle.segments.radius[0]

    thin = trunk_radius()
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    outline = [(x0 + 160 * np.cos(t), y0 - 330 + 120 * np.sin(t)) for t in a]
    touch(game, DOWN, 0, *outline[0])
    for p in outline[1:24]:
        game.clock_box[0] += 0.02
        touch(game, MOVE, 0, *p)
    pixels = np.frombuffer(game.hud.overlay_pixels(game.camera()), np.uint8).reshape(SIZE[1], SIZE[0], 4)
    green_line = (pixels[..., 1] > 200) & (pixels[..., 0] < 150) & (pixels[..., 3] > 200)
    assert green_line.sum() > 300  # the outline is drawn over the scene as it is traced
    for p in outline[24:]:
        game.clock_box[0] += 0.02
        touch(game, MOVE, 0, *p)
    touch(game, UP, 0, *outline[-1])
    grown = game.world.tree.lstring
    assert "branch pieces into the outline" in game.hud_info().message, game.hud_info().message
    assert len(grown) > len(before) + 500
    assert grown.count("L") > before.count("L") + 20  # the crown's twigs carry leaves
    assert trunk_radius() > 3 * thin  # and the trunk carries their pipes (pipe model)
    press_menu(game, "undo")
    assert game.world.tree.lstring.equals(before)


def test_prune_tool_cuts_the_tapped_branch_and_undo_restores_it(game):
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 6 * i, y0 - 8 * i) for i in range(40)])
    drawn = game.world.tree.lstring
    press_menu(game, "prune")
    assert game.modeling.pruning and not game.modeling.crown

    def pieces():
        return len(game.modeling.segments(game.world.tree.lstring))

    full = pieces()
    touch(game, DOWN, 0, x0 + 6 * 30, y0 - 8 * 30)  # a tap on the drawn branch, well above the trunk
    touch(game, UP, 0, x0 + 6 * 30, y0 - 8 * 30)
    assert not game.menu.visible and "Cut" in game.hud_info().message
    assert 0 < full - pieces() < full - 2  # only that branch's end went, the trunk stayed
    touch(game, DOWN, 0, 1000, 80)  # a tap on the sky still opens the menu
    touch(game, UP, 0, 1000, 80)
    assert game.menu.visible
    game.tap(1200, 700)
    press_menu(game, "undo")
    assert game.world.tree.lstring.equals(drawn)


def test_symbols_tool_writes_the_lstring_where_it_is(game):
    press_menu(game, "symbols")
    assert game.modeling.symbols
    x0, y0 = base_pixel(game)
    touch(game, DOWN, 0, x0 + 40, y0 - 60)
    game.clock_box[0] += 0.5
    touch(game, MOVE, 0, x0, y0 - 150)  # onto the trunk
    pixels = np.frombuffer(game.hud.overlay_pixels(game.camera()), np.uint8).reshape(SIZE[1], SIZE[0], 4)[::-1]
    labels = game.modeling.region_tool.labels
    ls = game.world.tree.lstring
    assert any(turn for *_, turn in labels) and any(not turn for *_, turn in labels)
    assert {symbol for symbol, *_ in labels} - {"…"} <= {chr(c) for c in ls.sym}  # … ends a long row
    assert len(labels) < len(ls)  # only the modules inside the region
    red = (pixels[..., 0] > 200) & (pixels[..., 1] < 120) & (pixels[..., 3] > 200)
    _, xs = np.nonzero(red)
    assert len(xs) > 20 and abs(np.median(xs) - x0) < 120  # red symbols drawn near the trunk
    touch(game, UP, 0, x0, y0 - 150)
    assert game.world.tree.lstring is ls  # reading never edits


def test_tap_inside_the_symbols_circle_applies_the_chosen_edit(game):
    press_menu(game, "symbols")
    x0, y0 = base_pixel(game)
    touch(game, DOWN, 0, x0, y0 - 100)
    game.clock_box[0] += 0.5
    touch(game, MOVE, 0, x0, y0 - 200)
    touch(game, UP, 0, x0, y0 - 200)
    before = game.world.tree.lstring
    assert game.modeling.edit == "add_leaves"
    game.clock_box[0] += 1.0
    touch(game, DOWN, 0, x0, y0 - 200)  # tap in the circle
    touch(game, UP, 0, x0, y0 - 200)
    assert not game.menu.visible
    added = game.world.tree.lstring
    assert added.count("L") > before.count("L") and "Add leaves" in game.hud_info().message
    press_menu(game, "edit")  # -> erase leaves
    assert game.menu.widget("edit").label == "Erase leaves"
    touch(game, DOWN, 0, x0, y0 - 200)
    touch(game, UP, 0, x0, y0 - 200)
    assert game.world.tree.lstring.count("L") < added.count("L")
    press_menu(game, "undo")
    assert game.world.tree.lstring.equals(added)


def test_crown_regrows_into_every_lobe_and_undo_brings_lobes_back(game):
    press_menu(game, "crown")
    base = game.world.tree.lstring
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 - 90 + 90 * np.cos(t), y0 - 330 + 100 * np.sin(t)) for t in a])
    one = game.world.tree.lstring
    assert "1 lobe," in game.hud_info().message
    draw(game, [(x0 + 130 + 110 * np.cos(t), y0 - 300 + 100 * np.sin(t)) for t in a])  # (the view stays as it was)
    two = game.world.tree.lstring
    assert "2 lobes" in game.hud_info().message
    assert game.modeling.crown_tool.state().base is base  # regrown from the tree before the crown
    assert two.count("L") > one.count("L")
    press_menu(game, "undo")
    assert game.world.tree.lstring is one and len(game.modeling.crown_tool.state().lobes) == 1
    # a 3D tracker draws rings around the crown: two rings at different heights make one more lobe
    ring = np.stack([np.cos(a), np.zeros_like(a), np.sin(a)], 1)
    for k, height in enumerate((2.6, 3.6)):
        for i, p in enumerate(ring * (0.8 - 0.2 * k) + [0.0, height, 0.0]):
            game.modeling.add3d(p, i * 0.02)
        game.modeling.finish()
        if k == 0:
            assert "ring" in game.hud_info().message and game.world.tree.lstring is one
    assert "2 lobes" in game.hud_info().message
    assert len(game.modeling.crown_tool.state().rings) == 2


def test_strokes_and_crowns_stay_within_the_tree_budget(game):
    press_menu(game, "modeler")
    before = game.world.tree.lstring
    game.world.tree.deriver.budget = len(before) + 10
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 6 * i, y0 - 8 * i) for i in range(40)])
    assert game.world.tree.lstring is before and "size limit" in game.hud_info().message
    game.world.tree.deriver.budget = len(before) + 400
    press_menu(game, "crown")
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 160 * np.cos(t), y0 - 330 + 120 * np.sin(t)) for t in a])
    grown = game.world.tree.lstring
    assert len(before) + 100 < len(grown) <= len(before) + 400
    assert "size limit" in game.hud_info().message


def test_shape_tool_moves_scales_and_pulls_lobes_and_the_crown_follows(game):
    press_menu(game, "crown")
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 100 * np.cos(t), y0 - 330 + 90 * np.sin(t)) for t in a])
    crowned = game.world.tree.lstring
    lobe = game.modeling.crown_tool.state().lobes[0]
    press_menu(game, "shape")
    assert game.modeling.shaping and game.menu.widget("edit").label == "Lobe: move"
    centre = game.hud.project(game.camera(), lobe.vertices.mean(axis=0))
    draw(game, [(centre[0] + 12 * i, centre[1]) for i in range(16)])  # drag the lobe 180 px right
    moved = game.modeling.crown_tool.state().lobes[0]
    shift = moved.vertices.mean(axis=0) - lobe.vertices.mean(axis=0)
    assert np.hypot(shift[0], shift[2]) > 0.5 and abs(shift[1]) < 1e-6
    assert np.allclose(np.ptp(moved.vertices, axis=0), np.ptp(lobe.vertices, axis=0))
    tips = game.modeling.segments(game.world.tree.lstring).end
    assert game.world.tree.lstring is not crowned and "Lobe move" in game.hud_info().message
    assert moved.contains(tips[-50:]).mean() > 0.8  # the regrown crown fills the moved lobe
    press_menu(game, "edit")
    assert game.menu.widget("edit").label == "Lobe: scale"
    centre = game.hud.project(game.camera(), moved.vertices.mean(axis=0))
    draw(game, [(centre[0], centre[1] - 10 * i) for i in range(15)])  # drag up: bigger
    scaled = game.modeling.crown_tool.state().lobes[0]
    assert np.ptp(scaled.vertices[:, 1]) / np.ptp(moved.vertices[:, 1]) == pytest.approx(np.exp(140 / 200), rel=0.02)
    for _ in range(3):
        press_menu(game, "edit")  # turn, squeeze, point
    assert game.menu.widget("edit").label == "Lobe: point"
    ring, index = 3, 0
    grab = game.hud.project(game.camera(), scaled.stroke_rings[ring, index])
    draw(game, [(grab[0], grab[1] - 6 * i) for i in range(12)])
    pulled = game.modeling.crown_tool.state().lobes[0]
    assert pulled.stroke_rings[ring, index][1] > scaled.stroke_rings[ring, index][1] + 0.2
    assert np.allclose(pulled.stroke_rings[ring, 16], scaled.stroke_rings[ring, 16])  # far side stays
    press_menu(game, "undo")
    assert game.modeling.crown_tool.state().lobes[0] is scaled  # undo brings the lobe back too


def test_tracker_arch_closes_the_ring_lobe_with_a_dome(game):
    press_menu(game, "crown")
    a = np.linspace(0, 2 * np.pi, 48)
    ring = np.stack([np.cos(a), np.zeros_like(a), np.sin(a)], 1)
    for height in (2.6, 3.4):
        for i, p in enumerate(ring * 0.8 + [0.0, height, 0.0]):
            game.modeling.add3d(p, i * 0.02)
        game.modeling.finish()
    flat = game.modeling.crown_tool.state().lobes[-1]
    t = np.linspace(-0.8, 0.8, 30)
    for i, p in enumerate(np.stack([t, 3.4 + 0.7 * (1 - (t / 0.8) ** 2), 0 * t], 1)):  # an arch over the top
        game.modeling.add3d(p, i * 0.02)
    game.modeling.finish()
    domed = game.modeling.crown_tool.state().lobes[-1]
    assert len(game.modeling.crown_tool.state().arches) == 1
    assert domed.vertices[:, 1].max() == pytest.approx(4.1, abs=0.05) and flat.vertices[:, 1].max() < 3.5
    assert domed.contains(np.array([[0.0, 3.8, 0.0]]))[0] and not flat.contains(np.array([[0.0, 3.8, 0.0]]))[0]


def test_two_outlines_make_a_supertoroid_region_and_edits_stay_inside_it(game):
    from arbor.engine.modeling.regions import Supertoroid

    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 5 * i, y0 - 9 * i) for i in range(45)])  # a long branch up to the right
    press_menu(game, "symbols")
    draw(game, [(x0 - 50, y0 - 60 - 12 * i) for i in range(20)])  # left outline
    assert game.modeling.region_tool.region is None and "outline" in game.hud_info().message
    draw(game, [(x0 + 70 + (i % 2), y0 - 60 - 12 * i) for i in range(20)])  # right outline
    region = game.modeling.region_tool.region
    assert isinstance(region, Supertoroid) and "two outlines" in game.hud_info().message
    before = game.world.tree.lstring
    positions = game.modeling.region_tool.positions(before)
    inside = region.contains(positions)
    eligible = np.isin(before.sym, [ord("I"), ord("F")]) & inside
    assert 0 < eligible.sum() < np.isin(before.sym, [ord("I"), ord("F")]).sum()  # some modules are outside
    touch(game, DOWN, 0, x0 + 10, y0 - 180)  # a tap inside the region
    touch(game, UP, 0, x0 + 10, y0 - 180)
    after = game.world.tree.lstring
    assert after.count("L") - before.count("L") == eligible.sum()  # one leaf per internode inside, none outside
    touch(game, DOWN, 0, x0 + 400, y0 - 180)  # a tap well outside: the menu, no edit
    touch(game, UP, 0, x0 + 400, y0 - 180)
    assert game.menu.visible and game.world.tree.lstring is after


def test_grow_edit_wakes_buds_in_the_region_and_starts_an_axis_in_an_empty_one(game):
    press_menu(game, "symbols")
    for _ in range(5):
        press_menu(game, "edit")
    assert game.modeling.edit == "grow" and game.menu.widget("edit").label == "Grow"
    x0, y0 = base_pixel(game)
    bx, by = game.hud.project(game.camera(), (0.0, 2.0, 0.0))  # where the sapling has buds
    touch(game, DOWN, 0, bx, by + 40)
    game.clock_box[0] += 0.5
    touch(game, MOVE, 0, bx, by)  # the sphere over the buds
    touch(game, UP, 0, bx, by)
    before = game.world.tree.lstring
    inside = game.modeling.region_tool.region.contains(game.modeling.region_tool.positions(before))
    buds = int(((before.sym == ord("D")) & inside).sum())
    assert buds > 0
    touch(game, DOWN, 0, bx, by)
    touch(game, UP, 0, bx, by)
    after = game.world.tree.lstring
    assert after.count("D") == before.count("D") - buds and after.count("A") == before.count("A") + buds
    now, p = game.world.clocks().length_time, game.world.tree.system.constants["P"]
    apices = [after.module(i)[1] for i in np.flatnonzero(after.sym == ord("A"))]
    due = sum(1 for params in apices if len(params) == 6 and params[0] == pytest.approx(p))  # progress: one P
    assert due >= buds and now > 0  # due at once
    touch(game, DOWN, 0, x0 + 300, y0 - 300)  # drag the sphere into the empty sky
    game.clock_box[0] += 0.5
    touch(game, MOVE, 0, x0 + 320, y0 - 320)
    touch(game, UP, 0, x0 + 320, y0 - 320)
    touch(game, DOWN, 0, x0 + 320, y0 - 320)
    touch(game, UP, 0, x0 + 320, y0 - 320)
    seeded = game.world.tree.lstring
    assert "new axis" in game.hud_info().message and seeded.count("A") == after.count("A") + 1


def test_a_region_is_moved_by_dragging_inside_it_and_resized_from_its_rim(game):
    from arbor.engine.modeling.regions import Sphere

    press_menu(game, "symbols")
    x0, y0 = base_pixel(game)
    draw(game, [(x0, y0 - 100), (x0, y0 - 160), (x0, y0 - 200)])  # a short drag places a sphere
    first = game.modeling.region_tool.region
    assert isinstance(first, Sphere)
    centre = game.hud.project(game.camera(), first.center)
    draw(game, [centre, (centre[0] + 30, centre[1]), (centre[0] + 80, centre[1] - 20)])  # from inside: move
    moved = game.modeling.region_tool.region
    assert moved.radius == pytest.approx(first.radius) and np.linalg.norm(np.subtract(moved.center, first.center)) > 0.3
    centre = game.hud.project(game.camera(), moved.center)
    right = game.camera().view()[0, :3]  # the screen's right, in the world
    ring = game.hud.project(game.camera(), np.add(moved.center, moved.radius * 0.95 * right))
    rim = (centre[0] + np.hypot(ring[0] - centre[0], ring[1] - centre[1]) * 0.9, centre[1])
    draw(game, [rim, (rim[0] + 30, rim[1]), (rim[0] + 70, rim[1])])  # from the rim outwards: bigger
    bigger = game.modeling.region_tool.region
    assert bigger.radius > 1.3 * moved.radius and bigger.center == pytest.approx(moved.center)


def test_a_pinch_over_the_region_resizes_it_and_one_elsewhere_zooms(game):
    press_menu(game, "symbols")
    x0, y0 = base_pixel(game)
    draw(game, [(x0, y0 - 100), (x0, y0 - 160), (x0, y0 - 200)])  # a short drag places a sphere
    first = game.modeling.region_tool.region
    cx, cy = game.hud.project(game.camera(), first.center)
    distance = game.control.distance

    def pinch(x, y, start, end):
        touch(game, DOWN, 3, x - start, y)
        touch(game, DOWN, 4, x + start, y)
        for k in range(1, 11):
            game.clock_box[0] += 0.02
            gap = start + (end - start) * k / 10
            touch(game, MOVE, 3, x - gap, y)
            touch(game, MOVE, 4, x + gap, y)
        touch(game, UP, 3, x - end, y)
        touch(game, UP, 4, x + end, y)

    pinch(cx, cy, 10, 30)  # fingers apart over the sphere: a bigger sphere, the same view
    bigger = game.modeling.region_tool.region
    assert bigger.radius > 1.8 * first.radius and bigger.center == pytest.approx(first.center)
    assert game.control.distance == pytest.approx(distance)
    pinch(150, 650, 10, 30)  # far from it: the camera zooms in, the region stays
    assert game.control.distance < 0.8 * distance and game.modeling.region_tool.region == bigger


def test_a_tool_pressed_in_the_menu_closes_it_so_the_first_drag_draws(game):
    game.tap(100, 100)
    center = game.menu.reveal("crown").rect.center
    touch(game, DOWN, 8, *center)
    touch(game, UP, 8, *center)
    assert game.modeling.active and game.modeling.crown and not game.menu.visible
    before = game.world.tree.lstring
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 150 * np.cos(t), y0 - 320 + 110 * np.sin(t)) for t in a])
    assert len(game.world.tree.lstring) > len(before) + 200  # the first outline grew a crown


def test_crown_refuses_an_open_line_and_an_outline_smaller_than_a_leaf(game):
    press_menu(game, "crown")
    before = game.world.tree.lstring
    x0, y0 = base_pixel(game)
    draw(game, [(x0 - 150 + 10 * i, y0 - 300 - 3 * i) for i in range(30)])  # an open line across the crown
    assert game.world.tree.lstring is before and not game.modeling.crown_tool.state().lobes
    assert game.hud_info().message.startswith("Close the outline")
    a = np.linspace(0, 2 * np.pi, 24)
    draw(game, [(x0 + 8 * np.cos(t), y0 - 300 + 6 * np.sin(t)) for t in a])  # 16 x 12 px: a tenth of a leaf
    assert game.world.tree.lstring is before and "smaller than a leaf" in game.hud_info().message


def test_a_stroke_under_way_that_a_second_finger_turns_into_a_gesture_is_said_to_be_let_go(game):
    press_menu(game, "modeler")
    before = game.world.tree.lstring.to_text()
    x0, y0 = base_pixel(game)
    touch(game, DOWN, 0, x0, y0)
    for i in range(1, 16):
        game.clock_box[0] += 0.02
        touch(game, MOVE, 0, x0 + 4 * i, y0 - 9 * i)
    touch(game, DOWN, 1, 900, 400)  # a second finger: the view moves, the stroke is dropped
    touch(game, UP, 1, 900, 400)
    touch(game, UP, 0, x0 + 60, y0 - 135)
    assert game.world.tree.lstring.to_text() == before
    assert "that stroke was let go" in game.hud_info().message


def test_a_drawn_branch_running_past_the_crown_sprouts_no_comb_of_twigs_toward_it(game):
    """A long branch drawn out to the side under a crown outline: the crown grows from the wood near
    its lobe, not from the far part of that branch (each of its nodes grew a bare twig toward the lobe)."""
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 25 * i, y0 - 20 - 8 * i) for i in range(25)])
    drawn = game.world.tree.lstring
    press_menu(game, "crown")
    a = np.linspace(0, 2 * np.pi * 1.05, 60)
    draw(game, [(x0 + 150 * np.cos(t), y0 - 330 + 110 * np.sin(t)) for t in a])
    before = game.modeling.segments(drawn)
    segs = game.modeling.segments(game.world.tree.lstring)
    lobe = game.modeling.crown_tool.state().lobes[0]
    new = np.arange(len(before), len(segs))
    roots = new[segs.parent[new] < len(before)]  # where the crown's branches leave the tree
    far = np.linalg.norm(segs.start[roots][:, None] - lobe.vertices[None], axis=2).min(axis=1)
    size = float(np.ptp(lobe.vertices, axis=0).max())
    print(f"{len(roots)} crown branches leave the tree, the farthest {far.max():.2f} from the lobe (size {size:.2f})")
    assert len(roots) and far.max() <= 0.35 * size


def test_a_crown_grown_on_a_young_sapling_has_branches_as_thick_as_the_pipes_they_carry(game):
    """The sapling's thin stem does not cap the crown's branches (they were invisible twigs under
    floating leaves): a branch leaving the grown stem is as thick as the pipe model makes its load, and
    the stem thickens to carry them."""
    press_menu(game, "crown")
    before = game.modeling.segments(game.world.tree.lstring)
    stem = float(before.radius.max())
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi * 1.05, 60)
    draw(game, [(x0 + 180 * np.cos(t), y0 - 300 + 130 * np.sin(t)) for t in a])
    ls = game.world.tree.lstring
    segs = game.modeling.segments(ls)
    crown = (ls.sym[segs.module] == ord("F")) & (ls.nparams[segs.module] == 11)
    roots = np.flatnonzero(crown & (segs.parent >= 0) & ~crown[np.maximum(segs.parent, 0)])  # leaving the stem
    widest = float(segs.radius[roots].max())
    print(f"sapling stem radius {stem:.4f}; widest crown branch {widest:.4f}; trunk now {segs.radius[0]:.4f}")
    assert widest > 2 * stem and segs.radius[0] >= 0.9 * widest
