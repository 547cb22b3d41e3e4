"""Velocity and acceleration polygons, constructed the way a textbook draws them.

The velocity polygon locates the *image* of every point, the tip of its
velocity drawn from the origin O_v, by ruler constructions; the acceleration
polygon does the same from O_a. Nothing is read off the analytic solution:
the construction uses the pose (the displacement diagram), the driver's
motion and, for accelerations, the velocity polygon's own results. The
analytic solve is used only afterwards, to check (``Polygon.max_error``).

**Plan.** :func:`construction_plan` orders the construction from the
mechanism alone (which images are known, which links' omegas are known):

* the frame's points image at the origin; the driver's images follow from
  ``V_B = V_A + omega x R_BA`` (a crank) or its known speed (a slider);
* *dyad* ('intersection', case 2a): an unknown image lies on two lines
  through known images, e.g. for a pin B of links 3 and 4,
  ``V_B = V_A + V_BA = V_O4 + V_BO4`` -- the line through a perpendicular to
  AB and the line through o4 perpendicular to O4B. A slider adds the line
  ``V_B3 = V_B4 + V_B3/B4`` through b4 parallel to the path (at any point
  of block and guide, as they turn together); a pin in a slot the line
  along the slot; a sliding contact the line along the common tangent;
* *image*: once two images of a link are known (or one and its omega), the
  link's figure is reproduced similar to the link, turned 90 deg in the sense
  of omega and scaled by |omega| (``omega = |ab| / |AB|``, sense from the turn);
* *known*: a rolling contact (``V_P(a) = V_P(b)``), a prescribed slip or a
  slider driver adds a known vector;
* *auxiliary* (where no dyad exists, e.g. a Stephenson III six-bar whose
  ternary coupler hangs on three binary links): a point S of the link with
  no known image, where the lines of two of its points' velocities meet,
  has its image at the intersection of those two lines (S is the link's
  instant centre when both lines pass through O_v; at acceleration level the
  same point works with the normal terms added).

**Acceleration** replays the same plan with the known vectors of the
acceleration level: ``A_B = A_A + A^n_BA + A^t_BA`` (normal omega^2 |AB|
towards A, tangential perpendicular to AB), Coriolis ``2 omega x V_rel`` and
the slip along the path for blocks on moving guides and pins in slots,
``V_rel^2 / rho`` towards the centre of a curved path, and for contacts the
normal relative acceleration of the contact points from the equivalent
linkage through the centres of curvature. Acceleration images are similar
to their links, turned by ``atan2(alpha, -omega^2)`` and scaled by
``sqrt(alpha^2 + omega^4)``.

Every intersection is solved with :func:`velpoly.geometry.intersect_lines`;
two lines closer to parallel than ``1 / kinematics.SINGULAR`` (the sine of
their angle) make a singular pose (:class:`~velpoly.errors.SingularPoseError`).

**Names.** The plan's steps are small frozen dataclasses named as the book names
them (:class:`FrameAtOrigin`, :class:`DriverStep`, :class:`SliderDriverStep`,
:class:`KnownMotionStep`, :class:`IntersectionStep` -- case 2a --,
:class:`VelocityImageStep`, :class:`AuxiliaryPointStep`, :class:`TrialSolutionStep`),
each writing its equation and its caption in words; their operations
(:class:`VelocityImage`, :class:`Intersection`, :class:`TrialSolution`, ...)
apply themselves to a replay (:class:`_Run`), whose chains hold
:class:`CentripetalTerm` and :class:`JointMotionTerm` (with the Coriolis term,
:meth:`_Run.coriolis_term`).

**Hand drafting.** :func:`hand_drafting` replays the same plan, vectorised
over many random perturbations (directions within +-0.25 deg, points within
+-0.25 mm at the scale that fits the polygon in ~120 mm), and reports the
2.5 and 97.5 percentiles of each omega and each speed.
"""
from __future__ import annotations

import dataclasses
import functools
import math
import weakref
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import ClassVar, NamedTuple

import numpy as np

from . import geometry as G
from .errors import ConstructionError, InputError, SingularPoseError
from .frozen import quick_init
from .kinematics import SINGULAR, singular_hint
from .motion import point_keys
from .rigid import coriolis as coriolis_term, dot as _dot, normal_acceleration, perp, rate_cross
from .names import lower_name, point_text, relative
from .names import place as named

__all__ = [
    "ConstructionLine", "Vector", "Step", "AuxiliaryPoint", "Polygon", "ConstructionError",
    "velocity_polygon", "acceleration_polygon", "construction_plan", "hand_drafting", "graphical_section", "point_text",
    "SINE_LIMIT",
]

SINE_LIMIT = 1.0 / SINGULAR   # |sin| between two construction lines below which the pose is singular


# -- the contract with the renderer (docs/internals.md) ----------------------------------------------
@quick_init
@dataclass(frozen=True)
class ConstructionLine:
    """A line of the construction: through ``base`` (polygon coordinates) along ``direction``."""

    base: np.ndarray
    direction: np.ndarray
    base_label: str
    reason: str


@quick_init
@dataclass(frozen=True)
class Vector:
    """An arrow of the polygon, from ``tail`` to ``head``, in its own true sense.

    ``kind``: 'absolute' | 'relative' | 'normal' | 'tangential' | 'coriolis' | 'slip'.
    ``head - tail`` is exactly the quantity ``label`` names (never its negative: where a
    construction starts from the other side of an equation, the arrow is drawn ending at
    the known image, so that the arrows still run tip to tail; where its line also adds terms, a
    subtracted term is drawn forwards as the negative quantity under its own name, V_A4/A3 for
    -V_A3/A4: :meth:`_Run.chain`). ``of`` says which quantity,
    in point keys (``"B"``, ``"P@3"``) or auxiliary keys (``"A@4"``, ``"S3@3"``), for checks:

    * ``("point", K)``: V_K (A_K), drawn from the origin;
    * ``("difference", W, Q)``: V_W - V_Q (A_W - A_Q): a rigid link's V_WQ, a rolling
      contact's A_P3/P4;
    * ``("normal", link, W, Q)``: -omega_link^2 R_WQ; ``("tangential", link, W, Q)``: alpha_link x R_WQ;
    * ``("coriolis", guide, A, B)``: 2 omega_guide x (V_A - V_B);
    * ``("slip", A, B, guide, K)``: the motion of A relative to the guide's point B under it:
      V_A - V_B; at acceleration level A_A - A_B - 2 omega_guide x V_AB, less the path's own
      normal term V_AB^2 / rho towards K on a circular path (K None: straight);
    * ``("path-normal", A, B, K)``: |V_A - V_B|^2 / |R_AK| towards K (a circular relative path);
    * ``("sum", ((sign, of), ...))``: a sum of the above (an auxiliary point's unknown).
    """

    tail: np.ndarray
    head: np.ndarray
    kind: str
    label: str
    of: tuple = ()


@dataclass(frozen=True)
class Step:
    """One step of the construction.

    ``kind``: 'known' | 'driver' | 'intersection' | 'image' | 'auxiliary' | 'instant-centre'.
    ``lines`` are the two lines intersected (empty for other kinds); ``found`` the
    point keys located; ``omegas`` the link rates (omega, or alpha in an acceleration
    polygon) this step fixes; ``sine`` the |sin| of the angle between the lines.
    ``auxiliary`` names the points located that are not point keys (a guide's point
    under a block, ``A@4``; an auxiliary point ``S3@3``); ``link`` is the link whose
    image a 'driver', 'image' or auxiliary step draws.
    """

    index: int
    kind: str
    equation: str
    lines: tuple
    found: tuple
    vectors: tuple
    omegas: dict
    sine: float
    auxiliary: tuple = ()
    link: str | None = None
    caption: str = field(default_factory=str)   # a factory, not a class attribute: see __getattr__

    # A polygon's steps write their equation and caption when first read (:meth:`_written`): most
    # uses of a polygon (the JSON's checks, a sheet without step frames) read neither, and writing
    # them was a third of building the polygons. The texts depend on the plan step and the names of
    # the pose's places alone, which the rest of the replay does not change: the same strings.
    def __getattr__(self, name):
        """``equation`` or ``caption`` of a step built by :meth:`_written`, written on first use and kept."""
        if name in ("equation", "caption"):
            texts = self.__dict__.get("_texts")
            if texts is not None:
                plan_step, run = texts
                value = plan_step.equation(run) if name == "equation" else plan_step.caption(run)
                object.__setattr__(self, name, value)
                return value
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    @classmethod
    def _written(cls, plan_step, run, **fields) -> "Step":
        """A step whose equation and caption ``plan_step`` writes from ``run`` when they are first read."""
        step = object.__new__(cls)
        step.__dict__.update(fields, _texts=(plan_step, run))
        return step

    def __getstate__(self):   # a copy or a pickle carries the texts, not the replay
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    def __setstate__(self, state):
        self.__dict__.update(state)


@quick_init
@dataclass(frozen=True)
class AuxiliaryPoint:
    """A point of a link used by the construction that is not one of the file's point keys."""

    key: str            # "A@4": link 4's point under A; "S3@3": the auxiliary point of link 3
    link: str
    position: np.ndarray
    image: np.ndarray
    label: str


@dataclass(frozen=True)
class Polygon:
    """A velocity or acceleration polygon: images, labels, construction steps, rates, check."""

    kind: str
    origin_label: str
    images: dict
    labels: dict
    steps: tuple
    link_images: dict
    rates: dict
    max_error: float
    auxiliary: dict = field(default_factory=dict)   # key -> AuxiliaryPoint
    scale: float = 1.0                               # drawing scale: mm per unit that fits ~120 mm


# -- the mechanism's geometry, as the construction sees it ------------------------------------------
@dataclass(frozen=True)
class _Rel:
    """A joint between the points of links a and b at the same place W.

    ``image_a(W) = image_b(W) + offset`` (``exact``), or that plus any multiple of
    ``direction`` (a path: slider, slot, sliding contact, a contact's centre of
    curvature). ``at`` is the point where it holds; None for a straight slider
    (every coincident point). ``centre``: the centre of a circular relative path.
    """

    source: str           # 'slider' | 'slot' | 'contact' | 'centre' | 'drive'
    index: int            # into m.sliders / m.slots / m.contacts
    a: str
    b: str
    at: str | None
    direction: np.ndarray
    exact: bool
    centre: str | None = None
    prefer: str | None = None   # where a relation that holds everywhere (at None) is best applied

    @property
    def zdir(self) -> complex:
        """The path's direction as x + iy."""
        return _z(self.direction)


