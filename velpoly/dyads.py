"""Closed-form assembly by dyads, vectorised over every driver position at once.

Most lecture mechanisms are assembled from the driver by a chain of dyads,
each a compass-and-ruler construction:

* **RRR** -- links u and v pinned together at P2, u pinned to a known body
  at P1, v at P3: P2 is an intersection of the circles (P1, |P1P2|) and
  (P3, |P3P2|), on the side of P1 -> P3 it was drawn on;
* **RRP** -- link u pinned to a known body at P1 and to a block v at P2, the
  block sliding on a known guide: P2 is an intersection of the circle
  (P1, |P1P2|) with the path's line through P2, on the side it was drawn on.

Evaluated over arrays of driver positions, a whole cycle is a few dozen
numpy operations. The side of each intersection is the one of the drawn
pose, which is the continuous branch as long as no dyad passes through a
toggle (its circles tangent): the first position where a dyad cannot close
ends the assembly there. Mechanisms that are not such a chain (contacts,
slots, inversions with the block on a moving guide, eight-bars) return no
plan and are assembled by continuation (:mod:`velpoly.pose`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .model import Mechanism
from .rigid import arg, dot, is_zero
from .motion import LinkMotion

__all__ = ["DyadPlan", "Walk", "closure", "dyad_plan", "draws_the_reference", "walk", "assemble", "coordinates", "rates"]


@dataclass(frozen=True)
class DyadPlan:
    """The driver and the dyads, in order; each dyad names its links and points."""

    driver: tuple       # ("crank", link, pivot point) or ("slider", block, direction)
    steps: tuple        # ("RRR", u, v, P1, known1, P2, P3, known3, side) / ("RRP", u, v, P1, known1, P2, guide, dir, side)
    margin: float = 0.0  # the drawn pose's smallest transmission sine times the shortest dyad arm / size


def _pins_between(m: Mechanism):
    out = {}
    for p in m.pins:
        a, b = p.links
        out.setdefault(frozenset((a, b)), []).append(p.point)
    return out


def dyad_plan(m: Mechanism) -> DyadPlan | None:
    """The chain of dyads that assembles the mechanism from its driver, or None.

    None when the mechanism has contacts or slots, a slider on a circular path, a driver that
    is not a crank pinned to the frame or a block on a straight frame guide, links no dyad
    reaches, a pin no dyad uses (a redundant loop), or a walk that does not draw the drawn pose.
    """
    if m.contacts or m.slots or any(s.centre is not None for s in m.sliders):
        return None
    pins = _pins_between(m)
    start = _plan_driver(m, pins)
    if start is None:
        return None
    driver, known = start
    P = {k: np.array(v, float) for k, v in m.points.items()}
    steps = []
    while len(known) < len(m.links):
        st = _next_dyad(m, pins, P, known)
        if st is None:
            return None
        steps.append(st)
        known.update((st[1], st[2]))
    if not _uses_every_pin(m, steps):
        return None
    plan = DyadPlan(driver, tuple(steps), _margin(m, steps, P))
    return plan if draws_the_reference(m, plan) else None


def _plan_driver(m: Mechanism, pins: dict):
    """``(driver, known links)``: a crank pinned to the frame ("crank", link, pivot), or a block
    on a straight frame guide ("slider", block, path angle); None for another driver."""
    frame, drv = m.frame.name, m.driver
    if drv.is_slider:
        sl = next(s for s in m.sliders if s.point == drv.slider)
        if sl.guide != frame or sl.centre is not None:
            return None
        return ("slider", sl.block, float(sl.angle)), {frame, sl.block}
    piv = pins.get(frozenset((drv.link, frame)))
    if not piv:
        return None
    return ("crank", drv.link, piv[0]), {frame, drv.link}


def _pin_to_known(m: Mechanism, pins: dict, known: set, u: str, exclude: str):
    """``(point, link)``: a pin of link u to a known link (in file order), other than ``exclude``."""
    for k in sorted(known, key=lambda n: m.link_names.index(n)):
        for pt in pins.get(frozenset((u, k)), []):
            if pt != exclude:
                return pt, k
    return None


def _next_dyad(m: Mechanism, pins: dict, P: dict, known: set):
    """The first dyad (in file order) of two unknown links u, v pinned together at P2 and to
    known links: ``("RRR", u, v, P1, k1, P2, P3, k3, side)`` (u pinned to k1 at P1, v to k3 at
    P3) or ``("RRP", u, v, P1, k1, P2, guide, d, side)`` (v a block on a known guide along d);
    ``side`` is the drawn pose's assembly. None when no dyad closes."""
    sliders = {s.block: s for s in m.sliders}
    unknown = [k.name for k in m.links if not k.frame and k.name not in known]
    for u in unknown:
        for v in unknown:
            if u == v:
                continue
            for p2 in pins.get(frozenset((u, v)), []):
                a = _pin_to_known(m, pins, known, u, p2)
                if a is None:
                    continue
                p1, k1 = a
                if v in sliders and sliders[v].guide in known and u not in sliders:
                    s = sliders[v]
                    d = np.array([np.cos(np.radians(s.angle)), np.sin(np.radians(s.angle))])
                    # P2 is on the path, on this side of the foot of P1
                    side = float(np.sign(np.dot(P[p2] - P[p1], d)) or 1.0)
                    return ("RRP", u, v, p1, k1, p2, s.guide, d, side)
                b = _pin_to_known(m, pins, known, v, p2)
                if b is None or v in sliders or u in sliders:
                    continue
                p3, k3 = b
                e = (P[p3] - P[p1]) / m.size       # in units of the size: no overflow
                f = (P[p2] - P[p1]) / m.size
                cross = e[0] * f[1] - e[1] * f[0]
                if np.hypot(*e) == 0:
                    continue
                return ("RRR", u, v, p1, k1, p2, p3, k3, float(np.sign(cross) or 1.0))
    return None


