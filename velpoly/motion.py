"""What the solved coordinates mean: every point's, link's and joint's motion.

Given the poses q, velocities q' and accelerations q'' (leading axis over
poses), a link k with origin x_k moves each of its points P as::

    V_P = V_O + omega_k x R_PO,    A_P = A_O + alpha_k x R_PO - omega_k^2 R_PO

Point keys follow FORMAT.md section 5: ``P`` where every link carrying P
moves it alike (pinned together), else ``P@link`` for each carrier; a
coincident carrier (a slider's guide, a slot's link, a contact's links)
is evaluated at the point's current place. Relative motion along a path
(sliders, slots): ``V_rel = V_P(block) - V_P(guide)``,
``A_rel = A_P(block) - A_P(guide) - 2 omega_guide x V_rel``.
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, replace

import numpy as np

from .constraints import Frame, as_poses, contact_frame, contact_slip_equation
from .model import Mechanism
from .rigid import arg, coriolis, direction, dot, is_zero, perp, point_acceleration, point_velocity, rate_cross
from .rigid import relative_acceleration, unit, xy

__all__ = ["Motion", "LinkMotion", "point_keys", "evaluate_motion", "wrap_deg", "wrap_deg_float"]


def wrap_deg(a):
    """Angles in degrees wrapped into (-180, 180]."""
    a = np.asarray(a, float)
    w = np.mod(a + 180.0, 360.0) - 180.0
    return np.where(w == -180.0, 180.0, w)


def wrap_deg_float(a: float) -> float:
    """:func:`wrap_deg` of one float (the same operations, on floats)."""
    w = (a + 180.0) % 360.0 - 180.0
    return 180.0 if w == -180.0 else w


@dataclass(frozen=True)
class LinkMotion:
    """One link's motion over N poses, in complex numbers x + iy.

    The link's point with reference position ``s0`` is at ``p0``, with velocity
    ``v0`` and acceleration ``a0``; the link has turned by ``rot`` = e^(i theta)
    (its modulus 1 up to rounding) and turns at ``omega``, ``alpha``. Any point s
    of the link, at the arm r = rot (s - s0) from p0::

        P = p0 + r,    V = v0 + i omega r,    A = a0 + (i alpha - omega^2) r

    A value equal at every pose may be a scalar (the frame: p0 = s0 = 0, rot = 1,
    the rest 0). v0, a0, omega, alpha are None when only positions are known.
    """

    s0: complex
    p0: object
    rot: object
    v0: object = None
    a0: object = None
    omega: object = None
    alpha: object = None

    def arm(self, s: complex):
        """rot (s - s0): from p0 to the link's point with reference position s."""
        return 0.0 if s == self.s0 else self.rot * (s - self.s0)

    def place(self, s: complex):
        """Where the link's point with reference position s is."""
        return self.p0 if s == self.s0 else self.p0 + self.rot * (s - self.s0)

    def velocity(self, r):
        """V of the link's point at the arm r from p0."""
        om = self.omega
        return self.v0 if is_zero(r) or is_zero(om) else _plus(self.v0, rate_cross(om, r))

    def acceleration(self, r):
        """A of the link's point at the arm r from p0."""
        om, al = self.omega, self.alpha
        if is_zero(r) or (is_zero(om) and is_zero(al)):
            return self.a0
        return _plus(self.a0, relative_acceleration(al, om, r))

    def motion(self, r):
        """(V, A) of the link's point at the arm r from p0."""
        return self.velocity(r), self.acceleration(r)

    def point(self, s: complex, rates: bool = True):
        """(P, V, A) of the link's point with reference position s (V, A None without rates)."""
        r = self.arm(s)
        p = _plus(self.p0, r)
        return (p, *self.motion(r)) if rates else (p, None, None)

    def moving(self, v0, a0, omega, alpha) -> "LinkMotion":
        """The same positions with these rates."""
        return replace(self, v0=v0, a0=a0, omega=omega, alpha=alpha)


