"""Instant centres (poles): inspection, the Aronhold-Kennedy theorem, the instant-centre method.

n links have n(n-1)/2 poles. The pole P_ij of links i and j is the point
where their velocity fields agree, ``V_i(P_ij) = V_j(P_ij)``; seen as a
homogeneous point it is the difference of the links' twists,

    P_ij ~ (-(v_i - v_j)_y, (v_i - v_j)_x, omega_i - omega_j),

(v_k: the velocity of link k's body point at the origin), so a pole at
infinity (equal omegas, a relative translation) needs no special case.

How the poles are found, the way a textbook draws them (seed 000, sections
3.9 and 3.10, Examples 3.7 and 3.8):

1. **By inspection.** A pin is its own pole (``how='pin'``); a block on a
   straight path has its pole at infinity normal to the path (``'slider'``);
   a block on a circular path, at the path's centre K (``'circular path'``);
   rolling without slip, at the contact point (``'rolling'``). A sliding
   contact puts the pole on the common normal through the contact point, a
   pin in a slot on the slot's normal through the pin (through K for a
   circular slot): these are *constraint lines*, used like Kennedy lines.
2. **Aronhold-Kennedy.** P_ij, P_ik and P_jk are collinear. On the Kennedy
   circle (the links as points, known poles as solid chords), an unknown
   chord i-j that closes two triangles (i, j, k) and (i, j, l) with known
   sides is found by intersecting the lines P_ik-P_jk and P_il-P_jl (or one
   such line and a constraint line): ``P_ij = l x m`` in homogeneous
   coordinates, parallel lines meeting at infinity. Poles are found in
   rounds, each round using only poles known before it; among a pole's
   candidate lines the pair meeting at the largest angle is drawn (a line
   through two nearly coincident poles counts as poorly drawn; lines meeting
   at a sine under 1e-6 nearly coincide and fix nothing). The order
   of discovery, the two triangles (``via``) and the two lines (``lines``)
   are recorded (``how='kennedy'``; ``'normals'`` when two constraint lines
   meet).
3. **What Kennedy cannot finish** (some eight-bars, where no unknown chord
   closes two triangles of known ones; degenerate poses where the lines
   coincide) is finished from the velocity solution, one pole at a time --
   the unknown pole on the most known lines -- then Kennedy resumes
   (``how='velocity'``).

Two links moving alike at the instant (same omega and the same velocity
field: a block that momentarily does not slide) have an undefined pole
(``how='undefined'``, position and direction ``None``; FORMAT.md section 5).
"Alike" means zero to the velocity solution's precision, not small: the
relative twist is at most what the solve's componentwise error bound allows
it to be in error by (:func:`_alike_pairs`, from
:func:`velpoly.kinematics.velocity_error_bound`), so a link far down a chain
of stages, turning at 1e-13 of the crank's speed but known to a relative
1e-10, keeps its poles. A pin (a rolling contact) is still the pole of two
links moving alike: the joint itself makes their velocities agree at its
point (any point is then a pole of the two). A block's inspection pole is read
from the direction it slides in, which a block at rest on its guide (at a dead
centre) does not have: its pole is undefined. Every other link k sees two
links moving alike alike, ``P_jk = P_ik`` (``how='alike'``). A pole farther
than 1e9 mechanism sizes is at infinity, with its ``direction`` in [0, 180).

Up to 24 links the construction runs on plain floats, storing each line
drawn (:class:`_Kennedy`); beyond, on arrays without a line store, each
round's lines gathered at once (:class:`_KennedyArrays`: the same order,
lines and numbers wherever a pole has at most 12 lines; with more, its pair
is chosen in two sweeps among at most 32 of them).

The **instant-centre method** (:func:`instant_centre_velocities`) then gives
every omega from the driver's through the poles,

    omega_j = omega_i (P_ij - P_1i) / (P_ij - P_1j)   (signed, along their common line),

written homogeneously (twists t_k = lambda_k P_1k, t_j - t_i ~ P_ij) so
that translating links (P_1k at infinity) are handled exactly, and any
point's velocity from its link's frame pole, ``V_B = omega_k x (B - P_1k)``.

:func:`poles_section` is the JSON section ``poles`` (FORMAT.md section 2) that
:meth:`velpoly.Solution.to_dict` calls; the readable tables of ``velpoly solve``
are :func:`velpoly.report.poles_tables`. This module imports neither.
"""
from __future__ import annotations

import functools
import gc
import math
import weakref
from dataclasses import dataclass, field

import numpy as np

from .frozen import quick_init
from .geometry import from_polar, ideal, join
from .kinematics import velocity_error_bound
from .motion import point_keys
from .rigid import point_velocity

__all__ = ["Pole", "PoleLine", "PoleSet", "KennedyCircle", "Chord", "locate_poles", "kennedy_circle",
           "instant_centre_velocities", "pole_caption", "link_twists", "pole_key", "pole_label", "poles_section",
           "FAR"]

FAR = 1e9        # a pole farther than FAR mechanism sizes is at infinity (FORMAT.md section 5)
_POOR = 1e-2     # a pair of lines meeting at a smaller sine waits a round for better lines
_BLUNT = 1e-6    # lines meeting at a smaller sine do not fix a pole (they nearly coincide)
_CLOSE = 0.05    # a line through two poles closer than this (in mechanism sizes) is discounted
_DEGENERATE = 1e-12

_UNKNOWN, _KNOWN, _UNDEFINED = 0, 1, 2
_JOINT_POLES = ("pin", "rolling")   # inspection poles kept where the two links move alike


# -- the data contract (docs/internals.md) ------------------------------------------------------
@quick_init
@dataclass(frozen=True)
class PoleLine:
    """A line drawn to locate a pole.

    A Kennedy line joins two known poles (``through`` names their keys); a
    constraint line (a sliding contact's common normal, a slot's normal) is
    known by inspection (``through`` is empty). ``point`` is a finite point
    of the line and ``direction`` its unit direction, in frame coordinates;
    both are None for the line at infinity (through two poles at infinity). ``marks`` are the
    frame points that define a constraint line (the contact point; the pin, and a circular slot's
    centre): a figure draws the line through them (a Kennedy line through its two poles).
    """

    label: str
    through: tuple[str, ...]
    point: np.ndarray | None
    direction: np.ndarray | None
    marks: tuple = ()


@quick_init
@dataclass(frozen=True)
class Pole:
    """The instant centre P_ij of links ``links = (i, j)``, i before j in file order.

    ``position`` is None at infinity (then ``direction`` is in [0, 180)) and
    when undefined (both None). ``how``: 'pin', 'slider', 'circular path',
    'rolling' (inspection, ``order`` 0), 'undefined' (the links move alike,
    order 0), 'kennedy', 'normals', 'alike', 'velocity' (order 1, 2, ... of
    discovery). For 'kennedy' ``via`` holds the two triples (i, j, k) whose
    lines met (a constraint line appears as its label instead) and
    ``lines`` the two lines as pairs of pole keys (``("1-2", "1-4")``) or,
    for a constraint line, ``("normal", point)`` / ``("slot normal", pin)``;
    ``construction`` has the same lines with their geometry. ``sine`` is
    |sin| of the angle between the two lines (1 where none were drawn; an
    'alike' pole has its source's).
    ``homogeneous`` is the pole as a unit homogeneous point (x, y, w) in
    frame coordinates (w = 0 at infinity; None when undefined).
    """

    links: tuple[str, str]
    key: str
    position: np.ndarray | None
    direction: float | None
    how: str
    order: int = 0
    via: tuple = ()
    lines: tuple = ()
    construction: tuple[PoleLine, ...] = ()
    sine: float = 1.0
    homogeneous: np.ndarray | None = None
    note: str = ""

    @property
    def at_infinity(self) -> bool:
        return self.position is None and self.direction is not None

    @property
    def undefined(self) -> bool:
        return self.position is None and self.direction is None

    @property
    def by_inspection(self) -> bool:
        return self.order == 0 and self.how != "undefined"


