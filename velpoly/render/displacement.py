"""The displacement (space) diagram: the mechanism to scale, as a textbook draws it.

Links are bars (two points) or plates (a link of three or more joints, light-filled and in one piece: a
polygon with its corners at its points, or the hull of its bars, slotted bar and profile, with the slot cut in
it), frame pivots stand on hatched ground, pins are open circles,
slider blocks are rectangles aligned with their path on a hatched guide (a
slotted bar when the guide moves), contacts show their profiles' circles
about the centres of curvature. Every point is labelled once, every link
numbered; the driver's omega is a curved arrow with its value, its alpha
another (two heads), a slider driver's speed and acceleration straight
arrows, and the driver is drawn over the links it turns. Positions
are the solution's (``sol.position``, ``sol.place``), so a solution at
another driver angle draws the re-assembled pose.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import shapely
from shapely.geometry import LineString, MultiPoint, Point
from shapely.geometry import Polygon as SPolygon
from shapely.affinity import translate
from shapely.ops import nearest_points, unary_union

from ..rigid import direction as _unit, perp as _perp
from ..names import driver_index, key_text, link_math, quantity_math, upper_name
from .canvas import (Artists, add_patch, arrow, border_point, box, fit_view, get_ax, literal, math_literal, per_cm,
                     per_point, tex, view_box, view_scale)
from .labels import all_farther, meets_any, placer
from .options import drawing_options
from .scalebar import scale_bar, unit_label
from .style import get_style, link_fill
from .table import number_math

__all__ = ["draw_mechanism", "away_from", "neighbours", "mechanism_bounds", "shape_patch", "link_bodies", "mark_auxiliary",
           "equivalent_linkage_note", "plate_outline", "plate_fill", "plain_links", "PLATE_FILL",
           "NUMBER_RADIUS"]

PLATE_FILL = "0.9"      # a plate's fill where links are white (textbook): light, so that it reads as one body
SMALLER = (0.85, 0.72)   # a text with no free place off the lines at its size: these fractions of it tried
VALUE_NEAR = 1.0        # cm: a driver's value sought first within this of its arrow, in every form and size, before
#                         a place farther out at the end of a leader (a long leader reads worse than a smaller value)
CROSSING = 3            # a driver's value with no free place off the lines whose leader crosses none: its leader may
#                        cross so many lines and outlines (out of a plate that holds its block) to reach one
NUMBER_RADIUS = 0.8     # slides: a link number's circle at most this many bar widths in radius
LABEL_NEAR = 2.0        # cm: a point's label off the other links at most this far from its point (farther out, its
#                         leader reads worse than a label beside its point over a plate or an outline)
NUMBER_BESIDE = 0.4     # cm: else (no such place found off the lines) a number's circle at most this far from its link
BESIDE_STEP = 0.08      # cm: the grid of places searched there
ON_BAR = (0.5, 0.42, 0.58, 0.34, 0.66)   # a number on its own bar: these fractions of the way along it tried
ON_BAR_CLEAR = 0.25     # bar widths: such a number's circle at least this far from each pin's ring (the bar seen)
LABEL_ROOM = 0.3        # cm: such a number's circle at least this far from every labelled point (room for its label)
NUMBER_NEAR = 1.0       # cm: a link number at most this far from its own link (beside it, not out at a leader's end)
GROUND_CLEAR = 0.15     # cm: a driver's value is nudged this far from hatched ground it crowds, where that is free
#                         (omega's value crowded the ground of a swinging block's pivot)
ARC_RADIUS = 0.8       # cm: a driver's omega arc about its pivot, in the widest gap between its links and ground
ARC_RADII = (0.8, 0.6, 0.45, 1.1)   # cm: else (that arc crosses a link, block or label: a pivot in a crowd) in a
#                                     run of directions where a circle of one of these radii is clear, the first
#                                     radius that crosses least
ARC_STEP = 3.0         # deg: the directions about a pivot tested for such a run
PEDESTAL, HATCH = 0.5, 0.5   # cm: a pivot's pedestal's height (to its hatched ground's line), that line's half width
DRIVER_ROOM = 0.65     # cm: a plate notched about the driver's pivot keeps this far from it (room for its arcs)
CRANK_OVER = 0.25      # a plate notched about a pivot whose link would lie over it by more than this fraction of
#                        that link is not notched (bars): the link's number and arcs need the room about it
GROUND_GAP = 0.2       # cm: a plate notched about a frame pivot keeps this far from its ground's line ends
UNDER_LIGHT = 0.5      # a plate drawn beneath every link (over another link's frame pivot) is this much lighter
SIDE_GAP = 12.0        # deg: alpha's arc beside omega's in one free run (where every other layout crosses a link)
RUN_SPAN = 45.0        # deg: the least span of an arc in such a run (a shorter arc reads as a tick, not a turn)


def shape_patch(geom, **kw):
    """A matplotlib PathPatch of a shapely (Multi)Polygon, holes included."""
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path
    polys = getattr(geom, "geoms", [geom])
    verts, codes = [], []
    for poly in polys:
        for ring in (poly.exterior, *poly.interiors):
            xy = np.asarray(ring.coords)
            verts.extend(xy)
            codes.extend([Path.MOVETO] + [Path.LINETO] * (len(xy) - 2) + [Path.CLOSEPOLY])
    return PathPatch(Path(np.array(verts), codes), **kw)


def _groups(sol) -> dict:
    """Point name -> list of (key, position) of its keys."""
    out: dict = {}
    for key, pos in sol.position.items():
        out.setdefault(key.split("@")[0], []).append((key, np.asarray(pos, float)))
    return out


def mechanism_bounds(sol) -> tuple[float, float, float, float]:
    """The box of every point of the pose, every contact profile small enough to draw whole, and guides."""
    m = sol.mechanism
    pts = [np.asarray(p, float) for p in sol.position.values()]
    for c, r in zip(m.contacts, sol.motion.contacts):
        place = np.asarray(r["place"][0], float)
        for lk, cn in zip(c.links, c.centres or ()):
            if cn is None:
                continue
            ctr = sol.place(lk, cn)
            rad = float(np.hypot(*(place - ctr)))
            if rad < 1.5 * m.size:
                pts += [ctr - rad, ctr + rad]
    for s, r in zip(m.sliders, sol.motion.sliders):   # a guide runs some way past its block
        if s.centre is None:
            d = _unit(float(r["direction"][0])) * 0.18 * m.size
            q = sol.place(s.block, s.point)
            pts += [q - d, q + d]
    p = np.array(pts)
    return (*p.min(axis=0), *p.max(axis=0))


def neighbours(sol, point: str, links) -> list[np.ndarray]:
    """Current positions of the other points of ``links`` (seen from ``point``)."""
    out = []
    for lk in links:
        for q in sol.mechanism.link(lk).points:
            if q != point:
                out.append(sol.place(lk, q))
    return out


def away_from(p, others, default: float = -90.0) -> float:
    """The direction (deg) pointing away from the mean direction towards ``others``."""
    if not others:
        return default
    u = sum((o - p) / max(np.hypot(*(o - p)), 1e-300) for o in others)
    if np.hypot(*u) < 1e-6:
        return default
    return math.degrees(math.atan2(-u[1], -u[0]))


def link_bodies(sol, bar_width: float, bars=None) -> dict:
    """Link -> shapely geometry of its body: a bar, or the buffered hull of its points.

    One-point links (slider blocks, wheels) have no body here; they are drawn
    as blocks and profiles. A link of three or more points whose plate would
    cover a point it does not carry (another link's pivot or pin: a slotted
    lever's plate over the crank's pivot), or that is in ``bars`` (a set of links:
    an animation's choice for every frame), is drawn as bars from its first
    point to the others instead, as a bell-crank is.
    """
    out = {}
    m = sol.mechanism
    for link in m.moving_links:
        if len(link.points) < 2:
            continue
        pts = [tuple(sol.place(link.name, p)) for p in link.points]
        out[link.name] = body_shape(pts, foreign_points(sol, link.name), bar_width,
                                    None if bars is None else link.name in bars)
    return out


def equivalent(c) -> bool:
    """Whether the polygons construct a contact through its equivalent linkage (a sliding contact
    with centres of curvature and no prescribed slip)."""
    return c.kind == "sliding" and c.slip is None and c.centres is not None


def equivalent_linkage_note(m) -> str:
    """The caption's note on the dashed equivalent linkage of a mechanism's sliding contacts ('' if none).

    Short, to fit beside the scale in every style; the dashed coupler joins the two centres of
    curvature (a dashed block sits at the centre facing a flat), whose names are on the figure."""
    return "dashed: equivalent linkage" if any(equivalent(c) for c in m.contacts) else ""


def foreign_points(sol, link, own=()) -> list:
    """Where the points that ``link`` does not carry (nor names in ``own``) are now: the other links' pivots
    and pins a body of ``link`` must not cover."""
    m = sol.mechanism
    return [tuple(sol.place(k, p)) for p in m.point_order if link not in m.carriers.get(p, ()) and p not in own
            for k in m.carriers.get(p, ())[:1]]


def foreign_bars(sol, link, own=()) -> list:
    """The points :func:`foreign_points` lists, each with the directions (deg) of its links' bars from it (to their
    other points) and whether it is a frame pivot: (point, directions, pivot), for a plate's notches
    (:func:`bitten_plate`)."""
    m, out = sol.mechanism, []
    pivots = {pin.point for pin in m.pins if m.frame.name in pin.links}
    for p in m.point_order:
        carriers = m.carriers.get(p, ())
        if link in carriers or p in own or not carriers:
            continue
        f = np.asarray(sol.place(carriers[0], p), float)
        along = [math.degrees(math.atan2(*(q - f)[::-1])) for k in carriers if not m.link(k).frame
                 for q in (np.asarray(sol.place(k, r), float) for r in m.link(k).points if r != p)
                 if float(np.hypot(*(q - f))) > 0]
        out.append((tuple(f), along, p in pivots))
    return out


def joints(m, link) -> set:
    """The joints of a link: its points (pins), the points of the blocks it guides, the pins in its slots and
    its contact points (where it has a profile: a contact given by its normal alone draws none on the link).
    A moving link with three or more is a plate (one rigid body), however they mix."""
    out = set(m.link(link).points)
    out |= {s.point for s in m.sliders if s.guide == link} | {s.pin for s in m.slots if s.slot == link}
    return out | {c.point for c in m.contacts if link in c.links and c.centres is not None}


def covers(shape, foreign, margin: float) -> bool:
    """Whether ``shape`` (a plate), grown by ``margin``, covers one of the ``foreign`` points (another link's
    pivot or pin: the plate is then drawn as bars)."""
    grown = shape.buffer(margin)
    return any(grown.contains(Point(*q)) for q in foreign)


def on_body(m, link) -> set:
    """The points a plate of ``link`` may cover: its joints and the points of the blocks it guides (the blocks lie
    over it)."""
    return joints(m, link) | {p for s in m.sliders if s.guide == link for p in m.link(s.block).points}


def whole_body(shape, foreign, bar_width: float, bars: bool | None = None):
    """A plate's body in one piece with its outline whole: the convex hull of its ``shape`` (its bars, its slotted
    bar, its profile), or, where that hull would cover one of the ``foreign`` points (or ``bars`` is True: an
    animation keeps one choice in every frame), the shape itself with its separate pieces joined by bars
    (nearest to nearest), as a bell-crank's arms are."""
    hull = shape.convex_hull
    if bars is None:
        bars = covers(hull, foreign, bar_width / 2)
    if not bars:
        return hull
    pieces = sorted(getattr(shape, "geoms", [shape]), key=lambda g: -g.area)
    whole = pieces[0]
    for g in pieces[1:]:
        a, b = nearest_points(whole, g)
        whole = unary_union([whole, g, LineString([a, b]).buffer(bar_width / 2, quad_segs=12)])
    return whole


def body_shape(pts, foreign, bar_width: float, bars: bool | None = None):
    """The buffered hull of ``pts`` (a bar or a plate), or bars from the first point to the others where
    the hull would cover one of the ``foreign`` points (or ``bars`` is True)."""
    hull = MultiPoint(pts).convex_hull
    if bars is None:
        bars = covers(hull, foreign, bar_width)
    if len(pts) >= 3 and bars:
        return unary_union([LineString([pts[0], q]).buffer(bar_width / 2, quad_segs=12) for q in pts[1:]])
    return hull.buffer(bar_width / 2, quad_segs=12)


def hull_plate(sol, link, bar_width: float):
    """The hull of a moving link's three or more points (a polygon with its corners at the points), or None (the
    frame, a bar, a hull thinner than a bar: drawn as a bar)."""
    m = sol.mechanism
    lk = m.link(link)
    if lk.frame or len(lk.points) < 3:
        return None
    pts = [tuple(map(float, sol.place(link, p))) for p in lk.points]
    hull = MultiPoint(pts).convex_hull
    if hull.geom_type != "Polygon":
        return None
    x, y = hull.minimum_rotated_rectangle.exterior.xy
    sides = np.hypot(np.diff(x), np.diff(y))
    return None if float(sides.min()) < bar_width else hull


def plate_outline(sol, link, bar_width: float):
    """The plate of a link of three or more points drawn as one: the hull of its points (a polygon with its
    corners at the points), or None where the link is drawn otherwise (a plate notched clear of another link's
    pin, :func:`bitten_plate`, or the bars of a bell-crank; a hull thinner than a bar, drawn as a bar)."""
    hull = hull_plate(sol, link, bar_width)
    return None if hull is None or covers(hull, foreign_points(sol, link), bar_width) else hull


BITE = 1.0          # bar widths: a plate bitten clear of another link's pivot or pin keeps this far from it
BITE_TURNS = 48     # directions tried for a bite's way out of the plate (and those along the pivot's own links)
NECK = 0.3          # bar widths: a bitten plate's part thinner than twice this is trimmed (a joint's corner kept);
#                     a plate that this leaves in pieces is no plate (drawn as bars)


def _pieces(g) -> list:
    """The polygons of a shapely geometry (one, or the parts of a collection)."""
    return [q for q in getattr(g, "geoms", [g]) if q.geom_type == "Polygon" and not q.is_empty]


def _trimmed(g, joints, r: float):
    """``g`` without its parts thinner than ``2 r`` (slivers a bite leaves along the hull's edge) but those at a
    joint (a plate's sharp corner at its pin), or None where what is left is not one polygon without holes."""
    at = MultiPoint([tuple(j) for j in joints])
    spurs = [q for q in _pieces(g.difference(g.buffer(-r).buffer(r, quad_segs=4)))
             if q.area > 1e-3 * r * r and q.distance(at) > r]
    out = g.difference(unary_union(spurs)) if spurs else g
    out = out if out.geom_type == "Polygon" else None
    return out if out is not None and not out.interiors and not out.is_empty else None