def _plus(a, b):
    """a + b, skipping a scalar zero."""
    return a if is_zero(b) else b if is_zero(a) else a + b


def _turn_deg(rot, base: float, n: int) -> np.ndarray:
    """arg(rot) + base in degrees, wrapped into (-180, 180] like :func:`wrap_deg`."""
    if not isinstance(rot, np.ndarray):
        a = (base + math.degrees(math.atan2(rot.imag, rot.real)) + 180.0) % 360.0 - 180.0
        return np.full(n, 180.0 if a == -180.0 else a)
    a = arg(rot * complex(math.cos(math.radians(base)), math.sin(math.radians(base))) if base else rot)
    a *= 180.0 / math.pi
    a[a == -180.0] = 180.0
    return a


_KEYS: dict = {}


def point_keys(m: Mechanism) -> list[tuple[str, str, str]]:
    """Every point key with its point and carrying link: ``(key, point, link)``.

    Cached per mechanism (mechanisms are immutable); the list returned is a copy.
    """
    hit = _KEYS.get(id(m))
    if hit is None or hit[0] is not m:
        if len(_KEYS) > 64:
            _KEYS.clear()
        hit = _KEYS[id(m)] = (m, _point_keys(m))
    return list(hit[1])


def _point_keys(m: Mechanism) -> list[tuple[str, str, str]]:
    contact_pts = {c.point for c in m.contacts}
    # a circular path's centre listed in no link is its guide's (slot link's), keyed K@guide (FORMAT.md section 5)
    unlisted = {j.centre for j in (*m.sliders, *m.slots) if j.centre is not None} - {
        p for lk in m.links for p in lk.points}
    out, frame = [], m.frame.name
    for p in m.point_order:
        carriers = list(m.carriers[p])
        parent = {lk: lk for lk in carriers}

        def find(x):
            while parent[x] != x:
                x = parent[x]
            return x
        for pin in m.pins:
            if pin.point == p and all(lk in parent for lk in pin.links):
                parent[find(pin.links[0])] = find(pin.links[1])
        groups = {find(lk) for lk in carriers}
        if len(groups) == 1 and p not in contact_pts and p not in unlisted:   # the frame's point is at rest exactly
            out.append((p, p, frame if frame in carriers else carriers[0]))
        else:
            out.extend((f"{p}@{lk}", p, lk) for lk in carriers)
    return out


@dataclass(frozen=True)
class Motion:
    """Arrays of one or many poses: ``position[key]`` is (N, 2), ``omega[link]`` is (N,)."""

    angle: dict
    omega: dict
    alpha: dict
    position: dict
    velocity: dict
    acceleration: dict
    sliders: list
    contacts: list
    slots: list


class _Bodies:
    def __init__(self, m, index, q, qd, qdd):
        self.m, self.index, self.q, self.qd, self.qdd = m, index, q, qd, qdd
        self.n = len(q)

    def theta(self, lk, arr=None):
        arr = self.q if arr is None else arr
        k = self.index.get(lk)
        return np.zeros(self.n) if k is None or arr is None else arr[:, 3 * k + 2]

    def origin(self, lk, arr=None):
        arr = self.q if arr is None else arr
        k = self.index.get(lk)
        return np.zeros((self.n, 2)) if k is None or arr is None else arr[:, 3 * k:3 * k + 2]

    def place(self, lk, s):
        """r_k(s): world position of the link's point with reference position s."""
        th = self.theta(lk)
        c, sn = np.cos(th), np.sin(th)
        return self.origin(lk) + np.stack([c * s[0] - sn * s[1], sn * s[0] + c * s[1]], axis=-1)

    def turn(self, lk, d):
        th = self.theta(lk)
        c, sn = np.cos(th), np.sin(th)
        return np.stack([c * d[0] - sn * d[1], sn * d[0] + c * d[1]], axis=-1)

    def vel(self, lk, w):
        return point_velocity(self.origin(lk, self.qd), self.theta(lk, self.qd), w - self.origin(lk))

    def acc(self, lk, w):
        r = w - self.origin(lk)
        if self.qdd is None:
            return np.full_like(r, np.nan)
        return point_acceleration(self.origin(lk, self.qdd), self.theta(lk, self.qdd), self.theta(lk, self.qd), r)


