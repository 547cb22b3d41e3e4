"""Run every benchmark and print one summary table of the measurements and ratios.

    python benchmarks/run_all.py [--repeats 5] [--update-doc]

Runs ``bench_sweep.py``, ``bench_instant.py``, ``bench_json.py``, ``bench_sheet.py``, ``bench_draw.py``,
``bench_gallery.py``, ``bench_animate.py``,
``bench_poles.py`` (where present) and any other ``benchmarks/bench_*.py``,
each in its own process, one after the other, showing their reports; then
prints the summary with the machine and this command. ``--update-doc``
also writes the summary into docs/performance.md between the markers
``<!-- results:start -->`` and ``<!-- results:end -->``. Exit status 1 if
any benchmark failed (a crash, or contenders that disagree).
"""
from __future__ import annotations

import datetime
import json
import subprocess
import sys
import tempfile
from pathlib import Path

from _common import HERE, ROOT, code_note, command_line, machine_note, row, table

ORDER = ["bench_sweep.py", "bench_instant.py", "bench_json.py", "bench_sheet.py", "bench_draw.py", "bench_gallery.py",
         "bench_poles.py", "bench_animate.py"]
DOC = ROOT / "docs" / "performance.md"
START, END = "<!-- results:start -->", "<!-- results:end -->"


def scripts() -> list[Path]:
    found = {p.name: p for p in HERE.glob("bench_*.py")}
    return [found[n] for n in ORDER if n in found] + [p for n, p in sorted(found.items()) if n not in ORDER]


def run(script: Path, repeats: int, tmp: Path):
    """Run one benchmark and show its output when it ends; returns (exit status, JSON or None)."""
    out = tmp / (script.stem + ".json")
    attempts = [["--json", str(out), "--repeats", str(repeats)], ["--json", str(out)], []]
    for extra in attempts:          # a benchmark that does not take our options still runs
        proc = subprocess.run([sys.executable, str(script)] + extra, capture_output=True, text=True,
                              cwd=ROOT)
        if not (proc.returncode == 2 and "unrecognized arguments" in proc.stderr):
            break
    sys.stdout.write(proc.stdout)
    sys.stderr.write(proc.stderr)
    data = json.loads(out.read_text()) if out.exists() else None
    return proc.returncode, data


def main(argv=None) -> int:
    import argparse
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5, help="repeats of each benchmark (best reported)")
    p.add_argument("--update-doc", action="store_true", help=f"write the summary into {DOC.relative_to(ROOT)}")
    args = p.parse_args(argv)
    rows, notes, failed = [], [], []
    with tempfile.TemporaryDirectory(prefix="velpoly-bench-") as tmp:
        for script in scripts():
            print(f"=== {script.name} " + "=" * max(0, 60 - len(script.name)), flush=True)
            status, data = run(script, args.repeats, Path(tmp))
            if status != 0:
                failed.append(script.name)
            if data:
                rows += data["rows"]
                notes += [f"{script.stem}: {n}" for n in data.get("notes", [])]
            else:
                rows.append(row(f"{script.stem}", None, "", note=f"exit {status}; see its output above"))
            print(flush=True)
    machine, code, command = machine_note(), code_note(), command_line()
    when = datetime.date.today().isoformat()
    print("=== summary " + "=" * 57)
    print(table(rows))
    for n in notes:
        print(f"note: {n}")
    print(f"machine: {machine}\ncode: {code}\ncommand: {command}\ndate: {when}")
    if failed:
        print(f"failed: {', '.join(failed)}")
    if args.update_doc:
        text = DOC.read_text() if DOC.exists() else f"{START}\n{END}\n"
        if START not in text or END not in text:
            raise SystemExit(f"{DOC}: the markers {START} and {END} are missing")
        block = [START, "", table(rows), ""] + [f"- {n}" for n in notes] + \
                ["", f"Machine: {machine}.  ", f"Code: {code}.  ", f"Command: `{command}`, {when}.", "", END]
        head, rest = text.split(START, 1)
        DOC.write_text(head + "\n".join(block) + rest.split(END, 1)[1])
        print(f"wrote the summary into {DOC.relative_to(ROOT)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
