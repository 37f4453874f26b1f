"""light_day is a daily total whatever the sampling: the light caught over the last game day (a sliding day),
not a window's mean x 24 (which zig-zagged between day and night with two samples a day)."""

import numpy as np
import pytest

from arbor.engine.life.experiment.lab import Experiment, Lab, Regime, Watering
from arbor.engine.life.rules.rules import load_rules
from tests.conftest import ROOT

DAY = 2 * np.pi / 0.05


def light_days(sample_every: float, days: float = 4.0) -> tuple[list[float], list[float]]:
    experiment = Experiment("light a day", seed=2, duration=days * DAY, sample_every=sample_every,
                            regimes=[Regime("watered", watering=Watering(below=0.55, until=0.75))],
                            lsystem=ROOT / "assets" / "lsystems" / "game_tree.lsys", seasons=False)
    lab = Lab(experiment, load_rules(ROOT / "assets" / "rules.toml", pace="demo"))
    lab.run()
    return lab.series[0].day, lab.series[0].values["light_day"]


def test_light_day_does_not_depend_on_the_sampling():
    days_half, half = light_days(DAY / 2)
    days_whole, whole = light_days(DAY)
    by_day = dict(zip(np.round(days_half, 3), half, strict=True))
    for day, value in zip(np.round(days_whole, 3), whole, strict=True):
        if day >= 1:
            assert by_day[day] == pytest.approx(value, rel=1e-9)  # the same total at the same moment
    later = np.array(half)[np.array(days_half) >= 1.5]
    # no zig-zag between a day's window and a night's (it was 30x): sample to sample, the tree's growth alone
    assert np.all(later > 0) and np.all(np.abs(np.diff(np.log(later))) < np.log(3))


def test_the_real_units_follow_the_declared_time_scale():
    from arbor.engine.life.plant import solar

    experiment = Experiment("real units", seed=2, duration=2 * DAY, sample_every=DAY,
                            regimes=[Regime("watered", watering=Watering(below=0.55, until=0.75))],
                            lsystem=ROOT / "assets" / "lsystems" / "game_tree.lsys", seasons=False)
    rules = load_rules(ROOT / "assets" / "rules.toml", pace="demo")
    lab = Lab(experiment, rules)
    lab.run()
    values, day = lab.series[0].values, lab.series[0].day
    assert values["real_days"][-1] == pytest.approx(day[-1] * rules.seasons.real_year / rules.seasons.year_days)
    full = solar.full_par(rules.sun)
    assert 500 < full < 510  # W/m² of PAR under a clear sky's zenith sun
    assert values["par_day"][-1] > 0
    assert values["par_day"][-1] == pytest.approx(values["light_day"][-1] * 3600 * full * 1e-6)