class _WalkBodies(_Bodies):
    """The same queries answered from the dyad walk's link motions (no cos/sin of q)."""

    def __init__(self, walk, m, index, q, qd, qdd):
        super().__init__(m, index, q, qd, qdd)
        self.links = walk.links

    def place(self, lk, s):
        return xy(self.links[lk].place(complex(s[0], s[1])), self.n)

    def turn(self, lk, d):
        return xy(self.links[lk].rot * complex(d[0], d[1]), self.n)

    def _arm(self, lk, w):
        lm = self.links[lk]
        return lm, (w[:, 0] + 1j * w[:, 1]) - lm.p0

    def vel(self, lk, w):
        lm, r = self._arm(lk, w)
        return xy(lm.velocity(r), self.n)

    def acc(self, lk, w):
        if self.qdd is None:
            return np.full_like(w, np.nan)
        lm, r = self._arm(lk, w)
        return xy(lm.acceleration(r), self.n)


def evaluate_motion(m: Mechanism, index: dict, q, qd, qdd=None, walk=None) -> Motion:
    """Every output of FORMAT.md section 2, as arrays over the poses q.

    ``walk``: the :class:`velpoly.dyads.Walk` that solved these poses (with
    velocities and accelerations); the body points and the links' angles and
    rates are then taken from it instead of being rebuilt from q, q', q''.
    """
    q, qd = as_poses(q), as_poses(qd)
    qdd = None if qdd is None else as_poses(qdd)
    if walk is None and len(q) == 1 and not m.contacts:
        return _evaluate_one(m, index, q, qd, qdd)
    B = _Bodies(m, index, q, qd, qdd) if walk is None else _WalkBodies(walk, m, index, q, qd, qdd)
    P = {k: np.array(v, float) for k, v in m.points.items()}
    contact_place = {c.point: _contact_place(m, c, B, P) for c in m.contacts}
    position, velocity, acceleration = _points(m, B, index, P, walk, contact_place)
    angle, omega, alpha = _link_angles(m, B, P, walk)
    sliders = [_relative(B, s.block, s.guide, B.place(s.block, P[s.point]), _path_dir(B, s, P), q, qd, qdd)
               for s in m.sliders]
    slots = [_relative(B, s.link, s.slot, B.place(s.link, P[s.pin]),
                       _path_dir(B, s, P, block=s.link, guide=s.slot, point=s.pin), q, qd, qdd)
             for s in m.slots]
    contacts = [_contact_slip(m, c, B, index, *contact_place[c.point]) for c in m.contacts]
    return Motion(angle, omega, alpha, position, velocity, acceleration, sliders, contacts, slots)


def _contact_place(m: Mechanism, c, B, P) -> tuple:
    """Where contact c touches now, with the common normal u and tangent t = perp(u):
    ``(place, u, t)``. With centres of curvature A, B (the equivalent linkage), u runs from
    A to B and the place is A + l_a u (or B + l_b u); without them, the contact point rides on
    the first link and the normal turns with nothing (it is given)."""
    a, b = c.links
    u0, t0, la, lb = contact_frame(m, c, P)
    if c.centres is None:
        place = B.place(a, P[c.point])
        u = np.broadcast_to(u0, place.shape)
    else:
        ca, cb = c.centres
        if ca is not None and cb is not None:
            A, Bc = B.place(a, P[ca]), B.place(b, P[cb])
            u = unit(Bc - A)
            place = A + la * u
        elif cb is None:
            u = B.turn(b, u0)
            place = B.place(a, P[ca]) + la * u
        else:
            u = B.turn(a, u0)
            place = B.place(b, P[cb]) + lb * u
    return place, u, perp(u)