@dataclass(frozen=True)
class PoleSet:
    """All n(n-1)/2 poles of a solution.

    ``links`` in file order (the points of the Kennedy circle); ``poles``
    maps every key "i-j" to its :class:`Pole`; ``order`` lists the keys of
    the poles found (not known by inspection) in order of discovery;
    ``constraint_lines`` maps a pair's key to its constraint lines;
    ``max_error`` is the largest disagreement of a pole with the velocity
    solution: |P_ij x (T_i - T_j)| (unit P_ij, coordinates scaled by the
    mechanism's size), relative to the largest twist -- the two links'
    relative velocity at the pole found, relative to the largest speed; for
    a pole near the mechanism and links not moving nearly alike, about its
    distance from the true pole in mechanism sizes. ``frame`` names the frame link,
    ``centre`` and ``scale`` the normalisation used for the homogeneous
    arithmetic.
    """

    links: tuple[str, ...]
    poles: dict
    frame: str = ""
    order: tuple[str, ...] = ()
    constraint_lines: dict = field(default_factory=dict)
    max_error: float = 0.0
    centre: np.ndarray = field(default_factory=lambda: np.zeros(2))
    scale: float = 1.0

    def pole(self, i: str, j: str) -> Pole:
        """The pole of links i and j, in either order."""
        return self.poles[pole_key(self.links, i, j)]

    def __len__(self) -> int:
        return len(self.poles)


@dataclass(frozen=True)
class Chord:
    """A chord of the Kennedy circle: the pole ``key`` between two links.

    ``solid`` when known by inspection (drawn solid from the start), else
    drawn dashed and made solid at step ``order``.
    """

    key: str
    links: tuple[str, str]
    solid: bool
    order: int


@dataclass(frozen=True)
class KennedyCircle:
    """The Kennedy circle: the links at equal spacing on a unit circle, the poles as chords.

    Link 1 (the first in file order) is at the top, the others follow
    clockwise, as textbooks draw it.
    """

    points: dict          # link -> np.ndarray (2,) on the unit circle
    chords: tuple[Chord, ...]


def pole_key(links, i: str, j: str) -> str:
    """The key "i-j" with i before j in file order."""
    a, b = links.index(i), links.index(j)
    return f"{i}-{j}" if a < b else f"{j}-{i}"


# -- twists ---------------------------------------------------------------------------------
def _normalisation(sol) -> tuple[np.ndarray, float]:
    """The centre of the points' bounding box (finite points) and the mechanism's size."""
    pts = [xy for v in sol.motion.position.values() for xy in v.tolist() if math.isfinite(xy[0]) and math.isfinite(xy[1])]
    if not pts:
        return np.zeros(2), float(sol.kinematics.system.size)
    xs, ys = [x for x, _ in pts], [y for _, y in pts]
    # the mechanism's size, as the system took it from the mechanism once
    return np.array((0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys)))), float(sol.kinematics.system.size)


def link_twists(sol, centre=None, scale=None) -> np.ndarray:
    """Every link's twist as a homogeneous point, rows in file order: (-v_y, v_x, omega).

    v is the velocity of the link's body point at ``centre`` divided by
    ``scale`` (coordinates x' = (x - centre) / scale): v = V_O + omega k x (centre - O).
    The pole of links i and j is the homogeneous point T_i - T_j: ``V_i = V_j`` where
    ``(v_i - v_j) + (omega_i - omega_j) k x x' = 0``. The frame's row is zero.
    """
    if centre is None or scale is None:
        centre, scale = _normalisation(sol)
    index = sol.kinematics.system.index
    c0, c1 = float(centre[0]), float(centre[1])
    q, qd = sol.q.tolist(), sol.qd.tolist()
    out = []
    for lk in sol.mechanism.links:
        k = index.get(lk.name)
        if k is None:
            out.append((0.0, 0.0, 0.0))
            continue
        out.append(_twist((qd[3 * k], qd[3 * k + 1]), qd[3 * k + 2], (q[3 * k], q[3 * k + 1]), (c0, c1), scale))
    return np.array(out).reshape(len(out), 3)


def _twist(v_o, omega, origin, centre, scale) -> tuple:
    """A link's twist (-v_y, v_x, omega), v = (V_O + omega k x (centre - O)) / scale the velocity of its body
    point at ``centre``: linear in (V_O, omega), so the same map takes the rows of the velocity solve's inverse
    (floats, or arrays over the equations: :func:`_twist_errors`)."""
    vx, vy = point_velocity(v_o, omega, (centre[0] - origin[0], centre[1] - origin[1]))
    return (-vy / scale, vx / scale, omega)


def _unit(h) -> np.ndarray:
    n = math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2])
    return h / n if n > 0 else h


def _to_local(h, centre, scale) -> np.ndarray:
    return _unit(np.array([h[0] - centre[0] * h[2], h[1] - centre[1] * h[2], scale * h[2]]))


def _local_point(x, centre, scale) -> tuple:
    """The frame point x as a unit homogeneous triple in normalised coordinates (floats)."""
    u, v = (float(x[0]) - float(centre[0])) / scale, (float(x[1]) - float(centre[1])) / scale
    n = math.sqrt(u * u + v * v + 1.0)
    return (u / n, v / n, 1.0 / n)


def _local_direction(deg) -> np.ndarray:
    """The point at infinity in direction ``deg`` (the same in every normalisation)."""
    return ideal(from_polar(1.0, deg))


# -- inspection ------------------------------------------------------------------------------
def _inspection(sol, centre, scale):
    """Poles known by inspection and the constraint lines, in normalised coordinates.

    Returns ``(points, lines)``: points is a list of ``(i, j, h, how, note, at)`` (``at``: the
    frame position of a finite pole, exactly (an array, or a tuple of floats), else None); lines a list of ``(i, j, h_line,
    label_pair, description, marks)`` (``marks``: the frame points that define the line: the
    contact point, the pin, a circular slot's centre).
    """
    m = sol.mechanism
    mo = sol.motion
    points, lines = [], []
    for pin in m.pins:
        i, j = pin.links
        at = sol.place_xy(i, pin.point)
        points.append((i, j, _local_point(at, centre, scale), "pin", f"pin {pin.point}", at))
    for s, r in zip(m.sliders, mo.sliders):
        if s.centre is None:
            d = float(r["direction"][0])
            points.append((s.block, s.guide, _local_direction(d + 90.0), "slider",
                           f"slider {s.point}: normal to its path", None))
        else:
            k = np.array(sol.place(s.guide, s.centre), float)
            points.append((s.block, s.guide, _local_point(k, centre, scale), "circular path",
                           f"centre {s.centre} of the path of {s.point}", k))
    for c, r in zip(m.contacts, mo.contacts):
        a, b = c.links
        place = np.asarray(r["place"][0], float)
        if c.kind == "rolling":
            points.append((a, b, _local_point(place, centre, scale), "rolling", f"rolling contact {c.point}",
                           place.copy()))
        else:
            p = _local_point(place, centre, scale)
            h = join(p, _local_direction(float(r["normal"][0])))
            lines.append((a, b, _unit(h), ("normal", c.point), f"common normal at {c.point}", (place.copy(),)))
    for s, r in zip(m.slots, mo.slots):
        pin = np.array(sol.place(s.link, s.pin), float)
        p = _local_point(pin, centre, scale)
        if s.centre is None:
            q = _local_direction(float(r["direction"][0]) + 90.0)
            desc, marks = f"normal to the slot at {s.pin}", (pin,)
        else:
            k = np.array(sol.place(s.slot, s.centre), float)
            q = _local_point(k, centre, scale)
            desc, marks = f"line {s.pin}{s.centre} (normal to the circular slot)", (pin, k)
        lines.append((s.link, s.slot, _unit(join(p, q)), ("slot normal", s.pin), desc, marks))
    return points, lines


# -- Kennedy -------------------------------------------------------------------------------------
# Joining two poles and meeting two lines are both cross products of homogeneous triples
# (velpoly.geometry's join and meet). One instant has a few dozen of them: the construction does
# them on plain float triples; _cross and _norm do them on arrays (the instant-centre method).
def _cross(a, b) -> np.ndarray:
    """a x b over the last axis (numpy's cross is slow on many small triples)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0), axis=-1)


def _norm(v) -> np.ndarray:
    return np.sqrt(np.einsum("...k,...k->...", v, v))


def _cross3(a, b) -> tuple:
    """a x b of two homogeneous triples of floats: the line through two points, the meet of two lines."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _norm3(v) -> float:
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


_SMALL = 24      # up to this many links the construction runs on plain floats (_Kennedy), beyond on arrays
_SAMPLE = 32     # a pole with more lines than this has its pair chosen among this many, evenly spread
_EXACT = 12      # a pole with at most this many lines drawn has every pair of them tried; more, two sweeps


def _seg_first_max(vals, seg, nseg) -> np.ndarray:
    """Per segment (``seg`` sorted, every segment non-empty), the index of its first largest value."""
    starts = np.flatnonzero(np.r_[True, seg[1:] != seg[:-1]])
    top = np.maximum.reduceat(vals, starts)
    hit = np.flatnonzero(vals == top[seg])
    first = np.full(nseg, -1)
    s, at = np.unique(seg[hit], return_index=True)
    first[s] = hit[at]
    return first


