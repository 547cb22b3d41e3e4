"""A whole driver cycle: :func:`sweep` and the :class:`Sweep` it returns.

Every pose is continued from the previous one on the drawn branch
(:func:`velpoly.pose.reassemble`); velocities and accelerations are then
solved for all poses at once (batched linear solves), so a crank cycle is a
handful of numpy passes, not a Python loop per pose.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from .arguments import MAX_ANGLE, check_angles, check_mechanism
from .errors import ArgumentValueError, InputError, PoseError
from .dyads import coordinates, rates, walk
from .kinematics import SINGULAR, Kinematics, accelerations, condition, involved_links, prepare, velocities
from .model import Mechanism
from .motion import Motion, evaluate_motion, wrap_deg
from . import pose
from .pose import plan_for, reassemble, walked_reach
from .driver import driver_reference_angle, reachable_range, reachable_text
from .solution import Solution

__all__ = ["Sweep", "sweep", "memory_estimate", "check_memory", "MEMORY_BUDGET", "check_step", "cycle_poses",
           "cycle_angles", "run_cycle", "join_sweeps", "solution_at", "check_cycle", "stop_note"]


@dataclass(frozen=True)
class Sweep(Motion):
    """Results over many driver positions, one row per solved angle: a :class:`Motion` of
    the poses reached, with the driver's positions and the coordinates.

    ``angles`` (degrees; for a slider driver, displacements along its path
    from the reference position), ``omega[link]``, ``alpha[link]`` and
    ``angle[link]`` of shape (N,), ``position[key]``, ``velocity[key]``,
    ``acceleration[key]`` of shape (N, 2); ``stopped`` tells why the sweep
    ended before the last requested angle (empty if it did not); ``leaves`` is
    ``(pin, slot link, driver angle)`` where the sweep stopped because a pin
    reached an end of its slot (FORMAT.md ``ends``), else None;
    ``condition`` is each pose's condition number (computed on first use:
    exact above 1e6, a close estimate below).
    """

    mechanism: Mechanism
    angles: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    stopped: str = ""
    kinematics: Kinematics | None = field(default=None, repr=False, compare=False)
    known_condition: np.ndarray | None = field(default=None, repr=False, compare=False)
    leaves: tuple | None = None

    @cached_property
    def condition(self) -> np.ndarray:
        if self.known_condition is not None:
            return self.known_condition
        if len(self.q) == 0:
            return np.zeros(0)
        return condition(self.kinematics or prepare(self.mechanism), self.q)


def _walk(m: Mechanism, plan, deltas):
    """The dyad walk with the driver's rates: every link's position, velocity and acceleration.

    Past a dyad's toggle the walk's square roots and divisions give NaN or inf; those poses are
    cut off by ``reach`` and the condition screen, so numpy is not let to warn about them."""
    drv = m.driver
    rate, accel = (drv.speed, drv.accel) if drv.is_slider else (drv.omega, drv.alpha)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return walk(m, plan, deltas, rate, accel)


MEMORY_BUDGET = 2_000_000_000   # bytes a sweep may use (docs/sweep.md): beyond it, refused before any work


def memory_estimate(m: Mechanism, kin: Kinematics, n: int) -> int:
    """Bytes a sweep of ``n`` poses needs at its peak, from the sizes of what it keeps and builds.

    Kept per pose: q, q', q'' (3 nq floats), every point key's position, velocity and acceleration
    (6 K), every link's angle, omega and alpha (3 L), each slider's, slot's and contact's slip
    (about 8 each). The closed form walks the dyads in about a quarter more; continuation solves
    with one dense nq x nq Jacobian a pose (about 6 of them at its peak). Measured: within 20% of
    the peak (tracemalloc) for chains of 4 to 42 links, both ways."""
    from .motion import point_keys
    nq = kin.system.nq
    kept = 8 * (3 * nq + 6 * len(point_keys(m)) + 3 * len(m.links)
                + 8 * (len(m.sliders) + len(m.slots) + len(m.contacts)))
    peak = 1.25 * kept if plan_for(kin.system) is not None else kept + 6 * 8 * nq * nq
    return int(n * peak)


def check_memory(m: Mechanism, kin: Kinematics, n: int, where: str = "angles", hint: str = "",
                 walked: int = 0) -> None:
    """Refuse a sweep of ``n`` poses (and ``walked`` more on the path between them) whose
    :func:`memory_estimate` is beyond MEMORY_BUDGET: an InputError naming ``where`` and the number
    of poses, before anything is allocated."""
    need = memory_estimate(m, kin, n + walked)
    if need > MEMORY_BUDGET:
        most = int(MEMORY_BUDGET / max(need / max(n + walked, 1), 1))
        poses = f"{n} poses" + (f" (and {walked} more walked between them)" if walked > n else "")
        raise ArgumentValueError(f"{poses} would need about {need / 1e9:.3g} GB, beyond the sweep's memory "
                         f"budget of {MEMORY_BUDGET / 1e9:.3g} GB", where=where, file=m.source,
                         hint=hint or (f"sweep at most about {most} poses of this mechanism at once"
                                       + (", angles closer together (the path between them is walked)"
                                          if walked > n else "")))


WALK_LIMIT = 1e4   # a slider driver's displacements, in mechanism sizes (MAX_ANGLE for a crank's degrees)


def _walk_poses(m: Mechanism, angles: np.ndarray) -> int:
    """About how many poses walking the path between the angles takes (the gaps wider than a
    continuation step are walked, as ``pose.walked_reach`` does): for the memory estimate."""
    if len(angles) < 2:
        return 0
    travel = float(np.abs(np.diff(angles)).sum()) + 180.0 * (not m.driver.is_slider)
    return int(travel / (0.04 * m.size if m.driver.is_slider else 6.0))


def _deltas(m: Mechanism, angles: np.ndarray, ref) -> tuple[np.ndarray, float]:
    """The driver's travel from the reference pose to each angle, and the first angle's
    ``first`` (degrees from the reference): for a crank the first angle is reached the shorter
    way round and later ones continue from it (radians); a slider's displacements as given."""
    if m.driver.is_slider:
        return angles.copy(), 0.0
    first = float(wrap_deg(angles[0] - ref)) if len(angles) else 0.0
    return ((angles - (angles[0] - first)) * (np.pi / 180.0) if len(angles) else angles), first


