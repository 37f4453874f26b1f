"""The modeler's tool state through the real game, headless (issue 31): a tool bar in the modeler only, the
tool in use lit on it, reachable by touch and mouse; Draw always starts the draw tool; Done and a new
sapling leave no overlay behind; the hint line says what a drag does; the view frames the tree and its
lobes; a tracker's ring group drawn away from a lobe starts a new lobe."""

import numpy as np
import pygame
import pytest

from arbor.engine.life.world.actions import Action
from arbor.game.input.events import DOWN, MOVE, UP, InputEvent
from arbor.game.render.ui import BAR_TOOLS, LIT
from arbor.game.strings import text

SIZE = (1280, 720)
SCENE = (slice(215, 630), slice(0, 1090))  # rows, columns of the overlay where only the tools draw (no HUD)


@pytest.fixture
def game(modeler_game):
    return modeler_game(seed=3)


def touch(game, kind, fid, x, y):
    game.handle_input(InputEvent(kind, game.clock_box[0], "touch:1", fid, x, y))


def finger(game, kind, x, y, fid=7):
    """A real SDL finger event (positions 0..1 of the window), through the game's translator."""
    kinds = {DOWN: pygame.FINGERDOWN, MOVE: pygame.FINGERMOTION, UP: pygame.FINGERUP}
    game.handle_event(pygame.event.Event(kinds[kind], touch_id=1, finger_id=fid, x=x / SIZE[0], y=y / SIZE[1],
                                         dx=0.0, dy=0.0, pressure=1.0))


def click(game, x, y):
    """A real mouse click."""
    game.handle_event(pygame.event.Event(pygame.MOUSEBUTTONDOWN, pos=(int(x), int(y)), button=1))
    game.handle_event(pygame.event.Event(pygame.MOUSEBUTTONUP, pos=(int(x), int(y)), button=1))


def press_menu(game, name):
    game.tap(100, 100)
    center = game.menu.reveal(name).rect.center
    touch(game, DOWN, 8, *center)
    touch(game, UP, 8, *center)
    if game.menu.visible:
        game.tap(1000, 700)  # close the menu again
    assert not game.menu.visible


def press_bar(game, name):
    """A finger on the tool bar's button ``name`` (where the player sees it)."""
    x, y = game.modeling.bar.widgets[name].rect.center
    finger(game, DOWN, x, y)
    finger(game, UP, x, y)


def draw(game, points, fid=0, dt=0.02):
    touch(game, DOWN, fid, *points[0])
    for p in points[1:]:
        game.clock_box[0] += dt
        touch(game, MOVE, fid, *p)
    game.clock_box[0] += dt
    touch(game, UP, fid, *points[-1])


def overlay(game):
    """The HUD layer as the player sees it (RGBA, top row first)."""
    return np.frombuffer(game.hud.overlay_pixels(game.camera()), np.uint8).reshape(SIZE[1], SIZE[0], 4)[::-1]


def frame(game):
    game.draw(game.fbo)
    return np.frombuffer(game.fbo.read(components=3), np.uint8).reshape(SIZE[1], SIZE[0], 3)[::-1].astype(int)


def lit(pixels, rect):
    """Share of a button's pixels in the lit (active tool) yellow."""
    box = pixels[rect.top:rect.bottom, rect.left:rect.right, :3].astype(int)
    return float((np.abs(box - LIT).sum(axis=2) < 40).mean())


def base_pixel(game):
    return game.hud.project(game.camera(), (0.0, 0.5, 0.0))


def drawn_pieces(ls):
    return int(((ls.sym == ord("F")) & (ls.nparams == 11)).sum())


