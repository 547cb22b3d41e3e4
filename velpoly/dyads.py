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

from dataclasses import dataclass

import numpy as np

from .model import Mechanism

__all__ = ["DyadPlan", "dyad_plan", "assemble"]


@dataclass(frozen=True)
class DyadPlan:
    """The driver and the dyads, in order; each dyad names its links and points."""

    driver: tuple       # ("crank", link, pivot point) or ("slider", block, direction)
    steps: tuple        # ("RRR", u, v, P1, known1, P2, P3, known3, side) / ("RRP", u, v, P1, known1, P2, guide, dir, side)


def _pins_between(m: Mechanism):
    out = {}
    for p in m.pins:
        a, b = p.links
        out.setdefault(frozenset((a, b)), []).append(p.point)
    return out


def dyad_plan(m: Mechanism) -> DyadPlan | None:
    """The chain of dyads that assembles the mechanism from its driver, or None."""
    if m.contacts or m.slots:
        return None
    frame = m.frame.name
    pins = _pins_between(m)
    P = {k: np.array(v, float) for k, v in m.points.items()}
    drv = m.driver
    if drv.is_slider:
        sl = next(s for s in m.sliders if s.point == drv.slider)
        if sl.guide != frame or sl.centre is not None:
            return None
        driver = ("slider", sl.block, float(sl.angle))
        known = {frame, sl.block}
    else:
        piv = pins.get(frozenset((drv.link, frame)))
        if not piv:
            return None
        driver = ("crank", drv.link, piv[0])
        known = {frame, drv.link}
    sliders = {s.block: s for s in m.sliders}
    for s in m.sliders:
        if s.centre is not None:
            return None
    moving = [k.name for k in m.links if not k.frame]
    steps = []

    def pin_to_known(u, exclude):
        for k in sorted(known, key=lambda n: m.link_names.index(n)):
            for pt in pins.get(frozenset((u, k)), []):
                if pt != exclude:
                    return pt, k
        return None

    progress = True
    while progress and len(known) < len(m.links):
        progress = False
        unknown = [u for u in moving if u not in known]
        for u in unknown:
            for v in unknown:
                if u == v:
                    continue
                shared = pins.get(frozenset((u, v)), [])
                for p2 in shared:
                    a = pin_to_known(u, p2)
                    if a is None:
                        continue
                    p1, k1 = a
                    if v in sliders and sliders[v].guide in known and u not in sliders:
                        s = sliders[v]
                        d = np.array([np.cos(np.radians(s.angle)), np.sin(np.radians(s.angle))])
                        foot = P[p1] + np.dot(P[p2] - P[p1], d) * d
                        side = float(np.sign(np.dot(P[p2] - foot, d)) or 1.0)
                        steps.append(("RRP", u, v, p1, k1, p2, s.guide, d, side))
                        known.update((u, v))
                        progress = True
                        break
                    b = pin_to_known(v, p2)
                    if b is None or v in sliders or u in sliders:
                        continue
                    p3, k3 = b
                    e = P[p3] - P[p1]
                    f = P[p2] - P[p1]
                    cross = e[0] * f[1] - e[1] * f[0]
                    if np.hypot(*e) == 0:
                        continue
                    steps.append(("RRR", u, v, p1, k1, p2, p3, k3, float(np.sign(cross) or 1.0)))
                    known.update((u, v))
                    progress = True
                    break
                if progress:
                    break
            if progress:
                break
    if len(known) < len(m.links):
        return None
    # every joint must be one the plan used or one it satisfies by construction; check the
    # joint count: a pin not used by any step (a redundant loop) makes the plan unsafe
    used = {("pin", frozenset((drv.link, frame))) if not drv.is_slider else None}
    for st in steps:
        if st[0] == "RRR":
            _, u, v, p1, k1, p2, p3, k3, _ = st
            used |= {("pin", frozenset((u, k1))), ("pin", frozenset((u, v))), ("pin", frozenset((v, k3)))}
        else:
            _, u, v, p1, k1, p2, g, _, _ = st
            used |= {("pin", frozenset((u, k1))), ("pin", frozenset((u, v)))}
    for p in m.pins:
        if ("pin", frozenset(p.links)) not in used:
            return None
    return DyadPlan(driver, tuple(steps))


def _c(p) -> complex:
    """A point as a complex number x + iy (the walk below works in complex numbers:
    perp(v) = i v, a . b = Re(conj(a) b), a x b = Im(conj(a) b))."""
    return complex(p[0], p[1])


