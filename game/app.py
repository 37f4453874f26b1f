"""The `arbor` window: the tamagotchi game by default, or a plain L-system viewer (`arbor view`)."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import time
from pathlib import Path

from arbor.engine.base.files import FolderBusyError, FolderLock
from arbor.game.errors import NO_DISPLAY, NO_DISPLAY_FOUND, UserError
from arbor.game.signals import StopSignals
from arbor.game.watchdog import STAFF_EXIT, started

WINDOW = (1280, 720)


def open_window(size: tuple[int, int], title: str, fullscreen: bool = False):
    """A pygame OpenGL 3.3 core window (or the whole screen) and its moderngl context."""
    import moderngl
    import pygame

    _refuse_invisible_window(_driver_without_display())  # before SDL probes (and complains about) what is absent
    try:
        pygame.display.init()  # display and fonts only: no audio device is needed (or probed)
        _refuse_invisible_window(pygame.display.get_driver())
        pygame.font.init()
        pygame.display.gl_set_attribute(pygame.GL_CONTEXT_MAJOR_VERSION, 3)
        pygame.display.gl_set_attribute(pygame.GL_CONTEXT_MINOR_VERSION, 3)
        pygame.display.gl_set_attribute(pygame.GL_CONTEXT_PROFILE_MASK, pygame.GL_CONTEXT_PROFILE_CORE)
        flags = pygame.OPENGL | pygame.DOUBLEBUF | (pygame.FULLSCREEN if fullscreen else 0)
        pygame.display.set_mode((0, 0) if fullscreen else size, flags)
        pygame.display.set_caption(title)
        ctx = moderngl.create_context(require=330)
    except UserError:
        pygame.quit()
        raise
    except Exception as exc:  # pygame.error, moderngl.Error: no display, no GL, too old a GL
        pygame.quit()
        raise UserError(NO_DISPLAY.format(detail=str(exc).strip().splitlines()[0] if str(exc).strip()
                                          else type(exc).__name__)) from None
    ctx.gc_mode = "auto"  # GL objects are freed with their Python objects (a recovered kiosk leaks nothing)
    return ctx


INVISIBLE_DRIVERS = ("offscreen", "dummy")  # SDL's fallbacks when there is no display: a window nobody sees


def _refuse_invisible_window(driver: str) -> None:
    """Refuse to run a window on a video driver SDL fell back to (no DISPLAY: "offscreen"), where the game
    would run unseen. A driver asked for by name in SDL_VIDEODRIVER is the user's choice and is kept."""
    asked = os.environ.get("SDL_VIDEODRIVER", "").strip().lower()
    if driver.lower() in INVISIBLE_DRIVERS and asked != driver.lower():
        raise UserError(NO_DISPLAY_FOUND.format(driver=driver))


def _driver_without_display() -> str:
    """"offscreen" when nothing says where a window could go on Linux (no DISPLAY, WAYLAND_DISPLAY or
    SDL_VIDEODRIVER): what SDL would fall back to; otherwise "" (let SDL look)."""
    names = ("DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER")
    return "offscreen" if sys.platform.startswith("linux") and not any(os.environ.get(n) for n in names) else ""


def _frames_limit() -> int:
    return int(os.environ.get("ARBOR_MAX_FRAMES", "0"))


def _save_screen(ctx, size: tuple[int, int], path: str) -> None:
    """Save what the window shows (used by tests and bug reports)."""
    import numpy as np

    from arbor.game.render.renderer import save_png  # imported here: the renderer (numba) is slow to load

    pixels = np.frombuffer(ctx.screen.read(components=3), np.uint8).reshape(size[1], size[0], 3)
    save_png(pixels[::-1], path)


class Heartbeat:
    """Touches the file named by ARBOR_HEARTBEAT about once a second: the watchdog's sign of life."""

    def __init__(self) -> None:
        path = os.environ.get("ARBOR_HEARTBEAT")
        self.path = Path(path) if path else None
        self.last = 0.0

    def beat(self, now: float) -> None:
        """Touch the file if a second has passed (never raises: a full disk must not stop the app)."""
        if self.path is None or now - self.last < 1.0:
            return
        self.last = now
        with contextlib.suppress(OSError):
            self.path.touch()


