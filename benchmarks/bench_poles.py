"""All the instant centres of long chains: 190 poles of a 20-link chain up to 19,900 of a 200-link one.

    python benchmarks/bench_poles.py [--repeats 5] [--json OUT] [--sizes 20,50,100,200]

Two chains (tests/chains.py). The stage chain of DESIGN.md section 5: the frame, a crank, then nine
four-bar stages in series (20 links, 28 pins), timed against its target, under 50 ms, with the
instant-centre method and, for scale, the six-bar of ``velpoly/examples``. Then the growth (issue 20):
a chain of nearly parallelogram stages (every link turning at about the crank's speed, so that every
one of the n(n-1)/2 poles is defined) at n = 20, 50, 100 and 200 links: ``locate_poles`` uncached,
best of ``--repeats`` (at most 3 at 100 links and more), wall and CPU time, the exponent of the
growth between sizes (from the CPU times, steadier than wall times on a machine shared with other work),
and at 200 links the peak memory it allocates (tracemalloc, in a run of its own). Target at 200
links: under 1 s. The first solve of each chain (the equations prepared, the velocities and
accelerations) is timed once and printed, and at the largest size reported as a row of its own,
with the BLAS threads it ran with (see docs/performance.md: on a loaded machine OpenBLAS's threads
cost more than they bring at this size).

Every result is checked before it is timed: all n(n-1)/2 poles, none undefined, every pin's pole the
pin exactly, and the largest disagreement with the velocity solution under 1e-9.
"""
from __future__ import annotations

import collections
import math
import os
import sys
import time
import tracemalloc
from pathlib import Path

from _common import ROOT, best_of, finish, parser, row

sys.path.insert(0, str(ROOT / "tests"))
from chains import parallel_chain, stage_chain  # noqa: E402


def check(sol, ps) -> collections.Counter:
    """The poles are all there, every pin is its pole exactly, and they agree with the velocities."""
    import numpy as np
    n = len(sol.mechanism.links)
    assert len(ps) == n * (n - 1) // 2, len(ps)
    assert ps.max_error < 1e-9, ps.max_error
    for pin in sol.mechanism.pins:
        p = ps.pole(*pin.links)
        assert p.how == "pin" and np.array_equal(p.position, sol.place(pin.links[0], pin.point)), pin
    return collections.Counter(p.how for p in ps.poles.values())


