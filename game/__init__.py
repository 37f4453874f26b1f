"""Everything that knows pygame and moderngl: the app, its screens, tools, input devices and renderer."""

import os

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")  # no banner in front of our own messages
