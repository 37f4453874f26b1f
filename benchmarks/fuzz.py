"""Fuzz campaign: hostile saves, .lsys sources, TUIO packets and every other file a user can hand us
through the real load paths.

Run: python -m benchmarks.fuzz [SAVES] [LSYS] [OSC] [FILES] [--seed N] [--keep DIR]
(defaults 10000 10000 2000 10000; FILES: benchmarks/fuzz_files.py, each stopped at FILE_HANG_SECONDS)
Every case goes through what the game does with such input (a save: load, then geometry and a little
catch-up, then the game's own save of it, which must load back to the same bytes; an .lsys: parse,
derive under the budget, geometry; a packet: the TUIO parser). A case
passes when it works or ends in the error meant for users (SaveError / LSysError, nothing for OSC).
Prints cases, uncaught exceptions (with the first few), cases slower than 5 s and peak RSS. The
suite runs the same mutators on fewer cases (tests/test_fuzz.py).
"""

from __future__ import annotations

import functools
import hashlib
import random
import re
import resource
import signal
import sys
import time
import tomllib
import traceback
from pathlib import Path
from tempfile import TemporaryDirectory

import numpy as np

from arbor.engine.base.errors import LSysError
from arbor.engine.geometry.tree import build_geometry
from arbor.engine.life.keep.save import SavedGarden, garden_text, read_garden, write_garden
from arbor.engine.life.rules.rules import load_rules
from arbor.engine.life.world.actions import Action
from arbor.engine.life.world.world import World
from arbor.engine.lsystem.derive import Deriver
from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem

ROOT = Path(__file__).resolve().parent.parent
LSYSTEMS = ROOT / "assets" / "lsystems"
NASTY_NUMBERS = ["1e400", "-1e400", "nan", "inf", "-1", "0", "1e308", "-1e308", "10000000000000000000000000",
                 "2.5", '"x"', "true", "[]", "{}", "-0.0", "1e-320", "99999999999", "-99999999999"]
EDGE_NUMBERS = ["1e12", "999999999999", "1000000000001", "9007199254740992", "9007199254740993", "4294967296",
                "9223372036854775807", "1e-300", "5e-324", "0.0", "1"]  # at and just past the reader's bounds
EDGE_LSTRINGS = ["F", "F(1e12)", "F(1e12,1e12)", "I(0,0,1e12,0,1e12)", "I(1e12,1e12,0,0,0)", "A(1e12,0,0,1,0,0)",
                 "[" * 5000 + "]" * 5000, "F[" * 3000 + "]" * 3000, "L(0,1e12,0)", "O(-1e12)", "K(1e12)", "F(0)" * 5000]
LSTRING_BLOCK = re.compile(r"lstring = '''\n.*?'''", re.S)
NASTY_TEXT = ["[", "]", "(", ")", ",", "\\", '"', "'''", "\x00", "é", "\ufeff", "((((((((", "--------", "%", "ε",
              "->", ":", "#define", "F(", "1e999", "nan", "A(1,2,3,4,5,6,7,8,9)", "[[[[", "]]]]"]


SOURCE_BLOCK = re.compile(r'lsystem_source = """\n(.*?)"""', re.S)


