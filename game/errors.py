"""The one error a user can cause outside files: it ends the command with a single line saying what to do."""

from __future__ import annotations


class UserError(Exception):
    """A problem the user can fix (no display, a missing recording, ...); ``str()`` is the whole message."""


NO_DISPLAY = ("no OpenGL 3.3 display ({detail}). Run it on a desktop, or headless under a virtual display: "
              "xvfb-run -a arbor ...; without any window: arbor render / export / lab --out")

NO_DISPLAY_FOUND = ("no display found (SDL fell back to its {driver} driver: the window would be invisible). "
                    "Run it on a desktop, or under a virtual display: xvfb-run -a arbor")

LAB_EXTRA = ("{what} needs matplotlib, which a player's install leaves out (86 MB): pip install 'arbor-trees[lab]' "
             "(in a checkout: .venv/bin/pip install -e '.[lab]')")


def need_lab_extra(what: str) -> None:
    """Refuse, in one line saying what to install, a teacher's command whose figures need matplotlib (the
    `lab` extra) when it is missing; imports nothing when it is there."""
    from importlib.util import find_spec

    if find_spec("matplotlib") is None:
        raise UserError(LAB_EXTRA.format(what=what))
