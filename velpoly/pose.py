"""Poses: compass-and-ruler point constructions, and reassembly at other driver positions.

The reference pose is drawn by the file's constructions, evaluated once in
file order (:func:`circle_circle`, :func:`circle_line`). Any other driver
position is reached by continuation from the reference pose along the
branch the user drew: the driver is stepped, each pose predicted from the
velocities of the last (q(delta + h) ~ q + h q') and corrected by Newton's
method on the constraint equations, Phi(q) = 0. Poses between the steps are
corrected all at once (one batched Newton over every remaining pose); a pose
that batch misses is retried step by step, halving the step, from the
nearest pose already found. A pose where the Jacobian degenerates or Newton
cannot converge even with the step halved (to 1e-6 rad, or 1e-6 of a slider's size) is a toggle:
continuation stops there, with the reachable range. So is a pose on or within that travel of a
singular one (a change point: :func:`_clear`), and one Newton converges to only linearly (a double
root: :func:`_newton`), as the dyad walk refuses a dyad whose circles touch (:data:`TOUCH`).
"""
from __future__ import annotations

import math

import numpy as np

from .constraints import System
from .dyads import assemble, dyad_plan, walk

__all__ = ["circle_circle", "coarse_step", "circle_line", "Reassembly", "reassemble", "select_rows", "check_closed_form",
           "walked_reach", "slot_travel", "same_mechanism", "TOUCH"]


# -- compass and ruler ----------------------------------------------------------
def circle_circle(p, r1: float, q, r2: float):
    """Both intersections of the circles (p, r1) and (q, r2).

    Returns ``(left, right, gap)``: the intersections to the left and to the
    right of the directed line p -> q, and the gap by which the circles miss
    each other (0 when they meet; positive when they do not, in which case
    the two points are the nearest approach).
    """
    p, q = np.asarray(p, float), np.asarray(q, float)
    d = q - p
    dist = float(np.hypot(*d))
    if dist == 0.0:
        return p, p, (abs(r1 - r2) if r1 != r2 else float("inf"))
    gap = max(dist - (r1 + r2), abs(r1 - r2) - dist, 0.0)
    k = _pow2(max(dist, r1, r2))   # squares in units of the construction: no overflow, no underflow (exact)
    dk, r1k, r2k = dist * k, r1 * k, r2 * k
    a = (r1k * r1k - r2k * r2k + dk * dk) / (2 * dk) / k
    ak = a * k
    h2 = r1k * r1k - ak * ak
    h = np.sqrt(h2) / k if h2 > 0 else 0.0
    e = d / dist
    n = np.array([-e[1], e[0]])
    m = p + a * e
    return m + h * n, m - h * n, gap


def circle_line(c, r: float, through, direction_deg: float):
    """Both intersections of the circle (c, r) with a line through ``through`` at an angle.

    Returns ``(first, second, gap)``: the intersections in order along the
    line's direction, and the gap by which the line misses the circle.
    """
    c, p = np.asarray(c, float), np.asarray(through, float)
    t = np.radians(direction_deg)
    e = np.array([np.cos(t), np.sin(t)])
    foot = p + np.dot(c - p, e) * e
    d = float(np.hypot(*(c - foot)))
    gap = max(d - r, 0.0)
    k = _pow2(max(r, d))   # as in circle_circle: the squares taken at the scale of the construction
    rk, dk = r * k, d * k
    h = np.sqrt(max(rk * rk - dk * dk, 0.0)) / k
    return foot - h * e, foot + h * e, gap


def _pow2(x: float) -> float:
    """A power of two near 1/x (1 for 0 or non-finite x): scaling by it is exact in floating point."""
    if not (x > 0 and math.isfinite(x)):
        return 1.0
    return math.ldexp(1.0, -min(max(math.frexp(x)[1], -1000), 1000))   # 2^+-1000: finite


# -- Newton and continuation -------------------------------------------------------
def select_rows(system: System, jac: np.ndarray, tol: float = 1e-9) -> list[int]:
    """Indices of a maximal set of independent constraint rows of ``jac`` (m x nq), in order.

    Row i is kept when its part orthogonal to the rows kept before it is longer than ``tol`` times
    its length (at least 1). Gram-Schmidt in blocks of rows: a block is first cleared of the basis
    so far by two matrix products (classical Gram-Schmidt twice, as accurate as one row at a time),
    then its rows are taken one by one against the basis vectors of the block only; a long chain's
    few hundred rows cost matrix products, not a Python loop per pair of rows.
    """
    jac = np.asarray(jac, float)
    keep: list[int] = []
    basis = np.empty((min(len(jac), jac.shape[1]), jac.shape[1]))
    k = 0
    for start in range(0, len(jac), _ROW_BLOCK):
        block = jac[start:start + _ROW_BLOCK].copy()
        for _ in range(2 if k else 0):
            block -= (block @ basis[:k].T) @ basis[:k]
        first = k
        for i, r in enumerate(block):
            for b in basis[first:k]:
                r -= np.dot(r, b) * b
            nr = np.linalg.norm(r)
            if nr > tol * max(1.0, np.linalg.norm(jac[start + i])):
                basis[k] = r / nr
                k += 1
                keep.append(start + i)
    return keep


_ROW_BLOCK = 32   # rows cleared of the basis together (select_rows)


class Reassembly:
    """The result of carrying a mechanism to other driver positions.

    ``deltas`` are the driver displacements reached (from the reference
    pose), ``q`` the poses (len(deltas), nq); ``stopped`` says why the sweep
    ended early, or is empty.
    """

    def __init__(self, deltas, q, stopped="", continued=False, leaves=None):
        self.deltas = deltas
        self.q = q
        self.stopped = stopped
        self.continued = continued   # True when found by continuation, not the closed-form dyads
        self.leaves = leaves         # (slot index, end point, driver position) where a pin leaves its slot