def hostile_edit(text: str, rng: random.Random) -> str:
    """One edit aimed at the load-time budgets (what made loads slow): a flooded journal or family, an
    embedded .lsys with a long axiom or a huge module budget (its hash made to match, as a hostile
    file can), a tree much larger than its budget."""
    kind = rng.randrange(5)
    if kind == 0:  # a journal of many rows (a 33 MB one took 65 s in TOML)
        rows = '[1.0, "height", 2.0], ' * rng.choice([500, 20_000, 300_000])
        return text.replace("entries = [", "entries = [" + rows, 1)
    if kind == 1:  # a family of many members (lineage entries)
        row = '{id = "a", parents = [], generation = 0, seed = 1, planted = 0.0, species = "x"},'
        return text.replace("\n[[trees]]", "\nfamily = [" + row * rng.choice([100, 5_000, 50_000]) + "]\n[[trees]]", 1)
    if kind == 4:  # far more modules than any budget
        n = rng.choice([30_000, 200_000])
        text = LSTRING_BLOCK.sub(lambda _: "lstring = '''\n" + "F(1)[L(1,1,0)]" * (n // 3) + "'''", text, count=1)
        return re.sub(r"(?m)^modules = \d+$", f"modules = {n}", text, count=1)
    try:
        source = tomllib.loads(text)["trees"][0]["lsystem_source"]
    except (tomllib.TOMLDecodeError, KeyError, IndexError, TypeError):
        return text
    if kind == 2:  # a long axiom (its parse evaluates every module)
        source = re.sub(r"(?m)^w: .*$", lambda m: m.group(0) + " F(1,2)[+(3)A(4)]" * rng.choice([100, 700, 3000]),
                        source, count=1)
    else:  # a huge module budget, so the tree's size limit would be huge too
        source = re.sub(r"(?m)^budget: \d+", "budget: 20000000", source)
    from arbor.engine.life.keep.save import _toml_text

    digest = hashlib.sha256(source.encode("utf-8")).hexdigest()
    text = SOURCE_BLOCK.sub(lambda _: "lsystem_source = " + _toml_text(source), text)
    return re.sub(r'lsystem_sha256 = "[0-9a-f]+"', f'lsystem_sha256 = "{digest}"', text)


def mutate_text(text: str, rng: random.Random) -> str:
    """One to three random edits: swap a number for a nasty one, insert nasty text, drop or duplicate a
    line, flip a byte, truncate; or (one case in twenty) an edit aimed at the load-time budgets."""
    if "[[trees]]" in text and rng.random() < 0.05:
        return hostile_edit(text, rng)
    for _ in range(rng.randint(1, 3)):
        op = rng.randrange(8)
        if op in (0, 6):  # a nasty number, or one at the edge of a range
            numbers = list(re.finditer(r"-?\d+(\.\d+)?(e[-+]?\d+)?", text))
            if numbers:
                m = rng.choice(numbers)
                text = text[:m.start()] + rng.choice(NASTY_NUMBERS if op == 0 else EDGE_NUMBERS) + text[m.end():]
        elif op == 7 and LSTRING_BLOCK.search(text):  # a whole L-string at the edges: bare F, F(1e12), nesting
            text = LSTRING_BLOCK.sub(lambda _: "lstring = '''\n" + rng.choice(EDGE_LSTRINGS) + "'''", text, count=1)
        elif op == 1:
            at = rng.randrange(len(text) + 1)
            text = text[:at] + rng.choice(NASTY_TEXT) * rng.choice([1, 1, 3, 200]) + text[at:]
        elif op in (2, 3):
            lines = text.split("\n")
            k = rng.randrange(len(lines))
            lines[k:k + 1] = [] if op == 2 else [lines[k], lines[k]]
            text = "\n".join(lines)
        elif op == 4 and text:
            at = rng.randrange(len(text))
            text = text[:at] + chr(rng.randrange(1, 0x250)) + text[at + 1:]
        elif text:
            text = text[: rng.randrange(len(text))]
    return text


def sample_garden_text(trees: int = 2) -> str:
    """A real save of a small garden (the starting point of save mutations)."""
    system = load_lsystem(LSYSTEMS / "game_tree.lsys")
    rules = load_rules(ROOT / "assets" / "rules.toml", pace="demo")
    worlds = []
    for k in range(trees):
        world = World(system, rules, seed=k + 1)
        world.sim.state.sun_meter = world.sim.state.water_meter = 0.9
        for _ in range(400):
            world.apply(Action.WATER, float(world.sim.state.water_meter < 0.6))
            world.step(0.5)
        world.position = (7.0 * k, 0.0)
        worlds.append(world)
    return garden_text(SavedGarden(worlds, 0, 1.7e9))


def try_save(text: str, folder: Path) -> str:
    """What the game does with a save file: load it, grow it a little (journal, light, shedding), build
    its geometry, then save it and check the save's own round trip (load it back, save again: the same
    bytes). Returns "refused" or "loaded"; raises only if that path has a bug (SaveError is the expected
    answer to a bad file), :class:`RoundTripError` when the game could not read back what it wrote."""
    path = folder / "fuzz.arbor"
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    rules = _rules()
    try:
        saved = read_garden(path, rules)
    except LSysError:
        return "refused"
    for world in saved.worlds:
        world.catch_up(30.0)
        world.tree.geometry(world.clocks())
    again = folder / "again.arbor"
    write_garden(saved, again)
    first = again.read_bytes()
    try:
        write_garden(read_garden(again, rules), again)
    except LSysError as err:
        raise RoundTripError(f"the game refused its own save: {err}") from None
    if again.read_bytes() != first:
        raise RoundTripError("save -> load -> save changed the file")
    return "loaded"


class RoundTripError(AssertionError):
    """An accepted save whose own save does not read back the same (the writer and reader disagree)."""


@functools.lru_cache(maxsize=1)
def _rules():
    return load_rules(ROOT / "assets" / "rules.toml", pace="demo")


def sample_sources() -> list[str]:
    """Every .lsys file we ship (the starting points of source mutations)."""
    return [p.read_text(encoding="utf-8") for p in sorted(LSYSTEMS.glob("*.lsys"))]


def try_source(text: str) -> None:
    """Parse, derive a few steps under a small budget, build geometry (if it can run alone)."""
    try:
        system = parse_lsystem(text, "fuzz.lsys")
    except LSysError:
        return
    if system.externs or system.host:
        return
    deriver = Deriver(system, budget=20_000)
    ls, _ = deriver.derive(steps=min(system.iterations, 6))
    build_geometry(ls, system, lod=2)


def random_packet(rng: random.Random) -> bytes:
    """A TUIO-like OSC datagram: valid messages with wrong argument types and ranges, or garbage."""
    from pythonosc.osc_bundle_builder import IMMEDIATELY, OscBundleBuilder
    from pythonosc.osc_message_builder import OscMessageBuilder

    if rng.random() < 0.3:
        return bytes(rng.randrange(256) for _ in range(rng.choice([0, 1, 7, 16, 64, 300])))
    bundle = OscBundleBuilder(IMMEDIATELY)
    for _ in range(rng.randint(1, 4)):
        msg = OscMessageBuilder(address=rng.choice(["/tuio/2Dcur", "/tuio/2Dobj", "/x"]))
        msg.add_arg(rng.choice(["set", "alive", "fseq", "source", 5]))
        for _ in range(rng.randint(0, 7)):
            msg.add_arg(rng.choice([rng.randint(-2**31, 2**31 - 1), rng.random(), float("nan"), float("inf"),
                                    -1.0, 2.5, "sid", True, b"\x00\x01", 0, 1]))
        bundle.add_content(msg.build())
    data = bundle.build().dgram
    if rng.random() < 0.3:  # truncated or bit-flipped
        data = bytearray(data[: rng.randrange(1, len(data) + 1)])
        if data:
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        data = bytes(data)
    return data


def try_packet(parser, data: bytes) -> None:
    """Feed one datagram to the TUIO parser (it must never raise)."""
    parser.packet(data, 0.0)


class HangError(Exception):
    """A case that ran past HANG_SECONDS (the alarm stopped it)."""


HANG_SECONDS = 60.0  # a case is stopped here and counted as a hang
FILE_HANG_SECONDS = 10.0  # a file case (fuzz_files) is a hang past this: issue 45's bound
SLOW_SECONDS = 5.0  # a case slower than this is counted (and kept with --keep): the bound on a start


def _alarm(signum, frame):
    raise HangError()


def _file_maker(rng: random.Random, base_save: str, folder: Path):
    """The file cases' maker and runner (benchmarks/fuzz_files.py): (make(), run(case))."""
    import io

    from PIL import Image

    from arbor.engine.life.keep.card import card_bytes
    from benchmarks import fuzz_files

    (folder / "card-base.arbor").write_text(base_save, encoding="utf-8")
    png = io.BytesIO()
    Image.new("RGB", (16, 16), (40, 90, 40)).save(png, "PNG")
    card = card_bytes(png.getvalue(), read_garden(folder / "card-base.arbor", _rules()))
    bases, read, cases = fuzz_files.samples(), fuzz_files.readers(), folder / "files"
    cases.mkdir()

    def make():
        if rng.randrange(fuzz_files.DERIVE_EVERY) == 0:
            return fuzz_files.heavy_case(rng)
        return fuzz_files.make_case(rng, bases, base_save, card, mutate_text)

    def run(case):
        return fuzz_files.try_heavy(case) if case[0] == "derive" else fuzz_files.try_file(case, cases, read)
    return make, run


def campaign(n_saves: int, n_lsys: int, n_osc: int, n_files: int = 0, seed: int = 0,
             keep: Path | None = None) -> int:
    """Run the whole campaign; prints the figures and returns the number of uncaught exceptions, hangs
    and failed round trips. ``keep``: a folder where every failing case is written (to replay it)."""
    from arbor.game.input.tuio import TuioParser

    rng = random.Random(seed)
    failures, slow, slowest = [], 0, []
    outcomes = {"loaded": 0, "refused": 0, "round trip": 0, "hang": 0, "read": 0, "derived": 0, "file refused": 0}
    base_save, sources, parser = sample_garden_text(), sample_sources(), TuioParser((1280, 720))
    signal.signal(signal.SIGALRM, _alarm)
    with TemporaryDirectory() as tmp:
        cases = [("save", n_saves), ("lsys", n_lsys), ("osc", n_osc), ("file", n_files)]
        make_file, run_file = _file_maker(rng, base_save, Path(tmp)) if n_files else (None, None)
        file_slow, file_peak = 0, 0.0
        start = time.perf_counter()
        for kind, count in cases:
            for _ in range(count):
                if kind == "save":
                    case, run = mutate_text(base_save, rng), lambda c: try_save(c, Path(tmp))
                elif kind == "lsys":
                    case, run = mutate_text(rng.choice(sources), rng), try_source
                elif kind == "file":
                    case, run = make_file(), run_file
                else:
                    case, run = random_packet(rng), lambda c: try_packet(parser, c)
                t0 = time.perf_counter()
                signal.setitimer(signal.ITIMER_REAL, FILE_HANG_SECONDS if kind == "file" else HANG_SECONDS)
                try:
                    result = run(case)
                    signal.setitimer(signal.ITIMER_REAL, 0)
                    result = "file refused" if kind == "file" and result == "refused" else result
                    if result in outcomes:
                        outcomes[result] += 1
                except Exception as exc:
                    signal.setitimer(signal.ITIMER_REAL, 0)
                    outcomes["hang"] += isinstance(exc, HangError)
                    outcomes["round trip"] += isinstance(exc, RoundTripError)
                    failures.append((kind, traceback.format_exc(limit=4), case))
                    if keep is not None:
                        _keep(keep, kind, len(failures), case)
                took = time.perf_counter() - t0
                if kind == "file":
                    file_slow += took > FILE_HANG_SECONDS
                    file_peak = max(file_peak, took)
                if took > SLOW_SECONDS:
                    slow += 1
                    slowest.append((took, kind, case))
                    if keep is not None:
                        _keep(keep, f"slow-{kind}", slow, case)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"cases: {n_saves:,} saves, {n_lsys:,} .lsys, {n_osc:,} OSC packets, {n_files:,} other files in "
          f"{time.perf_counter() - start:.0f} s")
    if n_files:
        print(f"files: {outcomes['read']:,} read, {outcomes['file refused']:,} refused with their own error, "
              f"{outcomes['derived']:,} heavy derivations ended in their budgets; "
              f"slowest file case {file_peak:.1f} s, over {FILE_HANG_SECONDS:g} s: {file_slow}")
    print(f"saves: {outcomes['loaded']:,} loaded and round-tripped, {outcomes['refused']:,} refused with one line, "
          f"{outcomes['round trip']} failed their own round trip")
    print(f"uncaught: {len(failures)} (hangs over {HANG_SECONDS:g} s: {outcomes['hang']}); slower than "
          f"{SLOW_SECONDS:g} s: {slow}; peak RSS {peak:.0f} MiB (every load below it)")
    for took, kind, case in sorted(slowest, key=lambda s: -s[0])[:5]:
        print(f"slow {kind} case: {took:.1f} s ({len(case):,} characters)")
    for kind, text, case in failures[:5]:
        print(f"--- {kind}: {(case[:2] if isinstance(case, tuple) else case[:300])!r}\n{text}")
    return len(failures)


def _keep(folder: Path, kind: str, number: int, case) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    if isinstance(case, tuple):  # a file case: (kind, how, bytes) or a heavy derivation
        kind, case = f"{kind}-{case[0]}-{case[1]}", case[-1] if isinstance(case[-1], bytes) else repr(case)
    data = case if isinstance(case, bytes) else case.encode("utf-8", "surrogatepass")
    (folder / f"{kind}-{number:04d}.{'arbor' if kind == 'save' else kind}").write_bytes(data)


def main() -> None:
    """Command line: counts, optional --seed."""
    argv = sys.argv[1:]
    options = {argv[i]: argv[i + 1] for i in range(len(argv) - 1) if argv[i] in ("--seed", "--keep")}
    args = [a for i, a in enumerate(argv) if not a.startswith("--") and (i == 0 or argv[i - 1] not in options)]
    counts = [int(a) for a in args[:4]] + [10_000, 10_000, 2_000, 10_000][len(args[:4]):]
    keep = Path(options["--keep"]) if "--keep" in options else None
    sys.exit(1 if campaign(*counts, seed=int(options.get("--seed", 0)), keep=keep) else 0)


if __name__ == "__main__":
    import logging

    logging.disable(logging.WARNING)  # dropped packets are logged one per line: not for this run
    np.seterr(all="ignore")
    main()