class _Shape:
    """What a pose's geometry (:class:`_Geo`) has of its mechanism alone, made once per mechanism: the
    links, the point keys and which link carries which point, the places pins join (union-find: each
    group's canonical place first, a frame place where there is one), the joints (``specs``: a
    :class:`_Rel` but for its direction, which is the pose's) and the links turning together."""

    def __init__(self, sol):
        m = sol.mechanism
        self.fixed = dict(m=m, frame=m.frame.name, links=m.link_names, moving=tuple(k.name for k in m.moving_links),
                          size=sol.kinematics.system.size,   # m.size, computed once for the system
                          tol=1e-9 * sol.kinematics.system.size, key={}, own={lk: [] for lk in m.link_names},
                          rate_eq=[], _named={})   # _named: a place's name (or a term's) as the mechanism names it
        self.frame, key, own = m.frame.name, self.fixed["key"], self.fixed["own"]
        self.places, seen = [], set()   # (key, point): each point's position, read from its first key
        for k, p, lk in point_keys(m):   # one key P for every carrier, or P@link for each
            if p not in seen:
                seen.add(p)
                self.places.append((k, p))
            for c in (m.carriers[p] if k == p else (lk,)):
                key[(p, c)] = k
                own[c].append(p)
        self.extra = {lk: [] for lk in m.link_names}
        self._parent = {}
        for pin in m.pins:
            self._union((pin.links[0], pin.point), (pin.links[1], pin.point))
        self.specs = self._joints(m, own)
        root = {p: self._find(p) for p in self._parent}   # the unions are complete
        groups = {}
        for p, r in root.items():
            groups.setdefault(r, [r]).extend([p] if p != r else [])
        self.fixed.update(_root=root, _groups=groups)

    def _joints(self, m, own) -> list:
        """The joints as :class:`_Rel` s but for their directions: ``(origin, fields)``, origin the
        (kind, index) of the motion's entry that gives the pose's direction."""
        specs, drv, rate_eq = [], m.driver, self.fixed["rate_eq"]
        for i, s in enumerate(m.sliders):
            if s.centre is not None:   # a curved block turns about K relative to its guide: a pin at K
                if s.centre not in own[s.block]:
                    self.extra[s.block].append(s.centre)
                self._union((s.block, s.centre), (s.guide, s.centre))
            else:
                rate_eq.append((s.block, s.guide))
            if drv.is_slider and drv.slider == s.point:
                # on a straight path block and guide turn together: the driver's slip is the
                # relative velocity of every pair of coincident points, not only at the block's point
                at = s.point if s.centre is not None else None
                specs.append((("slider", i), ("drive", i, s.block, s.guide, at, True, s.centre, s.point)))
            elif s.centre is None:
                specs.append((("slider", i), ("slider", i, s.block, s.guide, None, False, None, None)))
        for i, s in enumerate(m.slots):
            specs.append((("slot", i), ("slot", i, s.link, s.slot, s.pin, False, s.centre, None)))
        for i, c in enumerate(m.contacts):
            exact = c.kind == "rolling" or c.slip is not None
            specs.append((("contact", i), ("contact", i, c.links[0], c.links[1], c.point, exact, None, None)))
            # the equivalent linkage: each centre of curvature moves on the other link along the
            # tangent, on a circle about the other centre (or parallel to the other's flat)
            for k, (ca, cb) in enumerate((c.centres, c.centres[::-1]) if c.centres else ()):
                if ca is not None:
                    specs.append((("contact", i), ("centre", i, c.links[k], c.links[1 - k], ca, False, cb, None)))
        return specs

    # places are (link, point name); pins (and the centres of curved sliders) share one image
    def _find(self, p):
        while self._parent.get(p, p) != p:
            p = self._parent[p]
        return p

    def _union(self, p, q):
        a, b = self._find(p), self._find(q)
        if b[0] == self.frame:   # a frame point is the root: grounded places are canon(p)[0] == frame
            a, b = b, a
        if a != b:
            self._parent[b] = a

    def rels(self, mo) -> list:
        """The joints at the pose of ``mo``: sliders' and slots' paths, contacts' common tangents."""
        dirs, out = {}, []
        for origin, (source, i, a, b, at, exact, centre, prefer) in self.specs:
            d = dirs.get(origin)
            if d is None:
                kind, k = origin
                if kind == "contact":
                    d = perp(G.from_polar(1.0, float(mo.contacts[k]["normal"][0])))
                else:
                    d = G.from_polar(1.0, float((mo.sliders if kind == "slider" else mo.slots)[k]["direction"][0]))
                dirs[origin] = d
            out.append(_Rel(source, i, a, b, at, d, exact, centre, prefer))
        return out


def _of_mechanism(cache: dict, m, make):
    """``cache``'s value for the mechanism m, ``make()`` where there is none yet; dropped with m."""
    hit = cache.get(id(m))
    if hit is not None and hit[0]() is m:
        return hit[1]
    value = make()
    cache[id(m)] = (weakref.ref(m), value)
    weakref.finalize(m, cache.pop, id(m), None)
    return value


_SHAPES: dict = {}   # id(mechanism) -> (weak reference, _Shape)


class _Geo:
    """Positions, places and joints of a solved pose (no velocities); the mechanism's part
    (:class:`_Shape`) shared by its poses, never changed."""

    def __init__(self, sol):
        shape = _of_mechanism(_SHAPES, sol.mechanism, lambda: _Shape(sol))
        self.__dict__.update(shape.fixed)
        self.extra = {lk: list(v) for lk, v in shape.extra.items()}   # auxiliary points are added per pose
        self.names = {}          # place -> textbook name of a place that is no point key
        position = sol.motion.position
        self.pos = {p: position[k][0] for k, p in shape.places}
        self.zpos = {p: _z(v) for p, v in self.pos.items()}   # as x + iy (what the replays compute with)
        self.rels = shape.rels(sol.motion)

    def canon(self, place):
        """The place whose image stands for this one's (pinned places share one image)."""
        return self._root.get(place, place)

    def group(self, place) -> list:
        """Every place sharing the image of ``place`` (the canonical one first)."""
        c = self.canon(place)
        return self._groups.get(c, [c])

    def grounded(self, place) -> bool:
        return self.canon(place)[0] == self.frame

    def places(self, lk) -> list:
        """The link's points: its own, then the extra ones (curved sliders' centres, auxiliary points)."""
        own, extra = self.own[lk], self.extra[lk]
        return own + [n for n in extra if n not in own] if extra else own

    def point_key(self, place):
        """The point key of a place, or None (a coincident or auxiliary point)."""
        lk, n = place
        return self.key.get((n, lk))

    def name(self, place) -> str:
        """Textbook name: B for a point key B, B4 for link 4's point at B, S3 for an auxiliary point."""
        got = self.names.get(place)   # an auxiliary point's: the pose's
        if got is None:
            got = self._named.get(place)   # the mechanism's, made once
            if got is None:
                lk, n = place
                got = self._named[place] = n if self.key.get((n, lk)) == n else named(n, lk)
        return got

    def aux_key(self, place) -> str:
        lk, n = place
        return f"{n}@{lk}"

    def qkey(self, place) -> str:
        """The key a vector's ``of`` names a place by: its point key, else its auxiliary key."""
        return self.point_key(place) or self.aux_key(place)

    def dist(self, n1, n2) -> float:
        return abs(self.zpos[n1] - self.zpos[n2])


# -- the plan (structure only, the same at both levels) ----------------------------------------------
# What a construction line is made of: its base image, the known vectors chained on it (terms), and
# the one unknown component it leaves, along its direction.
@quick_init
@dataclass(frozen=True)
class KnownVector:
    """A known vector of a chain, in its true sense: ``value`` is what ``label`` names.

    The chain adds it ``sign`` times (-1 where the line starts from the other side of the joint's
    equation). ``reverse`` is (label, of) of the negative quantity where it has a name of its own
    (-A^n_WQ = A^n_QW, -V_B3/B4 = V_B4/B3, -2 omega_4 x V_B3/B4 = 2 omega_4 x V_B4/B3), else None
    (a circular path's V_rel^2/rho towards its centre is not the reverse motion's).
    """

    kind: str
    label: str
    value: object      # complex (exact run) or an array of complex samples (hand drafting)
    of: tuple
    sign: int = 1
    reverse: tuple | None = None

    @property
    def written(self) -> str:
        """As the equation writes it: "-2 omega_4 x V_A3/A4" where subtracted."""
        return ("-" if self.sign < 0 else "") + self.label


_UNNAMED = ("", ())   # a KnownVector's reverse in a replay that records nothing (its names unused)


@dataclass(frozen=True)
class CentripetalTerm:
    """The normal (centripetal) acceleration of W about Q on a rigid link:
    ``A^n_WQ = -omega_link^2 R_WQ``, towards Q. Nothing at velocity level."""

    link: str
    q: str
    w: str

    def known(self, run: "_Run") -> list[KnownVector]:
        if run.level == "velocity":
            return []
        g = run.g
        om = run.vel.rate[self.link]
        r = g.zpos[self.w] - g.zpos[self.q]
        if not run.record:   # a replay for its images alone (max_error): the value, no names
            return [KnownVector("normal", "", normal_acceleration(om, r), (), 1, _UNNAMED)]
        names = None if g.names else g._named.get(self)   # the mechanism's names, made once (where no
        if names is None:                                     # auxiliary point is named at this pose)
            nw, nq = g.name((self.link, self.w)), g.name((self.link, self.q))
            kw, kq = g.qkey((self.link, self.w)), g.qkey((self.link, self.q))
            names = f"A^n_{nw}{nq}", ("normal", self.link, kw, kq), (f"A^n_{nq}{nw}", ("normal", self.link, kq, kw))
            if not g.names:
                g._named[self] = names
        label, of, reverse = names
        return [KnownVector("normal", label, normal_acceleration(om, r), of, 1, reverse)]


@dataclass(frozen=True)
class JointMotionTerm:
    """The known part of a joint's relative motion at the place of W (link a's point relative to
    link b's, :meth:`_Run.joint_motion`: a driven or prescribed slip; at acceleration level the
    Coriolis term, the path's normal term, a contact's relative acceleration), added ``sign`` times."""

    rel: int
    sign: int
    w: str

    def known(self, run: "_Run") -> list[KnownVector]:
        sign = self.sign   # each term added sign times (KnownVector built anew: dataclasses.replace's checks cost more)
        return [KnownVector(k.kind, k.label, k.value, k.of, sign, k.reverse) for k in run.joint_motion(self.rel, self.w)]


class UnknownPart(NamedTuple):
    """A line's unknown component at a level: its label, the sign the line adds it with, what it
    shows (a Vector's ``of``) and the arrow's kind."""

    label: str
    sign: int
    of: tuple
    kind: str


@dataclass(frozen=True)
class RotationAbout:
    """The unknown of a rigid link's line: ``V_WQ = omega x R_WQ``, perpendicular to QW, of unknown
    magnitude (at acceleration level its tangential component ``A^t_WQ = alpha x R_WQ``)."""

    link: str
    q: str
    w: str
    sign: ClassVar[int] = 1   # the line adds it

    def describe(self, run: "_Run") -> UnknownPart:
        g, lk = run.g, self.link
        kw, kq = g.qkey((lk, self.w)), g.qkey((lk, self.q))
        name = f"{g.name((lk, self.w))}{g.name((lk, self.q))}"
        if run.level == "velocity":
            return UnknownPart(f"V_{name}", 1, ("difference", kw, kq), "relative")
        return UnknownPart(f"A^t_{name}", 1, ("tangential", lk, kw, kq), "tangential")

    def direction_words(self, run: "_Run") -> str:
        return f"⊥ {_segment(self.q, self.w)}"

    def zdir(self, g: _Geo) -> complex:
        """The line's unit direction at the pose of ``g``, perpendicular to QW: ``i R_WQ / |R_WQ|``."""
        r = g.zpos[self.w] - g.zpos[self.q]
        rn = abs(r)
        return complex(-r.imag / rn, r.real / rn)


@dataclass(frozen=True)
class SlipAlongPath:
    """The unknown of a joint's line: the slip ``V_Wa/Wb`` (``A_Wa/Wb``) of link a's point W
    relative to link b's, along the path (a slider, slot, sliding contact), added ``sign`` times."""

    rel: int
    sign: int
    w: str

    def describe(self, run: "_Run") -> UnknownPart:
        r = run.g.rels[self.rel]
        ka, kb, kk = run.rel_keys(r, self.w)
        return UnknownPart(f"{run.X}_{_relative_names(self.w, r.a, r.b)[0]}", self.sign, ("slip", ka, kb, r.b, kk),
                           "relative" if run.level == "velocity" else "slip")

    def direction_words(self, run: "_Run") -> str:
        return _path_reason(run.g, run.g.rels[self.rel], prose=True)

    def zdir(self, g: _Geo) -> complex:
        """The path's unit direction at the pose of ``g`` (the slider's, slot's or common tangent's)."""
        return g.rels[self.rel].zdir


@dataclass(frozen=True)
class ThroughAuxiliaryPoint:
    """The unknown of an auxiliary point S of a link reached from its point X: the unknown of X's
    own ``line`` plus ``V_SX`` (``A^t_SX``), both along that line (S is on X's normal)."""

    line: "_Line"
    link: str
    x: str
    s: str
    sign: ClassVar[int] = 1   # the line adds it

    def describe(self, run: "_Run") -> UnknownPart:
        inner = self.line.unknown.describe(run)
        vel = run.level == "velocity"
        ks, kx = (run.g.qkey((self.link, p)) for p in (self.s, self.x))
        t_of = ("difference", ks, kx) if vel else ("tangential", self.link, ks, kx)
        label = _sum([("-" if inner.sign < 0 else "") + inner.label, f"{run.X}{'' if vel else '^t'}_{self.s}{self.x}"])
        return UnknownPart(label, 1, ("sum", ((inner.sign, inner.of), (1, t_of))), "relative")

    def direction_words(self, run: "_Run") -> str:
        return self.line.unknown.direction_words(run)

    def zdir(self, g: _Geo) -> complex:
        """X's own line's direction (S lies on X's normal)."""
        return self.line.unknown.zdir(g)


