"""The tree a headless command works on: grown from an .lsys source, or read from a save (.arbor)."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.geometry.mesh import lod_level, merge_trees, tree_mesh
from arbor.engine.geometry.tree import TreeGeometry, build_geometry
from arbor.engine.life.keep.save import read_garden
from arbor.engine.lsystem.derive import DEFAULT_BUDGET, MAX_BUDGET, Deriver
from arbor.engine.lsystem.lstring import LString
from arbor.engine.lsystem.lsys import LSystem
from arbor.game.errors import UserError


@dataclass
class TreeSource:
    """What the command was asked for: the source file and how to grow or pick the tree."""

    path: Path
    steps: int | None = None
    seed: int | None = None
    budget: int | None = None
    tree: int = 0  # which tree of a garden save
    species: str | None = None  # the GeoMaTree species a source asking for its functions grows as


def is_save(path: Path) -> bool:
    """True for save files (.arbor), which hold grown trees rather than rules to grow one."""
    return path.suffix.lower() == ".arbor"


def scene_metres(source: TreeSource) -> float:
    """Metres per scene unit of the tree this source grows: the .lsys file's declared ``unit:``, else the
    game's scene metre (saves and sources without one)."""
    from arbor.engine.base.units import METRE

    unit = None if is_save(source.path) else load_source(source).unit
    return unit if unit is not None else 1.0 / METRE


TALLEST, SHORTEST = 100.0, 0.01  # metres: an export outside these is likely a unit mistake (a warning says so)


def size_warning(height_m: float) -> str | None:
    """The warning for a tree of ``height_m`` metres outside TALLEST..SHORTEST, else None."""
    if SHORTEST <= height_m <= TALLEST:
        return None
    what = f"over {TALLEST:g} m" if height_m > TALLEST else f"under {SHORTEST * 100:g} cm"
    return (f"arbor: warning: the tree is {height_m:.3g} m tall ({what}): if its source is in another unit, "
            "give --height METRES, or declare 'unit: METRES_PER_UNIT' in the .lsys")


def load_source(source: TreeSource) -> LSystem:
    """The .lsys source as it will grow: GeoMaTree's functions supplied from ``source.species`` when it asks
    for them (engine/forest/geomatree.load_grown)."""
    from arbor.engine.forest.geomatree import load_grown

    return load_grown(source.path, source.species, source.seed or 0)


DERIVE_SECONDS = 30.0  # a command's derivation stops before a step that would end later than this
DERIVE_MEMORY = 1024**3  # bytes a command's derivation may use at most (its module budget is cut to fit)
DERIVE_MODULE_BYTES = 110  # a module's peak share while rewriting (measured: 72 B plain, 104-105 B with
# parameters at 4M modules; 20M modules with one parameter peaked at 2.08 GB)


def derive_budget(system: LSystem, source: TreeSource, most: int | None = None) -> tuple[int, str]:
    """The module budget a command derives ``source`` with, estimated before any work: the asked-for
    one (--budget, the file's budget:, else the default, at most MAX_BUDGET), cut to what DERIVE_MEMORY
    holds and to ``most`` (what the caller can afford: a render's or an export's mesh); and a line saying
    why when cut (:func:`derive_source` says it when the cut budget held growth back)."""
    asked = source.budget if source.budget is not None else system.budget if system.budget is not None \
        else DEFAULT_BUDGET
    asked = min(int(asked), MAX_BUDGET)
    budget, why = asked, ""
    if asked * DERIVE_MODULE_BYTES > DERIVE_MEMORY:
        budget = DERIVE_MEMORY // DERIVE_MODULE_BYTES
        why = (f"module budget {asked:,} would need about {asked * DERIVE_MODULE_BYTES / 1024**3:.1f} GB to "
               f"derive, over the limit of {DERIVE_MEMORY / 1024**3:.0f} GB: growing to {budget:,} modules at most")
    if most is not None and most < budget:
        budget = max(int(most), 1)
        why = (f"growing to {budget:,} modules at most (what a picture's or a mesh's memory limit of "
               f"{RENDER_MEMORY / 1024**3:.1f} GB holds at this --lod)")
    return budget, why


