"""The file classes of the fuzz campaign (issue 45): every kind of file a user can hand us, hostile.

Used by ``python -m benchmarks.fuzz`` (its fourth count, FILES): each case is one file of one kind
(settings.toml, kiosk.toml, an experiment, a sweep, devices.toml, a species preset, a recording, a
save, a card, an .lsys source) made from a shipped sample by the save mutators, or by an edit aimed at
the readers' bounds (arrays and inline tables nested up to 100,000 deep, long dotted keys, a table
where a name belongs, a 2 MB file), or put where the file should be as something that is not a plain
file (a FIFO, /dev/zero, a link out of the folder, a folder); one case in DERIVE_EVERY is a derivation
meant to cost time or memory (the shipped context_plant.lsys for 1000 steps, a parametric rule with
``budget: 20000000``) run as commands run it (module budget cut to memory, a time budget). A case
passes when it reads or ends in the file's own error (an LSysError naming the file).
"""

from __future__ import annotations

import os
import random
from pathlib import Path

from arbor.engine.base.errors import LSysError

ROOT = Path(__file__).resolve().parent.parent
ASSETS = ROOT / "assets"
DERIVE_EVERY = 200  # one case in this many is a time- or memory-heavy derivation
DERIVE_SECONDS = 5.0  # the time budget those derivations run with (commands use 30 s)
HEAVY_SOURCES = [
    (ASSETS / "lsystems" / "context_plant.lsys", 1000, None),
    (None, 60, "budget: 20000000\nw: A(1)\np1: A(x) -> A(x+1)F[A(x*2)]\n"),
    (None, 1000, "budget: 20000000\nw: A\np1: A -> A[+A]A\n"),
]


def samples() -> dict[str, str]:
    """The shipped (or written) sample of each file kind, the starting point of its mutations."""
    from arbor.game.screens.config import Preferences, write_preferences

    out = {
        "kiosk": (ASSETS / "kiosk.toml").read_text(encoding="utf-8"),
        "experiment": (ASSETS / "experiments" / "sun_vs_shade.toml").read_text(encoding="utf-8"),
        "sweep": (ASSETS / "experiments" / "sweep_sun_height.toml").read_text(encoding="utf-8"),
        "devices": (ASSETS / "input" / "devices.toml").read_text(encoding="utf-8"),
        "species": (ASSETS / "presets" / "broadleaf.toml").read_text(encoding="utf-8"),
        "recording": "\n".join((ASSETS / "attract" / "demo.jsonl").read_text(encoding="utf-8").splitlines()[:40]),
        "lsys": (ASSETS / "lsystems" / "game_tree.lsys").read_text(encoding="utf-8"),
    }
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        write_preferences(Preferences(), Path(tmp) / "settings.toml")
        out["settings"] = (Path(tmp) / "settings.toml").read_text(encoding="utf-8")
    return out


def readers() -> dict:
    """Each file kind's reader, as the game or a command calls it."""
    from arbor.engine.forest.geomatree import load_species
    from arbor.engine.life.experiment.lab import load_experiment
    from arbor.engine.life.experiment.sweep_file import load_sweep
    from arbor.engine.life.keep.card import read_card
    from arbor.engine.life.keep.save import read_garden
    from arbor.engine.lsystem.lsys import load_lsystem
    from arbor.game.input.events import load_recording
    from arbor.game.input.hid import load_profiles
    from arbor.game.screens.config import read_preferences
    from arbor.game.screens.kiosk import load_kiosk_config

    lsystems = ASSETS / "lsystems"
    return {"settings": read_preferences, "kiosk": load_kiosk_config, "devices": load_profiles,
            "experiment": lambda p: load_experiment(p, lsystems), "sweep": lambda p: load_sweep(p, lsystems),
            "species": load_species, "recording": load_recording, "lsys": load_lsystem,
            "save": read_garden, "card": read_card}


