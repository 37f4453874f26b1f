"""Pictures of the game's renderer for the record: one grown tree at each level of detail, in the wind
(two moments), at night and a close-up of a joint, as the game draws them headless (EGL; on this
machine Mesa llvmpipe, so with the software-GL budget).

Run: python -m benchmarks.shots [OUT.png] [DAYS]   (default docs/renderer.png, a tree grown 12 days)
"""

from __future__ import annotations

import sys
from pathlib import Path
from tempfile import TemporaryDirectory

import numpy as np

PANEL = (640, 360)


def main() -> None:
    """Render the eight panels and write them as one picture (two rows of four)."""
    import pygame
    from PIL import Image, ImageDraw

    from arbor.game.render.camera import OrbitCamera
    from arbor.game.render.garden import TWIG_PIXELS
    from arbor.game.render.instanced import LEAF_KEPT, Detail
    from arbor.game.render.renderer import headless_context
    from arbor.game.screens.game import Game, GameConfig
    from benchmarks.game import grown_tree

    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("docs/renderer.png")
    days = float(sys.argv[2]) if len(sys.argv) > 2 else 12.0
    pygame.init()
    pygame.display.set_mode((64, 64))
    ctx = headless_context()
    fbo = ctx.framebuffer(color_attachments=[ctx.renderbuffer(PANEL)], depth_attachment=ctx.depth_renderbuffer(PANEL))
    with TemporaryDirectory() as saves:
        clock = [1000.0]
        game = Game(ctx, PANEL, GameConfig(saves=Path(saves), seed=5, resume=False), clock=lambda: clock[0])
        game.garden.worlds[0] = grown_tree(days)
        game.world.sim.state.sun_angle = 1.1  # mid-morning
        game.hud.draw = lambda camera: None  # the scene alone
        renderer = game.renderer

        def shot() -> Image.Image:
            game.draw(fbo)
            pixels = np.frombuffer(fbo.read(components=3), np.uint8).reshape(PANEL[1], PANEL[0], 3)[::-1]
            return Image.fromarray(pixels.copy())

        panels = []
        game.rules.wind.strength = 0.0
        shot()
        for lod in range(4):
            placed = renderer.placed[0]
            per_pixel = renderer._per_pixel(placed.buffers, placed.offset, game.camera(), PANEL[1])
            renderer._detail = (lambda buffers, *a, lod=lod, px=per_pixel:
                                Detail.of(buffers, lod, TWIG_PIXELS[lod] * px, LEAF_KEPT[lod]))
            panels.append((shot(), f"level {lod}"))
        del renderer._detail
        game.rules.wind.strength = 3.0
        panels.append((shot(), "wind, t"))
        clock[0] += 1.3
        panels.append((shot(), "wind, t + 1.3 s"))
        game.rules.wind.strength = 0.0
        game.world.sim.state.sun_angle = 4.7
        panels.append((shot(), "night"))
        game.world.sim.state.sun_angle = 1.1
        view = renderer.placed[0].buffers.view
        tubes = view.tubes.data
        row = tubes[np.argmax((tubes[:, 25] == 1) * (1.0 / (1.0 + tubes[:, 1])))]  # the lowest first branch
        joint, reach = row[0:3].copy(), max(30.0 * float(row[18]), 0.3)  # (its start; 30 radii away)
        game.camera = lambda: OrbitCamera(yaw=35.0, pitch=10.0, distance=reach, target=joint)
        panels.append((shot(), "joint, close"))
    sheet = Image.new("RGB", (PANEL[0] * 4, PANEL[1] * 2))
    for k, (image, label) in enumerate(panels):
        ImageDraw.Draw(image).text((10, 10), label, fill=(255, 255, 255))
        sheet.paste(image, ((k % 4) * PANEL[0], (k // 4) * PANEL[1]))
    out.parent.mkdir(parents=True, exist_ok=True)
    sheet.save(out)
    print(f"wrote {out}")
    ctx.release()


if __name__ == "__main__":
    main()
