"""The `arbor` command: the game window by default, headless subcommands for tools and CI."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from arbor.engine.base.errors import LSysError
from arbor.engine.base.memory import keep_freed_memory
from arbor.engine.base.units import METRE
from arbor.engine.lsystem.derive import DEFAULT_BUDGET, MAX_BUDGET
from arbor.game.errors import UserError
from arbor.game.paths import ASSETS
from arbor.game.report import detail, say, set_level


def _source(args: argparse.Namespace):
    from arbor.game.commands.trees import TreeSource

    return TreeSource(args.source, args.steps, args.seed, args.budget, getattr(args, "tree", 0),
                      getattr(args, "species", None))


def _cmd_derive(args: argparse.Namespace) -> int:
    from arbor.game.commands.trees import derive_source
    from arbor.game.progress import Progress

    with Progress("derive", 1.0, unit="s") as bar:
        _, result = derive_source(_source(args), progress=bar)
        text = result.to_text()
    print(text)
    return 0


MAX_STEPS = 1000  # derivation steps (the module budget stops growth long before)
MAX_TREES = 20_000  # trees in a landscape
MAX_LOD = 3


def _bounded(low: int, high: int, what: str):
    """An argparse type: a whole number in [low, high], with a message that says the limit."""
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{what} must be a whole number") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"{what} must be from {low:,} to {high:,} (got {value:,})")
        return value

    return parse


def _metres(what: str):
    """An argparse type: a length in metres (or metres per unit), finite, above 0 and at most 10 km."""
    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{what} must be a number of metres") from None
        if not 0.0 < value <= 10_000.0:
            raise argparse.ArgumentTypeError(f"{what} must be above 0 and at most 10,000 metres (got {text})")
        return value

    return parse


def _size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError("size must look like 1280x720") from None
    if not (16 <= w <= 8192 and 16 <= h <= 8192):
        raise argparse.ArgumentTypeError("size must be between 16 and 8192 pixels per side")
    return w, h


def _in_metres(mesh, factor: float):
    """The mesh with its positions multiplied by ``factor`` (a source's unit to the scene's metre)."""
    from dataclasses import replace

    if factor == 1.0:
        return mesh
    return replace(mesh, **{part: replace(getattr(mesh, part), positions=getattr(mesh, part).positions * factor)
                            for part in ("wood", "leaves", "blossoms")})


def _cmd_render(args: argparse.Namespace) -> int:
    from arbor.engine.geometry.tree import tree_height
    from arbor.game.commands.trees import check_render_memory, render_modules, scene_metres, tree_geometry
    from arbor.game.progress import PER_TRIANGLE, TRIANGLES_PER_MODULE, Progress
    from arbor.game.render.renderer import render_image, save_png

    check_render_memory(args.size, 0, args.lod)  # the picture alone, before any derivation
    drawing = PER_TRIANGLE["png"] * TRIANGLES_PER_MODULE
    with Progress(f"render {args.out.name}", 1.0, unit="s") as bar:
        geometry, ls = tree_geometry(_source(args), args.lod,
                                     check=lambda n: check_render_memory(args.size, n, args.lod),
                                     most=render_modules(args.size, args.lod),  # (derives no more than it can draw)
                                     progress=bar, after=lambda modules: modules * drawing)
        with bar.timed("rendering", geometry.mesh.n_triangles * PER_TRIANGLE["png"]):
            scale = ""
            if args.scale_bar is None:
                pixels = render_image(geometry.mesh, args.size, yaw=args.yaw, pitch=args.pitch)
            else:
                from arbor.game.render.scale_bar import frame_for, render_to_scale

                metres = scene_metres(_source(args))  # the source's unit: the bar measures real metres
                height = tree_height(geometry) * metres
                frame = args.scale_bar or frame_for(height)
                mesh = _in_metres(geometry.mesh, metres * METRE)
                pixels = render_to_scale(mesh, args.size, frame, yaw=args.yaw, pitch=args.pitch)
                scale = f", {height:.2f} m tall (top of the wood) in a frame {frame:g} m high (metre bar at the left)"
            save_png(pixels, args.out)
    say(f"{args.out}: {len(ls):,} modules, {len(geometry.turtle.segments):,} segments, "
        f"{geometry.mesh.n_triangles:,} triangles{scale}")
    return 0


def _cmd_export(args: argparse.Namespace) -> int:
    from arbor.engine.geometry.export import export_tree
    from arbor.engine.geometry.tree import tree_height
    from arbor.game.commands.trees import render_modules, scene_metres, size_warning, tree_geometry
    from arbor.game.progress import PER_TRIANGLE, TRIANGLES_PER_MODULE, Progress

    fmt = (args.format or args.out.suffix.lstrip(".")).lower()
    if fmt not in ("glb", "obj"):
        raise UserError(f"cannot export as {fmt or 'a file without a suffix'!r}: use --out NAME.glb or NAME.obj "
                        "(or --format glb|obj)")
    if args.lods and fmt != "glb":
        raise UserError("--lods writes every level of detail into one GLB: use --out NAME.glb")
    args.format = fmt
    with Progress(f"export {args.out.name}", 1.0, unit="s") as bar:
        geometry, _ = tree_geometry(_source(args), args.lod, roots=True, progress=bar,
                                    after=lambda modules: modules * TRIANGLES_PER_MODULE * PER_TRIANGLE[fmt],
                                    most=render_modules((0, 0), args.lod))  # (no more than its mesh's memory holds)
        height = tree_height(geometry)
        if args.height is not None and height <= 0:
            raise UserError("--height needs a tree with some height: this one has none (more --steps?)")
        metres = args.height / height if args.height is not None else args.scale or scene_metres(_source(args))
        coarser = tuple(tree_geometry(_source(args), lod, roots=True, most=render_modules((0, 0), lod))[0].mesh
                        for lod in range(args.lod + 1, MAX_LOD + 1)) if args.lods else ()
        with bar.timed(f"writing {fmt.upper()}", geometry.mesh.n_triangles * PER_TRIANGLE[fmt]):
            files = export_tree(geometry.mesh, args.out, ASSETS / "textures", args.format, metres, height=height,
                                coarser=coarser)
    warning = size_warning(height * metres)
    if warning:
        print(warning, file=sys.stderr)
    lods = f"lod {args.lod}; with lods up to {MAX_LOD} in one GLB" if args.lods else f"lod {args.lod}"
    say(f"{args.out}: {geometry.mesh.n_triangles:,} triangles ({lods}), {height * metres:.2f} m tall "
        f"(top of the wood); wrote {len(files)} file(s)")
    return 0


def _cmd_lab(args: argparse.Namespace) -> int:
    from arbor.game.errors import need_lab_extra

    need_lab_extra("arbor lab (its charts)")
    if args.build:
        if args.out is not None:
            raise UserError("--build opens the experiment builder's window: give --out only to run an experiment "
                            "without a window")
        from arbor.game.app import run_builder_window

        return run_builder_window(args.experiment)
    if args.out is None:
        from arbor.game.app import run_lab_window

        return run_lab_window(args.experiment)
    from arbor.game.commands.lab import run_headless

    files = run_headless(args.experiment, args.out)
    say("\n".join(str(f) for f in files))
    return 0


def _cmd_sweep(args: argparse.Namespace) -> int:
    from arbor.game.commands.sweep import run_sweep
    from arbor.game.errors import need_lab_extra

    if not args.no_plots:
        need_lab_extra("arbor sweep's figures (--no-plots writes the CSV tables without it)")
    return run_sweep(args.sweep, args.out, args.workers, args.scheduler, plots=not args.no_plots, keep=args.keep)


def _cmd_compare(args: argparse.Namespace) -> int:
    from arbor.game.commands.compare import compare
    from arbor.game.errors import need_lab_extra

    if not args.no_plots:
        need_lab_extra("arbor compare's figure (--no-plots writes the table without it)")
    for path in compare(args.folders, args.out, plots=not args.no_plots):
        say(str(path))
    return 0


def _cmd_worksheet(args: argparse.Namespace) -> int:
    from arbor.game.commands.worksheet import make_worksheet
    from arbor.game.errors import need_lab_extra

    need_lab_extra("arbor worksheet (its charts)")
    for path in make_worksheet(args.lesson, args.out, args.seeds, args.workers):
        say(str(path))
    return 0


def _cmd_landscape(args: argparse.Namespace) -> int:
    from arbor.game.commands.landscape import parse_presets, render_landscape

    presets = render_landscape(args.trees, args.out, args.size, args.seed or 0, args.lod, parse_presets(args.presets))
    if args.glb:
        from arbor.engine.forest.landscape import scatter
        from arbor.engine.geometry.export import export_garden
        from arbor.game.commands.landscape import landscape_size

        instances = scatter(args.trees, len(presets), landscape_size(args.trees), args.seed or 0)
        export_garden(presets, instances, args.glb, ASSETS / "textures")
        say(f"{args.glb}: {args.trees:,} trees as glTF nodes sharing {len(presets)} trees' meshes")
    return 0


def _cmd_breed(args: argparse.Namespace) -> int:
    from arbor.game.commands.family import breed_saves

    garden = breed_saves(args.a, args.b, args.seed, args.out, args.tree_a, args.tree_b)
    child = garden.world
    say(f"{args.out}: {child.lineage.species} {child.lineage.id}, generation {child.lineage.generation}, "
          f"from {garden.worlds[0].lineage.id} x {child.lineage.parents[-1]} (seed {args.seed})")
    return 0


def _cmd_lineage(args: argparse.Namespace) -> int:
    from arbor.game.commands.family import lineage_text

    print(lineage_text(args.save))
    return 0


def _cmd_card(args: argparse.Namespace) -> int:
    from arbor.game.commands.card import make_card

    world = make_card(args.save, args.out, args.tree)
    say(f"{args.out}: a postcard of {world.lineage.species} {world.lineage.id} carrying its save "
          f"(arbor import {args.out} plants it in a garden)")
    return 0


def _cmd_import(args: argparse.Namespace) -> int:
    import os

    from arbor.game.app import lock_saves
    from arbor.game.commands.card import import_card
    from arbor.game.paths import default_saves

    saves = args.saves or (Path(os.environ["ARBOR_SAVES"]) if os.environ.get("ARBOR_SAVES") else default_saves())
    lock = lock_saves(saves)  # a game playing this garden would overwrite the import at its next autosave
    try:
        world, count = import_card(args.card, lock.folder)
    finally:
        lock.release()
    where = "as the garden's first tree" if count == 1 else \
        f"beside the other{'s' if count > 2 else ''} ({count} trees in the garden)"
    say(f"{lock.folder / 'autosave.arbor'}: planted {world.lineage.species} {world.lineage.id} from {args.card} "
        f"{where}")
    return 0


def _add_growth_args(p: argparse.ArgumentParser, saves: bool = False) -> None:
    p.add_argument("source", type=Path, help=".lsys file, or a save (.arbor)" if saves else ".lsys file")
    if saves:
        p.add_argument("--tree", type=int, default=0, help="which tree of a garden save (default: the first, 0)")
    p.add_argument("--steps", type=_bounded(0, MAX_STEPS, "--steps"), default=None,
                   help=f"derivation steps, 0-{MAX_STEPS} (default: the file's n:)")
    p.add_argument("--seed", type=_bounded(0, 2**63 - 1, "--seed"), default=None,
                   help="seed of the source's rand() and stochastic rules (default: the file's seed:, else 0)")
    p.add_argument("--species", default=None, metavar="NAME",
                   help="for a source asking for GeoMaTree's functions (geomatree.lsys, divisor_tree.lsys): "
                   "grow it as this species of assets/presets (broadleaf, weeping) or a preset .toml "
                   "(default: broadleaf)")
    p.add_argument("--budget", type=_bounded(1, MAX_BUDGET, "--budget"), default=None,
                   help=f"module budget, at most {MAX_BUDGET:,} (default: the file's budget:, else {DEFAULT_BUDGET:,})")


WINDOWS = ("view", "lab")  # subcommands with a window of their own: they take the input options too


def _add_global_options(parser: argparse.ArgumentParser, here: bool, inputs: bool = True) -> None:
    """The options of every command, anywhere on the line (``arbor -q render X`` and ``arbor render X -q``,
    as git and pip accept theirs): --saves, -q and -v; with ``inputs`` the input options of a window (TUIO,
    recording, replay). ``here``: the top-level parser (the game), which holds the defaults and the game's own
    options (--pace, --kiosk, --windowed); a subcommand's copies default to SUPPRESS, so an option given
    before the subcommand is not reset by the subcommand."""
    group = parser.add_argument_group("options of every command (before or after the command)")
    own = parser.add_argument_group("options of the window") if here or inputs else None

    def add(*flags: str, into=group, **kw) -> None:
        if not here:
            kw["default"] = argparse.SUPPRESS
        into.add_argument(*flags, **kw)

    add("--saves", type=Path, default=None, metavar="DIR",
        help="folder for save files (default: saves/ in a checkout, else ~/.local/share/arbor/saves)")
    add("-q", "--quiet", action="store_true", default=False, help="say nothing but errors: no report of what was "
        "written, no progress, no first-start notice (errors still say one line)")
    add("-v", "--verbose", action="store_true", default=False, help="each step of a long run (every finished "
        "sweep run) and the time taken")
    if own is None:
        return
    add("--tuio", into=own, action="store_true", default=False, help="accept TUIO 1.1 touch over UDP")
    add("--tuio-host", into=own, default="127.0.0.1", metavar="ADDRESS",
        help="address to listen on for TUIO (default 127.0.0.1)")
    add("--tuio-port", into=own, type=_bounded(1, 65535, "--tuio-port"), default=3333, metavar="PORT",
        help="UDP port to listen on for TUIO (default 3333, TUIO's own)")
    add("--record", into=own, type=Path, default=None, metavar="FILE", help="record this session's input to a file")
    add("--replay", into=own, type=Path, default=None, metavar="FILE", help="replay recorded input")
    if not here:
        return
    add("--pace", into=own, choices=("home", "demo"), default=None,
        help="home: a day of the sun lasts a day (default); demo: 2-minute days, as in the thesis")
    add("--kiosk", into=own, action="store_true", default=False,
        help="unattended touchscreen mode (see assets/kiosk.toml)")
    add("--windowed", into=own, action="store_true", default=False, help="with --kiosk: a window instead of fullscreen")


EPILOG = """examples:
  arbor                                      the game (a window)
  arbor render assets/lsystems/abop_2_8_tree.lsys --out tree.png
  arbor export saves/autosave.arbor --out tree.glb -q
  arbor sweep assets/experiments/sweep_sun_height.toml --out sun/ -v
  arbor compare alice/ bob/ carol/ --out class/   a class's sweep folders in one table and figure
  arbor worksheet light --out light.pdf          lesson 1's printable sheet, with an answer key
  arbor card saves/autosave.arbor --out tree.png && arbor import tree.png --saves other/

