"""The enlarged detail of a crushed polygon: a long vector sets the scale, the rest is a cluster.

When one image is far longer than the rest (a slotted lever's crank, a wheel's far point), the
polygon's scale is set by it and the other images crowd about the origin, unreadable. As books do,
the polygon panel then shows the crowd again, enlarged, at a round scale of its own: a framed
detail captioned "detail, 1 cm = X", in a free part of the panel, with a thin box marking the
region on the polygon and a leader joining the box to the detail. The detail is the same drawing
(link images, construction lines, vectors, the origin, the labels of the images in the region),
its data coordinates still velocities (accelerations), at the larger scale; the images in the
marked region are labelled in the detail only, every label inside the frame (``EDGE_PT`` clear of its
rule) and off the lines where it finds room (``polygon._PolygonDrawing._off_lines``), the origin's with
room of its own about the crowd (:func:`_pads`).

The rule (:func:`crowd`), on paper at the panel's scale: join two of the polygon's points (the
origin, the images, the auxiliary points' images) closer than ``JOIN_CM``; the origin's group is
the crowd (or closer than a sixth of the polygon's larger side, if that is more). A detail is drawn when the crowd holds at least ``MIN_POINTS`` distinct points (the
origin and three images), its box's larger side is at most ``MAX_CM``, and the whole polygon's box
is at least ``RATIO`` times larger. Its scale is the finest round scale, at least ``MIN_ZOOM`` times
finer than the panel's, at which the region fits a free place of the panel.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
import shapely.affinity
from shapely.geometry import Polygon, box
from shapely.ops import nearest_points

from .canvas import Artists, fit_view, nice_scale, per_cm, per_point, view_box, view_scale
from .labels import placer
from .scalebar import scale_text

__all__ = ["Crowd", "Detail", "crowd", "draw_detail", "JOIN_CM", "JOIN_PART", "MIN_POINTS", "MAX_CM", "RATIO", "MIN_ZOOM",
           "MOST_STEPS", "make_room"]

JOIN_CM = 1.3      # two points closer than this on paper belong to one group,
JOIN_PART = 6.0    # or than this part of the polygon's larger side
MIN_POINTS = 4     # the origin and three images at least
MAX_CM = 3.0       # the crowd's box at most this large on paper
RATIO = 3.0        # the polygon at least this many times larger than the crowd
MIN_ZOOM = 2.0     # the detail at least twice the panel's scale
PAD_CM = 0.45      # room about the region in the detail, for the labels
MARK_CM = 0.15     # the region's mark about the crowd's box, on the polygon
MOST_STEPS = 4     # the panel's scale at most so many round steps coarser, to make room for the detail
EDGE_PT = 2.0      # the detail's labels at least this far inside its frame (points)
ORIGIN_LINES = 1.5 # room for the origin's label beside the crowd, in the detail: lines of type (see _pads)


@dataclass(frozen=True)
class Crowd:
    """The origin's group of a crushed polygon: its keys (images and auxiliary points, at the origin
    too), its box in data units, and the rule's numbers on paper (cm)."""

    keys: tuple
    bounds: tuple          # (x0, y0, x1, y1), data units
    points: int            # distinct points, the origin counted
    size_cm: float         # the box's larger side
    polygon_cm: float      # the polygon's box's larger side


def _all_points(polygon) -> dict:
    pts = {k: np.asarray(v, float) for k, v in polygon.images.items()}
    for a, aux in (getattr(polygon, "auxiliary", None) or {}).items():
        pts[a] = np.asarray(aux.image, float)
    return pts


