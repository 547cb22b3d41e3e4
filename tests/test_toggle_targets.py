"""A driver angle asked exactly at a change point, or within rounding of one, is refused by both paths.

At a four-bar's change point (a + d = b + c at 180 deg; a parallelogram's 0 and 180 deg; a kite's 0 deg,
and 180 deg where crank = coupler) the dyad's circles touch: the assembly branches meet, and the drawn
one cannot be told from the other there. ``velpoly.solve`` must refuse such an angle (PoseError) by the
dyad walk (``walked_reach``: the closure dips to TOUCH) and by continuation (the path of mechanisms the
dyad walk cannot follow: slots, contacts, loops) alike, whatever the last bits of the lengths.

On main b313165 the continuation accepted some of them: at the change point itself Newton converges
linearly onto the double root and stops, its residual below tolerance, 1e-6 off it, where the sign of
the Jacobian's determinant is rounding's; 1e-7 deg short of one the pose is a true root, its determinant
of the drawn sign but 1e-9 of the step's start. Which of them it took depended on the machine.

Generated mechanisms (``test_change_points.dims``: every class with a change point the test there asks
exactly), each drawn with its lengths as generated and nudged by a few ulps each (``np.nextafter``:
the circles then touch, cross or miss by rounding's width), asked at each change point and 1e-12,
1e-9 and 1e-7 deg either side, and 2 deg either side (one side reachable: the refusals are not a
refusal of everything). The oracle is ``test_change_points.expected`` (the closure's margin along the
arc, independent of velpoly); where it is not "ambiguous", both paths must give its answer.
"""
from __future__ import annotations

import numpy as np
import velpoly
from velpoly import pose, solution, sweeps
from tests.mechanisms import fourbar
from test_change_points import closure_margin, dims, expected

# each class with its change points (driver angles, deg)
CHANGE_POINTS = {"change-point": (180.0,), "parallelogram": (0.0, 180.0), "parallelogram-crossed": (0.0, 180.0),
                 "kite-frame": (0.0,), "kite-coupler": (0.0, 180.0)}
OFFSETS = (0.0, 1e-12, -1e-12, 1e-9, -1e-9, 1e-7, -1e-7, 2.0, -2.0)


def nudged(x: float, ulps: int) -> float:
    """x moved by ``ulps`` units in the last place (down for negative)."""
    for _ in range(abs(ulps)):
        x = float(np.nextafter(x, np.inf if ulps > 0 else -np.inf))
    return x


def cases(seed: int):
    """(kind, (a, b, c, d), reference angle, Mechanism): one mechanism of each class as generated and one
    with each length nudged by up to 4 ulps, drawn 10 to 170 deg from its change points, on the branch
    the class asks for (the open parallelogram, the crossed one, either side for the others)."""
    rng = np.random.default_rng(seed)
    out = []
    for kind in CHANGE_POINTS:
        abcd = dims(kind, rng)
        for exact in (True, False):
            a, b, c, d = abcd if exact else tuple(nudged(x, int(k)) for x, k in zip(abcd, rng.integers(-4, 5, 4)))
            while True:
                theta = float(np.round(rng.uniform(10.0, 170.0) * rng.choice([-1.0, 1.0]), 3))
                if closure_margin(a, b, c, d, theta) > 0.05:
                    break
            # the open parallelogram's B = O4 + (A - O2) lies left of A -> O4 where A is above the frame
            open_side = "left" if np.sin(np.radians(theta)) > 0 else "right"
            branch = {"parallelogram": open_side,
                      "parallelogram-crossed": {"left": "right", "right": "left"}[open_side]}.get(
                kind, str(rng.choice(["left", "right"])))
            out.append((kind, (a, b, c, d), theta, velpoly.load(fourbar(a, b, c, d, theta=theta, branch=branch))))
    return out


def decision(m, angle: float) -> str:
    """'yes' where ``solve`` reaches the angle, 'no' where it refuses it (PoseError)."""
    try:
        velpoly.solve(m, angle=angle)
    except velpoly.PoseError:
        return "no"
    return "yes"


def test_an_angle_at_a_change_point_is_refused_by_the_dyads_and_by_continuation(monkeypatch, seed=3):
    # the range in the message is not asked here (test_change_points): by continuation it takes four more
    monkeypatch.setattr(solution, "reachable_range", lambda kin: (0.0, 0.0))
    dyad_plan = pose.plan_for
    seen = {"yes": 0, "no": 0}
    for kind, (a, b, c, d), ref, m in cases(seed):
        for at in CHANGE_POINTS[kind]:
            for offset in OFFSETS:
                angle = at + offset
                want = expected(a, b, c, d, ref, angle)
                got = []
                for plan in (dyad_plan, lambda system: None):       # the dyad walk, then continuation
                    monkeypatch.setattr(pose, "plan_for", plan)
                    monkeypatch.setattr(sweeps, "plan_for", plan)
                    got.append(decision(m, angle))
                label = (kind, (a, b, c, d), ref, angle, want, got)
                assert got[0] == got[1], label
                if want != "ambiguous":
                    assert got[0] == want, label
                    seen[want] += 1
    assert seen["no"] >= 5 * seen["yes"] > 0, seen


def test_the_nudged_lengths_touch_cross_and_miss():
    """The nudges reach each side of the exact touch: a + d - (b + c) (or the kites' and parallelograms'
    equalities) of both signs and zero among the generated change-point mechanisms."""
    signs = set()
    for kind, (a, b, c, d), _, _ in cases(3):
        if kind == "change-point":
            signs.add(np.sign((a + d) - (b + c)))
        elif kind.startswith("parallelogram"):
            signs.add(np.sign(a - c))
    assert signs == {-1.0, 0.0, 1.0}, signs