def assemble(m: Mechanism, index: dict, plan: DyadPlan, deltas) -> tuple[np.ndarray, int]:
    """Poses q (N, nq) at the driver positions ``deltas``, and how many are reachable.

    Positions are reachable up to (not including) the first one where a dyad
    does not close; q beyond it is NaN. A link's pose is its origin o and turn
    rot = e^(i theta); its point s (reference position) is at o + rot s.
    """
    deltas = np.asarray(deltas, float)
    n = len(deltas)
    P = {k: _c(v) for k, v in m.points.items()}
    one = np.ones(n, complex)
    poses = {m.frame.name: (np.zeros(n, complex), one)}
    kind, link, extra = plan.driver
    if kind == "crank":
        rot = np.exp(1j * deltas)
        poses[link] = (P[extra] - rot * P[extra], rot)
    else:
        poses[link] = (deltas * np.exp(1j * np.radians(extra)), one)

    def place(lk, s):
        o, rot = poses[lk]
        return o + rot * s

    def pose_from(a, s1, c2, s2):
        rot = (c2 - a) / (s2 - s1)
        rot /= np.abs(rot)
        return a - rot * s1, rot

    bad = np.zeros(n, bool)
    for st in plan.steps:
        if st[0] == "RRR":
            _, u, v, p1, k1, p2, p3, k3, side = st
            a, b = place(k1, P[p1]), place(k3, P[p3])
            r1, r2 = abs(P[p2] - P[p1]), abs(P[p2] - P[p3])
            d = b - a
            dist = np.abs(d)
            along = (r1 * r1 - r2 * r2 + dist * dist) / (2 * dist)
            h2 = r1 * r1 - along * along
            bad |= ~(h2 >= 0) | (dist == 0)
            e = d / dist
            c2 = a + (along + side * 1j * np.sqrt(np.maximum(h2, 0.0))) * e
            poses[u] = pose_from(a, P[p1], c2, P[p2])
            poses[v] = pose_from(b, P[p3], c2, P[p2])
        else:
            _, u, v, p1, k1, p2, g, dref, side = st
            a = place(k1, P[p1])
            og, rotg = poses[g]
            e = rotg * _c(dref)
            through = place(g, P[p2])
            r = abs(P[p2] - P[p1])
            foot = through + (np.conj(e) * (a - through)).real * e
            off = a - foot
            h2 = r * r - (off.real ** 2 + off.imag ** 2)
            bad |= ~(h2 >= 0)
            c2 = foot + side * np.sqrt(np.maximum(h2, 0.0)) * e
            poses[u] = pose_from(a, P[p1], c2, P[p2])
            poses[v] = (c2 - rotg * P[p2], rotg)   # the block translates on its guide: it turns with it
    reach = int(np.argmax(bad)) if bad.any() else n
    q = np.zeros((n, 3 * len(index)))
    for name, k in index.items():
        o, rot = poses[name]
        q[:, 3 * k], q[:, 3 * k + 1] = o.real, o.imag
        th = np.angle(rot)
        if name == link and kind == "crank":
            th = deltas                       # the driver's own angle, exactly
        q[:, 3 * k + 2] = th
    # angles continuous with the reference pose (0), not wrapped into (-pi, pi]
    th = q[:, 2::3]
    if n:
        jumps = np.abs(np.diff(th, axis=0, prepend=0.0)).max(axis=0) > np.pi
        if jumps.any():
            th[:, jumps] = np.unwrap(np.concatenate([np.zeros((1, int(jumps.sum()))), th[:, jumps]]), axis=0)[1:]
    q[reach:] = np.nan
    return q, reach