SETTLED = 1e-10   # Newton's last correction (unit lengths, radians) on a converged pose (_newton)


def _newton(system: System, rows, q, targets, iters=30):
    """Batched Newton on the selected rows plus the driver row.

    Iterates until the correction is at rounding level (at least once, so a
    good prediction is still corrected to full precision): below 1e-14, or,
    where rounding in the equations leaves more than that (a Jacobian
    conditioned worse than ~100), once the correction is below 1e-10 and no
    longer shrinks (Newton converging would cut it by orders of magnitude; what
    is left is noise, and iterating on it only walks q about in its last
    digits). Steps are limited so that Newton cannot jump to another branch.
    Returns (q, converged mask, Jacobians of the selected rows).

    A pose has converged when its residual is below 1e-9 of the size and Newton's last correction
    below 1e-10 (:data:`SETTLED`): the pose is then determined by the equations to that tolerance.
    The residual alone does not tell: at a double root (a target on a toggle or a change point,
    where the circles touch) Newton converges only linearly, and rounding holds its corrections near
    the square root of the rounding (1e-8: 5e-9 to 2.5e-7 at a change-point four-bar's 180 deg) however
    long it iterates, while the residual (their square) passes. A simple root near a singular pose may
    still settle (a change point 1e-7 deg away): :func:`_clear` refuses that one.
    """
    if len(q) == 1:
        return _newton_one(system, rows, q, float(targets[0]), iters)
    return _newton_batch(system, rows, q, targets, iters)


def _newton_batch(system: System, rows, q, targets, iters=30):
    """:func:`_newton` for a batch of poses, each converged pose left out of the next iterations."""
    q = q.copy()
    L = max(system.size, 1e-300)
    active = np.ones(len(q), bool)
    last = np.full(len(q), np.inf)     # each pose's previous correction
    for _ in range(iters):
        if not active.any():
            break
        phi, jac, _ = system.evaluate(q[active])
        phi = phi[:, rows]
        jac = jac[:, rows]
        phi[:, -1] -= targets[active]
        try:
            dq = np.linalg.solve(jac, -phi[..., None])[..., 0]
        except np.linalg.LinAlgError:
            dq = np.stack([_solve_or_nan(j, -p) for j, p in zip(jac, phi)])
        size = np.abs(_scaled(system, dq)).max(axis=1, initial=0.0)
        scale = np.where(size > 0.5, 0.5 / np.maximum(size, 1e-300), 1.0)
        idx = np.flatnonzero(active)
        q[idx] += dq * scale[:, None]
        done = (size <= 1e-14) | ((size <= SETTLED) & (size >= last[idx]))
        last[idx] = size
        active[idx[done]] = False
    phi, jac, _ = system.evaluate(q)
    phi = phi[:, rows]
    phi[:, -1] -= targets
    ok = np.all(np.isfinite(phi), axis=1) & (np.abs(phi).max(axis=1) <= 1e-9 * L) & (last <= SETTLED)
    return q, ok, jac[:, rows]


def _newton_one(system, rows, q, target: float, iters: int):
    """:func:`_newton` for one pose (a knot step's): :func:`_newton_batch`'s operations on the same
    values, without the batch's masks; the correction's size in unit lengths divides by (L, L, 1, ...) (the system's
    column scales; 1.0 an exact identity), as :func:`_scaled` divides the lengths' columns."""
    q = q.copy()
    unit = system.column_scales
    last = size = math.inf
    every = None       # rows selecting every equation: the evaluation's own (fresh) arrays serve
    for _ in range(iters):
        phi, jac, _ = system.evaluate(q)
        if every is None:
            every = list(rows) == list(range(phi.shape[1]))
        if not every:
            phi = phi[:, rows]
            jac = jac[:, rows]
        phi[0, -1] -= target
        try:
            dq = np.linalg.solve(jac, -phi[..., None])[..., 0]
        except np.linalg.LinAlgError:
            dq = _solve_or_nan(jac[0], -phi[0])[None, :]
        size = float(np.abs(dq[0] / unit).max())
        if size > 0.5:
            dq = dq * (0.5 / max(size, 1e-300))
        q += dq
        if size <= 1e-14 or (size <= SETTLED and size >= last):
            break
        last = size
    phi, jac, _ = system.evaluate(q)
    if not every:
        phi = phi[:, rows]
        jac = jac[:, rows]
    phi[0, -1] -= target
    ok = np.all(np.isfinite(phi), axis=1) & (np.abs(phi).max(axis=1) <= 1e-9 * max(system.size, 1e-300)) \
        & (size <= SETTLED)
    return q, ok, jac