def _main_loop(ctx, size: tuple[int, int], poll, frame, on_first_frame=None,
               signals: StopSignals | None = None) -> None:
    """Run ``frame(events, seconds)`` at up to 60 fps until it returns False, or until ARBOR_MAX_FRAMES
    frames have run (then save ARBOR_SCREENSHOT if set: used by tests and bug reports). ``poll(events,
    now)`` turns the window's events into input events; ``on_first_frame()`` runs once the first frame
    is shown (start-up figures). ``signals``: stop signals the caller installed before the window's
    start (one that came while the garden was being built ends the loop at once)."""
    import pygame

    clock = pygame.time.Clock()
    heart = Heartbeat()
    frames, limit, last = 0, _frames_limit(), time.perf_counter()
    # Ctrl-C, SIGTERM, SIGHUP: leave the loop; the caller saves and exits 0
    with contextlib.nullcontext(signals) if signals is not None else StopSignals() as signals:
        while not signals.stop:
            now = time.perf_counter()
            heart.beat(now)
            if not frame(poll(pygame.event.get(), now), now - last):
                return
            last = now
            frames += 1
            if limit and frames >= limit:
                if os.environ.get("ARBOR_SCREENSHOT"):
                    ctx.finish()
                    _save_screen(ctx, size, os.environ["ARBOR_SCREENSHOT"])
                return
            pygame.display.flip()
            if frames == 1:
                started()  # (files read at start are not to blame for what follows: game/watchdog.py)
            if frames == 1 and on_first_frame is not None:
                on_first_frame()
            clock.tick(60)


def _screen_frame(screen, fbo):
    """A frame function for anything with handle_input(), update() and draw() (a game, a viewer, a screen
    stack)."""
    def frame(events, seconds: float) -> bool:
        keep = True
        for event in events:
            keep = screen.handle_input(event) and keep
        screen.update(seconds)
        screen.draw(fbo)
        return keep

    return frame


def run_app(args: argparse.Namespace | None = None) -> int:
    """Open the game window and run until closed (Esc or the close button); saves on the way out."""
    import importlib

    import pygame

    from arbor.game.first_start import show_until_ready, timing
    from arbor.game.paths import default_saves

    saves = getattr(args, "saves", None) or os.environ.get("ARBOR_SAVES")
    lock = lock_saves(Path(saves) if saves else default_saves())  # before the window: a second Arbor ends here
    ctx = open_window(WINDOW, "Arbor")  # first: the title screen is up before the game's modules load
    with StopSignals() as signals:  # (from the window on: a signal during the start ends it cleanly too)
        if not show_until_ready(ctx, WINDOW, lambda: importlib.import_module("arbor.game.screens.game"),
                                beat=Heartbeat().beat, stop=lambda: signals.stop):
            pygame.quit()  # closed while the kernels compiled: nothing was played, nothing to save
            return 0
        from arbor.game.screens.game import Game, GameConfig

        config = GameConfig(title=True, sprout=True)  # (the title screen follows the first start's preparing screen)
        config.saves = lock.folder
        if getattr(args, "pace", None):
            config.pace = args.pace
        game = Game(ctx, WINDOW, config, clock=time.perf_counter)
        hub = make_input_hub(args, WINDOW, time.perf_counter())
        _main_loop(ctx, WINDOW, hub.poll, _screen_frame(game, ctx.screen), on_first_frame=lambda: timing("garden"),
                   signals=signals)
        game.quit()
    hub.close()
    pygame.quit()
    timing("closed")
    lock.release()
    return 0


