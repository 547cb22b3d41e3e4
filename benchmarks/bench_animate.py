"""`velpoly animate` against the `velpoly sweep --gif` it replaces, per frame, side by side.

    python benchmarks/bench_animate.py [--repeats 3] [--json OUT] [--file MECHANISM.toml] [--baseline COMMIT]

Both are timed as whole processes (start-up, imports, the sweep, every frame, the file), side by
side, best of ``--repeats``:

* animate: ``velpoly animate FILE -o OUT.gif --size 1280x720`` (a four-bar by default: 180 frames,
  one every 2 degrees), this checkout;
* before:  ``velpoly sweep FILE --step 8 --gif OUT.gif`` of the velpoly of ``--baseline`` (default
  0de6fa9, the last commit before `animate`: 45 frames of 648 x 324 px, each frame drawn anew),
  exported from git into a temporary folder; skipped with a note where git cannot export it.

Per frame: the process's time over its frames (the start-up and the sweep included, so the
figures are an upper bound of each frame's cost). Targets (issue 15): animate at least 10 frames
a second at 1280 x 720, so the 180 frames take under 20 s; and the ratio of seconds a frame,
before / animate, is reported.
"""
from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

from _common import ROOT, export, finish, parser, row, run_timed

BASELINE = "0de6fa9"


def frames_of(gif: Path) -> int:
    from PIL import Image
    with Image.open(gif) as im:
        return im.n_frames


def main(argv=None) -> int:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--file", default=str(ROOT / "velpoly" / "examples" / "ex3_6_fourbar.toml"))
    p.add_argument("--baseline", default=BASELINE)
    p.set_defaults(repeats=3)
    args = p.parse_args(argv)
    notes = []
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    with tempfile.TemporaryDirectory(prefix="velpoly-bench-animate-") as tmp:
        tmp = Path(tmp)
        old = export(args.baseline, tmp / "before")
        new_cmd = [sys.executable, "-m", "velpoly", "animate", args.file, "-o", str(tmp / "new.gif"),
                   "--size", "1280x720"]
        old_cmd = [sys.executable, "-m", "velpoly", "sweep", args.file, "--step", "8", "--gif", str(tmp / "old.gif")]
        best = {"animate": float("inf"), "before": float("inf")}
        cpu = float("inf")
        for _ in range(args.repeats):          # side by side: one of each per round
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            t, proc = run_timed(new_cmd, 1, env=env, cwd=tmp)
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = min(cpu, (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime))
            if proc.returncode:
                print(proc.stderr, file=sys.stderr)
                return 1
            best["animate"] = min(best["animate"], t)
            if old is not None:
                t, proc_old = run_timed(old_cmd, 1, env=dict(os.environ, PYTHONPATH=str(old)), cwd=tmp)
                if proc_old.returncode:
                    notes.append(f"the baseline failed: {proc_old.stderr.strip()[-200:]}")
                    old = None
                else:
                    best["before"] = min(best["before"], t)
        n_new = frames_of(tmp / "new.gif")
        size_new = (tmp / "new.gif").stat().st_size
        per_new = best["animate"] / n_new
        print(f"animate: {n_new} frames at 1280x720 in {best['animate']:.2f} s ({n_new / best['animate']:.1f} "
              f"frames/s), {size_new / 1e6:.2f} MB")
        rows = [row("animate: four-bar, 180 frames at 1280x720, whole command", best["animate"], "s",
                    "< 20 s", best["animate"] < 20.0),
                row("animate: frames a second (whole command)", n_new / best["animate"], "frames/s", ">= 10",
                    n_new / best["animate"] >= 10.0),
                row("animate: frames a CPU second (user + sys, whole command)", n_new / cpu, "frames/s", ">= 10",
                    n_new / cpu >= 10.0, "less sensitive to other load than the wall time")]
        if old is not None:
            n_old = frames_of(tmp / "old.gif")
            per_old = best["before"] / n_old
            print(f"before ({args.baseline}): sweep --gif, {n_old} frames at 648x324 in {best['before']:.2f} s "
                  f"({n_old / best['before']:.2f} frames/s)")
            rows.append(row(f"sweep --gif before ({args.baseline}): seconds a frame, 648x324", per_old, "s"))
            rows.append(row("seconds a frame: before / animate (animate's frames 4.4x the pixels)",
                            per_old / per_new, "x", "", None))
        else:
            notes.append(f"baseline {args.baseline} not available (git archive failed): ratio skipped")
    notes.append(f"file: {Path(args.file).name}")
    return finish("animate", args, rows, notes)


if __name__ == "__main__":
    sys.exit(main())
