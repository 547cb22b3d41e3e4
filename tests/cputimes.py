"""CPU seconds per test, for measuring the suite on a machine that other work loads (docs/internals.md,
"Tests: keeping the suite fast"): wall times there say little, a test's CPU seconds do.

    python3 -m pytest -p tests.cputimes                      # each worker appends to .cputimes.jsonl
    python3 -m tests.cputimes .cputimes.jsonl [more.jsonl]   # CPU seconds per file, per worker, in all

A test's CPU is ``os.times()``' user + system, its waited-for children's included (a subprocess, a forked
pool's workers), over its setup, call and teardown, so a module fixture counts in the test that first
needs it; ``end`` is the wall clock (seconds since the epoch) when it ended. The last test's teardown,
where pytest tears down every fixture still standing (its module's and the session's), is a row of its own
(``__last_teardown__``: the browser's close, where Chromium's CPU is waited for, about 2 CPU s, landed on the
last doctest, velpoly.tables.zero_floor, until issue 19 item 7). Each process
also records its CPU at the session's end (``__session__``: collection and start-up included). The summary gives each
worker's last test's end against the other workers' (a worker idle at the end while another still runs a
long test wastes a core). Not loaded unless asked for with ``-p``.
"""
from __future__ import annotations

import collections
import json
import os
import sys
import time

import pytest

OUT = os.environ.get("VELPOLY_CPUTIMES", ".cputimes.jsonl")
_rows: list[dict] = []


def _cpu() -> float:
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


_last: dict = {}   # the CPU and wall clock where the last test's teardown began


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    cpu, wall = _cpu(), time.perf_counter()
    _last.clear()
    yield
    now, clock = _cpu(), time.perf_counter()
    if _last:   # the last test: its teardown (every fixture still standing) a row of its own
        _rows.append({"id": "__last_teardown__", "cpu": round(now - _last["cpu"], 4),
                      "wall": round(clock - _last["wall"], 4), "end": round(time.time(), 3)})
        now, clock = _last["cpu"], _last["wall"]
    _rows.append({"id": item.nodeid, "cpu": round(now - cpu, 4), "wall": round(clock - wall, 4),
                  "end": round(time.time(), 3)})


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_teardown(item, nextitem):
    """Where the last test's teardown begins (``__last_teardown__``)."""
    if nextitem is None:
        _last.update(cpu=_cpu(), wall=time.perf_counter())
    yield


def pytest_sessionfinish(session):
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    if worker == "main" and not _rows:   # the xdist controller: its workers ran the tests
        return
    with open(OUT, "a", encoding="utf-8") as f:
        for row in _rows + [{"id": "__session__", "cpu": round(_cpu(), 4), "wall": 0.0}]:
            f.write(json.dumps({**row, "worker": worker}) + "\n")


def summary(paths) -> str:
    """CPU seconds per test file (most first), per worker, and in all."""
    files, workers, sessions, ends = collections.Counter(), collections.Counter(), {}, {}
    for path in paths:
        with open(path, encoding="utf-8") as f:
            for row in map(json.loads, f):
                if row["id"] == "__session__":
                    sessions[row["worker"]] = row["cpu"]
                    continue
                files[row["id"].split("::")[0]] += row["cpu"]
                workers[row["worker"]] += row["cpu"]
                ends[row["worker"]] = max(ends.get(row["worker"], 0.0), row.get("end", 0.0))
    lines = [f"{cpu:8.1f}  {name}" for name, cpu in files.most_common()]
    lines += [f"tests {sum(files.values()):.1f} CPU s; per worker (tests / whole process): "
              + ", ".join(f"{w} {workers[w]:.1f} / {sessions.get(w, float('nan')):.1f}" for w in sorted(workers))]
    if len(ends) > 1 and all(ends.values()):
        last = max(ends.values())
        lines += ["idle at the end (wall s before the last worker's last test ended): "
                  + ", ".join(f"{w} {last - ends[w]:.1f}" for w in sorted(ends))]
    return "\n".join(lines)


if __name__ == "__main__":
    print(summary(sys.argv[1:] or [OUT]))
