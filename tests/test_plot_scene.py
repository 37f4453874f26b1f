"""Trees sharing a plot (the competition lesson) drawn in one scene, at their spacing, lit from the front,
each tree's name and state beneath it: in the lab window and in `arbor lab --out`'s scene.png."""

from __future__ import annotations

import numpy as np
import pytest

from tests.conftest import ROOT

LESSON = ROOT / "assets" / "experiments" / "lesson_competition.toml"


@pytest.fixture()
def competition(tmp_path):
    from arbor.game.commands.lab import new_lab

    text = LESSON.read_text(encoding="utf-8").replace("duration = 3142", "duration = 400")
    path = tmp_path / "competition.toml"
    path.write_text(text, encoding="utf-8")
    lab = new_lab(path)
    lab.run()
    return lab


def _read(ctx, fbo, size):
    return np.frombuffer(fbo.read(components=3, viewport=(0, 0, *size)), np.uint8).reshape(size[1], size[0], 3)[::-1]


def test_the_lab_window_draws_a_shared_plot_in_one_scene_with_names_beneath(gl_ctx, competition, tmp_path):
    import pygame

    from arbor.game.input.events import DOWN, KEY_DOWN, InputEvent
    from arbor.game.screens.lab import LabScreen

    size = (1280, 720)
    screen = LabScreen(gl_ctx, size, competition, results=tmp_path / "results")
    assert screen.plot is not None and screen.renderers == []  # one scene, not three panes
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(size)],
                             depth_attachment=gl_ctx.depth_renderbuffer(size))
    screen.draw(fbo)
    scene_h = int(size[1] * 0.55)
    bases = screen.plot.bases(competition.worlds, (size[0], scene_h))
    x = bases[:, 0]
    assert 0 < x[0] < x[1] < x[2] < size[0] and np.all((bases[:, 1] > 0) & (bases[:, 1] < scene_h))
    assert abs((x[1] - x[0]) - (x[2] - x[1])) < 0.2 * (x[1] - x[0])  # equal spacing: near-equal gaps (perspective)
    img = _read(gl_ctx, fbo, size).astype(int)
    for bx, by in bases:  # under each tree: its name's coloured box and its state's dark one
        below = img[int(by) + 12:int(by) + 90, int(bx) - 30:int(bx) + 30]
        assert (below.sum(axis=2) < 150).mean() > 0.2 or (np.ptp(below, axis=2) > 80).mean() > 0.2
    rect = screen.buttons["Light"]
    screen.handle(InputEvent(DOWN, 0.0, "touch:1", 0, *rect.center))
    assert not screen.front_lit and screen.message == "Lit by the simulation's sun"
    screen.handle(InputEvent(KEY_DOWN, 0.0, "keyboard", key=pygame.K_l))
    assert screen.front_lit


def test_the_plot_is_lit_from_the_front_whatever_the_simulations_sun_does(gl_ctx, competition):
    import math

    from arbor.engine.geometry.mesh import Mesh, TreeMesh
    from arbor.game.render.plot_scene import PlotScene, front_light

    size = (960, 540)
    scene = PlotScene(gl_ctx)
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(size)],
                             depth_attachment=gl_ctx.depth_renderbuffer(size))
    sims = [w.sim for w in competition.worlds]
    pictures = {}
    for name, angle, own in (("noon", math.pi / 2, False), ("midnight", -math.pi / 2, False),
                             ("midnight, the simulation's sun", -math.pi / 2, True)):
        for sim in sims:
            sim.state.sun_angle = angle
        scene.render(fbo, competition.worlds, size, sun=sims[0].sun_direction() if own else None)
        pictures[name] = _read(gl_ctx, fbo, size).astype(float)

    def depth():
        return np.frombuffer(fbo.read(components=1, attachment=-1, dtype="f4", viewport=(0, 0, *size)), np.float32)

    trees = depth()
    empty = Mesh(np.zeros((0, 3), np.float32), np.zeros((0, 3), np.float32), np.zeros((0, 2), np.float32),
                 np.zeros((0, 3), np.uint32), np.zeros(0, np.int32))
    scene.renderer.set_tree(TreeMesh(empty, empty, empty))
    scene.renderer.render(fbo, scene.camera, front_light(), size)  # the same camera, no trees: the ground's depth
    mask = (trees < depth() - 1e-5).reshape(size[1], size[0])[::-1]  # the trees' own pixels
    assert mask.mean() > 0.003
    assert np.array_equal(pictures["noon"], pictures["midnight"])  # the default light does not follow the sim
    lit, dark = pictures["midnight"][mask].mean(), pictures["midnight, the simulation's sun"][mask].mean()
    assert lit > 2 * dark, (lit, dark)  # (the panes of old: a tree at night under its own sun, dark)
    assert front_light(scene.camera.yaw) @ (scene.camera.eye - scene.camera.target) > 0  # from the viewer's side
    scene.release()


def test_arbor_lab_out_draws_the_plot_in_one_scene(tmp_path):
    import matplotlib.image as mpimg

    from arbor.game.commands.lab import run_headless

    text = LESSON.read_text(encoding="utf-8").replace("duration = 3142", "duration = 300")
    path = tmp_path / "competition.toml"
    path.write_text(text, encoding="utf-8")
    files = run_headless(path, tmp_path / "out")
    assert tmp_path / "out" / "scene.png" in files
    img = mpimg.imread(tmp_path / "out" / "scene.png")[..., :3]
    assert img.shape[:2] == (900, 1600)  # one picture of the row, not three tiles side by side
    sky = img[:200].reshape(-1, 3)
    assert (sky[:, 2] > sky[:, 0]).mean() > 0.95  # one sky over the whole width: no tile borders


def test_labels_of_trees_closer_than_a_label_spread_apart_in_the_trees_order():
    from arbor.game.screens.lab import _fitted, _spread

    xs = np.array([620.0, 500.0, 560.0])  # (the lab's order need not be the row's)
    spread = _spread(xs, 130.0)
    assert list(np.argsort(spread)) == list(np.argsort(xs)) and np.min(np.diff(np.sort(spread))) >= 130.0 - 1e-9
    assert np.mean(spread) == np.mean(xs)
    assert np.array_equal(_spread(np.array([100.0, 400.0]), 130.0), [100.0, 400.0])  # room enough: under each
    state = "alive, wilt 0.00, 1.19 m"
    assert _fitted(state, lambda t: len(t) < 30) == [state]
    assert _fitted(state, lambda t: len(t) < 20) == ["alive, wilt 0.00", "1.19 m"]
    assert _fitted(state, lambda t: len(t) < 12) == ["alive", "wilt 0.00", "1.19 m"]


def test_the_lab_title_fits_left_of_the_buttons():
    import pygame

    from arbor.game.screens.lab import _fitting_text

    pygame.font.init()
    big, small = pygame.font.Font(None, 40), pygame.font.Font(None, 24)
    title = "Three in a row - day 25.0 (52.4 of 52 min)"
    assert _fitting_text([big, small], title, 2000).get_size() == big.render(title, True, "white").get_size()  # room
    room = small.size(title)[0] + 30
    assert _fitting_text([big, small], title, room).get_width() + 24 <= room  # the small one
    assert _fitting_text([big, small], title, 120).get_width() + 24 <= 120  # cut short, never under the buttons