def _cross_rows(a, b):
    """a x b row by row, (k, 3) arrays, component by component (the same floats as :func:`_cross3`)."""
    a0, a1, a2 = a[:, 0], a[:, 1], a[:, 2]
    b0, b1, b2 = b[:, 0], b[:, 1], b[:, 2]
    return np.stack((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0), axis=1)


def _norm_rows(x) -> np.ndarray:
    return np.sqrt(x[:, 0] * x[:, 0] + x[:, 1] * x[:, 1] + x[:, 2] * x[:, 2])


def _twist_errors(sol, centre, scale):
    """What each link's twist (:func:`link_twists`) can be in error by, and the linear maps that give it.

    A link k's twist is T_k = M_k (v_x, v_y, omega) of its velocity coordinates (v at the body
    origin O_k; c the centre, s the scale)::

        T_k = (-(v_y + omega (c_x - O_x)) / s, (v_x - omega (c_y - O_y)) / s, omega),

    so with the solve's componentwise bound (:func:`velpoly.kinematics.velocity_error_bound`,
    ``(A^-1, g)``) W_k = M_k A^-1 (rows of link k) maps the equations' errors to the twist's:
    |T_k - T_k exact| <= |W_k| g. Returns ``(W, g, e)``: W of shape (links, 3, coordinates) (the
    frame's zero), and e_k = || |W_k| g ||, a link's error (all infinite where the solve gives no
    bound).
    """
    kin = sol.kinematics
    inv, g = velocity_error_bound(kin, sol.q, sol.qd)
    links = sol.mechanism.links
    w = np.zeros((len(links), 3, len(g)))
    c0, c1 = float(centre[0]), float(centre[1])
    for row, lk in enumerate(links):
        k = kin.system.index.get(lk.name)
        if k is None:
            continue
        w[row] = _twist((inv[3 * k], inv[3 * k + 1]), inv[3 * k + 2], (sol.q[3 * k], sol.q[3 * k + 1]), (c0, c1),
                        scale)
    if not np.isfinite(g).all():
        return w, g, np.full(len(links), np.inf)
    return w, g, _norm(np.abs(w) @ g)


def _alike_pairs(sol, twists, centre, scale) -> np.ndarray:
    """``alike[a, b]``: links a and b move alike, their relative twist zero to the velocity solution's
    precision (FORMAT.md section 5: then their pole is undefined).

    |T_a - T_b| <= || |W_a - W_b| g ||, what the difference of the two twists can be in error by
    (:func:`_twist_errors`): the bound of the difference itself, not the sum of the two links'
    bounds, since a block and its guide share their equations' errors. "Zero" is not "small": a
    link far down a chain of stages turning at 1e-13 of the crank's speed is known to a relative
    1e-10 or better and keeps its poles, while a block at its dead centre slides at most at its
    bound. The sum e_a + e_b screens the pairs first (the difference's bound is at most that).
    """
    t = np.asarray(twists, float)
    n = len(t)
    w, g, e = _twist_errors(sol, centre, scale)
    rel = _norm(t[:, None, :] - t[None, :, :])
    if not np.isfinite(e).all():
        alike = np.ones((n, n), bool)
    else:
        alike = rel <= e[:, None] + e[None, :]
        a_, b_ = np.nonzero(np.triu(alike, 1))
        if len(a_):
            bound = _norm(np.abs(w[a_] - w[b_]) @ g)
            alike[a_, b_] = alike[b_, a_] = rel[a_, b_] <= bound
    np.fill_diagonal(alike, False)
    return alike


@functools.lru_cache(maxsize=16)   # the same links at every pose of a mechanism
def _pair_keys(names: tuple) -> tuple:
    """``keys[a][b]``: the pole key "i-j" of links a and b (i the one first in file order)."""
    return tuple(tuple(f"{x}-{y}" if a < b else f"{y}-{x}" for b, y in enumerate(names)) for a, x in enumerate(names))


class _Construction:
    """What both forms of the construction share (docs/poles.md): the links, their twists, which
    move alike, the constraint lines and what the figures need of them.

    ``alike[a, b]``: the links move alike (their relative twist is zero to the velocity
    solution's precision); their pole is undefined unless known by inspection (a pin between
    them still is their pole), and every other link k sees them alike: P_ak = P_bk.
    """

    def __init__(self, names, twists, alike, pairs):
        self.names, self.n = names, len(names)
        self.keys = _pair_keys(tuple(names))
        self.twists = np.asarray(twists, float).reshape(self.n, 3)
        self.alike = alike               # alike[a][b]: the links move alike (a != b)
        self.info = {}
        self.constraints = {}            # (a, b) -> [(label pair, description)]
        self.cons = {}                   # (a, b) -> [unit line triple]
        self.marks = {}                  # (a, b, c) -> the points that define the pair's c-th constraint line
        self.exact = {}                  # (a, b) -> the frame position of a finite pole by inspection
        for a, b in pairs:
            self.info[(a, b)] = dict(how="undefined", order=0, note="the links move alike")

    def key(self, a, b) -> str:
        return self.keys[a][b]

    def set_many(self, items) -> None:
        """Set the poles ``(a, b, h, info)`` of one round."""
        for a, b, h, info in items:
            self.set(a, b, h, info)

    def add_constraint(self, a, b, h, label, desc, marks=()) -> None:
        a, b = min(a, b), max(a, b)
        self.constraints.setdefault((a, b), []).append((label, desc))
        self.cons.setdefault((a, b), []).append(tuple(map(float, h)))
        self.marks[(a, b, len(self.cons[(a, b)]) - 1)] = tuple(marks)

    def _alike(self, i, x, y) -> dict:
        """P_xy = P_iy: link x moves like link i."""
        pole = self.pole
        return dict(how="alike", h=tuple(map(float, pole[i][y])),
                    sine=self.info[(min(i, y), max(i, y))].get("sine", 1.0),
                    via=((self.names[i], self.names[x], self.names[y]),),
                    lines=((self.key(i, x), self.key(i, y)),),
                    note=f"{self.names[x]} moves like {self.names[i]}: P_{self.key(x, y)} = P_{self.key(i, y)}")