def _closed_form(m: Mechanism, kin: Kinematics, plan, deltas: np.ndarray):
    """The sweep by the dyad walk: ``(walk, n, q, q', q'', stopped)``, or None when the plan is
    not the mechanism's (the joint equations on the walk's poses disagree).

    The walk goes until a dyad's closure goes negative (``pose.walked_reach``); only poses near
    a dyad's toggle (transmission sine below 1e-3) need the condition number, and the first
    singular one ends the sweep."""
    w = _walk(m, plan, deltas)
    rate = m.driver.speed if m.driver.is_slider else m.driver.omega
    n = min(w.reach, walked_reach(m, plan, deltas, pose.coarse_step(kin.system), w, rate))
    stopped = "toggle" if n < len(deltas) else ""
    if n < len(deltas):
        w = _walk(m, plan, deltas[:n])     # past a toggle the walk is NaN: walked to it only
    # q, q', q'' in one block: the three levels of the same coordinates
    block = np.empty((3, n, kin.system.nq))
    q = coordinates(w, kin.system.index, plan, deltas[:n], out=block[0])
    if not pose.check_closed_form(kin.system.positions, list(kin.rows), q, deltas[:n]):
        return None                        # not the mechanism the plan assumed
    near = np.flatnonzero(w.sine < 1e-3)
    if len(near):
        c = condition(kin, q[near])
        bad = near[~(c <= SINGULAR)]
        if len(bad):
            n, stopped = int(bad[0]), "toggle"
            w, block = _walk(m, plan, deltas[:n]), block[:, :n]
            q = block[0]
    qd, qdd = rates(w, kin.system.index, n, out=(block[1], block[2]))
    return w, n, q, qd, qdd, stopped


