"""CPU seconds per test, for measuring the suite on a machine that other work loads (docs/internals.md,
"Tests: keeping the suite fast"): wall times there say little, a test's CPU seconds do.

    python3 -m pytest -p tests.cputimes                      # each worker appends to .cputimes.jsonl
    python3 -m tests.cputimes .cputimes.jsonl [more.jsonl]   # CPU seconds per file, per worker, in all

A test's CPU is ``os.times()``' user + system, its waited-for children's included (a subprocess, a forked
pool's workers), over its setup, call and teardown, so a module fixture counts in the test that first
needs it; ``end`` is the wall clock (seconds since the epoch) when it ended. Each process also records its
CPU at the session's end (``__session__``: collection and start-up included). The summary gives each
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


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    cpu, wall = _cpu(), time.perf_counter()
    yield
    _rows.append({"id": item.nodeid, "cpu": round(_cpu() - cpu, 4), "wall": round(time.perf_counter() - wall, 4),
                  "end": round(time.time(), 3)})


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
