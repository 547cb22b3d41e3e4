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

**Hand drafting.** :func:`hand_drafting` replays the same plan, vectorised
over many random perturbations (directions within +-0.25 deg, points within
+-0.25 mm at the scale that fits the polygon in ~120 mm), and reports the
2.5 and 97.5 percentiles of each omega and each speed.
"""
from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field

import numpy as np

from . import geometry as G
from .errors import InputError, SingularPoseError, VelpolyError
from .kinematics import SINGULAR
from .motion import point_keys
from .report import SECTIONS, Table, fmt, on_links, pinned_keys, polar
from .solution import register_section

__all__ = [
    "ConstructionLine", "Vector", "Step", "AuxiliaryPoint", "Polygon", "ConstructionError",
    "velocity_polygon", "acceleration_polygon", "construction_plan", "hand_drafting",
    "SINE_LIMIT",
]

SINE_LIMIT = 1.0 / SINGULAR   # |sin| between two construction lines below which the pose is singular


# -- the contract with the renderer (docs/internals.md) ----------------------------------------------
@dataclass(frozen=True)
class ConstructionLine:
    """A line of the construction: through ``base`` (polygon coordinates) along ``direction``."""

    base: np.ndarray
    direction: np.ndarray
    base_label: str
    reason: str


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


class ConstructionError(VelpolyError):
    """The mechanism has no construction order this module knows (exit status 2)."""

    exit_code = 2


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


class _Geo:
    """Positions, places and joints of a solved pose (no velocities)."""

    def __init__(self, sol):
        m = sol.mechanism
        self.m = m
        self.frame = m.frame.name
        self.links = m.link_names
        self.moving = tuple(k.name for k in m.moving_links)
        self.size = sol.kinematics.system.size   # m.size, computed once for the system
        self.tol = 1e-9 * self.size
        self.key, self.pos, self.own = {}, {}, {lk: [] for lk in self.links}
        self.zpos = {}   # the same positions as complex numbers x + iy (what the replays compute with)
        position = sol.position
        for key, p, lk in point_keys(m):   # one key P for every carrier, or P@link for each
            if p not in self.pos:
                self.pos[p] = np.asarray(position[key], float)
                self.zpos[p] = _z(self.pos[p])
            for c in (m.carriers[p] if key == p else (lk,)):
                self.key[(p, c)] = key
                self.own[c].append(p)
        self.extra = {lk: [] for lk in self.links}
        self.names = {}          # place -> textbook name of a place that is no point key
        self._parent = {}
        for pin in m.pins:
            self._union((pin.links[0], pin.point), (pin.links[1], pin.point))
        mo = sol.motion
        self.rels, self.rate_eq = [], []
        drv = m.driver
        for i, (s, r) in enumerate(zip(m.sliders, mo.sliders)):
            d = G.from_polar(1.0, float(r["direction"][0]))
            if s.centre is not None:   # a curved block turns about K relative to its guide: a pin at K
                if s.centre not in self.own[s.block]:
                    self.extra[s.block].append(s.centre)
                self._union((s.block, s.centre), (s.guide, s.centre))
            else:
                self.rate_eq.append((s.block, s.guide))
            if drv.is_slider and drv.slider == s.point:
                # on a straight path block and guide turn together: the driver's slip is the
                # relative velocity of every pair of coincident points, not only at the block's point
                at = s.point if s.centre is not None else None
                self.rels.append(_Rel("drive", i, s.block, s.guide, at, d, True, s.centre, s.point))
            elif s.centre is None:
                self.rels.append(_Rel("slider", i, s.block, s.guide, None, d, False))
        for i, (s, r) in enumerate(zip(m.slots, mo.slots)):
            self.rels.append(_Rel("slot", i, s.link, s.slot, s.pin, G.from_polar(1.0, float(r["direction"][0])), False, s.centre))
        for i, (c, r) in enumerate(zip(m.contacts, mo.contacts)):
            t = G.perp(G.from_polar(1.0, float(r["normal"][0])))
            exact = c.kind == "rolling" or c.slip is not None
            self.rels.append(_Rel("contact", i, c.links[0], c.links[1], c.point, t, exact))
            # the equivalent linkage: each centre of curvature moves on the other link along the
            # tangent, on a circle about the other centre (or parallel to the other's flat)
            for k, (ca, cb) in enumerate((c.centres, c.centres[::-1]) if c.centres else ()):
                if ca is not None:
                    self.rels.append(_Rel("centre", i, c.links[k], c.links[1 - k], ca, t, False, cb))
        self._root = {p: self._find(p) for p in self._parent}   # the unions are complete
        self._groups = {}
        for p, r in self._root.items():
            self._groups.setdefault(r, [r]).extend([p] if p != r else [])

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
        if place in self.names:
            return self.names[place]
        lk, n = place
        return n if self.key.get((n, lk)) == n else f"{n}{lk}"

    def aux_key(self, place) -> str:
        lk, n = place
        return f"{n}@{lk}"

    def qkey(self, place) -> str:
        """The key a vector's ``of`` names a place by: its point key, else its auxiliary key."""
        return self.point_key(place) or self.aux_key(place)

    def dist(self, n1, n2) -> float:
        return abs(self.zpos[n1] - self.zpos[n2])