@dataclass(frozen=True)
class _Line:
    """A construction line on an unknown image: the chain ``base`` + ``terms``, then along the
    unknown's direction (:meth:`zdir`: the pose's, so that a plan serves every pose of its mechanism).

    ``terms``: :class:`CentripetalTerm` and :class:`JointMotionTerm` (the known vectors chained);
    ``unknown``: :class:`RotationAbout`, :class:`SlipAlongPath` or :class:`ThroughAuxiliaryPoint`.
    """

    base: tuple
    terms: tuple
    unknown: object
    reason: str
    links: tuple

    @property
    def rigid_link(self) -> str | None:
        """The link whose rigidity this line uses (directly or through an auxiliary point's line)."""
        u = self.unknown
        if isinstance(u, ThroughAuxiliaryPoint):
            u = u.line.unknown
        return u.link if isinstance(u, RotationAbout) else None

    def zdir(self, g: _Geo) -> complex:
        """The line's unit direction at the pose of ``g``, as x + iy."""
        return self.unknown.zdir(g)

    def direction(self, g: _Geo) -> np.ndarray:
        """The line's unit direction at the pose of ``g``, as the contract's 2-vector."""
        z = self.unknown.zdir(g)
        return np.array((z.real, z.imag))


# The operations of the plan: each applies itself to a replay (_Run) of the construction.
@dataclass(frozen=True)
class DriverRate:
    """The driver's omega (alpha) is given."""

    link: str

    def apply(self, run: "_Run") -> None:
        drv = run.g.m.driver
        run.rate[self.link] = run._const(drv.omega if run.level == "velocity" else drv.alpha)


@dataclass(frozen=True)
class TurnsTogether:
    """A block and its straight guide turn together: ``link``'s omega is ``other``'s (alpha likewise)."""

    link: str
    other: str

    def apply(self, run: "_Run") -> None:
        run.rate[self.link] = run.rate[self.other]


@dataclass(frozen=True)
class RateFromImages:
    """omega = |qw| / |QW| with the sense of the turn: ``omega = Im((V_W - V_Q) / R_WQ)``
    (``alpha`` likewise from the acceleration images)."""

    link: str
    q: str
    w: str

    def apply(self, run: "_Run") -> None:
        r = run.g.zpos[self.w] - run.g.zpos[self.q]
        d = run.image((self.link, self.w)) - run.image((self.link, self.q))
        run.rate[self.link] = (d / r).imag


@dataclass(frozen=True)
class VelocityImage:
    """A point W of a link from its velocity (acceleration) image: the link's image is similar to
    the link, ``V_W = V_Q + omega x R_WQ`` (``A_W = A_Q + alpha x R_WQ - omega^2 R_WQ``)."""

    link: str
    q: str
    w: str

    def apply(self, run: "_Run") -> None:
        run._set((self.link, self.w), run.rigid_point(self.link, self.q, self.w))


@dataclass(frozen=True)
class KnownRelativeMotion:
    """A known relative vector (case 1): a rolling contact ``V_P3 = V_P4``, a prescribed slip or a
    slider driver ``V_F5 = V_F0 + V_F5/F0``: ``dst`` is ``src`` plus the joint's known motion."""

    dst: tuple
    src: tuple
    rel: int
    sign: int

    def apply(self, run: "_Run") -> None:
        tip, parts = run.chain(self.src, (JointMotionTerm(self.rel, self.sign, self.dst[1]),))
        run._set(self.dst, tip)
        run._draw(parts)


@dataclass(frozen=True)
class Intersection:
    """Case 2a: the unknown image lies on two lines through known images (two unknown magnitudes,
    e.g. ``V_B = V_A + V_BA = V_O4 + V_BO4``): where ``first`` and ``second`` meet."""

    target: tuple
    first: _Line
    second: _Line

    def apply(self, run: "_Run") -> None:
        run.meet(self.target, self.first, self.second)


@dataclass(frozen=True)
class TrialSolution:
    """False position: ``seed`` assumed on its one ``line``, the ``ops`` that follow replayed for two
    trial values, and the ``closure`` link (link, Q, W), rigid, fixes the assumed value."""

    seed: tuple
    line: _Line
    ops: tuple
    closure: tuple

    def apply(self, run: "_Run") -> None:
        run.trial(self.seed, self.line, self.ops, self.closure)


@dataclass
class _PStep:
    """A step while it is planned (``cls``: the :class:`PlanStep` it becomes, :meth:`frozen`)."""

    cls: type
    ops: list = field(default_factory=list)
    found: list = field(default_factory=list)      # canonical places located
    omegas: list = field(default_factory=list)     # links whose rate is fixed here
    lines: tuple = ()
    sine: float = 1.0
    target: tuple | None = None
    link: str | None = None
    rel: int | None = None

    def frozen(self) -> "PlanStep":
        return self.cls(tuple(self.ops), tuple(self.found), tuple(self.omegas), self.lines, self.sine,
                        self.target, self.link, self.rel)


