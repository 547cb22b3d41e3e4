"""Shared helpers of the benchmark scripts (not a test module, not part of the package).

Every ``bench_*.py`` prints its own report and, with ``--json PATH``, writes
its measurements as ``{"bench": name, "rows": [...], "notes": [...]}`` for
``run_all.py``. A row is one line of the summary table::

    {"what": "sweep: velpoly vs floor", "value": 3.2, "unit": "x",
     "target": "<= 4x", "met": True}

``met`` is None where there is no target or the measurement was skipped.
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import shlex
import io
import subprocess
import sys
import tarfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HERE = Path(__file__).resolve().parent
LOAD_AT_START = os.getloadavg()[0] if hasattr(os, "getloadavg") else None   # before our own work adds to it


def parser(description: str) -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--json", metavar="PATH", help="also write the measurements as JSON (for run_all.py)")
    p.add_argument("--repeats", type=int, default=5, help="repeats; the best is reported (default 5)")
    return p


def command_line() -> str:
    """The command that is running, as a user would type it from the repository's root."""
    script = Path(sys.argv[0]).resolve()
    try:
        script = script.relative_to(ROOT)
    except ValueError:
        pass
    return " ".join(["python", shlex.quote(str(script))] + [shlex.quote(a) for a in sys.argv[1:]])


def machine_note() -> str:
    """One line about the machine, the versions and the 1-minute load when this process started."""
    import numpy as np
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    load = "" if LOAD_AT_START is None else f", load average {LOAD_AT_START:.2f} at start"
    return (f"{cores} cores ({cpu}), {platform.system()} {platform.release()}, "
            f"Python {platform.python_version()}, numpy {np.__version__}{load}")


def code_note() -> str:
    """Which velpoly was measured: the commit, and whether the working tree had changes."""
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              cwd=ROOT, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "velpoly"],
                               capture_output=True, text=True, cwd=ROOT, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "velpoly (commit unknown)"
    if not head:
        return "velpoly (not a git checkout)"
    return f"velpoly at {head}" + (" with uncommitted changes in velpoly/" if dirty else "")


def interleaved(contenders: dict, repeats: int) -> dict:
    """Time every contender ``repeats`` times, round-robin, so all are measured side by side.

    A contender is a zero-argument callable, timed whole, or a ``(setup, run)``
    pair: ``setup()`` is not timed, ``run(setup())`` is. Returns name -> list
    of seconds.
    """
    times = {name: [] for name in contenders}
    for _ in range(repeats):
        for name, job in contenders.items():
            setup, run = job if isinstance(job, tuple) else (None, job)
            arg = setup() if setup else None
            t0 = time.perf_counter()
            run(arg) if setup else run()
            times[name].append(time.perf_counter() - t0)
    return times


def best_of(fn, repeats: int, number: int = 1) -> float:
    """Best wall time of ``number`` calls of fn, over ``repeats`` repeats, per call (seconds)."""
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


def run_timed(cmd, repeats: int, **kw):
    """Run a command ``repeats`` times; returns (best seconds, the last CompletedProcess)."""
    best, proc = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True, **kw)
        best = min(best, time.perf_counter() - t0)
        if proc.returncode != 0:
            break
    return best, proc


def row(what: str, value, unit: str, target: str = "", met=None, note: str = "") -> dict:
    return {"what": what, "value": value, "unit": unit, "target": target, "met": met, "note": note}


def verdict(met) -> str:
    return "met" if met is True else "NOT met" if met is False else "-"


def fmt_value(value, unit: str) -> str:
    if value is None:
        return "skipped"
    if unit == "x":
        return f"{value:.3g}x"
    return f"{value:.4g} {unit}"


def table(rows: list[dict], markdown: bool = True) -> str:
    """The rows as a table (markdown pipes, which also read well in a terminal)."""
    head = ("measurement", "value", "target", "verdict", "note")
    body = [(r["what"], fmt_value(r["value"], r["unit"]), r["target"] or "-", verdict(r["met"]),
             r.get("note", "")) for r in rows]
    widths = [max(len(h), *(len(b[i]) for b in body)) if body else len(h) for i, h in enumerate(head)]
    line = lambda cells: "| " + " | ".join(c.ljust(w) for c, w in zip(cells, widths)) + " |"  # noqa: E731
    out = [line(head), "|" + "|".join("-" * (w + 2) for w in widths) + "|"]
    out += [line(b) for b in body]
    return "\n".join(out)


def finish(name: str, args, rows: list[dict], notes: list[str]) -> int:
    """Print the summary of one benchmark and write its JSON; exit status 0."""
    print()
    print(table(rows))
    for n in notes:
        print(f"note: {n}")
    print(f"machine: {machine_note()}")
    print(f"code: {code_note()}")
    print(f"command: {command_line()}")
    if args.json:
        Path(args.json).write_text(json.dumps({"bench": name, "rows": rows, "notes": notes,
                                               "machine": machine_note(), "code": code_note(),
                                               "command": command_line()}, indent=2))
    return 0


BEFORE = "dec406d"   # the last commit before issue 20's work on the JSON, the sheets, the draw command and the gallery


def file_before_arguments(doc: str, argv=None) -> argparse.Namespace:
    """A benchmark's arguments: ``--file`` (a mechanism, default Problem 1.4.4's six-bar, made absolute)
    and ``--before`` (the commit to compare with), besides :func:`parser`'s."""
    p = parser(doc.splitlines()[0])
    p.add_argument("--file", default=str(ROOT / "velpoly" / "examples" / "problem_1_4_4_sixbar.toml"))
    p.add_argument("--before", default=BEFORE, help="the commit to compare with (default %(default)s)")
    args = p.parse_args(argv)
    args.file = str(Path(args.file).resolve())
    return args


def export(commit: str, dest: Path) -> Path | None:
    """The ``velpoly`` package of ``commit`` under ``dest``; None where git cannot give it."""
    try:
        data = subprocess.run(["git", "archive", "--format=tar", commit, "velpoly"], cwd=ROOT,
                              capture_output=True, timeout=60, check=True).stdout
    except (OSError, subprocess.SubprocessError):
        return None
    with tarfile.open(fileobj=io.BytesIO(data)) as tar:
        tar.extractall(dest, filter="data")
    return dest


def bytecode_env(tmp: Path, **extra) -> dict:
    """The environment of a timed subprocess: bytecode cached (in ``tmp``), as an installed package has
    it, even where PYTHONDONTWRITEBYTECODE is set (then every run would compile velpoly's source anew:
    0.2-0.35 s here). Run each command once untimed to fill the cache."""
    env = dict(os.environ, PYTHONPYCACHEPREFIX=str(Path(tmp) / "pycache"), **extra)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env
