"""A reminder while the player is elsewhere (issue 47): a thirsty tree rings once per thirst while the
window is not focused (its taskbar entry flashes, its title says so), never while the player is there;
it is kept in settings.toml (remind) and on by default."""

from arbor.game.screens.bell import NeedBell
from arbor.game.screens.config import Preferences, read_preferences, write_preferences


def test_the_bell_rings_once_a_thirst_and_only_while_the_window_is_elsewhere():
    bell = NeedBell()
    assert not bell.check(thirsty=True, focused=True)  # (the player is there: the HUD tells them)
    assert bell.check(thirsty=True, focused=False)  # elsewhere: ring
    assert not bell.check(thirsty=True, focused=False)  # ... once
    assert not bell.check(thirsty=False, focused=False)  # watered (by the rain, a neighbour)
    assert bell.check(thirsty=True, focused=False)  # a new thirst rings again


def test_the_reminder_is_a_kept_setting(tmp_path):
    assert Preferences().remind
    path = tmp_path / "settings.toml"
    write_preferences(Preferences(remind=False, unlocked="oak,birch"), path)
    prefs = read_preferences(path)
    assert not prefs.remind and prefs.unlocked == "oak,birch"
