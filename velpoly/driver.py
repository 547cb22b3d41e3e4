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

__all__ = ["driver_reference_angle", "reachable_range", "reachable_ends", "reachable_words", "inward_words",
           "reachable_text", "driver_label"]


def driver_reference_angle(m: Mechanism) -> float | None:
    """The driver link's angle in the reference pose (degrees), None for a slider driver."""
    if m.driver.is_slider:
        return None
    lk = m.link(m.driver.link)
    if len(lk.points) < 2:  # a one-point crank: its angle is its rotation from the reference pose
        return 0.0
    (ax, ay), (bx, by) = m.points[lk.points[0]], m.points[lk.points[1]]
    return wrap_deg_float(math.degrees(math.atan2(float(by) - float(ay), float(bx) - float(ax))))


_RANGES: list = []   # (mechanism, arguments, ends) of the last few reachable_range calls, newest last


def reachable_range(kin: Kinematics, limit: float = 360.0, step: float = 1.0,
                    resolution: float = 0.01) -> tuple[float, float]:
    """Driver displacements (degrees) reachable from the reference pose on its branch, each end to
    ``resolution`` degrees: followed in ``step``-degree steps to the last pose before a toggle, then
    in ``resolution`` steps across the next ``step`` (one more continuation each way). An end where
    a pin leaves its bounded slot is given to 1e-6 degree (where it reaches the slot's end).

    The answer depends on the mechanism alone (its equations and the drawn pose): the last few are
    kept and an equal mechanism (the same file loaded again: a solve, a sweep, a page and a report of
    it each ask) gets its range without the continuation again (a second or more past a toggle)."""
    (lo, _), (hi, _) = reachable_ends(kin, limit, step, resolution)
    return lo, hi


class _Range(tuple):
    """``(lo, hi)`` as :func:`reachable_range` gives it, with ``ends``: each end as (reached, bound), for
    :func:`reachable_ends` (one walk computes both)."""

    ends: tuple


def reachable_ends(kin: Kinematics, limit: float = 360.0, step: float = 1.0,
                   resolution: float = 0.01) -> tuple[tuple[float, float], tuple[float, float]]:
    """Each end of :func:`reachable_range` as (reached, bound): the last displacement reached and
    one the driver does not pass (the next ``resolution`` step, where the continuation failed; the
    slot's end itself where a pin leaves its slot; ``limit`` where the way is open), so that every
    displacement ``--angle`` reaches lies between the two bounds."""
    m, args = kin.system.mechanism, (tuple(kin.rows), limit, step, resolution)
    for known, known_args, found in reversed(_RANGES):
        if known_args == args and same_mechanism(known, m):
            return found.ends
    found = _reachable_range(kin, limit, step, resolution)
    _RANGES.append((m, args, found))
    del _RANGES[:-16]
    return found.ends


def _reachable_range(kin: Kinematics, limit: float, step: float, resolution: float) -> _Range:
    """:func:`reachable_range`, computed, with its :func:`reachable_ends`. The second continuation of a
    direction follows the first's knots (kept in a :class:`velpoly.pose.Knots`): the same steps, not made again."""
    out = []
    for sign in (1.0, -1.0):
        coarse = np.arange(step, limit + step / 2, step)
        knots = Knots()
        r = reassemble(kin.system, list(kin.rows), np.radians(coarse) * sign, knots=knots)
        if r.leaves is not None:    # a pin leaves its slot: that end is known to 1e-8 deg
            end = round(float(np.degrees(r.leaves[2])), 6)
            out.append((end, end))
            continue
        last = float(np.degrees(abs(r.deltas[-1]))) if len(r.deltas) else 0.0
        if last < limit:
            fine = np.arange(last + resolution, min(last + step, limit) + resolution / 2, resolution)
            path = np.concatenate([coarse[coarse <= last + 1e-9], fine])
            r = reassemble(kin.system, list(kin.rows), np.radians(path) * sign, knots=knots)
            last = float(np.degrees(abs(r.deltas[-1]))) if len(r.deltas) else 0.0
        reached = round(last / resolution) * resolution
        out.append((sign * reached, sign * min(reached + resolution, limit)))
    found = _Range((out[1][0], out[0][0]))
    found.ends = (out[1], out[0])
    return found