def crowd(polygon, unit_per_cm: float, tol: float | None = None) -> Crowd | None:
    """The crowd of ``polygon`` drawn at ``unit_per_cm`` if the rule (module docstring) calls for a
    detail, else None. The whole polygon counts (a step frame has the finished polygon's detail)."""
    pts = _all_points(polygon)
    if not pts:
        return None
    size = max(float(np.hypot(*p)) for p in pts.values()) or 1.0
    tol = 1e-9 * size if tol is None else tol
    distinct = [np.zeros(2)]
    for p in pts.values():
        if all(float(np.hypot(*(p - q))) > tol for q in distinct):
            distinct.append(p)
    xy = np.array(distinct)
    p_cm = float((xy.max(axis=0) - xy.min(axis=0)).max()) / unit_per_cm
    join = max(JOIN_CM, p_cm / JOIN_PART) * unit_per_cm
    group, todo = {0}, [0]
    while todo:
        i = todo.pop()
        near = np.flatnonzero(np.hypot(*(xy - xy[i]).T) < join)
        for j in near:
            if int(j) not in group:
                group.add(int(j))
                todo.append(int(j))
    g = xy[sorted(group)]
    lo, hi = g.min(axis=0), g.max(axis=0)
    g_cm = float((hi - lo).max()) / unit_per_cm
    if len(g) < MIN_POINTS or g_cm > MAX_CM or p_cm < RATIO * g_cm:
        return None
    keys = tuple(k for k, p in pts.items() if np.any(np.hypot(*(g - p).T) <= tol))
    return Crowd(keys, (*map(float, lo), *map(float, hi)), len(g), g_cm, p_cm)


@dataclass
class Detail:
    """A drawn detail: the crowd, its scale (units per cm), the inset axes, the region marked on the
    polygon (``region``, data units of the panel), the inset's box in the panel (``frame``), the panel's
    part outside the region (``outside``: the panel labels the images there), the caption, the inset's
    Artists (``art``: images, construction, shafts, arrows, origin, labels; ``.arrows``) and the marks
    drawn on the panel (the region's box, the leader, the frame)."""

    crowd: Crowd
    scale: float
    ax: object
    region: object
    frame: object
    outside: object
    caption: object
    art: Artists
    marks: list
    hits: int = 0          # what its frame meets of the panel (0: a free place)


def _inset_size(bounds, s: float, pads, cap: float, min_w: float = 0.0) -> tuple[float, float]:
    """The inset's width (at least ``min_w``) and height in cm of paper showing ``bounds`` at the scale ``s``, with
    ``pads`` (left, bottom, right, top; cm) of room about them."""
    x0, y0, x1, y1 = bounds
    pl, pb, pr, pt = pads
    return max((x1 - x0) / s + pl + pr, min_w), (y1 - y0) / s + pb + pt + cap


def _pads(c: Crowd, st) -> tuple:
    """The room (cm) about the region in the detail, left, bottom, right and top: ``PAD_CM`` for the images'
    labels, and ``ORIGIN_LINES`` lines of type more on a side the origin lies at (within a quarter of the
    crowd's box from it): the origin's label lists every point at rest and needs the room its vectors leave
    it (they all leave it on the crowd's side)."""
    x0, y0, x1, y1 = c.bounds
    more = ORIGIN_LINES * st.font_size / 72 * 2.54
    w, h = max(x1 - x0, 1e-300), max(y1 - y0, 1e-300)
    return (PAD_CM + (more if -x0 <= w / 4 else 0.0), PAD_CM + (more if -y0 <= h / 4 else 0.0),
            PAD_CM + (more if x1 <= w / 4 else 0.0), PAD_CM + (more if y1 <= h / 4 else 0.0))


def round_below(x: float) -> float:
    """The largest round scale (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^k) that is <= x."""
    s = nice_scale(x)
    while s > x * (1 + 1e-12):
        s = nice_scale(s / 1.6)
        while nice_scale(s * 1.0001) <= x * (1 + 1e-12):
            s = nice_scale(s * 1.0001)
    return s


def _scales(bounds, main: float, room: tuple[float, float], pads, cap: float) -> list[float]:
    """The detail's candidate scales, finest first: the round scales at least MIN_ZOOM times finer than the
    panel's ``main``, from the finest whose inset fits in ``room`` (cm); at least the coarsest of them."""
    x0, y0, x1, y1 = bounds
    pl, pb, pr, pt = pads
    need = max((x1 - x0) / max(room[0] - pl - pr, 1e-9), (y1 - y0) / max(room[1] - pb - pt - cap, 1e-9), 1e-300)
    top = round_below(main / MIN_ZOOM)
    out, s = [], nice_scale(need)
    while s <= top * (1 + 1e-12):
        out.append(s)
        s = nice_scale(s * 1.0001)
    return out or [top]


def _caption_cm(st) -> float:
    return 1.5 * st.small_size / 72 * 2.54


