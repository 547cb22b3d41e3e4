"""Where velpoly's time goes: the sweep of bench_sweep.py and the six-bar instant of bench_instant.py.

    python benchmarks/profile_kernel.py [--top 15]

Prints, for the 3600-pose four-bar sweep and the six-bar ``solve``:

* a stage breakdown (wall time of each kernel function ``sweep``/``solve``
  calls, found by wrapping them), with the number of constraint evaluations
  (``System.evaluate``) by batch size: one pose at a time (the knots'
  sequential continuation) or many at once;
* cProfile's top functions by own time and by cumulative time;
* ``python -X importtime``: the slowest imports when the API is first touched.

The evidence behind docs/requests/performance.md. It only reads the kernel
(wrapping functions in this process); it changes nothing.
"""
from __future__ import annotations

import argparse
import cProfile
import importlib
import io
import pstats
import re
import subprocess
import sys
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

from bench_sweep import ANGLES_DEG, FOURBAR

# the kernel functions timed, where they exist (the kernel changes; missing names are skipped)
SWEEP_STAGES = ("prepare", "_closed_form", "reassemble", "walk", "coordinates", "rates", "condition", "velocities",
                "accelerations", "evaluate_motion")
STAGES = {"velpoly.sweeps": SWEEP_STAGES,
          "velpoly.sweep": SWEEP_STAGES,        # the module's name before a4055dd
          "velpoly.solution": ("prepare", "reassemble", "velocities", "accelerations", "evaluate_motion"),
          "velpoly.pose": ("_closed_form", "assemble", "_step", "_newton", "_velocity", "_cond"),
          "velpoly.polygons": ("velocity_polygon", "acceleration_polygon"),
          "velpoly.poles": ("locate_poles",)}


class Recorder:
    """Wraps module functions and System.evaluate to time them and count evaluations."""

    def __init__(self):
        self.time = defaultdict(float)
        self.calls = defaultdict(int)
        self.evals = defaultdict(lambda: [0, 0.0])      # batch kind -> [calls, seconds]
        self._undo = []

    def wrap(self, owner, name, label, top_only=False):
        fn = getattr(owner, name, None)
        if fn is None:
            return
        depth = [0]

        def wrapper(*a, **k):
            depth[0] += 1
            t0 = time.perf_counter()
            try:
                return fn(*a, **k)
            finally:
                depth[0] -= 1
                self.calls[label] += 1
                if not top_only or depth[0] == 0:
                    self.time[label] += time.perf_counter() - t0
        setattr(owner, name, wrapper)
        self._undo.append((owner, name, fn))

    def install(self):
        for mod_name, names in STAGES.items():
            try:
                mod = importlib.import_module(mod_name)
            except ImportError:
                continue
            for n in names:
                self.wrap(mod, n, f"{mod_name.split('.')[1]}.{n}", top_only=(n == "_step"))
        from velpoly.constraints import System
        self.wrap(System, "residual", "System.residual")
        evaluate = System.evaluate

        def timed_evaluate(system, q, *a, **k):
            t0 = time.perf_counter()
            try:
                return evaluate(system, q, *a, **k)
            finally:
                n = np.atleast_2d(q).shape[0]
                rec = self.evals["1 pose" if n == 1 else f"{n} poses" if n < 100 else ">= 100 poses"]
                rec[0] += 1
                rec[1] += time.perf_counter() - t0
        System.evaluate = timed_evaluate
        self._undo.append((System, "evaluate", evaluate))
        return self

    def remove(self):
        for owner, name, fn in reversed(self._undo):
            setattr(owner, name, fn)
        self._undo.clear()

    def report(self, total: float):
        print(f"  total {total * 1e3:.2f} ms")
        for label, t in sorted(self.time.items(), key=lambda kv: -kv[1]):
            note = " (outer calls' time; count includes halvings)" if label.endswith("_step") else ""
            print(f"  {label:28s} {t * 1e3:9.2f} ms  {self.calls[label]:5d} calls{note}")
        for kind, (n, t) in sorted(self.evals.items(), key=lambda kv: -kv[1][1]):
            print(f"  System.evaluate, {kind:12s} {t * 1e3:9.2f} ms  {n:5d} calls  "
                  f"({t / n * 1e6:.0f} us each)")


def breakdown(title: str, fn, runs: int = 10):
    fn()                                                  # warm-up: caches, imports
    best = None
    for _ in range(runs):
        rec = Recorder().install()
        t0 = time.perf_counter()
        try:
            fn()
        finally:
            total = time.perf_counter() - t0
            rec.remove()
        if best is None or total < best[0]:
            best = (total, rec)
    print(f"\n{title}: stages (wrapped, best of {runs}; wrapping adds a little)")
    best[1].report(best[0])


def profile(title: str, fn, top: int, calls: int = 1):
    fn()
    pr = cProfile.Profile()
    pr.enable()
    for _ in range(calls):
        fn()
    pr.disable()
    for key in ("tottime", "cumulative"):
        s = io.StringIO()
        pstats.Stats(pr, stream=s).strip_dirs().sort_stats(key).print_stats(top)
        text = s.getvalue()
        body = text[text.index("ncalls"):] if "ncalls" in text else text
        print(f"\n{title}: cProfile, top {top} by {key} ({calls} call{'s' if calls > 1 else ''})")
        print(body.rstrip())


def import_times(top: int):
    code = "import velpoly; velpoly.load, velpoly.solve, velpoly.sweep"   # the package imports lazily
    proc = subprocess.run([sys.executable, "-X", "importtime", "-c", code],
                          capture_output=True, text=True)
    rows = []
    for line in proc.stderr.splitlines():
        m = re.match(r"import time:\s+(\d+) \|\s+(\d+) \|(\s*)(\S+)", line)
        if m:
            rows.append((int(m.group(2)), len(m.group(3)), m.group(4)))
    print(f"\n{code}: slowest imports (cumulative microseconds, python -X importtime), top {top}")
    for cum, indent, name in sorted(rows, reverse=True)[:top]:
        print(f"  {cum:8d} us  {'  ' * ((indent - 1) // 2)}{name}")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--top", type=int, default=15)
    args = p.parse_args(argv)
    import velpoly
    m4 = velpoly.load(FOURBAR)
    m6 = velpoly.load(Path(velpoly.__file__).parent / "examples" / "problem_1_4_4_sixbar.toml")
    breakdown("four-bar sweep, 3600 poses", lambda: velpoly.sweep(m4, ANGLES_DEG), runs=10)
    parts = []
    for mod_name, names in (("velpoly.polygons", ("velocity_polygon", "acceleration_polygon")),
                            ("velpoly.poles", ("locate_poles",))):
        try:
            mod = importlib.import_module(mod_name)
            parts += [(mod, n) for n in names if hasattr(mod, n)]
        except ImportError:
            print(f"{mod_name} not importable: left out of the instant")

    def instant():           # looked up at each call, so that the wrapped functions are the ones run
        sol = velpoly.solve(m6)
        for mod, n in parts:
            getattr(mod, n)(sol)
    what = "six-bar whole instant (solve" + "".join(f" + {n}" for _, n in parts) + ")"
    breakdown(what, instant, runs=20)
    profile("four-bar sweep, 3600 poses", lambda: velpoly.sweep(m4, ANGLES_DEG), args.top)
    profile(what, instant, args.top, calls=100)
    import_times(args.top)
    return 0


if __name__ == "__main__":
    sys.exit(main())