Every command exits 0 when done, 1 on a failure at run time (one line on stderr says what to fix) and 2 on
bad arguments. Documentation: README.md and docs/ (docs/troubleshooting.md when something goes wrong)."""


def build_parser() -> argparse.ArgumentParser:
    """The argument parser for `arbor` and its subcommands."""
    parser = argparse.ArgumentParser(prog="arbor", description="Grow and model 3D trees.", epilog=EPILOG,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command")
    derive = sub.add_parser("derive", help="print the L-string an .lsys source derives")
    _add_growth_args(derive)
    derive.set_defaults(run=_cmd_derive)
    render = sub.add_parser("render", help="render a tree (.lsys or a save) to PNG without a window")
    _add_growth_args(render, saves=True)
    render.add_argument("--size", type=_size, default=(1280, 720))
    render.add_argument("--yaw", type=float, default=30.0)
    render.add_argument("--pitch", type=float, default=12.0)
    render.add_argument("--lod", type=_bounded(0, MAX_LOD, "--lod"), default=0, help="level of detail 0-3")
    render.add_argument("--out", type=Path, default=Path("tree.png"), metavar="FILE.png",
                        help="the picture to write (default tree.png)")
    render.add_argument("--scale-bar", type=_metres("--scale-bar"), nargs="?", const=0.0, default=None,
                        metavar="METRES", help="frame METRES high round the trunk (the same for every tree "
                        "rendered so: one shared scale; default: the tree's height rounded up to a whole metre) "
                        "and draw a metre bar")
    render.set_defaults(run=_cmd_render)
    export = sub.add_parser("export", help="export a tree (.lsys or a save) as GLB or OBJ+MTL")
    _add_growth_args(export, saves=True)
    export.add_argument("--format", choices=("glb", "obj"), default=None, help="default: from --out's suffix")
    export.add_argument("--lod", type=_bounded(0, MAX_LOD, "--lod"), default=0, help="level of detail 0-3")
    export.add_argument("--lods", action="store_true", help="every level of detail in one GLB, from --lod to 3 "
                        "(nodes NAME_LOD0, NAME_LOD1, ...: the suffix engines group levels by)")
    export.add_argument("--out", type=Path, default=Path("tree.glb"), metavar="FILE",
                        help="NAME.glb, or NAME.obj (with NAME.mtl and NAME_bark.png ... beside it; default tree.glb)")
    size = export.add_mutually_exclusive_group()
    size.add_argument("--height", type=_metres("--height"), default=None, metavar="METRES",
                      help="scale the tree to this height in metres, the top of its wood (for sources of any unit)")
    size.add_argument("--scale", type=_metres("--scale"), default=None, metavar="METRES",
                      help=f"metres per scene unit (default: the source's 'unit:', else {1 / METRE:g}: the game's "
                      f"{METRE:g} units = 1 m)")
    export.set_defaults(run=_cmd_export)
    lab = sub.add_parser("lab", help="educators' lab: run an experiment (window, or --out DIR headless)")
    lab.add_argument("experiment", type=Path, help="experiment .toml (see assets/experiments)")
    lab.add_argument("--out", type=Path, default=None, help="write CSV, PNG charts and saves here, no window")
    lab.add_argument("--build", action="store_true", help="the experiment builder: set up a sweep in FILE with the "
                     "mouse (a new file, or one to change), save it and run it with its progress shown")
    lab.set_defaults(run=_cmd_lab)
    sweep = sub.add_parser("sweep", help="educators: many headless runs (factors x seeds) -> CSVs and plots")
    sweep.add_argument("sweep", type=Path, help="sweep .toml (see assets/experiments/sweep_*.toml)")
    sweep.add_argument("--out", type=Path, required=True, help="folder for runs, CSVs and figures (resumable)")
    sweep.add_argument("--workers", type=_bounded(1, 256, "--workers"), default=None,
                       help="worker processes (default: every core)")
    sweep.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help="run on an existing Dask cluster, e.g. tcp://10.0.0.5:8786 "
                       "(pip install 'arbor-trees[cluster]')")
    sweep.add_argument("--no-plots", action="store_true", help="CSV tables only")
    sweep.add_argument("--keep", choices=("all", "first", "none"), default="first",
                       help="final trees saved in DIR/trees, named by level and seed: every seed, each level's "
                            "first seed (default) or none; docs/columns.md documents the CSV columns")
    sweep.set_defaults(run=_cmd_sweep)
    comp = sub.add_parser("compare", help="educators: merge several students' sweep folders into one table and "
                          "figure (they must have run the same sweep file; seeds may differ)")
    comp.add_argument("folders", type=Path, nargs="+", metavar="DIR", help="arbor sweep --out folders, the first "
                      "the reference (the teacher's); each folder's name is its student's")
    comp.add_argument("--out", type=Path, required=True, help="folder for class.csv and the class figure")
    comp.add_argument("--no-plots", action="store_true", help="the table only")
    comp.set_defaults(run=_cmd_compare)
    sheet = sub.add_parser("worksheet", help="educators: a printable worksheet for a lesson (question, prediction, "
                           "setup, an empty chart, discussion, an answer key from a real run)")
    sheet.add_argument("lesson", help="light, water, competition or pruning (docs/teaching.md)")
    sheet.add_argument("--out", type=Path, required=True, help="the sheet: NAME.html (one page to print) or NAME.pdf "
                       "(A4 pages); a sweep lesson's runs are kept beside it in NAME_runs/")
    sheet.add_argument("--seeds", type=_bounded(1, 50, "--seeds"), default=3,
                       help="seeds of the answer key's run (default 3; the lesson's own file has 6-8)")
    sheet.add_argument("--workers", type=_bounded(1, 256, "--workers"), default=None,
                       help="worker processes for the answer key's runs (default: every core)")
    sheet.set_defaults(run=_cmd_worksheet)
    land = sub.add_parser("landscape", help="render a landscape of many trees (instancing, LOD, culling)")
    land.add_argument("trees", type=_bounded(1, MAX_TREES, "the number of trees"),
                      help=f"number of trees, 1-{MAX_TREES:,}")
    land.add_argument("--size", type=_size, default=(1280, 720))
    land.add_argument("--seed", type=_bounded(0, 2**63 - 1, "--seed"), default=0)
    land.add_argument("--lod", type=_bounded(0, MAX_LOD, "--lod"), default=None,
                      help="force one level 0-3 (default: by distance)")
    land.add_argument("--out", type=Path, default=Path("landscape.png"), metavar="FILE.png",
                      help="the picture to write (default landscape.png)")
    land.add_argument("--glb", type=Path, default=None, help="also export the trees as one GLB (shared meshes)")
    land.add_argument("--presets", default="abop_2_8_tree:4,abop_2_6_monopodial:7,broadleaf,weeping",
                      help="comma-separated: LSYS_NAME[:STEPS] or a species from assets/presets")
    land.set_defaults(run=_cmd_landscape)
    breed = sub.add_parser("breed", help="cross the trees of two saves into a child's save")
    breed.add_argument("a", type=Path, help="the mother's save (.arbor)")
    breed.add_argument("b", type=Path, help="the father's save (.arbor)")
    breed.add_argument("--seed", type=_bounded(0, 2**63 - 1, "--seed"), default=0,
                       help="the same parents and seed give the same child")
    breed.add_argument("--tree-a", type=_bounded(0, 5, "--tree-a"), default=None, help="tree of a (default: cared-for)")
    breed.add_argument("--tree-b", type=_bounded(0, 5, "--tree-b"), default=None, help="tree of b (default: cared-for)")
    breed.add_argument("--out", type=Path, default=Path("child.arbor"), metavar="FILE.arbor",
                       help="the child's save to write (default child.arbor)")
    breed.set_defaults(run=_cmd_breed)
    lineage = sub.add_parser("lineage", help="print the family tree of a save's trees")
    lineage.add_argument("save", type=Path)
    lineage.set_defaults(run=_cmd_lineage)
    view = sub.add_parser("view", help="open a window showing an .lsys tree (drag, wheel, space)")
    view.add_argument("source", type=Path)
    view.set_defaults(run=lambda a: __import__("arbor.game.app", fromlist=["run_viewer"]).run_viewer(a.source))
    card = sub.add_parser("card", help="share a tree as a postcard PNG that carries its save (arbor import reads it)")
    card.add_argument("save", type=Path, help="the save (.arbor) the tree is in")
    card.add_argument("--tree", type=_bounded(0, 5, "--tree"), default=None, help="which tree (default: cared-for)")
    card.add_argument("--out", type=Path, default=Path("tree.png"), metavar="FILE.png",
                      help="the postcard to write (default tree.png)")
    card.set_defaults(run=_cmd_card)
    imp = sub.add_parser("import", help="plant the tree of a postcard PNG (arbor card) in your garden")
    imp.add_argument("card", type=Path, help="the postcard (.png)")
    imp.set_defaults(run=_cmd_import)
    sub.add_parser("watchdog", help="arbor watchdog ARGS...: keep `arbor ARGS...` running (restarts it when it "
                   "crashes or hangs; for kiosks: arbor watchdog --kiosk; arbor watchdog --help says more)")
    _add_global_options(parser, here=True)
    for name, command in sub.choices.items():
        _add_global_options(command, here=False, inputs=name in WINDOWS)
    parser.add_argument("--version", action="version", version=f"arbor {_version()}")
    return parser


COMPILING = ("render", "export", "landscape", "lab", "sweep", "view", "card", "import",
             "worksheet")  # use numba kernels
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2  # argparse exits with EXIT_USAGE for bad arguments
EXIT_INTERRUPTED = 130  # Ctrl-C (SIGINT) before a window or a command handled it: 128 + 2, as shells report it


def _version() -> str:
    """The installed distribution's version (what `arbor --version` prints)."""
    from arbor.engine.base.version import version

    return version()