def _shifts(d, pc) -> list:
    """Moves (dx, dy) of the panel's view that keep the polygon in it, the present view first: the polygon
    against a side or a corner of the panel leaves the room on the other side in one piece. None in a step
    frame or a view the caller set to a scale of its own (the finished construction's view stays)."""
    if d.pl.pins.get("_scale") is not None:
        return [(0.0, 0.0)]
    vx0, vy0, vx1, vy1 = view_box(d.ax).bounds
    px0, py0, px1, py1 = d.bounds()
    gap = 0.4 * pc
    xs = (0.0, min(0.0, px1 + gap - vx1), max(0.0, px0 - gap - vx0))
    ys = (0.0, min(0.0, py1 + gap - vy1), max(0.0, py0 - gap - vy0))
    out = []
    for dx in xs:
        for dy in ys:
            if (dx, dy) not in out:
                out.append((dx, dy))
    return out


def _find(d, region, min_w: float, options):
    """(hits, scale, frame box in panel data units, view shift, pads): the detail's place (:func:`_find_at`) with
    the first of the ``options`` of room about the region (:func:`_pads`: with the origin's label's room, then
    without) that finds a free one; else the one meeting the fewest marks, lines and images (the first among
    equals). A panel with no free place for the larger inset keeps its scale and the detail its scale rather
    than drawing the polygon smaller for the origin's label (Example 3.4's velocity polygon, textbook)."""
    best = None
    for pads in dict.fromkeys(options):
        got = _find_at(d, region, min_w, pads) + (pads,)
        if got[0] == 0:
            return got
        if best is None or got[0] < best[0]:
            best = got
    return best


def _find_at(d, region, min_w: float, pads):
    """(hits, scale, frame box in panel data units, view shift): the finest candidate scale whose inset, with
    ``pads`` of room about the region, finds a place free of every mark, line and link image of the panel and
    away from the region (hits 0), in the present view or one moved with the polygon against a side; else the
    place meeting the fewest marks, then lines and images."""
    pl, pc = d.pl, d.pc
    view = view_box(d.ax)
    wcm, hcm = (view.bounds[2] - view.bounds[0]) / pc, (view.bounds[3] - view.bounds[1]) / pc
    cap = _caption_cm(d.st)
    marks = d.hit_counter(pl)
    # and the link images (not obstacles of the labels, which may sit on them)
    images = np.array([Polygon(p.get_xy()) for p in d.art.get("images", [])], dtype=object)
    keep_off = region.buffer(0.3 * pc)

    def hits_of(b):
        return marks(b) + (int(np.count_nonzero(shapely.intersects(images, b))) if len(images) else 0)
    best = None
    scales = _scales(region.bounds, pc, (0.7 * wcm, 0.6 * hcm), pads, cap)
    for s in scales:
        w, h = (v * pc for v in _inset_size(region.bounds, s, pads, cap, min_w))
        for dx, dy in _shifts(d, pc):
            moved = shapely.affinity.translate(view, dx, dy)
            named, grid = d.spots(moved.bounds, w, h, 0.1 * pc)
            for lx, ly in named + grid:
                b = box(lx, ly, lx + w, ly + h)
                if not moved.contains(b):
                    continue
                score = hits_of(b) + (1000 if b.intersects(keep_off) else 0)
                if score == 0:
                    return 0, s, b, (dx, dy)
                if best is None or score < best[0]:
                    best = (score, s, b, (dx, dy))
    if best is None:   # an inset larger than the panel: the coarsest, at the upper right
        w, h = (v * pc for v in _inset_size(region.bounds, scales[-1], pads, cap, min_w))
        vx0, vy0, vx1, vy1 = view.bounds
        b = box(vx1 - w, vy1 - h, vx1, vy1)
        return 10000 + hits_of(b), scales[-1], b, (0.0, 0.0)
    return best


def _place(d, region, min_w: float, options):
    """(hits, scale, frame box in panel data units, view shift, pads) of the detail (:func:`_find`; a step frame:
    where, and with the room, the finished construction has it)."""
    pin = d.pl.pins.get("detail")
    if pin is not None:      # a step frame: where the finished construction has it
        return 0, pin[2], box(*pin[1]), (0.0, 0.0), pin[4]
    return _find(d, region, min_w, options)