def reachable_words(kin: Kinematics, ref: float, refused: float | None = None) -> str:
    """``LO to HI``: the absolute driver angles (the reference pose's ``ref`` plus the displacements
    of :func:`reachable_ends`) between which every angle ``--angle`` reaches lies, each end rounded
    outward to 0.01 deg. Given the ``refused`` displacement (one the driver did not reach), the end
    on its side is narrowed (bisection between the last pose reached and it) and printed to as many
    digits (at most 6 decimals) as it takes to leave the refused angle outside the printed range."""
    (lo_in, lo_out), (hi_in, hi_out) = reachable_ends(kin)
    if refused is not None and refused > 0:
        return f"{_outward(ref, lo_in, lo_out, None)} to {_outward(ref, hi_in, hi_out, refused, kin)}"
    return f"{_outward(ref, lo_in, lo_out, refused, kin)} to {_outward(ref, hi_in, hi_out, None)}"


def _outward(ref: float, reached: float, bound: float, refused: float | None, kin: Kinematics = None) -> str:
    """One end of :func:`reachable_words`: ``ref + bound`` rounded away from the reference pose to 0.01
    deg, or to the first number of decimals (up to 6) that leaves ``ref + refused`` beyond it. A slot's
    end (``reached == bound``, known to 1e-6 deg) may be printed that much inside; a toggle's bound is
    narrowed first where the refused displacement lies short of it (or on it)."""
    sign = 1.0 if bound >= 0 else -1.0
    if refused is not None and reached != bound and sign * reached < sign * refused < sign * bound + 1e-6:
        reached, bound = _narrowed(kin, reached, refused)
    edge = sign * (ref + bound) - (1e-6 if reached == bound else 1e-9)   # outward is up, for either sign
    for places in range(2, 7):
        unit = 10.0 ** -places
        text = _decimal(sign * math.ceil(edge / unit) * unit, places)
        if refused is None or sign * float(text) < sign * (ref + refused) - 1e-9:   # beyond its rounding noise
            break
    return text


def inward_words(ref: float, lo: float, hi: float) -> str:
    """``LO to HI``: the absolute driver angles ``ref + lo`` and ``ref + hi`` (displacements reached)
    rounded inward to 0.01 deg, so that every angle between the printed two is reached as well."""
    first, last = math.ceil((ref + lo) * 100 - 1e-7) / 100, math.floor((ref + hi) * 100 + 1e-7) / 100
    return f"{_decimal(first, 2)} to {_decimal(last, 2)}"


def _narrowed(kin: Kinematics, reached: float, refused: float, halvings: int = 24) -> tuple[float, float]:
    """(reached, bound) about a toggle between the displacement ``reached`` and the ``refused`` one,
    by bisection: the driver is carried from the reference pose to the midpoint (as ``--angle`` is)
    until the bound lies a millionth of a degree from the refused displacement or nearer the toggle."""
    bound = refused
    for _ in range(halvings):
        if abs(refused - bound) > 2e-6:
            break
        mid = 0.5 * (reached + bound)
        if len(reassemble(kin.system, list(kin.rows), [math.radians(mid)]).deltas):
            reached = mid
        else:
            bound = mid
    return reached, bound


def _decimal(x: float, places: int) -> str:
    """``x`` to ``places`` decimals without trailing zeros (``60``, ``98.71``, never ``-0``)."""
    text = f"{x:.{places}f}".rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def driver_label(m: Mechanism) -> tuple[str, str]:
    """(axis name, unit) of the driver's position."""
    if m.driver.is_slider:
        return f"slider {m.driver.slider} displacement", m.units
    return f"driver angle (link {m.driver.link})", "deg"


def reachable_text(m: Mechanism, kin: Kinematics) -> str:
    """``reachable on this branch: LO to HI deg`` for a crank driver (a sweep's note): the range to 0.01 deg as a
    refused ``--angle`` prints it, each end rounded inward (:func:`inward_words`: every angle printed is reached,
    as the sweep's outputs are; the refusal's :func:`reachable_words` rounds outward, at most 0.01 deg beyond);
    empty for a slider driver, whose stroke is the cycle."""
    if m.driver.is_slider:
        return ""
    lo, hi = reachable_range(kin)
    return f"reachable on this branch: {inward_words(driver_reference_angle(m), lo, hi)} deg"