def _uses_every_pin(m: Mechanism, steps) -> bool:
    """Whether every pin is the crank's pivot or a joint some dyad closes (a pin no step uses,
    a redundant loop, makes the plan unsafe)."""
    drv, frame = m.driver, m.frame.name
    used = {("pin", frozenset((drv.link, frame))) if not drv.is_slider else None}
    for st in steps:
        if st[0] == "RRR":
            _, u, v, p1, k1, p2, p3, k3, _ = st
            used |= {("pin", frozenset((u, k1))), ("pin", frozenset((u, v))), ("pin", frozenset((v, k3)))}
        else:
            _, u, v, p1, k1, p2, g, _, _ = st
            used |= {("pin", frozenset((u, k1))), ("pin", frozenset((u, v)))}
    return all(("pin", frozenset(p.links)) in used for p in m.pins)


def draws_the_reference(m: Mechanism, plan: DyadPlan) -> bool:
    """Whether the plan's walk at the reference driver position puts every dyad's joint where
    it is drawn: the sides it takes are the drawn pose's.

    Both assemblies of a dyad satisfy the joint equations, so the equations cannot tell the
    branch; this can. From the drawn pose the walk stays on its branch as long as no dyad
    reaches a toggle (where the walk stops). The other branch's joint is 2 h |P1P3| away (h the
    dyad's height), so 1e-7 of the size tells them apart wherever they differ visibly.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        w = walk(m, plan, np.zeros(1))
    tol = 1e-7 * m.size
    for st in plan.steps:
        at = w.joints[(st[1], st[5])][0]
        if not abs(complex(at[0] if isinstance(at, np.ndarray) else at) - _c(m.points[st[5]])) <= tol:
            return False
    return True


def _margin(m: Mechanism, steps, P) -> float:
    """How far the drawn pose is from a singular one, for the dyads: the smallest of
    |sin| of a dyad's two directions (RRR: |u x v| / |u||v|; RRP: |u . e| / |u|)
    times the shortest arm over the mechanism's size. Far above 1e-3, the velocity
    equations of the drawn pose are regular (a dyad's 2 x 2 system is the only part
    that can lose rank)."""
    out = np.inf
    for st in steps:
        u = (P[st[5]] - P[st[3]]) / m.size     # in units of the size: no overflow
        lu = np.hypot(*u)
        if st[0] == "RRR":
            v = (P[st[5]] - P[st[6]]) / m.size
            lv = np.hypot(*v)
            sine = abs(u[0] * v[1] - u[1] * v[0]) / (lu * lv) if lu * lv > 0 else 0.0
            arm = min(lu, lv)
        else:
            sine = abs(np.dot(u, st[7])) / lu if lu > 0 else 0.0
            arm = lu
        out = min(out, sine * arm)
    return float(out) if steps else 1.0


def _c(p) -> complex:
    """A point as a complex number x + iy (the walk below works in complex numbers:
    perp(v) = i v, a . b = Re(conj(a) b), a x b = Im(conj(a) b))."""
    return complex(p[0], p[1])


def _dot(a, b):
    """a . b = Re(conj(a) b) (0 when b is a scalar zero)."""
    return 0.0 if is_zero(b) else dot(a, b)


def _re(ca, b):
    """Re(ca b): with ca = conj(a), a . b (0 when b is a scalar zero)."""
    return 0.0 if is_zero(b) else (ca * b).real


def _sub(a, b):
    return a if is_zero(b) else a - b


def _solver(det, r1, r2):
    """(K1, K2) with x = b1 K1 + b2 K2 the solution of Re(conj(r1) x) = b1,
    Re(conj(r2) x) = b2, det = Im(conj(r1) r2): K1 = -i r2 / det, K2 = i r1 / det."""
    k = 1.0 / det
    return (-1j * r2) * k, (1j * r1) * k


def _lin(b1, K1, b2, K2):
    """b1 K1 + b2 K2, skipping scalar zeros."""
    if is_zero(b2):
        return 0.0 if is_zero(b1) else b1 * K1
    return b2 * K2 if is_zero(b1) else b1 * K1 + b2 * K2


def _sq(z):
    """|z|^2."""
    return 0.0 if is_zero(z) else (z * z.conjugate()).real


@dataclass(frozen=True)
class Walk:
    """The dyad walk over N driver positions: every link's motion and the joints' points.

    ``links[name]`` is a :class:`velpoly.motion.LinkMotion`; ``joints[(link, point)]`` is
    ``(P, V, A)`` (complex, V and A None for positions only) of each point the walk placed;
    ``sine`` is the smallest |sin| of a dyad's two directions at each pose (the
    transmission angle, zero at a dyad's toggle); ``reach`` the number of positions,
    from the first, where every dyad closes. ``closure`` holds, per dyad, the square of its
    transmission sine as a smooth function of the pose, negative where the dyad cannot close
    (:func:`closure`), and ``closure_rate`` its rate of change (per second, with rates; else
    None): a dip of it to zero between two positions is a toggle or a change point on the way.
    """

    links: dict
    joints: dict
    sine: np.ndarray
    reach: int
    closure: tuple = ()
    closure_rate: tuple = ()


def walk(m: Mechanism, plan: DyadPlan, deltas, rate: float | None = None, accel: float = 0.0) -> Walk:
    """Positions (and, given the driver's rate and acceleration, velocities and
    accelerations) of every link, dyad by dyad, over all driver positions at once.

    Positions: an RRR dyad's joint P2 is an intersection of the circles (P1, r1) and
    (P3, r3): with d = P3 - P1, P2 = P1 + (s + i side h) d, s = (r1^2 - r3^2 + |d|^2) / (2 |d|^2),
    h = sqrt(r1^2 / |d|^2 - s^2). An RRP dyad's joint is on the guide's line through G:
    P2 = F + side sqrt(r^2 - |P1 - F|^2) e, F = G + ((P1 - G) . e) e.

    Rates: each dyad is two vector equations of case 2a. For an RRR dyad
    (u = P2 - P1, v = P2 - P3)::

        u . V2 = u . V1,               v . V2 = v . V3
        u . A2 = u . A1 - |V2 - V1|^2, v . A2 = v . A3 - |V2 - V3|^2

    and omega_u = u x (V2 - V1) / |u|^2, alpha_u = u x (A2 - A1) / |u|^2. For an
    RRP dyad (block on a guide g, path e, n = i e, G the guide's point at P2)
    the second equation is n . V2 = n . V_G and
    n . A2 = n . A_G + 2 omega_g e . (V2 - V_G) (Coriolis); the block turns with
    its guide.
    """
    deltas = np.asarray(deltas, float)
    n = len(deltas)
    rates = rate is not None
    # lengths far from 1 are walked in units of a power of two near the size (exact), so that
    # their squares neither overflow nor underflow
    exp = math.frexp(m.size)[1]
    unit = math.ldexp(1.0, exp) if abs(exp) > 200 else 1.0
    P = {k: _c(v) / unit for k, v in m.points.items()}
    links = _driver_motion(m, plan, P, deltas, rate, accel, unit)
    joints, bad, sine, mus, dmus = _walk_dyads(plan, links, P, n, rates)
    reach = n if bad is None or not bad.any() else int(np.argmax(bad))
    if unit != 1.0:   # back to the mechanism's lengths
        links = {k: LinkMotion(lk.s0 * unit, lk.p0 * unit, lk.rot, _times(lk.v0, unit), _times(lk.a0, unit),
                               lk.omega, lk.alpha) for k, lk in links.items()}
        joints = {k: tuple(_times(x, unit) for x in j) for k, j in joints.items()}
    return Walk(links, joints, np.ones(n) if sine is None else sine, reach, tuple(mus), tuple(dmus))


def _walk_dyads(plan: DyadPlan, links: dict, P: dict, n: int, rates: bool):
    """Every dyad of the plan in turn, on all n positions at once (adds its links to ``links``):
    ``(joints, bad, sine, mus, dmus)``: the joints' (P, V, A), where some dyad does not close,
    the smallest transmission sine (None without rates), each dyad's closure and its rate."""
    joints = {}

    def at(lk, p):
        hit = joints.get((lk, p))
        if hit is None:
            hit = joints[(lk, p)] = links[lk].point(P[p], rates)
        return hit

    bad = sine = None
    mus, dmus = [], []
    for st in plan.steps:
        _, u_, v_, p1, k1, p2 = st[:6]
        if st[0] == "RRR":
            p3, k3 = st[6:8]
            c2, V2, A2, h2, here = _rrr(links, u_, v_, at(k1, p1), at(k3, p3), P[p1], P[p2], P[p3], st[8], n,
                                        rates)
            joints[(v_, p3)] = joints[(k3, p3)]
        else:
            c2, V2, A2, h2, here = _rrp(links, u_, v_, at(k1, p1), links[st[6]], P[p1], P[p2], st[7], st[8], n,
                                        rates)
        joints[(u_, p1)] = joints[(k1, p1)]
        joints[(u_, p2)] = joints[(v_, p2)] = (c2, V2, A2)
        mu, dmu = closure(st, links, joints, P, n, rates)
        mus.append(mu)
        dmus.append(dmu)
        miss = ~(h2 >= 0)
        bad = miss if bad is None else bad | miss
        if rates:
            sine = here if sine is None else np.minimum(sine, here)
    return joints, bad, sine, mus, dmus


def _driver_motion(m: Mechanism, plan: DyadPlan, P: dict, deltas, rate, accel, unit: float) -> dict:
    """The frame's and the driver's :class:`LinkMotion` (lengths in ``unit``): a crank turned by
    deltas (radians) about its pivot at omega = rate, alpha = accel; a block moved by deltas
    along its path at speed ``rate`` and acceleration ``accel``."""
    links = {m.frame.name: LinkMotion(0j, 0j, 1.0, 0.0, 0.0, 0.0, 0.0)}
    kind, link, extra = plan.driver
    if kind == "crank":
        c = P[extra]
        links[link] = LinkMotion(c, c, np.exp(1j * deltas), 0.0, 0.0, float(rate or 0.0), float(accel))
    else:
        e = complex(np.exp(1j * np.radians(extra))) / unit
        links[link] = LinkMotion(0j, deltas * e, 1.0, (rate or 0.0) * e, accel * e, 0.0, 0.0)
    return links


def closure(st, links, joints, P, n, rates):
    """How near one dyad of a walk is to a toggle: mu = sin^2 of its transmission angle, written
    as a polynomial in the pose that stays smooth through the toggle and turns negative past it,
    and its rate (None without rates).

    RRR (d = P3 - P1, D2 = |d|^2): the circles (P1, r1), (P3, r3) meet where
    mu = (r1^2 D2 - ((r1^2 - r3^2 + D2) / 2)^2) / (r1^2 r3^2) >= 0 (zero when tangent, or when
    P1 and P3 coincide: a kite's change point); mu' = (r1^2 - (r1^2 - r3^2 + D2) / 2) D2' / (r1^2 r3^2),
    D2' = 2 d . (V3 - V1). RRP (path e on the guide g, sigma = e x (P1 - P2) the distance of P1
    from the path): mu = 1 - sigma^2 / r1^2, sigma' = e x (V1 - V_g(P2)) + omega_g e . (P2 - P1),
    mu' = -2 sigma sigma' / r1^2."""
    _, u_, v_, p1, k1, p2 = st[:6]
    a, V1, _ = joints[(k1, p1)]
    r1 = abs(P[p2] - P[p1])
    if st[0] == "RRR":
        p3, k3 = st[6:8]
        b, V3, _ = joints[(k3, p3)]
        r3 = abs(P[p2] - P[p3])
        d = b - a
        D2 = (d * np.conjugate(d)).real
        k = 1.0 / (r1 * r1 * r3 * r3)
        half = 0.5 * (r1 * r1 - r3 * r3 + D2)
        mu = (r1 * r1 * D2 - half * half) * k
        dmu = None
        if rates:
            dmu = (r1 * r1 - half) * (2.0 * _dot(d, _sub(V3, V1))) * k
    else:
        G = links[st[6]]
        e = G.rot * _c(st[7])
        c2 = joints[(u_, p2)][0]
        u = c2 - a
        sigma = -(np.conjugate(e) * u).imag
        mu = 1.0 - sigma * sigma / (r1 * r1)
        dmu = None
        if rates:
            VG = G.velocity(c2 - G.p0)
            ds = (np.conjugate(e) * _sub(V1, VG)).imag if not (is_zero(V1) and is_zero(VG)) else 0.0
            if not is_zero(G.omega):
                ds = ds + G.omega * _dot(e, u)
            dmu = -2.0 * sigma * ds / (r1 * r1)
    mu = np.broadcast_to(np.asarray(mu, float), (n,))
    if dmu is not None:
        dmu = np.broadcast_to(np.asarray(dmu, float), (n,))
    return mu, dmu


def _times(x, unit):
    return None if x is None else x * unit


def _rrr(links, u_, v_, j1, j3, s1, s2, s3, side, n, rates):
    """One RRR dyad: P2 (and V2, A2) from P1 on u's known neighbour and P3 on v's; sets the
    motions of u and v. Returns (P2, V2, A2, h2, sine): h2 < 0 where the circles miss."""
    (a, V1, A1), (b, V3, A3) = j1, j3
    r1, r3 = abs(s2 - s1), abs(s2 - s3)
    d = b - a
    if not isinstance(d, np.ndarray):
        d = np.full(n, d)
    inv = 1.0 / (d * d.conjugate()).real
    s = (r1 * r1 - r3 * r3) * 0.5 * inv + 0.5
    h2 = r1 * r1 * inv - s * s
    c2 = a + (s + (1j * side) * np.sqrt(np.maximum(h2, 0.0))) * d
    u, v = c2 - a, c2 - b
    links[u_] = LinkMotion(s2, c2, u * (1.0 / (s2 - s1)))
    links[v_] = LinkMotion(s2, c2, v * (1.0 / (s2 - s3)))
    if not rates:
        return c2, None, None, h2, None
    cu, cv = u.conjugate(), v.conjugate()
    det = (cu * v).imag
    K1, K3 = _solver(det, u, v)
    V2 = _lin(_re(cu, V1), K1, _re(cv, V3), K3)
    W1, W3 = _sub(V2, V1), _sub(V2, V3)
    A2 = _lin(_sub(_re(cu, A1), _sq(W1)), K1, _sub(_re(cv, A3), _sq(W3)), K3)
    links[u_] = links[u_].moving(V2, A2, (cu * W1).imag * (1.0 / (r1 * r1)),
                                 (cu * _sub(A2, A1)).imag * (1.0 / (r1 * r1)))
    links[v_] = links[v_].moving(V2, A2, (cv * W3).imag * (1.0 / (r3 * r3)),
                                 (cv * _sub(A2, A3)).imag * (1.0 / (r3 * r3)))
    return c2, V2, A2, h2, np.abs(det) * (1.0 / (r1 * r3))


def _rrp(links, u_, v_, j1, G, s1, s2, dref, side, n, rates):
    """One RRP dyad: the block v's joint P2 on its guide G's line, from P1 on u's known
    neighbour; sets the motions of u and v. Returns (P2, V2, A2, h2, sine)."""
    a, V1, A1 = j1
    e = G.rot * _c(dref)
    through = G.place(s2)
    r1 = abs(s2 - s1)
    foot = through + _dot(e, a - through) * e
    off = a - foot
    h2 = r1 * r1 - (off * off.conjugate()).real
    if not isinstance(h2, np.ndarray):
        h2 = np.full(n, h2)
    c2 = foot + (side * np.sqrt(np.maximum(h2, 0.0))) * e
    u = c2 - a
    links[u_] = LinkMotion(s2, c2, u * (1.0 / (s2 - s1)))
    links[v_] = LinkMotion(s2, c2, G.rot)
    if not rates:
        return c2, None, None, h2, None
    VG, AG = G.motion(c2 - G.p0)
    nn = 1j * e
    cu = u.conjugate()
    K1, KG = _solver((cu * nn).imag, u, nn)
    V2 = _lin(_re(cu, V1), K1, _dot(nn, VG), KG)
    W1 = _sub(V2, V1)
    cor = 0.0 if is_zero(G.omega) else 2 * G.omega * _dot(e, _sub(V2, VG))
    A2 = _lin(_sub(_re(cu, A1), _sq(W1)), K1, _dot(nn, AG) + cor, KG)
    links[u_] = links[u_].moving(V2, A2, (cu * W1).imag * (1.0 / (r1 * r1)),
                                 (cu * _sub(A2, A1)).imag * (1.0 / (r1 * r1)))
    links[v_] = links[v_].moving(V2, A2, G.omega, G.alpha)
    return c2, V2, A2, h2, np.abs(_dot(u, e)) * (1.0 / r1)


def assemble(m: Mechanism, index: dict, plan: DyadPlan, deltas) -> tuple[np.ndarray, int]:
    """Poses q (N, nq) at the driver positions ``deltas``, and how many are reachable.

    Positions are reachable up to (not including) the first one where a dyad
    does not close; q beyond it is NaN.
    """
    w = walk(m, plan, deltas)
    q = coordinates(w, index, plan, deltas)
    q[w.reach:] = np.nan
    return q, w.reach


def coordinates(w: Walk, index: dict, plan: DyadPlan, deltas, out=None) -> np.ndarray:
    """The links' coordinates q (N, nq) of a walk: the place of each link's point whose
    reference position is the origin, O = p0 - rot s0, and its turn theta = arg(rot),
    continuous from the reference pose (the crank's: the driver positions themselves).
    ``out``: an (N, nq) array to fill."""
    deltas = np.asarray(deltas, float)
    n = len(deltas)
    q = np.empty((n, 3 * len(index))) if out is None else out
    kind, drv, _ = plan.driver
    for name, k in index.items():
        lk = w.links[name]
        q[:, 3 * k:3 * k + 2].view(complex)[:, 0] = lk.place(0j)
        if name == drv and kind == "crank":
            q[:, 3 * k + 2] = deltas                  # the driver's own angle, exactly
        elif isinstance(lk.rot, np.ndarray):
            th = arg(lk.rot)
            # continuous with the reference pose (0), not wrapped into (-pi, pi]
            if n > 1 and np.abs(np.diff(th)).max() > np.pi:
                th = np.unwrap(np.concatenate([[0.0], th]))[1:]
            q[:, 3 * k + 2] = th
        else:
            q[:, 3 * k + 2] = 0.0
    return q


def rates(w: Walk, index: dict, n: int, out=None) -> tuple[np.ndarray, np.ndarray]:
    """The links' coordinate rates q' and q'' (N, nq) from a walk with velocities: the
    place of each link's reference origin O moves at V_O = v0 + i omega (O - p0),
    A_O = a0 + (i alpha - omega^2)(O - p0). ``out``: two (N, nq) arrays to fill."""
    qd, qdd = (np.empty((n, 3 * len(index))), np.empty((n, 3 * len(index)))) if out is None else out
    for name, k in index.items():
        lk = w.links[name]
        qd[:, 3 * k:3 * k + 2].view(complex)[:, 0], qdd[:, 3 * k:3 * k + 2].view(complex)[:, 0] = \
            lk.motion(lk.arm(0j))
        qd[:, 3 * k + 2], qdd[:, 3 * k + 2] = lk.omega, lk.alpha
    return qd, qdd