class _Planner:
    """Orders the construction: which image is found next, from which known images."""

    def __init__(self, geo: _Geo):
        self.g = geo
        self.known = set()
        self.rk = {geo.frame}
        self.kp = {lk: [] for lk in geo.links}
        self.steps: list[_PStep] = []
        self.singular = None     # the first target whose two lines were parallel
        self.trial = False       # inside a trial solution: links' rigidity is tracked
        self.rigid_used = set()  # links whose rigidity located one of their images
        self.closure = None      # (link, Q, W): a link whose two images were located without it
        self.tape = _Tape()      # the decisions the pose made (the plan serves every pose that makes them alike)

    def decide(self, fn, *args):
        """``fn(geometry, *args)``: a decision that depends on the pose, recorded on the tape."""
        return self.tape.record(fn, self.g, args)

    # knowledge ---------------------------------------------------------------------------------
    def is_known(self, place) -> bool:
        c = self.g.canon(place)
        return c[0] == self.g.frame or c in self.known

    def full(self, lk) -> bool:
        return lk == self.g.frame or (lk in self.rk and bool(self.kp[lk]))

    def mark(self, place, step: _PStep):
        c = self.g.canon(place)
        if c in self.known:
            return
        self.known.add(c)
        step.found.append(c)
        for lk, n in self.g.group(c):
            if n not in self.kp[lk]:
                self.kp[lk].append(n)

    def ensure(self, place, step: _PStep):
        """Locate a place of a fully known link by that link's image (a coincident point)."""
        lk, n = place
        if self.is_known(place):
            return
        step.ops.append(VelocityImage(lk, self.kp[lk][0], n))
        self.mark(place, step)

    def settle(self, step: _PStep):
        """Rates that follow: a block turns with its straight guide; two images give omega."""
        changed = True
        while changed:
            changed = False
            for a, b in self.g.rate_eq:
                for x, y in ((a, b), (b, a)):
                    if x in self.rk and y not in self.rk:
                        step.ops.append(TurnsTogether(y, x))
                        self.rk.add(y)
                        step.omegas.append(y)
                        changed = True
            for lk in self.g.moving:
                if lk in self.rk or len(self.kp[lk]) < 2 or self.closure:
                    continue
                q = self.kp[lk][0]
                w = self.decide(_farthest, q, tuple(self.kp[lk][1:]))
                if w is not None:
                    if self.trial and lk not in self.rigid_used:   # over-determined: closes the trial
                        self.closure = (lk, q, w)
                        return
                    step.ops.append(RateFromImages(lk, q, w))
                    self.rk.add(lk)
                    step.omegas.append(lk)
                    changed = True

    def add(self, step: _PStep):
        self.settle(step)
        self.steps.append(step)

    # the plan ----------------------------------------------------------------------------------
    def run(self) -> list[PlanStep]:
        """The plan: every step, in order, frozen."""
        g = self.g
        s0 = _PStep(FrameAtOrigin)
        for n in g.places(g.frame):
            self.mark((g.frame, n), s0)
        self.add(s0)
        drv = g.m.driver
        if not drv.is_slider:
            s = _PStep(DriverStep, ops=[DriverRate(drv.link)], omegas=[drv.link], link=drv.link)
            self.rk.add(drv.link)
            self._image_ops(drv.link, s)
            self.add(s)
        self._loop()
        return [st.frozen() for st in self.steps]

    def _loop(self):
        """Steps until every image is located (or, in a trial, until it closes or stalls)."""
        g = self.g
        while not self.closure:
            if self._equality() or self._image():
                continue
            if all(self.full(lk) and all(self.is_known((lk, n)) for n in g.places(lk)) for lk in g.links):
                return
            if self._intersection() or self._auxiliary():
                continue
            if self.trial:
                return
            if self.singular or not self._trial():   # two parallel lines through known images: singular
                self._fail()

    def _save(self):
        g = self.g
        return (set(self.known), set(self.rk), {k: list(v) for k, v in self.kp.items()}, list(self.steps),
                self.singular, dict(g.pos), dict(g.zpos), {k: list(v) for k, v in g.extra.items()}, dict(g.names))

    def _restore(self, saved):
        g = self.g
        self.known, self.rk, self.kp, self.steps, self.singular, g.pos, g.zpos, g.extra, g.names = saved

    def _trial(self) -> bool:
        """Trial solution (false position): assume an image on its one line, construct on, close.

        The unknown image x = tip + tau e (tip, e: its one line) is assumed; the construction
        goes on until some link has two images located without its own rigidity. Everything
        is linear in tau, so two trial values give the closing condition exactly. Of the
        possible assumptions, the one whose construction is best conditioned is taken.
        """
        self.tape.usable = False   # which trial is best compares whole constructions: planned afresh each pose
        best = None
        for t in self._targets(every=True):
            lines = self.lines_for(t)
            if not lines:
                continue
            saved = self._save()
            head = self._try_seed(t, lines[0])
            if head is not None and (best is None or head.sine > best[0]):
                best = (head.sine, t, lines[0])
            self._restore(saved)
        if best is None:
            return False
        self._try_seed(best[1], best[2])
        return True

    def _try_seed(self, t, seed) -> _PStep | None:
        self.trial, self.closure = True, None
        self.rigid_used = {seed.rigid_link} if seed.rigid_link else set()
        head = _PStep(TrialSolutionStep, lines=(seed,), target=t)
        self.mark(t, head)
        self.steps.append(head)
        n0 = len(self.steps)
        self.settle(head)
        self._loop()
        self.trial = False
        if self.closure is None:
            return None
        lk, q, w = self.closure
        self.closure = None
        sub = self.steps[n0:]
        del self.steps[n0:]
        head.ops = [TrialSolution(t, seed, tuple(op for st in [head] + sub for op in st.ops), (lk, q, w)),
                    RateFromImages(lk, q, w)]
        head.found += [p for st in sub for p in st.found]
        head.omegas = [x for st in [head] + sub for x in st.omegas if x != lk] + [lk]
        head.sine = min([1.0] + [st.sine for st in sub])   # the closure's own sine is added when drawn
        self.rk.add(lk)
        self.rigid_used = set()
        self.settle(head)
        return head

    def _image_ops(self, lk, step):
        self.rigid_used.add(lk)
        base = self.kp[lk][0]
        for n in self.g.places(lk):
            if not self.is_known((lk, n)):
                step.ops.append(VelocityImage(lk, base, n))
                self.mark((lk, n), step)

    def _image(self) -> bool:
        for lk in self.g.moving:
            if self.full(lk) and any(not self.is_known((lk, n)) for n in self.g.places(lk)):
                s = _PStep(VelocityImageStep, link=lk)
                self._image_ops(lk, s)
                self.add(s)
                return True
        return False

    def _equality(self) -> bool:
        """A rolling contact, a prescribed slip or a slider driver: a known relative vector."""
        for i, r in enumerate(self.g.rels):
            if not r.exact:
                continue
            for n in self._rel_points(r):
                pa, pb = (r.a, n), (r.b, n)
                for src, dst, sign in ((pb, pa, 1), (pa, pb, -1)):
                    if self.is_known(dst) or not (self.is_known(src) or self.full(src[0])):
                        continue
                    if r.at is None and (self.full(dst[0]) or (n != r.prefer and self.g.grounded(src))):
                        continue   # only to give a link an image it lacks (no spare points)
                    s = _PStep(SliderDriverStep if r.source == "drive" else KnownMotionStep, target=self.g.canon(dst), rel=i)
                    self.ensure(src, s)
                    s.ops.append(KnownRelativeMotion(dst, src, i, sign))
                    self.mark(dst, s)
                    self.add(s)
                    return True
        return False

    def _rel_points(self, r: _Rel) -> list:
        """Where a known relative motion is applied: its point, or (a straight slider driver's,
        which holds at every coincident point) its block's point first, then the known ones."""
        if r.at is not None:
            return [r.at]
        return list(dict.fromkeys([r.prefer] + self.kp[r.a] + self.kp[r.b]))

    def lines_on(self, place) -> list[_Line]:
        """Every line through known images that the unknown image of ``place`` lies on."""
        g = self.g
        out = []
        for lk, n in g.group(place):
            if lk not in self.rk and lk != g.frame:
                q = self.decide(_apart, n, tuple(self.kp[lk]))
                if q is not None:
                    out.append(_Line((lk, q), (CentripetalTerm(lk, q, n),), RotationAbout(lk, q, n),
                                     f"perpendicular to {q}{n}", (lk,)))
            for i, r in enumerate(g.rels):
                if r.exact or r.at not in (None, n) or lk not in (r.a, r.b):
                    continue
                if r.source == "contact" and g.m.contacts[r.index].centres is not None:
                    continue   # a sliding contact with centres: the equivalent linkage's lines ('centre')
                partner, sign = (r.b, 1) if lk == r.a else (r.a, -1)
                pp = (partner, n)
                if self.is_known(pp) or self.full(partner):
                    out.append(_Line(pp, (JointMotionTerm(i, sign, n),), SlipAlongPath(i, sign, n),
                                     _path_reason(g, r), (r.a, r.b)))
        return out

    def lines_for(self, place) -> list[_Line]:
        """The lines of :meth:`lines_on` (a link's rigidity, a joint's path) and, for a slider
        driver whose other side is not located yet, that side's lines carried over, offset by the
        known slip: a block driven along a turning guide, ``V_A3 = V_O4 + V_A4O4 + V_A3/A4``, lies
        on the line through o4 + V_A3/A4 perpendicular to O4A (case 2a with a known slip).
        """
        g = self.g
        out = self.lines_on(place)
        c = g.canon(place)
        for lk, n in g.group(place):
            for i, r in enumerate(g.rels):
                if r.source != "drive" or r.at not in (None, n) or lk not in (r.a, r.b):
                    continue   # (contacts keep the equivalent linkage's lines, as the books draw them)
                partner, sign = (r.b, 1) if lk == r.a else (r.a, -1)
                pp = (partner, n)
                if g.canon(pp) == c or self.is_known(pp) or self.full(partner):
                    continue   # known: an equality step, not a line
                for ln in self.lines_on(pp):
                    out.append(_Line(ln.base, ln.terms + (JointMotionTerm(i, sign, n),), ln.unknown,
                                     f"{ln.reason}, offset by the driver's slip of {n}{r.a} on {n}{r.b}",
                                     tuple(dict.fromkeys(ln.links + (r.a, r.b)))))
        return out

    def _targets(self, every: bool = False):
        """Unknown places worth locating, in textbook order (``every``: of any link not fully known)."""
        g = self.g
        seen = set()
        order = list(g.m.point_order) + [n for lk in g.links for n in g.extra[lk]]
        carriers = {}   # point -> the moving links that carry it, in link order
        for lk in g.moving:
            for n in g.places(lk):
                carriers.setdefault(n, []).append(lk)
        cands = [(lk, n) for n in order for lk in carriers.get(n, ())]
        for r in g.rels:
            if r.at is not None:
                cands += [(r.a, r.at), (r.b, r.at)]
        for r in g.rels:
            if r.at is None:
                for x, y in ((r.a, r.b), (r.b, r.a)):
                    cands += [(y, n) for n in self.kp[x]]
        if every:
            cands += [(lk, n) for lk in g.moving for n in g.places(lk)]
        for p in cands:
            c = g.canon(p)
            if c not in seen and not self.is_known(p) and not self.full(p[0]):
                seen.add(c)
                yield c

    def _intersection(self) -> bool:
        for t in self._targets():
            lines = tuple(self.lines_for(t))
            best = self.decide(_best_pair, lines) if len(lines) > 1 else None
            if best is None:
                continue
            l1, l2 = lines[best[0]], lines[best[1]]
            sine = _pair_sine(self.g, l1, l2)
            if not best[2]:   # closer to parallel than SINE_LIMIT
                self.singular = self.singular or (t, l1, l2, sine)
                continue
            s = _PStep(IntersectionStep, lines=(l1, l2), sine=sine, target=t)
            for ln in (l1, l2):
                self.ensure(ln.base, s)
                if ln.rigid_link:
                    self.rigid_used.add(ln.rigid_link)
            s.ops.append(Intersection(t, l1, l2))
            self.mark(t, s)
            self.add(s)
            return True
        return False

    def _auxiliary(self) -> bool:
        """A link T with no known image: the point S of T where two of its points' lines meet."""
        g = self.g
        groups = []   # (link, ((point, its first line), ...)) for each link T that may have one
        for lk in g.moving:
            if lk in self.rk or self.kp[lk] or len(g.places(lk)) < 3:   # S must locate a third point
                continue
            one = []
            for n in g.places(lk):
                ls = self.lines_for((lk, n))
                if ls:
                    one.append((n, ls[0]))
            groups.append((lk, tuple(one)))
        best = self.decide(_auxiliary_choice, tuple(groups))
        if best is None:
            return False
        lk, one = groups[best[0]]
        (x, lx), (y, ly) = one[best[1]], one[best[2]]
        name = named("S", lk)
        while name in g.pos:
            name += "'"
        self.decide(_place_auxiliary, lk, name, x, lx, y, ly)
        sine = _normals_meet(g, x, lx, y, ly)[1]
        aux = [_Line(ln.base, ln.terms + (CentripetalTerm(lk, p, name),), ThroughAuxiliaryPoint(ln, lk, p, name),
                     ln.reason + f" (auxiliary point {name} of link {lk} on the normal through {p})",
                     ln.links + (lk,)) for p, ln in ((x, lx), (y, ly))]
        s = _PStep(AuxiliaryPointStep, lines=tuple(aux), sine=sine, target=(lk, name), link=lk)
        self.rigid_used.add(lk)
        for ln in aux:
            self.ensure(ln.base, s)
            if ln.rigid_link:
                self.rigid_used.add(ln.rigid_link)
        s.ops.append(Intersection((lk, name), aux[0], aux[1]))
        self.mark((lk, name), s)
        self.add(s)
        return True

    def _fail(self):
        g = self.g
        if self.singular:
            t, l1, l2, sine = self.singular
            links = tuple(dict.fromkeys(l1.links + l2.links))
            raise SingularPoseError(
                f"singular pose: the construction lines locating the image of {g.name(t)} are parallel "
                f"({l1.reason}; {l2.reason}; sine {sine:.2g})", where="pose", file=g.m.source, links=links,
                hint=singular_hint(g.m))
        left = [lk for lk in g.moving if not self.full(lk)]
        raise ConstructionError(
            f"no graphical construction order: links {', '.join(left)} form a group that neither a dyad "
            f"(two lines through known images), an auxiliary point nor a trial solution determines",
            where="links",
            file=g.m.source, hint="the analytic results (velpoly solve) are still exact")


class _Tape:
    """The decisions a plan was made with that depend on the pose, each ``(fn, args, outcome)`` once, in
    the order made (with the auxiliary points placed on the way, :func:`_place_auxiliary`).

    The planner reads the pose only through them (the directions, sines and auxiliary points' places
    are computed at each pose from the plan's lines): a pose where every one gives the same outcome
    (:meth:`holds`) gets the same plan from the planner. ``usable`` is False where the planner
    compared whole trial constructions (a trial solution), which are not recorded.
    """

    def __init__(self):
        self.entries, self.seen, self.usable = [], set(), True

    def record(self, fn, g: _Geo, args):
        out = fn(g, *args)
        if self.usable and (fn, args) not in self.seen:
            self.seen.add((fn, args))
            self.entries.append((fn, args, out))
        return out

    def holds(self, g: _Geo) -> bool:
        """Whether the pose of ``g`` makes every decision alike (placing the auxiliary points in g)."""
        try:
            for fn, args, out in self.entries:
                if fn(g, *args) != out:
                    return False
        except (ArithmeticError, ValueError):   # a degenerate pose: planned afresh, as without the tape
            return False
        return True


# The planner's decisions that depend on the pose (the rest follows from the mechanism alone): each is a
# function of the pose's geometry and of what the plan knows, giving a plain outcome (a point's name, a
# pair of indices, a flag), so that another pose can be checked to give the same ones (:class:`_Tape`).
def _apart(g: _Geo, n, cands):
    """The first of ``cands`` (points of a link with known images) apart from n (to draw a line ⊥ QN)."""
    for q in cands:
        if g.dist(q, n) > g.tol:
            return q
    return None


def _farthest(g: _Geo, q, cands):
    """The point of ``cands`` farthest from q, which with q gives a link's rate; None if all are at q."""
    w = max(cands, key=lambda n: g.dist(q, n))
    return w if g.dist(q, w) > g.tol else None


def _normals_meet(g: _Geo, x, lx, y, ly) -> tuple:
    """(S, sine): where the normals at x and y to their lines ``lx`` and ``ly`` meet (S None where they
    are parallel) and the sine of their angle."""
    s, _, _, sine = G.intersect_lines(g.pos[x], perp(lx.direction(g)), g.pos[y], perp(ly.direction(g)))
    return s, sine


def _auxiliary_choice(g: _Geo, groups):
    """(k, i, j): of each link's points with a line (``groups``), the two whose normals meet at the
    link's auxiliary point S best: the instant centre (both lines through O_v, Kennedy) unless badly
    conditioned, else the largest sine; None where no two normals meet at SINE_LIMIT or better."""
    best = None
    for k, (_, one) in enumerate(groups):
        for i in range(len(one)):
            for j in range(i + 1, len(one)):
                (x, lx), (y, ly) = one[i], one[j]
                s, sine = _normals_meet(g, x, lx, y, ly)
                if s is None or sine < SINE_LIMIT:
                    continue
                pole = g.grounded(lx.base) and g.grounded(ly.base) and sine >= 0.05
                if best is None or (pole, sine) > best[0]:
                    best = ((pole, sine), k, i, j)
    return None if best is None else best[1:]


def _place_auxiliary(g: _Geo, lk, name, x, lx, y, ly) -> None:
    """Add the auxiliary point ``name`` of link lk to the pose, where the normals at x and y meet."""
    spos = _normals_meet(g, x, lx, y, ly)[0]
    g.pos[name] = np.asarray(spos, float)
    g.zpos[name] = _z(spos)
    g.extra[lk].append(name)
    g.names[(lk, name)] = name


def _pair_sine(g: _Geo, l1, l2) -> float:
    """|sin| of the angle between two construction lines at the pose of ``g``."""
    d, e = l1.zdir(g), l2.zdir(g)
    return abs(d.real * e.imag - d.imag * e.real)


def _best_pair(g: _Geo, lines):
    """(i, j, regular): the two lines meeting at the largest angle (the first such pair), and whether
    that angle's sine reaches SINE_LIMIT."""
    dirs = [ln.zdir(g) for ln in lines]
    best = None
    for i in range(len(lines)):
        d = dirs[i]
        for j in range(i + 1, len(lines)):
            e = dirs[j]
            sine = abs(d.real * e.imag - d.imag * e.real)
            if best is None or sine > best[2]:
                best = (i, j, sine)
    return best[0], best[1], not best[2] < SINE_LIMIT


def _path_reason(g: _Geo, r: _Rel, prose: bool = False) -> str:
    """The direction of a joint's path line: the construction line's reason ("parallel to the path of
    F on 0"), or with ``prose`` as a caption writes it ("∥ the path of F on link 0")."""
    m = g.m
    par, perp, name, link = ("∥", "⊥", point_text, "link ") if prose else ("parallel to", "perpendicular to", str, "")
    if r.source == "slider":
        return f"{par} the path of {name(m.sliders[r.index].point)} on {link}{r.b}"
    if r.source == "slot":
        s = m.slots[r.index]
        return f"along the slot of {link}{s.slot} at {name(s.pin)}"
    if r.source == "centre":
        if r.centre is None:
            return f"{par} the flat of {link}{r.b}" + ("" if prose else f" (the path of {r.at} on {r.b})")
        if prose:
            return f"{perp} {_segment(r.centre, r.at)} (a circle about {name(r.centre)} on link {r.b})"
        return f"{perp} {r.centre}{r.at} (the path of {r.at} on {r.b}, a circle about {r.centre})"
    return f"along the common tangent at {name(r.at)}"