GROUND_TURNS = (-90.0, 0.0, 180.0, 90.0, -45.0, -135.0, 45.0, 135.0)   # the directions a pivot's ground may take


def _notches(f, turns, rad: float, reach: float, ground=None):
    """The ways out of a plate clear of the point ``f``, one for each direction (deg) of ``turns``: a disc of
    radius ``rad`` about ``f`` with a channel as wide to beyond the plate's edge (the notch a bell-crank's plate
    has where another link's pin and bar pass it); for a frame pivot (``ground``: the distance from the pivot to
    its hatched ground's line and that line's half width) the channel widens to the ground, so that its pedestal
    and hatching stand in the notch."""
    f = np.asarray(f, float)
    disc = Point(*f).buffer(rad, quad_segs=8)
    for t in turns:
        u = _unit(t)
        if ground is None:
            yield t, LineString([tuple(f), tuple(f + u * reach)]).buffer(rad, quad_segs=8)
            continue
        depth, half = ground
        n = _perp(u) * half
        base, far = f + u * depth, f + u * (depth + reach)
        yield t, unary_union([MultiPoint([tuple(base + n), tuple(base - n)]).union(disc).convex_hull,
                              SPolygon([tuple(base + n), tuple(far + n), tuple(far - n), tuple(base - n)])])


def bitten_plate(plate, foreign, joints, bar_width: float, keep=None, under=None, ground=None, room=None):
    """A plate in one piece clear of the other links' pivots and pins: ``plate`` with a notch about each of the
    ``foreign`` points it covers, open to its edge, as a bell-crank's or lever's plate is drawn about a pivot
    it turns past; None where no such plate holds its ``joints`` (then it is drawn as bars).

    ``foreign`` is a list of (point, directions, pivot): each point another link's pin (or a point it carries),
    the directions (deg) of that link's bars from it (a notch along them holds the bar too), and whether it is
    a frame pivot. A notch (:func:`_notches`) is a disc of :data:`BITE` bar widths about the point and a channel
    as wide from it out of the plate, the way that cuts least (along the point's own bars where that costs
    little more); a frame pivot's widens to its hatched ground (``ground``: (depth, half width)), one of the
    eight ways the ground may point. A notch must keep half a bar width from each joint and leaves ``keep`` (a
    slotted bar, a slot's rim, a profile: parts of the body that must stay whole) whole, however near the point
    they pass; what is left must be one polygon without holes (the point is not enclosed) and with no neck
    thinner than :data:`NECK` bar widths twice. The bodies ``under`` it (links drawn beneath,
    shared pins aside) are cut out of it first. ``room`` (point, radius): the driver's pivot, whose notch's disc
    is that wide (its curved arrows stand in it, clear of the plate).
    """
    rad = BITE * bar_width
    x0, y0, x1, y1 = plate.bounds
    reach = 2.0 * float(np.hypot(x1 - x0, y1 - y0)) + 2 * max(rad, room[1] if room else 0.0)
    own = unary_union([Point(*j).buffer(bar_width / 2, quad_segs=8) for j in joints])
    out = plate
    if under is not None and not under.is_empty:
        out = _trimmed(plate.difference(under.difference(own.buffer(bar_width / 2))), joints, NECK * bar_width)
        if out is None:
            return None
    for f, along, pivot in sorted(foreign, key=lambda fa: plate.exterior.distance(Point(*fa[0]))):
        r = room[1] if room and np.allclose(f, room[0]) else rad
        if out.distance(Point(*f)) >= r * 0.999:
            continue
        turns = GROUND_TURNS if pivot and ground else [*along, *np.arange(BITE_TURNS) * 360.0 / BITE_TURNS]
        ways = []   # (the area it cuts, its order, the cut), cheapest first: the first that leaves one plate
        for k, (t, cut) in enumerate(_notches(f, turns, r, reach, ground if pivot else None)):
            if not cut.intersects(own):
                cut = cut if keep is None else cut.difference(keep)
                ways.append((out.intersection(cut).area * (0.8 if t in along else 1.0), k, cut))
        out = next((g for _, _, cut in sorted(ways, key=lambda w: w[:2])
                    for g in [_trimmed(out.difference(cut), joints, NECK * bar_width)] if g is not None), None)
        if out is None:
            return None
    return out


def plate_fill(fill, st):
    """A plate's fill: the link's, or :data:`PLATE_FILL` where links are white (it must read as one body)."""
    return PLATE_FILL if fill == st.paper else fill


def under_fill(fill, st):
    """A plate's fill drawn beneath the other links (:attr:`_Drawing.underlays`): lighter than a plate's,
    :data:`UNDER_LIGHT` of the way from ``fill`` to the paper (it reads as a body beneath, the links over it)."""
    from matplotlib.colors import to_rgb
    a, b = np.asarray(to_rgb(fill)), np.asarray(to_rgb(st.paper))
    return tuple(float(x) for x in a + UNDER_LIGHT * (b - a))


def stacked(text: str) -> str:
    """A value written in two lines, its name over its value (``"V_A = 1.2 m/s"`` as ``"V_A =" / "1.2 m/s"``):
    half as wide, where a crowd leaves no room for one line (a slip's name V_A₃/A₄ is wide).

    >>> stacked("$V_{A}$ = 1.2 m/s")
    '$V_{A}$ =\\n1.2 m/s'
    """
    name, _, rest = text.partition(" = ")
    return f"{name} =\n{rest}" if rest else text


def plain_links(m) -> set:
    """The links drawn as bars or plates alone: none that carries a moving guide, a slot or a contact's
    profile (those are drawn with their own bodies)."""
    extra = {s.guide for s in m.sliders} | {s.slot for s in m.slots} | {lk for c in m.contacts for lk in c.links}
    return {k.name for k in m.moving_links} - extra


class _ArcPlace(NamedTuple):
    """Where a driver's curved arrow goes: its rank among the choices, mid direction and span (deg) about the
    pivot, radius, and the angular gap (width, start) it lies in."""
    rank: int
    mid: float
    span: float
    rad: float
    gap: tuple


class _Drawing:
    """The state of one displacement diagram being drawn."""

    def __init__(self, sol, ax, st, opts, under_cranks: bool = False):
        self.sol, self.m, self.ax, self.st, self.opts = sol, sol.mechanism, ax, st, opts
        self.under_cranks = under_cranks   # a plate notched about a crank's pivot with the crank over it drawn so
        #                                    (:meth:`reads`), not as bars (:meth:`cranks_over`)
        self.beneath_cranks: set = set()  # the links so drawn
        self.underlays: set = set()       # plates over another link's frame pivot that no notch clears (or whose
        #                                   notch a crank over it would crowd): whole, lighter, beneath every link
        self.astray: list = []            # the links whose numbers, as drawn, read as another link's, and the points
        #                                   whose labels stand over a link not theirs or on an outline
        self.pc, self.pp = per_cm(ax), per_point(ax)
        self.pl = placer(ax)
        self.art = Artists(ax)
        self.art.exempt = {}   # each ground hatch (a LineCollection) -> the links it may touch
        self.pins_at: dict = {}          # point -> set of links pinned there
        for pin in self.m.pins:
            self.pins_at.setdefault(pin.point, set()).update(pin.links)
        self.blocks = {s.block for s in self.m.sliders}
        self.bodies = link_bodies(sol, st.bar_width * self.pc)
        self.extra_body: dict = {}       # link -> geometry to union (slotted bars, wheels)
        self.keep: dict = {}             # link -> the parts of it a notch must leave whole (slotted bars, a slot's
        #                                  rim, profiles: :func:`bitten_plate`)
        self.slots: list = []            # (link, slot geometry) drawn white over bodies
        self.slotted: set = set()        # links with a slot or a moving guide's slotted bar
        self.hatches: list = []          # ground to draw once the bodies are known
        self.grounds: list = []          # the hatched strips drawn (shapely): the driver's values keep off
        self.geoms: dict = {}            # link -> its body as drawn
        self.slot_cuts: dict = {}        # slot index -> (link, centre line, cut) of a moving link's slot
        self.zorders: dict = {s.block: 3.2 for s in self.m.sliders}   # link -> its body's zorder (blocks: 3.2)
        self.guide_bars: dict = {}       # moving guide -> its slotted bar (in a plate: the part a block's number
        #                                  keeps off; the rest of the plate it may stand on, beside its block)
        self.reserved: list = []         # the point labels' boxes in a clear field (:meth:`marks`)
        self.outlines: dict = {}         # link -> its outline's and slots' soft obstacles (a number on its own bar
