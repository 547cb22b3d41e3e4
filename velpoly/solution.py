"""One instant solved: :func:`solve` and the :class:`Solution` it returns.

``solve(m)`` analyses the mechanism at its reference pose (or with the
driver at ``angle``): pose, velocities and accelerations from the analytic
solve (:mod:`velpoly.kinematics`). The graphical constructions
(:mod:`velpoly.polygons`) and the instant centres (:mod:`velpoly.poles`)
are built from it on first use and checked against it.
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field

import numpy as np

from .errors import AssemblyError, InputError
from .kinematics import WARN, Kinematics, accelerations, prepare, velocities
from .model import Mechanism
from .motion import Motion, evaluate_motion, wrap_deg_float
from .pose import reassemble
from .driver import driver_reference_angle, reachable_range   # re-exported: solve places the driver by them
from .driver import inward_words, reachable_words
from .rigid import point_acceleration, point_velocity
from .arguments import check_angle, check_mechanism

__all__ = ["Solution", "solve", "driver_reference_angle", "reachable_range", "polygon_at_rest", "polygon_out_of_range",
           "DRAWN_RANGE", "FRAMES_RANGE"]


@dataclass(frozen=True)
class Solution:
    """The mechanism solved at one instant.

    Attributes are dicts keyed by link or point key (see FORMAT.md section 2):
    ``angle``, ``omega``, ``alpha`` (links), ``position``, ``velocity``,
    ``acceleration`` (points, numpy arrays of shape (2,)); ``sliders``,
    ``slots``, ``contacts`` (lists of dicts in file order); ``warnings``.
    """

    mechanism: Mechanism
    kinematics: Kinematics
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    condition: float
    motion: Motion
    driver_angle: float | None
    warnings: tuple[str, ...] = field(default=())

    # -- convenient views ------------------------------------------------------------
    @property
    def angle(self) -> dict:
        return {k: float(v[0]) for k, v in self.motion.angle.items()}

    @property
    def omega(self) -> dict:
        return {k: float(v[0]) for k, v in self.motion.omega.items()}

    @property
    def alpha(self) -> dict:
        return {k: _f(v[0]) for k, v in self.motion.alpha.items()}

    @property
    def position(self) -> dict:
        return {k: v[0] for k, v in self.motion.position.items()}

    @property
    def velocity(self) -> dict:
        return {k: v[0] for k, v in self.motion.velocity.items()}

    @property
    def acceleration(self) -> dict:
        return {k: v[0] for k, v in self.motion.acceleration.items()}

    @property
    def has_accelerations(self) -> bool:
        return all(map(math.isfinite, self.qdd.tolist()))

    def _arm(self, link: str, w):
        """``(k, R)``: the link's index in q and the arm R = w - O from its point O (the one at the world
        origin in the reference pose) to world position w; None for the frame."""
        k = self.kinematics.system.index.get(link)
        if k is None:
            return None
        return k, np.asarray(w, float) - self.q[3 * k:3 * k + 2]

    def body_velocity(self, link: str, w) -> np.ndarray:
        """Velocity of the point of ``link`` now at world position w: V_O + omega x R."""
        arm = self._arm(link, w)
        if arm is None:
            return np.zeros(2)
        k, r = arm
        return point_velocity(self.qd[3 * k:3 * k + 2], self.qd[3 * k + 2], r)

    def body_acceleration(self, link: str, w) -> np.ndarray:
        """Acceleration of the point of ``link`` now at w: A_O + alpha x R - omega^2 R."""
        arm = self._arm(link, w)
        if arm is None:
            return np.zeros(2)
        k, r = arm
        return point_acceleration(self.qdd[3 * k:3 * k + 2], self.qdd[3 * k + 2], self.qd[3 * k + 2], r)

    def place(self, link: str, point: str) -> np.ndarray:
        """Where the point of ``link`` that was at ``point`` in the reference pose is now."""
        return np.array(self.place_xy(link, point), float)

    def place_xy(self, link: str, point: str) -> tuple[float, float]:
        """:meth:`place` as a tuple of floats: (x, y) + R(theta) s for the point s of the reference pose
        on the link whose coordinates are (x, y, theta) (s itself on the frame)."""
        sx, sy = self.mechanism.points[point]
        k = self.kinematics.system.index.get(link)
        if k is None:
            return float(sx), float(sy)
        x, y, th = self.q[3 * k:3 * k + 3].tolist()
        c, sn = math.cos(th), math.sin(th)
        return x + (c * sx - sn * sy), y + (sn * sx + c * sy)

    def _repr_html_(self) -> str:   # a notebook shows the tables of `velpoly solve`
        from .report import solution_html
        return solution_html(self)

    # -- JSON -------------------------------------------------------------------------------
    def to_dict(self) -> dict:
        """The JSON object of FORMAT.md section 2."""
        m = self.mechanism
        drv = m.driver
        if drv.is_slider:
            driver = {"slider": drv.slider, "speed": drv.speed, "accel": drv.accel}
        else:
            driver = {"link": drv.link, "angle": self.driver_angle, "omega": drv.omega, "alpha": drv.alpha}
        mo = self.motion
        out = {
            "format": 1,
            "title": m.title,
            "units": {"length": m.units},
            "driver": driver,
            "links": {k.name: {"angle": mo.angle[k.name].item(), "omega": mo.omega[k.name].item(),
                               "alpha": _f(mo.alpha[k.name].item())} for k in m.links},
            "points": {key: {"position": _v(mo.position[key]), "velocity": _v(mo.velocity[key]),
                             "acceleration": _v(mo.acceleration[key])} for key in mo.position},
            "sliders": [{"block": s.block, "guide": s.guide, "point": s.point,
                         "slip_velocity": r["slip_velocity"].item(),
                         "slip_acceleration": _f(r["slip_acceleration"].item()),
                         "coriolis": _v(r["coriolis"])} for s, r in zip(m.sliders, mo.sliders)],
            "contacts": [{"links": list(c.links), "point": c.point, "kind": c.kind,
                          "slip_velocity": r["slip_velocity"].item(),
                          "slip_acceleration": _f(r["slip_acceleration"].item()),
                          "normal": r["normal"].item()} for c, r in zip(m.contacts, mo.contacts)],
        }
        if m.slots:
            out["slots"] = [{"pin": s.pin, "link": s.link, "slot": s.slot,
                             "slip_velocity": r["slip_velocity"].item(),
                             "slip_acceleration": _f(r["slip_acceleration"].item()),
                             "coriolis": _v(r["coriolis"])} for s, r in zip(m.slots, mo.slots)]
        from .poles import poles_section          # the constructions, a layer above the solve: their
        from .polygons import graphical_section   # JSON sections (FORMAT.md section 2), in this order
        for name, section in (("poles", poles_section(self)), ("graphical", graphical_section(self))):
            if section is not None:
                out[name] = section
        if self.warnings:
            out["warnings"] = list(self.warnings)
        return out


def _f(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def _v(a) -> list | None:
    """The one pose's vector of a (1, 2) array as plain floats (one ``tolist``: a numpy reduction, or
    a float per component, per vector cost much of to_dict's own time), None where not finite."""
    x, y = v = a.tolist()[0]
    return v if math.isfinite(x) and math.isfinite(y) else None