def _watched(step, progress, asked: int, budget: int, after: Callable[[int], float]):
    """``step`` (a Deriver's) reporting to ``progress`` after each step: seconds so far, and an estimate of
    the whole: the steps left at the last step's time grown as the string grows (up to ``budget`` modules;
    within DERIVE_SECONDS), then ``after(modules)``, the stages that follow (meshing, writing)."""
    started, taken = time.perf_counter(), [0]

    def watched(ls, *args, **kwargs):
        begun = time.perf_counter()
        result, report = step(ls, *args, **kwargs)
        taken[0] += 1
        last, now = time.perf_counter() - begun, time.perf_counter() - started
        growth = max(report.modules_out / max(report.modules_in, 1), 1.0)
        modules, left = float(report.modules_out), 0.0
        for _ in range(asked - taken[0]):  # (at the budget a step still takes its time: it grows no more)
            if modules < budget:
                modules, last = min(modules * growth, budget), last * growth
            left += last
            if left >= DERIVE_SECONDS:
                break
        left = min(left, max(DERIVE_SECONDS - now, 0.0))
        progress.to(now, f"deriving: step {taken[0]} of {asked:,}", total=now + left + after(int(modules)))
        return result, report

    return watched


def derive_source(source: TreeSource, most: int | None = None, progress=None,
                  after: Callable[[int], float] = lambda modules: 0.0):
    """Grow an .lsys source: (system, L-string), bounded in memory (:func:`derive_budget`, estimated before
    the work starts) and time (DERIVE_SECONDS); says on stderr, in one line each, when a bound held growth
    back. ``progress`` (game/progress.Progress) hears of each step, ``after`` estimates the seconds the
    caller's later stages take for the modules grown."""
    system = load_source(source)
    if system.externs:
        names = ", ".join(system.externs)
        raise LSysError(f"this L-system needs values from the game at every step (#extern {names}); "
                        "grow it in the game and render its save (.arbor) instead", str(source.path))
    budget, why = derive_budget(system, source, most)
    deriver = Deriver(system, seed=source.seed, budget=budget, seconds=DERIVE_SECONDS)
    asked = system.iterations if source.steps is None else source.steps
    if progress is not None:
        deriver.step = _watched(deriver.step, progress, asked, deriver.budget, after)
    result, reports = deriver.derive(steps=asked)
    if why and any(r.budget_hit for r in reports):  # (said only when the cut budget held growth back)
        print(why, file=sys.stderr)
    if deriver.out_of_time:
        print(f"time budget {DERIVE_SECONDS:.0f} s reached at step {len(reports)} of {asked:,}: derivation stopped "
              f"there ({len(result):,} modules; ask for fewer --steps)", file=sys.stderr)
    elif reports and reports[-1].only_copied and len(reports) < asked:
        print(f"module budget {deriver.budget:,} full at step {len(reports)} of {asked:,}: derivation stopped "
              f"there ({len(result):,} modules; every further step would only copy them)", file=sys.stderr)
    elif any(r.budget_hit for r in reports):
        held = sum(r.deferred for r in reports)
        print(f"module budget {deriver.budget:,} reached: {held:,} rewrites held back", file=sys.stderr)
    return system, result


RENDER_MEMORY = 2 * 1024**3  # bytes a headless render may use at most (the picture and the tree's mesh)
RENDER_BASE = 300 * 1024**2  # the process, numba and the GL context before any picture or tree
PIXEL_BYTES = 48  # a pixel: 4x multisampled colour and depth, the resolved copy, the read-back and the PNG
MODULE_BYTES = (4800, 700, 300, 200)  # a module's share of the mesh at LOD 0..3 (measured on abop_2_8_tree; at
# LOD 0 a parametric A(x) -> A(x+1)F[A(x*2)] tree took 4.3 KB a module: 2.43 GB at 497k modules)