#                                          may cross them and those of the links beneath it: the bar hides them)
        self.plan: int | None = None     # the driver's layout chosen (:meth:`turning_driver`), drawn again the same
        self.bare = not self.pl.soft     # nothing drawn in the panel before (a poles sheet's Kennedy lines are)
        self.styles: dict = {}           # link -> its number's Text keywords (:meth:`number_style`)
        self.radii: dict = {}            # (link, type size) -> its number's circle's radius (:meth:`number_radius`)

    # -- pieces ------------------------------------------------------------------------
    def patch(self, geom, role, zorder, facecolor, lw=None, gid=None, **kw):
        p = shape_patch(geom, facecolor=facecolor, edgecolor=self.st.ink,
                        lw=self.st.link_lw if lw is None else lw, zorder=zorder, **kw)
        if gid:
            p.set_gid(gid)
        add_patch(self.ax, p)
        self.art.add(role, p)
        return p

    def body(self, lk, geom, zorder):
        """A link's body: a plate as one polygon with its corners at the link's points, in a light fill (a
        plate reads as one link, not as bars), else its shape (bars, slotted bars, discs)."""
        fill = link_fill(self.m, self.opts, self.st, lk)
        if lk not in self.plates:
            fill = plate_fill(fill, self.st) if lk in self.filled else fill
            return self.patch(geom, "links", zorder, fill, gid=f"link-{lk}")
        from matplotlib.patches import Polygon as MPolygon
        fill = plate_fill(fill, self.st) if lk not in self.underlays else under_fill(plate_fill(fill, self.st), self.st)
        p = MPolygon(np.asarray(geom.exterior.coords)[:-1], closed=True, facecolor=fill, edgecolor=self.st.ink,
                     lw=self.st.link_lw, zorder=zorder, gid=f"link-{lk}")
        add_patch(self.ax, p)
        self.art.add("links", p)
        return p

    def whole(self, lk, shape, under=None, notch: bool = True):
        """The body of a link of three or more joints drawn otherwise than as a bare plate (with a slot, a
        moving guide or a profile; or as bars): in one piece, its outline whole (:func:`whole_body`), notched
        clear of the other links' pins where its hull covers one (:func:`bitten_plate`, its slotted bars, slot
        rims and profiles whole, clear of the bodies ``under`` it), else (or not ``notch``) as bars. The points
        of the blocks it guides are not foreign: the blocks lie over it. Returns (body, notched)."""
        w, own = self.st.bar_width * self.pc, on_body(self.m, lk)
        foreign = foreign_points(self.sol, lk, own)
        hull = shape.convex_hull
        if not covers(hull, foreign, w / 2):
            return hull, False
        keep = unary_union(self.keep[lk]) if self.keep.get(lk) else None
        bars = lambda: whole_body(shape, foreign, w, True)   # noqa: E731
        return self.notched(lk, hull, own, keep, under, bars) if notch else (bars(), False)

    def notched(self, lk, hull, own, keep, under, bars):
        """``hull`` notched clear of the other links' points (:func:`bitten_plate`) and True, else ``bars()`` (a
        bell-crank's) and False. Its joints are its points but those in its slots and on its slotted bars (which
        ``keep`` holds). The notch about the driver's pivot leaves room for its arcs (:data:`DRIVER_ROOM`); a
        plate notched about a pivot whose crank would lie over it (:meth:`cranks_over`) is not notched, but where
        :attr:`under_cranks` is set and each such crank is long enough to carry its number (:meth:`bar_room`:
        over the plate, a number beside it reads as the plate's), it is, and noted in :attr:`beneath_cranks`."""
        m = self.m
        moving = {s.pin for s in m.slots if s.slot == lk} | {s.point for s in m.sliders if s.guide == lk}
        pts = [tuple(map(float, self.sol.place(lk, p))) for p in m.link(lk).points if p not in moving]
        drv = m.driver.link if not m.driver.is_slider else None
        pivot = next((p for p, links in self.pins_at.items() if drv in links and m.frame.name in links), None)
        room = None if pivot is None else (tuple(self.sol.place(drv, pivot)), DRIVER_ROOM * self.pc)
        g = bitten_plate(hull, foreign_bars(self.sol, lk, own), pts, self.st.bar_width * self.pc, keep,
                         unary_union(under) if under else None, (PEDESTAL * self.pc, (HATCH + GROUND_GAP) * self.pc),
                         room)
        cranks = [] if g is None else self.cranks_over(lk, hull, g)
        if cranks and self.under_cranks and all(self.bar_room(k) for k in cranks):
            self.beneath_cranks.add(lk)
        elif cranks:
            g = None   # a crank about its pivot in the notch, lying over the plate: its number (and arcs) need room
        if g is None and self.over_pivot(lk, hull):   # the whole plate beneath every link (:attr:`underlays`)
            self.underlays.add(lk)
            return hull, False
        return (g, True) if g is not None else (bars(), False)

    def over_pivot(self, lk, hull) -> bool:
        """Whether ``hull`` (link ``lk``'s plate) covers, within a bar width, a frame pivot of a link ``lk`` does
        not carry (a lever about a crank's pivot: :func:`under_crank`), the driver a turning link (a slider
        driver's arrows and values lie by its block, which such a plate would hold: its bars kept, as on main
        9945c0a, where a value then stood 1.03 cm out at a leader's end, over :data:`VALUE_NEAR`)."""
        w = self.st.bar_width * self.pc
        return not self.m.driver.is_slider and any(pivot and hull.distance(Point(*f)) < w
                   for f, _, pivot in foreign_bars(self.sol, lk, on_body(self.m, lk)))

    def cranks_over(self, lk, hull, plate) -> list:
        """The links pivoted on the frame near ``hull`` (within a bar width: in a notch of ``plate``) that lie over
        ``plate`` by more than :data:`CRANK_OVER` of their body (a slotted lever about its crank)."""
        m, w, out = self.m, self.st.bar_width * self.pc, []
        for p, links in self.pins_at.items():
            if m.frame.name not in links or lk in links:
                continue
            q = next(k for k in sorted(links) if k != m.frame.name)
            if hull.distance(Point(*self.sol.place(q, p))) >= w:
                continue
            for k in sorted(links - {m.frame.name}):
                body = self.bodies.get(k)
                if body is not None and plate.intersection(body).area > CRANK_OVER * body.area:
                    out.append(k)
        return out

    def bar_room(self, lk) -> list:
        """The sizes at which link ``lk``'s circled number fits on its bar, a bar at least twice ``end`` long:
        [(the fraction of its size, its Text keywords, ``end``)], where ``end`` is how far from each pin the circle's centre may come (the
        circle's radius, a pin's, :data:`ON_BAR_CLEAR` bar widths: the bar seen between them); at its size first,
        then smaller (:data:`SMALLER`: books set a short crank's number smaller on it). [] where the numbers are not
        circled, the link is not a bar or the bar is too short even so."""
        kw, pts = self.number_style(lk), self.m.link(lk).points
        if "bbox" not in kw or len(pts) != 2:
            return []
        a, b = (np.asarray(self.sol.place(lk, p), float) for p in pts)
        length, out = float(np.hypot(*(b - a))), []
        for f in (1.0, *SMALLER):
            sized = {**kw, "fontsize": kw["fontsize"] * f}
            end = self.number_radius(lk, sized) + (self.st.pin_radius + ON_BAR_CLEAR * self.st.bar_width) * self.pc
            if length >= 2 * end:
                out.append((f, sized, end))
        return out

    def link_shape(self, lk, under, notch: bool = True):
        """A moving link's body and how it is drawn: (the hull plate, "plate"), (a plate notched clear of another
        link's pins, "notched"), else (its bars, slotted bars, profiles or disc, None); (None, None) for a block."""
        sol, m, st = self.sol, self.m, self.st
        plate = None if self.extra_body.get(lk) else plate_outline(sol, lk, st.bar_width * self.pc)
        if plate is not None:     # a ternary (or larger) link: one plate with its corners at its points
            return plate, "plate"
        hull = None if self.extra_body.get(lk) or not notch else hull_plate(sol, lk, st.bar_width * self.pc)
        g, notched = (None, False) if hull is None else self.notched(lk, hull, (), None, under, lambda: None)
        if lk in self.underlays:
            return g, "under"
        if not notched:   # (else its plate would cover another link's pin, and no notch clears it: bars)
            parts = ([self.bodies[lk]] if lk in self.bodies else []) + self.extra_body.get(lk, [])
            if not parts and lk not in self.blocks:
                p = sol.place(lk, m.link(lk).points[0])
                parts = [Point(*p).buffer(2.2 * st.pin_radius * self.pc)]
            if parts:
                g = unary_union(parts)
            if g is not None and len(joints(m, lk)) >= 3:   # a plate with a slot, a guide or a profile, or bars
                g, notched = self.whole(lk, g, under, notch)
        return g, "notched" if notched else "under" if lk in self.underlays else None

    def link_shapes(self, order, drv):
        """Each link's body (link -> shapely geometry), and the order to draw them in: ``order`` with the plates
        notched clear of another link's pin (:meth:`link_shape`) moved beneath every link but those with a slot
        or a guide (so that the links crossing them are seen whole; the driver stays on top). A notched plate is
        cut clear of the bodies beneath it (the driver's of every other), and is drawn as bars after all where
        it lies under or over another link's plate (:meth:`stacked`: plates on plates read as one)."""
        m = self.m
        geoms, self.plates, self.filled, self.notched_links, moved = {}, {}, set(), set(), []
        for lk in order:
            under = [geoms[k] for k in geoms if lk == drv or lk in self.slotted or k in self.slotted or k in moved]
            g, kind = self.link_shape(lk, under)
            if kind in ("plate", "under"):
                self.plates[lk] = g
            if kind == "under" or kind != "plate" and g is not None and len(joints(m, lk)) >= 3:
                self.filled.add(lk)   # (a plate beneath the links: its slotted bar, if any, a block's marks keep off)
            if g is not None:
                geoms[lk] = g
            if kind == "notched":
                self.notched_links.add(lk)
                moved += [lk] if lk != drv and lk not in self.slotted else []
        for lk in [k for k in order if k in self.notched_links and self.stacked(k, geoms)]:
            geoms[lk] = self.link_shape(lk, None, notch=False)[0]
            self.notched_links.discard(lk)
            moved = [k for k in moved if k != lk]
        first = [lk for lk in order if lk in self.underlays] + [lk for lk in order if lk in self.slotted
                                                                 and lk not in self.underlays]
        return geoms, first + moved + [lk for lk in order if lk not in first and lk not in moved]

    def stacked(self, lk, geoms) -> bool:
        """Whether the body of ``lk`` overlaps another link's plate (a link of three or more joints) by more than
        a bar's width squared, away from the joints they share."""
        m, w = self.m, self.st.bar_width * self.pc
        for k, g in geoms.items():
            if k == lk or len(joints(m, k)) < 3:
                continue
            shared = joints(m, k) & joints(m, lk)
            over = geoms[lk].intersection(g)
            if shared and not over.is_empty:
                over = over.difference(unary_union([Point(*self.sol.place(lk, j)).buffer(w) for j in shared
                                                    if lk in m.carriers.get(j, ())]))
            if over.area > w * w:
                return True
        return False

    def hatch(self, a, b, side, role="ground", zorder=1.0, exempt=()):
        """A ground line a-b with short slanted strokes on ``side`` (a unit normal).

        Drawn once the links' bodies are known (:meth:`draw_hatches`): ground never crosses a
        moving link, so the line and its strokes stop where a body (other than the ``exempt``
        links', those pinned to this ground) lies over them.
        """
        self.hatches.append((np.asarray(a, float), np.asarray(b, float), np.asarray(side, float), role, zorder,
                             frozenset(exempt)))

    def hatch_strokes(self, a, b, side):
        """The ground line and its strokes [(p, q), ...], and the hatched strip's polygon."""
        d = b - a
        length = float(np.hypot(*d))
        u = d / length
        step = 0.14 * self.pc
        tick = 0.2 * self.pc
        slant = (side + u * 0.75) / np.hypot(*(side + u * 0.75))
        segs = [(a, b)]
        n = max(int(length / step), 1)
        for i in range(n + 1):
            p = a + u * (i * length / n)
            segs.append((p, p + slant * tick))
        strip = SPolygon([tuple(a), tuple(b), tuple(b + slant * tick), tuple(a + slant * tick)])
        return segs, strip

    def forbidden(self, exempt=()):
        """The moving links' bodies ground must keep clear of (the ``exempt`` links' excepted)."""
        return unary_union([g for lk, g in self.geoms.items() if lk not in exempt] or [Point(0, 0).buffer(0)])

    def draw_hatches(self):
        from matplotlib.collections import LineCollection
        margin = 0.6 * self.pp
        for a, b, side, role, zorder, exempt in self.hatches:
            segs, strip = self.hatch_strokes(a, b, side)
            keep = self.forbidden(exempt).buffer(margin)
            lines, widths = [], []
            for i, (p, q) in enumerate(segs):
                rest = LineString([tuple(p), tuple(q)]).difference(keep)
                for piece in getattr(rest, "geoms", [rest]):
                    if not piece.is_empty and piece.length > 1e-9 * self.pc:
                        lines.append(np.asarray(piece.coords))
                        widths.append(self.st.link_lw if i == 0 else self.st.thin_lw)
            if not lines:
                continue
            lc = LineCollection(lines, colors=self.st.ink, linewidths=widths, zorder=zorder)
            self.art.exempt[lc] = exempt
            self.ax.add_collection(lc)
            self.art.add(role, lc)
            # the hatched strip itself (the strokes lie on one side of the line), with a little margin
            self.pl.add_obstacle(strip.difference(keep).buffer(0.05 * self.pc), hard=False)
            self.grounds.append(strip.difference(keep))

    def pin(self, p, gid=None, radius=None):
        r = (radius or self.st.pin_radius) * self.pc
        c = Point(*p).buffer(r, quad_segs=10)
        self.patch(c, "pins", 5, self.st.paper, lw=self.st.link_lw, gid=gid)
        self.pl.add_obstacle(c)

    # -- frame ---------------------------------------------------------------------------
    def ground_pivot(self, point, links):
        """A pivot's pedestal and hatched ground, on the side most free of links: of the eight
        directions, the one whose ground crosses no other link's body (the least of them), then the
        one most free of this pivot's links, downwards when that is nearly as free."""
        p = self.sol.position[point] if point in self.sol.position else self.sol.place(self.m.frame.name, point)
        p = np.asarray(p, float)
        away = _unit(away_from(p, neighbours(self.sol, point, links)))
        pc = self.pc
        others = self.forbidden(set(links))

        def shape(g):
            u = _unit(g)
            n = _perp(u)
            apex, base = p, p + u * PEDESTAL * pc
            tri = SPolygon([apex + n * 0.12 * pc, base + n * 0.3 * pc, base - n * 0.3 * pc, apex - n * 0.12 * pc])
            return u, n, base, tri, tri.union(self.hatch_strokes(base + n * HATCH * pc, base - n * HATCH * pc, u)[1])

        def score(g):
            crossed = others.intersection(shape(g)[4]).area / (pc * pc)
            return (-round(crossed, 3), float(np.dot(_unit(g), away)) + (0.45 if g == -90 else 0)
                    + (0.1 if g % 90 == 0 else 0))

        g = max((-90.0, 0.0, 180.0, 90.0, -45.0, -135.0, 45.0, 135.0), key=score)
        u, n, base, tri, whole = shape(g)
        # over the link bodies: a pivot inside a plate or a cam disc keeps its ground in sight
        z, exempt = self.ground_layer(p, links, whole)
        self.patch(tri, "ground", z, self.st.paper, lw=self.st.link_lw)
        self.pl.add_obstacle(tri)
        self.hatch(base + n * HATCH * pc, base - n * HATCH * pc, u, zorder=z, exempt=exempt)
        return g

    def ground_layer(self, p, links, ground) -> tuple[float, set]:
        """A pivot's ground's zorder and the links its hatching may cross, so that every frame pivot shows its
        ground. It lies over the link bodies (2.9), and over the driver's too (3.3, drawn over the links it
        drives) where the driver's body would hide it: a quarter or more of the ground (pedestal and hatching)
        inside it, as a cam's or a gear's disc about its own pivot. Its hatching keeps off other links' bodies,
        but for those the pivot lies in (a pinion's pivot inside its internal gear's disc), which it cannot
        keep off."""
        drv = None if self.m.driver.is_slider else self.m.driver.link
        body = self.geoms.get(drv) if drv in links and drv not in self.slotted else None
        z = 3.35 if body is not None and body.intersection(ground).area >= 0.25 * ground.area else 2.9
        return z, set(links) | {lk for lk, g in self.geoms.items() if g.contains(Point(*p))}

    # -- sliders, slots, contacts --------------------------------------------------------
    def _path_segment(self, p, d, half):
        return LineString([tuple(p - d * half), tuple(p + d * half)])

    def _clipped_to_link(self, path, p, d, link, point, L, H):
        """A moving guide's straight path, cut short of the guide link's other pins on it.

        A slotted lever's slot runs between its pins (a pin at the slot's end would sit in the
        slot, its label inside the bar), but always leaves the block room to show it sliding.
        """
        sol = self.sol
        (x0, y0), (x1, y1) = path.coords
        lo = float(np.dot(np.array([x0, y0]) - p, d))
        hi = float(np.dot(np.array([x1, y1]) - p, d))
        keep = L / 2 + 0.25 * self.pc                    # the block and a little travel either side
        clear = 2.2 * self.st.pin_radius * self.pc + H / 2   # from a pin to the slot's end
        for q in self.m.link(link).points:
            if q == point:
                continue
            v = sol.place(link, q) - p
            t = float(np.dot(v, d))
            if abs(float(_perp(d) @ v)) > H:             # off the path's line: the slot passes it by
                continue
            if t > 0:
                hi = min(hi, max(t - clear, keep))
            elif t < 0:
                lo = max(lo, min(t + clear, -keep))
        return LineString([tuple(p + d * lo), tuple(p + d * hi)])

    def _arc(self, k, radius, mid, half_angle):
        a = np.linspace(mid - half_angle, mid + half_angle, 48)
        return LineString(np.c_[k[0] + radius * np.cos(a), k[1] + radius * np.sin(a)])

    def slider(self, i, s, r):
        sol, st, pc = self.sol, self.st, self.pc
        p = sol.place(s.block, s.point)
        d = _unit(float(r["direction"][0]))
        L, H = st.block[0] * pc, st.block[1] * pc
        n = _perp(d)
        side = -self.guide_side(s, p, n)   # the guide's hatch away from the links
        if s.centre is None:
            path = self._path_segment(p, d, 2.1 * L)
            if not self.m.link(s.guide).frame:
                path = self._clipped_to_link(path, p, d, s.guide, s.point, L, H)
        else:
            k = sol.place(s.guide, s.centre)
            rad = float(np.hypot(*(p - k)))
            mid = math.atan2(*(p - k)[::-1])
            path = self._arc(k, rad, mid, min(2.1 * L / max(rad, 1e-300), 2.6))
        if self.m.link(s.guide).frame:
            surface = path.offset_curve(side * H / 2) if s.centre is None else \
                self._arc(k, rad + side * H / 2 * (1 if np.dot(n, p - k) >= 0 else -1), mid,
                          min(2.1 * L / max(rad, 1e-300), 2.6))
            coords = np.asarray(surface.coords)
            for a, b in zip(coords[:-1], coords[1:]):
                seg_n = _perp((b - a) / max(np.hypot(*(b - a)), 1e-300))
                if np.dot(seg_n, n * side) < 0:
                    seg_n = -seg_n
                self.hatch(a, b, seg_n, role="guides")
            self.centre_line(path)
        else:
            bar = path.buffer(H / 2 + 0.09 * pc, cap_style="flat")
            self.profile(s.guide, bar)
            self.guide_bars[s.guide] = unary_union([self.guide_bars.get(s.guide, bar), bar])
            self.slotted.add(s.guide)
            self.slots.append((s.guide, path.buffer(H * 0.3, cap_style="round")))
        block = SPolygon([p - d * L / 2 - n * H / 2, p + d * L / 2 - n * H / 2, p + d * L / 2 + n * H / 2,
                          p - d * L / 2 + n * H / 2])
        fill = link_fill(self.m, self.opts, st, s.block)
        self.patch(block, "sliders", 3.2, fill, gid=f"block-{s.block}")
        self.outlines.setdefault(s.block, []).append(block)
        self.pl.add_obstacle(block, hard=False)
        self.block_geom[s.block] = block

    def frame_profile(self, place, outward, centre, exempt=()):
        """The frame's side of a contact: a hatched line along the tangent, or a hatched arc about its centre.

        ``outward`` points from the contact into the frame's material.
        """
        pc = self.pc
        t = _perp(outward)
        if centre is None:
            self.hatch(place - t * 1.6 * pc, place + t * 1.6 * pc, outward, role="contacts", exempt=exempt)
            return
        rad = float(np.hypot(*(place - centre)))
        mid = math.atan2(*(place - centre)[::-1])
        arc = np.asarray(self._arc(centre, rad, mid, min(1.6 * pc / max(rad, 1e-300), 2.6)).coords)
        for a, b in zip(arc[:-1], arc[1:]):
            n = _perp((b - a) / max(float(np.hypot(*(b - a))), 1e-300))
            if np.dot(n, outward) < 0:
                n = -n
            self.hatch(a, b, n, role="contacts", exempt=exempt)

    def centre_line(self, path):
        from matplotlib.lines import Line2D
        xy = np.asarray(path.coords)
        ln = Line2D(xy[:, 0], xy[:, 1], lw=self.st.thin_lw, color=self.st.ink, linestyle=(0, (8, 2, 1.5, 2)),
                    zorder=1.1)
        self.ax.add_line(ln)
        self.art.add("guides", ln)
        self.pl.add_obstacle(path, hard=False)   # a label (its point's own) rather off the path it reads along

    def slot_ends(self, s):
        """The positions of a slot's ``ends`` (FORMAT.md ``[[slots]] ends``) now, or None without them."""
        ends = s.ends
        if not ends:
            return None
        return [np.asarray(self.sol.place(s.slot, e), float) for e in ends]

    def slot_path(self, s, r):
        """The centre line of a slot's cut: along its path, through the pin's travel.

        Straight: between its ``ends`` where the file gives them; else a length about the pin,
        cut short of the slot link's other points on its line (a slotted lever's slot stops
        before the lever's pivot: it does not enclose it). Circular: an arc about K through the pin.
        """
        sol, st, pc = self.sol, self.st, self.pc
        p = sol.place(s.link, s.pin)
        w = 2.6 * st.pin_radius * pc
        half = 1.6 * st.block[0] * pc
        if s.centre is not None:
            k = sol.place(s.slot, s.centre)
            rad = float(np.hypot(*(p - k)))
            mid = math.atan2(*(p - k)[::-1])
            ends = self.slot_ends(s)
            if ends:
                a = sorted(math.atan2(*(e - k)[::-1]) for e in ends)
                a0, a1 = a if a[1] - a[0] <= math.pi else (a[1], a[0] + 2 * math.pi)
                return self._arc(k, rad, (a0 + a1) / 2, (a1 - a0) / 2)
            return self._arc(k, rad, mid, min(half / max(rad, 1e-300), 2.6))
        d = _unit(float(r["direction"][0]))
        ends = self.slot_ends(s)
        if ends:
            ts = sorted(float(np.dot(e - p, d)) for e in ends)
            return LineString([tuple(p + d * ts[0]), tuple(p + d * ts[1])])
        path = self._path_segment(p, d, half)
        if self.m.link(s.slot).frame:
            return path
        return self._clipped_to_link(path, p, d, s.slot, s.pin, 2.0 * w, w)

    def slot(self, i, s, r):
        """A pin's slot cut in its link's body: the body reaches round the slot (attached to the link)."""
        st, pc = self.st, self.pc
        w = 2.6 * st.pin_radius * pc
        path = self.slot_path(s, r)
        cut = path.buffer(w / 2, cap_style="round")
        if self.m.link(s.slot).frame:
            self.patch(path.buffer(w / 2 + 0.12 * pc, cap_style="round"), "guides", 1.3, st.paper)
            self.slots.append((None, cut))
            return
        # the slotted part of the body, joined to the rest of the link: the hull of the link's own points
        # (the pin's point excepted: it is the slot's) and of the slot's centre line, as one plate or bar
        m = self.m
        own = [tuple(self.sol.place(s.slot, q)) for q in m.link(s.slot).points if q != s.pin]
        line = list(path.coords)
        if own:   # the nearest of the link's points first: bars from it where a plate would cover others' pins
            own.sort(key=lambda q: path.distance(Point(*q)))
        web = body_shape(own[:1] + [line[0], line[-1]] + own[1:], foreign_points(self.sol, s.slot, {s.pin}),
                         st.bar_width * pc)
        rim = path.buffer(w / 2 + 0.12 * pc, cap_style="round")
        self.extra_body.setdefault(s.slot, []).append(web.union(rim))
        self.keep.setdefault(s.slot, []).append(rim)
        self.slotted.add(s.slot)
        self.slots.append((s.slot, cut))
        self.slot_cuts[i] = (s.slot, path, cut)

    def profile(self, lk, geom):
        """A part of a link's body that a notch must leave whole (a slotted bar, a profile)."""
        self.extra_body.setdefault(lk, []).append(geom)
        self.keep.setdefault(lk, []).append(geom)

    def equivalent_linkage(self, i, c, place, t):
        """A sliding contact's equivalent linkage, dashed: the coupler joining the two centres of
        curvature, or (one profile flat) a block at the other's centre sliding parallel to the flat.
        The polygons are constructed through it (docs/polygons.md)."""
        from matplotlib.lines import Line2D
        st, pc = self.st, self.pc
        ca, cb = (None if n is None else np.asarray(self.sol.place(lk, n), float)
                  for lk, n in zip(c.links, c.centres))
        dash = (0, (4, 2))
        lines = []
        if ca is not None and cb is not None:
            lines.append([ca, cb])
            for q in (ca, cb):   # the coupler's pins
                ring = Point(*q).buffer(0.6 * st.pin_radius * pc, quad_segs=8)
                p = shape_patch(ring, facecolor="none", edgecolor=st.ink, lw=st.thin_lw, zorder=4.6, linestyle=dash)
                add_patch(self.ax, p)
                self.art.add("equivalent", p)
        else:
            q = ca if ca is not None else cb
            lines.append([q - t * 1.2 * pc, q + t * 1.2 * pc])
            n = _perp(t)
            L, H = 0.5 * pc, 0.3 * pc
            block = [q - t * L / 2 - n * H / 2, q + t * L / 2 - n * H / 2, q + t * L / 2 + n * H / 2,
                     q - t * L / 2 + n * H / 2, q - t * L / 2 - n * H / 2]
            lines.append(block)
        for xy in lines:
            xy = np.asarray(xy, float)
            ln = Line2D(xy[:, 0], xy[:, 1], lw=st.thin_lw * 1.3, color=st.ink, linestyle=dash, zorder=4.6,
                        gid=f"equivalent-{i}")
            self.ax.add_line(ln)
            self.art.add("equivalent", ln)
            self.pl.add_obstacle(LineString([tuple(q) for q in xy]), hard=False)   # labels rather off it

    def contact(self, i, c, r):
        sol, st, pc = self.sol, self.st, self.pc
        place = np.asarray(r["place"][0], float)
        u = _unit(float(r["normal"][0]))
        t = _perp(u)
        from matplotlib.lines import Line2D
        if equivalent(c):
            self.equivalent_linkage(i, c, place, t)
        if c.centres is None:
            for a, b, ls in ((place - t * 1.2 * pc, place + t * 1.2 * pc, "-"),
                             (place - u * 1.5 * pc, place + u * 1.5 * pc, (0, (8, 2, 1.5, 2)))):
                ln = Line2D([a[0], b[0]], [a[1], b[1]], lw=st.link_lw if ls == "-" else st.thin_lw,
                            color=st.ink, linestyle=ls, zorder=2.9)
                self.ax.add_line(ln)
                self.art.add("contacts", ln)
                self.pl.add_obstacle(LineString([tuple(a), tuple(b)]), hard=False)   # labels rather off them
            return
        for j, (lk, cn) in enumerate(zip(c.links, c.centres)):
            if self.m.link(lk).frame:   # the frame's profile: a hatched surface (flat) or arc
                self.frame_profile(place, u if j == 1 else -u, None if cn is None else sol.place(lk, cn),
                                   exempt=set(c.links))
                continue
            if cn is None:  # a flat profile: a straight edge through the contact, along the tangent
                if lk in self.bodies:      # a link with a shape of its own shows the face already
                    continue
                inward = -u if j == 0 else u     # the flat's link lies behind its edge
                # a one-point link (a flat-faced follower): a plate on a stem from its point to the face
                own = sol.place(lk, self.m.link(lk).points[0])
                foot = place + t * float(np.dot(own - place, t))
                half = max(1.4 * pc, abs(float(np.dot(place - foot, t))) + 0.6 * pc)
                e0, e1 = foot - t * half, foot + t * half
                geom = SPolygon([e0, e1, e1 + inward * 0.22 * pc, e0 + inward * 0.22 * pc])
                if float(np.hypot(*(own - foot))) > 0.3 * pc:
                    geom = geom.union(LineString([tuple(own), tuple(foot)]).buffer(st.bar_width * pc / 2,
                                                                                  cap_style="flat"))
                self.profile(lk, geom)
                continue
            ctr = sol.place(lk, cn)
            rad = float(np.hypot(*(place - ctr)))
            if rad < 1.5 * self.m.size:
                self.profile(lk, Point(*ctr).buffer(rad, quad_segs=32))
            else:
                mid = math.atan2(*(place - ctr)[::-1])
                arc = self._arc(ctr, rad, mid, min(2.0 * pc / rad, 1.0))
                self.profile(lk, arc.buffer(0.11 * pc, cap_style="flat"))

    # -- the whole -----------------------------------------------------------------------
    def draw(self):
        sol, m, st = self.sol, self.m, self.st
        frame = m.frame.name
        self.block_geom = {}
        for i, (s, r) in enumerate(zip(m.sliders, sol.motion.sliders)):
            self.slider(i, s, r)
        for i, (s, r) in enumerate(zip(m.slots, sol.motion.slots)):
            self.slot(i, s, r)
        for i, (c, r) in enumerate(zip(m.contacts, sol.motion.contacts)):
            self.contact(i, c, r)
        # bodies, in file order (later links over earlier ones)
        order = [k.name for k in m.moving_links]
        # a link with a slot or a moving guide lies under the others (the crank that drives the block
        # in a slotted lever is seen over the lever), otherwise file order: later links over earlier ones
        order = [lk for lk in order if lk in self.slotted] + [lk for lk in order if lk not in self.slotted]
        drv = None if m.driver.is_slider else m.driver.link
        if drv in order and drv not in self.slotted:   # the driver over the links it drives (the crank seen
            order = [lk for lk in order if lk != drv] + [drv]   # over the lever or the block it turns)
        geoms, order = self.link_shapes(order, drv)
        self.geoms = geoms
        # ground pivots, clear of the bodies
        ground_dir = {}
        for point, links in self.pins_at.items():
            if frame in links:
                ground_dir[point] = self.ground_pivot(point, sorted(links - {frame}))
        self.draw_hatches()
        self.art.bodies = dict(geoms)                # link -> its drawn body (shapely), for checks
        self.art.plates = {k: g for k, g in self.plates.items() if k not in self.underlays}   # link -> its plate
        #                                                                                       (the hull of its points)
        self.art.notched = set(self.notched_links)   # the plates notched clear of another link's pins
        self.art.underlays = set(self.underlays)     # the plates drawn whole beneath every link (over a pivot)
        self.art.slot_cuts = dict(self.slot_cuts)    # slot index -> (link, centre line, cut)
        self.art.guide_bars = {k: g for k, g in self.guide_bars.items() if k in self.filled}   # a plate's slotted bar
        for z, lk in enumerate(order):
            if lk in geoms:
                zorder = self.zorders[lk] = 3.3 if lk == drv and lk not in self.slotted else 2 + 0.01 * z
                self.body(lk, geoms[lk], zorder)
                # its outline, not its area: a label may sit inside a plate or a wheel, clear of its edges
                self.outline(lk, geoms[lk])
        for lk, g in self.slots:
            z = 2.5 if lk is None else 2 + 0.01 * order.index(lk) + 0.005
            self.patch(g, "links", z, st.paper, lw=st.thin_lw * 1.5)
            self.outline(lk, g)
        # pins and points
        self.points(ground_dir)
        self.seen_as_outline(geoms)
        self.marks(ground_dir, self.geoms)
        self.art.add("scale_bar", *scale_bar(self.ax, st, m.units, 0))
        return self.art

    def seen_as_outline(self, geoms):
        """The marks' view of the bodies (:attr:`geoms`): a plate beneath every link (:attr:`underlays`) is its
        outline, a line width wide (:attr:`Artists.seen`): over it the links, their pins, numbers and the driver's
        arcs are drawn as on the paper, and a mark reads as the link nearest it, the plate's where by its edge; a
        mark across that edge reads as crossing the plate."""
        seen = {lk: geoms[lk].boundary.buffer(0.6 * self.pp) for lk in sorted(self.underlays)}
        self.geoms = {**geoms, **seen}
        self.art.seen = seen

    def outline(self, lk, g):
        """A body's or slot's outline, a soft obstacle (a label may sit inside a plate, clear of its edges), kept as
        link ``lk``'s (:attr:`outlines`)."""
        line = g.boundary.buffer(0.6 * self.pp)
        self.outlines.setdefault(lk, []).append(line)
        self.pl.add_obstacle(line, hard=False)

    def marks(self, ground_dir, geoms):
        """The driver's arrows and values, the link numbers, then the point labels: the labels come last, so
        their places in a clear field are found first (:attr:`reserved`), and the driver's values keep off them.
        Where a link number then reads as another link's (:meth:`owned`: the values took the places by its short
        crank), the places the numbers find with the driver's arrows alone drawn are found first too, and the values
        keep off those that read as their links' (a value has more room by its arrow than a number by its link);
        where that is no better, the first pass is put back as it was drawn (kept aside: the same artists, not drawn
        again). A plate beneath a crank whose marks already do not read (:meth:`refused`) goes no further."""
        labelled = self.opts.label_points is None or self.opts.label_points
        if labelled and self.bare:   # (on a poles sheet the poles' labels, placed after, need that room too)
            with self.pl.trial():
                self.reserved = self.point_labels(record=False)
        drawn, aside = _roles(self.art), []
        with self.pl.trial(aside):
            self.driver(ground_dir)      # before the link numbers, which then keep clear of its arrow
            if self.refused():           # (its arrows across another link: whatever the numbers)
                return None
            astray = _astray(self.link_numbers(geoms))
            self.pl.keep = not astray
        if not astray:
            return self.point_labels() if labelled else None
        first = (_roles(self.art), self.astray)   # the first pass, kept aside (put back, not drawn again, below)
        self.art.clear()
        self.art.update(drawn)
        points = self.reserved
        with self.pl.trial():
            self.driver(ground_dir, values=False)
            alone = self.link_numbers(geoms, record=False)
        with self.pl.trial():            # kept where fewer numbers read as another link's
            self.reserved = points + [b for b, ok in alone.values() if ok]
            self.driver(ground_dir)
            self.reserved = points
            better = self.pl.keep = len(_astray(self.link_numbers(geoms))) < len(astray)
        if not better:   # the first pass as it was drawn
            self.art.clear()
            self.art.update(first[0])
            self.astray = first[1]
            self.pl.back_to(aside[0])
        if labelled and not self.refused():
            self.point_labels()

    def points(self, ground_dir):
        sol, m, st = self.sol, self.m, self.st
        from matplotlib.lines import Line2D
        centres = {cn for c in m.contacts for cn in (c.centres or ()) if cn}
        contact_pts = {c.point for c in m.contacts}
        path_centres = {s.centre for s in (*m.sliders, *m.slots) if s.centre}
        for name, keys in _groups(sol).items():
            p = keys[0][1]
            if name in self.pins_at or name in {s.pin for s in m.slots}:
                self.pin(p, gid=f"pin-{name}")
            elif name in centres or name in path_centres:
                h = 0.12 * self.pc
                ln = Line2D([p[0] - h, p[0] + h, np.nan, p[0], p[0]], [p[1], p[1], np.nan, p[1] - h, p[1] + h],
                            lw=st.thin_lw, color=st.ink, zorder=4)
                self.ax.add_line(ln)
                self.art.add("points", ln)
                self.pl.add_obstacle(Point(*p).buffer(h))
            else:
                r = 0.045 * self.pc if name not in contact_pts else 0.06 * self.pc
                self.patch(Point(*p).buffer(r, quad_segs=8), "points", 4, st.ink, lw=0)
                self.pl.add_obstacle(Point(*p).buffer(r))

    def off_links(self, links):
        """The test a point label's box (data coordinates) passes where it reads as its point's: over no body
        (link or block) but those of ``links`` (the point's own; where one of them lies over another link, as a
        gear inside an internal gear, the label may stand on it), and on no body's outline."""
        bodies = {**self.block_geom, **self.geoms}
        outlines = np.array([g.boundary for g in bodies.values()], dtype=object)
        z = self.zorders

        def seen(k, g):   # the part of another link's body that none of the point's own links lies over
            over = [bodies[j] for j in links if j in bodies and z.get(j, 0) > z.get(k, 0)]
            return g.difference(unary_union(over)) if over else g
        others = np.array([seen(k, g) for k, g in bodies.items() if k not in links], dtype=object)

        def test(b) -> bool:
            return not (shapely.intersects(outlines, b).any() or shapely.intersects(others, b).any())
        return test

    def _point_label(self, pos, text, links, **kw):
        """A point's label placed where it reads as its point's (:meth:`off_links`: a free place with a leader,
        if need be, within :data:`LABEL_NEAR` of the point, rather than one over another link's plate or on an
        outline), else where it is free."""
        test = self.off_links(links)
        with self.pl.trial():
            n = len(self.pl.overlapping)
            t = self.pl.place(pos, text, accept=test, only=True, **kw)
            b = self.pl.of(t).box
            kept = self.pl.keep = len(self.pl.overlapping) == n and test(b) and \
                b.distance(Point(*pos)) <= LABEL_NEAR * self.pc
        return t if kept else self.pl.place(pos, text, **kw)

    def point_labels(self, record: bool = True) -> list:
        """Each point's label beside it, away from its links, where it can off the other links' bodies and
        off every outline (:meth:`off_links`); returns their boxes with their leaders (``record``: kept as the
        drawing's labels)."""
        sol, m, st = self.sol, self.m, self.st
        out = []
        wanted = self.opts.label_points
        for name, keys in _groups(sol).items():
            if wanted is not None and name not in wanted:
                continue
            spots = [keys[0]]
            for key, pos in keys[1:]:   # keys of one point that have drifted apart get their own label
                if all(np.hypot(*(pos - q)) > 1e-9 * m.size for _, q in spots):
                    spots.append((key, pos))
            for key, pos in spots:
                links = m.carriers.get(name, ())
                prefer = away_from(pos, neighbours(sol, name, links), default=45.0)
                text = tex(name) if len(spots) == 1 else tex(key_text(key))   # P₂, velpoly.names
                t = self._point_label(pos, text, links, prefer=prefer, fontsize=st.font_size, zorder=7,
                                      fontstyle="italic",
                                      gid=f"label-point-{name}" if len(spots) == 1 else f"label-point-{key}")
                own = self.pl.of(t)   # (with its leader, if any: a value or number across it sends the label elsewhere)
                b = self.pl.box_of(t, pad=0.0)
                out.append(b if own is None or own.leader_geom is None else b.union(own.leader_geom))
                if not record:
                    continue
                if not self.off_links(links)(self.pl.of(t).box if own is not None else b):
                    self.astray.append(name)   # (where no place that reads as its point's was free)
                self.art.add("labels", t)
                for k, q in keys:
                    if len(spots) == 1 or k == key:
                        self.art.labels[k] = t
        return out

    def number_style(self, lk) -> dict:
        """The Text keywords of a link's number: circled (by default); on slides, the circle no larger in
        radius than NUMBER_RADIUS bar widths (the type set smaller to fit), so that it is no bigger than
        the link it names. Found once per link for the drawing (each pass of :meth:`marks` asks again): a copy."""
        if lk not in self.styles:
            self.styles[lk] = self._number_style(lk)
        kw = dict(self.styles[lk])
        return kw if "bbox" not in kw else {**kw, "bbox": dict(kw["bbox"])}

    def _number_style(self, lk) -> dict:
        """:meth:`number_style`'s keywords, found (on slides, the type size by measuring the circle)."""
        st = self.st
        kw = dict(fontsize=st.small_size * 1.1, zorder=7)
        if self.opts.link_numbers != "circled":
            return kw
        kw["bbox"] = dict(boxstyle="circle,pad=0.18", facecolor=st.paper, edgecolor=st.ink, lw=st.thin_lw * 1.4)
        if st.name != "slides":
            return kw
        limit = NUMBER_RADIUS * st.bar_width * self.pc
        for _ in range(6):
            r = self.number_radius(lk, kw)
            if r <= limit * (1 + 1e-6):
                break
            kw["fontsize"] *= 0.97 * limit / r
        return kw

    def number_radius(self, lk, kw) -> float:
        """The radius (data units) of a link number's circle drawn with ``kw`` (:meth:`number_style`'s, at its type
        size or one tried there: measured once for the drawing)."""
        key = (lk, kw["fontsize"])
        if key not in self.radii:
            t = self.ax.text(0, 0, literal(lk), ha="center", va="center", **kw)
            r = self.pl.renderer
            t.update_bbox_position_size(r)
            bb = t.get_bbox_patch().get_window_extent(r)
            t.remove()
            self.radii[key] = max(bb.width, bb.height) / 2 / self.ax.figure.dpi * 72 * self.pp
        return self.radii[key]

    def link_numbers(self, geoms, record: bool = True) -> dict:
        """Every moving link's number beside or on its own link: a bar's beside its middle, a plate's inside it, a
        block's beside it; each nearer its own link than any other, with nothing between (:meth:`owned`), where
        any such place is free; else where it was placed before that rule. Returns link -> (its number's box with
        its margin and leader, whether it reads as its link's there) (``record``: kept as the drawing's numbers)."""
        out = {}
        if self.opts.link_numbers == "none":
            return out
        sol, m = self.sol, self.m
        centre = np.mean(np.array(list(sol.position.values())), axis=0)
        bodies = {**self.block_geom, **geoms}
        for lk in [k.name for k in m.moving_links]:
            g = bodies.get(lk)
            if g is None:
                continue
            pts = [sol.place(lk, p) for p in m.link(lk).points]
            if len(pts) >= 2:
                a, b = pts[0], pts[1]
                anchor = (a + b) / 2 if len(pts) == 2 else np.array(g.centroid.coords[0])
                n = _perp((b - a) / max(np.hypot(*(b - a)), 1e-300))
                if np.dot(n, anchor - centre) < 0:
                    n = -n
                prefer = math.degrees(math.atan2(n[1], n[0]))
            else:   # a one-point link (a gear or cam turning about its pivot): no bar to stand beside
                anchor, n = np.array(g.centroid.coords[0]), None
                prefer = away_from(anchor, [centre], default=90.0)
            kw = self.number_style(lk)
            pad = 3.5 if "bbox" in kw else 1.0
            t = on_bar = None
            if len(pts) == 2:   # a leader from a point of the bar no other link covers (its middle, if free)
                mine = next((a + (b - a) * f for f in (0.5, 0.38, 0.62, 0.27, 0.73, 0.16, 0.84)
                             if not self._covered(lk, a + (b - a) * f)), anchor)
            else:
                mine = anchor
            test = self.owned(lk, bodies, mine)
            with self.pl.trial():   # where the rule below would put it, if it reads as its link's there, off the lines
                t = self._first_number(lk, pts, g, anchor, prefer, n, pad, kw)
                owned = test(self.pl.of(t).box)
                b = self._number_box(t)
                self.pl.keep = owned and not self.pl.soft_hits(b) and self._unreserved(b)
            if not self.pl.of(t):   # else a place that reads as its own, off the lines (near it, else on a grid)
                clear = self._off_lines(lk, kw, test)
                t = self._link_number(lk, pts, g, mine, prefer, n if len(pts) >= 2 else None, pad, kw, clear, True)
                if t is None:
                    t = self._number_beside(lk, bodies, mine, pad, kw, nearest=True)
                if t is None and len(pts) == 2:
                    t = on_bar = self._number_on_bar(lk, pts)
                if t is None:
                    t = self._number_last(lk, pts, g, (anchor, mine), prefer, n, pad, kw, test, owned, bodies)
            own, ring = self.pl.of(t), self._number_box(t)   # (the box it keeps, its margin too: a value in it
            b = ring if own is None else own.box.union(ring)   # would send it elsewhere)
            out[lk] = (b if own is None or own.leader_geom is None else b.union(own.leader_geom),
                       own is None or t is on_bar or test(ring))   # its circle, as drawn
            if record:
                self.art.add("link_numbers", t)
        if record:
            self.astray = _astray(out)   # (the point labels, placed after, add theirs)
        return out

    def reads(self) -> bool:
        """Whether the marks read as drawn: every link number as its own link's (:meth:`owned`), every point label
        as its point's (:meth:`off_links`) and the driver's arrows across no other link or block
        (:meth:`arrows_clear`). A plate beneath a crank (:attr:`under_cranks`) is kept only where they do."""
        return not self.astray and self.arrows_clear()

    def refused(self) -> bool:
        """Whether a plate drawn beneath a crank (:attr:`beneath_cranks`) is refused already, as far as the marks
        are drawn (:meth:`reads`: the driver's arrows across another link, or a number or label astray, which
        nothing placed later mends): the drawing is thrown away (:func:`draw_mechanism`), so its marks go no
        further."""
        return bool(self.beneath_cranks) and not self.reads()

    def arrows_clear(self) -> bool:
        """Whether the driver's arrows cross no other link or block (a slider driver's: but those pinned at its
        point, and its guide's plate off the slotted bar)."""
        from matplotlib.lines import Line2D
        drv = self.m.driver
        own = set(self.m.carriers.get(drv.slider, ())) if drv.is_slider else {drv.link}
        bodies = {**self.geoms, **self.block_geom}
        if drv.is_slider:
            bodies.update({s.guide: self.guide_bars[s.guide] for s in self.m.sliders
                           if s.point == drv.slider and s.guide in self.guide_bars})
        others = [g for k, g in bodies.items() if k not in own]
        arrows = [LineString(np.column_stack(a.get_data())) for a in self.art.get("driver", [])
                  if isinstance(a, Line2D) and len(a.get_xdata()) >= 2]
        return not any(a.intersects(g) for a in arrows for g in others)

    def _number_last(self, lk, pts, g, anchors, prefer, n, pad: float, kw, test, owned: bool, bodies):
        """Link ``lk``'s number where no place off the lines reads as its own: where the first rule's place does not
        read as its own, one that does (``test``), else the first rule's; unless that lies on a line and a free place
        beside the link is on none (:meth:`_number_beside`, ``nearest=False``: text never on lines comes first).
        ``anchors``: the first rule's anchor and the point of the link a leader starts from."""
        anchor, mine = anchors

        def last():
            t = None if owned else self._link_number(lk, pts, g, mine, prefer, n if len(pts) >= 2 else None, pad,
                                                     kw, test)
            return t if t is not None else self._first_number(lk, pts, g, anchor, prefer, n, pad, kw)
        aside = []
        with self.pl.trial(aside):
            t = last()
            self.pl.keep = not self.pl.soft_hits(self._number_box(t))
        if self.pl.of(t):
            return t
        beside = self._number_beside(lk, bodies, mine, pad, kw, nearest=False)
        if beside is None:   # (that placed nothing) the trial's place after all: put back, not placed again
            self.pl.back_to(aside[0])
        return t if beside is None else beside

    def _number_on_bar(self, lk, pts):
        """Link ``lk``'s circled number on its own bar, where no free place beside the bar reads as its own: the
        circle's centre on the bar's centre line at its middle (else farther along, :data:`ON_BAR`), the bar seen
        on both sides of it (at least :data:`ON_BAR_CLEAR` bar widths of it between the circle and each pin's
        ring), over no link or block drawn above the bar, on no line but the outlines of the bar and of the links
        beneath it (the bar and the circle hide them there), clear of every mark and label and off the point
        labels' places (:attr:`reserved`); at its size, else smaller where only that fits (:meth:`bar_room`). A
        circled number on its own bar reads as that bar's, as books draw it. None where the numbers are not
        circled, the bar is too short or no such place is free."""
        sizes = self.bar_room(lk)
        if not sizes:
            return None
        a, b = (np.asarray(p, float) for p in pts)
        length, z = float(np.hypot(*(b - a))), self.zorders.get(lk, 0.0)
        bodies = (*self.geoms.items(), *self.block_geom.items())
        above = [g for k, g in bodies if k != lk and self.zorders.get(k, 0.0) > z]
        hidden = {id(g) for k, lines in self.outlines.items() if k == lk or self.zorders.get(k, 9.0) < z
                  for g in lines}
        avoid = above + [g for g in self.pl.soft if id(g) not in hidden]
        for f, kw, end in sizes:   # (end: from a pin to the circle's centre)
            r = self.number_radius(lk, kw)
            centres = [c for x in ON_BAR for c in [a + (b - a) * x] if min(x, 1 - x) * length >= end
                       for ring in [Point(*c).buffer(r, quad_segs=8)]
                       if self.pl.free(ring) and self._unreserved(ring) and not any(g.intersects(ring) for g in avoid)]
            if centres and f == 1.0:
                t = self.pl.place_at(centres, literal(lk), gid=f"link-number-{lk}", pad=3.5, avoid=avoid,
                                     anchor=(a + b) / 2, **kw)
                if t is not None:
                    return t
            elif centres:   # set smaller: its box the circle (a margin of 3.5 points about its type reaches the pins)
                t = self.ax.text(*centres[0], literal(lk), ha="center", va="center", gid=f"link-number-{lk}", **kw)
                self.pl.add_box(t, Point(*centres[0]).buffer(r, quad_segs=8), anchor=(a + b) / 2)
                return t
        return None

    def _number_beside(self, lk, bodies, anchor, pad: float, kw, nearest: bool):
        """Link ``lk``'s number, with its circle on no line, at the free place nearest its body within
        :data:`NUMBER_BESIDE` of it (a grid of places :data:`BESIDE_STEP` apart, finer than the placer's rings,
        which miss a gap between lines) where it reads as its link's (:meth:`owned`; ``nearest=False``: merely
        beside it), off the point labels' places (:attr:`reserved`) and :data:`LABEL_ROOM` from every
        labelled point (the room its label takes, placed last): None where there is no such place."""
        own, pc = bodies[lk], self.pc
        probe = self.ax.text(0, 0, literal(lk), ha="center", va="center", **kw)
        r = self.number_radius(lk, kw) if "bbox" in kw else 0.5 * max(self.pl.text_size(probe, pad))
        probe.remove()
        x0, y0, x1, y1 = own.buffer(NUMBER_BESIDE * pc + r).bounds
        step, view = BESIDE_STEP * pc, view_box(self.ax)
        xs, ys = np.meshgrid(_grid_in(x0, x1, step, *view.bounds[::2], r), _grid_in(y0, y1, step, *view.bounds[1::2], r))
        cx, cy = xs.ravel(), ys.ravel()
        corners = np.column_stack([cx - r, cy - r, cx + r, cy + r])
        rings = shapely.box(*corners.T)
        ok = shapely.contains(view, rings) & (shapely.distance(rings, own) <= NUMBER_BESIDE * pc)
        taken = np.array(self.pl.boxes + self.pl.hard + self.pl.soft + self.reserved, dtype=object)
        if taken.size:
            ok[ok] = ~meets_any(taken, rings[ok])
        if self.opts.label_points is None or self.opts.label_points:   # the points' labels, placed last, go there
            xy = np.array([keys[0][1] for keys in _groups(self.sol).values()], float).reshape(-1, 2)
            ok[ok] = all_farther(shapely.points(xy), xy, rings[ok], corners[ok], LABEL_ROOM * pc)
        idx = np.flatnonzero(ok)
        if not len(idx):
            return None
        idx = idx[np.lexsort((np.hypot(cx[idx] - anchor[0], cy[idx] - anchor[1]),
                              np.round(shapely.distance(rings[idx], own) / (0.5 * step))))]
        test = self.owned(lk, bodies, anchor, nearest)
        for i in idx:
            if test(rings[i], leader=False):
                t = self.pl.place_at([(cx[i], cy[i])], literal(lk), gid=f"link-number-{lk}", pad=pad, soft=True,
                                     anchor=anchor, **kw)
                if t is not None:
                    return t
        return None

    def _first_number(self, lk, pts, g, anchor, prefer, n, pad: float, kw):
        """A link's number placed by the first rule (:meth:`_link_number` with no test), else near ``anchor``."""
        t = self._link_number(lk, pts, g, anchor, prefer, n if len(pts) >= 2 else None, pad, kw, None)
        if t is None:
            t = self.pl.place(anchor, literal(lk), prefer=prefer, gap=2.0, gid=f"link-number-{lk}", pad=pad, **kw)
        return t

    def beside_block(self, guide, body):
        """What a block's marks (its number, a slider driver's arrows) keep off of the ``body`` of the ``guide`` it
        lies in: the whole of a bar, only the slotted bar of a plate (beside the block, on the plate, they read as
        the block's: its slot runs there)."""
        return self.guide_bars[guide] if guide in self.filled and guide in self.guide_bars else body

    def owned(self, lk, bodies, anchor, nearest: bool = True):
        """The test a link number's box (data coordinates) passes where it reads as link ``lk``'s: within
        :data:`NUMBER_NEAR` of that link's body, nearer it (of ``bodies``) than any other's (unless ``nearest`` is
        False: only beside it, a place a number takes rather than one on a line), nothing of another link (nor hatched ground) between the two,
        nor across its leader from ``anchor`` where it stands far enough to have one (unless called with
        ``leader=False``: a number put beside its link, with none). A block lies in its guide: the guide is no other link here, but
        the number keeps off it (off its slotted bar, where the guide is a plate: on the plate beside the block it
        reads as the block's)."""
        own = bodies[lk]
        guides = {s.guide for s in self.m.sliders if s.block == lk}
        others = np.array([g for k, g in bodies.items() if k != lk and k not in guides], dtype=object)
        off = [self.beside_block(k, bodies[k]) for k in guides if k in bodies]
        a = Point(*anchor)

        def crossed(p, q) -> bool:
            if p.distance(q) < 1e-9 * self.pc:
                return False
            line = LineString([(p.x, p.y), (q.x, q.y)]).difference(own)
            return bool(shapely.intersects(others, line).any()) or any(g.intersects(line) for g in self.grounds)

        def test(b, leader: bool = True) -> bool:
            if any(g.intersects(b) for g in off):
                return False
            if not len(others):
                return True
            if b.distance(own) > NUMBER_NEAR * self.pc or \
                    nearest and float(shapely.distance(others, b).min()) <= b.distance(own):
                return False
            if crossed(*nearest_points(own, b)):
                return False
            return not leader or b.distance(a) < 8.0 * self.pp or not crossed(a, nearest_points(b, a)[0])
        return test

    def _covered(self, lk, p) -> bool:
        """Whether the point ``p`` of link ``lk`` lies under another link's body or block."""
        return any(g.intersects(Point(*p)) for k, g in (*self.geoms.items(), *self.block_geom.items()) if k != lk)

    def _off_lines(self, lk, kw, test):
        """``test`` (:meth:`owned`) and the box of the number's circle (drawn with ``kw``; its text's box, where it
        has none), about the centre of the box tested, on no line (the circle reaches past the box searched)."""
        r = self.number_radius(lk, kw) if "bbox" in kw else None

        def clear(b, leader: bool = True) -> bool:
            x, y = b.centroid.coords[0]
            ring = box(x - r, y - r, x + r, y + r) if r else b
            return test(b, leader) and not self.pl.soft_hits(ring) and self._unreserved(ring)
        return clear

    def _number_box(self, t):
        """A link number's box as drawn (data coordinates): its circle's, where it has one."""
        ring = t.get_bbox_patch()
        if ring is None:
            return self.pl.box_of(t, pad=0.0)
        t.update_bbox_position_size(self.pl.renderer)
        e = ring.get_window_extent(self.pl.renderer)
        (x0, y0), (x1, y1) = self.ax.transData.inverted().transform([[e.x0, e.y0], [e.x1, e.y1]])
        return box(min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))

    def _link_number(self, lk, pts, g, anchor, prefer, n, pad: float, kw, test, strict: bool = False):
        """Link ``lk``'s number placed where ``test`` passes (None: anywhere): a plate's inside it; a bar's beside
        its middle, clear of every line, else near it off every line, else (unless ``strict``: off the lines
        only) beside it clear of marks and labels; anything else near ``anchor`` off every line. None where no
        such place is."""
        gid = f"link-number-{lk}"
        if len(pts) >= 3:
            t = self._plate_number(lk, g, anchor, prefer, pad, kw, test, strict)
            if t is not None or test is None:
                return t
        if len(pts) == 2:
            a, b = pts
            probe = self.ax.text(*anchor, literal(lk), ha="center", va="center", **kw)
            w, h = self.pl.text_size(probe, pad)
            probe.remove()
            off = self.st.bar_width * self.pc / 2 + 2.0 * self.pp + 0.5 * (abs(n[0]) * w + abs(n[1]) * h)
            if np.hypot(*(b - a)) <= 2 * off:   # too short to be beside: near it
                return None if test is None else self._off_the_lines(anchor, literal(lk), prefer=prefer, gap=2.0,
                                                                        gid=gid, pad=pad, test=test, **kw)
            along = (0.5, 0.38, 0.62, 0.27, 0.73) + ((0.16, 0.84) if test is not None else ())
            spots = [a + (b - a) * f + side * n * off for f in along for side in (1, -1)]
            if test is not None:   # (farther along too: a bar that lies over another link in its middle)
                spots = [c for c in spots if test(box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2),
                                                  leader=False)]
            t = self.pl.place_at(spots, literal(lk), gid=gid, pad=pad, soft=True, anchor=anchor, **kw) if spots else None
            if t is None:   # nothing clear of every line beside it: near it off every line, if anywhere
                t = self._off_the_lines(anchor, literal(lk), prefer=prefer, gap=2.0, gid=gid, pad=pad, test=test, **kw)
            if t is None and spots and not strict:   # else clear of marks and labels beside it
                t = self.pl.place_at(spots, literal(lk), gid=gid, pad=pad, anchor=anchor, **kw)
            return t
        return self._off_the_lines(anchor, literal(lk), prefer=prefer, gap=2.0, gid=gid, pad=pad, test=test, **kw) \
            if test is not None else None

    def _plate_number(self, lk, g, anchor, prefer, pad: float, kw, test=None, strict: bool = False):
        """A plate's number inside it, at its centroid ``anchor``, if there is room there off every line (and
        ``test`` passes there); else near it off every line (where ``test`` passes); else (unless ``strict``) at
        the centroid all the same; None if the centroid has no room."""
        gid = f"link-number-{lk}"
        t = self.ax.text(*anchor, literal(lk), ha="center", va="center", gid=gid, **kw)
        b = self.pl.box_of(t, pad=pad)
        if not (g.contains(b) and self.pl.free(b) and (test is None or test(b))):
            t.remove()
            return None
        if self.pl.soft_hits(b):
            t.remove()
            near = self._off_the_lines(anchor, literal(lk), prefer=prefer, gap=2.0, gid=gid, pad=pad, test=test, **kw)
            if near is not None or strict:
                return near
            t = self.ax.text(*anchor, literal(lk), ha="center", va="center", gid=gid, **kw)
        self.pl.add_box(t, b, anchor=anchor)
        return t

    def _off_the_lines(self, anchor, text, test=None, **kw):
        """The text placed near ``anchor`` where it is free and on no line (a soft obstacle), and where ``test`` (of
        its box, data coordinates) passes if given; None if no such place is near."""
        kept = None
        with self.pl.trial():
            n = len(self.pl.overlapping)
            t = self.pl.place(anchor, text, accept=test, only=test is not None, **kw)
            self.pl.keep = len(self.pl.overlapping) == n and not self.pl.soft_hits(self.pl.box_of(t, pad=0.0)) and \
                (test is None or test(self.pl.of(t).box))
            kept = t if self.pl.keep else None
        return kept

    def driver(self, ground_dir, values: bool = True):
        """The driver's motion: omega (and alpha, when not zero) as curved arrows about its pivot in their
        senses, each with its value; a slider driver's speed and acceleration as straight arrows (``values``
        False: the arrows alone, not kept as the drawing's)."""
        m = self.m
        if m.driver.is_slider:
            self.slider_driver(values)
            return
        frame = m.frame.name
        pivot = next((pin.point for pin in m.pins if set(pin.links) == {m.driver.link, frame}), None)
        if pivot is None:
            return
        p = np.asarray(self.sol.position.get(pivot, self.sol.place(m.driver.link, pivot)), float)
        self.turning_driver(pivot, p, ground_dir, values)

    def slider_driver(self, values: bool = True):
        """A slider driver's speed beside its block as an arrow along its path in its sense, and its acceleration
        (when not zero) as a double-headed arrow in its sense next to it along the path, each with its value:
        beside the block on the side of the path away from its hatched guide, else farther along the path or
        on the other side, where that keeps an arrow in the panel and off the other links (:meth:`_slide_places`)."""
        sol, m, st, pc = self.sol, self.m, self.st, self.pc
        drv = m.driver
        s = next(s for s in m.sliders if s.point == drv.slider)
        path = _unit(float(sol.motion.sliders[m.sliders.index(s)]["direction"][0]))
        p = sol.place(s.block, s.point)
        n = _perp(path) * self.guide_side(s, p, _perp(path))
        speed_name, accel_name = (quantity_math(q, driver_index(m)) for q in "VA")   # V_A, or V_A₃/A₄ on a moving guide
        base = p + n * (st.block[1] * 0.5 + 0.35) * pc
        # the other side: beyond the guide's hatching, or its slotted bar
        other = p - n * (st.block[1] * 0.5 + (0.6 if m.link(s.guide).frame else 0.45)) * pc
        speed = self._slide_places(base, other, path, drv.speed, (0.0, 0.9, -0.9, 1.6, -1.6), s.block, [])[0]
        arrows = [(speed, "driver-arrow", "driver-label", speed_name, 1)]
        if drv.accel:   # next to the speed's, along the path on the side clear of the links
            ahead = [sum(1 for g in self.geoms.values() if g.intersects(LineString(
                [tuple(base + k * path * 0.9 * pc), tuple(base + k * path * 2.1 * pc)]))) for k in (1, -1)]
            k = 1.0 if ahead[0] <= ahead[1] else -1.0
            at = speed[2]
            steps = (at + 1.5 * k, at - 1.5 * k, at + 2.3 * k, at - 2.3 * k, at + 3.1 * k, at - 3.1 * k)
            kept = LineString([tuple(speed[0]), tuple(speed[1])]).buffer(1.0 * self.pp)
            if speed[3] is base:
                accel = self._slide_places(base, other, path, drv.accel, steps, s.block, [kept])[0]
            else:
                accel = self._slide_places(other, base, path, drv.accel, steps, s.block, [kept])[0]
            arrows.append((accel, "driver-accel-arrow", "driver-label-accel", accel_name, 2))
        spots = []
        for (a, b, _, side), gid, label_gid, symbol, power in arrows:
            value = drv.speed if power == 1 else drv.accel
            drawn = self.straight_arrow(a, b, gid, double=power == 2)
            if values:
                self.art.add("driver", *drawn)
            away = n if side is base else -n
            spots.append(((a, b), f"{symbol} = {number_math(abs(value), 4, 0.0)} {unit_label(m.units, power)}", label_gid, away))
        if not values:
            return
        for (a, b), text, label_gid, away in spots:   # the values once both arrows are drawn: clear of both
            t = self.value((a + b) / 2, text, prefer=math.degrees(math.atan2(away[1], away[0])),
                           fontsize=st.small_size * 1.15, arrow=LineString([tuple(a), tuple(b)]), zorder=7,
                           gid=label_gid)
            self.art.add("driver", t)

    def _slide_places(self, first, second, path, value, steps, block, kept) -> list:
        """The places (tail, tip, offset along the path in cm, side: ``first`` or ``second``) for a slider driver's
        straight arrow of ``value``'s sense, 1.2 cm long, centred ``steps`` cm along the ``path`` from the side
        points ``first`` (every step) then ``second``: best first, the first of them that stays in the panel,
        crosses the fewest other links and blocks (those pinned at the block's point aside: they run from it)
        and none of the ``kept`` (arrows already placed)."""
        pc = self.pc
        d = path * (1 if value >= 0 else -1)
        view = view_box(self.ax)
        at = set(self.m.carriers.get(self.m.driver.slider, ()))   # the links pinned at the block run from it
        guides = {s.guide for s in self.m.sliders if s.block == block}
        bodies = [self.beside_block(lk, g) if lk in guides else g
                  for lk, g in (*self.geoms.items(), *self.block_geom.items()) if lk not in at] + list(kept)
        places = []
        for side in (first, second):
            for along in steps:
                a = side + path * along * pc - d * 0.6 * pc
                places.append((a, a + d * 1.2 * pc, along, side))

        def cost(place):
            shape = LineString([tuple(place[0]), tuple(place[1])]).buffer(0.5 * self.st.head_length * self.pp)
            return (not view.contains(shape), sum(1 for g in bodies if g.intersects(shape)))
        return sorted(places, key=cost)

    def guide_side(self, s, p, n) -> float:
        """+1 or -1: the side of a slider's path (along ``n``) away from its hatched guide (towards its links)."""
        others = neighbours(self.sol, s.point, [lk for lk in self.m.carriers.get(s.point, ()) if lk not in
                                                 (s.block, s.guide)])
        side_v = sum((o - p) for o in others) if others else -n
        return 1.0 if np.dot(side_v, n) > 0 else -1.0

    def straight_arrow(self, a, b, gid, double=False) -> list:
        """An arrow a -> b (a second head behind the first when ``double``: an acceleration); its artists."""
        st = self.st
        sh, hd, poly = arrow(self.ax, a, b, lw=st.arrow_lw, head_length=st.head_length, colour=st.ink,
                             zorder=6, gid=gid)
        self.pl.add_obstacle(poly)
        self.pl.add_obstacle(LineString([tuple(a), tuple(b)]).buffer(1.0 * self.pp))
        out = [sh, hd]
        if double:
            u = (b - a) / float(np.hypot(*(b - a)))
            _, hd2, poly2 = arrow(self.ax, a, b - u * 0.8 * st.head_length * self.pp, lw=st.arrow_lw,
                                  head_length=st.head_length, colour=st.ink, zorder=6, gid=gid + "-second")
            self.pl.add_obstacle(poly2)
            out.append(hd2)
        return out

    def _driver_gaps(self, pivot, p, ground_dir) -> list:
        """(width, start) of the angular gaps (deg) about the pivot between the driver's links and its ground."""
        frame = self.m.frame.name
        dirs = [math.degrees(math.atan2(*(q - p)[::-1]))
                for q in neighbours(self.sol, pivot, self.pins_at[pivot] - {frame})]
        if pivot in ground_dir:   # the ground symbol takes a sector of its own
            dirs += [ground_dir[pivot] - 40.0, ground_dir[pivot], ground_dir[pivot] + 40.0]
        dirs = sorted(d % 360 for d in dirs) or [270.0]
        return [((dirs[(i + 1) % len(dirs)] - d) % 360 or 360, d) for i, d in enumerate(dirs)]

    def _free_runs(self, p, rad, ground) -> list:
        """(width, start) of the runs of directions (deg) about the pivot ``p`` where the circle of radius ``rad`` is
        in view, off the pivot's ground (``ground``: its direction, or None) and clear of every other link, block and
        label: where an arc reads as turning about this pivot alone (over the driver's own link, as books draw it)."""
        drv = self.m.driver.link
        bodies = [g for lk, g in (*self.geoms.items(), *self.block_geom.items()) if lk != drv] + list(self.pl.boxes)
        ang = np.arange(0.0, 360.0, ARC_STEP)
        t = np.radians(ang)
        pts = shapely.points(p[0] + rad * np.cos(t), p[1] + rad * np.sin(t))
        ok = shapely.contains(view_box(self.ax).buffer(-0.5 * self.st.head_length * self.pp), pts)
        if ground is not None:
            ok &= np.abs((ang - ground + 180.0) % 360.0 - 180.0) > 45.0
        if bodies:
            ok &= ~shapely.intersects(unary_union(bodies).buffer(0.5 * self.st.head_length * self.pp), pts)
        if ok.all() or not ok.any():
            return [(360.0, 0.0)] if ok.all() else []
        k = int(np.flatnonzero(~ok)[0])   # runs read round the circle from a blocked direction
        runs, n = [], 0
        for j in range(1, len(ang) + 1):
            if ok[(k + j) % len(ang)]:
                n += 1
                continue
            if n > 1:
                runs.append(((n - 1) * ARC_STEP, float(ang[(k + j - n) % len(ang)])))
            n = 0
        return runs

    def _run_plans(self, runs, rad) -> list:
        """Every (omega's place, alpha's place or None) in the free ``runs`` (:meth:`_free_runs`): omega's arc filling
        a run (up to 130 deg), alpha's another or beyond omega's; each arc at least :data:`RUN_SPAN` and long enough
        for its heads."""
        hl, pc = self.st.head_length * self.pp, self.pc

        def places(rs, r, most, length):
            out = []
            for w, start in sorted(rs, reverse=True):
                span = min(most, w)
                if span >= RUN_SPAN and math.radians(span) * r >= length * hl:
                    out.append(_ArcPlace(len(out), start + w / 2, span, r, (w, start)))
            return out
        plans = []
        for w in places(runs, rad, 130.0, 1.8):
            if not self.m.driver.alpha:
                plans.append((w, None))
                continue
            rest = places([g for g in runs if g != w.gap], rad, 130.0, 2.8)
            beyond = places([w.gap], rad + 0.45 * pc, 110.0, 2.8)
            plans += [(w, a) for a in rest + [b._replace(rank=len(rest)) for b in beyond]]
        return plans

    def _side_plans(self, runs, rad) -> list:
        """The (omega's place, alpha's place) side by side in one free run (:meth:`_free_runs`) at the same radius,
        :data:`SIDE_GAP` apart, either first, each at least :data:`RUN_SPAN` and long enough for its heads (the run
        shared in proportion to what each needs, alpha's two heads more than omega's one): with a
        plate beneath the crank (:attr:`beneath_cranks`), where every other layout's arcs cross a link
        (:meth:`_best_plan`'s ``fallback``: alpha's arc beyond omega's crossed the plate, whose notch about the
        pivot holds one radius of arcs, and the plate was refused for bars)."""
        hl, out = self.st.head_length * self.pp, []
        if not self.m.driver.alpha:
            return out
        need = [max(RUN_SPAN, math.degrees(k * hl / rad)) for k in (1.8, 2.8)]   # omega's, alpha's least spans
        for w, start in sorted(runs, reverse=True):
            room = w - SIDE_GAP
            if room < sum(need):
                continue
            spans = [min(110.0, room * q / sum(need)) for q in need]   # the room shared in proportion
            for a, b in ((0, 1), (1, 0)):   # omega's arc first round the run, then alpha's first
                first = start + spans[a] / 2
                places = {a: _ArcPlace(len(out), first, spans[a], rad, (w, start)),
                          b: _ArcPlace(len(out), start + w - spans[b] / 2, spans[b], rad, (w, start))}
                out.append((places[0], places[1]))
        return out

    def _arc_points(self, p, rad, mid, span, sense) -> np.ndarray:
        a0, a1 = mid - sense * span / 2, mid + sense * span / 2
        t = np.radians(np.linspace(a0, a1, 60))
        return np.c_[p[0] + rad * np.cos(t), p[1] + rad * np.sin(t)]

    @staticmethod
    def _arc_options(gaps, rad, least: float = 0.0) -> list:
        """The places for a driver's arc in the angular ``gaps`` (widest first; a gap under 50 deg only when it
        is the widest): (rank, mid direction, span, radius, gap), for gaps at least ``least`` deg wide."""
        out = []
        for rank, (gap, start) in enumerate(sorted(gaps, reverse=True)):
            if gap < 50.0 and rank > 0:
                break
            if gap >= least:
                out.append(_ArcPlace(len(out), start + gap / 2, min(130.0, 0.75 * gap), rad, (gap, start)))
        return out

    def _driver_plans(self, gaps, rad) -> list:
        """Every (omega's place, alpha's place or None) to choose from: omega's arc in a gap about the pivot;
        alpha's in another gap at least 50 deg wide, or beyond omega's arc in the same gap."""
        plans = []
        for w in self._arc_options(gaps, rad):
            if not self.m.driver.alpha:
                plans.append((w, None))
                continue
            rest = self._arc_options([g for g in gaps if g != w.gap], rad, least=50.0)
            beyond = _ArcPlace(len(rest), w.mid, min(110.0, 0.7 * w.gap[0]), rad + 0.45 * self.pc, w.gap)
            plans += [(w, a) for a in rest + [beyond]]
        return plans

    def _draw_driver(self, p, plan, texts, label_kw, values: bool = True) -> tuple[list, list]:
        """omega's arc (alpha's, double-headed) at the places of ``plan``, then (with ``values``) their values
        beside them: (the artists, the labels)."""
        drv = self.m.driver
        arts, labels = [], []
        for place, value, gid, label_gid, text in zip(plan, (drv.omega, drv.alpha), ("driver", "driver-alpha"),
                                                     ("driver-label", "driver-label-alpha"), texts):
            if place is not None:
                xy = self._arc_points(p, place.rad, place.mid, place.span, 1.0 if value >= 0 else -1.0)
                arts += self.curved_arrow(xy, gid, double=gid == "driver-alpha")
        for place, value, label_gid, text in zip(plan if values else (), (drv.omega, drv.alpha),
                                                 ("driver-label", "driver-label-alpha"), texts):
            if place is not None:
                arc = LineString(self._arc_points(p, place.rad, place.mid, place.span, 1.0 if value >= 0 else -1.0))
                labels.append(self.value(p + place.rad * _unit(place.mid), text, prefer=place.mid, gid=label_gid,
                                         arrow=arc, **label_kw))
        return arts, labels

    def value(self, at, text, *, fontsize: float, reserve: bool = True, arrow=None, **kw):
        """A driver's value beside its arrow (placed about ``at``, the middle of ``arrow``: its arc or shaft,
        shapely), off every line: first within :data:`VALUE_NEAR` of the arrow, at its size in one line, else in
        two (its name over its value: :func:`stacked`), else smaller (:data:`SMALLER`, never below the style's
        small size: a value is read from the back of the room), each with its leader off the point labels' places
        (``reserve``: not when placed again, once the point labels are drawn); only where none of these is free
        (a long leader reads worse than a value by its arrow), farther out with a leader in the same order of
        forms (off those places where any free place is), farther still, else at the small size where it covers
        least. Where every place off the lines lies
        beyond a line or outline from the arrow (a block amid a plate), its leader crosses up to
        :data:`CROSSING` of them to one off the point labels' places: a line across a leader reads, a line
        through a value does not."""
        def again():   # placed again, where a later label's leader crosses it (velpoly.render.kennedy)
            return self.value(at, text, fontsize=fontsize, reserve=False, arrow=arrow, **kw)
        floor = self.st.small_size / fontsize
        sizes = tuple(dict.fromkeys((1.0,) + tuple(max(f, floor) for f in SMALLER)))
        forms = [(s, f) for f in sizes for s in (text, stacked(text))]
        anchor, near = Point(*at) if arrow is None else arrow, VALUE_NEAR * self.pc

        def nearby(b) -> bool:   # (``only``: a place farther out, on no line, does not count here)
            return b.distance(anchor) <= near and (not reserve or self._unreserved(b, at))
        tries = [(s, f, False, 0, nearby, True) for s, f in forms]
        tries += [(s, f, reach, crossing, self._unreserved if reserve else None, bool(crossing))
                  for reach, crossing in ((False, 0), (True, 0), (True, CROSSING)) for s, f in forms]
        for s, f, reach, crossing, accept, only in tries:
            with self.pl.trial():
                n = len(self.pl.overlapping)
                t = self.pl.place(at, s, fontsize=fontsize * f, clear=True, reach=reach, again=again, accept=accept,
                                  crossing=crossing, only=only, **kw)
                self.pl.keep = len(self.pl.overlapping) == n and not self.pl.soft_hits(self.pl.box_of(t, pad=0.0))
            if self.pl.of(t) is not None:
                return self.off_ground(t)
        return self.off_ground(self.pl.place(at, text, fontsize=fontsize * sizes[-1], clear=True, again=again, **kw))

    def _unreserved(self, b, at=None) -> bool:
        """Whether the box ``b`` (data coordinates) keeps off the point labels' places (:attr:`reserved`: their
        boxes and leaders), and with ``at`` (its anchor) its leader too."""
        if at is not None and self.reserved:
            b = b.union(LineString([tuple(at), nearest_points(b, Point(*at))[0].coords[0]]))
        return not any(b.intersects(q) for q in self.reserved)

    def off_ground(self, t):
        """A driver's value that crowds hatched ground nudged straight away from it to :data:`GROUND_CLEAR`
        (its leader, if any, drawn again to the new box from the same start), where that box is in view, free,
        on no more lines than before and clear of all ground, and its leader crosses no other label or leader:
        nothing else moves (no other label is placed anew); else left where it is. Returns ``t``."""
        own = self.pl.of(t)
        if own is None or not self.grounds:
            return t
        b, clear = self.pl.box_of(t, pad=0.0), GROUND_CLEAR * self.pc
        near = min(self.grounds, key=b.distance)
        gap = b.distance(near)
        if gap >= clear:
            return t
        pb, pg = nearest_points(b, near)
        u = np.array([pb.x - pg.x, pb.y - pg.y])
        if float(np.hypot(*u)) < 1e-12 * self.pc:   # on the ground: away from its middle
            u = np.array(b.centroid.coords[0]) - np.array(near.centroid.coords[0])
        u = u / max(float(np.hypot(*u)), 1e-300) * (clear - gap + 0.02 * self.pc)
        nb, moved = translate(own.box, *u), translate(b, *u)
        others = [q.box for q in self.pl.labels if q is not own] + [g for g in self.pl.hard if g is not own.leader_geom]
        if (not view_box(self.ax).contains(nb) or any(g.intersects(nb) for g in others) or
                self.pl.soft_hits(nb) > self.pl.soft_hits(own.box) or
                any(moved.distance(g) < clear for g in self.grounds)):
            return t
        geom = None
        if own.leader is not None:
            start = np.column_stack(own.leader.get_data())[0]
            q = nearest_points(nb.exterior, Point(*own.anchor))[0]
            line = LineString([tuple(start), (q.x, q.y)])
            crossed = [p.box for p in self.pl.labels if p is not own] + \
                [p.leader_geom for p in self.pl.labels if p is not own and p.leader_geom is not None]
            if any(g.intersects(line) for g in crossed):
                return t
            own.leader.set_data([start[0], q.x], [start[1], q.y])
            geom = line.buffer(0.4 * self.pp)
        self.pl.move(t, u, nb, geom)
        return t

    def _plan_crossings(self, p, plan) -> tuple:
        """How many of a plan's arcs (with their heads) leave the view (an arc cut by the panel's edge runs into the
        caption above it), then how many other links, blocks and labels they cross."""
        drv = self.m.driver
        others = [g for lk, g in self.geoms.items() if lk != drv.link]
        others += [g for lk, g in self.block_geom.items() if lk != drv.link] + list(self.pl.boxes)
        view = view_box(self.ax)
        arcs = [LineString(self._arc_points(p, place.rad, place.mid, place.span, 1.0 if value >= 0 else -1.0))
                for place, value in zip(plan, (drv.omega, drv.alpha)) if place is not None]
        return (sum(1 for arc in arcs if not view.contains(arc.buffer(0.5 * self.st.head_length * self.pp))),
                sum(1 for arc in arcs for g in others if g.intersects(arc)))

    def _plan_score(self, p, k, plan, texts, label_kw) -> tuple:
        """How plan ``k``'s values read, lower is better (its arcs crossing nothing comes first:
        :meth:`_plan_crossings`): its values lie on no line (soft obstacle) and are placed, close to their arcs;
        then the wider gaps. Returns (the score, the plan as drawn to score it: its artists, its values and the
        trial's :class:`~velpoly.render.labels.Moment`, which :meth:`turning_driver` comes back to if it wins)."""
        aside = []
        with self.pl.trial(aside):
            self.pl.placed["driver-plan"] = ("plan", k)   # (as the plan chosen is drawn)
            n_bad = len(self.pl.overlapping)
            arts, labels = self._draw_driver(p, plan, texts, label_kw)
            boxes = [self.pl.box_of(t, pad=0.0) for t in labels]
            lost = len(self.pl.overlapping) - n_bad
            on_lines = sum(self.pl.soft_hits(b) for b in boxes)
            far = sum(round(float(b.distance(Point(*(p + place.rad * _unit(place.mid))))) / self.pp / 6.0)
                      for b, place in zip(boxes, [q for q in plan if q is not None]))
        return (lost, on_lines, far) + tuple(q.rank for q in plan if q is not None), (arts, labels, aside[0])

    def _best_plan(self, p, plans, family, texts, label_kw, fallback: int | None = None) -> tuple:
        """The index of the plan to draw, and that plan as drawn to score it (:meth:`_plan_score`): of those whose
        arcs cross fewest (:meth:`_plan_crossings`), the one whose values are all placed and on no line, in the first
        family (the widest gap's arc, then each radius's free runs: :data:`ARC_RADII`) that has one; then closest to
        their arcs, in the widest gaps. A later family is scored only where no earlier one has such a plan. The
        plans from index ``fallback`` on (:meth:`_side_plans`) count only where they cross fewer than every one before."""
        n = len(plans) if fallback is None else fallback
        crossings = [self._plan_crossings(p, plan) for plan in plans[:n]]
        least = min(crossings)
        if n < len(plans) and least != (0, 0):
            more = [self._plan_crossings(p, plan) for plan in plans[n:]]
            if min(more) < least:
                crossings, least = crossings + more, min(more)
        crossings += [(math.inf,)] * (len(plans) - len(crossings))   # (not counted: never the least)
        best = None
        for fam in sorted(set(family)):
            for i in range(len(plans)):
                if family[i] != fam or crossings[i] != least:
                    continue
                score, drawn = self._plan_score(p, i, plans[i], texts, label_kw)
                key = score[:2] + (fam,) + score[2:]
                if best is None or key < best[0]:
                    best = (key, i, drawn)
            if best is not None and best[0][:2] == (0, 0):
                break
        return best[1:]

    def curved_arrow(self, xy, gid, double=False) -> list:
        """An arrow along the points ``xy`` (its head at the last; a second head behind it when ``double``)."""
        from matplotlib.lines import Line2D
        st = self.st
        hl = st.head_length * self.pp
        d = np.hypot(*(xy - xy[-1]).T)
        # the shaft stops where the head begins (the second head's, when there are two)
        keep = d > hl * (1.75 if double else 0.9)
        ln = Line2D(xy[keep, 0], xy[keep, 1], lw=st.arrow_lw, color=st.ink, zorder=6, gid=gid + "-arc")
        self.ax.add_line(ln)
        self.pl.add_obstacle(LineString(xy).buffer(1.0 * self.pp))
        if not double:
            sh, hd, poly = arrow(self.ax, xy[keep][-1], xy[-1], lw=st.arrow_lw, head_length=st.head_length,
                                 colour=st.ink, zorder=6, gid=gid + "-arrow")
            self.pl.add_obstacle(poly)
            return [ln, sh, hd]
        j = int(np.flatnonzero(d > 0.85 * hl)[-1])
        return [ln] + [self._head(xy, i, gid + name) for i, name in ((j, "-second"), (len(xy) - 1, "-arrow"))]

    def _head(self, xy, i, gid):
        """A full arrowhead with its tip at xy[i], along the curve there."""
        st = self.st
        t = xy[i] - xy[i - 1]
        t = t / float(np.hypot(*t))
        sh, hd, poly = arrow(self.ax, xy[i] - t * 3 * st.head_length * self.pp, xy[i], lw=st.arrow_lw,
                             head_length=st.head_length, colour=st.ink, zorder=6, gid=gid)
        sh.remove()
        self.pl.add_obstacle(poly)
        return hd

    def turning_driver(self, pivot, p, ground_dir, values: bool = True):
        """omega's arc in a free gap about the pivot (the widest, unless another reads better), alpha's
        (double-headed) in another free gap or beyond omega's in the same, each in its sense, each labelled
        with its value beside it: of every such layout, the one whose arcs cross nothing (at the radius of
        :data:`ARC_RADII` that crosses least, the first of them where that is no worse) and whose values lie
        on no line, close to their arcs."""
        drv, st = self.m.driver, self.st
        lk = link_math(drv.link)   # velpoly.names: a word upright, as written
        texts = (rf"$\omega_{{{lk}}}$ = {number_math(abs(drv.omega), 4, 0.0)} rad/s {'ccw' if drv.omega >= 0 else 'cw'}",
                 rf"$\alpha_{{{lk}}}$ = {number_math(abs(drv.alpha), 4, 0.0)} rad/s² {'ccw' if drv.alpha > 0 else 'cw'}")
        label_kw = dict(fontsize=st.small_size * 1.15, zorder=7)
        gaps = self._driver_gaps(pivot, p, ground_dir)
        plans, family, side = self._driver_plans(gaps, ARC_RADIUS * self.pc), [], []
        family += [0] * len(plans)
        for i, r in enumerate(ARC_RADII, 1):
            runs = self._free_runs(p, r * self.pc, ground_dir.get(pivot))
            more = self._run_plans(runs, r * self.pc)
            plans += more
            family += [i] * len(more)
            side += [(i, q) for q in self._side_plans(runs, r * self.pc)] if self.beneath_cranks else []
        first_side = len(plans)   # (the side plans last, so that a plan's index is the same each time it is drawn)
        plans += [q for _, q in side]
        family += [fam for fam, _ in side]
        pin = self.pl.pins.get("driver-plan")   # a step frame: the finished construction's layout (scored here, with
        drawn = None                             # its values at their pins, another may win)
        if pin is not None and pin[0] == "plan" and pin[1] < len(plans):
            k = pin[1]
        elif self.plan is not None:
            k = self.plan
        else:
            k, drawn = self._best_plan(p, plans, family, texts, label_kw, first_side)
        self.plan = k
        if drawn is not None and values:   # the plan as it was drawn to score it: put back, not drawn again
            arts, labels, aside = drawn
            self.pl.back_to(aside)
        else:
            self.pl.placed["driver-plan"] = ("plan", k)
            arts, labels = self._draw_driver(p, plans[k], texts, label_kw, values)
        if values:
            self.art.add("driver", *arts, *labels)


