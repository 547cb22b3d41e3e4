"""A whole crank turn of a four-bar, 3600 poses: velpoly against pylinkage, mechanism and a numpy floor.

    python benchmarks/bench_sweep.py [--repeats 5] [--mechanism-poses 3600] [--json OUT]

The four-bar (the `mechanism` package's README example): frame A-D = 8, crank
A-B = 5, coupler B-C = 8, rocker D-C = 9, omega = 10 rad/s, alpha = 0, C
above the frame. Poses at crank angles 0.1, 0.2, ..., 360 degrees: the poses
pylinkage's ``step_with_derivatives`` yields after each of its 3600 steps.

Contenders, all timed in this one process, round-robin, best of ``--repeats``:

* velpoly:   ``velpoly.sweep(m, angles)`` (positions, velocities, accelerations
             of every point and link), ``m`` loaded once from a dict;
* pylinkage: ``Linkage.step_with_derivatives`` (a Python loop over poses, each
             dyad in closed form), the linkage built untimed before each run;
* mechanism: ``Mechanism.iterate()`` (three scipy ``fsolve`` calls per pose),
             built untimed before each run; ``--mechanism-poses N`` times the
             first N poses only and scales per pose (said in the output);
* floor:     positions, velocities and accelerations of B and C and the link
             rates in closed form, vectorised over all 3600 angles at once.

Every contender's positions (and velocities and accelerations, where it
gives them) are checked against the floor before any number is reported;
a disagreement beyond the stated tolerance makes the exit status 1.
"""
from __future__ import annotations

import math
import sys
import time

import numpy as np

from _common import finish, interleaved, parser, row

N = 3600
FRAME, CRANK, COUPLER, ROCKER = 8.0, 5.0, 8.0, 9.0
OMEGA, ALPHA = 10.0, 0.0
ANGLES_DEG = 0.1 * np.arange(1, N + 1)          # 0.1 .. 360 degrees
THETA = np.radians(ANGLES_DEG)

FOURBAR = {
    "format": 1,
    "title": "Four-bar 5-8-8-9 (benchmark)",
    "units": "in",
    "points": {
        "A": [0, 0],
        "D": [FRAME, 0],
        "B": {"from": "A", "length": CRANK, "angle": 0},
        "C": {"circles": [["B", COUPLER], ["D", ROCKER]], "side": "left"},
    },
    "links": {
        "1": {"points": ["A", "D"], "frame": True},
        "2": {"points": ["A", "B"]},
        "3": {"points": ["B", "C"]},
        "4": {"points": ["D", "C"]},
    },
    "driver": {"link": "2", "omega": OMEGA, "alpha": ALPHA},
}

# Largest relative difference from the floor (of the largest magnitude over the cycle) allowed.
TOLERANCE = {"velpoly": 1e-9, "pylinkage": 1e-9, "mechanism": 1e-6}


# -- the floor: closed form, vectorised -------------------------------------------------------
def floor(theta, a=CRANK, b=COUPLER, c=ROCKER, d=FRAME, w=OMEGA, al=ALPHA):
    """B and C, their velocities and accelerations, and the coupler's and rocker's rates."""
    ct, st = np.cos(theta), np.sin(theta)
    bx, by = a * ct, a * st
    vbx, vby = -a * w * st, a * w * ct
    abx, aby = -a * w * w * ct - a * al * st, -a * w * w * st + a * al * ct
    ex, ey = d - bx, -by                             # B -> D
    l2 = ex * ex + ey * ey
    s = (b * b - c * c + l2) / (2.0 * l2)            # along B -> D, in units of |BD|
    h = np.sqrt(b * b / l2 - s * s)                  # to the left, in units of |BD|
    cx, cy = bx + s * ex - h * ey, by + s * ey + h * ex
    ux, uy = cx - bx, cy - by                        # coupler B -> C
    rx, ry = cx - d, cy                              # rocker D -> C
    det = ux * ry - uy * rx
    k = ux * vbx + uy * vby                          # u . V_C = u . V_B, r . V_C = 0
    vcx, vcy = k * ry / det, -k * rx / det
    dvx, dvy = vcx - vbx, vcy - vby
    r1 = ux * abx + uy * aby - (dvx * dvx + dvy * dvy)
    r2 = -(vcx * vcx + vcy * vcy)
    acx, acy = (r1 * ry - r2 * uy) / det, (ux * r2 - rx * r1) / det
    w3 = (ux * dvy - uy * dvx) / (b * b)
    w4 = (rx * vcy - ry * vcx) / (c * c)
    a3 = (ux * (acy - aby) - uy * (acx - abx)) / (b * b)
    a4 = (rx * acy - ry * acx) / (c * c)
    return {"B": np.stack([bx, by], 1), "C": np.stack([cx, cy], 1),
            "V_B": np.stack([vbx, vby], 1), "V_C": np.stack([vcx, vcy], 1),
            "A_B": np.stack([abx, aby], 1), "A_C": np.stack([acx, acy], 1),
            "omega_3": w3, "omega_4": w4, "alpha_3": a3, "alpha_4": a4}