class _Kennedy(_Construction):
    """The construction on plain floats (a few dozen links at most), in normalised coordinates.

    ``pole[a][b]``: the pole P_ab as a unit homogeneous triple (floats); ``state[a][b]``:
    unknown, known or undefined; ``known[x]``: the set of links c with P_xc known, ``when[x][c]``
    the round it was known in (0: by inspection). ``lines[a, b]`` (a < b) holds the lines drawn for
    P_ab by slot: slot x < n is the line that triangle (a, b, x) of the Kennedy circle gives, drawn
    once P_xa and P_xb are both known, from the later of them (P_xb x P_xa when both came in one
    round); slot n + c is the pair's c-th constraint line; each with its drafting quality (a line
    through two nearly coincident poles, quality 0, is not kept). A pair's lines are drawn when
    its candidate is asked for (:meth:`candidates`). Memory O(n^3) at most: for big mechanisms
    :class:`_KennedyArrays` does the same without storing lines.
    """

    def __init__(self, names, twists, alike):
        array = np.asarray(twists, float)
        n = len(names)
        pairs = [(int(a), int(b)) for a, b in zip(*np.nonzero(np.triu(alike, 1)))]
        super().__init__(names, array, np.asarray(alike, bool).tolist(), pairs)
        self.pole = [[(0.0, 0.0, 0.0)] * n for _ in range(n)]
        self.state = [[_UNKNOWN] * n for _ in range(n)]
        self.known = [set() for _ in range(n)]
        self.when = [[0] * n for _ in range(n)]
        self.round = 0
        self.lines = {}     # (a, b) -> {slot: (unit line, quality > 0)}
        self.through = {}   # (a, b) -> the links x whose triangle's line is drawn for P_ab
        self.unknown = n * (n - 1) // 2 - len(pairs)  # pairs a < b still unknown
        self.any_alike = bool(pairs)
        self.best = {}   # (a, b) -> the pair's candidate from its lines drawn so far (None: none), until one is drawn
        for a in range(n):
            self.state[a][a] = _UNDEFINED
        for a, b in pairs:
            self.state[a][b] = self.state[b][a] = _UNDEFINED

    def set(self, a, b, h, info) -> None:
        if type(h) is not tuple:   # an array (a slider's pole at infinity, the velocity fallback)
            h = tuple(map(float, h))
        if a > b:
            a, b = b, a
        state = self.state
        self.pole[a][b] = self.pole[b][a] = h
        if state[a][b] != _KNOWN:
            if state[a][b] == _UNKNOWN:
                self.unknown -= 1
            state[a][b] = state[b][a] = _KNOWN
            self.known[a].add(b)
            self.known[b].add(a)
            self.when[a][b] = self.when[b][a] = self.round
        self.info[a, b] = info

    def add_constraint(self, a, b, h, label, desc, marks=()) -> None:
        super().add_constraint(a, b, h, label, desc, marks)
        a, b = min(a, b), max(a, b)
        self.best.pop((a, b), None)
        cons = self.cons[a, b]
        self.lines.setdefault((a, b), {})[self.n + len(cons) - 1] = (cons[-1], 1.0)

    def spread(self, new) -> None:
        """The round's poles are set: the next round's lines may pass through them."""
        self.round += 1

    def _draw(self, a, b, links) -> None:
        """The Kennedy lines of P_ab through P_xa and P_xb for each link x of ``links`` (triangle a, b, x of
        the Kennedy circle): the line l = P x P' from the pole known later, P, through the other, P'."""
        pole, when, sqrt = self.pole, self.when, math.sqrt
        drawn = self.lines.get((a, b))
        for x in links:
            px, wx = pole[x], when[x]
            if wx[b] >= wx[a]:
                (a0, a1, a2), (b0, b1, b2) = px[b], px[a]
            else:
                (a0, a1, a2), (b0, b1, b2) = px[a], px[b]
            l0, l1, l2 = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0   # _cross3, _norm3 written out
            sep = sqrt(l0 * l0 + l1 * l1 + l2 * l2)
            if not sep >= _DEGENERATE:   # through two coincident poles: quality 0, not kept
                continue
            q = sep / _CLOSE
            if not q < 1.0:    # min(1.0, q)
                q = 1.0
            if drawn is None:
                drawn = self.lines[a, b] = {}
            drawn[x] = ((l0 / sep, l1 / sep, l2 / sep), q)

    def candidates(self) -> list:
        """The unknown poles two lines locate now, in key order: (a, b, score, info).

        A pair's lines through poles known since it was last asked are drawn first. Of a pole's
        drawn lines, the pair with the best score, max(sine, |l x m|) times both lines' qualities,
        is taken (the first such pair in slot order); it stands until another line is drawn for
        the pole (``self.best``).
        """
        n, state, known, through, memo = self.n, self.state, self.known, self.through, self.best
        out = []
        for a in range(n):
            sa, ka = state[a], known[a]
            for b in range(a + 1, n):
                if sa[b] != _UNKNOWN:
                    continue
                common = ka & known[b]   # the links x with P_xa and P_xb known
                cand = memo.get((a, b), False)
                if common:
                    old = through.get((a, b), ())
                    if len(common) > len(old):
                        self._draw(a, b, common.difference(old))
                        through[a, b] = common
                        cand = False
                if cand is False:
                    cand = memo[a, b] = self._candidate(a, b)
                if cand is not None:
                    out.append(cand)
        if self.any_alike:   # some links move alike: copy their poles
            done = {(a, b) for a, b, _, _ in out}
            for a in range(n):
                for b in range(a + 1, n):
                    hit = self._alike_pair(a, b) if state[a][b] == _UNKNOWN else None
                    if hit is not None:
                        if (a, b) in done:
                            out = [o for o in out if (o[0], o[1]) != (a, b)]
                        out.append((a, b, 1.0, hit))
            out.sort(key=lambda o: (o[0], o[1]))
        return out

    def _candidate(self, a, b):
        """``(a, b, score, info)`` of the pole P_ab where the best pair of its lines drawn meets; None where
        fewer than two are drawn or the best two meet too bluntly to fix it."""
        best = self._best_lines(a, b)
        if best is None:
            return None
        score, i, j, li, lj, x, proj, sine = best
        if proj >= _DEGENERATE and score >= _BLUNT:
            return (a, b, score, {"how": None, "slots": (i, j), "sine": sine if sine < 1.0 else 1.0,
                                  "line_vectors": (li, lj), "h": (x[0] / proj, x[1] / proj, x[2] / proj)})
        return None

    def _best_lines(self, a, b):
        """Of the pair's lines drawn, the two with the best score: ``(score, slot i, slot j, line i, line j,
        their meet x, |x|, sine)``, None where fewer than two are drawn."""
        got = self.lines.get((a, b))
        if got is None or len(got) < 2:
            return None
        hypot, sqrt = math.hypot, math.sqrt
        lines = sorted(got.items())   # [(slot, (line, quality))] in slot order
        best, top = None, 0.0
        for u in range(len(lines) - 1):
            i, (li, qi) = lines[u]
            ni = hypot(li[0], li[1])
            a0, a1, a2 = li
            for v in range(u + 1, len(lines)):
                j, (lj, qj) = lines[v]
                b0, b1, b2 = lj   # x = li x lj, proj = |x| (_cross3, _norm3 written out)
                x0, x1, x2 = a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0
                proj = sqrt(x0 * x0 + x1 * x1 + x2 * x2)
                den = ni * hypot(b0, b1)
                sine = abs(x2) / den if den > 0 else 0.0
                score = (proj if proj > sine else sine) * qi * qj   # max(sine, proj)
                if best is None or score > top:
                    best, top = (score, i, j, li, lj, (x0, x1, x2), proj, sine), score
        return best

    def most_lines(self) -> tuple[int, int]:
        """The unknown pair with the most lines drawn (the first in key order)."""
        best = None
        for a in range(self.n):
            for b in range(a + 1, self.n):
                if self.state[a][b] == _UNKNOWN:
                    count = len(self.lines.get((a, b), ()))
                    if best is None or count > best[0]:
                        best = (count, a, b)
        return best[1], best[2]

    def world(self, centre, scale, error: bool = True, exact: bool = True):
        """The known poles in frame coordinates: the largest disagreement with the velocity solution,
        |P_ab x (T_a - T_b)| (0 without ``error``), and ``(a, b, (x, y, w) unit, position or None, at
        infinity)`` for each (a pole farther than FAR sizes is at infinity; the position never a signed
        zero; tuples of floats); without ``exact``, not the finite poles known by inspection (``self.exact``:
        their places are exact already)."""
        c0, c1 = float(centre[0]), float(centre[1])
        twists, state, pole, sqrt = self.twists.tolist(), self.state, self.pole, math.sqrt
        skip = () if exact else self.exact
        err, out = 0.0, []
        for a in range(self.n):
            for b in range(a + 1, self.n):
                if state[a][b] != _KNOWN or (a, b) in skip:
                    continue
                h = pole[a][b]
                if error:
                    ta, tb = twists[a], twists[b]
                    e = _norm3(_cross3(h, (ta[0] - tb[0], ta[1] - tb[1], ta[2] - tb[2])))
                    if e > err:
                        err = e
                x, y, w = scale * h[0] + c0 * h[2], scale * h[1] + c1 * h[2], h[2]
                nw = sqrt(x * x + y * y + w * w)   # max(_norm3(hw), 1e-300), written out
                if 1e-300 > nw:
                    nw = 1e-300
                x, y, w = hw = (x / nw, y / nw, w / nw)
                far = w == 0 or math.hypot(x, y) > FAR * scale * abs(w)
                out.append((a, b, hw, None if far else (x / w + 0.0, y / w + 0.0), far))   # tuples: the
        return err, out                                                                # PoleSet makes arrays

    def _alike_pair(self, a, b):
        """P_ab = P_ib when link a moves like link i, or P_ai when b moves like i (the first such i)."""
        state, alike = self.state, self.alike
        for x, y in ((a, b), (b, a)):
            for i in range(self.n):
                if alike[x][i] and state[i][y] == _KNOWN:
                    return self._alike(i, x, y)
        return None