def _velocity(system, rows, q, jac=None):
    """q' per unit driver rate at the poses q (the continuation's tangent)."""
    if jac is None:
        jac = system.evaluate(q)[1][:, rows]
    rhs = np.zeros(jac.shape[:2])
    rhs[:, -1] = 1.0
    try:
        return np.linalg.solve(jac, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:   # a singular pose among them: no tangent there (NaN)
        return np.stack([_solve_or_nan(j, r) for j, r in zip(jac, rhs)])


def _solve_or_nan(a, b):
    try:
        return np.linalg.solve(a, b)
    except np.linalg.LinAlgError:
        return np.full(a.shape[1], np.nan)


def _cond(system, rows, jac):
    """Condition numbers of the (row-selected) Jacobians, in unit lengths."""
    return np.linalg.cond(system.scale_matrix(jac, rows))


def reassemble(system: System, rows: list[int], deltas, coarse: float | None = None,
               knots: "Knots | None" = None) -> Reassembly:
    """Carry the mechanism from the reference pose through the driver positions ``deltas``.

    ``deltas`` are driver displacements from the reference pose (radians for
    a crank, lengths for a slider), followed in the order given, each pose
    continued from the previous one. ``rows`` are the independent
    constraint rows plus the driver's (last); the equations are those of
    :attr:`System.positions` (a prescribed slip integrated over the time the
    driver takes at its constant rate). Stops before the first
    position that cannot be reached without crossing a toggle: one that the
    sequential continuation (:func:`_step`, halving the step) cannot reach
    either, not merely one the batched correction missed; or, for a pin in
    a slot with ``ends``, before the first position past the one where the
    pin reaches an end (``stopped`` is then "slot" and ``leaves`` says where).

    ``knots`` (a :class:`Knots`, optional) keeps the continuation's knots for the next call with
    the same system, rows and ``coarse``: a knot step it has made (or seen fail) is not made again.
    Without it, the knots of the last few continuations are kept by mechanism equality, one
    :class:`Knots` for each way from the drawn pose (:func:`_kept_knots`): solving an equal mechanism
    at angle after angle walks the way to each from the drawn pose once, not again for every angle.
    """
    system = system.positions   # a prescribed slip in positions, or InputError (no position equation)
    deltas = np.asarray(deltas, float).ravel()
    fast = _closed_form(system, rows, deltas)
    if fast is not None:
        return fast
    if knots is None and len(deltas):
        knots = _kept_knots(system, rows, coarse_step(system) if coarse is None else coarse, deltas[0])
    ends = [i for i, s in enumerate(system.mechanism.slots) if s.ends]
    r, kd, kq, attach, sign = _continue(system, rows, deltas, coarse, knots)
    return _within_slots(system, rows, r, ends, kd, kq, attach, sign) if ends else r


def same_mechanism(a, b) -> bool:
    """Whether two mechanisms are equal (frozen dataclasses of tuples, mappings and floats): their
    equations are then the same and a continuation of one is that of the other, bit for bit."""
    try:
        return a is b or bool(a == b)
    except (TypeError, ValueError):   # a field that does not compare (an array): not known equal
        return False


_KEPT: list = []    # (mechanism, (rows, coarse, way), Knots) of the last continuations, newest last


def _kept_knots(system, rows, coarse: float, first: float) -> "Knots":
    """The kept :class:`Knots` of an equal mechanism's continuation on the same rows with the same
    ``coarse`` step the same way (the sign of the ``first`` driver position), or a new one."""
    key = (tuple(rows), float(coarse), first < 0.0)
    m = system.mechanism
    for i in range(len(_KEPT) - 1, -1, -1):
        known, known_key, knots = _KEPT[i]
        if known_key == key and same_mechanism(known, m):
            _KEPT.append(_KEPT.pop(i))
            return knots
    knots = Knots()
    _KEPT.append((m, key, knots))
    del _KEPT[:-8]
    return knots


class Knots:
    """The knots of a continuation (:func:`_continue`), kept for the next one on the same system.

    Knot k + 1 is :func:`_step` from knot k to a driver position; the step is a function of
    its inputs alone, so a later continuation that asks the same step from the same knot (the
    same driver positions, bit for bit) gets the answer kept here, as it would compute it: the
    pose and Jacobian, or None for a step that failed (a toggle). :func:`velpoly.driver.reachable_range`
    walks each direction twice, the second time along the first's knots to the last pose before
    the toggle.
    """

    def __init__(self):
        self.key = None
        self.d: list[float] = []       # the knots' driver positions, from 0.0
        self.made: list = []           # (q, jac) at each knot after the first
        self.failed: set = set()       # (knot, target) steps that failed
        self.retried: dict = {}        # (pose bytes, from, to) -> a retried pose's step (Knots.retry)

    def start(self, system, rows, coarse) -> None:
        """Use these knots for a continuation of ``system`` on ``rows`` with steps of ``coarse``
        (forgetting them if they were another's)."""
        key = (system, tuple(rows), coarse)
        if self.key is None or self.key[1:] != key[1:] or not (
                self.key[0] is system or same_mechanism(self.key[0].mechanism, system.mechanism)):
            self.key, self.d, self.made, self.failed, self.retried = key, [0.0], [], set(), {}

    def retry(self, system, rows, q, d0: float, d1: float, sign):
        """:func:`_step` from the pose ``q`` (1, nq) at driver position d0 to d1, kept: the sequential
        retry of a pose the batched correction missed (:func:`_continue`), which near a toggle halves
        its step a score of times; the same continuation asked again (an equal mechanism swept or
        solved again at the same positions) retries from the same pose, bit for bit."""
        key = (q.tobytes(), d0, d1, sign)
        if key not in self.retried:
            if len(self.retried) >= 64:
                self.retried.clear()
            self.retried[key] = _step(system, rows, q, system.evaluate(q)[1][:, rows], d0, d1, sign)
        return self.retried[key]

    def step(self, system, rows, q, jac, k: int, target: float, sign):
        """:func:`_step` from knot ``k`` (pose ``q``, Jacobian ``jac``) to ``target``, kept."""
        if k + 1 < len(self.d) and self.d[k + 1] == target:
            return self.made[k]
        if (k, target) in self.failed:
            return None
        nxt = _step(system, rows, q, jac, self.d[k], target, sign)
        del self.d[k + 1:], self.made[k:]
        self.failed = {f for f in self.failed if f[0] <= k}
        if nxt is None:
            self.failed.add((k, target))
        else:
            self.d.append(target)
            self.made.append(nxt)
        return nxt


def _walk_knots(system, rows, deltas, coarse, knots: Knots | None):
    """Step 1 of :func:`_continue`: the knots, a sequential continuation never stepping farther than
    ``coarse`` (default :func:`coarse_step`), every requested position attached to the knot before it.
    Returns (knot positions, knot poses, attach, how many positions are reached, stopped, the sign of
    the drawn pose's Jacobian determinant)."""
    n, nq = len(deltas), system.nq
    if coarse is None:
        coarse = coarse_step(system)
    if knots is None:
        knots = Knots()
    knots.start(system, rows, coarse)
    knot_d, knot_q = [0.0], [np.zeros(nq)]
    jac = system.evaluate(np.zeros((1, nq)))[1][:, rows]
    # the drawn branch keeps the sign of the Jacobian's determinant: it changes only through a
    # singular pose, as at a change point, where Newton would carry on along the other branch
    sign = _orientation(jac)[0]
    attach = np.empty(n, int)
    q = np.zeros((1, nq))
    for idx, d in enumerate(deltas):
        if abs(d - knot_d[-1]) > coarse:
            start = knot_d[-1]
            k = int(np.floor(abs(d - start) / coarse))   # whole steps of `coarse` towards d
            for target in start + np.sign(d - start) * coarse * np.arange(1, k + 1):
                nxt = knots.step(system, rows, q, jac, len(knot_d) - 1, float(target), sign)
                if nxt is None:
                    return knot_d, knot_q, attach, idx, "toggle", sign
                q, jac = nxt
                knot_d.append(float(target))
                knot_q.append(q[0].copy())
        attach[idx] = len(knot_d) - 1
    return knot_d, knot_q, attach, n, "", sign


def _continue(system, rows, deltas, coarse, knots: Knots | None = None):
    """:func:`reassemble` by continuation; also returns the knots (driver positions and poses),
    the knot each reached position was continued from, and the determinant's sign."""
    nq = system.nq
    knot_d, knot_q, attach, n, stopped, sign = _walk_knots(system, rows, deltas, coarse, knots)
    deltas, attach = deltas[:n], attach[:n]
    kd, kq = np.array(knot_d), np.array(knot_q)
    if n == 0:
        return Reassembly(deltas, np.zeros((0, nq)), stopped, continued=True), kd, kq, attach, sign
    # 2. every requested pose at once: predicted from its knot, corrected by batched Newton
    jk = system.evaluate(kq)[1][:, rows]
    qd = _velocity(system, rows, kq, jk)
    h = deltas - kd[attach]
    guess = kq[attach] + h[:, None] * qd[attach]
    out, ok, jo = _newton(system, rows, guess, deltas)
    ok &= _drift(system, out - guess) <= _drift_bound(system, h, qd[attach])
    ok &= _orientation(jo) == sign
    ok &= _clear(system, h, jk[attach], jo)
    ok &= _smooth(system, out - kq[attach], h[:, None] * qd[attach], h[:, None] * _velocity(system, rows, out, jo))
    # 3. a pose the batched correction missed (a poor prediction where the links turn fast) is
    #    retried sequentially, with the knots' halving, from the nearest pose already converged
    #    on its knot's stretch; it is a toggle only if that fails too, and then the sweep stops there.
    for i in np.flatnonzero(~ok):
        same = np.flatnonzero(ok & (attach == attach[i]))
        j = same[np.argmin(np.abs(deltas[same] - deltas[i]))] if len(same) else -1
        if j >= 0 and abs(deltas[j] - deltas[i]) < abs(h[i]):
            d0, q0 = float(deltas[j]), out[j:j + 1]
        else:
            d0, q0 = float(kd[attach[i]]), kq[attach[i]][None, :]
        nxt = (knots or Knots()).retry(system, rows, q0, d0, float(deltas[i]), sign)
        if nxt is None:
            return Reassembly(deltas[:i], out[:i], "toggle", continued=True), kd, kq, attach[:i], sign
        out[i], ok[i] = nxt[0][0], True
    return Reassembly(deltas, out, stopped, continued=True), kd, kq, attach, sign


def slot_travel(m, index: dict, q, slots=None) -> np.ndarray:
    """Where each pin stands in its bounded slot at the poses q (N, nq): (N, len(slots)) slip
    coordinates t = (P - S1) . e / (S2 - S1) . e, 0 at the end S1 and 1 at S2 (e the slot's
    direction on the slot link; P the pin on its link, S1 and S2 on the slot link)."""
    q = np.atleast_2d(q)
    slots = [i for i, s in enumerate(m.slots) if s.ends] if slots is None else slots
    out = np.empty((len(q), len(slots)))
    for col, i in enumerate(slots):
        s = m.slots[i]
        e = np.array([math.cos(math.radians(s.angle)), math.sin(math.radians(s.angle))])
        s1, s2 = (np.array(m.points[n], float) for n in s.ends)
        pin = _place(m, index, q, s.link, s.pin)
        k = index.get(s.slot)
        th = q[:, 3 * k + 2] if k is not None else np.zeros(len(q))
        ew = np.stack([np.cos(th) * e[0] - np.sin(th) * e[1], np.sin(th) * e[0] + np.cos(th) * e[1]], axis=1)
        d = pin - _place(m, index, q, s.slot, s.ends[0])
        out[:, col] = np.einsum("ij,ij->i", d, ew) / float(np.dot(s2 - s1, e))
    return out


def _place(m, index, q, link, point):
    """(N, 2): where the point of ``link`` drawn at ``point`` is at the poses q."""
    p = np.array(m.points[point], float)
    k = index.get(link)
    if k is None:
        return np.broadcast_to(p, (len(q), 2))
    x, y, th = q[:, 3 * k], q[:, 3 * k + 1], q[:, 3 * k + 2]
    c, s = np.cos(th), np.sin(th)
    return np.stack([x + c * p[0] - s * p[1], y + s * p[0] + c * p[1]], axis=1)


def _within_slots(system, rows, r, ends, kd, kq, attach, sign):
    """Cut a continuation where a pin reaches an end of its slot (FORMAT.md: the end of the motion).

    The way runs through the knots and the reached positions in order (each position after the
    knots made on the way to it). Each pin's slip coordinate t must stay in [0, 1]: at the way's
    points, and between two of them where the cubic through their t and slopes dt/d(driver)
    leaves [0, 1] (the pose at its extreme is continued and checked: a pin that overshoots an end
    and comes back within a step). At the first point beyond an end, the driver position where
    the pin reaches it is found by regula falsi between that point and the one before (poses
    continued from the nearest inside), to 1e-10 of a radian (or of the size)."""
    m = system.mechanism
    nq = system.nq
    n = len(r.deltas)
    # the way: (driver position, pose, reached position index it leads to)
    order = []
    last_knot = 0
    for i in range(n + 1):
        top = attach[i] if i < n else len(kd) - 1
        order += [(kd[j], kq[j], i) for j in range(last_knot + 1, top + 1)]
        last_knot = max(last_knot, top)
        if i < n:
            order.append((r.deltas[i], r.q[i], i))
    if not order:
        return r
    d = np.array([0.0] + [o[0] for o in order])
    q = np.vstack([kq[:1]] + [o[1][None, :] for o in order]).reshape(-1, nq)
    t, slope = _travel_and_slope(system, rows, q, ends)
    for k in range(1, len(d)):
        i = order[k - 1][2]
        prev = (d[k - 1], q[k - 1], t[k - 1])
        if not np.all(_in_slot(t[k])):
            return _cut(system, rows, r, i, ends, prev, (d[k], t[k]), sign)
        h = d[k] - d[k - 1]
        for c in range(len(ends)):
            s0, s1 = slope[k - 1, c] * h, slope[k, c] * h
            low, at_low = _hermite_extreme(t[k - 1, c], t[k, c], s0, s1)
            high, at_high = _hermite_extreme(-t[k - 1, c], -t[k, c], -s0, -s1)
            for over, at in ((not _in_slot(low), at_low), (not _in_slot(-high), at_high)):
                if not over:
                    continue
                x = float(d[k - 1] + at * h)
                nxt = _step(system, rows, q[k - 1][None, :], system.evaluate(q[k - 1][None, :])[1][:, rows],
                            float(d[k - 1]), x, sign)
                if nxt is None:
                    continue
                tx = slot_travel(m, system.index, nxt[0], ends)[0]
                if not np.all(_in_slot(tx)):
                    return _cut(system, rows, r, i, ends, prev, (x, tx), sign)
    return r


# A pin this near an end of its slot (a fraction of the slot's length, either way) is at it: rounding in
# the slip coordinate t is 1e-16..1e-15 (the pose converged to 1e-14 unit lengths; SETTLED bounds it), and a position
# at the end but for that (the end at a sweep's step exactly) is reached on every machine, not on one and cut
# on another; the end itself is found to 1e-10 rad (_cut), on a slope dt/d(driver) of order 1
AT_END = 1e-12


def _in_slot(t) -> np.ndarray:
    """Whether the slip coordinates t are within the slot's ends, 0 <= t <= 1, give or take AT_END."""
    t = np.asarray(t)
    return (t >= -AT_END) & (t <= 1.0 + AT_END)


def _travel_and_slope(system, rows, q, ends):
    """Each bounded slot's slip coordinate t at the poses q and its rate per unit driver motion
    (central differences along the continuation's tangent)."""
    m = system.mechanism
    qd = _velocity(system, rows, q)
    eps = 1e-6 * (m.size if m.driver.is_slider else 1.0)
    t = slot_travel(m, system.index, q, ends)
    slope = (slot_travel(m, system.index, q + eps * qd, ends) - slot_travel(m, system.index, q - eps * qd, ends)) \
        / (2 * eps)
    return t, slope


def _hermite_extreme(m0: float, m1: float, s0: float, s1: float) -> tuple[float, float]:
    """The lowest value on [0, 1] of the cubic with values m0, m1 and slopes s0, s1 at 0 and 1,
    and where it lies (a fraction of the interval)."""
    c1, c2, c3 = s0, 3 * (m1 - m0) - 2 * s0 - s1, 2 * (m0 - m1) + s0 + s1
    ts = []
    if c3 != 0.0:
        disc = c2 * c2 - 3 * c3 * c1
        if disc >= 0.0:
            root = math.sqrt(disc)
            ts += [(-c2 + root) / (3 * c3), (-c2 - root) / (3 * c3)]
    elif c2 != 0.0:
        ts.append(-c1 / (2 * c2))
    low, at = (m0, 0.0) if m0 <= m1 else (m1, 1.0)
    for x in ts:
        if 0.0 < x < 1.0:
            v = m0 + x * (c1 + x * (c2 + x * c3))
            if v < low:
                low, at = v, x
    return low, at


def _cut(system, rows, r, i, ends, inside, outside, sign):
    """The reassembly up to (not including) position i, and where the pin leaves its slot between
    the driver positions ``inside`` (d, q, t) and ``outside`` (d, t)."""
    m = system.mechanism
    d0, q0, t0 = inside
    d1, t1 = outside
    col = int(np.argmax(~_in_slot(t1)))
    bound = 0.0 if t1[col] < 0 else 1.0
    f0, f1 = t0[col] - bound, t1[col] - bound
    lo, hi = float(d0), float(d1)
    q_lo = np.asarray(q0)[None, :]
    unit = m.size if m.driver.is_slider else 1.0
    last = 0
    if abs(f0) <= AT_END:       # the last position inside is at the end itself
        hi = lo
    for _ in range(100):
        if abs(hi - lo) <= 1e-10 * unit:
            break
        x = hi - f1 * (hi - lo) / (f1 - f0) if f1 != f0 else 0.5 * (lo + hi)
        if not (min(lo, hi) < x < max(lo, hi)):
            x = 0.5 * (lo + hi)
        nxt = _step(system, rows, q_lo, system.evaluate(q_lo)[1][:, rows], lo, x, sign)
        if nxt is None:         # a toggle before the end: the motion stops there
            hi, f1 = x, f1
            break
        f = float(slot_travel(m, system.index, nxt[0], [ends[col]])[0, 0]) - bound
        if (f < 0) == (f0 < 0):
            lo, f0, q_lo = x, f, nxt[0]
            if last < 0:
                f1 *= 0.5
            last = -1
        else:
            hi, f1 = x, f
            if last > 0:
                f0 *= 0.5
            last = 1
    s = m.slots[ends[col]]
    where = 0.5 * (lo + hi)
    return Reassembly(r.deltas[:i], r.q[:i], "slot", continued=True,
                      leaves=(ends[col], s.ends[int(bound)], where))


def coarse_step(system: System) -> float:
    """The longest continuation step: 6 degrees for a crank, 4% of the size for a slider."""
    return 0.04 * system.size if system.mechanism.driver.is_slider else np.radians(6.0)


_PLANS: dict = {}


def plan_for(system: System):
    """The mechanism's chain of dyads (:func:`velpoly.dyads.dyad_plan`), cached per system."""
    key = id(system)
    if key not in _PLANS or _PLANS[key][0] is not system:
        if len(_PLANS) > 64:
            _PLANS.clear()
        _PLANS[key] = (system, dyad_plan(system.mechanism))
    return _PLANS[key][1]


def _closed_form(system: System, rows, deltas) -> Reassembly | None:
    """All poses at once by the mechanism's chain of dyads, if it has one (verified)."""
    m = system.mechanism
    plan = plan_for(system)
    if plan is None or len(deltas) == 0:
        return None
    q, reach = assemble(m, system.index, plan, deltas)
    if not check_closed_form(system, rows, q[:reach], deltas[:reach]):
        return None   # not the mechanism the plan assumed: use continuation
    reach = min(reach, walked_reach(m, plan, deltas, coarse_step(system)))
    return Reassembly(deltas[:reach], q[:reach], "toggle" if reach < len(deltas) else "")


# A dyad whose squared transmission sine (its closure, :func:`velpoly.dyads.closure`) dips to TOUCH
# between two driver positions touches a toggle or a change point there: the branches meet, and
# the walk, which keeps each dyad's drawn side, would come out on the other one. 1e-12 (a sine of
# 1e-6) is the floor to which the bottom of such a double root is found in floating point.
TOUCH = 1e-12
_TRIGGER = 1e-6   # a dip whose estimated bottom lies below this (or below half its ends) is searched


def _quiet_walk(m, plan, deltas, rate=None):
    """The dyad walk without numpy's warnings past a toggle (NaN there, screened by the callers)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return walk(m, plan, np.asarray(deltas, float), rate, 0.0)


def walked_reach(m, plan, deltas, coarse: float, w=None, rate: float | None = None) -> int:
    """How many of ``deltas`` a dyad walk reaches on the drawn branch: from the drawn pose (0) to
    the first, then each from the one before, never across a position where a dyad's circles miss
    each other (a toggle, a gap between two arcs of a double rocker) or touch (a toggle, or the
    change point of a parallelogram or a kite, where the walk would go on in the crossed assembly).

    The way is walked in steps no longer than ``coarse`` (driver units); where the positions are
    that close, ``w``, their walk with the driver's ``rate``, serves (with the drawn pose's).
    Every dyad's closure mu (:func:`velpoly.dyads.closure`) must stay positive at the steps and
    between them: where its slope along the way turns from falling to rising and the cubic through
    the two ends' values and slopes comes near zero, its lowest point is found (regula falsi on
    the slope) and must lie above TOUCH.
    """
    deltas = np.asarray(deltas, float).ravel()
    n = len(deltas)
    if n == 0:
        return 0
    path, ends, mu, dmu = _closures_along(m, plan, deltas, coarse, w, rate)
    if mu.size == 0:
        return n
    # NaN (a dyad before it open) counts as open; so does a position at the bottom of a dip to
    # zero (mu and its slope both vanish there: a change point, not a toggle's simple root)
    stop = len(path)
    if not mu[:, 1:].min(initial=np.inf) > TOUCH:
        closed = np.all(mu >= 0, axis=0) & ~np.any((mu <= TOUCH) & (np.abs(dmu) <= 1e-5), axis=0)
        closed[0] = True                         # the drawn pose, checked on its own
        stop = len(path) if closed.all() else int(np.argmin(closed))
    if stop > 1:
        stop = _dip_stop(m, plan, path, mu, dmu, stop)
    return int(np.searchsorted(ends, stop))


def _closures_along(m, plan, deltas: np.ndarray, coarse: float, w, rate):
    """``(path, ends, mu, dmu)``: the driver positions walked from the drawn pose (0) through the
    deltas in steps no longer than ``coarse``, where each delta stands on it, and every dyad's
    closure and its slope (per driver unit) there, one row per dyad; taken from ``w`` where the
    deltas are that close."""
    n = len(deltas)
    steps = np.abs(np.diff(np.concatenate([[0.0], deltas])))
    if (w is not None and rate and math.isfinite(rate) and steps.max() <= coarse
            and len(w.closure_rate) and w.closure_rate[0] is not None):
        path, ends = deltas, np.arange(n)
        mu, dmu = np.array(w.closure), np.array(w.closure_rate) / rate
        if deltas[0] != 0.0:                      # the way starts at the drawn pose
            mu0, dmu0 = _drawn_closure(m, plan)
            path, ends = np.concatenate([[0.0], deltas]), ends + 1
            mu, dmu = np.concatenate([mu0, mu], axis=1), np.concatenate([dmu0, dmu], axis=1)
    else:
        counts = np.maximum(np.ceil(steps / coarse).astype(int), 1)
        knots = np.concatenate([[0.0], deltas])
        ends = np.cumsum(counts)                  # where each of the deltas stands on the path
        seg = np.repeat(np.arange(n), counts)     # each segment in `counts` equal steps
        j = np.arange(1, ends[-1] + 1) - np.repeat(ends - counts, counts)
        path = np.concatenate([[0.0], knots[seg] + (knots[seg + 1] - knots[seg]) * (j / counts[seg])])
        pw = _quiet_walk(m, plan, path, 1.0)
        mu, dmu = np.array(pw.closure), np.array(pw.closure_rate)
    return path, ends, mu, dmu


def _dip_stop(m, plan, path: np.ndarray, mu: np.ndarray, dmu: np.ndarray, stop: int) -> int:
    """Where the way stops (an index of ``path``, at most ``stop``) because a dyad's closure dips
    to TOUCH between two positions: where its slope along the way turns from falling to rising
    and the cubic through the ends comes near zero, its lowest point is found (:func:`_touches`)."""
    way = np.sign(np.diff(path[:stop]))
    g0, g1 = dmu[:, :stop - 1] * way, dmu[:, 1:stop] * way
    # the slope along the way goes from falling (or flat) to rising (or flat), not flat to flat
    js, ks = np.nonzero(np.sign(g1) - np.sign(g0) > 0)
    unit = m.size if m.driver.is_slider else 1.0
    for i in np.argsort(ks, kind="stable"):
        j, k = int(js[i]), int(ks[i])
        if k + 1 >= stop:
            break
        m0, m1, length = float(mu[j, k]), float(mu[j, k + 1]), abs(float(path[k + 1] - path[k]))
        if _hermite_low(m0, m1, length * float(g0[j, k]), length * float(g1[j, k])) \
                >= max(_TRIGGER, 0.5 * min(m0, m1)):
            continue        # a shallow dip, far above zero
        if _touches(m, plan, j, path[k], path[k + 1], g0[j, k], g1[j, k], unit):
            return k if k > 0 and mu[:, k].min() <= TOUCH else k + 1
    return stop


def _hermite_low(m0: float, m1: float, s0: float, s1: float) -> float:
    """The lowest value on [0, 1] of the cubic with values m0, m1 and slopes s0, s1 at 0 and 1."""
    return _hermite_extreme(m0, m1, s0, s1)[0]


_DRAWN: dict = {}


def _drawn_closure(m, plan):
    """The dyads' closures and slopes (per unit driver motion) at the drawn pose, cached per plan."""
    key = id(plan)
    if key not in _DRAWN or _DRAWN[key][0] is not plan:
        if len(_DRAWN) > 64:
            _DRAWN.clear()
        w0 = _quiet_walk(m, plan, [0.0], 1.0)
        _DRAWN[key] = (plan, np.array(w0.closure), np.array(w0.closure_rate))
    return _DRAWN[key][1:]


