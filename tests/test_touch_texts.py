"""Issue 47: a touch screen's texts name no keys (the kiosk says "tap Go on", never "Water it (W), or press G")."""

import re
import tomllib

from arbor.engine.life.world.guardian import Need
from arbor.engine.life.world.status import need_line
from arbor.game.screens.game import Game, GameConfig
from arbor.game.screens.kiosk import Kiosk, load_kiosk_config
from arbor.game.strings import STRINGS_DIR, set_language, set_touch, text
from tests.conftest import FakeClock

KEY_NAMES = re.compile(r"\([A-Z]\)|\b[Pp]ress\b|\bEsc\b|Ctrl|\bkeys?\b")
NO_KIOSK = {"messages.quit_confirm"}  # (said for the Esc key, which the kiosk stops before the game)


def _kiosk(gl_ctx, tmp_path):
    clock = FakeClock(100.0)
    return Kiosk(lambda: Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path, seed=4, resume=False, pace="demo"),
                              clock=clock), load_kiosk_config("assets/kiosk.toml"), tmp_path, clock=clock)


def test_the_kiosk_s_thirst_stop_names_no_key(gl_ctx, tmp_path):
    """The guardian's stop in the kiosk: "tap Go on", not "Water it (W), or press G"; the game at a desk
    made after it names its keys again."""
    kiosk = _kiosk(gl_ctx, tmp_path)
    g = kiosk.game
    g.world.sim.state.water_meter = need_line(g.rules) - 0.02
    g.loop.speed = 10.0
    g.state.halt(Need(0, "water"))
    said = g.hud.hud_info().message
    assert "tap Go on" in said and not KEY_NAMES.search(said), said
    desk = Game(gl_ctx, (640, 360), GameConfig(saves=tmp_path / "desk", seed=1, resume=False), clock=FakeClock())
    assert "press G" in text("guardian.water", number=1, speed="10"), "the desk game lost its keys"
    desk.quit()


def test_every_text_a_kiosk_can_show_names_no_key():
    """With the touch texts on, no text of the strings file names a key (but the Esc quit's, never shown)."""
    set_language("en")
    table = tomllib.loads((STRINGS_DIR / "en.toml").read_text("utf-8"))
    set_touch(True)
    try:
        named = [f"{section}.{name}" for section, values in table.items() if not section.startswith("touch_")
                 for name in values if f"{section}.{name}" not in NO_KIOSK
                 and KEY_NAMES.search(text(f"{section}.{name}"))]
    finally:
        set_touch(False)
    assert named == [], named
    assert KEY_NAMES.search(text("guardian.water"))  # (the keyboard's texts keep their keys)
