"""The experiment builder (arbor lab FILE --build): every choice it offers writes a sweep file that loads
(valid by construction), an existing file reopens into it, and a sweep is built, saved, reopened and run
with the mouse alone in the window (driven headless)."""

from __future__ import annotations

import csv
import io
import itertools
import math

import numpy as np
import pytest

from arbor.engine.life.experiment.builder import FACTORS, WATERING, Draft, NotBuildableError, draft_of
from arbor.engine.life.experiment.sweep_file import load_sweep
from arbor.engine.life.rules.rules import load_rules
from arbor.game.paths import ASSETS

LSYS = ASSETS / "lsystems"
DAY = 2 * math.pi / load_rules(ASSETS / "rules.toml", "demo").sun.speed


@pytest.mark.parametrize("key", list(FACTORS))
def test_every_choice_the_builder_offers_writes_a_file_that_loads(tmp_path, key):
    for watering, days in itertools.product(WATERING, (1, 60)):
        draft = Draft(seeds=50, days=days, watering=watering, responses=list(Draft().offered))
        draft.choose_factor(key)
        for level in draft.ladders[key]:
            if level not in draft.levels:
                draft.toggle_level(level)
        path = tmp_path / f"{key}.toml"
        path.write_text(draft.toml(DAY), encoding="utf-8")
        sweep = load_sweep(path, LSYS)  # (a problem would be one SweepError naming the line)
        assert [f.key for f in sweep.factors] == [key] and list(sweep.factors[0].levels) == list(draft.ladders[key])
        assert len(sweep.seeds) == 50 and sweep.duration == pytest.approx(days * DAY, rel=1e-5)
        assert list(sweep.responses) == list(draft.offered)
        reopened = draft_of(sweep, DAY)  # and it reopens as it was
        assert reopened.toml(DAY) == draft.toml(DAY)


def test_hand_written_lessons_reopen_and_files_it_would_change_are_refused_by_name():
    from arbor.game.screens.builder import reopen

    light = reopen(ASSETS / "experiments" / "lesson_light.toml", DAY)
    assert (light.factor, light.levels, light.seeds, light.days) == ("day_length", [6, 10, 14, 18], 8, 20)
    assert "light_day" in light.responses and light.title() == "Day length" and light.elevation == 60
    for lesson in ("lesson_water", "lesson_pruning", "sweep_sun_height"):  # saved again, the same experiment
        reopen(ASSETS / "experiments" / f"{lesson}.toml", DAY)
    with pytest.raises(NotBuildableError, match="this one varies orbit_height, species: edit it in a text editor"):
        reopen(ASSETS / "experiments" / "sweep_species_sun.toml", DAY)
    with pytest.raises(NotBuildableError, match="the builder cannot keep its base as written: edit it in a text"):
        reopen(ASSETS / "experiments" / "sweep_watering.toml", DAY)  # (its [base] sets the orbit's height)


def test_a_sweep_built_saved_reopened_and_run_with_the_mouse_alone(gl_ctx, tmp_path):

    from arbor.game.commands.sweep import run_sweep
    from arbor.game.input.events import DOWN, InputEvent
    from arbor.game.screens.builder import OFF, ON, BuilderScreen
    from arbor.game.screens.stack import ScreenStack

    size = (1280, 720)
    path = tmp_path / "my_sweep.toml"

    def tap(screen, stack, action) -> None:
        x, y = screen.buttons[action].center
        assert stack.handle_input(InputEvent(DOWN, 0.0, "mouse", 0, x, y))

    screen = BuilderScreen(gl_ctx, size, path, run_sweep, results=tmp_path / "results", workers=1)
    stack = ScreenStack(screen)
    while screen.draft.factor != "watering.every":
        tap(screen, stack, ("factor", 1))
    for level in (30, 120, 480):  # chosen at first: 30, 120, 480; wanted: 60 and 240
        tap(screen, stack, ("level", level)) if level != 480 else None
    tap(screen, stack, ("level", 60))
    tap(screen, stack, ("level", 240))
    tap(screen, stack, ("level", 480))
    assert screen.draft.levels == [60, 240]
    while screen.draft.seeds > 2:
        tap(screen, stack, ("seeds", -1))
    while screen.draft.days > 1:
        tap(screen, stack, ("days", -1))
    tap(screen, stack, ("response", "water_min"))
    tap(screen, stack, ("response", "leaf_area"))
    tap(screen, stack, ("save",))
    sweep = load_sweep(path, LSYS)
    assert [f.key for f in sweep.factors] == ["watering.every"] and sweep.factors[0].levels == (60, 240)
    assert sweep.seeds == [1, 2] and sweep.responses == ("height", "biomass", "water_min", "alive")
    assert sweep.base.watering.every == 60 and "# a 5 s drink on a timetable" in path.read_text(encoding="utf-8")
    fbo = gl_ctx.framebuffer(color_attachments=[gl_ctx.renderbuffer(size)])

    def lit(level) -> bool:  # is the level's button lit in what the window shows (drawn only when it changed)
        screen.draw(fbo)
        img = np.frombuffer(fbo.read(components=3), np.uint8).reshape(size[1], size[0], 3)[::-1]
        x, y = screen.buttons[("level", level)].center
        colour = img[y - 15, x - 20].astype(int)
        assert min(np.abs(colour - ON).max(), np.abs(colour - OFF).max()) <= 2, colour
        return bool(np.abs(colour - ON).max() <= 2)

    assert [lit(level) for level in (60, 240, 30, 480)] == [True, True, False, False]
    tap(screen, stack, ("level", 30))
    assert lit(30) and lit(30)  # the tap shows at once, and stays shown when nothing changes
    tap(screen, stack, ("level", 30))
    assert not lit(30)

    again = BuilderScreen(gl_ctx, size, path, run_sweep, results=tmp_path / "results", workers=1)
    assert again.message == "Opened my_sweep.toml" and again.draft.toml(DAY) == screen.draft.toml(DAY)
    stack = ScreenStack(again)
    tap(again, stack, ("seeds", -1))  # one seed: two runs
    tap(again, stack, ("run",))
    again.running.join(timeout=300)
    assert again.progress() == f"Done: 2 runs; tables and figures in {tmp_path / 'results' / 'my_sweep'}"
    rows = list(csv.DictReader(io.StringIO((tmp_path / "results" / "my_sweep" / "tidy.csv").read_text())))
    assert {r["Time between drinks"] for r in rows} == {"60", "240"} and {r["seed"] for r in rows} == {"1"}
    assert load_sweep(path, LSYS).seeds == [1]  # Run saved the change first


def test_a_save_that_cannot_be_written_keeps_the_draft_and_says_why(gl_ctx, tmp_path):
    from arbor.game.commands.sweep import run_sweep
    from arbor.game.input.events import DOWN, InputEvent
    from arbor.game.screens.builder import BuilderScreen
    from arbor.game.screens.stack import ScreenStack

    path = tmp_path / "gone" / "my_sweep.toml"  # (its folder does not exist)
    screen = BuilderScreen(gl_ctx, (1280, 720), path, run_sweep, results=tmp_path / "results", workers=1)
    stack = ScreenStack(screen)
    draft = screen.draft.toml(DAY)
    x, y = screen.buttons[("save",)].center
    assert stack.handle_input(InputEvent(DOWN, 0.0, "mouse", 0, x, y))  # the window stays open
    assert screen.message.startswith("Not saved:") and screen.draft.toml(DAY) == draft and not path.exists()