def _choose(ref: float, lo: float, hi: float, hint: str) -> str:
    """The hint of an angle refused beyond a toggle: the driver angles ``--angle`` reaches. It carries
    the driver the shorter way round, so of the range ref + [lo, hi] only those within 180 deg of the
    reference pose; where the range reaches farther, the hint gives that part of it."""
    a, b = max(lo, -179.99), min(hi, 179.99)
    if (a, b) == (lo, hi):
        return hint
    return (f"choose an angle from {inward_words(ref, a, b)} deg: --angle turns the driver the shorter way "
            f"round from the reference pose ({ref:g} deg), so the rest of the range, beyond 180 deg from it, is "
            "reached only by velpoly sweep (or draw the mechanism nearer to that angle)")


def _angle(target: float) -> str:
    """The refused driver angle as given: ``{:g}`` where that is the number, else all its digits (220 is
    not 219.9999999)."""
    short = f"{target:g}"
    return short if float(short) == target else repr(float(target))


def _carried(kin, ref: float, target: float, delta: float) -> tuple[np.ndarray, float]:
    """The pose with the driver turned by ``delta`` degrees from the reference pose (the shorter way round, on
    the drawn branch) and the turn taken: at half a turn either way is the shorter, and the one that reaches the
    angle without crossing a toggle is taken. A pin leaving its slot or a toggle on the way: AssemblyError."""
    m = kin.mechanism
    r = reassemble(kin.system, list(kin.rows), [math.radians(delta)])
    if len(r.deltas) == 0 and abs(abs(delta) - 180.0) < 1e-9:   # half a turn: either way round is the shorter
        other = reassemble(kin.system, list(kin.rows), [math.radians(-delta)])
        if len(other.deltas):
            return other.q, -delta
    if len(r.deltas) == 0 and r.leaves is not None:
        lo, hi = reachable_range(kin)
        sl = m.slots[r.leaves[0]]
        words = reachable_words(kin, ref, delta)
        # where it leaves (ref + r.leaves[2], unwrapped) is the range's end on the refused side: printed as the range is
        leaves = words.split(" to ")[1 if delta > 0 else 0]
        raise AssemblyError(
            f"cannot assemble at driver angle {_angle(target)} deg: pin {sl.pin} leaves the slot of "
            f"{sl.slot} at its end {r.leaves[1]} at {leaves} deg; the pin is in the slot from {words} deg",
            where="driver.angle", file=m.source, links=(sl.link, sl.slot),
            hint=_choose(ref, lo, hi, "choose an angle in that range (the slot's ends bound the motion)"))
    if len(r.deltas) == 0:
        lo, hi = reachable_range(kin)
        raise AssemblyError(
            f"cannot assemble at driver angle {_angle(target)} deg: a toggle lies on the way from the "
            f"reference pose ({ref:g} deg); reachable: {reachable_words(kin, ref, delta)} deg",
            where="driver.angle", file=m.source, links=tuple(kin.system.index),
            hint=_choose(ref, lo, hi, "choose an angle in the reachable range"))
    return r.q, delta