# -- evaluating the plan: exact, or perturbed like a hand drawing ---------------------------------
@functools.lru_cache(maxsize=4096)   # a pure function of three names, asked again at every pose
def _relative_names(w: str, a: str, b: str) -> tuple[str, str]:
    """Link a's point W relative to link b's, and back, as names: ("B3/B4", "B4/B3")."""
    return relative(named(w, a), named(w, b)), relative(named(w, b), named(w, a))


def _z(v) -> complex:
    """The 2-vector (x, y) as the complex number x + iy."""
    return complex(v[0], v[1])



class _Run:
    """One replay of the plan at a level ('velocity' or 'acceleration') over n samples.

    Vectors are complex numbers x + iy (k x v = i v, the cross product R x V = Im(conj(R) V)):
    plain Python complex numbers in the exact run, numpy arrays of n samples in the
    hand-drafting run; the same code serves both. Rates are floats or arrays likewise.
    """

    def __init__(self, geo: _Geo, level: str, vel: "_Run | None" = None, n: int = 1,
                 rng=None, angle: float = 0.0, point: float = 0.0, record: bool = False):
        self.g, self.level, self.vel, self.n = geo, level, vel, n
        self.rng, self.angle, self.point = rng, angle, point
        self.zero = 0j if rng is None else np.zeros(n, complex)   # the image of a point at rest
        self.img, self.rate = {}, {geo.frame: self._const(0.0)}
        self.record = record
        self.sine = 1.0        # conditioning of the last trial closure
        self.lines, self.vectors = [], []
        self.X = "V" if level == "velocity" else "A"
        self.origin = "O_v" if level == "velocity" else "O_a"

    def _const(self, x: float):
        """A rate known exactly: a float, or the same value for every sample."""
        return x if self.rng is None else np.full(self.n, x)

    # drafting errors (none in the exact run)
    def _turn(self, v):
        """A drawn direction or vector, turned by the drafting error."""
        if self.rng is None:
            return v
        return v * np.exp(1j * self.rng.uniform(-self.angle, self.angle, self.n))

    def _mark(self, p):
        if self.rng is None:
            return p
        e = self.rng.uniform(-self.point, self.point, (self.n, 2))
        return p + (e[:, 0] + 1j * e[:, 1])

    def image(self, place):
        c = self.g.canon(place)
        return self.zero if c[0] == self.g.frame else self.img[c]

    def _set(self, place, v):
        self.img[self.g.canon(place)] = v

    def label(self, place) -> str:
        """The image's label: b, b4, s3 (primed in an acceleration polygon)."""
        return lower_name(self.g.name(place)) + ("'" if self.level == "acceleration" else "")

    def base_label(self, place) -> str:
        """The label of a line's base image: the origin for points that do not move."""
        return self.origin if self.g.grounded(place) else self.label(place)

    # A recording run keeps its arrows and lines with their points as x + iy: :func:`_assemble` makes
    # every 2-vector of the polygon in one array (a numpy call per 2-vector was a tenth of the polygons)
    def _vec(self, tail, head, kind, label, of=()):
        if self.record:
            self.vectors.append((tail, head, kind, label, of))

    def _line(self, base, direction, base_label, reason):
        self.lines.append((base, direction, base_label, reason))

    # known terms -----------------------------------------------------------------------------------
    def terms(self, terms) -> list[KnownVector]:
        """The known vectors of a chain (:class:`CentripetalTerm`, :class:`JointMotionTerm`), in order."""
        return [k for t in terms for k in t.known(self)]

    def term_labels(self, terms) -> list:
        """The chain's terms as written in its equation: "-2 omega_4 x V_A3/A4" where subtracted."""
        return [k.written for k in self.terms(terms)]

    def rel_keys(self, r: _Rel, w) -> tuple:
        """The keys of a joint's two places at w (a's, b's) and of its relative path's centre."""
        g = self.g
        k = g.qkey((r.b, r.centre)) if r.centre is not None else None
        return g.qkey((r.a, w)), g.qkey((r.b, w)), k

    def joint_motion(self, i, w) -> list[KnownVector]:
        """Known relative motion of a joint, a relative to b, at the place of w (``reverse``: see
        :class:`KnownVector`).

        Blocks, pins in slots and the equivalent linkage's centres of curvature:
        ``A_a = A_b + 2 omega_b x V_a/b (Coriolis) + V_a/b^2 / rho (towards the centre of a
        circular path) + A_a/b (slip along the path)``. An exact contact (rolling, or a
        prescribed slip): ``A_Pa = A_Pb + 2 omega_b x V_Pa/Pb + A_Pa/Pb``, the last the contact
        points' relative acceleration on b (along the common normal, from the equivalent linkage).
        """
        g, r = self.g, self.g.rels[i]
        m = g.m
        rel, rrel = _relative_names(w, r.a, r.b)
        ka, kb, kk = self.rel_keys(r, w)
        slip_of = ("slip", ka, kb, r.b, kk)
        if self.level == "velocity":
            back = (f"V_{rrel}", ("slip", kb, ka, r.b, kk))   # V_b - V_a
            if r.source == "drive":
                return [KnownVector("slip", f"V_{rel}", m.driver.speed * _z(r.direction), slip_of, 1, back)]
            if r.source == "contact" and m.contacts[r.index].slip:
                return [KnownVector("slip", f"V_{rel}", m.contacts[r.index].slip * _z(r.direction), slip_of, 1, back)]
            return []
        vrel = self.vel.image((r.a, w)) - self.vel.image((r.b, w))
        out = []
        cor = self.coriolis_term(r, w, vrel) if r.b != g.frame else None   # a guide on the frame has none
        # the slip reversed (A_b - A_a + 2 omega_b x V_a/b) is b's slip on a only on a straight path
        back = (f"A_{rrel}", ("slip", kb, ka, r.b, None)) if kk is None else None
        if r.source != "contact":
            if r.source == "drive":
                out.append(KnownVector("slip", f"A_{rel}", m.driver.accel * _z(r.direction), slip_of, 1, back))
            if r.b != g.frame:   # a guide on the frame has no Coriolis term: 2 omega x V_rel
                out.append(cor)
            if r.centre is not None:   # a circular relative path: V_rel^2 / rho towards its centre
                k = g.zpos[r.centre] - g.zpos[w]
                rho = abs(k)
                speed2 = vrel.real ** 2 + vrel.imag ** 2
                out.append(KnownVector("normal", f"A^n_{rel}", speed2 / rho * (k / rho), ("path-normal", ka, kb, kk)))
        elif m.contacts[r.index].kind == "rolling":   # no slip: the contact points' relative acceleration
            out.append(KnownVector("relative", f"A_{rel}", self._contact_normal(r, w, vrel), ("difference", ka, kb), 1,
                                   (f"A_{rrel}", ("difference", kb, ka))))
        else:   # a prescribed slip: Coriolis, and the rest of the relative acceleration on b
            rest = self._contact_normal(r, w, vrel)
            if r.b != g.frame:
                out.append(cor)
                rest = rest - cor.value
            out.append(KnownVector("relative", f"A_{rel}", rest, ("slip", ka, kb, r.b, None), 1,
                                   (f"A_{rrel}", ("slip", kb, ka, r.b, None))))
        return out

    def coriolis_term(self, r: _Rel, w, vrel) -> KnownVector:
        """The Coriolis term of link a's point W moving relative to link b (the guide, slot or other
        profile): ``2 omega_b x V_Wa/Wb``, with V_Wa/Wb = ``vrel`` from the velocity polygon."""
        ka, kb, _ = self.rel_keys(r, w)
        rel, rrel = _relative_names(w, r.a, r.b)
        return KnownVector("coriolis", f"2 omega_{r.b} x V_{rel}", coriolis_term(self.vel.rate[r.b], vrel),
                           ("coriolis", r.b, ka, kb), 1, (f"2 omega_{r.b} x V_{rrel}", ("coriolis", r.b, kb, ka)))

    def _contact_normal(self, r: _Rel, w, vrel):
        """(A_P(a) - A_P(b)) . u u from the equivalent linkage through the centres of curvature.

        The centres Ca, Cb stay D = la - lb apart (la = (P - Ca).u, lb = (P - Cb).u), the
        common normal u turns at omega_v with la omega_a - lb omega_b - D omega_v = slip, so
        ``A_Cb - A_Ca = alpha_v x R - omega_v^2 D u`` and the normal component of the contact
        points' relative acceleration is ``omega_v^2 D - omega_a^2 la + omega_b^2 lb``. A flat
        profile is the limit of an infinite radius: ``-la (omega_a - omega_b)^2 - 2 omega_b slip``
        (flat on b) or ``lb (omega_a - omega_b)^2 - 2 omega_a slip`` (flat on a).
        """
        g, c = self.g, self.g.m.contacts[r.index]
        t = _z(r.direction)
        u = -1j * t                       # t = u turned +90 deg
        ca, cb = c.centres
        p = g.zpos[w]
        wa, wb = self.vel.rate[r.a], self.vel.rate[r.b]
        slip = (vrel * t.conjugate()).real
        if ca is None:
            lb = _dot(p - g.zpos[cb], u)
            k = lb * (wa - wb) ** 2 - 2.0 * wa * slip
        elif cb is None:
            la = _dot(p - g.zpos[ca], u)
            k = -la * (wa - wb) ** 2 - 2.0 * wb * slip
        else:
            la, lb = _dot(p - g.zpos[ca], u), _dot(p - g.zpos[cb], u)
            wv = (la * wa - lb * wb - slip) / (la - lb)
            k = wv ** 2 * (la - lb) - wa ** 2 * la + wb ** 2 * lb
        return k * u

    # operations ------------------------------------------------------------------------------------
    def chain(self, base, terms, forward: bool = False, known=None) -> tuple:
        """The tip of base image + known terms, and the arrows drawn: (tip, [(kind, label, tail, head, of)]).

        Every arrow points in the true sense of what its label names and they run tip to tail:
        a subtracted term (the line starts from the known image on the other side of the
        equation, b3' to find b4' in ``A_B3 = A_B4 + 2 omega_4 x V_B3/B4 + A_B3/B4``) is drawn
        back from the image, ending at it, and comes first; added terms follow, forwards.
        ``forward`` (a line that subtracts some terms and adds others, see :meth:`mixed`): a
        subtracted term is drawn forwards as the negative quantity it equals, under that
        quantity's own name (-V_A3/A4 is V_A4/A3, -A^n_SA is A^n_AS), so that the arrows run tip
        to tail from the base image to the image found; only a term with no such name (a
        circular path's V_rel^2/rho) is still drawn back from the base image. ``known``: the terms'
        known vectors where the caller has them already.
        """
        tip = self.image(base)
        parts = []
        ts = self.terms(terms) if known is None else known
        drawn_back = [t.sign < 0 and not (forward and t.reverse) for t in ts]
        back = [t for t, b in zip(ts, drawn_back) if b]
        ahead = [t if t.sign > 0 else KnownVector(t.kind, t.reverse[0], -t.value, t.reverse[1])
                 for t, b in zip(ts, drawn_back) if not b]
        for t in back:
            new = self._mark(tip - self._turn(t.value))
            parts.append((t.kind, t.label, new, tip, t.of))
            tip = new
        for t in ahead:
            new = self._mark(tip + self._turn(t.value))
            parts.append((t.kind, t.label, tip, new, t.of))
            tip = new
        return tip, parts

    def mixed(self, ln: _Line, known=None) -> bool:
        """Whether the line's chain both subtracts and adds (its known terms and its unknown at this
        level): then no order of true-sense arrows runs tip to tail, and :meth:`chain` draws the
        subtracted ones as their negatives (an auxiliary point reached through a driven slip:
        ``V_S4 = V_O2 + V_A2O2 - V_A3/A4 + V_S4A4``; a block's line offset by a slip it subtracts)."""
        signs = {t.sign for t in (self.terms(ln.terms) if known is None else known)} | {ln.unknown.sign}
        return len(signs) > 1

    def _draw(self, parts):
        for k, lab, t0, t1, of in parts:
            self._vec(t0, t1, k, lab, of)

    def rigid_point(self, lk, q, w):
        """V_W = V_Q + omega x R_WQ  (A_W = A_Q + alpha x R_WQ - omega^2 R_WQ)."""
        r = self.g.zpos[w] - self.g.zpos[q]
        base = self.image((lk, q))
        rate = self.rate[lk]
        if not self.record:   # the images alone (max_error): the same arithmetic, no arrows named
            if self.level == "velocity":
                return self._mark(base + self._turn(rate_cross(rate, r)))
            mid = self._mark(base + self._turn(normal_acceleration(self.vel.rate[lk], r)))
            return self._mark(mid + self._turn(rate_cross(rate, r)))
        name_w, name_q = self.g.name((lk, w)), self.g.name((lk, q))
        kw, kq = self.g.qkey((lk, w)), self.g.qkey((lk, q))
        if self.level == "velocity":
            tip = self._mark(base + self._turn(rate_cross(rate, r)))
            self._vec(base, tip, "relative", f"V_{name_w}{name_q}", ("difference", kw, kq))
            return tip
        om = self.vel.rate[lk]
        mid = self._mark(base + self._turn(normal_acceleration(om, r)))
        tip = self._mark(mid + self._turn(rate_cross(rate, r)))
        self._vec(base, mid, "normal", f"A^n_{name_w}{name_q}", ("normal", lk, kw, kq))
        self._vec(mid, tip, "tangential", f"A^t_{name_w}{name_q}", ("tangential", lk, kw, kq))
        return tip

    def meet(self, target, l1, l2):
        """Case 2a: the image of ``target`` where the two lines meet (each drawn from the tip of its chain)."""
        tips, dirs = [], []
        for ln in (l1, l2):
            known = self.terms(ln.terms)
            tip, parts = self.chain(ln.base, ln.terms, self.mixed(ln, known), known)
            tips.append(tip)
            dirs.append(self._turn(ln.zdir(self.g)))
            self._draw(parts)
            if self.record:
                label = _sum([self.base_label(ln.base)] + self.term_labels(ln.terms))
                self._line(tip, ln.zdir(self.g), label, ln.reason)
        x, _, _ = self._intersect(tips[0], dirs[0], tips[1], dirs[1])
        if x is None:   # the planner checked the directions; only a degenerate pose gets here
            raise SingularPoseError(f"parallel construction lines for {self.g.name(target)}",
                                    where="pose", file=self.g.m.source, links=l1.links + l2.links)
        x = self._mark(x)
        self._set(target, x)
        if self.record:
            for ln, tip in zip((l1, l2), tips):
                self.vectors.append(self.unknown_vector(ln, tip, x))

    def _intersect(self, p, d, q, e):
        """(x, s, sine): where p + s d meets q + t e (:func:`velpoly.geometry.intersect_lines`).

        x is None when the lines are parallel (sine below SINE_LIMIT) in the exact run.
        """
        if self.rng is None:
            x, s, _, sine = G.intersect_lines_z(p, d, q, e)
            if x is None or sine < SINE_LIMIT:
                return None, None, sine
            return x, s, sine
        xy = [np.stack((v.real, v.imag), axis=-1) for v in np.broadcast_arrays(p, d, q, e)]
        x, s, _, sine = G.intersect_lines_batch(*xy)
        return x[:, 0] + 1j * x[:, 1], s, sine

    def trial(self, seed, line, sub, closure):
        """Two trial polygons with x = tip + tau e, then tau from the closing link.

        The closing link (W, Q) has its images located without its own rigidity; it needs
        (V_W - V_Q) . R_WQ = 0 (A: = -omega^2 |R_WQ|^2): the locus of V_W - V_Q over the trial
        values, drawn from the origin, meets the line perpendicular to R_WQ at the true value.
        """
        lk, q, w = closure
        known = self.terms(line.terms)
        tip, parts = self.chain(line.base, line.terms, self.mixed(line, known), known)
        e = self._turn(line.zdir(self.g))
        known = [abs(v) for v in self.img.values()] + [abs(tip), self._const(self._level_scale())]
        tau1 = np.maximum(np.max(known, axis=0), 1e-300)
        start, record = (dict(self.img), dict(self.rate)), self.record
        self.record = False
        z = []
        for tau in (0.0, tau1):
            self.img, self.rate = dict(start[0]), dict(start[1])
            self._set(seed, tip + tau * e)
            for o in sub:
                o.apply(self)
            z.append(self.image((lk, w)) - self.image((lk, q)))
        r = self.g.zpos[w] - self.g.zpos[q]
        rn = abs(r)
        c = 0.0 if self.level == "velocity" else normal_acceleration(self.vel.rate[lk], rn)
        locus = z[1] - z[0]
        target = c * (r / rn) + self.zero
        x, s, sine = self._intersect(z[0], locus, target, self._turn(1j * r))
        self.sine = float(np.min(sine))
        if x is None:
            raise SingularPoseError(
                f"singular pose: the trial solution for {self.g.name(seed)} does not close on link {lk} "
                f"(the locus of {self.X}_{w}{q} is parallel to the line perpendicular to {q}{w})",
                where="pose", file=self.g.m.source, links=(lk,))
        tau = s * tau1
        self.img, self.rate, self.record = dict(start[0]), dict(start[1]), record
        found = self._mark(tip + tau * e)
        self._set(seed, found)
        if record:
            self._draw(parts)
            self._line(z[0], locus / abs(locus), self.origin, f"locus of {self.X}_{w}{q} over the trial values")
            self._line(target, 1j * r / rn, self.origin, f"perpendicular to {q}{w}: link {lk} is rigid")
            self._line(tip, line.zdir(self.g), _sum([self.base_label(line.base)] + self.term_labels(line.terms)),
                       line.reason + " (the trial image's line)")
            self.vectors.append(self.unknown_vector(line, tip, found))
        for o in sub:
            o.apply(self)

    def _level_scale(self) -> float:
        """A speed (acceleration) of the mechanism's size from the driver and the known terms alone,
        so that a trial value is not lost in rounding when every image located so far is zero
        (a slider driver or a prescribed slip is the only motion known)."""
        g, m = self.g, self.g.m
        drv = m.driver
        slips = [abs(c.slip) for c in m.contacts if c.slip]
        if self.level == "velocity":
            return max([abs(drv.speed) if drv.is_slider else abs(drv.omega) * g.size] + slips)
        vel = self.vel
        w = max([float(np.max(np.abs(x))) for x in vel.rate.values()] + [0.0])
        v = max([float(np.max(np.abs(x))) for x in vel.img.values()] + slips + [0.0])
        acc = abs(drv.accel) if drv.is_slider else abs(drv.alpha) * g.size
        return max(acc, w * w * g.size, w * v)

    def unknown(self, ln: _Line) -> "UnknownPart":
        """The line's unknown component, the line adding ``sign`` times it.

        V_BA, A^t_BA (the rigid link's), V_B3/B4 or A_B3/B4 (the slip of a relative to b,
        subtracted where the line starts from a's image), or for an auxiliary point S reached
        from X the sum of X's unknown and V_SX (A^t_SX), which lie along one line.
        """
        return ln.unknown.describe(self)

    def unknown_label(self, ln: _Line) -> str:
        """How the line's unknown component reads in its equation: V_BA, A^t_BA, -A_B3/B4, ..."""
        lab, sign, _, _ = self.unknown(ln)
        return ("-" if sign < 0 else "") + lab

    def unknown_vector(self, ln: _Line, tip, x) -> tuple:
        """The arrow of the line's unknown, between the tip of its known chain and the image x found,
        as :meth:`_vec` records it: ``(tail, head, kind, label, of)``.

        True sense: from the tip to x where the line adds it, from x to the tip where it subtracts it;
        on a line that also adds terms (:meth:`mixed`) a subtracted slip is drawn from the tip to x
        as the negative quantity it equals (-A_B3/B4 = A_B4/B3 on a straight path).
        """
        lab, sign, of, kind = self.unknown(ln)
        if sign < 0 and of[0] == "slip" and self.mixed(ln) and (self.level == "velocity" or of[4] is None):
            _, ka, kb, guide, kk = of
            a, b = lab[2:].split("/")
            lab, sign, of = f"{self.X}_{b}/{a}", 1, ("slip", kb, ka, guide, kk)
        t0, t1 = (tip, x) if sign > 0 else (x, tip)
        return (t0, t1, kind, lab, of)

    def run(self, steps):
        for st in steps:
            for op in st.ops:
                op.apply(self)
        return self

    # the construction in words (the steps' captions) ------------------------------------------------
    def _parts(self, place) -> tuple:
        """(point, link or None): a place as :func:`point_text` names it (the link only where the
        place's name carries it: a coincident point, B4)."""
        lk, n = place
        g = self.g
        return (n, None) if place in g.names or g.key.get((n, lk)) == n else (n, lk)

    def point_words(self, place) -> str:
        """A place in words: B, B₄, S₃."""
        return point_text(*self._parts(place))

    def image_words(self, place, vertex: bool = False) -> str:
        """A place's image in words: b, b₄ (b' in an acceleration polygon); O_v for a point at rest
        (its own name, o₂, as a ``vertex`` of a link's image)."""
        if self.g.grounded(place) and not vertex:
            return self.origin
        n, lk = self._parts(place)
        return point_text(n.lower(), lk) + ("'" if self.level == "acceleration" else "")

    def line_words(self, ln: _Line) -> str:
        """A construction line in words: "the line through a ⊥ AB", "the line through b₄ + 2 omega_4 x
        V_B3/B4 ∥ the path of B on link 4"."""
        base = self.image_words(ln.base)
        through = _sum([base] + self.term_labels(ln.terms)) if ln.terms else base
        return f"the line through {through} {ln.unknown.direction_words(self)}"

    def rates_words(self, step) -> str:
        """The rates a step fixes, in words: "; omega_3 = V_BA / AB" from two images, "; omega_3 =
        omega_4 (a block turns with its straight guide)"."""
        out = []
        rate = "omega" if self.level == "velocity" else "alpha"
        ops = [o for op in step.ops for o in (op.ops if isinstance(op, TrialSolution) else (op,))]
        for op in ops:
            if isinstance(op, RateFromImages) and op.link in step.omegas:
                name = f"{self.g.name((op.link, op.w))}{self.g.name((op.link, op.q))}"
                diff = f"V_{name}" if self.level == "velocity" else f"A^t_{name}"
                out.append(f"{rate}_{op.link} = {diff} / {_segment(op.q, op.w)}")
            elif isinstance(op, TurnsTogether):
                if op.other == self.g.frame:
                    out.append(f"{rate}_{op.link} = 0 (a block on a straight guide of the frame)")
                else:
                    out.append(f"{rate}_{op.link} = {rate}_{op.other} (block and straight guide turn together)")
        return "".join("; " + o for o in dict.fromkeys(out))

    def pinned_words(self, step) -> str:
        """Points pinned together share one image, named once by the step: "; V_A3 = V_A2 (a pin
        of links 2 and 3)" for each other name a located image has."""
        g, out = self.g, []
        for place in step.found:
            names = list(dict.fromkeys(g.name(q) for q in g.group(place) if q == place or g.point_key(q) is not None))
            if len(names) > 1:
                links = sorted({q[0] for q in g.group(place)}, key=g.links.index)
                out.append(" = ".join(f"{self.X}_{n}" for n in names)
                           + f" (a pin of links {', '.join(links[:-1])} and {links[-1]})")
        return "".join("; " + o for o in out)

    def located_first(self, step) -> str:
        """The coincident points a step locates first from their links' images, in words (none for
        the driver's and the image steps, whose words are these)."""
        if isinstance(step, _LinkImage):
            return ""
        ops = [op for op in step.ops if isinstance(op, VelocityImage)]
        if not ops:
            return ""
        level = "velocity" if self.level == "velocity" else "acceleration"
        return "; ".join(f"{self.image_words((op.link, op.w))} from the {level} image of link {op.link}, "
                         + _LinkImage.point_equation(self, op) for op in ops) + "; then "


