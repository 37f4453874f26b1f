"""The first start that talks: Arbor's compiled kernels (numba) are built once per machine, which takes
tens of seconds; the window shows a title and a progress bar meanwhile, headless commands say one line.

The kernels compile on a thread (``Warmup``) by growing a small tree through the public engine API, stage
by stage; the progress is the share of the stages' measured compile time done (STAGES), so the bar moves
with numba's real work rather than with the count of kernels (one of which took half the time)."""

from __future__ import annotations

import gc
import importlib
import sys
import threading
import time

# Every module holding numba kernels (keep in step with engine/: a module missing here only makes the
# progress bar coarser, never wrong, because the bar is full when the warm-up thread ends).
KERNEL_MODULES = (
    "arbor.engine.geometry.turtle_kernel",
    "arbor.engine.geometry.mesh_kernel",
    "arbor.engine.geometry.chains",
    "arbor.engine.lsystem.context_kernel",
    "arbor.engine.lsystem.expand_kernel",
    "arbor.engine.life.plant.light_kernel",
)
FIRST_START = "preparing Arbor for this machine (first start only)"


def kernel_dispatchers() -> list:
    """The numba dispatchers of Arbor's kernels (functions inlined into others are left out: they never
    compile on their own)."""
    from numba.core.registry import CPUDispatcher

    from arbor.engine.base.jit import defer_blas_check

    defer_blas_check()  # (before any kernel runs: numba's first use would import scipy.linalg, 150 ms)
    found = []
    for name in KERNEL_MODULES:
        module = importlib.import_module(name)
        for value in vars(module).values():
            if isinstance(value, CPUDispatcher) and value.__module__ == name \
                    and value.targetoptions.get("inline") != "always":
                found.append(value)
    return found


def _cached(dispatcher) -> bool:
    """True when numba's disk cache holds a current (not stale) build of this kernel."""
    try:
        return bool(dispatcher._cache._cache_file._load_index())  # {} when missing or the source changed
    except Exception:  # a numba without these internals: assume cached, so nothing false is said
        return True


def kernels_cold() -> bool:
    """True when some kernel has no usable build on disk: the next use compiles it (tens of seconds)."""
    return not all(_cached(d) for d in kernel_dispatchers())


def _warm_context() -> None:
    from arbor.engine.base.assets import assets_dir
    from arbor.engine.lsystem.derive import Deriver
    from arbor.engine.lsystem.lsys import load_lsystem

    Deriver(load_lsystem(assets_dir() / "lsystems" / "context_plant.lsys"), seed=0).derive(steps=4)


def _warm_plain() -> None:
    from arbor.engine.lsystem.derive import Deriver
    from arbor.engine.lsystem.lsys import parse_lsystem

    Deriver(parse_lsystem("w: F\np1: F -> F[+F]F[-F]F[+F]F[-F]FF\n"), seed=0).derive(steps=2)


def _small_tree():
    from arbor.engine.lsystem.derive import Deriver
    from arbor.engine.lsystem.lsys import parse_lsystem

    tree = parse_lsystem("n: 3\ndelta: 30\nw: A\np1: A -> F[+A L][-A L]F A\n")
    return tree, Deriver(tree, seed=0).derive(steps=3)[0]


def _warm_geometry(lod: int) -> None:
    from arbor.engine.geometry.tree import build_geometry

    tree, ls = _small_tree()
    build_geometry(ls, tree, lod=lod)  # leaves where the string has them


def _warm_tips() -> None:
    from arbor.engine.geometry.tree import build_geometry

    tree, ls = _small_tree()
    build_geometry(ls, tree, lod=0, leaves_at_tips=3)  # and clusters at the twigs' tips


def _warm_light() -> None:
    import numpy as np

    from arbor.engine.life.plant.light import optical_depth

    points = np.array([[0.0, 1.0, 0.0], [0.1, 2.0, 0.0], [0.0, 3.0, 0.1]])
    optical_depth(points, np.ones(3), points, np.array([0.0, 1.0, 0.0]), 0.5, np.arange(3))


# The warm-up's stages with the CPU seconds each took to compile on a cold cache (measured on 2 shared cores
# at load 2-10: NUMBA_CACHE_DIR set to an empty folder, each stage timed in turn, four runs); the progress
# moves by this measured work, not by the count of kernels (the turtle's and the mesh's kernels are most of it).
STAGES = (
    ("context rules", _warm_context, 0.4),
    ("plain rules", _warm_plain, 2.1),  # (2.14-2.18 s since the block step's 32-byte stores, 4f18ff3)
    ("the turtle and the mesh", lambda: _warm_geometry(0), 4.2),
    ("the coarser mesh", lambda: _warm_geometry(1), 0.2),
    ("leaf clusters", _warm_tips, 0.3),
    ("the light grid", _warm_light, 1.8),
)


