"""Labels that never overlap: placement with shapely, in data coordinates.

A :class:`LabelPlacer` belongs to one axes (:func:`placer`). Drawings
register what labels must not cover (arrowheads, pins, pivots: *hard*
obstacles) and what they should rather not cover (links, lines: *soft*).
:meth:`LabelPlacer.place` measures the text with the figure's renderer,
converts its box into data coordinates, and tries candidate positions around
the anchor, ring after ring, in a fixed order of directions (the preferred
one first): the first box that stays in view, meets no placed label and no
hard obstacle, and crosses the fewest soft ones, wins. Far from its anchor, a
label gets a thin leader line. Nothing is random: the same drawing gives
the same placement.
"""
from __future__ import annotations

import math

import numpy as np
import shapely
from shapely import affinity
from shapely.geometry import LineString, box

from .canvas import per_point, renderer_of, view_box

__all__ = ["LabelPlacer", "placer", "segment", "half_extent"]

# ring radii, in points of gap between the anchor and the box
RINGS = (2.5, 5.0, 9.0, 14.0, 21.0, 30.0, 42.0, 58.0)
FAR_RINGS = (9.0, 21.0, 42.0, 80.0, 105.0)   # finer directions, only when nothing above is free


class LabelPlacer:
    """Place texts on an axes so that no two boxes intersect (see the module's docstring)."""

    def __init__(self, ax):
        self.ax = ax
        self.renderer = renderer_of(ax.figure)
        self.hard: list = []
        self.soft: list = []
        self.boxes: list = []      # shapely polygons of placed labels
        self.texts: list = []      # their Text artists, same order
        # where each label (by gid) went, and where it must go: the frames of a step sequence put every
        # label, scale bar and legend where the finished construction has it, so that nothing jumps
        self.placed: dict = {}
        self.pins: dict = {}
        self.leaders: list = []    # leader lines drawn (also hard obstacles)

    # -- obstacles ---------------------------------------------------------------------
    def add_obstacle(self, geom, hard: bool = True) -> None:
        """Register a shapely geometry (data coordinates) labels must avoid (hard) or should (soft)."""
        if geom is None or geom.is_empty:
            return
        (self.hard if hard else self.soft).append(geom)

    def add_box(self, text) -> None:
        """Register an already drawn Text as a placed label (its box)."""
        self.boxes.append(self.box_of(text))
        self.texts.append(text)

    # -- measuring ---------------------------------------------------------------------
    def box_of(self, text, pad: float = 1.0):
        """The Text's box in data coordinates, grown by ``pad`` points (a rotated text: its outline)."""
        bb = text.get_window_extent(self.renderer)
        inv = self.ax.transData.inverted()
        (x0, y0), (x1, y1) = inv.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
        p = pad * per_point(self.ax)
        return box(min(x0, x1) - p, min(y0, y1) - p, max(x0, x1) + p, max(y0, y1) + p)

    def text_size(self, text, pad: float = 1.0) -> tuple[float, float]:
        rot = text.get_rotation()
        text.set_rotation(0)
        b = self.box_of(text, pad)
        text.set_rotation(rot)
        x0, y0, x1, y1 = b.bounds
        return x1 - x0, y1 - y0

    def free(self, geom, soft: bool = False) -> bool:
        """Whether ``geom`` meets no placed label and no hard (or, with ``soft``, any) obstacle."""
        others = self.boxes + self.hard + (self.soft if soft else [])
        if not others:
            return True
        return not bool(np.any(shapely.intersects(np.array(others, dtype=object), geom)))

    def soft_hits(self, geom) -> int:
        if not self.soft:
            return 0
        return int(np.count_nonzero(shapely.intersects(np.array(self.soft, dtype=object), geom)))

    # -- placing -----------------------------------------------------------------------
    def place(self, anchor, s: str, *, prefer: float | None = None, gap: float = 2.5, leader: bool = True,
              gid: str | None = None, obstacle: bool = True, pad: float = 1.0, within: float | None = None,
              **text_kw):
        """Draw text ``s`` near ``anchor`` where it overlaps nothing; return the Text.

        ``prefer``: the preferred direction from the anchor (degrees), e.g.
        away from the link; the other directions follow alternately on either
        side of it. ``gap``: the smallest distance from the anchor (points);
        ``pad``: the margin kept around the text (points; more for a boxed text).
        A label that can find no free place in view is put at the candidate
        crossing the fewest obstacles (and the placement reports it through
        :attr:`overlapping`). ``within``: only directions within so many degrees
        of ``prefer`` (a label that must sit on one side of its anchor); if none
        of them is free, every direction.
        """
        ax = self.ax
        anchor = np.asarray(anchor, float)
        t = ax.text(anchor[0], anchor[1], s, ha="center", va="center", **text_kw)
        if gid:
            t.set_gid(gid)
        w, h = self.text_size(t, pad)
        pp = per_point(ax)
        view = view_box(ax)
        best = None
        pin = self.pins.get(gid) if gid else None
        if pin is not None and pin[0] == "place":
            c = np.asarray(pin[1], float)
            b = box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
            if view.contains(b) and self.free(b):
                best = (0, c, b, pin[2])
        rings = () if best is not None else (gap,) + tuple(r for r in RINGS if r > gap)
        # when nothing is free within the rings (a crowd of labels and their leaders): farther out, in
        # finer steps of direction, before giving up
        rings = rings + tuple((r, True) for r in FAR_RINGS) if rings else rings
        for ring_i, ring in enumerate(rings):
            far = isinstance(ring, tuple)
            if far:
                if best is not None:
                    break
                ring = ring[0]
            for ang in _directions(prefer, 24 if far else 16 if ring_i >= 2 else 8):
                if within is not None and abs((ang - (prefer or 45.0) + 180.0) % 360.0 - 180.0) > within + 1e-9:
                    continue
                u = np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
                # put the box's near side at distance ring from the anchor along u
                reach = ring * pp + half_extent(w, h, u)
                c = anchor + u * reach
                b = box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
                if not view.contains(b) or not self.free(b):
                    continue
                if leader and ring >= 9.0 and self.boxes and bool(np.any(shapely.intersects(
                        np.array(self.boxes, dtype=object), LineString([tuple(anchor), tuple(_toward(b, anchor))])))):
                    continue   # its leader would cross another label
                hits = self.soft_hits(b)
                if best is None or hits < best[0]:
                    best = (hits, c, b, ring)
                if hits == 0:
                    break
            if best is not None and best[0] == 0:
                break
        if best is None and within is not None:   # nothing free on that side: any side
            t.remove()
            return self.place(anchor, s, prefer=prefer, gap=gap, leader=leader, gid=gid, obstacle=obstacle, pad=pad,
                              **text_kw)
        if best is None:
            # nothing free: the place clear of every label (and of their leaders) covering the fewest
            # arrowheads and pins, then lines
            hard = np.array(self.hard, dtype=object)
            boxes = np.array(self.boxes + self.leaders, dtype=object)   # what its box must keep off
            labels_ = np.array(self.boxes, dtype=object)               # what its leader must not cross
            for ring in (gap,) + tuple(r for r in RINGS if r > gap) + FAR_RINGS[3:] + (135.0,):
                for ang in _directions(prefer, 16):
                    u = np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
                    c = anchor + u * (ring * pp + half_extent(w, h, u))
                    b = box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
                    if not view.contains(b) or (len(boxes) and bool(np.any(shapely.intersects(boxes, b)))):
                        continue
                    crossed = int(np.count_nonzero(shapely.intersects(
                        labels_, LineString([tuple(anchor), tuple(_toward(b, anchor))])))) \
                        if leader and ring >= 9.0 and len(labels_) else 0
                    score = (crossed, int(np.count_nonzero(shapely.intersects(hard, b))) if len(hard) else 0,
                             self.soft_hits(b))
                    if best is None or score < best[0]:
                        best = (score, c, b, ring)
            if best is not None:
                self.overlapping.append(t)
        if best is None:  # nothing clear of the labels in view: fall back to the first ring's preferred spot
            u = np.array([math.cos(math.radians(prefer or 45.0)), math.sin(math.radians(prefer or 45.0))])
            c = anchor + u * (gap * pp + half_extent(w, h, u))
            b = box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
            best = (math.inf, c, b, gap)
            self.overlapping.append(t)
        _, c, b, ring = best
        t.set_position((float(c[0]), float(c[1])))
        if gid:
            self.placed[gid] = ("place", (float(c[0]), float(c[1])), ring)
        if leader and ring >= 9.0:
            from matplotlib.lines import Line2D
            edge = _toward(b, anchor)
            start = anchor + (edge - anchor) * (1.5 * pp / max(np.hypot(*(edge - anchor)), 1e-300))
            ln = Line2D([start[0], edge[0]], [start[1], edge[1]], lw=0.4, color=t.get_color(),
                        zorder=t.get_zorder())
            ax.add_line(ln)
            t._velpoly_leader = ln
            if obstacle:   # later labels keep off it
                self.leaders.append(LineString([tuple(start), tuple(edge)]).buffer(0.4 * pp))
                self.hard.append(self.leaders[-1])
        if obstacle:
            self.boxes.append(b)
            self.texts.append(t)
        return t

    def place_at(self, centres, s: str, *, gid: str | None = None, pad: float = 1.0, avoid=(), soft: bool = False,
                 **text_kw):
        """Draw ``s`` centred on the first of ``centres`` where it is free; None if none is.

        For a mark that belongs *on* something (a number on a chord). ``avoid``:
        further geometries (data coordinates) the box must not meet, for this
        text only (the other chords, for a chord's number); ``soft``: the box must
        meet no soft obstacle either.
        """
        ax = self.ax
        c0 = np.asarray(centres[0], float)
        t = ax.text(c0[0], c0[1], s, ha="center", va="center", **text_kw)
        if gid:
            t.set_gid(gid)
        w, h = self.text_size(t, pad)
        view = view_box(ax)
        pin = self.pins.get(gid) if gid else None
        if pin is not None and pin[0] == "at":
            centres = [pin[1]] + list(centres)
        for c in centres:
            c = np.asarray(c, float)
            b = box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2)
            if view.contains(b) and self.free(b, soft=soft) and not any(g.intersects(b) for g in avoid):
                t.set_position((float(c[0]), float(c[1])))
                if gid:
                    self.placed[gid] = ("at", (float(c[0]), float(c[1])))
                self.boxes.append(b)
                self.texts.append(t)
                return t
        t.remove()
        return None

    def place_along(self, p0, p1, s: str, *, offset: float = 1.5, gid: str | None = None, pad: float = 1.0,
                    **text_kw):
        """Write ``s`` along the segment p0-p1 (rotated to it), where it is free; None if nowhere.

        Tried at fractions of the segment from its far end inwards, on either side. ``pad``: the
        margin (points) kept between the text's ends and other labels or arrowheads, so that the
        words do not run on into a label ("... the path of B on 1 O_v").
        """
        ax = self.ax
        p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
        d = p1 - p0
        length = float(np.hypot(*d))
        if length == 0:
            return None
        u = d / length
        ang = math.degrees(math.atan2(u[1], u[0]))
        if ang > 90:
            ang -= 180
        elif ang <= -90:
            ang += 180
        t = ax.text(p0[0], p0[1], s, ha="center", va="center", rotation=ang, rotation_mode="anchor", **text_kw)
        if gid:
            t.set_gid(gid)
        w, h = self.text_size(t)
        if w > 0.92 * length:
            t.remove()
            return None
        pp = per_point(ax)
        grow = max(pad - 1.0, 0.0) * pp
        n = np.array([-u[1], u[0]])
        view = view_box(ax)
        pin = self.pins.get(gid) if gid else None
        tries = [(f, side) for f in (0.78, 0.62, 0.46, 0.3, 0.7, 0.54, 0.38, 0.22) for side in (1, -1)]
        if pin is not None and pin[0] == "along":
            tries.insert(0, pin[1])
        for frac, side in tries:
            c = p0 + u * (frac * length) + n * side * (offset * pp + h / 2)
            b = affinity.rotate(box(c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2), ang,
                                origin=(c[0], c[1]))
            # its ends kept ``pad`` from labels and arrowheads (the words must not run on into a label)
            big = affinity.rotate(box(c[0] - w / 2 - grow, c[1] - h / 2, c[0] + w / 2 + grow, c[1] + h / 2), ang,
                                  origin=(c[0], c[1]))
            if view.contains(b) and self.free(b, soft=True) and (grow == 0 or self.free(big)):
                t.set_position((float(c[0]), float(c[1])))
                if gid:
                    self.placed[gid] = ("along", (frac, side))
                self.boxes.append(b)
                self.texts.append(t)
                return t
        t.remove()
        return None

    @property
    def overlapping(self) -> list:
        if not hasattr(self, "_overlapping"):
            self._overlapping = []
        return self._overlapping