# -- the plan's steps, by their textbook names ------------------------------------------------------
def _segment(q: str, w: str) -> str:
    """The segment QW in words: O₂A."""
    return point_text(q) + point_text(w)


@dataclass(frozen=True)
class PlanStep(ABC):
    """One step of the plan, from the mechanism alone (the same at both levels): its operations
    (:class:`VelocityImage`, :class:`Intersection`, ...), the canonical places it locates, the links
    whose rates it fixes. Each kind writes its own vector equation and caption at a level."""

    ops: tuple
    found: tuple
    omegas: tuple
    lines: tuple = ()
    sine: float = 1.0
    target: tuple | None = None
    link: str | None = None
    rel: int | None = None
    kind: ClassVar[str] = ""     # the public Step.kind

    def kind_at(self, run: "_Run") -> str:
        return self.kind

    def sine_at(self, run: "_Run") -> float:
        return self.sine

    def at(self, g: _Geo) -> "PlanStep":
        """The step at the pose of ``g`` (a plan made at another pose: its numbers at this one)."""
        return self

    def _with_sine(self, sine) -> "PlanStep":
        """``dataclasses.replace(self, sine=sine)`` without its checks (every pose of a kept plan)."""
        step = object.__new__(type(self))
        step.__dict__.update(self.__dict__, sine=sine)
        return step

    @abstractmethod
    def equation(self, run: "_Run") -> str:
        """The step's vector equation (every kind of step below writes its own)."""

    def caption(self, run: "_Run") -> str:
        """The step in the textbook's words: the coincident points it locates first from their
        links' images, what it constructs (:meth:`words`), the rates it fixes."""
        return run.located_first(self) + self.words(run) + run.pinned_words(self) + run.rates_words(self)

    @abstractmethod
    def words(self, run: "_Run") -> str:
        """What the step constructs, in words (every kind of step below writes its own)."""


