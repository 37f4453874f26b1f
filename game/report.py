"""What the headless commands tell the user on stdout: a line for each thing a command wrote (silenced by
``--quiet``) and the details a long run goes through (shown only with ``--verbose``). A command's product
(the L-string `derive` prints, the family tree `lineage` prints) is printed whatever the level; errors go to
stderr as one line."""

from __future__ import annotations

QUIET, NORMAL, VERBOSE = 0, 1, 2
level = NORMAL


def set_level(quiet: bool = False, verbose: bool = False) -> None:
    """The level for this process (the command line's --quiet / --verbose)."""
    global level
    level = QUIET if quiet else VERBOSE if verbose else NORMAL


def say(line: str) -> None:
    """Report what a command did (the files written); silent under --quiet."""
    if level >= NORMAL:
        print(line, flush=True)


def detail(line: str) -> None:
    """A step of a long run (each finished sweep run, timings); only with --verbose."""
    if level >= VERBOSE:
        print(line, flush=True)
