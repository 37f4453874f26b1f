"""Headless rendering (EGL, Mesa llvmpipe): look at pixels the way a player would."""

import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

from arbor.engine.geometry.mesh import Mesh, TreeMesh
from arbor.engine.geometry.tree import build_geometry
from arbor.engine.lsystem.derive import derive
from arbor.engine.lsystem.lsys import load_lsystem
from arbor.game.cli import main
from arbor.game.render.renderer import render_image

SIZE = (480, 320)


@pytest.fixture(scope="module")
def ctx(gl_ctx):
    return gl_ctx


@pytest.fixture(scope="module")
def pictures(lsys_dir):
    system = load_lsystem(lsys_dir / "abop_2_8_tree.lsys")
    tree = build_geometry(derive(system, 5), system).mesh
    empty = TreeMesh(Mesh.empty(), Mesh.empty(), Mesh.empty())
    with_tree = render_image(tree, SIZE)  # (a context of its own: no GL state left by earlier tests)
    # same camera and light, tree not drawn: isolates the tree's pixels
    without = render_image(tree_without_drawing(tree), SIZE)
    blank = render_image(empty, SIZE)
    return with_tree, without, blank


def tree_without_drawing(tree: TreeMesh) -> TreeMesh:
    """The same bounds (so the same framing) but triangles of zero area."""
    def collapse(m: Mesh) -> Mesh:
        idx = np.zeros_like(m.indices)
        return Mesh(m.positions, m.normals, m.uvs, idx, m.face_module)

    return TreeMesh(collapse(tree.wood), collapse(tree.leaves), collapse(tree.blossoms))


def tree_mask(with_tree, without):
    return np.abs(with_tree.astype(int) - without.astype(int)).sum(axis=2) > 40