# -- the plan (structure only, the same at both levels) ----------------------------------------------
@dataclass(frozen=True)
class _Line:
    """A construction line on an unknown image: the chain base + terms, then along ``direction``.

    ``terms``: ('normal', link, Q, W) is -omega_link^2 R_WQ (acceleration only);
    ('rel', rel index, sign, W) the known part of a joint's relative motion.
    ``unknown``: what the line's unknown component is: ('rigid', link, Q, W), ('path', rel, sign, W),
    or ('aux', inner line, link, X, S) for an auxiliary point S reached from its point X.
    """

    base: tuple
    terms: tuple
    direction: np.ndarray
    unknown: tuple
    reason: str
    links: tuple


@dataclass
class _PStep:
    kind: str
    ops: list = field(default_factory=list)
    found: list = field(default_factory=list)      # canonical places located
    omegas: list = field(default_factory=list)     # links whose rate is fixed here
    lines: tuple = ()
    sine: float = 1.0
    target: tuple | None = None
    link: str | None = None
    rel: int | None = None


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
        step.ops.append(("image", lk, self.kp[lk][0], n))
        self.mark(place, step)

    def settle(self, step: _PStep):
        """Rates that follow: a block turns with its straight guide; two images give omega."""
        changed = True
        while changed:
            changed = False
            for a, b in self.g.rate_eq:
                for x, y in ((a, b), (b, a)):
                    if x in self.rk and y not in self.rk:
                        step.ops.append(("rate_eq", y, x))
                        self.rk.add(y)
                        step.omegas.append(y)
                        changed = True
            for lk in self.g.moving:
                if lk in self.rk or len(self.kp[lk]) < 2 or self.closure:
                    continue
                q = self.kp[lk][0]
                w = max(self.kp[lk][1:], key=lambda n: self.g.dist(q, n))
                if self.g.dist(q, w) > self.g.tol:
                    if self.trial and lk not in self.rigid_used:   # over-determined: closes the trial
                        self.closure = (lk, q, w)
                        return
                    step.ops.append(("rate_from", lk, q, w))
                    self.rk.add(lk)
                    step.omegas.append(lk)
                    changed = True

    def add(self, step: _PStep):
        self.settle(step)
        self.steps.append(step)

    # the plan ----------------------------------------------------------------------------------
    def run(self) -> list[_PStep]:
        g = self.g
        s0 = _PStep("known")
        for n in g.places(g.frame):
            self.mark((g.frame, n), s0)
        self.add(s0)
        drv = g.m.driver
        if not drv.is_slider:
            s = _PStep("driver", ops=[("rate", drv.link)], omegas=[drv.link], link=drv.link)
            self.rk.add(drv.link)
            self._image_ops(drv.link, s)
            self.add(s)
        self._loop()
        return self.steps

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
        self.rigid_used = {seed.links[0]} if seed.unknown[0] == "rigid" else set()
        head = _PStep("auxiliary", lines=(seed,), target=t)
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
        head.ops = [("trial", t, seed, [op for st in [head] + sub for op in st.ops], (lk, q, w)),
                    ("rate_from", lk, q, w)]
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
                step.ops.append(("image", lk, base, n))
                self.mark((lk, n), step)

    def _image(self) -> bool:
        for lk in self.g.moving:
            if self.full(lk) and any(not self.is_known((lk, n)) for n in self.g.places(lk)):
                s = _PStep("image", link=lk)
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
                    s = _PStep("driver" if r.source == "drive" else "known", target=self.g.canon(dst), rel=i)
                    self.ensure(src, s)
                    s.ops.append(("equal", dst, src, i, sign))
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
                ks = [q for q in self.kp[lk] if g.dist(q, n) > g.tol]
                if ks:
                    q = ks[0]
                    r = g.zpos[n] - g.zpos[q]
                    rn = abs(r)
                    out.append(_Line((lk, q), (("normal", lk, q, n),), np.array((-r.imag / rn, r.real / rn)),
                                     ("rigid", lk, q, n), f"perpendicular to {q}{n}", (lk,)))
            for i, r in enumerate(g.rels):
                if r.exact or r.at not in (None, n) or lk not in (r.a, r.b):
                    continue
                if r.source == "contact" and g.m.contacts[r.index].centres is not None:
                    continue   # a sliding contact with centres: the equivalent linkage's lines ('centre')
                partner, sign = (r.b, 1) if lk == r.a else (r.a, -1)
                pp = (partner, n)
                if self.is_known(pp) or self.full(partner):
                    out.append(_Line(pp, (("rel", i, sign, n),), r.direction, ("path", i, sign, n),
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
                    out.append(_Line(ln.base, ln.terms + (("rel", i, sign, n),), ln.direction, ln.unknown,
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
            lines = self.lines_for(t)
            best = _best_pair(lines)
            if best is None:
                continue
            l1, l2, sine = best
            if sine < SINE_LIMIT:
                self.singular = self.singular or (t, l1, l2, sine)
                continue
            s = _PStep("intersection", lines=(l1, l2), sine=sine, target=t)
            for ln in (l1, l2):
                self.ensure(ln.base, s)
                if ln.unknown[0] == "rigid":
                    self.rigid_used.add(ln.links[0])
            s.ops.append(("meet", t, l1, l2))
            self.mark(t, s)
            self.add(s)
            return True
        return False

    def _auxiliary(self) -> bool:
        """A link T with no known image: the point S of T where two of its points' lines meet."""
        g = self.g
        best = None
        for lk in g.moving:
            if lk in self.rk or self.kp[lk] or len(g.places(lk)) < 3:   # S must locate a third point
                continue
            one = []
            for n in g.places(lk):
                ls = self.lines_for((lk, n))
                if ls:
                    one.append((n, ls[0]))
            for i in range(len(one)):
                for j in range(i + 1, len(one)):
                    (x, lx), (y, ly) = one[i], one[j]
                    s, _, _, sine = G.intersect_lines(g.pos[x], G.perp(lx.direction), g.pos[y], G.perp(ly.direction))
                    if s is None or sine < SINE_LIMIT:
                        continue
                    # prefer the instant centre (both lines through O_v: Kennedy) unless badly conditioned
                    pole = g.grounded(lx.base) and g.grounded(ly.base) and sine >= 0.05
                    if best is None or (pole, sine) > best[0]:
                        best = ((pole, sine), lk, x, lx, y, ly, s)
        if best is None:
            return False
        (_, sine), lk, x, lx, y, ly, spos = best
        name = f"S{lk}"
        while name in g.pos:
            name += "'"
        g.pos[name] = np.asarray(spos, float)
        g.zpos[name] = _z(spos)
        g.extra[lk].append(name)
        g.names[(lk, name)] = name
        aux = [_Line(ln.base, ln.terms + (("normal", lk, p, name),), ln.direction, ("aux", ln, lk, p, name),
                     ln.reason + f" (auxiliary point {name} of link {lk} on the normal through {p})",
                     ln.links + (lk,)) for p, ln in ((x, lx), (y, ly))]
        s = _PStep("auxiliary", lines=tuple(aux), sine=sine, target=(lk, name), link=lk)
        self.rigid_used.add(lk)
        for ln in aux:
            self.ensure(ln.base, s)
            if ln.unknown[1].unknown[0] == "rigid":
                self.rigid_used.add(ln.unknown[1].links[0])
        s.ops.append(("meet", (lk, name), aux[0], aux[1]))
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
                hint="links in line (a toggle or dead centre) or two pins at one place: choose another driver angle")
        left = [lk for lk in g.moving if not self.full(lk)]
        raise ConstructionError(
            f"no graphical construction order: links {', '.join(left)} form a group that neither a dyad "
            f"(two lines through known images), an auxiliary point nor a trial solution determines",
            where="links",
            file=g.m.source, hint="the analytic results (velpoly solve) are still exact")


def _best_pair(lines):
    best = None
    for i in range(len(lines)):
        for j in range(i + 1, len(lines)):
            d, e = lines[i].direction, lines[j].direction
            sine = abs(d[0] * e[1] - d[1] * e[0])
            if best is None or sine > best[2]:
                best = (lines[i], lines[j], sine)
    return best


def _path_reason(g: _Geo, r: _Rel) -> str:
    m = g.m
    if r.source == "slider":
        return f"parallel to the path of {m.sliders[r.index].point} on {r.b}"
    if r.source == "slot":
        s = m.slots[r.index]
        return f"along the slot of {s.slot} at {s.pin}"
    if r.source == "centre":
        if r.centre is None:
            return f"parallel to the flat of {r.b} (the path of {r.at} on {r.b})"
        return f"perpendicular to {r.centre}{r.at} (the path of {r.at} on {r.b}, a circle about {r.centre})"
    return f"along the common tangent at {r.at}"


# -- evaluating the plan: exact, or perturbed like a hand drawing ---------------------------------
def _z(v) -> complex:
    """The 2-vector (x, y) as the complex number x + iy."""
    return complex(v[0], v[1])


def _xy(z) -> np.ndarray:
    """The complex number x + iy as the contract's 2-vector array (x, y)."""
    return np.array((z.real, z.imag))


def _dot(a, b):
    """a . b of two 2-vectors written as complex numbers: Re(conj(a) b)."""
    return (a.conjugate() * b).real


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
        return self.g.name(place).lower() + ("'" if self.level == "acceleration" else "")

    def base_label(self, place) -> str:
        """The label of a line's base image: the origin for points that do not move."""
        return self.origin if self.g.grounded(place) else self.label(place)

    def _vec(self, tail, head, kind, label, of=()):
        if self.record:
            self.vectors.append(Vector(_xy(tail), _xy(head), kind, label, of))

    # known terms -----------------------------------------------------------------------------------
    def terms(self, terms) -> list:
        """The known vectors of a chain: [(kind, label, vector, of, sign, reverse)].

        ``vector`` is the quantity ``label`` names, in its true sense; the chain adds it
        ``sign`` times (-1 where the line starts from the other side of the joint's equation).
        ``reverse`` is (label, of) of the negative quantity where it has a name of its own
        (-A^n_WQ = A^n_QW, -V_B3/B4 = V_B4/B3, -2 omega_4 x V_B3/B4 = 2 omega_4 x V_B4/B3), else
        None (a circular path's V_rel^2/rho towards its centre is not the reverse motion's).
        """
        out = []
        for t in terms:
            if t[0] == "normal":
                if self.level == "velocity":
                    continue
                _, lk, q, w = t
                om = self.vel.rate[lk]
                r = self.g.zpos[w] - self.g.zpos[q]
                nw, nq = self.g.name((lk, w)), self.g.name((lk, q))
                kw, kq = self.g.qkey((lk, w)), self.g.qkey((lk, q))
                out.append(("normal", f"A^n_{nw}{nq}", -om ** 2 * r, ("normal", lk, kw, kq), 1,
                            (f"A^n_{nq}{nw}", ("normal", lk, kq, kw))))
            else:
                _, i, sign, w = t
                out += [(k, lab, v, of, sign, rev) for k, lab, v, of, rev in self.rel_terms(i, w)]
        return out

    def term_labels(self, terms) -> list:
        """The chain's terms as written in its equation: "-2 omega_4 x V_A3/A4" where subtracted."""
        return [("-" if t[4] < 0 else "") + t[1] for t in self.terms(terms)]

    def rel_keys(self, r: _Rel, w) -> tuple:
        """The keys of a joint's two places at w (a's, b's) and of its relative path's centre."""
        g = self.g
        k = g.qkey((r.b, r.centre)) if r.centre is not None else None
        return g.qkey((r.a, w)), g.qkey((r.b, w)), k

    def rel_terms(self, i, w) -> list:
        """Known relative motion of a joint, a relative to b, at the place of w:
        [(kind, label, vector, of, reverse)] (``reverse``: see :meth:`terms`).

        Blocks, pins in slots and the equivalent linkage's centres of curvature:
        ``A_a = A_b + 2 omega_b x V_a/b (Coriolis) + V_a/b^2 / rho (towards the centre of a
        circular path) + A_a/b (slip along the path)``. An exact contact (rolling, or a
        prescribed slip): ``A_Pa = A_Pb + 2 omega_b x V_Pa/Pb + A_Pa/Pb``, the last the contact
        points' relative acceleration on b (along the common normal, from the equivalent linkage).
        """
        g, r = self.g, self.g.rels[i]
        m = g.m
        rel, rrel = f"{w}{r.a}/{w}{r.b}", f"{w}{r.b}/{w}{r.a}"
        ka, kb, kk = self.rel_keys(r, w)
        slip_of = ("slip", ka, kb, r.b, kk)
        if self.level == "velocity":
            back = (f"V_{rrel}", ("slip", kb, ka, r.b, kk))   # V_b - V_a
            if r.source == "drive":
                return [("slip", f"V_{rel}", m.driver.speed * _z(r.direction), slip_of, back)]
            if r.source == "contact" and m.contacts[r.index].slip:
                return [("slip", f"V_{rel}", m.contacts[r.index].slip * _z(r.direction), slip_of, back)]
            return []
        vel = self.vel
        vrel = vel.image((r.a, w)) - vel.image((r.b, w))
        out = []
        coriolis = 2.0 * vel.rate[r.b] * 1j * vrel
        cor = ("coriolis", f"2 omega_{r.b} x V_{rel}", coriolis, ("coriolis", r.b, ka, kb),
               (f"2 omega_{r.b} x V_{rrel}", ("coriolis", r.b, kb, ka)))
        # the slip reversed (A_b - A_a + 2 omega_b x V_a/b) is b's slip on a only on a straight path
        back = (f"A_{rrel}", ("slip", kb, ka, r.b, None)) if kk is None else None
        if r.source != "contact":
            if r.source == "drive":
                out.append(("slip", f"A_{rel}", m.driver.accel * _z(r.direction), slip_of, back))
            if r.b != g.frame:   # a guide on the frame has no Coriolis term: 2 omega x V_rel
                out.append(cor)
            if r.centre is not None:   # a circular relative path: V_rel^2 / rho towards its centre
                k = g.zpos[r.centre] - g.zpos[w]
                rho = abs(k)
                speed2 = vrel.real ** 2 + vrel.imag ** 2
                out.append(("normal", f"A^n_{rel}", speed2 / rho * (k / rho), ("path-normal", ka, kb, kk), None))
        elif m.contacts[r.index].kind == "rolling":   # no slip: the contact points' relative acceleration
            out.append(("relative", f"A_{rel}", self._contact_normal(r, w, vrel), ("difference", ka, kb),
                        (f"A_{rrel}", ("difference", kb, ka))))
        else:   # a prescribed slip: Coriolis, and the rest of the relative acceleration on b
            rest = self._contact_normal(r, w, vrel)
            if r.b != g.frame:
                out.append(cor)
                rest = rest - coriolis
            out.append(("relative", f"A_{rel}", rest, ("slip", ka, kb, r.b, None),
                        (f"A_{rrel}", ("slip", kb, ka, r.b, None))))
        return out

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
    def chain(self, base, terms, forward: bool = False) -> tuple:
        """The tip of base image + known terms, and the arrows drawn: (tip, [(kind, label, tail, head, of)]).

        Every arrow points in the true sense of what its label names and they run tip to tail:
        a subtracted term (the line starts from the known image on the other side of the
        equation, b3' to find b4' in ``A_B3 = A_B4 + 2 omega_4 x V_B3/B4 + A_B3/B4``) is drawn
        back from the image, ending at it, and comes first; added terms follow, forwards.
        ``forward`` (a line that subtracts some terms and adds others, see :meth:`mixed`): a
        subtracted term is drawn forwards as the negative quantity it equals, under that
        quantity's own name (-V_A3/A4 is V_A4/A3, -A^n_SA is A^n_AS), so that the arrows run tip
        to tail from the base image to the image found; only a term with no such name (a
        circular path's V_rel^2/rho) is still drawn back from the base image.
        """
        tip = self.image(base)
        parts = []
        ts = self.terms(terms)
        drawn_back = [t[4] < 0 and not (forward and t[5]) for t in ts]
        back = [t for t, b in zip(ts, drawn_back) if b]
        ahead = [t if t[4] > 0 else (t[0], t[5][0], -t[2], t[5][1], 1, None) for t, b in zip(ts, drawn_back) if not b]
        for kind, lab, v, of, sign, _ in back:
            new = self._mark(tip - self._turn(v))
            parts.append((kind, lab, new, tip, of))
            tip = new
        for kind, lab, v, of, sign, _ in ahead:
            new = self._mark(tip + self._turn(v))
            parts.append((kind, lab, tip, new, of))
            tip = new
        return tip, parts

    def mixed(self, ln: _Line) -> bool:
        """Whether the line's chain both subtracts and adds (its known terms and its unknown at this
        level): then no order of true-sense arrows runs tip to tail, and :meth:`chain` draws the
        subtracted ones as their negatives (an auxiliary point reached through a driven slip:
        ``V_S4 = V_O2 + V_A2O2 - V_A3/A4 + V_S4A4``; a block's line offset by a slip it subtracts)."""
        signs = {t[4] for t in self.terms(ln.terms)} | {self.unknown(ln)[1]}
        return len(signs) > 1

    def _draw(self, parts):
        for k, lab, t0, t1, of in parts:
            self._vec(t0, t1, k, lab, of)

    def do(self, op):
        g = self.g
        kind = op[0]
        if kind == "rate":
            drv = g.m.driver
            self.rate[op[1]] = self._const(drv.omega if self.level == "velocity" else drv.alpha)
        elif kind == "rate_eq":
            self.rate[op[1]] = self.rate[op[2]]
        elif kind == "rate_from":   # omega = (R_WQ x (V_W - V_Q)) / |R_WQ|^2 = Im((V_W - V_Q) / R_WQ)
            _, lk, q, w = op
            r = g.zpos[w] - g.zpos[q]
            d = self.image((lk, w)) - self.image((lk, q))
            self.rate[lk] = (d / r).imag
        elif kind == "image":
            _, lk, q, w = op
            self._set((lk, w), self._rigid(lk, q, w))
        elif kind == "equal":
            _, dst, src, i, sign = op
            tip, parts = self.chain(src, (("rel", i, sign, dst[1]),))
            self._set(dst, tip)
            self._draw(parts)
        elif kind == "meet":
            self._meet(*op[1:])
        elif kind == "trial":
            self._trial(*op[1:])

    def _rigid(self, lk, q, w):
        """V_W = V_Q + omega x R_WQ  (A_W = A_Q + alpha x R_WQ - omega^2 R_WQ)."""
        r = self.g.zpos[w] - self.g.zpos[q]
        base = self.image((lk, q))
        rate = self.rate[lk]
        name_w, name_q = self.g.name((lk, w)), self.g.name((lk, q))
        kw, kq = self.g.qkey((lk, w)), self.g.qkey((lk, q))
        if self.level == "velocity":
            tip = self._mark(base + self._turn(rate * 1j * r))
            self._vec(base, tip, "relative", f"V_{name_w}{name_q}", ("difference", kw, kq))
            return tip
        om = self.vel.rate[lk]
        mid = self._mark(base + self._turn(-om ** 2 * r))
        tip = self._mark(mid + self._turn(rate * 1j * r))
        self._vec(base, mid, "normal", f"A^n_{name_w}{name_q}", ("normal", lk, kw, kq))
        self._vec(mid, tip, "tangential", f"A^t_{name_w}{name_q}", ("tangential", lk, kw, kq))
        return tip

    def _meet(self, target, l1, l2):
        tips, dirs = [], []
        for ln in (l1, l2):
            tip, parts = self.chain(ln.base, ln.terms, self.mixed(ln))
            tips.append(tip)
            dirs.append(self._turn(_z(ln.direction)))
            self._draw(parts)
            if self.record:
                label = _sum([self.base_label(ln.base)] + self.term_labels(ln.terms))
                self.lines.append(ConstructionLine(_xy(tip), ln.direction.copy(), label, ln.reason))
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

    def _trial(self, seed, line, sub, closure):
        """Two trial polygons with x = tip + tau e, then tau from the closing link.

        The closing link (W, Q) has its images located without its own rigidity; it needs
        (V_W - V_Q) . R_WQ = 0 (A: = -omega^2 |R_WQ|^2): the locus of V_W - V_Q over the trial
        values, drawn from the origin, meets the line perpendicular to R_WQ at the true value.
        """
        lk, q, w = closure
        tip, parts = self.chain(line.base, line.terms, self.mixed(line))
        e = self._turn(_z(line.direction))
        known = [abs(v) for v in self.img.values()] + [abs(tip), self._const(self._level_scale())]
        tau1 = np.maximum(np.max(known, axis=0), 1e-300)
        start, record = (dict(self.img), dict(self.rate)), self.record
        self.record = False
        z = []
        for tau in (0.0, tau1):
            self.img, self.rate = dict(start[0]), dict(start[1])
            self._set(seed, tip + tau * e)
            for o in sub:
                self.do(o)
            z.append(self.image((lk, w)) - self.image((lk, q)))
        r = self.g.zpos[w] - self.g.zpos[q]
        rn = abs(r)
        c = 0.0 if self.level == "velocity" else -self.vel.rate[lk] ** 2 * rn
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
            self.lines.append(ConstructionLine(_xy(z[0]), _xy(locus / abs(locus)), self.origin,
                                               f"locus of {self.X}_{w}{q} over the trial values"))
            self.lines.append(ConstructionLine(_xy(target), _xy(1j * r / rn), self.origin,
                                               f"perpendicular to {q}{w}: link {lk} is rigid"))
            self.lines.append(ConstructionLine(_xy(tip), line.direction.copy(),
                                               _sum([self.base_label(line.base)] + self.term_labels(line.terms)),
                                               line.reason + " (the trial image's line)"))
            self.vectors.append(self.unknown_vector(line, tip, found))
        for o in sub:
            self.do(o)

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

    def unknown(self, ln: _Line) -> tuple:
        """The line's unknown component: (label, sign, of, kind), the line adding ``sign`` times it.

        V_BA, A^t_BA (the rigid link's), V_B3/B4 or A_B3/B4 (the slip of a relative to b,
        subtracted where the line starts from a's image), or for an auxiliary point S reached
        from X the sum of X's unknown and V_SX (A^t_SX), which lie along one line.
        """
        u = ln.unknown
        g = self.g
        vel = self.level == "velocity"
        if u[0] == "rigid":
            _, lk, q, w = u
            kw, kq = g.qkey((lk, w)), g.qkey((lk, q))
            if vel:
                return f"V_{g.name((lk, w))}{g.name((lk, q))}", 1, ("difference", kw, kq), "relative"
            return f"A^t_{g.name((lk, w))}{g.name((lk, q))}", 1, ("tangential", lk, kw, kq), "tangential"
        if u[0] == "path":
            _, i, sign, w = u
            r = g.rels[i]
            ka, kb, kk = self.rel_keys(r, w)
            return (f"{self.X}_{w}{r.a}/{w}{r.b}", sign, ("slip", ka, kb, r.b, kk),
                    "relative" if vel else "slip")
        _, inner, lk, p, s = u
        lab, sign, of, _ = self.unknown(inner)
        ks, kp = g.qkey((lk, s)), g.qkey((lk, p))
        t_of = ("difference", ks, kp) if vel else ("tangential", lk, ks, kp)
        label = _sum([("-" if sign < 0 else "") + lab, f"{self.X}{'' if vel else '^t'}_{s}{p}"])
        return label, 1, ("sum", ((sign, of), (1, t_of))), "relative"

    def unknown_label(self, ln: _Line) -> str:
        """How the line's unknown component reads in its equation: V_BA, A^t_BA, -A_B3/B4, ..."""
        lab, sign, _, _ = self.unknown(ln)
        return ("-" if sign < 0 else "") + lab

    def unknown_vector(self, ln: _Line, tip, x) -> Vector:
        """The arrow of the line's unknown, between the tip of its known chain and the image x found.

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
        return Vector(_xy(t0), _xy(t1), kind, lab, of)

    def run(self, steps):
        for st in steps:
            for op in st.ops:
                self.do(op)
        return self


# -- building the polygons ------------------------------------------------------------------------
class _Construction:
    """A solution's plan and its exact replays (built once per solution; holds no reference to it)."""

    def __init__(self, sol):
        self.ref = weakref.ref(sol)
        self.geo = geo = _Geo(sol)
        self.plan = _Planner(geo).run()
        self.polygons = {}
        self.lean = {}   # level -> a replay without its record (max_error alone: the JSON)
        # what both levels report of the plan: each step's point keys and auxiliary points found,
        # every auxiliary place (not a point key, not on the frame) and the links' image figures
        self.found = [_found_keys(geo, st.found) for st in self.plan]
        self.aux = [tuple(geo.aux_key(p) for p in st.found if geo.point_key(p) is None) for st in self.plan]
        self.aux_places = {geo.aux_key(q): q for st in self.plan for p in st.found for q in geo.group(p)
                           if geo.point_key(q) is None and q[0] != geo.frame}
        m = sol.mechanism
        self.link_images = {k.name: tuple(geo.key[(p, k.name)] for p in k.points) for k in m.links}


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


def _assemble(c: _Construction, sol, level: str, vel) -> tuple[Polygon, _Run]:
    geo, m = c.geo, sol.mechanism
    run = _Run(geo, level, vel, record=True)
    steps = []
    for i, st in enumerate(c.plan):
        run.lines, run.vectors = [], []
        for op in st.ops:
            run.do(op)
        for p in st.found:   # absolute vectors of the images located
            if not geo.grounded(p):
                run._vec(0j, run.image(p), "absolute", f"{run.X}_{geo.name(p)}", ("point", geo.qkey(p)))
        kind = st.kind
        trial = bool(st.ops) and st.ops[0][0] == "trial"
        if kind == "auxiliary" and not trial and level == "velocity" and \
                all(geo.grounded(ln.base) and not run.terms(ln.terms) for ln in st.lines):
            kind = "instant-centre"   # both lines through O_v (not offset by a known slip): S's image is O_v
        sine = min(run.sine, st.sine) if trial else st.sine
        steps.append(Step(i, kind, _equation(run, st, kind), tuple(run.lines), c.found[i], tuple(run.vectors),
                          {lk: float(run.rate[lk]) for lk in st.omegas}, float(sine), c.aux[i], st.link))
    images, labels, zimages = {}, {}, {}
    for key, p, lk in point_keys(m):
        zimages[key] = run.image((lk, p))
        images[key] = _xy(zimages[key])
        labels[key] = run.label((lk, p))
    auxiliary = {k: AuxiliaryPoint(k, q[0], geo.pos[q[1]].copy(), _xy(run.image(q)), run.label(q))
                 for k, q in c.aux_places.items()}
    link_images = dict(c.link_images)
    rates = {lk: float(run.rate[lk]) for lk in geo.links}
    return Polygon(level, run.origin, images, labels, tuple(steps), link_images, rates,
                   _max_error(sol, level, zimages), auxiliary, _figure_scale(images, auxiliary)), run


def _max_error(sol, level: str, zimages: dict) -> float:
    """The largest |graphical - analytic| over the points' images, relative to the largest analytic one."""
    analytic = {k: _z(v) for k, v in (sol.velocity if level == "velocity" else sol.acceleration).items()}
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


def _equation(run: _Run, st: _PStep, kind: str) -> str:
    g, X = run.g, run.X
    if st.kind == "known" and st.rel is None:
        names = [g.name(p) for p in st.found]
        return (" = ".join(f"{X}_{n}" for n in names) + " = 0: the frame's points image at " + run.origin
                if names else f"the frame images at {run.origin}")
    if st.kind in ("known", "driver") and st.rel is not None:
        r = g.rels[st.rel]
        t = st.target
        other = (r.b if t[0] == r.a else r.a, t[1])
        what = ("the driver's speed along its path" if r.source == "drive"
                else f"{g.m.contacts[r.index].kind} contact")
        sign = 1 if t[0] == r.a else -1
        terms = run.term_labels((("rel", st.rel, sign, t[1]),)) or [f"{X}_{t[1]}{t[0]}/{t[1]}{other[0]}"]
        return _sum([f"{X}_{g.name(t)} = {X}_{g.name(other)}"] + terms) + f" ({what})"
    if st.kind in ("driver", "image"):
        lk = st.link
        parts = [f"{X}_{g.name((op[1], op[3]))} = {X}_{g.name((op[1], op[2]))} + "
                 + (f"omega_{lk} x R_{op[3]}{op[2]}" if X == "V" else
                    f"alpha_{lk} x R_{op[3]}{op[2]} - omega_{lk}^2 R_{op[3]}{op[2]}")
                 for op in st.ops if op[0] == "image"]
        om = float(run.rate[lk])
        if X == "V":
            turn, scale = (90.0 if om >= 0 else -90.0), abs(om)
        else:
            w = float(run.vel.rate[lk])
            turn, scale = math.degrees(math.atan2(om, -w * w)), math.hypot(om, w * w)
        what = "driver" if st.kind == "driver" else "image"
        return (f"{what} of link {lk}: similar to the link, turned {turn:+.4g} deg, scale {scale:.6g}: "
                + "; ".join(parts))
    t = st.target
    if st.ops and st.ops[0][0] == "trial":
        _, _, seed, _, (lk, q, w) = st.ops[0]
        terms = run.term_labels(seed.terms)
        rhs = "0" if X == "V" else f"-omega_{lk}^2 |R_{w}{q}|^2"
        return (f"trial solution: {X}_{g.name(t)} = " + _sum([f"{X}_{g.name(seed.base)}"] + terms
                                                             + [run.unknown_label(seed)])
                + f" assumed along its line; the construction closes on link {lk}: "
                  f"({X}_{w} - {X}_{q}) . R_{w}{q} = {rhs}, which fixes the assumed value")
    chains = []
    for ln in st.lines:
        terms = run.term_labels(ln.terms)
        chains.append(_sum([f"{X}_{g.name(ln.base)}"] + terms + [run.unknown_label(ln)]))
    head = f"{X}_{g.name(t)} = " + " = ".join(chains)
    if kind == "instant-centre":
        head += f"  ({g.name(t)} is the instant centre of link {t[0]}: its image is at {run.origin})"
    return head


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


# -- JSON section and readable tables ---------------------------------------------------------------
def _json_section(sol):
    try:
        v = max_error(sol, "velocity")
    except ConstructionError as e:
        return {"max_error": {"velocity": None, "acceleration": None}, "unsupported": e.what}
    a = max_error(sol, "acceleration") if sol.has_accelerations else None
    return {"max_error": {"velocity": v, "acceleration": a}}


def _tables(sol):
    try:
        polys = [velocity_polygon(sol)]
    except ConstructionError as e:
        return Table("Graphical construction", ("status",), ((f"not constructed: {e.what}",),))
    if sol.has_accelerations:
        polys.append(acceleration_polygon(sol))
    hd = hand_drafting(sol)
    pinned = pinned_keys(sol.mechanism)
    out = []
    for poly in polys:
        vel = poly.kind == "velocity"
        analytic_rate = sol.omega if vel else sol.alpha
        analytic_pt = sol.velocity if vel else sol.acceleration
        h = hd[poly.kind]
        rname, pname = ("omega", "V") if vel else ("alpha", "A")
        rows = []
        for lk in sol.mechanism.link_names:
            if lk == sol.mechanism.frame.name:
                continue
            lo, hi = h["omega" if vel else "alpha"][lk]
            rows.append((f"{rname}_{lk}", fmt(poly.rates[lk]), fmt(analytic_rate[lk]), f"{fmt(lo, 4)} .. {fmt(hi, 4)}"))
        for key, img in poly.images.items():
            if key in pinned and pinned[key] is None:
                continue   # a point of links pinned together: one row, with the first key's
            lo, hi = h["speed" if vel else "magnitude"][key]
            name = f"{pname}_{pinned[key][0]} (on {on_links(pinned[key][1])})" if key in pinned else f"{pname}_{key}"
            rows.append((f"{name} ({poly.labels[key]})", polar(img), polar(analytic_pt[key]),
                         f"{fmt(lo, 4)} .. {fmt(hi, 4)}"))
        rows.append(("max error (relative to the largest)", f"{poly.max_error:.2g}", "", ""))
        title = (f"{poly.kind.capitalize()} polygon ({len(poly.steps)} steps): graphical and analytic, "
                 f"hand-drafted 95% range at {fmt(h['scale'], 4)} mm per unit")
        out.append(Table(title, ("quantity", "graphical", "analytic", "hand-drafted"), tuple(rows)))
    return out


register_section("graphical", _json_section)
if _tables not in SECTIONS:
    SECTIONS.append(_tables)