@dataclass(frozen=True)
class FrameAtOrigin(PlanStep):
    """The frame's points are at rest: their images are the origin O_v (O_a)."""

    kind: ClassVar[str] = "known"

    def equation(self, run):
        names = [run.g.name(p) for p in self.found]
        if not names:
            return f"the frame images at {run.origin}"
        return " = ".join(f"{run.X}_{n}" for n in names) + " = 0: the frame's points image at " + run.origin

    def words(self, run):
        if not self.found:
            return f"The frame is at rest: its image is {run.origin}"
        names = [run.g.name(p) for p in self.found]
        words = ", ".join(run.point_words(p) for p in self.found)
        what = (f"the frame's points {words} are at rest, their images at" if len(names) > 1 else
                f"the frame's point {words} is at rest, its image at")
        return " = ".join(f"{run.X}_{n}" for n in names) + f" = 0: {what} {run.origin}"


class _LinkImage(PlanStep):
    """A link's points from its image: ``V_W = V_Q + omega x R_WQ`` for each (shared by the
    driver's and the velocity image's steps)."""

    def images(self):
        return [op for op in self.ops if isinstance(op, VelocityImage)]

    @staticmethod
    def point_equation(run, op) -> str:
        """``V_W = V_Q + omega_k x R_WQ`` (``A_W = A_Q + alpha_k x R_WQ - omega_k^2 R_WQ``) of one
        :class:`VelocityImage`."""
        lk, X, r = op.link, run.X, f"R_{op.w}{op.q}"
        rel = f"omega_{lk} x {r}" if X == "V" else f"alpha_{lk} x {r} - omega_{lk}^2 {r}"
        return f"{X}_{run.g.name((lk, op.w))} = {X}_{run.g.name((lk, op.q))} + {rel}"

    def equation(self, run):
        return "; ".join(self.point_equation(run, op) for op in self.images())


@dataclass(frozen=True)
class DriverStep(_LinkImage):
    """The crank's points: ``V_A = V_O2 + omega_2 x R_AO2``, perpendicular to O2A, |V_A| = omega_2 |O2A|
    (``A_A = A_O2 + alpha_2 x R_AO2 - omega_2^2 R_AO2``)."""

    kind: ClassVar[str] = "driver"

    def words(self, run):
        g, lk, X = run.g, self.link, run.X
        parts = []
        for op in self.images():
            w, q = g.name((lk, op.w)), g.name((lk, op.q))
            base = "" if g.grounded((lk, op.q)) else f"{X}_{q} + "
            seg = _segment(op.q, op.w)
            if X == "V":
                parts.append(f"V_{w} = {base}omega_{lk} x R_{op.w}{op.q}, ⊥ {seg}")
            else:
                parts.append(f"A_{w} = {base}A^n_{w}{q} + A^t_{w}{q}: A^n_{w}{q} = omega_{lk}^2 {seg} "
                             f"towards {point_text(op.q)}, A^t_{w}{q} = alpha_{lk} x R_{op.w}{op.q}, ⊥ {seg}")
        return "; ".join(parts)


@dataclass(frozen=True)
class VelocityImageStep(_LinkImage):
    """Once two images of a link are known (or one and its omega): the link's other points from its
    velocity (acceleration) image, similar to the link."""

    kind: ClassVar[str] = "image"

    def words(self, run):
        g, lk = run.g, self.link
        level = "velocity" if run.level == "velocity" else "acceleration"
        points = list(g.m.link(lk).points)
        found = [op.w for op in self.images()]
        shape = ""
        if len(points) >= 3:
            shape = (", " + "".join(run.image_words((lk, n), vertex=True) for n in points) + " similar to "
                     + "".join(point_text(n) for n in points))
        return (self.equation(run) + ": " + ", ".join(run.image_words((lk, n)) for n in found)
                + f" from the {level} image of link {lk}{shape}")


@dataclass(frozen=True)
class KnownMotionStep(PlanStep):
    """Case 1, a known vector: a rolling contact (``V_P3 = V_P4``) or a prescribed slip
    (``V_P3 = V_P4 + V_P3/P4``, along the common tangent)."""

    kind: ClassVar[str] = "known"

    def _sides(self, run):
        r, t = run.g.rels[self.rel], self.target
        other = (r.b if t[0] == r.a else r.a, t[1])
        sign = 1 if t[0] == r.a else -1
        return r, t, other, sign

    def _what(self, run, r) -> str:
        return f"{run.g.m.contacts[r.index].kind} contact"

    def equation(self, run):
        r, t, other, sign = self._sides(run)
        X, g = run.X, run.g
        terms = run.term_labels((JointMotionTerm(self.rel, sign, t[1]),)) or [f"{X}_{relative(named(t[1], t[0]), named(t[1], other[0]))}"]
        return _sum([f"{X}_{g.name(t)} = {X}_{g.name(other)}"] + terms) + f" ({self._what(run, r)})"

    def _how(self, run, r, t, other) -> str:
        c = run.g.m.contacts[r.index]
        there = f"at the contact point {point_text(r.at)}"
        if c.kind == "rolling" and run.level == "velocity":
            return f"rolling without slip {there}: {run.image_words(t)} = {run.image_words(other)}"
        if c.kind == "rolling":
            return f"rolling {there}: the contact points' relative acceleration, along the common normal"
        return f"the prescribed slip {there}, along the common tangent"

    def words(self, run):
        r, t, other, _ = self._sides(run)
        if r.source == "contact" and run.level == "velocity" and run.g.m.contacts[r.index].kind == "rolling":
            eq = f"V_{run.g.name(t)} = V_{run.g.name(other)}"   # no relative velocity
        else:
            eq = self.equation(run)
            eq = eq[:eq.rindex(" (")]
        return eq + ": " + self._how(run, r, t, other)


@dataclass(frozen=True)
class SliderDriverStep(KnownMotionStep):
    """A slider driver, case 1: the block's image is the guide's image at the same place plus the
    driven slip along the path, ``V_F5 = V_F0 + V_F5/F0`` (a known vector)."""

    kind: ClassVar[str] = "driver"

    def _what(self, run, r) -> str:
        return "the driver's speed along its path"

    def _how(self, run, r, t, other):
        what = "speed" if run.level == "velocity" else "acceleration"
        return (f"{run.image_words(t)} from {run.image_words(other)} by the driver's known {what} "
                f"along the path of {point_text(t[1])}")


@dataclass(frozen=True)
class IntersectionStep(PlanStep):
    """Case 2a: an unknown image where two lines through known images meet (a dyad):
    ``V_B = V_A + V_BA = V_O4 + V_BO4``, the line through a perpendicular to AB and the line
    through o4 perpendicular to O4B."""

    kind: ClassVar[str] = "intersection"

    def at(self, g):
        return self._with_sine(_pair_sine(g, *self.lines))

    def equation(self, run):
        g, X = run.g, run.X
        chains = [_sum([f"{X}_{g.name(ln.base)}"] + run.term_labels(ln.terms) + [run.unknown_label(ln)])
                  for ln in self.lines]
        return f"{X}_{g.name(self.target)} = " + " = ".join(chains)

    def words(self, run):
        return (self.equation(run) + f": {run.image_words(self.target)} on "
                + " and ".join(run.line_words(ln) for ln in self.lines))


@dataclass(frozen=True)
class AuxiliaryPointStep(IntersectionStep):
    """Where no dyad exists: the point S of a link with no known image where the lines of two of its
    points' velocities meet has its image where those lines meet; S is the link's instant centre
    when both lines pass through O_v (kind 'instant-centre')."""

    kind: ClassVar[str] = "auxiliary"

    def at(self, g):
        u, v = self.lines[0].unknown, self.lines[1].unknown
        return self._with_sine(_normals_meet(g, u.x, u.line, v.x, v.line)[1])

    def kind_at(self, run):
        if run.level == "velocity" and all(run.g.grounded(ln.base) and not run.terms(ln.terms)
                                           for ln in self.lines):
            return "instant-centre"   # both lines through O_v (not offset by a known slip): S's image is O_v
        return self.kind

    def equation(self, run):
        head = super().equation(run)
        t = self.target
        if self.kind_at(run) == "instant-centre":
            head += f"  ({run.g.name(t)} is the instant centre of link {t[0]}: its image is at {run.origin})"
        return head

    def words(self, run):
        t = self.target
        eq = IntersectionStep.equation(self, run)
        what = (f"{run.point_words(t)}, the instant centre of link {t[0]}, has its image at {run.origin}"
                if self.kind_at(run) == "instant-centre" else
                f"the auxiliary point {run.point_words(t)} of link {t[0]}: {run.image_words(t)}")
        return eq + f": {what}, on " + " and ".join(run.line_words(ln) for ln in self.lines)


@dataclass(frozen=True)
class TrialSolutionStep(PlanStep):
    """The trial solution (method of false position), where neither a dyad nor an auxiliary point
    exists: one image assumed on its line, the construction carried on until a link closes, and that
    link's rigidity fixes the assumed value (everything is linear in it: two trials suffice)."""

    kind: ClassVar[str] = "auxiliary"

    @property
    def trial(self) -> TrialSolution:
        return self.ops[0]

    def sine_at(self, run):
        return min(run.sine, self.sine)   # the closure's own conditioning, from the replay

    def equation(self, run):
        g, X, tr = run.g, run.X, self.trial
        lk, q, w = tr.closure
        rhs = "0" if X == "V" else f"-omega_{lk}^2 |R_{w}{q}|^2"
        chain = _sum([f"{X}_{g.name(tr.line.base)}"] + run.term_labels(tr.line.terms) + [run.unknown_label(tr.line)])
        return (f"trial solution: {X}_{g.name(self.target)} = {chain} assumed along its line; the construction "
                f"closes on link {lk}: ({X}_{w} - {X}_{q}) . R_{w}{q} = {rhs}, which fixes the assumed value")

    def words(self, run):
        g, X, tr = run.g, run.X, self.trial
        lk, q, w = tr.closure
        chain = _sum([f"{X}_{g.name(tr.line.base)}"] + run.term_labels(tr.line.terms) + [run.unknown_label(tr.line)])
        if X == "V":
            rigid = f"{run.image_words((lk, q), vertex=True)}{run.image_words((lk, w), vertex=True)}"
        else:
            rigid = f"A^t_{g.name((lk, w))}{g.name((lk, q))}"
        return (f"Trial solution (false position): {X}_{g.name(self.target)} = {chain}, "
                f"{run.image_words(self.target)} assumed on {run.line_words(tr.line)}; the construction goes on "
                f"until link {lk} closes, and its rigidity ({rigid} ⊥ {_segment(q, w)}) fixes the assumed value")


