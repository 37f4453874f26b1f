"""The one error a user can cause outside files: it ends the command with a single line saying what to do."""

from __future__ import annotations


class UserError(Exception):
    """A problem the user can fix (no display, a missing recording, ...); ``str()`` is the whole message."""


NO_DISPLAY = ("no OpenGL 3.3 display ({detail}). Run it on a desktop, or headless under a virtual display: "
              "xvfb-run -a arbor ...; without any window: arbor render / export / lab --out")

NO_DISPLAY_FOUND = ("no display found (SDL fell back to its {driver} driver: the window would be invisible). "
                    "Run it on a desktop, or under a virtual display: xvfb-run -a arbor")