def test_the_tool_bar_shows_in_the_modeler_only_and_lights_the_tool_in_use(game):
    bar = game.modeling.bar
    column = overlay(game)[:, bar.rect.left:]
    assert not bar.visible and (column[..., 3] > 0).sum() == 0  # the garden has no tool bar
    press_menu(game, "modeler")
    shown = [w.name for w in bar.shown()]
    assert shown == [*BAR_TOOLS, "undo", "redo", "modeler"] and bar.widgets["modeler"].label == "Done"
    assert all(w.rect.height >= 48 and w.rect.width >= 48 for w in bar.shown())  # touch-sized
    assert all(w.rect.right <= SIZE[0] and w.rect.bottom <= SIZE[1] - 100 for w in bar.shown())  # (above the toast)
    tree = game.world.tree.lstring
    for name in (*BAR_TOOLS[1:], "draw", "crown", "crown"):  # each tool, and one pressed twice stays in use
        press_bar(game, name)
        pixels = overlay(game)
        assert game.modeling.current_tool == name and not game.menu.visible
        assert lit(pixels, bar.widgets[name].rect) > 0.5, name  # the button of the tool in use is lit...
        assert all(lit(pixels, bar.widgets[other].rect) < 0.05 for other in BAR_TOOLS if other != name)  # ...alone
    assert game.world.tree.lstring is tree  # pressing the bar never drew a stroke
    click(game, *bar.widgets["prune"].rect.center)  # the mouse reaches it too
    assert game.modeling.pruning and lit(overlay(game), bar.widgets["prune"].rect) > 0.5
    press_bar(game, "shape")  # the option of the tool in use sits under the tools
    assert bar.widgets["edit"] in bar.shown() and bar.widgets["edit"].label == "Lobe: move"
    press_bar(game, "edit")
    assert game.modeling.crown_tool.op == "scale" and bar.widgets["edit"].label == "Lobe: scale"
    game.tap(500, 300)  # the tools page of the menu lights the tool in use as well
    assert game.menu.lit == {"shape"} and lit(overlay(game), game.menu.widget("shape").rect) > 0.5
    game.tap(500, 300)
    press_bar(game, "modeler")  # Done
    assert not game.modeling.active and not bar.visible
    assert (overlay(game)[:, bar.rect.left:, 3] > 0).sum() == 0


def test_draw_always_starts_the_draw_tool(game):
    press_menu(game, "symbols")  # the modeler, with the Symbols tool
    press_bar(game, "modeler")  # Done
    press_menu(game, "modeler")  # Draw
    assert game.modeling.active and game.modeling.current_tool == "draw"
    assert lit(overlay(game), game.modeling.bar.widgets["draw"].rect) > 0.5
    x0, y0 = base_pixel(game)
    before = drawn_pieces(game.world.tree.lstring)
    draw(game, [(x0 + 2 * np.sin(i / 5), y0 - 9 * i) for i in range(30)])  # a trunk stroke...
    assert drawn_pieces(game.world.tree.lstring) > before + 5  # ...draws a trunk, not a Symbols contour
    assert game.modeling.region_tool.contours == [] and game.modeling.region_tool.region is None
    press_bar(game, "crown")
    press_bar(game, "draw")  # and Draw on the bar is the draw tool, in the modeler too
    assert game.modeling.current_tool == "draw" and game.modeling.active
    drawn = drawn_pieces(game.world.tree.lstring)
    draw(game, [(x0 + 6 * i, y0 - 150 - 6 * i) for i in range(30)])
    assert drawn_pieces(game.world.tree.lstring) > drawn + 5 and len(game.modeling.crown_tool.state().lobes) == 0


def crown_and_region(game):
    """A lobe outline (rings drawn over the tree) and a Symbols region, both shown."""
    x0, y0 = base_pixel(game)
    press_bar(game, "crown")
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 110 * np.cos(t), y0 - 300 + 90 * np.sin(t)) for t in a])
    assert len(game.modeling.crown_tool.state().lobes) == 1
    rings = (overlay(game)[SCENE][..., 3] > 0).sum()
    press_bar(game, "symbols")
    draw(game, [(x0, y0 - 100), (x0, y0 - 160), (x0, y0 - 200)])  # a sphere over the trunk
    circle = (overlay(game)[SCENE][..., 3] > 0).sum()
    assert rings > 800 and circle > 800 and game.modeling.region_tool.region is not None


@pytest.mark.parametrize("tool", ["crown", "symbols", "draw"])
def test_done_leaves_no_modeler_overlay(game, tool):
    press_menu(game, "modeler")
    x0, y0 = base_pixel(game)
    press_bar(game, tool)
    if tool == "crown":  # the lobe's rings, drawn over the crown
        a = np.linspace(0, 2 * np.pi, 48)
        draw(game, [(x0 + 110 * np.cos(t), y0 - 300 + 90 * np.sin(t)) for t in a])
        assert len(game.modeling.crown_tool.state().lobes) == 1
    elif tool == "symbols":  # a region's circle and the symbols inside it
        draw(game, [(x0, y0 - 100), (x0, y0 - 160), (x0, y0 - 200)])
        assert game.modeling.region_tool.region is not None
    else:  # a stroke being drawn: the marker where it will join the tree
        touch(game, DOWN, 0, x0, y0 - 20)
        for i in range(1, 12):
            game.clock_box[0] += 0.06
            touch(game, MOVE, 0, x0 + 8 * i, y0 - 20 - 8 * i)
        assert game.modeling.joint is not None
    assert (overlay(game)[SCENE][..., 3] > 0).sum() > 150  # (the joint marker: 200 px)
    click(game, *game.modeling.bar.widgets["modeler"].rect.center)  # Done, with the mouse
    if tool == "draw":
        touch(game, UP, 0, x0 + 88, y0 - 108)
    assert not game.modeling.active
    pixels = overlay(game)
    assert (pixels[SCENE][..., 3] > 0).sum() == 0  # no lobe rings, region circle, symbols or joint marker
    assert (pixels[:, game.modeling.bar.rect.left:, 3] > 0).sum() == 0  # no tool bar
    press_menu(game, "modeler")  # and coming back starts clean: Draw, no lobes, no region
    assert game.modeling.current_tool == "draw" and (overlay(game)[SCENE][..., 3] > 0).sum() == 0
    press_bar(game, "symbols")
    assert game.modeling.region_tool.region is None and (overlay(game)[SCENE][..., 3] > 0).sum() == 0