INPUTS = ("source", "experiment", "sweep", "save", "card")  # the argument names of files a command reads
OUTPUTS = ("out", "glb")  # ... and of files it writes (lab's and sweep's --out are folders, made by them)


def check_files(args: argparse.Namespace) -> None:
    """Before anything slow: every file the command reads is there and a plain file, every file it writes
    has its folder, and an .lsys source parses (an OSError, LSysError or UserError naming the file)."""
    import errno

    for name in INPUTS:
        path = getattr(args, name, None)
        if isinstance(path, Path) and getattr(args, "build", False) and not path.exists():
            continue  # (the builder makes the file it is given)
        if isinstance(path, Path):
            if path.is_dir():
                raise UserError(f"{path}: is a folder; give a file")
            with open(path, "rb"):  # FileNotFoundError / PermissionError name it
                pass
            if path.suffix.lower() == ".lsys":
                from arbor.engine.forest.geomatree import load_grown

                load_grown(path, getattr(args, "species", None))
    if args.command in ("lab", "sweep"):
        return
    for name in OUTPUTS:
        path = getattr(args, name, None)
        if isinstance(path, Path) and not path.absolute().parent.is_dir():
            raise FileNotFoundError(errno.ENOENT, f"no such folder (to write {path.name} in)", str(path.parent))


