"""Files users edit (issue 33): every bad devices.toml entry and every bad replay file is one line, never a
traceback; the game still starts with a bad devices.toml (its trackers left out); pace and lab overrides
out of range (year_days = 0, meter_min > meter_max, rewrite_step = 1e-9) are one line each."""

import argparse
import os
import sys

import pytest

from arbor.game.app import _trackers, make_input_hub
from arbor.game.errors import UserError
from arbor.game.input.hid import DevicesError, load_profiles

GOOD = ('[[device]]\nname = "tracker"\nvendor_id = 0x1209\nproduct_id = 1\nreport_id = 1\n'
        'x = { offset = 1, type = "int16", scale = 0.001 }\ny = { offset = 3, type = "int16" }\n'
        'z = { offset = 5, type = "int16" }\n')

DEVICE_CASES = [  # (the file, what its one line says, its line number)
    ("[[device]\nname = 1\n", "not valid TOML", 1),
    ("devices = []\n", "unknown key 'devices'", 1),
    ("device = 5\n", "'device' must be [[device]] tables", 1),
    ("device = [5]\n", "device #1: must be a table", 1),
    (GOOD.replace("vendor_id", "vendorid"), "device #1: unknown key 'vendorid' (did you mean 'vendor_id'?)", 3),
    (GOOD.replace('name = "tracker"\n', ""), "device #1: missing 'name'", 1),
    (GOOD.replace('"tracker"', "42"), "device #1: 'name' must be text", 2),
    (GOOD.replace("0x1209", "70000"), "device #1: 'vendor_id' must be a whole number from 0 to 0xffff", 3),
    (GOOD.replace("0x1209", "-1"), "'vendor_id' must be a whole number", 3),
    (GOOD.replace("0x1209", "4.5"), "'vendor_id' must be a whole number", 3),
    (GOOD.replace("report_id = 1", "report_id = true"), "'report_id' must be a whole number from 0 to 0xff", 5),
    (GOOD.replace("report_id = 1", "report_id = 300"), "'report_id' must be a whole number from 0 to 0xff", 5),
    (GOOD + GOOD.replace('x = { offset = 1, type = "int16", scale = 0.001 }', "x = 5"),
     "device #2: 'x' must be a table like", 14),
    (GOOD.replace('"int16", scale', '"int128", scale'), "'x': unknown type 'int128'", 6),
    (GOOD.replace("offset = 1,", "offset = 63,"), "'x': offset must be a whole number from 0 to 62 for int16", 6),
    (GOOD.replace("offset = 1,", "offset = -2,"), "'x': offset must be", 6),
    (GOOD.replace("scale = 0.001", "scale = nan"), "'x': scale must be a finite number", 6),
    (GOOD.replace("scale = 0.001", 'scale = "big"'), "'x': scale must be a finite number", 6),
    (GOOD.replace("scale = 0.001", "scael = 1"), "'x': unknown key 'scael'", 6),
    (GOOD + 'buttons = { offset = 7, type = "uint8", bits = 3 }\n', "'buttons': unknown key 'bits'", 9),
]


@pytest.mark.parametrize(("text", "says", "line"), DEVICE_CASES)
def test_every_bad_devices_entry_is_one_line(tmp_path, text, says, line):
    path = tmp_path / "devices.toml"
    path.write_text(text)
    with pytest.raises(DevicesError) as info:
        load_profiles(path)
    assert "\n" not in str(info.value) and says in info.value.message
    assert str(info.value).startswith(f"{path}:{line}:")


def test_an_unreadable_devices_file_is_one_line(tmp_path):
    (tmp_path / "bytes.toml").write_bytes(b"\xff\xfe[[device]]")
    (tmp_path / "folder.toml").mkdir()
    for name in ("bytes.toml", "folder.toml", "missing.toml"):
        with pytest.raises(DevicesError) as info:
            load_profiles(tmp_path / name)
        assert "\n" not in str(info.value) and "cannot read" in info.value.message


def test_the_shipped_devices_file_and_a_good_one_load(tmp_path):
    assert load_profiles("assets/input/devices.toml")
    (tmp_path / "devices.toml").write_text(GOOD)
    [profile] = load_profiles(tmp_path / "devices.toml")
    assert (profile.vendor_id, profile.x.offset, profile.x.scale, profile.y.scale) == (0x1209, 1, 0.001, 1.0)