def sapling_pixels(game):
    """How tall the cared-for tree is drawn (pixels from its foot to its top)."""
    segs = game.modeling.segments(game.world.tree.lstring)
    return float(np.ptp(np.array(game.hud.project_many(game.camera(), np.r_[segs.start, segs.end]))[:, 1]))


def test_a_new_sapling_in_the_modeler_leaves_no_overlay_and_is_what_strokes_draw_on(game):
    press_menu(game, "modeler")
    first = sapling_pixels(game)
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 2 * np.sin(i / 5), y0 - 9 * i) for i in range(30)])
    crown_and_region(game)
    crowned = len(game.world.tree.lstring)
    game.draw(game.fbo)  # (a frame of the crowned tree)
    game.act(Action.REPLANT, 1.0)
    game.act(Action.REPLANT, 1.0)  # (the second press confirms)
    sapling = game.world.tree.lstring
    assert len(sapling) < crowned / 4 and game.modeling.active
    assert game.modeling.current_tool == "draw" and lit(overlay(game), game.modeling.bar.widgets["draw"].rect) > 0.5
    assert (overlay(game)[SCENE][..., 3] > 0).sum() == 0  # the old tree's lobe rings and region are gone
    assert sapling_pixels(game) > 0.8 * first  # framed as the first sapling was, not as the crowned tree
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 6 * i, y0 - 60 - 6 * i) for i in range(25)])
    grown = game.world.tree.lstring
    assert len(sapling) < len(grown) < len(sapling) + crowned / 4  # a stroke on the sapling, not the old tree back
    press_bar(game, "undo")
    assert game.world.tree.lstring is sapling
    press_bar(game, "undo")
    assert game.world.tree.lstring is sapling  # undo does not reach back into the tree that was replaced


def test_the_hint_line_in_the_modeler_says_what_a_drag_does_with_the_tool(game):
    garden_hints = {text(f"hints.{what}") for what in ("water", "sun", "turn")}
    game.world.sim.state.water_meter = game.world.sim.state.sun_meter = 0.9  # (only the turn hint applies)
    assert game.hud_info().hint == text("hints.turn")
    press_menu(game, "modeler")
    seen = {}
    for name in BAR_TOOLS:
        press_bar(game, name)
        info = game.hud_info()
        assert info.hint not in garden_hints and info.hint.startswith(text(f"menu.{name}") + ":"), info.hint
        assert info.reminder == ""  # (no "tap a fruit" or "tap a tree" while taps open the tools)
        assert info.status == info.season == ""  # (nor the paused garden's status lines across the drawing)
        seen[name] = overlay(game)[20:100, 300:980, 3].copy()  # the hint box, as drawn
    assert len({h.tobytes() for h in seen.values()}) == len(BAR_TOOLS)  # each tool's own line on the screen
    press_bar(game, "shape")
    assert "to move it" in game.hud_info().hint and "{" not in game.hud_info().hint
    press_bar(game, "modeler")
    assert game.hud_info().hint == text("hints.turn")  # back in the garden, the garden's hints


def in_view(game, points, margin=4):
    """Whether every point is drawn on the screen, clear of the tool bar."""
    pixels = game.hud.project_many(game.camera(), points)
    pixels = np.array(pixels)
    right = game.modeling.bar.rect.left if game.modeling.bar.visible else SIZE[0]
    return len(pixels) == len(points) and bool(
        (pixels[:, 0] >= margin).all() and (pixels[:, 0] <= right - margin).all()
        and (pixels[:, 1] >= margin).all() and (pixels[:, 1] <= SIZE[1] - margin).all())