class _KennedyArrays(_Construction):
    """The same construction for big mechanisms, on arrays (all in normalised coordinates).

    ``pole[a, b]``: the pole P_ab as a unit homogeneous triple; ``state[a, b]``: unknown, known or
    undefined. No line is stored: the line that triangle (a, b, c) of the Kennedy circle gives
    for P_ab is P_ca x P_cb, drawn once both are known (not drawn when they nearly coincide), and
    a pair's constraint lines are known from the start. Each round gathers every unknown pole's
    lines at once (the pairs with two lines or more found by one product of the known-matrix
    with itself), so a round costs O(n^2) plus its lines. With up to ``_EXACT`` lines a pole's
    best pair is chosen exactly as :class:`_Kennedy` does; with more, in two sweeps
    (:meth:`best_pairs`).
    """

    def __init__(self, names, twists, alike):
        twists = np.asarray(twists, float)
        n = len(names)
        alike = np.asarray(alike, bool)
        super().__init__(names, twists, alike, [(int(a), int(b)) for a, b in zip(*np.nonzero(np.triu(alike, 1)))])
        self.still = not twists.any()   # nothing moves: no pole but those by inspection is defined
        self.pole = np.zeros((n, n, 3))
        self.state = np.full((n, n), _UNKNOWN, np.int8)
        self.state[self.alike] = _UNDEFINED
        np.fill_diagonal(self.state, _UNDEFINED)

    @property
    def unknown(self) -> int:
        return int(np.count_nonzero(np.triu(self.state == _UNKNOWN, 1)))

    def spread(self, new) -> None:
        """Nothing to do: lines are gathered when needed."""

    def set_many(self, items) -> None:
        if not items:
            return
        A = np.array([it[0] for it in items])
        B = np.array([it[1] for it in items])
        h = np.array([tuple(map(float, it[2])) for it in items], float).reshape(-1, 3)
        self.pole[A, B] = self.pole[B, A] = h
        self.state[A, B] = self.state[B, A] = _KNOWN
        for a, b, _, info in items:   # a < b
            self.info[a, b] = info

    def set(self, a, b, h, info) -> None:
        self.pole[a, b] = self.pole[b, a] = h
        self.state[a, b] = self.state[b, a] = _KNOWN
        self.info[(min(a, b), max(a, b))] = info

    def world(self, centre, scale, error: bool = True, exact: bool = True):
        """As :meth:`_Kennedy.world`, on arrays (every known pole, ``exact`` or not)."""
        n, twists = self.n, self.twists
        A, B = np.nonzero(np.triu(self.state == _KNOWN, 1))
        h = self.pole[A, B]
        err = float(_norm_rows(_cross_rows(h, twists[A] - twists[B])).max()) if len(A) and error else 0.0
        hw = np.stack((scale * h[:, 0] + centre[0] * h[:, 2], scale * h[:, 1] + centre[1] * h[:, 2], h[:, 2]),
                      axis=1)
        hw /= np.maximum(_norm_rows(hw), 1e-300)[:, None]
        x, y, w = hw[:, 0], hw[:, 1], hw[:, 2]
        far = (w == 0) | (np.hypot(x, y) > FAR * scale * np.abs(w))
        with np.errstate(divide="ignore", invalid="ignore"):
            xy = np.stack((x / w + 0.0, y / w + 0.0), axis=1)    # + 0.0: never a signed zero
        return err, list(zip(A.tolist(), B.tolist(), hw, xy, far.tolist()))

    def lines(self, A, B, both=None, cap=None):
        """The lines drawn for the unknown pairs (A[p], B[p]): arrays (pair, slot, line, quality),
        sorted by pair and slot (slot: the third link, n + c for the pair's c-th constraint line).
        ``both``: the thirds whose poles with both links are known, (len(A), n), if at hand. With
        ``cap``, a pair with more thirds than that has only ``cap`` of them, evenly spread in file order."""
        if both is None:
            known = self.state == _KNOWN
            both = known[A] & known[B]
        if cap is not None:
            k = np.count_nonzero(both, axis=1)
            if (k > cap).any():
                many = np.flatnonzero(k > cap)
                sub = both[many]
                r = np.cumsum(sub, axis=1)
                kk = k[many][:, None]
                both = both.copy()
                both[many] = sub & ((r * cap) // kk != ((r - 1) * cap) // kk)
        p, c = np.nonzero(both)
        ln = _cross_rows(self.pole[c, A[p]], self.pole[c, B[p]])
        sep = _norm_rows(ln)
        keep = sep >= _DEGENERATE
        p, c, ln, sep = p[keep], c[keep], ln[keep], sep[keep]
        ln = ln / sep[:, None]
        q = np.minimum(1.0, sep / _CLOSE)
        if self.cons:
            where = {(int(a), int(b)): k for k, (a, b) in enumerate(zip(A, B)) if (int(a), int(b)) in self.cons}
            extra = [(k, self.n + i, h) for ab, k in where.items() for i, h in enumerate(self.cons[ab])]
            if extra:
                p = np.r_[p, [e[0] for e in extra]]
                c = np.r_[c, [e[1] for e in extra]]
                ln = np.r_[ln, np.array([e[2] for e in extra], float).reshape(-1, 3)]
                q = np.r_[q, np.ones(len(extra))]
                o = np.lexsort((c, p))
                p, c, ln, q = p[o], c[o], ln[o], q[o]
        return p, c, ln, q

    @staticmethod
    def _score(li, lj, ni, nj, qi, qj):
        """Two lines' meet x, |x|, the sine of their angle and the score max(sine, |x|) qi qj."""
        x = _cross_rows(li, lj)
        proj = _norm_rows(x)
        den = ni * nj
        with np.errstate(divide="ignore", invalid="ignore"):
            sine = np.where(den > 0, np.abs(x[:, 2]) / np.where(den > 0, den, 1.0), 0.0)
        return x, proj, sine, np.maximum(sine, proj) * qi * qj

    def best_pairs(self, A, B, both=None):
        """For each pair (A[p], B[p]) with two lines or more, the best pair of its lines.

        Returns (pairs, slot_i, slot_j, line_i, line_j, meet, |meet|, sine, score), one row per
        pair that has two lines. Up to ``_EXACT`` lines, every pair of lines is tried and the
        best score taken (the first in slot order); with more, two sweeps: the best-drawn line
        (the first of the largest quality), the line that meets it best, then the line that
        meets that one best, and the better of these two pairs.
        """
        p, c, ln, q = self.lines(A, B, both, _SAMPLE)
        nrm = np.hypot(ln[:, 0], ln[:, 1])
        cnt = np.bincount(p, minlength=len(A))
        start = np.r_[0, np.cumsum(cnt)[:-1]]
        rows = []      # (pair indices, i, j): line indices into p, c, ln
        for k in np.unique(cnt[(cnt >= 2) & (cnt <= _EXACT)]):
            ps = np.flatnonzero(cnt == k)
            tu, tv = np.triu_indices(int(k), 1)
            I = (start[ps][:, None] + tu[None, :]).ravel()
            J = (start[ps][:, None] + tv[None, :]).ravel()
            _, _, _, sc = self._score(ln[I], ln[J], nrm[I], nrm[J], q[I], q[J])
            at = np.argmax(sc.reshape(len(ps), -1), axis=1)
            rows.append((ps, I.reshape(len(ps), -1)[np.arange(len(ps)), at],
                         J.reshape(len(ps), -1)[np.arange(len(ps)), at]))
        big = np.flatnonzero(cnt > _EXACT)
        if len(big):
            sel = np.isin(p, big)
            idx = np.flatnonzero(sel)
            seg = np.searchsorted(big, p[idx])
            i0 = idx[_seg_first_max(q[idx], seg, len(big))]

            def partner(of):
                o = of[seg]
                _, _, _, sc = self._score(ln[idx], ln[o], nrm[idx], nrm[o], q[idx], q[o])
                sc = np.where(idx == o, -1.0, sc)
                return idx[_seg_first_max(sc, seg, len(big))]

            j0 = partner(i0)
            i1 = partner(j0)
            _, _, _, s0 = self._score(ln[i0], ln[j0], nrm[i0], nrm[j0], q[i0], q[j0])
            _, _, _, s1 = self._score(ln[j0], ln[i1], nrm[j0], nrm[i1], q[j0], q[i1])
            u, v = np.where(s1 > s0, j0, i0), np.where(s1 > s0, i1, j0)
            rows.append((big, np.minimum(u, v), np.maximum(u, v)))
        if not rows:
            e = np.zeros(0, int)
            return e, e, e, np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0), np.zeros(0), np.zeros(0)
        ps = np.concatenate([r[0] for r in rows])
        I = np.concatenate([r[1] for r in rows])
        J = np.concatenate([r[2] for r in rows])
        o = np.argsort(ps, kind="stable")
        ps, I, J = ps[o], I[o], J[o]
        x, proj, sine, sc = self._score(ln[I], ln[J], nrm[I], nrm[J], q[I], q[J])
        return ps, c[I], c[J], ln[I], ln[J], x, proj, sine, sc

    def candidates(self) -> list:
        """The unknown poles two lines locate now, in key order: (a, b, score, info)."""
        n, state = self.n, self.state
        A, B = np.nonzero(np.triu(state == _UNKNOWN, 1))
        if not len(A) or self.still:
            return []
        known = state == _KNOWN
        both = known[A] & known[B]          # the thirds that close a triangle of known poles
        count = np.count_nonzero(both, axis=1)
        for (a, b), ls in self.cons.items():
            if state[a, b] == _UNKNOWN:
                count[np.flatnonzero((A == a) & (B == b))] += len(ls)
        ev = np.flatnonzero(count >= 2)
        out = {}
        ps, si, sj, li, lj, x, proj, sine, sc = self.best_pairs(A[ev], B[ev], both[ev])
        ok = (proj >= _DEGENERATE) & (sc >= _BLUNT)
        h = x[ok] / proj[ok][:, None]
        at = ev[ps[ok]]
        for p, a, b, i, j, s, sn, hh, u, v in zip(at.tolist(), A[at].tolist(), B[at].tolist(), si[ok].tolist(),
                                                 sj[ok].tolist(), sc[ok].tolist(), np.minimum(1.0, sine[ok]).tolist(),
                                                 h.tolist(), li[ok].tolist(), lj[ok].tolist()):
            out[p] = (a, b, s, dict(how=None, slots=(i, j), sine=sn, line_vectors=(u, v), h=hh))
        if self.alike.any():   # some links move alike: copy their poles
            kn = state == _KNOWN
            for x_, y_, first in ((A, B, True), (B, A, False)):
                hit = self.alike[x_] & kn[:, y_].T
                has = np.flatnonzero(hit.any(axis=1))
                at = np.argmax(hit[has], axis=1)
                for p, i in zip(has.tolist(), at.tolist()):
                    if not first and p in out and out[p][3]["how"] == "alike":
                        continue
                    x, y = int(x_[p]), int(y_[p])
                    out[p] = (int(A[p]), int(B[p]), 1.0, self._alike(i, x, y))
        return [out[p] for p in sorted(out)]

    def most_lines(self) -> tuple[int, int]:
        """The unknown pair with the most lines drawn (the first in key order)."""
        A, B = np.nonzero(np.triu(self.state == _UNKNOWN, 1))
        p = self.lines(A, B)[0]
        k = int(np.argmax(np.bincount(p, minlength=len(A))))
        return int(A[k]), int(B[k])

    def _alike(self, i, x, y) -> dict:
        """P_xy = P_iy: link x moves like link i."""
        return dict(how="alike", h=tuple(map(float, self.pole[i, y])),
                    sine=self.info[(min(i, y), max(i, y))].get("sine", 1.0),
                    via=((self.names[i], self.names[x], self.names[y]),),
                    lines=((self.key(i, x), self.key(i, y)),),
                    note=f"{self.names[x]} moves like {self.names[i]}: P_{self.key(x, y)} = P_{self.key(i, y)}")


