"""tests/cputimes.py's summary: CPU per file and per worker, and how long each worker stood idle at the end."""
from __future__ import annotations

import json

import cputimes


def test_summary_gives_each_worker_s_idle_tail(tmp_path):
    rows = [{"id": "tests/test_a.py::test_one", "cpu": 1.5, "wall": 2.0, "end": 100.0, "worker": "gw0"},
            {"id": "tests/test_b.py::test_two", "cpu": 0.5, "wall": 1.0, "end": 112.5, "worker": "gw1"},
            {"id": "tests/test_a.py::test_three", "cpu": 1.0, "wall": 1.0, "end": 104.0, "worker": "gw0"},
            {"id": "__session__", "cpu": 4.0, "wall": 0.0, "worker": "gw0"},
            {"id": "__session__", "cpu": 2.0, "wall": 0.0, "worker": "gw1"}]
    path = tmp_path / "times.jsonl"
    path.write_text("".join(json.dumps(r) + "\n" for r in rows), encoding="utf-8")
    lines = cputimes.summary([str(path)]).splitlines()
    assert lines[:2] == ["     2.5  tests/test_a.py", "     0.5  tests/test_b.py"]
    assert lines[2] == "tests 3.0 CPU s; per worker (tests / whole process): gw0 2.5 / 4.0, gw1 0.5 / 2.0"
    assert lines[3] == "idle at the end (wall s before the last worker's last test ended): gw0 8.5, gw1 0.0"