def rates(m: Mechanism, index: dict, plan: DyadPlan, q: np.ndarray, rate: float, accel: float):
    """Velocities and accelerations dyad by dyad, in closed form: (q', q'', sine).

    Each dyad is two vector equations of case 2a. For an RRR dyad with joint
    P2 between links on P1 and P3 (u = P2 - P1, v = P2 - P3)::

        u . V2 = u . V1,               v . V2 = v . V3
        u . A2 = u . A1 - |V2 - V1|^2, v . A2 = v . A3 - |V2 - V3|^2

    and omega_u = u x (V2 - V1) / |u|^2, alpha_u = u x (A2 - A1) / |u|^2. For an
    RRP dyad (block on a guide g, path e, n = k x e, G the guide's point at P2)
    the second equation is n . V2 = n . V_G and
    n . A2 = n . A_G + 2 omega_g e . (V2 - V_G) (Coriolis); the block turns with
    its guide. ``sine`` is the smallest |sin| of a dyad's two directions
    (the transmission angle): zero exactly at a dyad's toggle.
    """
    n = len(q)
    P = {k: _c(v) for k, v in m.points.items()}
    zero = np.zeros(n)
    frame = m.frame.name
    state = {frame: (np.zeros(n, complex), np.zeros(n, complex), zero, zero, np.zeros(n, complex))}
    pose = {frame: (np.zeros(n, complex), np.ones(n, complex))}
    for name, k in index.items():
        pose[name] = (q[:, 3 * k] + 1j * q[:, 3 * k + 1], np.exp(1j * q[:, 3 * k + 2]))

    def place(lk, s):
        o, rot = pose[lk]
        return o + rot * s

    def motion_at(lk, w):
        vo, ao, om, al, o = state[lk]
        r = w - o
        return vo + 1j * om * r, ao + (1j * al - om * om) * r

    def set_link(lk, w, v, a, om, al):
        o = pose[lk][0]
        r = w - o
        state[lk] = (v - 1j * om * r, a - (1j * al - om * om) * r, om, al, o)

    def solve2(r1, b1, r2, b2):   # x with Re(conj(r1) x) = b1, Re(conj(r2) x) = b2
        det = (np.conj(r1) * r2).imag
        return ((b1 * r2.imag - b2 * r1.imag) + 1j * (r1.real * b2 - r2.real * b1)) / det

    def dot(a, b):
        return (np.conj(a) * b).real

    def cross(a, b):
        return (np.conj(a) * b).imag

    kind, link, extra = plan.driver
    if kind == "crank":
        w = place(link, P[extra])
        zc = np.zeros(n, complex)
        set_link(link, w, zc, zc, np.full(n, float(rate)), np.full(n, float(accel)))
    else:
        e = np.exp(1j * np.radians(extra))
        state[link] = (np.full(n, rate * e), np.full(n, accel * e), zero, zero, pose[link][0])
    sine = np.ones(n)
    for st in plan.steps:
        if st[0] == "RRR":
            _, u_, v_, p1, k1, p2, p3, k3, _ = st
            a1, a3, x2 = place(k1, P[p1]), place(k3, P[p3]), place(u_, P[p2])
            V1, A1 = motion_at(k1, a1)
            V3, A3 = motion_at(k3, a3)
            u, v = x2 - a1, x2 - a3
            V2 = solve2(u, dot(u, V1), v, dot(v, V3))
            A2 = solve2(u, dot(u, A1) - np.abs(V2 - V1) ** 2, v, dot(v, A3) - np.abs(V2 - V3) ** 2)
            uu, vv = np.abs(u) ** 2, np.abs(v) ** 2
            sine = np.minimum(sine, np.abs(cross(u, v)) / np.sqrt(uu * vv))
            set_link(u_, x2, V2, A2, cross(u, V2 - V1) / uu, cross(u, A2 - A1) / uu)
            set_link(v_, x2, V2, A2, cross(v, V2 - V3) / vv, cross(v, A2 - A3) / vv)
        else:
            _, u_, v_, p1, k1, p2, g, dref, _ = st
            a1, x2 = place(k1, P[p1]), place(u_, P[p2])
            V1, A1 = motion_at(k1, a1)
            VG, AG = motion_at(g, x2)
            omg, alg = state[g][2], state[g][3]
            e = pose[g][1] * _c(dref)
            nn = 1j * e
            u = x2 - a1
            V2 = solve2(u, dot(u, V1), nn, dot(nn, VG))
            A2 = solve2(u, dot(u, A1) - np.abs(V2 - V1) ** 2, nn, dot(nn, AG) + 2 * omg * dot(e, V2 - VG))
            uu = np.abs(u) ** 2
            sine = np.minimum(sine, np.abs(dot(u, e)) / np.sqrt(uu))
            set_link(u_, x2, V2, A2, cross(u, V2 - V1) / uu, cross(u, A2 - A1) / uu)
            set_link(v_, x2, V2, A2, omg, alg)
    qd = np.zeros_like(q)
    qdd = np.zeros_like(q)
    for name, k in index.items():
        vo, ao, om, al, _ = state[name]
        qd[:, 3 * k], qd[:, 3 * k + 1], qd[:, 3 * k + 2] = vo.real, vo.imag, om
        qdd[:, 3 * k], qdd[:, 3 * k + 1], qdd[:, 3 * k + 2] = ao.real, ao.imag, al
    return qd, qdd, sine