def test_a_bad_devices_file_leaves_its_trackers_out_and_the_game_starts(tmp_path, monkeypatch, capsys):
    from arbor.game import paths

    (tmp_path / "input").mkdir()
    (tmp_path / "input" / "devices.toml").write_text(GOOD.replace("0x1209", "70000"))
    monkeypatch.setattr(paths, "ASSETS", tmp_path)
    hid = _trackers()
    assert hid.profiles == []
    [line] = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("arbor: ") and line.endswith("(the trackers it describes are not used)")


REPLAY_CASES = [  # (a line of a recording, what the one line says)
    ('{"kind": "down", "t": "soon"}', "'t' must be a number"),
    ('{"kind": "down", "t": null}', "'t' must be a number"),
    ('{"kind": "down", "t": true}', "'t' must be a number"),
    ('{"kind": "down", "t": NaN}', "'t' must be a finite number"),
    ('{"kind": "down", "t": 1, "x": 1e400}', "'x' must be a finite number"),
    ('{"kind": "wheel", "t": 1, "amount": -1e9}', "'amount' must be a finite number from -100 to 100"),
    ('{"kind": "down", "t": 1, "pointer": 1.5}', "'pointer' must be a number"),
    ('{"kind": "down", "t": 1, "dims": 7}', "'dims' must be 2 or 3"),
    ('{"kind": "down", "t": 1, "text": "' + "x" * 2000 + '"}', "'text' is too long"),
    ('{"kind": "explode", "t": 1}', "unknown kind 'explode'"),
    ('{"kind": "down", "t": 1, "colour": 3}', "unknown field 'colour'"),
    ('{"kind": "down"}', "not an input event"),
    ("[1, 2]", "not an input event"),
    ("5", "not an input event"),
    ("[" * 100_000 + "]" * 100_000, "not an input event"),
    ("{not json", "Expecting property name"),
]


def _replay(path):
    return make_input_hub(argparse.Namespace(replay=path, tuio=False, record=None), (1280, 720), 0.0)


@pytest.mark.parametrize(("line", "says"), REPLAY_CASES)
def test_every_bad_replay_line_is_one_line(tmp_path, line, says):
    path = tmp_path / "bad.jsonl"
    path.write_text('{"arbor_input_recording":1}\n{"kind": "down", "t": 0.5, "x": 3}\n' + line + "\n")
    with pytest.raises(UserError) as info:
        _replay(path)
    message = str(info.value)
    assert "\n" not in message and message.startswith(f"cannot replay {path}: {path}:3:1: ") and says in message


def test_an_unreadable_replay_file_is_one_line_and_a_fifo_does_not_block(tmp_path):
    (tmp_path / "bytes.jsonl").write_bytes(b'{"kind": "down", "t": 1}\n\xff\xfe')
    (tmp_path / "folder.jsonl").mkdir()
    os.mkfifo(tmp_path / "fifo.jsonl")
    says = {"bytes.jsonl": "not UTF-8 text", "folder.jsonl": "Is a directory", "fifo.jsonl": "not a regular file",
            "missing.jsonl": "No such file"}
    for name, what in says.items():
        with pytest.raises(UserError) as info:
            _replay(tmp_path / name)
        assert "\n" not in str(info.value) and what in str(info.value), name


def test_a_good_replay_loads(tmp_path):
    path = tmp_path / "good.jsonl"
    path.write_text('{"arbor_input_recording":1}\n{"kind":"down","t":0.5,"x":3,"pointer":-1}\n\n'
                    '{"kind":"wheel","t":0.7,"amount":1}\n{"kind":"key_down","t":1,"device":"keyboard","key":27}\n')
    [player] = [s for s in _replay(path).sources if hasattr(s, "events")]
    assert [e.kind for e in player.events] == ["down", "wheel", "key_down"] and player.events[0].x == 3.0


@pytest.mark.parametrize(("override", "says"), [
    ('"seasons.year_days" = 0', "'year_days' in [seasons] must be from 1 to 1000"),
    ('"replant.meter_min" = 0.95', "[replant] meter_min must not be above meter_max"),
    ('"growth.rewrite_step" = 1e-9', "'rewrite_step' in [growth] must be from 0.01 to 100"),
])
def test_lab_overrides_out_of_range_are_one_line(tmp_path, capsys, override, says):
    from arbor.game.cli import main

    lab = tmp_path / "lab.toml"
    lab.write_text(f'title = "x"\nseed = 1\nduration = 60\nsample_every = 30\n\n[[tree]]\nname = "a"\n'
                   f"rules = {{ {override} }}\n")
    assert main(["lab", str(lab), "--out", str(tmp_path / "out")]) == 1
    [line] = capsys.readouterr().err.strip().splitlines()
    assert line.startswith(f"arbor: {lab}:") and says in line  # the file named, not the tree alone


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