def _touches(m, plan, j, a, b, ga, gb, unit) -> bool:
    """Whether dyad j's closure comes down to TOUCH between driver positions a and b, where its
    slope along the way from a to b is ga <= 0 at a and gb >= 0 at b: the slope's zero (the
    lowest point) by regula falsi, Illinois-style, checking the closure at each trial."""
    way = 1.0 if b > a else -1.0
    lo, hi, glo, ghi = float(a), float(b), float(ga), float(gb)
    last = 0
    for _ in range(80):
        x = hi - ghi * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
        if not (min(lo, hi) < x < max(lo, hi)):
            x = 0.5 * (lo + hi)
        pw = _quiet_walk(m, plan, [x], 1.0)
        mu, g = float(pw.closure[j][0]), float(pw.closure_rate[j][0]) * way
        if not mu > TOUCH:
            return True
        if g < 0:
            lo, glo = x, g
            if last < 0:
                ghi *= 0.5
            last = -1
        elif g > 0:
            hi, ghi = x, g
            if last > 0:
                glo *= 0.5
            last = 1
        else:
            return False
        if abs(hi - lo) <= 1e-13 * unit + 4e-16 * max(abs(lo), abs(hi)):
            return False
    return False


def check_closed_form(system: System, rows, q, deltas) -> bool:
    """Whether the poses ``q`` (N, nq) that a dyad walk found at the driver positions
    ``deltas`` satisfy the joint equations (``system``: :attr:`System.positions`; ``rows`` the
    independent rows plus the driver's), to 1e-9 of the size; True for no poses.

    The plan is structural: a sample of the poses (up to 65, both ends included) verifies it.
    Both assembly branches satisfy the joints: the branch is the drawn one because the plan's
    sides reproduce the drawn pose (:func:`velpoly.dyads.dyad_plan` checks that).
    """
    n = len(deltas)
    if n == 0:
        return True
    pick = np.unique(np.r_[np.arange(0, n, max(1, n // 64)), n - 1])
    phi = system.residual(q[pick])[:, rows]
    phi[:, -1] -= deltas[pick]
    return bool(np.all(np.abs(phi) <= 1e-9 * max(system.size, 1.0)))


def _scaled(system, dq):
    """Coordinates in unit lengths (lengths divided by the mechanism's size; angles by 1.0, exactly
    themselves: the system's column scales)."""
    return np.asarray(dq, float) / system.column_scales


def _drift(system, dq):
    """How far Newton moved from the predicted pose (unit lengths and radians)."""
    return np.abs(_scaled(system, dq)).max(axis=1)


def _driver_unit(system) -> float:
    """The driver's unit travel: 1 radian for a crank, the mechanism's size L for a slider (the
    lengths' unit in :func:`_scaled`), so that a slider's steps are the same at any drawing scale."""
    return system.size if system.mechanism.driver.is_slider else 1.0


def _drift_bound(system, h, qd):
    """The largest correction that is still on the predicted branch: half the predicted step.

    A jump to the other assembly moves links by a good part of their length;
    the predictor's own error is second order in the step ``h``. In unit lengths and radians
    the bound is 0.5 max(|h| / u, |h q'|): the predicted step h q' (scaled), or the driver's own
    travel h / u where the links move slower than the driver (u = 1 for a crank's radians, the
    mechanism's size L for a slider's lengths). q' is per driver unit, so h q' is the step for
    either driver; the driver's travel alone is divided by u (dividing h q' by L as well made a
    slider's bound L times too tight: a drawing of size 80 then halved every step to 1/30 of
    the coarse one, and a pose away from the batch's knots failed at any step).
    """
    rate = np.maximum(1.0 / _driver_unit(system), np.abs(_scaled(system, qd)).max(axis=1))
    return 0.5 * np.abs(h) * rate + 1e-9


def _orientation(jac) -> np.ndarray:
    """The signs of the determinants of square Jacobians (N, n, n): +1, -1 (0 if singular)."""
    with np.errstate(invalid="ignore"):          # NaN where Newton failed: sign NaN, never equal
        return np.linalg.slogdet(jac)[0]


# _smooth's floor (unit lengths): Newton stops once its correction stalls below 1e-10, so a step of no
# length (a requested position equal to its knot but for rounding: 96.00000000000001 deg from the knot
# at 16 x 6 deg) has a chord of that noise, which 0.1 of itself cannot bound; a real step's chord is
# at least the halving's 1e-6 rad, far above it
SMOOTH_FLOOR = 1e-9


def _smooth(system, chord, t0, t1) -> np.ndarray:
    """Whether each step's chord q1 - q0 agrees with the trapezoid of its end tangents h q'(0), h q'(1)
    to a tenth of its length: true on a smooth branch for steps short against its curvature, false
    for a step from or onto a singular pose (where the tangent is meaningless and Newton may leave
    on the other branch of a change point)."""
    c = _scaled(system, chord)
    err = np.abs(c - 0.5 * _scaled(system, t0 + t1)).max(axis=1)
    return err <= 0.1 * np.abs(c).max(axis=1) + SMOOTH_FLOOR     # NaN (a singular tangent): False


# The continuation resolves the driver's travel to 1e-6 of its unit (:func:`_driver_unit`): a step
# is not halved below it, and a pose that near a singular one is on it (:func:`_clear`)
RESOLUTION = 1e-6


def _clear(system, h, jac0, jac1) -> np.ndarray:
    """Whether each step of driver travel h, from a pose with the Jacobian jac0 to one with jac1 (the
    same determinant sign), ends clear of a singular pose: the determinant, linear along the step,
    vanishes no nearer its end than RESOLUTION driver units, |h| det1 / (det0 - det1) >= RESOLUTION u,
    i.e. det0 / det1 <= 1 + |h| / (RESOLUTION u).

    A target on or within rounding of a change point (the circles touch there; the determinant crosses
    zero linearly along the branch) has a determinant of rounding's size against the step's start, as
    close to zero on one machine as on another, and its sign is rounding's: the sign alone (the
    orientation) cannot tell such a pose. At a toggle the determinant falls as the square root of the
    travel left: a pose RESOLUTION short of it is still clear after a step of that length. A fall of
    1e-9 or less is rounding's, not the step's (a step of no length, as in :func:`_smooth`: a position
    equal to its knot but for the last bit lands on the knot's pose but for Newton's stopping noise)."""
    with np.errstate(invalid="ignore"):          # NaN (Newton failed), -inf - -inf (both singular): not clear
        (s0, l0), (s1, l1) = np.linalg.slogdet(jac0), np.linalg.slogdet(jac1)
        fall = l0 - l1                           # log |det0 / det1|
    u = RESOLUTION * _driver_unit(system)
    return (s0 * s1 > 0) & (fall <= np.log1p(np.abs(h) / u) + 1e-9)


def _step(system, rows, q, jac, d0, d1, sign):
    """One continuation step of the knots from driver position d0 to d1.

    Returns (q, jac) at d1, or None at a toggle (Newton fails, the pose
    jumps away from the prediction, the equations become singular, the
    Jacobian's determinant no longer has the drawn pose's ``sign``: a singular
    pose was crossed, or it vanishes at the pose reached (:func:`_clear`), or the step is not
    smooth: it starts or ends on one), even with the step halved to RESOLUTION of the driver's unit.
    """
    h = d1 - d0
    qd = _tangent(system, rows, q, jac)
    guess = q + h * qd
    qn, ok, jn = _newton(system, rows, guess, np.array([d1]))
    if ok[0] and _drift(system, qn - guess)[0] <= _drift_bound(system, np.array([h]), qd)[0] \
            and _cond(system, rows, jn)[0] <= 1e10 and _orientation(jn)[0] == sign \
            and _clear(system, h, jac, jn)[0] \
            and _smooth(system, qn - q, h * qd, h * _tangent(system, rows, qn, jn))[0]:
        return qn, jn
    if abs(h) < RESOLUTION * _driver_unit(system):     # 1e-6 rad, or 1e-6 of a slider's size
        return None
    mid = _step(system, rows, q, jac, d0, d0 + h / 2, sign)   # near a toggle: halve the step
    return None if mid is None else _step(system, rows, mid[0], mid[1], d0 + h / 2, d1, sign)


_TANGENT: tuple = (None, None)   # the last Jacobian given to _tangent (the array itself) and its tangent


def _tangent(system, rows, q, jac) -> np.ndarray:
    """:func:`_velocity` of one pose's Jacobian ``jac``, which alone it depends on: the last one's kept.
    A step's tangent at the pose it reaches (its smoothness check) is the next step's tangent at its
    start, and a halved step starts with the tangent of the step it halves; each was solved twice.
    The Jacobian is known by the array itself (kept here, so its id is not another's): continuation
    never writes into a Jacobian once it is made (Knots keeps them)."""
    global _TANGENT
    last, qd = _TANGENT
    if last is not jac:
        qd = _velocity(system, rows, q, jac)
        _TANGENT = (jac, qd)
    return qd
