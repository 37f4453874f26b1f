"""The kiosk's log is bounded (issue 45: no size limit on kiosk.log, and a paced flood of bad TUIO wrote
18.6 KB/s): rotated files of KIOSK_LOG_BYTES, KIOSK_LOG_FILES of them kept."""

from __future__ import annotations

import logging

from arbor.game import app


def test_the_kiosk_log_rotates_and_stays_bounded(tmp_path):
    root = logging.getLogger()
    before = root.handlers[:]
    root.handlers = []
    try:
        app._kiosk_log(tmp_path / "kiosk.log")
        log = logging.getLogger("arbor.kiosk")
        for i in range(30_000):  # about 3 MB of lines
            log.error("line %d: %s", i, "x" * 80)
        for handler in root.handlers:
            handler.flush()
        files = sorted(p.name for p in tmp_path.iterdir())
        total = sum(p.stat().st_size for p in tmp_path.iterdir())
        assert files == ["kiosk.log", "kiosk.log.1", "kiosk.log.2", "kiosk.log.3"]
        assert total <= (app.KIOSK_LOG_FILES + 1) * app.KIOSK_LOG_BYTES
    finally:
        for handler in root.handlers:
            handler.close()
        root.handlers = before
