"""Every labelled arrow of a polygon is the quantity its label and its legend name.

``assert_arrows_true(solution)`` checks, for the velocity polygon and (where the solution has
accelerations) the acceleration polygon of any :class:`velpoly.solution.Solution`:

* every arrow's ``head - tail`` equals the quantity its ``of`` names, computed here from the
  analytic solve alone (positions, omegas, alphas, body velocities and accelerations), to 1e-9
  of the largest value of the polygon: absolute V_P (A_P) from the origin; a rigid link's
  V_WQ = V_W - V_Q; normal A^n_WQ = -omega^2 R_WQ (towards Q); tangential A^t_WQ = alpha x R_WQ;
  Coriolis 2 omega_guide x V_rel in its true sense (V_rel of the block, pin or centre of
  curvature relative to the guide's point under it); the slip V_rel, or at acceleration level
  A_rel - Coriolis - V_rel^2/rho (towards the centre of a circular path), which lies along the path;
  the normal V_rel^2/rho of a circular relative path; a rolling contact's A_Pa - A_Pb;
* the label reads as that quantity (``A^n_BA`` for a normal component of B about A,
  ``2 omega_4 x V_...`` for a Coriolis term of guide 4, no leading minus sign), and the kind
  (the legend's entry) is the kind of that quantity;
* within each step the component arrows run tip to tail: every end of an arrow that is not an
  image (or the origin) is the head of exactly one arrow and the tail of exactly one other;
  absolute arrows run from the origin to their image.
"""
from __future__ import annotations

import numpy as np

from velpoly.motion import point_keys
from velpoly.names import place, relative
from velpoly.polygons import acceleration_polygon, velocity_polygon

REL = 1e-9

# the quantities each legend entry (vector kind) may show
KINDS = {
    "absolute": {"point"},
    "relative": {"difference", "slip", "sum"},
    "normal": {"normal", "path-normal"},
    "tangential": {"tangential"},
    "coriolis": {"coriolis"},
    "slip": {"slip"},
}


def _perp(v):
    return np.array([-v[1], v[0]])


class _Truth:
    """The analytic motion of every key a polygon's arrows name (point keys and auxiliary keys)."""

    def __init__(self, sol, polygon):
        self.sol, self.poly = sol, polygon
        self.m = sol.mechanism
        self.frame = self.m.frame.name
        self.vel = polygon.kind == "velocity"
        self.keys = {key: (p, lk) for key, p, lk in point_keys(self.m)}

    def split(self, key):
        """(point name, link) of a key: "P@3" -> ("P", "3"); a plain key by its first carrier."""
        if key in self.keys:
            return self.keys[key]
        n, lk = key.rsplit("@", 1)
        return n, lk

    def position(self, key):
        if key in self.sol.position:
            return np.asarray(self.sol.position[key], float)
        aux = self.poly.auxiliary.get(key)
        if aux is not None:
            return np.asarray(aux.position, float)
        n, lk = self.split(key)
        for k, (p, _) in self.keys.items():
            if p == n:
                return np.asarray(self.sol.position[k], float)
        raise AssertionError(f"no position for {key}")

    def name(self, key):
        """The textbook name the labels use (velpoly.names): B, P₃ (a contact point of link 3), A₄, S₃ (the
        auxiliary point of link 3: S₃@3), S₃₄ (link 4's point at S₃, e.g. a block on link 3); P(cam)."""
        if key in self.keys:
            p, lk = self.keys[key]
            return p if key == p else place(p, lk)
        n, lk = key.rsplit("@", 1)
        return n if n not in self.m.points and n.rstrip("'") == place("S", lk) else place(n, lk)

    def velocity(self, key):
        if key in self.sol.velocity:
            return np.asarray(self.sol.velocity[key], float)
        _, lk = self.split(key)
        return self.sol.body_velocity(lk, self.position(key))

    def acceleration(self, key):
        if key in self.sol.acceleration:
            return np.asarray(self.sol.acceleration[key], float)
        _, lk = self.split(key)
        return self.sol.body_acceleration(lk, self.position(key))

    def motion(self, key):
        return self.velocity(key) if self.vel else self.acceleration(key)

    def value(self, of):
        """The quantity ``of`` names, from the analytic solve alone."""
        what = of[0]
        if what == "point":
            return self.motion(of[1])
        if what == "difference":
            return self.motion(of[1]) - self.motion(of[2])
        if what in ("normal", "tangential"):
            _, lk, w, q = of
            r = self.position(w) - self.position(q)
            if what == "normal":
                assert not self.vel, "a normal component in a velocity polygon"
                return -self.sol.omega[lk] ** 2 * r
            return self.sol.alpha[lk] * _perp(r)
        if what == "coriolis":
            _, guide, a, b = of
            assert not self.vel, "a Coriolis component in a velocity polygon"
            return 2.0 * self.sol.omega[guide] * _perp(self.velocity(a) - self.velocity(b))
        if what == "path-normal":
            _, a, b, k = of
            v = self.velocity(a) - self.velocity(b)
            towards = self.position(k) - self.position(a)
            rho = float(np.hypot(*towards))
            return float(v @ v) / rho * towards / rho
        if what == "slip":
            _, a, b, guide, k = of
            if self.vel:
                return self.velocity(a) - self.velocity(b)
            rest = self.acceleration(a) - self.acceleration(b) - self.value(("coriolis", guide, a, b))
            if k is not None:
                rest = rest - self.value(("path-normal", a, b, k))
            return rest
        if what == "sum":
            return sum(sign * self.value(o) for sign, o in of[1])
        raise AssertionError(f"unknown quantity {of!r}")

    def label(self, of):
        """How the label of ``of`` must read (None: only checked in part)."""
        X = "V" if self.vel else "A"
        what = of[0]
        if what == "point":
            return f"{X}_{self.name(of[1])}"
        if what in ("normal", "tangential"):
            _, lk, w, q = of
            return f"{X}^{what[0]}_{self.name(w)}{self.name(q)}"
        return None   # the others: checked by the names they contain (_labels_ok)