def watchdog_help() -> str:
    """What `arbor watchdog --help` prints: the watchdog's own behaviour and its limits (the watched app's
    options are `arbor --help`'s)."""
    from arbor.game import watchdog as w

    return (f"usage: arbor watchdog [ARBOR OPTIONS...]\n\n"
            f"Keep `arbor ARBOR OPTIONS...` running: start it again whenever it crashes or hangs (for kiosks:\n"
            f"arbor watchdog --kiosk; docs/kiosk.md has a systemd unit). Every option after `watchdog` is the\n"
            f"watched app's (arbor --help lists them).\n\n"
            f"  start-up grace   {w.START_GRACE:g} s for the app's first heartbeat\n"
            f"  hang time        no heartbeat for {w.HANG_SECONDS:g} s after that: killed and restarted\n"
            f"  restarts         after 1 s, 2 s, 4 s, ... at most 30 s while crashes come quickly; back to 1 s\n"
            f"                   after a run of over a minute\n"
            f"  crash loop       {w.CRASH_LOOP} runs in a row shorter than {w.YOUNG:g} s: the file the app was\n"
            f"                   reading when it died (a settings file, a save) is set aside as NAME.crashed,\n"
            f"                   and the log says which, so a bad file cannot keep it down\n"
            f"  stops when       staff quit the kiosk with the PIN (status {w.STAFF_EXIT}), the app refuses its\n"
            f"                   arguments (status {w.USAGE_EXIT}), the home game quits cleanly (0), or the\n"
            f"                   watchdog gets SIGTERM, SIGINT or SIGHUP (passed on: the app saves and exits)")