def test_the_view_frames_the_tree_on_entering_and_its_lobes_when_f_is_pressed(game):
    game.control.distance = 0.3  # zoomed in on the garden (the tree's top is out of view)
    tree = game.modeling.segments(game.world.tree.lstring)
    ends = np.r_[tree.start, tree.end]
    press_menu(game, "modeler")
    assert in_view(game, ends)
    press_bar(game, "crown")
    # a tracker draws three lobes, one high above the tree and two wide to its sides
    a = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    ring = np.stack([np.cos(a), np.zeros_like(a), np.sin(a)], 1)
    for centre, radius in (((-3.0, 3.5, 0.0), 1.4), ((3.2, 3.5, 0.5), 1.4), ((0.0, 7.0, 0.0), 1.6)):
        for height in (-0.7, 0.7):
            path = ring * radius * (1 - 0.2 * abs(height)) + np.add(centre, (0.0, height, 0.0))
            for k, p in enumerate(path):
                kind = DOWN if k == 0 else (UP if k == len(path) - 1 else MOVE)
                game.handle_input(InputEvent(kind, 0.05 * k, "hid:SpaceMouse", 0, *p, dims=3))
    lobes = game.modeling.crown_tool.state().lobes
    assert len(lobes) == 3 and "3 lobes" in game.hud_info().message
    game.handle_event(pygame.event.Event(pygame.KEYDOWN, key=pygame.K_f, mod=0, scancode=0, unicode="f"))  # frame
    crown = game.modeling.segments(game.world.tree.lstring)
    assert in_view(game, np.concatenate([lobe.vertices for lobe in lobes]))  # every lobe, whole
    assert in_view(game, np.r_[crown.start, crown.end])  # and the grown crown
    game.control.turn(90.0)
    assert in_view(game, np.concatenate([lobe.vertices for lobe in lobes]))  # from the side as well
    pixels = frame(game)
    sky = pixels[:6, :1000]
    assert (np.abs(np.diff(sky, axis=1)).sum(axis=2) < 60).mean() > 0.95  # the crown stays below the top edge
    press_bar(game, "modeler")
    assert game.control.distance == pytest.approx(0.3)  # the garden's zoom comes back after the modeler


def tracker_ring(game, centre, radius, t0=0.0):
    a = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    path = np.stack([np.cos(a), np.zeros_like(a), np.sin(a)], 1) * radius + centre
    for k, p in enumerate(path):
        kind = DOWN if k == 0 else (UP if k == len(path) - 1 else MOVE)
        game.handle_input(InputEvent(kind, t0 + 0.05 * k, "hid:SpaceMouse", 0, *p, dims=3))


def test_a_tracker_ring_group_drawn_away_from_a_lobe_starts_a_new_lobe(game):
    press_menu(game, "crown")
    tracker_ring(game, (0.0, 2.6, 0.0), 0.9)
    tracker_ring(game, (0.1, 3.5, 0.0), 0.8)
    first = game.modeling.crown_tool.state().lobes
    assert len(first) == 1
    tracker_ring(game, (0.0, 4.2, 0.1), 0.6)  # a ring over the lobe goes on with it
    grown = game.modeling.crown_tool.state().lobes
    assert len(grown) == 1 and grown[0].rings == 3
    tracker_ring(game, (3.0, 2.8, 0.0), 0.8)  # a ring beside the lobe: a new lobe starts
    assert "new lobe" in game.hud_info().message
    assert game.modeling.crown_tool.state().lobes == grown
    tracker_ring(game, (3.0, 3.7, 0.0), 0.7)
    lobes = game.modeling.crown_tool.state().lobes
    assert len(lobes) == 2 and lobes[0] is grown[0] and "2 lobes" in game.hud_info().message
    assert lobes[1].rings == 2 and np.allclose(lobes[1].vertices.mean(axis=0)[[0, 2]], (3.0, 0.0), atol=0.15)
    assert lobes[1].contains(np.array([[3.0, 3.2, 0.0]]))[0] and not lobes[1].contains(np.array([[0.0, 3.2, 0.0]]))[0]
    assert not lobes[0].contains(np.array([[3.0, 3.2, 0.0], [1.6, 3.2, 0.0]])).any()  # nothing stitched between


def test_a_tree_planted_while_modeling_is_the_one_strokes_draw_on(game):
    press_menu(game, "crown")
    x0, y0 = base_pixel(game)
    a = np.linspace(0, 2 * np.pi, 48)
    draw(game, [(x0 + 110 * np.cos(t), y0 - 300 + 90 * np.sin(t)) for t in a])
    first_world, crowned = game.world, game.world.tree.lstring
    game.act(Action.PLANT, 1.0)  # (Garden -> Plant a tree, from the menu the modeler's tap opens)
    assert game.world is not first_world and game.modeling.active
    game.draw(game.fbo)
    assert (overlay(game)[SCENE][..., 3] > 0).sum() == 0  # the first tree's lobe rings are not drawn on this one
    sapling = game.world.tree.lstring
    press_bar(game, "draw")
    x0, y0 = base_pixel(game)
    draw(game, [(x0 + 6 * i, y0 - 60 - 6 * i) for i in range(25)])
    assert len(sapling) < len(game.world.tree.lstring) < len(sapling) + len(crowned) / 4
    assert first_world.tree.lstring is crowned  # the first tree keeps its crown