def nesting_edit(text: str, rng: random.Random) -> str:
    """An edit aimed at the TOML readers' bounds: deep arrays or inline tables, a long dotted key, a
    table or array where a name belongs, a huge file."""
    depth = rng.choice([10, 33, 200, 1000, 3000, 100_000])
    kind = rng.randrange(6)
    if kind == 0:
        piece = "deep = " + "[" * depth + "]" * depth
    elif kind == 1:
        piece = "deep = " + "{a = " * depth + "1" + "}" * depth
    elif kind == 2:
        piece = ".".join(["k"] * depth) + " = 1"
    elif kind == 3:  # a table or a list where a name (a factor's key, a title) belongs
        lines = [k for k, line in enumerate(text.split("\n")) if "= \"" in line]
        if not lines:
            return text + "\nkey = {a = 1}\n"
        out = text.split("\n")
        k = rng.choice(lines)
        out[k] = out[k].split("=")[0] + "= " + rng.choice(["{a = 1}", "[1, 2]", "[[1]]", "{}"])
        return "\n".join(out)
    elif kind == 4:
        piece = "# " + "x" * 2_000_000
    else:
        piece = "x = " + "[" * depth  # never closed
    lines = text.split("\n")
    at = rng.randrange(len(lines) + 1)
    return "\n".join([*lines[:at], piece, *lines[at:]])


NOT_PLAIN = ("fifo", "dev-zero", "link-out", "folder", "missing")


def place(case: tuple, folder: Path) -> Path:
    """Write ``case`` (kind, what, data) where its reader will look, as what it is meant to be."""
    kind, what, data = case
    suffix = {"save": ".arbor", "card": ".png", "lsys": ".lsys", "recording": ".jsonl"}.get(kind, ".toml")
    path = folder / f"case{suffix}"
    for old in folder.iterdir():
        if old.is_dir() and not old.is_symlink():
            for inner in old.iterdir():
                inner.unlink()
            old.rmdir()
        else:
            old.unlink()
    if what == "fifo":
        os.mkfifo(path)
    elif what == "dev-zero":
        return Path("/dev/zero")
    elif what == "link-out":
        outside = folder / "outside"
        outside.mkdir()
        (outside / "real").write_bytes(data)
        path.symlink_to(outside / "real")
    elif what == "folder":
        path.mkdir()
    elif what != "missing":
        path.write_bytes(data)
    return path


def make_case(rng: random.Random, bases: dict[str, str], save_text: str, card: bytes, mutate) -> tuple:
    """One file case: (kind, how it is made, its bytes)."""
    kinds = [*bases, "save", "card"]
    kind = rng.choice(kinds)
    if rng.random() < 0.15:
        base = card if kind == "card" else (save_text if kind == "save" else bases[kind]).encode("utf-8")
        return kind, rng.choice(NOT_PLAIN), base
    if kind == "card":
        data = bytearray(card)
        for _ in range(rng.randint(1, 4)):  # bytes flipped anywhere, the save chunk's CRC or after it
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
        return kind, "mutated", bytes(data[: rng.choice([len(data), rng.randrange(1, len(data) + 1)])])
    text = save_text if kind == "save" else bases[kind]
    text = nesting_edit(text, rng) if rng.random() < 0.5 else mutate(text, rng)
    return kind, "mutated", text.encode("utf-8", "surrogatepass")


def try_file(case: tuple, folder: Path, read: dict) -> str:
    """Read one file case with its kind's reader: "read" or "refused" (its own error); anything else
    raised is a bug the campaign counts."""
    path = place(case, folder)
    try:
        read[case[0]](path)
    except LSysError:
        return "refused"
    return "read"


def heavy_case(rng: random.Random) -> tuple:
    """A derivation meant to cost time or memory: (source path or text, steps)."""
    path, steps, text = rng.choice(HEAVY_SOURCES)
    return ("derive", path, text, steps)


def try_heavy(case: tuple) -> str:
    """Derive as a command does: the module budget cut to memory before the work, the time budget on."""
    from arbor.engine.lsystem.derive import Deriver
    from arbor.engine.lsystem.lsys import load_lsystem, parse_lsystem
    from arbor.game.commands.trees import TreeSource, derive_budget

    _, path, text, steps = case
    system = load_lsystem(path) if path is not None else parse_lsystem(text, "heavy.lsys")
    budget, _ = derive_budget(system, TreeSource(path or Path("heavy.lsys"), steps=steps))
    deriver = Deriver(system, seed=0, budget=budget, seconds=DERIVE_SECONDS)
    deriver.derive(steps=steps)
    return "derived"