def wall_and_cpu(fn, repeats: int) -> tuple[float, float]:
    """The best wall time and the best CPU time (this process) of ``repeats`` calls, seconds. On a
    machine shared with other work the CPU time is the steadier measure of the work itself."""
    wall = cpu = float("inf")
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        wall, cpu = min(wall, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
    return wall, cpu


def main(argv=None) -> int:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--sizes", default="20,50,100,200", help="chain sizes for the growth (links)")
    args = p.parse_args(argv)
    import velpoly
    from velpoly.poles import instant_centre_velocities, locate_poles

    notes: list[str] = []
    sol = velpoly.solve(velpoly.load(stage_chain()))
    n = len(sol.mechanism.links)
    ps = locate_poles(sol, cached=False)
    ic = instant_centre_velocities(sol, ps)
    hows = check(sol, ps)
    assert max(ic["max_error"].values()) < 1e-9, ic["max_error"]

    t_poles = best_of(lambda: locate_poles(sol, cached=False), args.repeats, 10)
    t_ic = best_of(lambda: instant_centre_velocities(sol, ps), args.repeats, 10)
    six = velpoly.solve(velpoly.load(Path(velpoly.__file__).parent / "examples" / "problem_1_4_4_sixbar.toml"))
    t_six = best_of(lambda: locate_poles(six, cached=False), args.repeats, 100)
    c_six = min(wall_and_cpu(lambda: [locate_poles(six, cached=False) for _ in range(100)], args.repeats)[1] / 100,
                t_six)

    print(f"{sol.mechanism.title}: {n} links, {len(ps)} poles "
          f"({', '.join(f'{k} {v}' for k, v in sorted(hows.items()))}), {len(ps.order)} found in "
          f"order; largest deviation from the velocity solution {ps.max_error:.1e}")
    print(f"  locate_poles                 {t_poles * 1e3:8.3f} ms   (best of {args.repeats} x 10 calls)")
    print(f"  instant_centre_velocities    {t_ic * 1e3:8.3f} ms   (omegas {ic['max_error']['omega']:.1e}, "
          f"speeds {ic['max_error']['velocity']:.1e} from the analytic solve)")
    print(f"  six-bar example, 15 poles    {t_six * 1e3:8.3f} ms   (CPU {c_six * 1e3:.3f} ms: the yardstick of how "
          f"loaded the machine is; 0.23-0.24 ms on a quiet one)")
    if hows.get("velocity"):
        notes.append(f"{hows['velocity']} poles came from the velocity solution (Kennedy stalled)")
    rows = [row(f"poles: {len(ps)} of a {n}-link chain", t_poles * 1e3, "ms", "< 50 ms", t_poles < 0.05),
            row("poles: instant-centre method, same chain", t_ic * 1e3, "ms"),
            row("poles: six-bar example (15 poles)", t_six * 1e3, "ms", note=f"CPU {c_six * 1e3:.3g} ms")]

    print("growth: chains of nearly parallelogram stages (tests/chains.py parallel_chain)")
    sizes = [int(x) for x in args.sizes.split(",") if x]
    times = {}
    for size in sizes:
        mech = velpoly.load(parallel_chain(size))
        t0, c0 = time.perf_counter(), time.process_time()
        s = velpoly.solve(mech)   # the first solve of a mechanism prepares its equations (kinematics.prepare)
        t_solve, c_solve = time.perf_counter() - t0, time.process_time() - c0
        ps = locate_poles(s, cached=False)
        hows = check(s, ps)
        assert not hows.get("undefined"), hows
        reps = args.repeats if size < 100 else min(args.repeats, 3)
        t, cpu = wall_and_cpu(lambda: locate_poles(s, cached=False), reps)
        times[size] = cpu   # the growth from CPU times: steadier than wall times on a shared machine
        extra = ""
        if size == max(sizes):
            tracemalloc.start()
            locate_poles(s, cached=False)
            peak = tracemalloc.get_traced_memory()[1] / 2 ** 20
            tracemalloc.stop()
            extra = f", peak {peak:.0f} MB allocated"
        npoles = size * (size - 1) // 2
        print(f"  {size:4d} links  {npoles:6d} poles  {t * 1e3:9.1f} ms, CPU {cpu * 1e3:7.1f} ms  (best of {reps}; "
              f"solve {t_solve:.1f} s, "
              f"{', '.join(f'{k} {v}' for k, v in sorted(hows.items()))}, deviation {ps.max_error:.1e}{extra})")
        target = ("< 1 s", t < 1.0) if size == 200 else ("", None)
        rows.append(row(f"poles: all {npoles:,} of a {size}-link chain", t * 1e3, "ms", *target,
                        note=f"CPU {cpu * 1e3:.4g} ms" + extra))
        if size == max(sizes):
            rows.append(row(f"solve: the {size}-link chain (first solve, equations prepared)", t_solve, "s",
                            note=f"CPU {c_solve:.3g} s; BLAS threads: OPENBLAS_NUM_THREADS="
                                 f"{os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}"))
    for a, b in zip(sizes, sizes[1:]):
        k = math.log(times[b] / times[a]) / math.log(b / a)
        print(f"  growth {a} -> {b} links: n^{k:.2f} (CPU times)")
    if len(sizes) > 1:
        a, b = sizes[0], sizes[-1]
        rows.append(row(f"poles: growth exponent, {a} to {b} links", math.log(times[b] / times[a]) / math.log(b / a),
                        "", note="CPU time ~ n^k; the poles themselves are n^2"))
    return finish("poles", args, rows, notes)


if __name__ == "__main__":
    sys.exit(main())