def _directions(prefer: float | None, k: int) -> list[float]:
    base = 45.0 if prefer is None else float(prefer)
    step = 360.0 / k
    out = [base]
    for i in range(1, k // 2 + 1):
        out.append(base + i * step)
        if i < k // 2:
            out.append(base - i * step)
    return out


def half_extent(w: float, h: float, u) -> float:
    """Distance from a w x h box's centre to its edge along unit u."""
    ux, uy = abs(u[0]), abs(u[1])
    cands = []
    if ux > 1e-12:
        cands.append((w / 2) / ux)
    if uy > 1e-12:
        cands.append((h / 2) / uy)
    return min(cands)


def _toward(b, p):
    """The point of box b's outline nearest to p."""
    from shapely.geometry import Point
    from shapely.ops import nearest_points
    q = nearest_points(b.exterior, Point(p))[0]
    return np.array([q.x, q.y])


def placer(ax) -> LabelPlacer:
    """The axes' :class:`LabelPlacer` (created on first use), shared by every drawing on it."""
    p = getattr(ax, "_velpoly_placer", None)
    if p is None:
        p = LabelPlacer(ax)
        ax._velpoly_placer = p
    return p


def segment(p0, p1) -> LineString:
    """A shapely segment (for soft obstacles)."""
    return LineString([tuple(map(float, p0)), tuple(map(float, p1))])