def run_kiosk(args: argparse.Namespace) -> int:
    """Kiosk mode: fullscreen, touch only, never quits without the staff PIN, recovers from faults."""
    import pygame

    from arbor.game.first_start import show_until_ready, timing
    from arbor.game.paths import ASSETS
    from arbor.game.screens.game import Game, GameConfig
    from arbor.game.screens.kiosk import Kiosk, kiosk_config_or_defaults

    config = GameConfig(sprout=True)  # (each visitor's sapling rises from its seed)
    saves = getattr(args, "saves", None) or os.environ.get("ARBOR_SAVES")
    if saves:
        config.saves = Path(saves)
    config.saves = config.saves / "kiosk"  # the kiosk keeps its own garden: never the home autosave
    lock = lock_saves(config.saves)  # (the watchdog's restart takes over the lock its killed child left)
    _kiosk_log(config.saves / "kiosk.log")
    settings, problem = kiosk_config_or_defaults(ASSETS / "kiosk.toml")
    if problem:
        print(f"arbor: {problem}", file=sys.stderr)
    config.pace = settings.pace
    ctx = open_window(WINDOW, "Arbor", fullscreen=not args.windowed)
    size = pygame.display.get_surface().get_size()
    pygame.mouse.set_visible(False)
    with StopSignals() as signals:  # (from the window on: a signal during the start ends it cleanly too)
        # the preparing screen while the kernels compile (a first start), beating the watchdog's heartbeat
        if not show_until_ready(ctx, size, beat=Heartbeat().beat, stop=lambda: signals.stop) and signals.stop:
            pygame.quit()  # stopped while the kernels compiled: no garden was loaded, nothing to save
            lock.release()
            return 0
        kiosk = Kiosk(lambda: Game(ctx, size, config, clock=time.perf_counter), settings, config.saves,
                      clock=time.perf_counter)
        if problem:
            kiosk.game.say(problem, 12)
        hub = make_input_hub(args, size, time.perf_counter())
        _main_loop(ctx, size, kiosk.guarded(hub.poll), lambda events, seconds: kiosk.frame(events, seconds, ctx.screen),
                   on_first_frame=lambda: timing("garden"), signals=signals)
        kiosk.game.quit()
    hub.close()
    pygame.quit()
    lock.release()
    return STAFF_EXIT if kiosk.quit_requested else 0


def lock_saves(folder: Path) -> FolderLock:
    """Hold ``folder``'s lock for this process's life (two games writing one folder would lose each
    other's trees): a second Arbor on the same folder ends in one line naming the process that has it.
    A lock left by a process that died (kill -9, a crash, a watchdog's restart) is taken over."""
    try:
        return FolderLock(folder).acquire()
    except FolderBusyError as busy:
        raise UserError(f"the saves folder {folder} is in use by another Arbor (pid {busy.pid or 'unknown'}): "
                        "close that one first, or start this one with --saves ANOTHER_FOLDER") from None


KIOSK_LOG_BYTES = 1_000_000  # a kiosk.log file at most; then it is rotated
KIOSK_LOG_FILES = 3  # rotated kiosk logs kept (kiosk.log.1 .. .3): at most 4 MB of log in all


def _kiosk_log(path: Path) -> None:
    """The kiosk logs to saves/kiosk/kiosk.log, rotated (at most KIOSK_LOG_FILES + 1 files of KIOSK_LOG_BYTES);
    a folder that cannot be written (read-only, full) logs to stderr instead, so the kiosk still starts."""
    import logging
    from logging.handlers import RotatingFileHandler

    form = "%(asctime)s %(name)s %(levelname)s %(message)s"
    try:  # (bounded: KIOSK_LOG_BYTES a file, the last KIOSK_LOG_FILES kept as kiosk.log.1 ...)
        handler = RotatingFileHandler(path, maxBytes=KIOSK_LOG_BYTES, backupCount=KIOSK_LOG_FILES)
        logging.basicConfig(handlers=[handler], level=logging.INFO, format=form)
    except OSError as exc:
        logging.basicConfig(level=logging.INFO, format=form)
        logging.getLogger("arbor.kiosk").error("cannot write %s (%s): logging here instead", path, exc.strerror)