def _continued(m: Mechanism, kin: Kinematics, deltas: np.ndarray, angles: np.ndarray, first: float):
    """The sweep by continuation (:func:`velpoly.pose.reassemble`) and batched linear solves:
    ``(n, q, q', q'', condition, stopped, leaves)``; it ends at the first pose whose condition
    number passes SINGULAR, or where a pin leaves its bounded slot (``leaves`` = (pin, slot
    link, driver angle))."""
    r = reassemble(kin.system, list(kin.rows), deltas)
    n, q, stopped, leaves = len(r.deltas), r.q, r.stopped, None
    if r.leaves is not None:
        sl = m.slots[r.leaves[0]]
        at = r.leaves[2] if m.driver.is_slider else \
            float(angles[0] - (first if len(angles) else 0.0) + np.degrees(r.leaves[2]))
        leaves = (sl.pin, sl.slot, at)
    qd, cond = velocities(kin, q, check=False) if n else (np.zeros((0, kin.system.nq)), np.zeros(0))
    if n and not np.all(cond <= SINGULAR):
        k = int(np.argmin(cond <= SINGULAR))
        n, q, qd, cond = k, q[:k], qd[:k], cond[:k]
        stopped = "toggle"
    if n and all(c.centres is not None for c in m.contacts):
        qdd = accelerations(kin, q, qd)
    else:
        qdd = np.full_like(qd, np.nan)
    return n, q, qd, qdd, cond, stopped, leaves


def _stop_message(m: Mechanism, angles: np.ndarray, n: int, ref, stopped: str, leaves) -> tuple[str, tuple | None]:
    """``(Sweep.stopped, Sweep.leaves)``: why the sweep ended after n of the angles, in words
    (a pin leaving its slot, or a toggle), and the slot exit only when that is why."""
    if stopped and leaves is not None and stopped == "slot":
        return (f"pin {leaves[0]} leaves the slot of {leaves[1]} at " +
                (f"{leaves[2]:g}" + (f" {m.units}" if m.units else "") if m.driver.is_slider else f"{leaves[2]:.1f} deg") +
                f": {len(angles) - n} of {len(angles)} positions not reached"), leaves
    if stopped:
        last = angles[n - 1] if n else (ref if ref is not None else 0.0)
        return (f"stopped at a toggle after {last:g}" + ((f" {m.units}" if m.units else "") if m.driver.is_slider
                                                          else " deg") +
                f": {len(angles) - n} of {len(angles)} positions not reached on this branch"), None
    return "", None


def sweep(m: Mechanism, angles, kin: Kinematics | None = None) -> Sweep:
    """Solve the mechanism at each driver angle (degrees, absolute), in the order given.

    Each pose is continued from the previous one, so ``ref .. ref + 360`` is
    one turn. The sweep stops before the first angle it cannot reach without
    crossing a toggle (``Sweep.stopped`` says so). For a slider driver the
    values are displacements along its path from the reference position.
    """
    m = check_mechanism(m)   # a wrong argument: an error naming it
    slider = m.driver.is_slider   # a slider's "angles" are displacements (length units)
    angles = check_angles(angles, limit=WALK_LIMIT * m.size if slider else MAX_ANGLE,
                          unit=m.units or "length units" if slider else "deg")
    kin = kin or prepare(m)
    check_memory(m, kin, len(angles), walked=_walk_poses(m, angles))
    ref = driver_reference_angle(m)
    deltas, first = _deltas(m, angles, ref)
    plan = plan_for(kin.system)
    # the drawn pose must be regular, to tell its branch; far from a dyad's toggle it is
    screened = plan is not None and plan.margin > 1e-3
    if not screened:
        velocities(kin, np.zeros((1, kin.system.nq)), where="reference pose")
    # the closed form, dyad by dyad, walked once. The plan's sides are the drawn pose's (dyad_plan
    # checks that the walk reproduces it); the joint equations on a sample of the walk's poses
    # check that the plan is the mechanism's, or the sweep falls back to continuation.
    found = _closed_form(m, kin, plan, deltas) if plan is not None and len(deltas) else None
    known_cond, leaves = None, None
    if found is not None:
        w, n, q, qd, qdd, stopped = found
    else:
        if screened:    # the plan was not the mechanism's after all: check as before
            velocities(kin, np.zeros((1, kin.system.nq)), where="reference pose")
        w = None
        n, q, qd, qdd, known_cond, stopped, leaves = _continued(m, kin, deltas, angles, first)
    stopped, leaves = _stop_message(m, angles, n, ref, stopped, leaves)
    mo = evaluate_motion(m, kin.system.index, q, qd, qdd, walk=w) if n else \
        Motion({}, {}, {}, {}, {}, {}, [], [], [])
    return Sweep(**vars(mo), mechanism=m, angles=angles[:n], q=q, qd=qd, qdd=qdd, stopped=stopped,
                 kinematics=kin, known_condition=known_cond, leaves=leaves)


