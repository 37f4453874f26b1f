"""The sun's shadow map for the garden: redrawn only when needed, and possibly over several frames."""

from __future__ import annotations

import math
from collections.abc import Callable

import moderngl
import numpy as np

from arbor.game.render.instanced import Piece

SHADOW_SIZE = 1024
SHADOW_TURN = math.cos(math.radians(0.75))  # redraw shadows when the sun turned more than this
SHADOW_FRAMES = 30  # ... or at least every this many frames while trees grow


class ShadowMaps:
    """Two depth maps of the trees seen from the sun: the front one is sampled by the frame, the back
    one redrawn (in one go, or a piece per frame) and then swapped in, so a map in use is always whole.
    A redraw is due when the sun turned, a tree changed, or the map is SHADOW_FRAMES old."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.maps = [self._map() for _ in range(2)]  # (texture, framebuffer): front, back
        self.key: tuple | None = None  # sun and trees the front map shows
        self.age = 0  # frames since it was drawn
        self.version = 0  # counts the maps drawn

    def _map(self) -> tuple[moderngl.Texture, moderngl.Framebuffer]:
        texture = self.ctx.depth_texture((SHADOW_SIZE, SHADOW_SIZE))
        texture.compare_func = "<="
        texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        return texture, self.ctx.framebuffer(depth_attachment=texture)

    @property
    def texture(self) -> moderngl.Texture:
        """The whole map frames sample."""
        return self.maps[0][0]

    def due(self, sun: np.ndarray, versions: tuple) -> bool:
        """Whether the map needs redrawing for ``sun`` and trees at ``versions``."""
        old = self.key
        return (old is None or old[1] != versions or float(np.dot(old[0], sun)) <= SHADOW_TURN
                or self.age >= SHADOW_FRAMES)

    def steps(self, sun: np.ndarray, versions: tuple, draw: Callable[[Piece], None],
              pieces: list[Piece]) -> list[Callable[[], None]]:
        """A redraw as steps: each of ``pieces`` drawn (by ``draw``) into the back map in turn, the
        first clearing it, the last swapping it in."""
        def step(k: int, piece: Piece) -> Callable[[], None]:
            def run() -> None:
                fbo = self.maps[1][1]
                fbo.use()
                self.ctx.viewport = (0, 0, SHADOW_SIZE, SHADOW_SIZE)
                if k == 0:
                    fbo.clear(depth=1.0)
                self.ctx.enable(moderngl.DEPTH_TEST)
                draw(piece)
                if k == len(pieces) - 1:
                    self.maps.reverse()
                    self.key, self.age = (sun, versions), 0
                    self.version += 1
            return run
        return [step(k, piece) for k, piece in enumerate(pieces)]