def _points(m: Mechanism, B, index: dict, P: dict, walk, contact_place: dict) -> tuple[dict, dict, dict]:
    """(position, velocity, acceleration) of every point key, in point_keys order: body points
    all at once (from the walk, or one vectorised pass); coincident points (a contact's, a
    slider's point on its guide, a slot's pin on the slot link) at their current place,
    ``V = V_O + omega x r`` and ``A = A_O + alpha x r - omega^2 r`` of the carrying link."""
    coincident_place = {}
    for s in m.sliders:
        coincident_place[(s.point, s.guide)] = B.place(s.block, P[s.point])
    for s in m.slots:
        coincident_place[(s.pin, s.slot)] = B.place(s.link, P[s.pin])
    position, velocity, acceleration = {}, {}, {}
    keys = point_keys(m)
    body = [(key, p, lk) for key, p, lk in keys if p not in contact_place and (p, lk) not in coincident_place]
    if body and walk is not None:
        _walk_points(walk, body, P, B.n, position, velocity, acceleration)
    elif body:   # every body point at once: r = x_k + R(theta_k) s, V = V_O + omega x r', A = ...
        _body_points(B, index, body, P, position, velocity, acceleration)
    for key, p, lk in keys:
        if key in position:
            continue
        w = contact_place[p][0] if p in contact_place else coincident_place[(p, lk)]
        position[key] = w
        velocity[key] = B.vel(lk, w)
        acceleration[key] = B.acc(lk, w)
    return ({key: position[key] for key, _, _ in keys}, {key: velocity[key] for key, _, _ in keys},
            {key: acceleration[key] for key, _, _ in keys})


def _link_angles(m: Mechanism, B, P: dict, walk) -> tuple[dict, dict, dict]:
    """(angle, omega, alpha) of every link: the angle (degrees, wrapped) of its first two
    points' line, a block's path direction, else its turn from the reference pose."""
    q, qd, qdd = B.q, B.qd, B.qdd
    angle, omega, alpha = {}, {}, {}
    block_path = {s.block: s for s in m.sliders}
    for link in m.links:
        omega[link.name] = B.theta(link.name, qd)
        alpha[link.name] = B.theta(link.name, qdd) if qdd is not None else np.full(len(q), np.nan)
        if walk is not None:
            angle[link.name] = _turn_deg(walk.links[link.name].rot, _base_deg(link, block_path, P), B.n)
            continue
        th = B.theta(link.name)
        if len(link.points) >= 2:
            d = P[link.points[1]] - P[link.points[0]]
            base = np.degrees(np.arctan2(d[1], d[0])) if np.hypot(*d) > 0 else 0.0
            angle[link.name] = wrap_deg(base + np.degrees(th))
        elif link.name in block_path:
            s = block_path[link.name]
            angle[link.name] = wrap_deg(np.degrees(np.arctan2(*_path_dir(B, s, P)[..., ::-1].T)))
        else:
            angle[link.name] = wrap_deg(np.degrees(th))
    return angle, omega, alpha


def _contact_slip(m: Mechanism, c, B, index: dict, w, u, t) -> dict:
    """A contact's slip velocity ``(V_Pa - V_Pb) . t`` along the common tangent t at its place w,
    its slip acceleration (from the contact's slip equation; NaN without one or without q''),
    the normal's direction (degrees) and the place."""
    a, b = c.links
    q, qd, qdd = B.q, B.qd, B.qdd
    slip_v = dot(B.vel(a, w) - B.vel(b, w), t)
    eq = contact_slip_equation(m, c)
    if eq is None or qdd is None:
        slip_a = np.full(len(q), np.nan)
    else:
        jet = eq.fn(Frame(_FakeSystem(index), q, qd))
        slip_a = np.einsum("ij,ij->i", jet.g, qdd) + jet.h
    return {"slip_velocity": slip_v, "slip_acceleration": slip_a,
            "normal": np.degrees(np.arctan2(u[:, 1], u[:, 0])), "place": w}