def warm_kernels(progress=None) -> None:
    """Use every kernel once on a small tree (context rules, turtle, leaves, mesh, chains, the light grid):
    compiles what the cache lacks and loads the rest, so the garden's first tree finds them ready.
    ``progress(done, total, stage)`` is called before each stage and at the end with the measured seconds."""
    total = sum(weight for _, _, weight in STAGES)
    done = 0.0
    for name, run, weight in STAGES:
        if progress is not None:
            progress(done, total, name)
        run()
        done += weight
    if progress is not None:
        progress(total, total, "ready")


def headless_notice(stream=None, quiet: bool = False) -> bool:
    """Before a headless command, when some kernel has no build on disk: say so in one line and build them
    all (not only the ones this command uses), so the notice's "first start only" holds for the next
    command too; under ``quiet`` build them without a word. True when it did."""
    if not kernels_cold():
        return False
    if quiet:
        warm_kernels()
        return True
    from arbor.game.progress import Progress

    stream = stream or sys.stderr
    total = sum(weight for _, _, weight in STAGES)
    print(f"arbor: {FIRST_START}: compiling its kernels, about {total:.0f} s on 2 cores...", file=stream, flush=True)
    with Progress("compiling", total, unit="s of work", stream=stream) as bar:
        warm_kernels(lambda done, _total, stage: bar.to(done, stage))
    return True