def test_scene_is_not_blank(pictures):
    with_tree, _, blank = pictures
    assert with_tree.shape == (SIZE[1], SIZE[0], 3)
    assert 60 < with_tree.mean() < 230 and with_tree.std() > 20
    sky = blank[5, SIZE[0] // 2]
    assert sky[2] > sky[0]  # blue sky on top
    grass = blank[-5, SIZE[0] // 2]
    assert grass[1] > grass[0] and grass[1] > grass[2]  # green ground below


def test_tree_is_present_and_framed(pictures):
    with_tree, without, _ = pictures
    mask = tree_mask(with_tree, without)
    assert mask.mean() > 0.03  # tree and its shadow cover a real part of the picture
    ys, xs = np.nonzero(mask)
    h, w = mask.shape
    assert ys.min() > 2 and xs.min() > 2 and xs.max() < w - 3  # nothing cut off at the edges
    assert (ys.max() - ys.min()) > 0.5 * h  # the tree fills the frame vertically


def test_leaves_are_green_and_bark_is_brown(pictures):
    with_tree, without, _ = pictures
    mask = tree_mask(with_tree, without)
    px = with_tree[mask].astype(int)
    r, g, b = px[:, 0], px[:, 1], px[:, 2]
    assert ((g > r + 15) & (g > b + 15)).mean() > 0.2  # leafy crown
    assert ((r > g) & (g >= b) & (r > 60)).sum() > 30  # lit bark somewhere


def test_cli_render_writes_png(tmp_path, lsys_dir, capsys):
    out = tmp_path / "tree.png"
    args = ["render", str(lsys_dir / "seed003_tree.lsys"), "--steps", "4", "--size", "320x200", "--out", str(out)]
    assert main(args) == 0
    import pygame

    img = pygame.image.load(str(out))
    assert img.get_size() == (320, 200)
    assert "segments" in capsys.readouterr().out


def test_cli_render_refuses_what_would_not_fit_in_memory(tmp_path, capsys, monkeypatch):
    from arbor.game.commands import trees

    source, out = tmp_path / "double.lsys", tmp_path / "tree.png"
    source.write_text("w: F\np1: F -> FF\n")
    big = ["render", str(source), "--out", str(out), "--size", "8192x8192", "--steps", "1000", "--budget", "20000000"]
    assert main(big) == 1  # refused on the pixels alone, before 20 M modules are derived
    lines = capsys.readouterr().err.strip().splitlines()
    assert lines[-1] == ("arbor: rendering 8192x8192 pixels needs about 3.3 GB, over the limit of 2 GB: "
                         "ask for a smaller --size, fewer --steps or a higher --lod")
    assert not out.exists()
    # a tree larger than the picture's memory holds is grown only as far as it fits, said in one line, before
    # the derivation (issue 45: a render derived for 204 s to 1.93 GB, then refused); the limit is made
    # small here so that the tree it fits is quick to draw
    monkeypatch.setattr(trees, "RENDER_MEMORY", trees.RENDER_BASE + 320 * 200 * trees.PIXEL_BYTES
                        + 5_000 * trees.MODULE_BYTES[0])
    many = ["render", str(source), "--out", str(out), "--size", "320x200", "--steps", "20"]  # 1,048,576 modules
    assert main(many) == 0 and out.exists()
    said = capsys.readouterr()
    assert "growing to 5,000 modules at most (what a picture's or a mesh's memory limit of 0.3 GB" in said.err
    drawn = int(re.search(r"([\d,]+) modules, ", said.out).group(1).replace(",", ""))
    assert 2_500 < drawn <= 5_000


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (CI installs it)")
def test_arbor_opens_a_window(tmp_path):
    shot = tmp_path / "window.png"
    env = dict(os.environ, SDL_VIDEODRIVER="x11", SDL_AUDIODRIVER="dummy", ARBOR_MAX_FRAMES="4",
               ARBOR_SCREENSHOT=str(shot), ARBOR_SAVES=str(tmp_path / "saves"))
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x720x24", sys.executable, "-m", "arbor.game.cli"]
    proc = subprocess.run(cmd, env=env, capture_output=True, timeout=120)
    assert proc.returncode == 0, proc.stderr.decode()[-2000:]
    import pygame

    pixels = pygame.surfarray.array3d(pygame.image.load(str(shot))).astype(int)
    assert pixels.std() > 20
    green = (pixels[..., 1] > pixels[..., 0] + 15) & (pixels[..., 1] > pixels[..., 2] + 15)
    assert green.mean() > 0.2
    title = pixels[500:780, :432].min(axis=2)  # x, y: the window opens on the title screen (issue 29), its
    assert (title > 235).mean() > 0.03  # name's pale letters over the sky or the ground (clear of the crown)
    assert (tmp_path / "saves" / "autosave.arbor").exists()  # saved on quit


WINDOW_FXAA = """
import numpy as np, pygame, moderngl
from arbor.game.app import open_window
from arbor.game.render.fxaa import Fxaa
ctx = open_window((320, 200), "fxaa")
fxaa = Fxaa(ctx)
for colour in ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0)):  # an old frame, then the new one
    ctx.screen.use()
    ctx.clear(*colour, 1.0)
    fxaa.smooth(ctx.screen, (320, 200), (140, 90, 40, 20))  # the trees only in the middle
px = np.frombuffer(ctx.screen.read(components=3), np.uint8).reshape(200, 320, 3)
print(px[10, 10].tolist(), px[100, 160].tolist())
"""


@pytest.mark.skipif(shutil.which("xvfb-run") is None, reason="needs xvfb-run (CI installs it)")
def test_a_window_shows_the_whole_new_frame_with_edge_smoothing(tmp_path):
    env = dict(os.environ, SDL_VIDEODRIVER="x11", SDL_AUDIODRIVER="dummy")
    cmd = ["xvfb-run", "-a", "-s", "-screen 0 640x480x24", sys.executable, "-c", WINDOW_FXAA]
    proc = subprocess.run(cmd, env=env, capture_output=True, timeout=120, text=True)
    assert proc.returncode == 0, proc.stderr[-2000:]
    corner, middle = [list(map(int, part.strip(" []").split(","))) for part in
                      proc.stdout.strip().splitlines()[-1].split("] [")]
    assert corner == [255, 0, 0] and middle == [255, 0, 0]  # not the old frame outside the smoothed part


def test_wilting_turns_leaves_yellow_brown(ctx):
    from arbor.engine.geometry.mesh import tree_mesh
    from arbor.engine.geometry.turtle import TurtleConfig, interpret
    from arbor.engine.lsystem.lstring import parse_lstring
    from arbor.game.render.camera import OrbitCamera
    from arbor.game.render.renderer import TreeRenderer, sun_direction
    from arbor.game.screens.game_view import HEALTHY_LEAF, WILTED_LEAF

    ls = parse_lstring("!(0.2)F(3)" + "".join(f"[/({k * 137.5})&(60)L(1.2)]F(0.3)" for k in range(12)))
    renderer = TreeRenderer(ctx)
    renderer.set_tree(tree_mesh(interpret(ls, TurtleConfig(leaves_at_tips=0, pipe_model=False))))
    camera = OrbitCamera()
    camera.frame_bounds(renderer.lo, renderer.hi, 4 / 3)
    fbo = ctx.simple_framebuffer((400, 300))
    ratios = []
    for tint in (HEALTHY_LEAF, WILTED_LEAF):
        renderer.leaf_tint = tuple(tint)
        renderer.render(fbo, camera, sun_direction(85, 48), (400, 300))
        px = np.frombuffer(fbo.read(components=3), np.uint8).reshape(300, 400, 3)[::-1].astype(int)
        sky = px[5, 5]
        leafy = (px[..., 1] > px[..., 2] + 30) & (np.abs(px - sky).sum(axis=2) > 60)  # not sky, not bluish
        leafy[110:] = False  # the crown stands against the sky; below the horizon is grass
        assert leafy.sum() > 200
        ratios.append((px[..., 0][leafy] / np.maximum(px[..., 1][leafy], 1)).mean())
    assert ratios[0] < 0.6 and ratios[1] > 0.9  # green leaves, then yellow-brown ones