def _roles(art) -> dict:
    """A copy of an :class:`~velpoly.render.canvas.Artists`' lists of artists by role, to restore it from."""
    return {role: list(v) for role, v in art.items()}


def _astray(numbers: dict) -> list:
    """The links whose numbers read as another link's, of :meth:`_Drawing.link_numbers`' answer."""
    return [lk for lk, (_, ok) in numbers.items() if not ok]


def _grid_in(a0: float, a1: float, step: float, v0: float, v1: float, r: float) -> np.ndarray:
    """``np.arange(a0, a1, step)``, the same numbers, but only those whose ring of half-width ``r`` may lie within
    the view ``v0 .. v1``: a body far larger than the view (a user's scale that draws the mechanism metres wide on
    paper) must not make a grid of millions of places, none of them in the view."""
    d = (a0 + step) - a0   # numpy's own increment: arange's i-th number is a0 + i * d
    n = max(int(math.ceil((a1 - a0) / step)), 0)
    i0 = min(max(int(math.floor((v0 + r - a0) / d)) - 1, 0), n) if math.isfinite((v0 + r - a0) / d) else 0
    i1 = min(max(int(math.ceil((v1 - r - a0) / d)) + 2, 0), n) if math.isfinite((v1 - r - a0) / d) else n
    return a0 + np.arange(i0, max(i0, i1)) * d