def _failure(err: BaseException) -> str:
    """The one line a user sees for a failure they can fix (a bad file, a folder, a size too large)."""
    if isinstance(err, OSError) and not isinstance(err, LSysError):
        return f"arbor: {err.filename or ''}: {err.strerror}"
    if isinstance(err, MemoryError):
        return "arbor: not enough memory for that: ask for fewer steps, a smaller budget or fewer trees"
    return f"arbor: {err}"


def _quiet_broken_pipe() -> int:
    """The reader of our output went away (``arbor derive ... | head``): end without a word."""
    import os

    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())  # Python's own flush at exit would fail again
    return EXIT_FAILED


def _exit_now(status: int) -> None:
    """End the process as soon as the game has saved and closed its window: Python's own teardown of numba,
    LLVM and the GL modules takes most of a second and shows nothing."""
    import logging
    import os

    logging.shutdown()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(status)


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `arbor` console script: user errors end in one line naming what to fix.

    Exit status: 0 done, 1 a failure at run time (bad or missing file, no memory, broken pipe), 2 a usage
    error (bad arguments; argparse's own status); the kiosk's staff quit is 3 (game/watchdog.py); 130 Ctrl-C
    before the work's own stop handling was up."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["watchdog"]:  # everything after it belongs to the watched app
        if argv[1:] in (["-h"], ["--help"]):
            print(watchdog_help())
            return EXIT_OK
        from arbor.game.watchdog import main as watchdog

        return watchdog(argv[1:])
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.quiet and args.verbose:
        parser.error("-q/--quiet and -v/--verbose ask for opposite things: give one of them")
    keep_freed_memory()
    set_level(args.quiet, args.verbose)
    try:
        if args.command is None:
            from arbor.game.app import run_app, run_kiosk

            if args.kiosk:
                return run_kiosk(args)
            _exit_now(run_app(args))
        if args.command in COMPILING:
            from arbor.game.first_start import headless_notice

            check_files(args)  # a mistyped name is told at once, not after a first start's compile
            headless_notice(quiet=args.quiet)
        started = time.perf_counter()
        status = args.run(args)
        detail(f"arbor {args.command}: {time.perf_counter() - started:.1f} s")
        sys.stdout.flush()  # a broken pipe shows here, inside the try, not at interpreter exit
        return status
    except BrokenPipeError:
        return _quiet_broken_pipe()
    except KeyboardInterrupt:  # Ctrl-C before a window's own signal handling is up: one line, no traceback
        print("arbor: stopped (Ctrl-C)", file=sys.stderr)
        return EXIT_INTERRUPTED
    except (LSysError, OSError, UserError, MemoryError) as err:
        print(_failure(err), file=sys.stderr)
        return EXIT_FAILED


if __name__ == "__main__":
    sys.exit(main())