def _base_deg(link, block_path, P) -> float:
    """The link's angle in the reference pose (degrees): its first two points' direction,
    a block's path direction, else 0."""
    if len(link.points) >= 2:
        d = P[link.points[1]] - P[link.points[0]]
        return math.degrees(math.atan2(d[1], d[0])) if d[0] or d[1] else 0.0
    if link.name in block_path and block_path[link.name].centre is None:
        return float(block_path[link.name].angle)
    return 0.0


def _walk_points(walk, body, P, n, position, velocity, acceleration):
    """Body points from the dyad walk: the joints it placed as they are, any other point
    of a link from the link's motion (P = p0 + r, V = v0 + i omega r, A = a0 + (i alpha - omega^2) r)."""
    for key, p, lk in body:
        hit = walk.joints.get((lk, p))
        if hit is None:
            hit = walk.links[lk].point(complex(*P[p]))
        position[key], velocity[key], acceleration[key] = (xy(z, n) for z in hit)


def _body_points(B, index, body, P, position, velocity, acceleration):
    """Positions, velocities and accelerations of many body points in one vectorised pass.

    Per link (rows; the frame last, at rest): r = x + R(theta) s,
    V = V_O + omega x R s, A = A_O + alpha x R s - omega^2 R s.
    """
    n = B.n
    nl = len(index)

    def rows(a):   # (nl + 1, N) per coordinate: the links' x, y, theta (and the frame's zeros)
        if a is None:
            return None
        t = np.zeros((3, nl + 1, n))
        if nl:
            t[:, :nl] = a.reshape(n, nl, 3).transpose(2, 1, 0)
        return t
    q, qd, qdd = rows(B.q), rows(B.qd), rows(B.qdd)
    c, sn = np.cos(q[2]), np.sin(q[2])
    k = np.array([index.get(lk, nl) for _, _, lk in body])
    s = np.array([P[p] for _, p, _ in body])
    ck, sk = c[k], sn[k]
    rx = ck * s[:, :1] - sk * s[:, 1:]
    ry = sk * s[:, :1] + ck * s[:, 1:]
    om = qd[2][k]
    px, py = q[0][k] + rx, q[1][k] + ry
    vx, vy = point_velocity((qd[0][k], qd[1][k]), om, (rx, ry))
    if qdd is None:
        ax = ay = np.full_like(px, np.nan)
    else:
        ax, ay = point_acceleration((qdd[0][k], qdd[1][k]), qdd[2][k], om, (rx, ry))
    out = np.empty((3, len(body), n, 2))
    out[0, ..., 0], out[0, ..., 1] = px, py
    out[1, ..., 0], out[1, ..., 1] = vx, vy
    out[2, ..., 0], out[2, ..., 1] = ax, ay
    for i, (key, _, _) in enumerate(body):
        position[key], velocity[key], acceleration[key] = out[0, i], out[1, i], out[2, i]


class _FakeSystem:
    def __init__(self, index):
        self.index = index


def _path_dir(B, s, P, block=None, guide=None, point=None):
    """The path's unit direction at the block's point, now (ccw about K for a circle)."""
    block = block or s.block
    guide = guide or s.guide
    point = point or s.point
    if s.centre is None:
        return B.turn(guide, direction(s.angle))
    r = B.place(block, P[point]) - B.place(guide, P[s.centre])
    return perp(unit(r))


def _relative(B, block, guide, w, d, q, qd, qdd):
    v_rel = B.vel(block, w) - B.vel(guide, w)
    slip_v = dot(v_rel, d)
    cor = coriolis(B.theta(guide, qd), v_rel)
    if qdd is None:
        slip_a = np.full(len(q), np.nan)
    else:
        a_rel = B.acc(block, w) - B.acc(guide, w) - cor
        slip_a = dot(a_rel, d)
    return {"slip_velocity": slip_v, "slip_acceleration": slip_a, "coriolis": cor,
            "direction": np.degrees(np.arctan2(d[:, 1], d[:, 0]))}