# -- one cycle of the driver (``velpoly sweep``, ``velpoly animate``, ``velpoly html``) ------------------
# A crank turns from its reference angle through 360 degrees in the sense of its omega, ``step`` degrees
# apart (the closing pose left out). A slider driver runs over the whole stroke it reaches from its
# reference position on the drawn branch (at most STROKE_REACH mechanism sizes either way), in ascending
# displacement, with steps of 1/(360/step) of the stroke (a unit-free step); each end of the stroke is a
# toggle, so the two halves are followed from the reference position outwards and stop within one step
# of each end: that is the cycle, not an early stop. A toggle on the way ends a crank's cycle early
# (Sweep.stopped).
STROKE_REACH = 2.0         # a slider driver is searched this many mechanism sizes either way
STROKE_SAMPLES = 2000      # grid of that search (the stroke's ends are found to 1/1000 size)


def check_step(step: float) -> float:
    """``--step`` as a float in (0, 180] degrees, else an InputError."""
    step = float(step)
    if not math.isfinite(step) or step <= 0 or step > 180:
        raise InputError(f"the step must be a number of degrees in (0, 180], got {step:g}", where="--step",
                         hint="e.g. --step 1 (360 poses a turn) or --step 5")
    return step


def cycle_poses(step: float) -> int:
    """The poses of one cycle ``step`` degrees apart: a turn, or each half of a slider's stroke."""
    return max(int(math.ceil(360.0 / check_step(step) - 1e-9)), 1)


def _slider_stroke(m: Mechanism, kin: Kinematics) -> tuple[float, float]:
    """The driver slider's reachable displacements (lo, hi) from its reference position."""
    grid = np.linspace(0.0, STROKE_REACH * m.size, STROKE_SAMPLES + 1)[1:]
    ends = []
    for sign in (-1.0, 1.0):
        w = sweep(m, sign * grid, kin)
        ends.append(float(w.angles[-1]) if len(w.angles) else 0.0)
    return ends[0], ends[1]