def draw_mechanism(sol, ax=None, *, style="textbook", options=None, scale: float | None = None) -> Artists:
    """Draw the displacement diagram of ``sol`` to scale; return its :class:`~velpoly.render.canvas.Artists`.

    Parameters
    ----------
    sol : Solution
        The solved instant; its positions are drawn (a re-assembled pose too).
    ax : matplotlib Axes, optional
        Drawn on pyplot's current axes if None. If the axes already has a
        velpoly view (another drawing set it), its scale is kept.
    style : {"textbook", "slides"} or Style
    options : DrawingOptions, optional
        The checked ``[drawing]`` table (read from the mechanism if None).
    scale : float, optional
        Length units per cm of paper; default ``[drawing] scale`` or a round
        scale that fits.

    Returns
    -------
    Artists
        Roles ``links``, ``ground``, ``guides``, ``sliders``, ``pins``,
        ``points``, ``labels``, ``link_numbers``, ``driver``, ``scale_bar``,
        ``equivalent`` (a sliding contact's dashed equivalent linkage);
        ``.labels`` maps each point key to its label, ``.bodies`` each moving
        link to its drawn body (shapely), ``.plates`` each link drawn as a plate to
        its polygon, ``.guide_bars`` each moving guide drawn in a plate to its slotted bar, ``.slot_cuts`` each
        moving link's slot
        (by index) to ``(link, centre line, cut)``, ``.exempt`` each ground hatch
        (a LineCollection) to the links it may touch.
    """
    ax = get_ax(ax)
    st = get_style(style)
    opts = options if options is not None else drawing_options(sol.mechanism)
    if view_scale(ax) is None:
        fit_view(ax, mechanism_bounds(sol), scale=scale if scale is not None else opts.scale, margin=0.1)
        ax.set_axis_off()
    if under_crank(sol, st.bar_width * per_cm(ax)):   # a plate beneath a crank, where its marks read so, else bars
        plated = _Drawing(sol, ax, st, opts, under_cranks=True)
        with placer(ax).trial() as pl:
            art = plated.draw()   # (no plate beneath a crank: drawn as it would be without)
            kept = pl.keep = not plated.beneath_cranks or plated.reads()
        if kept:
            return art
    return _Drawing(sol, ax, st, opts).draw()


