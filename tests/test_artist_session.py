"""The artist's whole session from issue 48's list, replayed in the real game headless with a shaky hand
(benchmarks/artist_session.py: trunk, two branches, three outlines, a moved lobe, a supertoroid region,
prune and grow in it, undo/redo, a wider branch, a crown preset, Done, save, restart, load, a lobe
edited after the restart, export): no step surprises. Before: Grow in the pruned region did nothing and
made no undo step, so the undo after it took the prune back; a lobe moved into a full budget was told
only as 'reached its size limit'."""

from benchmarks.artist_session import run


def test_the_whole_session_holds_no_surprise(tmp_path):
    steps = run(tmp_path)
    for step in steps:
        print(f"{'SURPRISE' if step.surprise else 'ok'}  {step.name}: {step.said} {step.surprise}")
    assert len(steps) == 20 and not [s.name for s in steps if s.surprise]
    assert (tmp_path / "session_tree.glb").is_file()