def _slider_positions(lo: float, hi: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Displacements from the reference (0) down towards ``lo`` and up towards ``hi``, (hi - lo) / n
    apart: the multiples of the step inside the stroke (an end itself is a toggle, left out)."""
    d = (hi - lo) / n if hi > lo else 1.0
    down = -d * np.arange(int(math.floor(-lo / d + 1e-9)) + 1)
    up = d * np.arange(int(math.floor(hi / d + 1e-9)) + 1)
    return down, up


def cycle_angles(m: Mechanism, step: float = 1.0, kin: Kinematics | None = None) -> np.ndarray:
    """The driver positions of one cycle (module docstring): degrees, or displacements for a slider."""
    step = check_step(step)
    n = cycle_poses(step)
    if m.driver.is_slider:
        down, up = _slider_positions(*_slider_stroke(m, kin or prepare(m)), n)
        return np.concatenate([down[::-1], up[1:]])
    ref = driver_reference_angle(m)
    sense = -1.0 if m.driver.omega < 0 else 1.0
    return ref + sense * step * np.arange(n)


def join_sweeps(down: Sweep, up: Sweep) -> Sweep:
    """One sweep from two that start at the reference pose: ``down`` reversed, then ``up`` (its
    first pose, the reference, once). Arrays, dicts of arrays and lists of such dicts are joined
    pose by pose; the mechanism is kept and the stop messages are combined."""
    def cat(a, b):
        if isinstance(a, dict):
            return {k: cat(a[k], b[k]) for k in a}
        if isinstance(a, list):
            return [cat(x, y) for x, y in zip(a, b)]
        return np.concatenate([np.asarray(a)[::-1], np.asarray(b)[1:]])
    joined = {}
    for f in dataclasses.fields(Sweep):
        a, b = getattr(down, f.name), getattr(up, f.name)
        if f.name == "stopped":
            joined[f.name] = "; ".join(x for x in (a, b) if x)
        elif isinstance(a, (np.ndarray, dict, list)) and type(a) is type(b):
            joined[f.name] = cat(a, b)
        elif isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
            joined[f.name] = None          # known on one side only (a cache): recomputed on use
        else:
            joined[f.name] = b
    return Sweep(**joined)


def run_cycle(m: Mechanism, step: float = 1.0, kin: Kinematics | None = None) -> Sweep:
    """One driver cycle on the drawn branch (see the module docstring).

    A slider driver's stroke is followed from the reference position down to
    its lower end and up to its upper end (two continuations, never turning
    round at an end, where the branches meet), and returned in ascending order.
    """
    kin = kin or prepare(m)
    step = check_step(step)
    n = cycle_poses(step)
    if not m.driver.is_slider:
        return sweep(m, cycle_angles(m, step, kin), kin)
    down, up = _slider_positions(*_slider_stroke(m, kin), n)
    w_down, w_up = sweep(m, down, kin), sweep(m, up, kin)
    if not len(w_up.angles):
        return w_up
    if not len(w_down.angles):
        return w_down
    # the stroke ends where it cannot go on: not a stop to warn about
    return dataclasses.replace(join_sweeps(w_down, w_up), stopped="")


def solution_at(sw: Sweep, kin: Kinematics, i: int):
    """The :class:`velpoly.Solution` of pose i of the sweep (for the figure functions)."""
    q, qd, qdd = sw.q[i:i + 1], sw.qd[i:i + 1], sw.qdd[i:i + 1]
    mo = evaluate_motion(sw.mechanism, kin.system.index, q, qd, qdd)
    angle = None if sw.mechanism.driver.is_slider else float(sw.angles[i])
    if angle is not None:
        angle = float((angle + 180.0) % 360.0 - 180.0) or 0.0
    return Solution(sw.mechanism, kin, q[0], qd[0], qdd[0], float(sw.condition[i]), mo, angle)


def check_cycle(sw: Sweep, kin: Kinematics, step: float | None = None) -> None:
    """A PoseError naming the links unless the cycle reached two poses or more: the pin that leaves
    its slot at once, or the links that come into line (a toggle at the reference pose, or one nearer
    ahead of it than the ``step``: the hint then names the step that reaches it)."""
    m = sw.mechanism
    if len(sw.angles) >= 2:
        return
    if sw.leaves is not None:
        sl = next(s for s in m.slots if s.pin == sw.leaves[0] and s.slot == sw.leaves[1])
        raise PoseError(f"cannot sweep: {len(sw.angles)} pose(s) reachable from the reference pose ({sw.stopped})",
                        where="driver", file=m.source, links=(sl.link, sl.slot),
                        hint="draw the pin inside its slot, away from the slot's ends")
    links = involved_links(kin, sw.q[-1] if len(sw.q) else np.zeros(kin.system.nq))
    reach = reachable_text(m, kin)
    raise PoseError(f"cannot sweep: {len(sw.angles)} pose(s) reachable from the reference pose"
                    + (f" ({sw.stopped})" if sw.stopped else "") + (f"; {reach}" if reach else ""),
                    where="driver", file=m.source,
                    links=links, hint="links " + ", ".join(links) + " come into line: " + _finer_step(m, kin, step))


def _finer_step(m: Mechanism, kin: Kinematics, step: float | None) -> str:
    """The way to a sweep of a crank whose cycle stopped after its first pose: a ``--step`` under the
    reach ahead of the drawn pose (the cycle runs from it in omega's sense), rounded down to 0.01 deg,
    where the step overshot a toggle it could have come nearer; else a pose away from the toggle."""
    away = "draw the mechanism in a pose away from the toggle"
    if step is None or m.driver.is_slider:
        return away
    lo, hi = reachable_range(kin)
    ahead = math.floor(100.0 * (-lo if m.driver.omega < 0 else hi)) / 100.0
    if not 0.0 < ahead < step:
        return away
    sense, end = ("clockwise", -ahead) if m.driver.omega < 0 else ("counter-clockwise", ahead)
    return (f"give a --step under {ahead:g} deg (the cycle runs {sense} from the drawn pose to the toggle near "
            f"{driver_reference_angle(m) + end:g} deg), or {away}")


def stop_note(sw: Sweep, kin: Kinematics) -> str:
    """Why the cycle ended early and what it reached (the command's warning), "" if it did not."""
    m = sw.mechanism
    if sw.stopped and sw.leaves is not None:
        reach = reachable_text(m, kin).replace("reachable on this branch:", "the pin is in its slot from")
        return f"{sw.stopped}" + (f"; {reach}" if reach else "") + "; the outputs hold the part before"
    if sw.stopped:
        links = involved_links(kin, sw.q[-1])
        reach = reachable_text(m, kin)
        return (f"{sw.stopped} (links {', '.join(links)} come into line); "
                + (f"{reach}; " if reach else "") + "the outputs hold the reachable part")
    return ""