def solve(m: Mechanism, angle: float | None = None) -> Solution:
    """Solve the mechanism at its reference pose, or with the driver at ``angle`` (degrees).

    ``angle`` is absolute (the driver link's angle, counter-clockwise from +x);
    the mechanism is carried there the shorter way round from the reference
    pose, on the drawn branch. Without ``angle``, the file's ``driver.angle``
    applies if given.
    """
    m, angle = check_mechanism(m), check_angle(angle)   # a wrong argument: an error naming it
    kin = prepare(m)
    nq = kin.system.nq
    q = np.zeros((1, nq))
    drv = m.driver
    ref = driver_reference_angle(m)
    target = angle if angle is not None else drv.angle
    if target is not None:
        if drv.is_slider:
            raise InputError("a slider driver has no angle", where="--angle", file=m.source,
                             hint="a slider driver is placed where the file draws it: leave out the angle")
        if not math.isfinite(target):
            raise InputError(f"the driver angle must be finite, got {target}", where="driver.angle", file=m.source)
        delta = wrap_deg_float(float(target) - ref)
        if abs(delta) > 1e-12:
            velocities(kin, q, where="reference pose")   # regular, to tell its branch (else exit 3)
            q, delta = _carried(kin, ref, target, delta)
        angle_now = wrap_deg_float(ref + delta)
    else:
        angle_now = ref
    _, jac, _ = kin.system.evaluate(q)   # one Jacobian for the velocities and the accelerations
    qd, cond = velocities(kin, q, where="reference pose" if angle_now == ref else f"driver angle {angle_now:g} deg",
                          jac=jac)
    if all(c.centres is not None for c in m.contacts):
        qdd = accelerations(kin, q, qd, jac=jac)
    else:  # a contact given by its normal alone: velocities only (FORMAT.md section 5)
        qdd = np.full_like(qd, np.nan)
    warnings = []
    if cond[0] > WARN:
        warnings.append(f"near-singular pose: condition number {cond[0]:.3g} (results lose accuracy)")
    motion = evaluate_motion(m, kin.system.index, q, qd, qdd)
    return Solution(m, kin, q[0], qd[0], qdd[0], float(cond[0]), motion, angle_now, tuple(warnings))