_CACHE: dict = {}   # id(solution) -> (weak reference, PoleSet): the JSON, tables and figures share one


def locate_poles(sol, *, cached: bool = True) -> PoleSet:
    """Locate all n(n-1)/2 instant centres of the solution (see the module's docstring).

    Inspection first (pins, sliders, circular paths, rolling contacts, and
    the constraint lines of sliding contacts and slots), then the
    Aronhold-Kennedy theorem, round by round: P_ij lies on the line
    P_ik P_jk for every third link k, so two such lines (or one and a
    constraint line) meet at P_ij, ``P_ij = l x m``. What Kennedy cannot
    reach comes from the velocity solution (P_ij ~ T_i - T_j, :func:`link_twists`).
    The result is kept for the solution's lifetime (``cached=False`` computes afresh).
    """
    if not cached:
        return _locate(sol)
    hit = _CACHE.get(id(sol))
    if hit is not None and hit[0]() is sol:
        return hit[1]
    ps = _locate(sol)
    _CACHE[id(sol)] = (weakref.ref(sol), ps)
    weakref.finalize(sol, _CACHE.pop, id(sol), None)
    return ps


def _locate(sol) -> PoleSet:
    return _without_gc(_pole_set, sol)


def _without_gc(finish, sol):
    """``finish(sol, *_construct(sol))``: the construction and what is made of it (the PoleSet, or the
    JSON alone). Tens of thousands of small objects for a big chain, none in a reference cycle: the
    cyclic garbage collector's passes over them would cost a third of the time at 200 links, so it
    waits until the end."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        return finish(sol, *_construct(sol))
    finally:
        if enabled:
            gc.enable()


def _construct(sol) -> tuple:
    """The Kennedy construction run to its end: ``(kennedy, centre, scale, found)``, what
    :func:`_pole_set` (the PoleSet) and :func:`_pole_places` (the JSON alone) read."""
    m = sol.mechanism
    names = list(m.link_names)
    idx = {nm: i for i, nm in enumerate(names)}
    centre, scale = _normalisation(sol)
    twists = link_twists(sol, centre, scale)
    points, cons = _inspection(sol, centre, scale)
    alike = _alike_pairs(sol, twists, centre, scale)
    kennedy = (_Kennedy if len(names) <= _SMALL else _KennedyArrays)(names, twists, alike)

    # by inspection: a pin (a rolling contact) is its pole whatever the other links do, even when the
    # two links move alike: the joint itself makes their velocities agree at its point. A block's
    # pole is read from the direction it slides in (normal to its path): a block that does not slide
    # (at a dead centre: it moves alike with its guide) has none, its pole is undefined (FORMAT.md
    # section 5). Either way P_ik = P_jk stays decided from the velocities.
    new = []
    for i, j, h, how, note, at in points:
        a, b = sorted((idx[i], idx[j]))
        if kennedy.state[a][b] == _UNKNOWN or (how in _JOINT_POLES and kennedy.state[a][b] != _KNOWN):
            kennedy.set(a, b, h, dict(how=how, order=0, note=note))
            new.append((a, b))
            if at is not None:
                kennedy.exact[a, b] = at
    for i, j, h, label, desc, marks in cons:
        kennedy.add_constraint(idx[i], idx[j], h, label, desc, marks)
    kennedy.spread(new)

    order = 0
    found = []
    while kennedy.unknown:
        cands = kennedy.candidates()
        if cands and max(c[2] for c in cands) >= _POOR:
            cands = [c for c in cands if c[2] >= _POOR]   # poorly meeting lines wait for better ones
        if not cands:
            # Kennedy is stuck: the unknown pole on the most known lines, from the velocity solution
            a, b = kennedy.most_lines()
            cands = [(a, b, 0.0, dict(how="velocity", h=_unit(np.subtract(twists[a], twists[b])),
                                      note="from the links' velocity fields: no two Kennedy lines reach it"))]
        new = []
        for a, b, _, info in cands:
            order += 1
            info["order"] = order
            if info["how"] is None:
                info["how"] = "kennedy" if min(info["slots"]) < kennedy.n else "normals"
            new.append((a, b, info.pop("h"), info))
        kennedy.set_many(new)
        new = [(a, b) for a, b, _, _ in new]
        found.extend(new)
        kennedy.spread(new)
    return kennedy, centre, scale, found


def _lines_drawn(kennedy, used, where, centre, scale) -> list:
    """The contract's (pair of labels, via entry, PoleLine) of each line ``(a, b, slot, vector)`` used
    for a pole P_ab: a Kennedy line (slot: the third link) through its two poles, or a constraint line."""
    n, names, keys = kennedy.n, kennedy.names, kennedy.keys
    out = []
    for a, b, slot, vec in used:
        if slot < n:
            ka, kb = keys[a][slot], keys[b][slot]
            out.append(((ka, kb), (names[a], names[b], names[slot]),
                        _pole_line(f"P_{ka} P_{kb}", (ka, kb), vec, (where[a][slot], where[b][slot]), centre, scale)))
        else:
            label, desc = kennedy.constraints[(a, b)][slot - n]
            marks = kennedy.marks.get((a, b, slot - n), ())
            out.append((label, desc, _pole_line(desc, (), vec, marks, centre, scale, marks)))
    return out


def _pole_line(label, through, l, ends, centre, scale, marks=()) -> PoleLine:
    """A line's geometry for drawing: a finite point (a known pole or a defining point where one is
    finite, else the foot of the perpendicular from the centre) and a unit direction, in frame
    coordinates."""
    l0, l1, l2 = map(float, l)
    nrm = math.hypot(l0, l1)
    if nrm < 1e-15:
        return PoleLine(label, through, None, None, marks)
    direction = np.array((-l1 / nrm, l0 / nrm))
    for pos in ends:
        if pos is not None:
            return PoleLine(label, through, pos, direction, marks)
    f = -scale * l2 / (nrm * nrm)
    return PoleLine(label, through, np.array((centre[0] + f * l0, centre[1] + f * l1)), direction, marks)


def _direction(hw) -> float:
    """The direction in [0, 180) of a world homogeneous point (x, y, w) at infinity (w = 0 or
    |(x, y)| > FAR size |w|: a pole farther than FAR mechanism sizes is at infinity)."""
    d = math.degrees(math.atan2(float(hw[1]), float(hw[0]))) % 180.0
    return (0.0 if d >= 180.0 else d) + 0.0


def _pole_set(sol, kennedy, centre, scale, found) -> PoleSet:
    """The contract's PoleSet: world positions (x, y, w) = (scale x' + centre w', ..., w'), the lines."""
    names, n = kennedy.names, kennedy.n
    tw = float(_norm_rows(kennedy.twists).max()) if n else 0.0
    err, known = kennedy.world(centre, scale)
    where = [[None] * n for _ in range(n)]   # each known pole's finite position, both ways round
    world = {}
    exact = kennedy.exact
    for a, b, hk, pos, inf in known:
        at = exact.get((a, b))   # a finite pole by inspection: exactly where it is
        if at is not None:
            pos, direction = np.array(at, float), None
        elif inf:
            pos, direction = None, _direction(hk)
        else:
            pos, direction = np.asarray(pos, float), None
        world[a, b] = np.asarray(hk, float), pos, direction
        where[a][b] = where[b][a] = pos
    pairs = [ab for ab, info in kennedy.info.items() if "slots" in info]   # poles found by two lines
    used = [(a, b, slot, v) for a, b in pairs
            for slot, v in zip(kennedy.info[a, b]["slots"], kennedy.info[a, b]["line_vectors"])]
    out = _lines_drawn(kennedy, used, where, centre, scale)
    drawn = dict(zip(pairs, zip(out[0::2], out[1::2])))
    poles = {}
    keys, infos = kennedy.keys, kennedy.info
    for a in range(n):
        na, ka = names[a], keys[a]
        for b in range(a + 1, n):
            key, info = ka[b], infos[a, b]
            got = world.get((a, b))
            if got is None:
                poles[key] = Pole((na, names[b]), key, None, None, "undefined", 0, note=info.get("note", ""))
                continue
            hw, position, direction = got
            parts = drawn.get((a, b))
            if parts is None:
                via, lines, construction = info.get("via", ()), info.get("lines", ()), ()
            else:
                (l0, v0, c0), (l1, v1, c1) = parts
                via, lines, construction = (v0, v1), (l0, l1), (c0, c1)
            poles[key] = Pole((na, names[b]), key, position, direction, info["how"], info["order"], via,
                              lines, construction, info.get("sine", 1.0), hw, info.get("note", ""))
    err /= tw or 1.0
    cl = {kennedy.key(a, b): tuple(_pole_line(desc, (), np.array(kennedy.cons[(a, b)][c]), kennedy.marks.get((a, b, c), ()),
                                        centre, scale, kennedy.marks.get((a, b, c), ()))
                             for c, (_, desc) in enumerate(items))
          for (a, b), items in kennedy.constraints.items()}
    return PoleSet(tuple(names), poles, sol.mechanism.frame.name, tuple(kennedy.key(a, b) for a, b in found), cl, err,
                   np.asarray(centre, float), scale)


def _pole_places(sol, kennedy, centre, scale, found) -> dict:
    """The JSON ``poles`` section from the construction as :func:`_pole_set` makes its PoleSet (the same
    positions, directions, how and order), without the lines drawn: what ``solve --json`` needs."""
    keys, infos, exact = kennedy.keys, kennedy.info, kennedy.exact
    out = dict.fromkeys(_key_order(keys))   # every pole in key order; None: undefined
    for (a, b), at in exact.items():         # a finite pole by inspection: exactly where it is
        info = infos[a, b]
        out[keys[a][b]] = {"position": [float(at[0]), float(at[1])], "how": info["how"], "order": info["order"]}
    for a, b, hk, pos, inf in kennedy.world(centre, scale, error=False, exact=False)[1]:
        if (a, b) in exact:
            continue
        info = infos[a, b]
        if inf:
            out[keys[a][b]] = {"position": None, "direction": _direction(hk), "how": info["how"],
                               "order": info["order"]}
        else:
            out[keys[a][b]] = {"position": [float(pos[0]), float(pos[1])], "how": info["how"],
                               "order": info["order"]}
    for key, got in out.items():
        if got is None:
            out[key] = {"position": None, "direction": None, "how": "undefined", "order": 0}
    return out


@functools.lru_cache(maxsize=16)   # the same links at every pose of a mechanism
def _key_order(keys: tuple) -> tuple:
    """The pole keys of :func:`_pair_keys` in key order: (a, b) for a < b."""
    return tuple(k for a, row in enumerate(keys) for k in row[a + 1:])


def kennedy_circle(ps: PoleSet) -> KennedyCircle:
    """The Kennedy circle of a pole set: n points, n(n-1)/2 chords (see :class:`KennedyCircle`)."""
    n = len(ps.links)
    pts = {}
    for i, lk in enumerate(ps.links):
        t = math.pi / 2 - 2 * math.pi * i / n
        pts[lk] = np.array([math.cos(t), math.sin(t)])
    chords = tuple(Chord(p.key, p.links, p.by_inspection, p.order) for p in ps.poles.values())
    return KennedyCircle(pts, chords)


# -- the instant-centre method -------------------------------------------------------------------
def instant_centre_velocities(sol, poles: PoleSet | None = None) -> dict:
    """Every omega and point velocity by the instant-centre method, from the driver through the poles.

    Each link's twist is a multiple of its frame pole, t_k = lambda_k P_1k
    (homogeneous, normalised coordinates), and t_j - t_i ~ P_ij, so

        lambda_j (P_1j x P_ij) = t_i x P_ij,

    which is omega_j = omega_i (P_ij - P_1i) / (P_ij - P_1j) along the line
    of the three poles, and stays exact for a translating link (P_1k at
    infinity: V = omega_i x (P_ij - P_1i) for the block). Links are reached
    from the driver in rounds (first every link with a pole on the driver,
    then the links with a pole on those, ...), each through the pole that
    fixes it best (P_ij farthest from P_1j, both poles well drawn). A point B of link k then moves with
    ``V_B = omega_k x (B - P_1k)``.

    Returns a dict: ``omega`` (link -> rad/s), ``velocity`` (point key ->
    array (2,)), ``path`` (tuples ``(link, from_link, pole_key)`` in the
    order found) and ``max_error`` (``{"omega", "velocity"}``: largest
    difference from the analytic solve, relative to the largest omega and
    the largest speed).
    """
    ic = _InstantCentres(sol, locate_poles(sol) if poles is None else poles)
    ic.at_rest()
    ic.from_driver()
    ic.through_poles()
    ic.from_velocity_solution()
    return ic.result()


class _InstantCentres:
    """The instant-centre method's state: every pole in normalised homogeneous coordinates
    (``pole[i, j]``, ``state[i, j]`` known or undefined, ``sure[i, j]`` how well it is fixed: 1, less
    for lines meeting at a small angle), each link's twist as found (``twist[k]`` = omega_k P_1k,
    ``known[k]``) and the ``path`` by which each link was reached."""

    def __init__(self, sol, ps: PoleSet):
        self.sol, self.m = sol, sol.mechanism
        self.names = names = list(ps.links)
        self.n = n = len(names)
        self.idx = {nm: i for i, nm in enumerate(names)}
        self.centre, self.scale = ps.centre, ps.scale
        self.pole = np.zeros((n, n, 3))
        self.state = np.zeros((n, n), np.int8)
        self.sure = np.ones((n, n))
        for p in ps.poles.values():
            a, b = self.idx[p.links[0]], self.idx[p.links[1]]
            if p.undefined:
                self.state[a, b] = self.state[b, a] = _UNDEFINED
            else:
                self.pole[a, b] = self.pole[b, a] = _to_local(p.homogeneous, self.centre, self.scale)
                self.state[a, b] = self.state[b, a] = _KNOWN
                self.sure[a, b] = self.sure[b, a] = min(1.0, p.sine / _POOR)
        self.frame = self.idx[self.m.frame.name]
        self.twist = np.zeros((n, 3))
        self.known = np.zeros(n, bool)
        self.known[self.frame] = True
        self.path = []

    def fix(self, j, twist, frm, key):
        """Link j moves with ``twist``, reached from link ``frm`` through the pole ``key``."""
        self.twist[j] = twist
        self.known[j] = True
        self.path.append((self.names[j], frm, key))

    def at_rest(self):
        """Links at rest move like the frame (their frame pole is undefined)."""
        f = self.frame
        for j in range(self.n):
            if j != f and self.state[f, j] == _UNDEFINED:
                self.fix(j, np.zeros(3), self.names[f], _key(self.names, f, j))

    def from_driver(self):
        """A crank turns with its omega about its frame pole; a slider driver: :func:`_slider_driver`."""
        drv, f = self.m.driver, self.frame
        if drv.is_slider:
            _slider_driver(self.sol, self.m, self.idx, f, self.pole, self.state, self.twist, self.known,
                           self.path, self.names, self.centre, self.scale)
            return
        d = self.idx[drv.link]
        if not self.known[d]:
            p = self.pole[f, d]
            self.fix(d, drv.omega * p / p[2], None, _key(self.names, f, d))

    def through_poles(self):
        """Rounds: every link reachable now, each through its best pole from a link known before:
        ``lambda_j (P_1j x P_ij) = t_i x P_ij`` (a link moving alike takes the other's twist)."""
        f, pole, state, twist = self.frame, self.pole, self.state, self.twist
        while not self.known.all():
            ks = np.nonzero(self.known & (np.arange(self.n) != f))[0]
            us = np.nonzero(~self.known)[0]
            if len(ks) == 0:
                break
            st = state[np.ix_(ks, us)]
            cond = _norm(_cross(pole[f, us][None, :, :], pole[np.ix_(ks, us)])) * self.sure[np.ix_(ks, us)] \
                * self.sure[f, us][None, :]
            cond = np.where(st == _UNDEFINED, 1.0, np.where((st == _KNOWN) & (state[f, us] == _KNOWN)[None, :],
                                                            cond, 0.0))
            best = cond.max(axis=0)
            if best.max() < _DEGENERATE:
                break
            take = best >= min(_POOR, best.max())
            new = []
            for u in np.nonzero(take)[0]:
                j, i = int(us[u]), int(ks[int(np.argmax(cond[:, u]))])
                if state[i, j] == _UNDEFINED:
                    new.append((j, twist[i].copy(), i))
                else:
                    q, pj = pole[i, j], pole[f, j]
                    cj = _cross(pj, q)
                    lam = float(_cross(twist[i], q) @ cj) / float(cj @ cj)
                    new.append((j, lam * pj, i))
            for j, t, i in new:
                self.fix(j, t, self.names[i], _key(self.names, i, j))

    def from_velocity_solution(self):
        """Links the poles cannot reach (degenerate): their twists from the velocity solution."""
        twists = None
        for j in range(self.n):
            if not self.known[j]:
                twists = link_twists(self.sol, self.centre, self.scale) if twists is None else twists
                self.fix(j, twists[j], None, "velocity")

    def result(self) -> dict:
        """omega, every point's velocity ``V_B = omega_k x (B - P_1k)``, the path, the largest errors."""
        sol, names = self.sol, self.names
        omega = {names[j]: float(self.twist[j][2]) for j in range(self.n)}
        velocity = {}
        for key, _, lk in point_keys(self.m):
            velocity[key] = _twist_velocity(self.twist[self.idx[lk]], sol.position[key], self.centre, self.scale)
        w_ref = max((abs(v) for v in sol.omega.values()), default=0.0) or 1.0
        v_ref = max((float(np.hypot(*v)) for v in sol.velocity.values()), default=0.0) or 1.0
        e_om = max((abs(omega[k] - sol.omega[k]) for k in omega), default=0.0) / w_ref
        e_v = max((float(np.hypot(*(velocity[k] - sol.velocity[k]))) for k in velocity), default=0.0) / v_ref
        return {"omega": omega, "velocity": velocity, "path": tuple(self.path),
                "max_error": {"omega": e_om, "velocity": e_v}}


def _key(names, a, b) -> str:
    """The pole key of two link indices (file order)."""
    return f"{names[a]}-{names[b]}" if a < b else f"{names[b]}-{names[a]}"


def _twist_velocity(t, x, centre, scale) -> np.ndarray:
    """V at frame point x of the twist t = (-v_y, v_x, omega) (normalised): v + omega k x x'."""
    xl = (np.asarray(x, float) - centre) / scale
    return scale * np.array([t[1] - t[2] * xl[1], -t[0] + t[2] * xl[0]])


def _slider_driver(sol, m, idx, f, pole, state, t, known, path, names, centre, scale):
    """Seed the twists from a slider driver: the block's motion relative to its guide is known.

    Straight path: a translation s e, the relative twist (-s e_y, s e_x, 0)/scale;
    circular path about K: omega_rel = s / R about K. With a moving guide,
    lambda_b P_1b - lambda_g P_1g equals that relative twist.
    """
    drv = m.driver
    k = next(i for i, s in enumerate(m.sliders) if s.point == drv.slider)
    s = m.sliders[k]
    b, g = idx[s.block], idx[s.guide]
    if s.centre is None:
        d = math.radians(float(sol.motion.sliders[k]["direction"][0]))
        e = np.array([math.cos(d), math.sin(d)]) * drv.speed / scale
        r = np.array([-e[1], e[0], 0.0])
    else:
        kk = sol.place(s.guide, s.centre)
        radius = float(np.hypot(*(sol.place(s.block, s.point) - kk)))
        w = drv.speed / radius
        r = w * np.array([(kk[0] - centre[0]) / scale, (kk[1] - centre[1]) / scale, 1.0])
    key = _key(names, b, g)
    if g == f:
        t[b] = r
        known[b] = True
        path.append((names[b], None, key))
        return
    A = np.stack([pole[f, b], -pole[f, g]], axis=1)
    sol_, _, rank, _ = np.linalg.lstsq(A, r, rcond=None)
    if rank < 2:  # the two frame poles coincide: the guide's twist from the velocity solution
        twists = link_twists(sol, centre, scale)
        t[g], t[b] = twists[g], twists[g] + r
    else:
        t[b], t[g] = sol_[0] * pole[f, b], sol_[1] * pole[f, g]
    known[b] = known[g] = True
    path.append((names[b], None, key))
    path.append((names[g], names[b], key))


# -- the JSON section --------------------------------------------------------------------------------
def poles_section(sol) -> dict:
    """The JSON ``poles`` section (FORMAT.md section 2), with ``how`` and ``order`` added."""
    hit = _CACHE.get(id(sol))
    if hit is None or hit[0]() is not sol:   # no pole set built: the construction without its lines
        return _without_gc(_pole_places, sol)
    out = {}
    for key, p in hit[1].poles.items():
        if p.position is not None:
            d = {"position": [float(p.position[0]), float(p.position[1])]}
        else:
            d = {"position": None, "direction": p.direction}
        d["how"] = p.how
        d["order"] = p.order
        out[key] = d
    return out


def pole_label(key: str, compact: bool = True) -> str:
    """The textbook name of a pole: ``P_13`` for key "1-3" (``P_{10-12}`` where names are longer)."""
    i, j = key.split("-")
    return f"P_{i}{j}" if compact and len(i) == 1 and len(j) == 1 else f"P_{{{key}}}"


def pole_caption(p: Pole, name=None) -> str:
    """How a pole found (``order`` > 0) was found, in the textbook's words: the caption of its step
    (``velpoly draw --steps`` and the html page's stepper alike). ``name(key)`` writes a pole's name
    (``"1-3"`` -> ``P_13``, :func:`pole_label` by default; the sheets pass mathtext's).

    Aronhold-Kennedy: "P_13 on the line P_12 P_23 and the line P_14 P_34 (Aronhold-Kennedy: the
    poles of three links lie on one line)"; a constraint line reads "the common normal at P" or
    "the slot's normal at A".
    """
    from .polygons import point_text
    name = name or pole_label
    me = name(p.key)
    if p.how == "alike" and p.lines:
        pair, same = p.lines[0]
        i, x = pair.split("-")
        return f"{me} = {name(same)}: links {i} and {x} move alike at this instant"
    if p.how == "velocity":
        return f"{me} from the velocity solution: no two Kennedy lines reach it"
    words = []
    for ln in p.lines:
        if ln[0] == "normal":
            words.append(f"the common normal at {point_text(ln[1])}")
        elif ln[0] == "slot normal":
            words.append(f"the slot's normal at {point_text(ln[1])}")
        else:
            words.append(f"the line {name(ln[0])} {name(ln[1])}")
    why = (" (Aronhold-Kennedy: the poles of three links lie on one line)"
           if any(ln[0] not in ("normal", "slot normal") for ln in p.lines) else "")
    return f"{me} on " + " and ".join(words) + why if words else f"{me} ({p.how})"