def _region(c: Crowd, pc: float):
    """The region marked on the polygon: the crowd's box, ``MARK_CM`` of paper about it."""
    x0, y0, x1, y1 = c.bounds
    m = MARK_CM * pc
    return box(x0 - m, y0 - m, x1 + m, y1 + m)


def _caption_width(d) -> float:
    """The width (cm) the detail's caption needs at its longest scale: the inset at least as wide."""
    units = d.m.units if d.m is not None else ""
    probe = d.ax.text(0, 0, "detail, " + scale_text(1.0, units, 1 if d.velocity else 2) + "0000",
                      fontsize=d.st.small_size, style="italic")
    bb = probe.get_window_extent(d.pl.renderer)
    probe.remove()
    return bb.width / d.ax.figure.dpi * 2.54 + 0.3


def _zoom(ax, lims, centre, k: float) -> None:
    """The view ``lims`` (xlim, ylim) scaled by ``k`` about ``centre``: the same panel, ``k`` times coarser."""
    (x0, x1), (y0, y1) = lims
    cx, cy = centre
    ax.set_xlim(cx + (x0 - cx) * k, cx + (x1 - cx) * k)
    ax.set_ylim(cy + (y0 - cy) * k, cy + (y1 - cy) * k)


def _bar_on(art, frame, pl=None) -> int:
    """1 if the panel's scale bar (drawn last) found its place only on the detail's frame, or found no place
    with its room free (``pl``: the panel's placer; ``placed["scale-bar"]``)."""
    bar = art.get("scale_bar", [])
    pin = pl.placed.get("scale-bar") if pl is not None else None
    return int(bool(bar) and (box(*bar[0].get_bbox().get_points().ravel()).intersects(frame) or
                              (pin is not None and len(pin) > 2 and not pin[2])))


def make_room(polygon, ax, draw, fixed: bool = False) -> None:
    """Before ``polygon`` is drawn on ``ax`` by ``draw()`` (its Artists): where it calls for a detail that finds
    no free place in its panel (a narrow panel, a crowd as wide as the polygon), make the panel's scale a round
    step coarser, and again (at most ``MOST_STEPS``), until the detail finds one: the polygon drawn smaller
    leaves the detail its room. Each scale is tried by drawing the polygon tentatively
    (``LabelPlacer.trial``), the scale bar too needing a place off the detail's frame; where none gives a free
    place, the one whose place meets the fewest marks and lines. The scale stays where it is ``fixed`` (the
    user's), or pinned (a step frame)."""
    pl = placer(ax)
    s0 = view_scale(ax) or per_cm(ax)
    if fixed or pl.pins.get("_scale") is not None or pl.pins.get("detail") is not None or \
            crowd(polygon, per_cm(ax)) is None:
        return
    lims = (ax.get_xlim(), ax.get_ylim())
    xy = np.array([np.zeros(2)] + list(_all_points(polygon).values()))
    centre = tuple((xy.min(axis=0) + xy.max(axis=0)) / 2)     # the polygon's box's, kept where it is
    best, s = None, s0
    for _ in range(MOST_STEPS + 1):
        _zoom(ax, lims, centre, s / s0)
        ax._velpoly_scale = s
        with pl.trial():
            art = draw()
            hits = None if art.detail is None else art.detail.hits + _bar_on(art, art.detail.frame, pl)
        if hits is not None and (best is None or hits < best[0]):
            best = (hits, s)
        if hits == 0:
            break
        s = nice_scale(s * 1.0001)
    s = s0 if best is None else best[1]
    _zoom(ax, lims, centre, s / s0)
    ax._velpoly_scale = s