def render_modules(size: tuple[int, int], lod: int) -> int:
    """The most modules a tree rendered at LOD ``lod`` into ``size`` pixels may have within RENDER_MEMORY
    (so a render derives no further than it could draw: it derived for 204 s to 1.93 GB, then refused);
    ``size`` (0, 0): the mesh alone (an export)."""
    room = RENDER_MEMORY - RENDER_BASE - size[0] * size[1] * PIXEL_BYTES
    return max(room // MODULE_BYTES[min(lod, len(MODULE_BYTES) - 1)], 1)


def render_memory(size: tuple[int, int], modules: int, lod: int) -> int:
    """About how many bytes rendering a tree of ``modules`` modules at LOD ``lod`` into a picture of
    ``size`` pixels takes (measured: 45 B a pixel, 3.5 KB a module at LOD 0, 170 B at LOD 3)."""
    return RENDER_BASE + size[0] * size[1] * PIXEL_BYTES + modules * MODULE_BYTES[min(lod, len(MODULE_BYTES) - 1)]


def check_render_memory(size: tuple[int, int], modules: int, lod: int) -> None:
    """Refuse, in one line naming the limit, a render that would need more than RENDER_MEMORY (checked
    before the mesh is built or the GL picture allocated: 8192x8192 alone would take 3.2 GB)."""
    need = render_memory(size, modules, lod)
    if need > RENDER_MEMORY:
        tree = f" of a tree of {modules:,} modules at --lod {lod}" if modules else ""
        raise UserError(f"rendering {size[0]}x{size[1]} pixels{tree} needs about {need / 1024**3:.1f} GB, "
                        f"over the limit of {RENDER_MEMORY / 1024**3:.0f} GB: "
                        "ask for a smaller --size, fewer --steps or a higher --lod")


def _meshing(progress, modules: int):
    """The meshing stage of ``progress`` (its measured seconds a module), or nothing without one."""
    from contextlib import nullcontext

    from arbor.game.progress import MESH_PER_MODULE

    if progress is None:
        return nullcontext()
    return progress.timed(f"meshing {modules:,} modules", modules * MESH_PER_MODULE)


def tree_geometry(source: TreeSource, lod: int, roots: bool = False,
                  check: Callable[[int], None] | None = None, most: int | None = None, progress=None,
                  after: Callable[[int], float] = lambda modules: 0.0) -> tuple[TreeGeometry, LString]:
    """The geometry of the asked-for tree at LOD ``lod``: exactly as it stands in a save (with its
    roots below the ground when ``roots``: exports carry them), or derived (to at most ``most`` modules).
    ``check`` is called with the tree's module count before the geometry is built (a budget that may
    refuse it). ``progress`` hears of the derivation and the meshing; ``after(modules)`` estimates the
    seconds of the caller's stages after them."""
    from arbor.game.progress import MESH_PER_MODULE

    if is_save(source.path):
        if source.steps is not None or source.budget is not None:
            raise LSysError("--steps and --budget grow an .lsys source; a save holds a grown tree", str(source.path))
        worlds = read_garden(source.path).worlds
        if not 0 <= source.tree < len(worlds):
            raise LSysError(f"--tree {source.tree}: this save holds {len(worlds)} tree(s), numbered from 0",
                            str(source.path))
        world = worlds[source.tree]
        modules = len(world.tree.lstring)
        if check is not None:
            check(modules)
        if progress is not None:
            progress.to(0.0, total=modules * MESH_PER_MODULE + after(modules))
        with _meshing(progress, modules):
            geometry = world.tree.geometry(world.clocks(), lod)
            if roots:
                below = tree_mesh(world.roots.turtle(), lod_level(lod))
                geometry.mesh = merge_trees([geometry.mesh, below], [np.zeros(3), np.zeros(3)])
        return geometry, world.tree.lstring
    system, ls = derive_source(source, most, progress, lambda modules: modules * MESH_PER_MODULE + after(modules))
    if check is not None:
        check(len(ls))
    with _meshing(progress, len(ls)):
        return build_geometry(ls, system, lod=lod), ls
