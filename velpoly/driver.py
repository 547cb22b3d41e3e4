"""The driver's positions: its angle in the reference pose and the range it reaches on the drawn branch.

Below :mod:`velpoly.solution` and :mod:`velpoly.sweeps` (both place the driver
by these rules) and :mod:`velpoly.reference` (the book's values belong to the
file's pose), so that none of them imports another for it.
"""
from __future__ import annotations

import math

import numpy as np

from .kinematics import Kinematics
from .model import Mechanism
from .motion import wrap_deg_float
from .pose import Knots, reassemble, same_mechanism

__all__ = ["driver_reference_angle", "reachable_range", "reachable_text", "driver_label"]


def driver_reference_angle(m: Mechanism) -> float | None:
    """The driver link's angle in the reference pose (degrees), None for a slider driver."""
    if m.driver.is_slider:
        return None
    lk = m.link(m.driver.link)
    if len(lk.points) < 2:  # a one-point crank: its angle is its rotation from the reference pose
        return 0.0
    (ax, ay), (bx, by) = m.points[lk.points[0]], m.points[lk.points[1]]
    return wrap_deg_float(math.degrees(math.atan2(float(by) - float(ay), float(bx) - float(ax))))


_RANGES: list = []   # (mechanism, arguments, range) of the last few reachable_range calls, newest last


def reachable_range(kin: Kinematics, limit: float = 360.0, step: float = 1.0,
                    resolution: float = 0.01) -> tuple[float, float]:
    """Driver displacements (degrees) reachable from the reference pose on its branch, each end to
    ``resolution`` degrees: followed in ``step``-degree steps to the last pose before a toggle, then
    in ``resolution`` steps across the next ``step`` (one more continuation each way). An end where
    a pin leaves its bounded slot is given to 1e-6 degree (where it reaches the slot's end).

    The answer depends on the mechanism alone (its equations and the drawn pose): the last few are
    kept and an equal mechanism (the same file loaded again: a solve, a sweep, a page and a report of
    it each ask) gets its range without the continuation again (a second or more past a toggle)."""
    m, args = kin.system.mechanism, (tuple(kin.rows), limit, step, resolution)
    for known, known_args, found in reversed(_RANGES):
        if known_args == args and same_mechanism(known, m):
            return found
    found = _reachable_range(kin, limit, step, resolution)
    _RANGES.append((m, args, found))
    del _RANGES[:-16]
    return found


def _reachable_range(kin: Kinematics, limit: float, step: float, resolution: float) -> tuple[float, float]:
    """:func:`reachable_range`, computed. The second continuation of a direction follows the
    first's knots (kept in a :class:`velpoly.pose.Knots`): the same steps, not made again."""
    out = []
    for sign in (1.0, -1.0):
        coarse = np.arange(step, limit + step / 2, step)
        knots = Knots()
        r = reassemble(kin.system, list(kin.rows), np.radians(coarse) * sign, knots=knots)
        if r.leaves is not None:    # a pin leaves its slot: that end is known to 1e-8 deg
            out.append(round(float(np.degrees(r.leaves[2])), 6))
            continue
        last = float(np.degrees(abs(r.deltas[-1]))) if len(r.deltas) else 0.0
        if last < limit:
            fine = np.arange(last + resolution, min(last + step, limit) + resolution / 2, resolution)
            path = np.concatenate([coarse[coarse <= last + 1e-9], fine])
            r = reassemble(kin.system, list(kin.rows), np.radians(path) * sign, knots=knots)
            last = float(np.degrees(abs(r.deltas[-1]))) if len(r.deltas) else 0.0
        out.append(sign * round(last / resolution) * resolution)
    return out[1], out[0]


def driver_label(m: Mechanism) -> tuple[str, str]:
    """(axis name, unit) of the driver's position."""
    if m.driver.is_slider:
        return f"slider {m.driver.slider} displacement", m.units
    return f"driver angle (link {m.driver.link})", "deg"


def reachable_text(m: Mechanism, kin: Kinematics) -> str:
    """``reachable on this branch: LO to HI deg`` for a crank driver (absolute driver angles, to
    0.01 degree, each toggle approached from the reference pose); empty for a slider driver, whose
    stroke is the cycle."""
    if m.driver.is_slider:
        return ""
    lo, hi = reachable_range(kin)
    ref = driver_reference_angle(m)
    return f"reachable on this branch: {ref + lo:g} to {ref + hi:g} deg"