def _mark(d, region, frame) -> list:
    """The region's box on the polygon, the inset's frame (over a white ground) and the leader joining them."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Rectangle
    from .labels import segment
    st, ax = d.st, d.ax
    marks = []
    x0, y0, x1, y1 = frame.bounds
    ground = Rectangle((x0, y0), x1 - x0, y1 - y0, facecolor=st.paper, edgecolor="none", zorder=7.4,
                       gid="detail-ground")
    ax.add_patch(ground)
    for g, gid, lw in ((region, "detail-region", st.thin_lw * 1.4), (frame, "detail-frame", st.thin_lw * 2.0)):
        x0, y0, x1, y1 = g.bounds
        r = Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, edgecolor=st.ink, lw=lw, zorder=8, gid=gid)
        ax.add_patch(r)
        marks.append(r)
    a, b = nearest_points(region.exterior, frame.exterior)
    ln = Line2D([a.x, b.x], [a.y, b.y], lw=st.thin_lw * 1.4, color=st.ink, zorder=8, gid="detail-leader")
    ax.add_line(ln)
    marks += [ln, ground]
    d.pl.add_obstacle(frame)
    d.pl.add_obstacle(region.exterior.buffer(0.6 * d.pp), hard=False)
    d.pl.add_obstacle(segment((a.x, a.y), (b.x, b.y)).buffer(0.6 * d.pp), hard=False)
    return marks


def _inset(d, region, frame, s, pads):
    """The detail's axes over ``frame`` beneath its caption's strip: the region at the scale ``s``, centred in
    it with ``pads`` (:func:`_pads`) about it."""
    pc = d.pc
    cap = _caption_cm(d.st) * pc
    fx0, fy0, fx1, fy1 = frame.bounds
    inset = d.ax.inset_axes((fx0, fy0, fx1 - fx0, fy1 - fy0 - cap), transform=d.ax.transData, zorder=7.5)
    fit_view(inset, region.bounds, scale=s, margin=0.0)
    fw, fh = (fx1 - fx0) / pc, (fy1 - fy0 - cap) / pc
    x0, y0, x1, y1 = region.bounds
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    pl, pb, pr, pt = pads
    cx, cy = cx + (pr - pl) * s / 2, cy + (pt - pb) * s / 2
    inset.set_xlim(cx - fw * s / 2, cx + fw * s / 2)
    inset.set_ylim(cy - fh * s / 2, cy + fh * s / 2)
    inset.set_axis_off()
    return inset


def draw_detail(d) -> Detail | None:
    """Draw the detail of the polygon drawing ``d`` (:class:`velpoly.render.polygon._PolygonDrawing`) if the
    rule calls for one; return it (or None). Called before the panel's legend and labels, which keep clear
    of it; the panel's view may move (not its scale: :func:`make_room` chose it) to make room for it."""
    pl, pc, ax = d.pl, d.pc, d.ax
    c = crowd(d.polygon, pc, d.tol)
    if c is None:
        return None
    region = _region(c, pc)
    units = d.m.units if d.m is not None else ""
    min_w = _caption_width(d)
    hits, s, frame, (dx, dy), pads = _place(d, region, min_w, (_pads(c, d.st), (PAD_CM,) * 4))
    if dx or dy:
        ax.set_xlim(*(v + dx for v in ax.get_xlim()))
        ax.set_ylim(*(v + dy for v in ax.get_ylim()))
    marks = _mark(d, region, frame)
    fx0, fy0, fx1, fy1 = frame.bounds
    caption = ax.text(fx0 + 0.15 * pc, fy1 - 0.08 * pc, "detail, " + scale_text(s, units, 1 if d.velocity else 2),
                      ha="left", va="top", fontsize=d.st.small_size, style="italic", zorder=9, gid="detail-caption")
    inset = _inset(d, region, frame, s, pads)
    ipl = placer(inset)
    pin = pl.pins.get("detail")
    ipl.pins = pin[3] if pin is not None else {}
    # the labels keep EDGE_PT inside the frame (its rule is as thick as a line; a glyph on it reads as cut)
    ipl.add_obstacle(view_box(inset).exterior.buffer(EDGE_PT * per_point(inset)))
    inner = type(d)(d.polygon, inset, d.st, d.opts, d.m, d.upto)   # (the polygon module's class: no import cycle)
    inner.shade_images()
    inner.construction_lines()
    inner.vectors()
    inner.origin()
    inner.labels(within=region, gid_prefix="detail-label", every=True)
    pl.placed["detail"] = ("detail", tuple(map(float, frame.bounds)), s, ipl.placed, pads)
    outside = view_box(ax).difference(region)
    return Detail(c, s, inset, region, frame, outside, caption, inner.art, marks, hits)