# -- velpoly -------------------------------------------------------------------------------------
def velpoly_job():
    import velpoly
    m = velpoly.load(FOURBAR)
    return lambda: velpoly.sweep(m, ANGLES_DEG)


def velpoly_result(w):
    if len(w.angles) != N:
        raise SystemExit(f"velpoly solved {len(w.angles)} of {N} poses: {w.stopped}")
    return {"B": w.position["B"], "C": w.position["C"], "V_B": w.velocity["B"],
            "V_C": w.velocity["C"], "A_B": w.acceleration["B"], "A_C": w.acceleration["C"],
            "omega_3": w.omega["3"], "omega_4": w.omega["4"], "alpha_3": w.alpha["3"],
            "alpha_4": w.alpha["4"]}


# -- pylinkage -----------------------------------------------------------------------------------
def pylinkage_job():
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import RRRDyad
    from pylinkage.simulation import Linkage

    def setup():
        a, d = Ground(0.0, 0.0, name="A"), Ground(FRAME, 0.0, name="D")
        crank = Crank(anchor=a, radius=CRANK, angular_velocity=2 * math.pi / N, name="B")
        # x, y: the hint that picks C's branch (pylinkage keeps the intersection nearest to it)
        rocker = RRRDyad(crank.output, d, distance1=COUPLER, distance2=ROCKER, x=3.7, y=7.9, name="C")
        linkage = Linkage([a, d, crank, rocker], name="four-bar")
        linkage.set_input_velocity(crank, omega=OMEGA, alpha=ALPHA)
        return linkage
    return setup, lambda linkage: list(linkage.step_with_derivatives(iterations=N))


def pylinkage_result(steps):
    pos = np.array([s[0] for s in steps], float)      # (N, components, 2): A, D, B, C
    vel = np.array([s[1] for s in steps], float)
    acc = np.array([s[2] for s in steps], float)
    return {"B": pos[:, 2], "C": pos[:, 3], "V_B": vel[:, 2], "V_C": vel[:, 3],
            "A_B": acc[:, 2], "A_C": acc[:, 3]}


# -- mechanism -----------------------------------------------------------------------------------
def mechanism_job(n):
    from mechanism import Mechanism, Vector, get_joints
    theta = THETA[:n]

    def setup():
        # the package's own four-bar: O crank pivot, A crank pin, B coupler-rocker pin, C rocker pivot
        o, a_, b_, c_ = get_joints("O A B C")
        a = Vector((o, a_), r=CRANK)
        b = Vector((a_, b_), r=COUPLER)
        c = Vector((o, c_), r=FRAME, theta=0, style="ground")
        d = Vector((c_, b_), r=ROCKER)

        def loop(x, i):
            return a(i) + b(x[0]) - c() - d(x[1])
        mech = Mechanism(vectors=(a, b, c, d), origin=o, loops=loop, pos=theta,
                         vel=np.full(n, OMEGA), acc=np.full(n, ALPHA),
                         guess=(np.radians([45.0, 90.0]), np.array([1000.0, 1000.0]),
                                np.array([1000.0, 1000.0])))
        return mech, (a_, b_)

    def run(built):
        built[0].iterate()
        return built[1]
    return setup, run


def mechanism_result(joints):
    crank_pin, pin = joints     # the package's A and B are velpoly's B and C

    def xy(j, what):
        return np.stack([getattr(j, f"x_{what}"), getattr(j, f"y_{what}")], 1)
    return {"B": xy(crank_pin, "positions"), "C": xy(pin, "positions"),
            "V_B": xy(crank_pin, "velocities"), "V_C": xy(pin, "velocities"),
            "A_B": xy(crank_pin, "accelerations"), "A_C": xy(pin, "accelerations")}