class _Link1:
    """One link's motion at one pose in plain floats: origin (x, y), turn (c, s) = (cos, sin)
    theta, origin velocity (vx, vy), omega, origin acceleration (ax, ay), alpha (NaN without
    q''). The frame is all zeros with c = 1."""

    __slots__ = ("x", "y", "c", "s", "vx", "vy", "om", "ax", "ay", "al")

    def __init__(self, k, q, qd, qdd):
        if k is None:
            self.x = self.y = self.s = self.vx = self.vy = self.om = 0.0
            self.c = 1.0
            self.ax = self.ay = self.al = math.nan if qdd is None else 0.0   # unknown without q''
            return
        i = 3 * k
        self.x, self.y, th = q[i:i + 3]
        self.c, self.s = math.cos(th), math.sin(th)
        self.vx, self.vy, self.om = qd[i:i + 3]
        self.ax, self.ay, self.al = (math.nan,) * 3 if qdd is None else qdd[i:i + 3]

    def turn(self, dx, dy):
        """R(theta) d."""
        return self.c * dx - self.s * dy, self.s * dx + self.c * dy

    def place(self, sx, sy):
        """r = x + R(theta) s: where the link's point with reference position s is."""
        rx, ry = self.turn(sx, sy)
        return self.x + rx, self.y + ry

    def vel(self, wx, wy):
        """V = V_O + omega x r of the link's point now at w, r = w - x."""
        return point_velocity((self.vx, self.vy), self.om, (wx - self.x, wy - self.y))

    def acc(self, wx, wy):
        """A = A_O + alpha x r - omega^2 r of the link's point now at w, r = w - x."""
        return point_acceleration((self.ax, self.ay), self.al, self.om, (wx - self.x, wy - self.y))


def _evaluate_one(m: Mechanism, index: dict, q, qd, qdd) -> Motion:
    """:func:`evaluate_motion` at one pose without contacts, in plain floats.

    The same equations, operation for operation: a body point P = x + R(theta) s,
    V_P = V_O + omega x (P - x), A_P = A_O + alpha x (P - x) - omega^2 (P - x); along a
    path with unit direction d, V_rel = V_P(block) - V_P(guide), slip V_rel . d, Coriolis
    2 omega_guide x V_rel, A_rel = A_P(block) - A_P(guide) - Coriolis, slip A_rel . d.
    Arrays are built only for the returned Motion: one block per kind, whose views are the
    values (shape (1, 2) per point, (1,) per link value).
    """
    q0, qd0 = q[0].tolist(), qd[0].tolist()
    qdd0 = None if qdd is None else qdd[0].tolist()
    P = m.points
    L = {lk.name: _Link1(index.get(lk.name), q0, qd0, qdd0) for lk in m.links}

    # a slider's point on its guide, a slot's pin on the slot link: where the block (pin link) has it
    coincident = {(s.point, s.guide): s.block for s in m.sliders}
    coincident.update({(s.pin, s.slot): s.link for s in m.slots})
    keys = point_keys(m)
    rows = []   # per key: x, y, Vx, Vy, Ax, Ay, one after another
    for _, p, lk in keys:
        b = L[lk]
        wx, wy = L[coincident.get((p, lk), lk)].place(*P[p])
        rows += (wx, wy, *b.vel(wx, wy), *b.acc(wx, wy))
    pva = np.fromiter(rows, float, len(rows)).reshape(len(keys), 3, 1, 2).transpose(1, 0, 2, 3)
    names = [key for key, _, _ in keys]
    position, velocity, acceleration = (dict(zip(names, block)) for block in pva)   # (1, 2) views

    angle, omega, alpha = _link_angles1(m, index, L, q0)
    sliders = [_relative1(L, P, s, s.block, s.guide, s.point, qdd is not None) for s in m.sliders]
    slots = [_relative1(L, P, s, s.link, s.slot, s.pin, qdd is not None) for s in m.slots]
    return Motion(angle, omega, alpha, position, velocity, acceleration, sliders, [], slots)