def _labels_ok(truth, v):
    X = "V" if truth.vel else "A"
    assert not v.label.startswith("-"), f"arrow {v.label!r} is labelled as a negative: draw it in its true sense"
    assert v.of, f"arrow {v.label!r} does not say what it is"
    assert v.of[0] in KINDS[v.kind], f"arrow {v.label!r} of kind {v.kind} shows {v.of[0]}"
    want = truth.label(v.of)
    if want is not None:
        assert v.label == want, f"arrow labelled {v.label!r} shows {want}"
        return
    what = v.of[0]

    def rel(a, b):
        """The names a relative quantity of a's place to b's (both at point n) may be written with."""
        (n, la), (nb, lb) = truth.split(a), truth.split(b)
        links = {la} | set(truth.m.carriers.get(n, ()))
        return {relative(place(n, x), place(nb, lb)) for x in links}

    if what == "coriolis":
        assert v.label in {f"2 omega_{v.of[1]} x V_{r}" for r in rel(v.of[2], v.of[3])}, v.label
    elif what == "slip":
        assert v.label in {f"{X}_{r}" for r in rel(v.of[1], v.of[2])}, v.label
    elif what == "path-normal":
        assert v.label in {f"A^n_{r}" for r in rel(v.of[1], v.of[2])}, v.label
    elif what == "difference":
        a, b = truth.name(v.of[1]), truth.name(v.of[2])
        assert v.label in {f"{X}_{a}{b}"} | {f"{X}_{r}" for r in rel(v.of[1], v.of[2])}, (v.label, a, b)
    elif what == "sum":
        assert " + " in v.label or " - " in v.label, v.label


def _chains_ok(poly, step, tol):
    """Component arrows run tip to tail: each free end is one arrow's head and another's tail."""
    images = [np.zeros(2)] + [np.asarray(p, float) for p in poly.images.values()] + \
        [np.asarray(a.image, float) for a in poly.auxiliary.values()]
    images = np.array(images)
    ends = []   # [point, heads in, tails out]

    def vertex(p):
        for e in ends:
            if np.hypot(*(e[0] - p)) <= tol:
                return e
        e = [p, 0, 0]
        ends.append(e)
        return e

    for v in step.vectors:
        t, h = np.asarray(v.tail, float), np.asarray(v.head, float)
        if v.kind == "absolute":
            assert np.hypot(*t) <= tol, f"absolute {v.label} does not start at the origin"
            continue
        if np.hypot(*(h - t)) <= tol:
            continue   # a null component is not drawn
        vertex(t)[2] += 1
        vertex(h)[1] += 1
    for p, n_in, n_out in ends:
        if np.min(np.hypot(*(images - p).T)) <= tol:
            continue
        assert n_in == n_out >= 1, (   # one chain through it, or several alike (coincident points)
            f"step {step.index} ({step.equation}): the arrows at {p} are not tip to tail "
            f"({n_in} heads, {n_out} tails)")


def assert_arrows_true(sol, rel: float = REL):
    """Assert every arrow of both polygons of ``sol`` is what its label and legend say (see the module)."""
    polys = [velocity_polygon(sol)]
    if sol.has_accelerations:
        polys.append(acceleration_polygon(sol))
    counts = {}
    for poly in polys:
        truth = _Truth(sol, poly)
        values = [np.asarray(v, float) for v in poly.images.values()]
        vecs = [(v, truth.value(v.of) if v.of else None) for st in poly.steps for v in st.vectors]
        big = max([float(np.hypot(*x)) for x in values] + [float(np.hypot(*x)) for _, x in vecs if x is not None]
                  + [1e-300])
        tol = rel * big
        for st in poly.steps:
            for v in st.vectors:
                _labels_ok(truth, v)
                want = truth.value(v.of)
                got = np.asarray(v.head, float) - np.asarray(v.tail, float)
                assert np.hypot(*(got - want)) <= tol, (
                    f"{poly.kind} step {st.index}: arrow {v.label!r} ({v.kind}) is {got}, "
                    f"its label names {want}")
                if v.of[0] == "point":
                    key = v.of[1]
                    img = poly.images.get(key, poly.auxiliary[key].image if key in poly.auxiliary else None)
                    assert np.hypot(*(np.asarray(img, float) - np.asarray(v.head, float))) <= tol, v.label
                counts[v.kind] = counts.get(v.kind, 0) + 1
            _chains_ok(poly, st, tol)
    return counts
