"""The `arbor` command: the game window by default, headless subcommands for tools and CI."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from engine.derive import Deriver
from engine.errors import LSysError
from engine.lsys import load_lsystem

ROOT = Path(__file__).resolve().parent.parent
ASSETS = ROOT / "assets"


def _cmd_derive(args: argparse.Namespace) -> int:
    system = load_lsystem(args.source)
    deriver = Deriver(system, seed=args.seed, budget=args.budget)
    result, reports = deriver.derive(steps=args.steps)
    if any(r.budget_hit for r in reports):
        held = sum(r.deferred for r in reports)
        print(f"module budget {deriver.budget:,} reached: {held:,} rewrites held back", file=sys.stderr)
    print(result.to_text())
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The argument parser for `arbor` and its subcommands."""
    parser = argparse.ArgumentParser(prog="arbor", description="Grow and model 3D trees.")
    sub = parser.add_subparsers(dest="command")
    derive = sub.add_parser("derive", help="print the L-string an .lsys source derives")
    derive.add_argument("source", type=Path)
    derive.add_argument("--steps", type=int, default=None)
    derive.add_argument("--seed", type=int, default=None)
    derive.add_argument("--budget", type=int, default=None)
    derive.set_defaults(run=_cmd_derive)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Entry point of the `arbor` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        from game.app import run_app

        return run_app(args)
    try:
        return args.run(args)
    except LSysError as err:
        print(f"arbor: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
