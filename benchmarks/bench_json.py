"""`velpoly.solve(m).to_dict()`: what `velpoly solve --json` computes, against solve alone and the code before.

    python benchmarks/bench_json.py [--repeats 5] [--json OUT] [--file MECHANISM.toml] [--before COMMIT]

The six-bar of ``velpoly/examples/problem_1_4_4_sixbar.toml`` (FORMAT.md section 1) loaded once,
then, side by side in rounds (best of ``--repeats`` batches of 100 calls, per call, CPU time of the
process: steadier than wall time on a machine shared with other work):

* to_dict:   ``velpoly.solve(m).to_dict()`` (target, issue 20: under 1 ms): the construction plan kept for
  the mechanism is re-used at each call (``velpoly.polygons`` keeps a mechanism's plans and re-uses one
  at a pose that makes every pose-dependent decision alike);
* afresh:    the same with no plan kept (the plans dropped before each call): the first pose of a
  mechanism, what one ``velpoly solve --json`` process does;
* solve:     ``velpoly.solve(m)`` alone, the floor (pose, velocities, accelerations);
* instant:   solve, both polygons and all poles (``bench_instant.py``'s instant);
* json text: ``json.dumps(to_dict, indent=2)``, what the command prints, on top of to_dict;
* before:    to_dict (and the whole instant) of the velpoly of ``--before`` (default: the commit before issue 20's work),
  exported from git, against this checkout's, each timed alike in a fresh process of its own in
  every round, best of 5 batches each (the ratio before / now comes from these two).

The JSON of this checkout and of the commit before are compared first: the bytes must be the same.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _common import ROOT, export, file_before_arguments, finish, row

CALLS = 100

TIMER = r'''
import json, sys, time
import velpoly
m = velpoly.load(sys.argv[1])
calls, repeats = int(sys.argv[2]), int(sys.argv[3])
from velpoly.polygons import velocity_polygon, acceleration_polygon
from velpoly.poles import locate_poles
text = json.dumps(velpoly.solve(m).to_dict(), indent=2, allow_nan=False, sort_keys=True)   # the order of a dict's keys is not the JSON's content

def instant():
    sol = velpoly.solve(m)
    velocity_polygon(sol), acceleration_polygon(sol), locate_poles(sol)

instant()
best = {"best": float("inf"), "instant": float("inf")}
for _ in range(repeats):
    for key, fn in (("best", lambda: velpoly.solve(m).to_dict()), ("instant", instant)):
        t0 = time.process_time()
        for _ in range(calls):
            fn()
        best[key] = min(best[key], (time.process_time() - t0) / calls)
print(json.dumps(dict(best, text=text)))
'''


def per_call(fn, calls: int) -> float:
    t0 = time.process_time()
    for _ in range(calls):
        fn()
    return (time.process_time() - t0) / calls


def main(argv=None) -> int:
    args = file_before_arguments(__doc__, argv)
    import velpoly
    from velpoly import polygons
    from velpoly.poles import locate_poles
    from velpoly.polygons import acceleration_polygon, velocity_polygon
    notes: list[str] = []
    m = velpoly.load(args.file)
    ours = json.dumps(velpoly.solve(m).to_dict(), indent=2, allow_nan=False, sort_keys=True)

    def instant():
        sol = velpoly.solve(m)
        velocity_polygon(sol)
        acceleration_polygon(sol)
        locate_poles(sol)

    def afresh():
        polygons._PLANS.clear()   # (private: the benchmark's view of the first pose of a mechanism)
        return velpoly.solve(m).to_dict()

    contenders = {"to_dict": lambda: velpoly.solve(m).to_dict(), "afresh": afresh, "solve": lambda: velpoly.solve(m),
                  "instant": instant,
                  "json text": lambda: json.dumps(velpoly.solve(m).to_dict(), indent=2, allow_nan=False)}
    best = dict.fromkeys(contenders, float("inf"))
    with tempfile.TemporaryDirectory(prefix="velpoly-bench-json-") as tmp:
        old = export(args.before, Path(tmp) / "before")
        if old is None:
            notes.append(f"commit {args.before} not available (git archive failed): no 'before'")
        else:
            best["before"] = best["now"] = best["instant before"] = best["instant now"] = float("inf")
        for fn in contenders.values():
            fn()                                                   # warm-up (prepare is cached per mechanism)
        for _ in range(args.repeats):                              # side by side: one batch of each a round
            for name, fn in contenders.items():
                best[name] = min(best[name], per_call(fn, CALLS))
            for which, where in (("before", old), ("now", ROOT)) if old is not None else ():
                proc = subprocess.run([sys.executable, "-c", TIMER, args.file, str(CALLS), "5"],
                                      capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(where)),
                                      cwd=tmp)   # not the checkout: python -c puts the folder first on the path
                if proc.returncode:
                    raise SystemExit(f"the velpoly of {where} failed: {proc.stderr.strip()[-300:]}")
                got = json.loads(proc.stdout)
                if got["text"] != ours:
                    print(f"the JSON of {args.before} and of this checkout differ", file=sys.stderr)
                    return 1
                best[which] = min(best[which], got["best"])
                best[f"instant {which}"] = min(best[f"instant {which}"], got["instant"])
    name = Path(args.file).name
    print(f"{name}, per call, CPU time, best of {args.repeats} x {CALLS} calls"
          + (f"; the JSON the same as {args.before}'s (keys sorted)" if old is not None else "") + ":")
    for k, v in best.items():
        print(f"  {k:14s} {v * 1e3:8.3f} ms" + (f"   ({v / best['solve']:.2f}x solve)" if k != "solve" else ""))
    t = best["to_dict"]
    rows = [row("to_dict: velpoly.solve(m).to_dict(), six-bar", t * 1e3, "ms", "< 1 ms", t < 1e-3),
            row("to_dict: solve(m) alone (the floor)", best["solve"] * 1e3, "ms"),
            row("to_dict, no plan kept (a mechanism's first pose)", best["afresh"] * 1e3, "ms"),
            row("to_dict / solve alone", t / best["solve"], "x"),
            row("to_dict / whole instant (solve, polygons, poles)", t / best["instant"], "x"),
            row("to_dict + json.dumps (solve --json's work)", best["json text"] * 1e3, "ms")]
    if "before" in best:
        rows += [row(f"to_dict before ({args.before}), a process of its own", best["before"] * 1e3, "ms"),
                 row("to_dict now, a process of its own", best["now"] * 1e3, "ms"),
                 row("to_dict: before / now", best["before"] / best["now"], "x", note="same JSON bytes"),
                 row(f"whole instant before ({args.before}), a process of its own", best["instant before"] * 1e3, "ms"),
                 row("whole instant now, a process of its own", best["instant now"] * 1e3, "ms"),
                 row("whole instant: before / now", best["instant before"] / best["instant now"], "x")]
    notes.append("CPU time of the process (time.process_time), per call")
    return finish("json", args, rows, notes)


if __name__ == "__main__":
    sys.exit(main())