def _path_dir1(L: dict, P: dict, s, block: str, guide: str, point: str) -> tuple[float, float]:
    """:func:`_path_dir` at one pose in plain floats: the path's unit direction now (ccw about
    K for a circle)."""
    if s.centre is None:
        t = math.radians(s.angle)
        return L[guide].turn(math.cos(t), math.sin(t))
    bx, by = L[block].place(*P[point])
    kx, ky = L[guide].place(*P[s.centre])
    rx, ry = bx - kx, by - ky
    n = math.sqrt(rx * rx + ry * ry)
    return -(ry / n), rx / n


_BASES: dict = {}   # id(mechanism) -> (weak reference, {link: its reference angle or None})


def _reference_angles(m: Mechanism) -> dict:
    """Each link's angle in the reference pose, degrees, from its first point to its second (None for a
    link of fewer points): the same floats :func:`_link_angles1` computed at every pose, made once."""
    hit = _BASES.get(id(m))
    if hit is not None and hit[0]() is m:
        return hit[1]
    P, out = m.points, {}
    for link in m.links:
        if len(link.points) >= 2:
            (x0, y0), (x1, y1) = P[link.points[0]], P[link.points[1]]
            dx, dy = float(x1) - float(x0), float(y1) - float(y0)
            out[link.name] = math.degrees(math.atan2(dy, dx)) if math.hypot(dx, dy) > 0 else 0.0
        else:
            out[link.name] = None
    _BASES[id(m)] = (weakref.ref(m), out)
    weakref.finalize(m, _BASES.pop, id(m), None)
    return out


def _link_angles1(m: Mechanism, index: dict, L: dict, q0: list) -> tuple[dict, dict, dict]:
    """:func:`_link_angles` at one pose in plain floats: (angle, omega, alpha), each value a
    (1,) view of one block."""
    P = m.points
    rows = []   # per link: angle, omega, alpha, one after another
    block_path = {s.block: s for s in m.sliders}
    bases = _reference_angles(m)
    for link in m.links:
        b, name = L[link.name], link.name
        k = index.get(name)
        th = 0.0 if k is None else q0[3 * k + 2]
        base = bases[name]
        if base is not None:
            a = wrap_deg_float(base + math.degrees(th))
        elif name in block_path:
            s = block_path[name]
            dx, dy = _path_dir1(L, P, s, s.block, s.guide, s.point)
            a = wrap_deg_float(math.degrees(math.atan2(dy, dx)))
        else:
            a = wrap_deg_float(math.degrees(th))
        rows += (a, b.om, b.al)
    links = np.fromiter(rows, float, len(rows)).reshape(-1, 3).T.reshape(3, -1, 1)
    names = [lk.name for lk in m.links]
    angle, omega, alpha = (dict(zip(names, t)) for t in links)   # (1,) views
    return angle, omega, alpha


def _relative1(L: dict, P: dict, s, block: str, guide: str, point: str, rates2: bool) -> dict:
    """:func:`_relative` at one pose in plain floats: V_rel = V_P(block) - V_P(guide), its slip
    V_rel . d, the Coriolis term 2 omega_guide x V_rel, and the slip acceleration
    (A_P(block) - A_P(guide) - Coriolis) . d (NaN without q'', ``rates2`` False)."""
    dx, dy = _path_dir1(L, P, s, block, guide, point)
    wx, wy = L[block].place(*P[point])
    (bvx, bvy), (gvx, gvy) = L[block].vel(wx, wy), L[guide].vel(wx, wy)
    rvx, rvy = bvx - gvx, bvy - gvy
    cx, cy = coriolis(L[guide].om, (rvx, rvy))
    if not rates2:
        slip_a = math.nan
    else:
        (bax, bay), (gax, gay) = L[block].acc(wx, wy), L[guide].acc(wx, wy)
        slip_a = (bax - gax - cx) * dx + (bay - gay - cy) * dy
    t = np.array((rvx * dx + rvy * dy, slip_a, cx, cy, math.degrees(math.atan2(dy, dx))))
    return {"slip_velocity": t[0:1], "slip_acceleration": t[1:2], "coriolis": t[2:4].reshape(1, 2),
            "direction": t[4:5]}