# -- agreement -----------------------------------------------------------------------------------
def disagreement(result: dict, ref: dict) -> dict:
    """quantity -> max |result - ref| / max |ref| over the poses result covers."""
    out = {}
    for key, val in result.items():
        r = ref[key][: len(val)]
        out[key] = float(np.max(np.abs(val - r)) / max(np.max(np.abs(r)), 1e-300))
    return out


def main(argv=None) -> int:
    p = parser(__doc__.splitlines()[0])
    p.add_argument("--mechanism-poses", type=int, default=N,
                   help=f"poses the mechanism package solves per run (default {N}: all); "
                        "fewer: time the first ones and scale per pose")
    args = p.parse_args(argv)
    n_mech = max(1, min(args.mechanism_poses, N))
    notes = []

    import velpoly
    t0 = time.perf_counter()
    cold = velpoly.sweep(velpoly.load(FOURBAR), ANGLES_DEG)
    t_cold = time.perf_counter() - t0
    del cold

    jobs = {"floor": lambda: floor(THETA), "velpoly": velpoly_job()}
    missing = []
    for name, make in (("pylinkage", pylinkage_job), ("mechanism", lambda: mechanism_job(n_mech))):
        try:
            jobs[name] = make()
        except ImportError as e:
            missing.append(name)
            notes.append(f"{name} not installed ({e}); install the bench extra: pip install -e '.[bench]'")

    # warm-up run of each (imports, caches), then the timed repeats side by side
    results = {}
    for name, job in jobs.items():
        setup, run = job if isinstance(job, tuple) else (None, job)
        results[name] = run(setup()) if setup else run()
    times = interleaved(jobs, args.repeats)

    # agreement with the floor, from the warm-up run's results
    ref = floor(THETA)
    convert = {"velpoly": velpoly_result, "pylinkage": pylinkage_result, "mechanism": mechanism_result}
    ok = True
    print(f"four-bar frame {FRAME:g}, crank {CRANK:g}, coupler {COUPLER:g}, rocker {ROCKER:g}; "
          f"omega {OMEGA:g} rad/s; {N} poses of one crank turn")
    print("\nagreement with the closed form (max |difference| / max |value| over the poses):")
    for name, conv in convert.items():
        if name not in results:
            continue
        diff = disagreement(conv(results[name]), ref)
        worst = max(diff.values())
        good = worst <= TOLERANCE[name]
        ok &= good
        shown = ", ".join(f"{k} {v:.1e}" for k, v in diff.items())
        print(f"  {name:9s} {'ok' if good else 'DISAGREES'} (tolerance {TOLERANCE[name]:g}): {shown}")
    if not ok:
        notes.append("a contender disagrees with the closed form beyond its tolerance: timings not comparable")

    poses = {name: N for name in jobs}
    poses["mechanism"] = n_mech
    per_pose = {name: min(t) / poses[name] * 1e6 for name, t in times.items()}
    print(f"\nmicroseconds per pose (best of {args.repeats}, round-robin in one process):")
    for name, us in per_pose.items():
        extra = "" if poses[name] == N else f"  (first {poses[name]} poses timed, scaled per pose)"
        print(f"  {name:9s} {us:10.3f} us/pose   {min(times[name]) * 1e3:9.2f} ms a run{extra}")
    print(f"  velpoly cold (load + first sweep, prepare included): {t_cold * 1e3:.1f} ms")

    scaled = {name: "" if poses[name] == N else f"first {poses[name]} poses, scaled" for name in poses}
    rows = [row(f"sweep: {name}" + (" (numpy closed form)" if name == "floor" else ""), us, "us/pose",
                note=scaled[name]) for name, us in per_pose.items()]
    ratio = per_pose["velpoly"] / per_pose["floor"]
    rows.append(row("sweep: velpoly / floor", ratio, "x", "<= 4x", ratio <= 4))
    for name, target in (("pylinkage", 20), ("mechanism", 700)):
        if name in per_pose:
            r = per_pose[name] / per_pose["velpoly"]
            rows.append(row(f"sweep: {name} / velpoly", r, "x", f">= {target}x", r >= target, scaled[name]))
        else:
            rows.append(row(f"sweep: {name} / velpoly", None, "x", f">= {target}x", None, "not installed"))
    try:
        from pylinkage._numba_compat import HAS_NUMBA
        notes.append(f"pylinkage {'with' if HAS_NUMBA else 'without'} numba" +
                     ("" if HAS_NUMBA else " (its optional accelerator; the bench extra does not install it)"))
    except ImportError:
        pass
    finish("sweep", args, rows, notes)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
