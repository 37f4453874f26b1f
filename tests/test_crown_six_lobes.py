"""Six lobes round a drawn tree with the game's budget (issue 48, benchmarks.lobes six_lobe_cases): no lobe
starves. A lobe that wood only touches from a neighbouring lobe is reached by an axis of its own (before,
the top one of six 0.9 m lobes filled 2.5 %). The issue's goal, each >= 85 %, is not met yet: the figures
are printed (0.9 m lobes 79-91 %, 0.55 m lobes 63-91 %)."""

from benchmarks.lobes import six_lobe_cases


def test_no_lobe_of_six_starves():
    for name, (fill, ms) in six_lobe_cases().items():
        print(f"{name}: fill {[round(f, 3) for f in fill]}, {ms:.0f} ms")
        assert min(fill) >= 0.6, name