def make_input_hub(args: argparse.Namespace | None, size: tuple[int, int], now: float):
    """The input layer for the window: HID trackers always, TUIO, recording and replay on request."""
    from arbor.game.input.events import InputHub, Player, Recorder, load_recording

    sources: list = [_trackers()]
    if getattr(args, "tuio", False):
        from arbor.game.input.tuio import TuioListener

        sources.append(TuioListener(size, args.tuio_host, args.tuio_port))
    if getattr(args, "replay", None):
        try:
            sources.append(Player(load_recording(args.replay), now))
        except (OSError, ValueError, UnicodeDecodeError) as exc:
            raise UserError(f"cannot replay {args.replay}: {getattr(exc, 'strerror', None) or exc}") from None
    recorder = Recorder(args.record) if getattr(args, "record", None) else None
    return InputHub(size, sources, recorder)


def _trackers():
    """The HID trackers: SpaceMice, and the absolute trackers devices.toml describes. A bad devices.toml
    is said in one line (stderr and the log) and its trackers are left out: the mouse, touch and
    SpaceMice still work, so the game and the kiosk still start."""
    import logging

    from arbor.game.input.hid import DevicesError, HidManager, load_profiles
    from arbor.game.paths import ASSETS

    try:
        profiles = load_profiles(ASSETS / "input" / "devices.toml")
    except DevicesError as err:
        line = f"arbor: {err} (the trackers it describes are not used)"
        print(line, file=sys.stderr)
        logging.getLogger("arbor.input").error(line)
        profiles = []
    return HidManager(profiles=profiles)


def run_lab_window(experiment: Path) -> int:
    """The lab screen in a window: trees side by side, live charts, speed and export buttons."""
    import pygame

    from arbor.game.commands.lab import new_lab
    from arbor.game.first_start import timing
    from arbor.game.input.events import InputHub
    from arbor.game.screens.lab import LabScreen
    from arbor.game.screens.stack import ScreenStack

    lab = new_lab(experiment)
    ctx = open_window(WINDOW, f"Arbor lab - {lab.experiment.title}")
    with StopSignals() as signals:  # (from the window on: a signal while the screen is built ends it too)
        signals.leave_at_once = True  # (its trees grow, maybe compiling kernels: nothing to save yet)
        screens = ScreenStack(LabScreen(ctx, WINDOW, lab))
        signals.leave_at_once = False
        _main_loop(ctx, WINDOW, InputHub(WINDOW).poll, _screen_frame(screens, ctx.screen),
                   on_first_frame=lambda: timing("garden"), signals=signals)
    pygame.quit()
    return 0


def run_builder_window(path: Path) -> int:
    """The experiment builder in a window (arbor lab FILE --build): a sweep file set up with the mouse, saved,
    and run with its progress shown."""
    import pygame

    from arbor.engine.life.experiment.builder import NotBuildableError
    from arbor.game.commands.sweep import run_sweep
    from arbor.game.input.events import InputHub
    from arbor.game.screens.builder import BuilderScreen
    from arbor.game.screens.stack import ScreenStack

    try:
        BuilderScreen(None, WINDOW, path, run_sweep)  # (a file it cannot show: one line, before any window)
    except NotBuildableError as err:
        raise UserError(f"{path}: {err}") from None
    ctx = open_window(WINDOW, f"Arbor experiment builder - {path.name}")
    with StopSignals() as signals:
        screens = ScreenStack(BuilderScreen(ctx, WINDOW, path, run_sweep))
        _main_loop(ctx, WINDOW, InputHub(WINDOW).poll, _screen_frame(screens, ctx.screen), signals=signals)
    pygame.quit()
    return 0


def run_viewer(source: Path) -> int:
    """Open the viewer window on an .lsys file."""
    import pygame

    from arbor.game.first_start import timing
    from arbor.game.input.events import InputHub
    from arbor.game.screens.viewer import Viewer

    ctx = open_window(WINDOW, f"Arbor - {source.name}")
    with StopSignals() as signals:  # (from the window on: a signal while the tree is built ends it too)
        signals.leave_at_once = True  # (the tree grows, maybe compiling kernels: nothing to save yet)
        viewer = Viewer(ctx, WINDOW, source)
        signals.leave_at_once = False
        _main_loop(ctx, WINDOW, InputHub(WINDOW).poll, _screen_frame(viewer, ctx.screen),
                   on_first_frame=lambda: timing("garden"), signals=signals)
    pygame.quit()
    return 0