def polygon_at_rest(sol: Solution, sheet: str, drawn: tuple[float, float] | None = None,
                    cycle: bool = False) -> InputError | None:
    """The input error of a sheet whose polygon would be one point: every velocity zero (the driver at rest,
    omega = 0, and no prescribed slip) for a sheet with the velocity polygon (``velocity``, ``full``), every
    acceleration zero as well for one with the acceleration polygon; None where the polygons have a size.
    A mechanism starting from rest (omega = 0, alpha given) has its acceleration sheet. ``drawn``: the range of
    :func:`polygon_out_of_range` (default ``DRAWN_RANGE``). ``cycle``: for a figure of the cycle (animate, html,
    sweep --gif), whose hint is the driver's rate alone (a driver at rest has no motion to show)."""
    m, drv = sol.mechanism, sol.mechanism.driver
    still_v = not any(np.any(v != 0) for v in sol.velocity.values()) and not any(sol.omega.values())
    still_a = still_v and sol.has_accelerations and not any(np.any(a != 0) for a in sol.acceleration.values())
    rate, accel = ("driver.speed", "driver.accel") if drv.is_slider else ("driver.omega", "driver.alpha")
    rate_, accel_ = rate.split(".")[1], accel.split(".")[1]
    moving = f"give the driver a rate ({rate_}): at rest it has no motion to show" if cycle else None
    if still_a and sheet in ("velocity", "acceleration", "full"):
        return InputError("the mechanism is at rest: every velocity and acceleration is zero, and its polygons "
                          "are single points", where=rate, file=m.source,
                          hint=moving or f"give {rate_} (or {accel_}); the poles and the displacement sheet need "
                                         "neither")
    if still_v and sheet in ("velocity", "full"):
        return InputError("the mechanism is at rest: every velocity is zero, and the velocity polygon is a "
                          "single point", where=rate, file=m.source,
                          hint=moving or f"draw --sheet acceleration (starting from rest: {accel_} only), "
                                         f"or give {rate_}")
    return polygon_out_of_range(sol, sheet, drawn)


DRAWN_RANGE = (1e-150, 1e150)   # a polygon's largest vector, its units: the drawing's geometry (shapely's areas,
#                                 distances squared) holds within it; beyond, squares overflow or vanish
FRAMES_RANGE = (sys.float_info.min / sys.float_info.epsilon, math.inf)   # a cycle's frames (animate, html, sweep
#   --gif), drawn without shapely, hold any polygon whose numbers keep a float's full precision (about 1e-292 and up)


def _largest(vectors) -> float:
    return max((float(np.max(np.abs(v))) for v in vectors if v is not None), default=0.0)


def polygon_out_of_range(sol: Solution, sheet: str, drawn: tuple[float, float] | None = None) -> InputError | None:
    """The input error of a sheet whose polygon is too small or too large to draw: its largest vector (a
    velocity, or an acceleration for a sheet with the acceleration polygon) outside ``drawn`` (default
    ``DRAWN_RANGE``; a cycle's frames: ``FRAMES_RANGE``); None otherwise (a polygon
    of zero vectors is :func:`polygon_at_rest`'s). The file's numbers are solved at any scale (``velpoly
    solve``); a drawing's geometry is not."""
    m, drv = sol.mechanism, sol.mechanism.driver
    lo, hi = drawn or DRAWN_RANGE
    need = f"{lo:g} to {hi:g}" if math.isfinite(hi) else f"at least {lo:.0e}"
    polygons = [("velocity", "speeds", "/s", sol.velocity.values())] if sheet in ("velocity", "full") else []
    if sheet in ("acceleration", "full") and sol.has_accelerations:
        polygons.append(("acceleration", "accelerations", "/s^2", sol.acceleration.values()))
    for kind, what, per, vectors in polygons:
        size = _largest(vectors)
        if size == 0.0 or lo <= size <= hi:
            continue
        if drv.is_slider:
            where = "driver.speed" if kind == "velocity" or abs(drv.accel) == 0 else "driver.accel"
        else:
            where = "driver.alpha" if kind == "acceleration" and abs(drv.alpha) > drv.omega ** 2 else "driver.omega"
        unit = m.units or "length units"
        return InputError(f"the {kind} polygon cannot be drawn: its {what} reach {size:.3g} {unit}{per} "
                          f"(a drawing needs {need})", where=where, file=m.source,
                          hint="solve gives the numbers at any scale; to draw, give the driver's rate and the "
                               "lengths in units that keep them within range")
    return None