# -- building the polygons ------------------------------------------------------------------------
class _Construction:
    """A solution's plan and its exact replays (built once per solution; holds no reference to it)."""

    def __init__(self, sol):
        self.ref = weakref.ref(sol)
        self.geo, self.plan, reported = _planned(sol)
        self.found, self.aux, self.aux_places, self.link_images = reported
        self.polygons = {}
        self.lean = {}   # level -> a replay without its record (max_error alone: the JSON)


class _Kept(NamedTuple):
    """A plan kept for its mechanism: the decisions it was made with, its steps, what it reports."""

    tape: _Tape
    steps: tuple
    reported: tuple


_PLANS: dict = {}   # id(mechanism) -> (weak reference, [_Kept, ...] latest first), dropped with the mechanism
KEPT_PLANS = 4      # plans kept per mechanism (a sweep across a pose where a decision changes uses two)


def _planned(sol) -> tuple:
    """``(geometry, plan, reported)`` of the solution's pose: a plan kept for its mechanism where this
    pose makes every decision the plan was made with alike (then the planner would make the same plan;
    only its sines are the pose's), else the planner's, kept for the next pose."""
    m = sol.mechanism
    kept = _of_mechanism(_PLANS, m, list)
    geo = _Geo(sol)
    for k, plan in enumerate(kept):
        if plan.tape.holds(geo):
            kept.insert(0, kept.pop(k))
            return geo, [st.at(geo) for st in plan.steps], plan.reported
        if geo.names:   # auxiliary points placed on the way: a clean geometry for the next
            geo = _Geo(sol)
    planner = _Planner(geo)
    steps = planner.run()
    reported = _reported(geo, steps, m)
    if planner.tape.usable:
        kept.insert(0, _Kept(planner.tape, tuple(steps), reported))
        del kept[KEPT_PLANS:]
    return geo, steps, reported


def _reported(geo: _Geo, plan, m) -> tuple:
    """What both levels report of a plan (the mechanism's alone): each step's point keys and auxiliary
    points found, every auxiliary place (not a point key, not on the frame), the links' image figures."""
    found = [_found_keys(geo, st.found) for st in plan]
    aux = [tuple(geo.aux_key(p) for p in st.found if geo.point_key(p) is None) for st in plan]
    aux_places = {geo.aux_key(q): q for st in plan for p in st.found for q in geo.group(p)
                  if geo.point_key(q) is None and q[0] != geo.frame}
    link_images = {k.name: tuple(geo.key[(p, k.name)] for p in k.points) for k in m.links}
    return found, aux, aux_places, link_images


_CACHE: dict = {}   # id(solution) -> _Construction, dropped when the solution is


def _construction(sol) -> _Construction:
    c = _CACHE.get(id(sol))
    if c is None or c.ref() is not sol:
        c = _Construction(sol)
        _CACHE[id(sol)] = c
        weakref.finalize(sol, _CACHE.pop, id(sol), None)
    return c


def construction_plan(sol) -> list[tuple[str, tuple]]:
    """The order of the construction: ``[(kind, point keys found), ...]``, from the mechanism alone."""
    c = _construction(sol)
    return [(st.kind, _found_keys(c.geo, st.found)) for st in c.plan]


def _found_keys(geo, places) -> tuple:
    out = []
    for p in places:
        for q in geo.group(p):
            k = geo.point_key(q)
            if k is not None and k not in out:
                out.append(k)
    return tuple(out)


def velocity_polygon(sol) -> Polygon:
    """The velocity polygon of the solved pose, constructed graphically and checked."""
    return _polygon(sol, "velocity")


def acceleration_polygon(sol) -> Polygon:
    """The acceleration polygon (needs the contacts' centres of curvature)."""
    m = sol.mechanism
    for i, c in enumerate(m.contacts):
        if c.centres is None:
            raise InputError("accelerations need centres of curvature: the contact is given by its normal only",
                             where=f"contacts[{i}]", file=m.source,
                             hint='give centres = ["Ca", "Cb"] ("flat" for a straight profile)')
    return _polygon(sol, "acceleration")


def _polygon(sol, level) -> Polygon:
    return _level(_construction(sol), sol, level)[0]


def _level(c: _Construction, sol, level) -> tuple[Polygon, _Run]:
    """The polygon of a level and its exact run (the acceleration level replays on the velocity's)."""
    if level not in c.polygons:
        vel = None if level == "velocity" else _level(c, sol, "velocity")[1]
        c.polygons[level] = _assemble(c, sol, level, vel)
    return c.polygons[level]


def _assemble(c: _Construction, sol, level: str, vel, eager: bool = False) -> tuple[Polygon, _Run]:
    geo, m = c.geo, sol.mechanism
    run = _Run(geo, level, vel, record=True)
    drawn = []   # each step's fields and its arrows and lines as the run records them (points as x + iy)
    for i, st in enumerate(c.plan):
        run.lines, run.vectors = [], []
        for op in st.ops:
            op.apply(run)
        for p in st.found:   # absolute vectors of the images located
            if not geo.grounded(p):
                run._vec(0j, run.image(p), "absolute", f"{run.X}_{geo.name(p)}", ("point", geo.qkey(p)))
        fields = dict(index=i, kind=st.kind_at(run), found=c.found[i], omegas={lk: float(run.rate[lk]) for lk in st.omegas},
                      sine=float(st.sine_at(run)), auxiliary=c.aux[i], link=st.link)
        if eager:   # the texts written at once, as the step is drawn (tests: the same as when read later)
            fields.update(equation=st.equation(run), caption=st.caption(run))
        drawn.append((st, fields, run.vectors, run.lines))
    keys = point_keys(m)
    zimages = {key: run.image((lk, p)) for key, p, lk in keys}
    zs = [z for _, _, vectors, lines in drawn for arrow in vectors + lines for z in arrow[:2]]
    zs += zimages.values()
    zs += [run.image(q) for q in c.aux_places.values()]
    rows = iter(_rows(zs))   # in the order of zs: each step's arrows and lines, the images, the auxiliary images
    steps = []
    for st, fields, vectors, lines in drawn:
        fields["vectors"] = tuple([Vector(next(rows), next(rows), *v[2:]) for v in vectors])
        fields["lines"] = tuple([ConstructionLine(next(rows), next(rows), *ln[2:]) for ln in lines])
        steps.append(Step._written(st, run, **fields))
    images = {key: next(rows) for key in zimages}
    labels = {key: run.label((lk, p)) for key, p, lk in keys}
    auxiliary = {k: AuxiliaryPoint(k, q[0], geo.pos[q[1]].copy(), next(rows), run.label(q))
                 for k, q in c.aux_places.items()}
    link_images = dict(c.link_images)
    rates = {lk: float(run.rate[lk]) for lk in geo.links}
    return Polygon(level, run.origin, images, labels, tuple(steps), link_images, rates,
                   _max_error(sol, level, zimages), auxiliary, _figure_scale(images, auxiliary)), run


def _rows(zs) -> list:
    """The points x + iy as the contract's 2-vectors (2,), in order: the rows of one (n, 2) array, the
    same floats as :func:`velpoly.rigid.xy` of each."""
    if not zs:
        return []
    return list(np.array(zs, complex).view(np.float64).reshape(len(zs), 2))


def _max_error(sol, level: str, zimages: dict) -> float:
    """The largest |graphical - analytic| over the points' images, relative to the largest analytic one."""
    mo = sol.motion   # each point's analytic vector, a (1, 2) array, as x + iy
    analytic = {k: complex(*v.tolist()[0]) for k, v in (mo.velocity if level == "velocity" else mo.acceleration).items()}
    scale_ref = max(map(abs, analytic.values()), default=0.0)
    err = max((abs(zimages[k] - analytic[k]) for k in zimages), default=0.0)
    return err / scale_ref if scale_ref > 0 else err


def max_error(sol, level: str) -> float:
    """The max_error of the polygon of ``level`` ('velocity' or 'acceleration'), as the polygon gives it.

    Where the polygon is not built yet, the plan is replayed without recording its steps (the JSON needs
    no more: the same images in a third of the time); a polygon built already gives its own.
    """
    c = _construction(sol)
    if level in c.polygons:
        return c.polygons[level][0].max_error
    run = _lean_run(c, level)
    return _max_error(sol, level, {key: run.image((lk, p)) for key, p, lk in point_keys(sol.mechanism)})


def _lean_run(c: _Construction, level: str) -> _Run:
    """The exact replay of a level without its record (the acceleration's on the velocity's), kept."""
    if level in c.polygons:
        return c.polygons[level][1]
    if level not in c.lean:
        vel = None if level == "velocity" else _lean_run(c, "velocity")
        c.lean[level] = _Run(c.geo, level, vel).run(c.plan)
    return c.lean[level]


def _figure_scale(images, auxiliary, figure_mm: float = 120.0) -> float:
    """mm per unit that fits the origin, the images and the auxiliary images in ``figure_mm``."""
    pts = [(0.0, 0.0)] + [(float(v[0]), float(v[1])) for v in images.values()] + \
        [(float(a.image[0]), float(a.image[1])) for a in auxiliary.values()]
    xs, ys = [x for x, _ in pts], [y for _, y in pts]
    extent = max(max(xs) - min(xs), max(ys) - min(ys))
    return figure_mm / extent if extent > 0 else 1.0


def _sum(parts) -> str:
    """Terms joined as a vector sum: ["a", "b", "-c"] -> "a + b - c"."""
    out = parts[0]
    for p in parts[1:]:
        out += f" - {p[1:]}" if p.startswith("-") else f" + {p}"
    return out


# -- the hand-drafting estimate -------------------------------------------------------------------
def hand_drafting(sol, samples: int = 400, seed: int = 20261122, angle_error: float = 0.25,
                  point_error: float = 0.25, figure_mm: float = 120.0) -> dict:
    """How far a careful hand construction at the figure's scale would stray.

    The plan is replayed ``samples`` times at once with every drawn direction
    turned by up to ``angle_error`` degrees and every drawn or read point moved
    by up to ``point_error`` mm (uniformly) at the scale that fits the polygon
    in ``figure_mm``; the acceleration replay uses each sample's own perturbed
    velocities. Returns the 2.5 and 97.5 percentiles::

        {"samples": 400, "seed": ..., "angle_error": 0.25, "point_error": 0.25, "figure_mm": 120.0,
         "velocity": {"scale": mm per unit, "omega": {link: [lo, hi]}, "speed": {key: [lo, hi]}},
         "acceleration": {"scale": ..., "alpha": {...}, "magnitude": {...}} or None}
    """
    c = _construction(sol)
    rng = np.random.default_rng(seed)
    out = {"samples": samples, "seed": seed, "angle_error": angle_error, "point_error": point_error,
           "figure_mm": figure_mm}
    vel = None
    for level, rate_key, mag_key in (("velocity", "omega", "speed"), ("acceleration", "alpha", "magnitude")):
        if level == "acceleration" and not sol.has_accelerations:
            out[level] = None
            break
        exact = _polygon(sol, level)
        scale = _figure_scale(exact.images, exact.auxiliary, figure_mm)
        run = _Run(c.geo, level, vel, n=samples, rng=rng, angle=math.radians(angle_error),
                   point=point_error / scale).run(c.plan)
        pk = point_keys(sol.mechanism)
        out[level] = {
            "scale": scale,
            rate_key: {lk: _interval(run.rate[lk]) for lk in c.geo.moving},
            mag_key: {key: _interval(np.abs(run.image((lk, p)))) for key, p, lk in pk},
        }
        vel = run
    return out


def _interval(x) -> list:
    lo, hi = np.percentile(x, [2.5, 97.5])
    return [float(lo), float(hi)]


# -- the JSON section ------------------------------------------------------------------------------
def graphical_section(sol) -> dict:
    """The JSON ``graphical`` section (FORMAT.md section 2): each polygon's ``max_error``, or why the
    construction is not drawn (``unsupported``)."""
    try:
        v = max_error(sol, "velocity")
    except ConstructionError as e:
        return {"max_error": {"velocity": None, "acceleration": None}, "unsupported": e.what}
    a = max_error(sol, "acceleration") if sol.has_accelerations else None
    return {"max_error": {"velocity": v, "acceleration": a}}