class Warmup:
    """The kernels' warm-up on a background thread, plus anything else slow to import (``extra``)."""

    def __init__(self, extra=None) -> None:
        self.dispatchers = kernel_dispatchers()
        self.cold = not all(_cached(d) for d in self.dispatchers)
        self.error: BaseException | None = None
        self.started = time.perf_counter()
        self._extra = extra
        self.share = 0.0  # of the warm-up's measured work done (STAGES)
        self._stage_at, self._stage_share, self._stage_seconds = self.started, 0.0, 1.0
        self._thread = threading.Thread(target=self._run, name="arbor-warmup", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        try:
            warm_kernels(self._advance)
            if self._extra is not None:
                self._extra()
        except BaseException as exc:  # handed to the main thread, which raises it there
            self.error = exc

    def _advance(self, done: float, total: float, _stage: str) -> None:
        self.share, self._stage_at = done / total, time.perf_counter()
        self._stage_seconds = next((w for name, _, w in STAGES if name == _stage), 0.0)
        self._stage_share = self._stage_seconds / total

    @property
    def done(self) -> bool:
        """True once the warm-up thread has finished (successfully or not)."""
        return not self._thread.is_alive()

    @property
    def progress(self) -> float:
        """0..1: the warm-up's measured work done so far (the last tenth is the imports after it)."""
        if self.done:
            return 1.0
        # within a stage: its measured seconds, at most nine tenths of it until it ends
        inside = min((time.perf_counter() - self._stage_at) / max(self._stage_seconds, 1e-3), 0.9)
        return 0.9 * (self.share + inside * self._stage_share)

    def result(self) -> None:
        """Wait for the thread; raise what it raised."""
        self._thread.join()
        if self.error is not None:
            raise self.error


def since_launch() -> float:
    """Seconds since this process started (Linux /proc; 0.0 elsewhere): for start-up figures."""
    import os

    try:
        with open("/proc/self/stat") as f:
            started = int(f.read().rsplit(")", 1)[1].split()[19]) / os.sysconf("SC_CLK_TCK")
        with open("/proc/uptime") as f:
            return float(f.read().split()[0]) - started
    except (OSError, ValueError, IndexError):
        return 0.0


def timing(what: str) -> None:
    """With ARBOR_TIMING set, say on stderr when a start-up milestone happened (benchmarks.startup reads it)."""
    import os

    if os.environ.get("ARBOR_TIMING"):  # seconds since launch, the wall clock, CPU seconds (all threads)
        print(f"arbor-timing {what} {since_launch():.3f} {time.time():.3f} {time.process_time():.3f}",
              file=sys.stderr, flush=True)


_VERTEX = """#version 330
in vec2 pos; out vec2 uv;
void main() { uv = vec2(pos.x * 0.5 + 0.5, 0.5 - pos.y * 0.5); gl_Position = vec4(pos, 0.0, 1.0); }"""
_FRAGMENT = """#version 330
uniform sampler2D image; in vec2 uv; out vec4 color;
void main() { color = texture(image, uv); }"""


class TitleScreen:
    """Arbor's title, a line of what is happening and a progress bar, drawn with pygame and shown as one
    texture (no game renderer needed: it is up before the game's modules are imported)."""

    _backdrop = None  # the sky, the meadow and the name: drawn on the first frame, then copied

    def __init__(self, ctx, size: tuple[int, int]) -> None:
        from array import array

        import pygame

        pygame.font.init()
        self.ctx, self.size = ctx, size
        self.title = pygame.font.Font(None, max(48, size[1] // 7))
        self.small = pygame.font.Font(None, max(20, size[1] // 28))
        self.texture = ctx.texture(size, 3)
        program = ctx.program(vertex_shader=_VERTEX, fragment_shader=_FRAGMENT)
        quad = ctx.buffer(array("f", [-1, -1, 1, -1, -1, 1, 1, 1]).tobytes())
        self.vao = ctx.vertex_array(program, [(quad, "2f", "pos")])

    def surface(self, progress: float, line: str):
        """The title screen as a pygame Surface: sky to meadow, the name, the line, the bar."""
        import pygame

        w, h = self.size
        if self._backdrop is None:  # drawn once: a soft dawn sky over a meadow strip, and the name
            self._backdrop = pygame.Surface(self.size)
            for y in range(0, h, 4):
                t = y / h
                colour = (38 + 90 * t, 62 + 100 * t, 92 + 70 * t) if t < 0.78 else (70, 112, 58)
                self._backdrop.fill([int(c) for c in colour], (0, y, w, 4))
            name = self.title.render("Arbor", True, (246, 240, 222))
            self._backdrop.blit(name, name.get_rect(center=(w // 2, int(h * 0.36))))
        surf = self._backdrop.copy()
        text = self.small.render(line, True, (236, 232, 214))
        surf.blit(text, text.get_rect(center=(w // 2, int(h * 0.55))))
        bar = pygame.Rect(w // 4, int(h * 0.62), w // 2, max(8, h // 48))
        pygame.draw.rect(surf, (28, 40, 34), bar, border_radius=bar.height // 2)
        filled = bar.copy()
        filled.width = max(bar.height, int(bar.width * min(max(progress, 0.0), 1.0)))
        pygame.draw.rect(surf, (150, 206, 110), filled, border_radius=bar.height // 2)
        return surf

    def draw(self, progress: float, line: str) -> None:
        """Draw the title screen into the window's framebuffer."""
        import pygame

        self.texture.write(pygame.image.tobytes(self.surface(progress, line), "RGB"))
        self.ctx.screen.use()
        self.ctx.viewport = (0, 0, *self.size)
        self.texture.use(0)
        self.vao.render(mode=self.ctx.TRIANGLE_STRIP)


def _settle_garbage() -> None:
    """Once the game's modules and kernels are loaded: keep what they made out of the garbage collector's
    scans from now on (gc.freeze) and let it run again. The start makes about 150,000 objects that live as
    long as the game (modules, numba's type registries); scanning them cost the start about 0.1 s of CPU in
    collections, and a full collection in the garden cost 156-195 ms with them scanned, 0.6-0.9 ms with them
    kept out (one run at load average 7). Objects made from here on (the game's) are collected as usual."""
    gc.freeze()
    gc.enable()


REDRAWS = 5  # title screen frames a second at most (a warm start's CPU went to redrawing it at 30)


def show_until_ready(ctx, size: tuple[int, int], extra=None, beat=None, stop=None) -> bool:
    """Show the title screen while the kernels warm up on a thread (and ``extra`` runs after them);
    False when the player closed the window meanwhile, or ``stop()`` became true (a stop signal). Keys
    pressed meanwhile are given back to the window's queue: the game's first frame gets them.
    ``beat(now)`` is called every frame (a watchdog's heartbeat: a first start that compiles for minutes
    on a slow machine is alive, not hung). The garbage collector rests meanwhile (see _settle_garbage)."""
    import pygame

    gc.disable()
    try:
        screen, clock = TitleScreen(ctx, size), pygame.time.Clock()
        warm = Warmup(extra)
        if warm.cold:  # (a first start's compile makes garbage for tens of seconds: collected as it goes)
            gc.enable()
        kept: list = []  # keys pressed meanwhile: given back to the window's queue for the game (never lost)
        first = _show_while(warm, screen, clock, kept, beat, stop)
        if first is None:
            return False
        warm.result()
    finally:
        gc.enable()
    _settle_garbage()
    for event in kept:
        pygame.event.post(event)
    screen.draw(1.0, "planting the garden...")
    pygame.display.flip()
    if first:
        timing("first-frame")
    return True


def _show_while(warm: Warmup, screen: TitleScreen, clock, kept: list, beat, stop) -> bool | None:
    """The title screen's loop while ``warm`` works: None when the window was closed or ``stop()`` came
    true, else whether the screen is still to be shown for the first time. Keys go into ``kept``."""
    import pygame

    line = FIRST_START + "..." if warm.cold else "waking the garden..."
    first, shown, shown_at = True, None, 0.0
    while not warm.done:
        events = pygame.event.get()
        if any(e.type == pygame.QUIT for e in events) or (stop is not None and stop()):
            return None
        kept += [e for e in events if e.type in (pygame.KEYDOWN, pygame.KEYUP)]
        now = time.perf_counter()
        if beat is not None:
            beat(now)
        step = round(100 * warm.progress)  # redrawn when the bar moves a step, at most REDRAWS a second: a
        if step != shown and now - shown_at >= 1 / REDRAWS:  # redraw and flip cost ~25 ms of CPU each
            screen.draw(warm.progress, line)
            pygame.display.flip()
            shown, shown_at = step, now
            if first:
                timing("first-frame")
                first = False
        clock.tick(30)
    return first