def under_crank(sol, bar_width: float) -> bool:
    """Whether a moving link's plate (the hull of its joints) would cover a frame pivot of a link it does not carry,
    within a bar width: a slotted lever or an inverted slider-crank's guide about its crank, whose plate may lie
    beneath the crank (:meth:`_Drawing.reads`) or be drawn as bars (:meth:`_Drawing.cranks_over`)."""
    m = sol.mechanism
    for link in m.moving_links:
        own = joints(m, link.name)
        pts = [tuple(sol.place(m.carriers[p][0], p)) for p in own if m.carriers.get(p)]
        if len(own) < 3 or len(pts) < 3:
            continue
        hull = MultiPoint(pts).convex_hull.buffer(bar_width)
        foreign = foreign_bars(sol, link.name, on_body(m, link.name))
        if any(pivot and hull.contains(Point(*f)) for f, _, pivot in foreign):
            return True
    return False


def mark_auxiliary(sol, ax, polygon, *, style="textbook") -> Artists:
    """Mark on the space diagram the auxiliary points a polygon's construction uses.

    An auxiliary point that is not one of the mechanism's points (the point
    S of a link where the lines of two of its points' velocities meet) is
    drawn as a small ring at its position, labelled with its name (the
    image's label in capitals: s5 -> S5); one outside the view is an arrow
    at the border pointing to it, labelled with its position. Points that
    coincide with a mechanism point (a guide's point under a block) are
    already labelled.
    """
    st = get_style(style)
    art = Artists(ax)
    pl = placer(ax)
    pc = per_cm(ax)
    tol = 1e-9 * sol.mechanism.size
    existing = [np.asarray(p, float) for p in sol.position.values()]
    for key, aux in polygon.auxiliary.items():
        p = np.asarray(aux.position, float)
        if any(float(np.hypot(*(p - q))) <= tol for q in existing):
            continue
        name = upper_name(aux.label.rstrip("'")) if aux.label else key.split("@")[0]
        view = view_box(ax)
        if not view.contains(Point(*p)):
            x0, y0, x1, y1 = mechanism_bounds(sol)
            c = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
            d = (p - c) / max(float(np.hypot(*(p - c))), 1e-300)
            tip = border_point(view, c, d, 0.3 * pc)
            sh, hd, poly = arrow(ax, tip - d * 1.0 * pc, tip, lw=st.arrow_lw, head_length=st.head_length,
                                 colour=st.ink, zorder=6, gid=f"auxiliary-{key}")
            pl.add_obstacle(poly)
            art.add("auxiliary", sh, hd)
            where = f" ({p[0]:.4g}, {p[1]:.4g})".replace("-", "−")
            t = pl.place(tip - d * 1.0 * pc, tex(name) + where, prefer=math.degrees(
                math.atan2(-d[1], -d[0])), fontsize=st.font_size * 0.9, fontstyle="italic", zorder=7,
                gid=f"label-point-{key}")
            art.add("labels", t)
            art.labels[key] = t
            continue
        ring = Point(*p).buffer(0.07 * pc, quad_segs=8)
        patch = shape_patch(ring, facecolor=st.paper, edgecolor=st.ink, lw=st.thin_lw * 1.5, zorder=5,
                            gid=f"auxiliary-{key}")
        add_patch(ax, patch)
        pl.add_obstacle(ring)
        t = pl.place(p, tex(name), fontsize=st.font_size, fontstyle="italic", zorder=7, gid=f"label-point-{key}")
        art.add("auxiliary", patch)
        art.add("labels", t)
        art.labels[key] = t
        existing.append(p)
    return art
