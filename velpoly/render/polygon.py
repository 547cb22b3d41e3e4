"""Velocity and acceleration polygons, drawn from :mod:`velpoly.polygons`' objects.

A polygon's data coordinates are velocities (accelerations): the image of a
point sits at its velocity, the origin O_v (O_a) at zero. Drawn, in the
order a textbook builds them: the dashed construction lines of each step,
extended past their intersection and marked with their reason where there
is room; the absolute vectors from the origin to each image; the relative
vectors between images (for accelerations, the normal, tangential, Coriolis
and slip components, each in its own line style, with a legend); each
link's image shaded in the link's colour; one label per image (images that
coincide share it); a scale bar in units/s (units/s²).

Nothing is computed here but where to put things: every point drawn is an
image, a vector or a line of the :class:`~velpoly.polygons.Polygon`.
"""
from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import Point, box
from shapely.geometry import Polygon as SPolygon

from .canvas import Artists, arrow, fit_view, get_ax, per_cm, per_point, prose_tex, tex, view_box, view_scale
from .labels import placer, segment
from .options import drawing_options
from .scalebar import scale_bar
from .style import KIND_LABELS, get_style, link_colour

__all__ = ["draw_polygon", "draw_velocity_polygon", "draw_acceleration_polygon", "polygon_bounds",
           "known_keys", "image_groups", "legend_room"]

_REL_TOL = 1e-9


def _size(polygon) -> float:
    pts = np.array([np.zeros(2)] + [np.asarray(v, float) for v in polygon.images.values()])
    return float(np.hypot(*(pts.max(axis=0) - pts.min(axis=0)))) or 1.0


def polygon_bounds(polygon) -> tuple[float, float, float, float]:
    """The box of the origin and every image (and every vector's ends)."""
    pts = [np.zeros(2)] + [np.asarray(v, float) for v in polygon.images.values()]
    for st in polygon.steps:
        for v in st.vectors:
            pts += [np.asarray(v.tail, float), np.asarray(v.head, float)]
    p = np.array([q for q in pts if np.all(np.isfinite(q))])
    return (*p.min(axis=0), *p.max(axis=0))


def known_keys(polygon, upto: int | None = None) -> list[str]:
    """Keys whose images are drawn after ``upto`` steps (all if None), in the polygon's order.

    An image is known once a step finds it; images at the origin (frame
    points) are known from the start.
    """
    if upto is None:
        return list(polygon.images)
    tol = _REL_TOL * _size(polygon)
    found = {k for st in polygon.steps[:upto] for k in st.found}
    return [k for k, v in polygon.images.items() if k in found or float(np.hypot(*v)) <= tol]


def image_groups(polygon, points: dict) -> tuple[list[str], list[list[str]]]:
    """Keys at the origin, and the other keys grouped by coinciding images (one label a group).

    ``points`` maps keys to images: the polygon's images and auxiliary points drawn.
    """
    tol = _REL_TOL * _size(polygon)
    at_origin = [k for k, v in points.items() if float(np.hypot(*v)) <= tol]
    groups: list[list[str]] = []
    for k, v in points.items():
        if k in at_origin:
            continue
        p = np.asarray(v, float)
        for g in groups:
            if float(np.hypot(*(p - np.asarray(points[g[0]], float)))) <= tol:
                g.append(k)
                break
        else:
            groups.append([k])
    return at_origin, groups


def _label_text(polygon, names: dict, keys, with_origin: bool) -> str:
    labels = [polygon.origin_label] if with_origin else []
    for k in keys:
        lab = names.get(k, k)
        if lab not in labels:
            labels.append(lab)
    math = any(tex(lab).startswith("$") for lab in labels)   # primes beside mathtext go in mathtext too
    return ", ".join(tex(lab, math=math) for lab in labels)


def draw_polygon(polygon, ax=None, *, mechanism=None, style="textbook", options=None, scale: float | None = None,
                 upto: int | None = None) -> Artists:
    """Draw a velocity or acceleration :class:`~velpoly.polygons.Polygon`; return its Artists.

    Parameters
    ----------
    polygon : Polygon
        From :func:`velpoly.polygons.velocity_polygon` or ``acceleration_polygon``.
    ax : matplotlib Axes, optional
        pyplot's current axes if None; an axes with a velpoly view keeps its scale.
    mechanism : Mechanism, optional
        For the links' colours, the units and the ``[drawing]`` options.
    upto : int, optional
        Draw only the first ``upto`` steps (the ``--steps`` frames); the view
        is that of the whole polygon, so frames do not jump.

    Returns
    -------
    Artists
        Roles ``images`` (shaded link images), ``construction``, ``reasons``,
        ``arrows`` (arrowheads; each has the gid ``"<kind>-<tail>-<head>"``),
        ``shafts``, ``origin``, ``labels``, ``legend``, ``scale_bar``;
        ``.labels`` maps every image's key (and every auxiliary point's) to its label, ``.arrows`` lists
        ``(kind, tail, head, patch)`` for every vector drawn.
    """
    ax = get_ax(ax)
    st = get_style(style)
    m = mechanism
    opts = options if options is not None else (drawing_options(m) if m is not None else None)
    velocity = polygon.kind == "velocity"
    if view_scale(ax) is None:
        user = None if opts is None else (opts.velocity_scale if velocity else opts.acceleration_scale)
        fit_view(ax, polygon_bounds(polygon), scale=scale if scale is not None else user, margin=0.08)
        ax.set_axis_off()
    art = Artists(ax)
    art.arrows = []
    pl = placer(ax)
    pc, pp = per_cm(ax), per_point(ax)
    keys = known_keys(polygon, upto)
    known = set(keys)
    steps = polygon.steps if upto is None else polygon.steps[:upto]
    origin = np.zeros(2)
    # auxiliary points (a guide's point under a block, an auxiliary point of a link) located so far
    aux = getattr(polygon, "auxiliary", None) or {}
    aux_keys = [a for st_ in steps for a in getattr(st_, "auxiliary", ()) if a in aux]
    points = {k: np.asarray(polygon.images[k], float) for k in keys}
    points.update({a: np.asarray(aux[a].image, float) for a in aux_keys})
    names = dict(polygon.labels)
    names.update({a: aux[a].label for a in aux_keys})

    # shaded link images
    for z, (lk, img_keys) in enumerate(polygon.link_images.items()):
        if len(img_keys) >= 3 and all(k in known for k in img_keys):
            # the image is similar to the link, whose body is the hull of its points (a plate): the hull
            # of the images, not the images in file order (A, B, E, F with E on AB would shade a, e, f)
            hull = shapely.MultiPoint([tuple(map(float, polygon.images[k])) for k in img_keys]).convex_hull
            if hull.geom_type != "Polygon" or hull.area <= (1e-9 * _size(polygon)) ** 2:
                continue
            pts = [tuple(map(float, xy)) for xy in hull.exterior.coords[:-1]]
            colour = link_colour(m, opts, st, lk) if m is not None else st.palette[z % len(st.palette)]
            from matplotlib.patches import Polygon as MPolygon
            patch = MPolygon(pts, closed=True, facecolor=colour, alpha=st.image_alpha, edgecolor="none",
                             zorder=1, gid=f"image-{lk}")
            ax.add_patch(patch)
            art.add("images", patch)

    # construction lines
    show_reasons = opts is None or opts.reasons
    from matplotlib.lines import Line2D
    view = view_box(ax)
    for si, step in enumerate(steps):
        located = list(step.found) + [a for a in getattr(step, "auxiliary", ()) if a in aux]
        hit = points[located[0]] if located else None
        current = upto is not None and si == len(steps) - 1
        for li, ln in enumerate(step.lines):
            base = np.asarray(ln.base, float)
            d = np.asarray(ln.direction, float)
            d = d / max(float(np.hypot(*d)), 1e-300)
            t_hit = float(np.dot(hit - base, d)) if hit is not None else 0.0
            ext = 0.9 * pc
            a = base + d * (min(0.0, t_hit) - ext)
            b = base + d * (max(0.0, t_hit) + ext)
            seg = segment(a, b).intersection(view)
            if seg.is_empty or seg.geom_type != "LineString":
                continue
            (x0, y0), (x1, y1) = seg.coords[0], seg.coords[-1]
            trial = li >= 2     # a trial solution's own lines, beyond the two intersected
            heavy = 1.6 if current and not trial else 1.0   # the current step's lines; dashes as long as the others'
            line = Line2D([x0, x1], [y0, y1], lw=st.thin_lw * heavy, color=st.ink,
                          linestyle=(0, (1, 2)) if trial else (0, (6 / heavy, 3 / heavy)), zorder=1.5,
                          gid=f"construction-{step.index}-{li}-{ln.base_label}")
            line._velpoly_line = ln
            ax.add_line(line)
            art.add("construction", line)
            pl.add_obstacle(segment((x0, y0), (x1, y1)), hard=False)

    # vectors: absolute from the origin to each known image, then the steps' other vectors
    drawn = set()
    tol = _REL_TOL * _size(polygon)

    def vec(kind, tail, head, label=""):
        """Draw the vector unless it is null or already drawn; whether it was drawn."""
        tail, head = np.asarray(tail, float), np.asarray(head, float)
        if float(np.hypot(*(head - tail))) <= tol:
            return False
        key = tuple(np.round(np.r_[tail, head] / tol).astype(np.int64))
        if key in drawn:   # one arrow a vector: an absolute one that is also relative (from O_v) stays absolute
            return False
        drawn.add(key)
        ls, colour, f = st.kind_styles.get(kind, st.kind_styles["relative"])
        colour = st.ink if colour is None else colour
        gid = f"{kind}-{label}" if label else None
        sh, hd, poly = arrow(ax, tail, head, lw=st.arrow_lw * f, head_length=st.head_length, colour=colour,
                             linestyle=ls, zorder=3 if kind == "absolute" else 3.5, gid=gid)
        art.add("shafts", sh)
        art.add("arrows", hd)
        art.arrows.append((kind, tail, head, hd))
        pl.add_obstacle(poly)
        pl.add_obstacle(segment(tail, head).buffer(0.6 * pp), hard=False)
        return True

    for k in keys:
        vec("absolute", origin, polygon.images[k], label=k)
    kinds = {"absolute"}
    for step in steps:
        for v in step.vectors:
            # the legend lists the kinds drawn: a component that is also an absolute vector (the slip of a
            # block on the frame, the normal acceleration of a crank) is drawn, and listed, as absolute
            if vec(v.kind, v.tail, v.head, label=v.label):
                kinds.add(v.kind)

    # the origin
    r = 0.05 * pc
    o = Point(0, 0).buffer(r, quad_segs=8)
    from .displacement import shape_patch
    op = shape_patch(o, facecolor=st.ink, edgecolor=st.ink, lw=0, zorder=4, gid=f"origin-{polygon.kind}")
    ax.add_patch(op)
    art.add("origin", op)
    pl.add_obstacle(o)

    # the legend before the labels, which then keep clear of it
    pinned = pl.pins.get("legend")
    if pinned is not None:    # a step frame: the finished construction's legend, so that it does not change
        kinds = set(pinned[4])
    if not velocity and len(kinds) > 1:
        art.add("legend", *_legend(ax, st, [k for k in st.kind_styles if k in kinds]))

    # labels: one per group of coinciding images; the origin's group is labelled with the origin
    at_origin, groups = image_groups(polygon, points)
    cx, cy = np.mean(np.array([np.zeros(2)] + list(points.values())), axis=0)
    for gi, g in enumerate([at_origin] + groups):
        p = np.zeros(2) if gi == 0 else points[g[0]]
        away = p - np.array([cx, cy])
        prefer = math.degrees(math.atan2(away[1], away[0])) if np.hypot(*away) > tol else -135.0
        # an image close to another (a short relative velocity): its label on the side away from the
        # other, so that the two labels do not read as one ("e f" over two images a millimetre apart)
        near = [q for q in [np.zeros(2)] + [points[h[0]] for h in groups]
                if tol < float(np.hypot(*(q - p))) < 1.0 * pc]
        if near:
            q = min(near, key=lambda q: float(np.hypot(*(q - p))))
            d = (p - q) / float(np.hypot(*(p - q)))
            a = np.array([math.cos(math.radians(prefer)), math.sin(math.radians(prefer))])
            v = d + 0.35 * a if np.dot(d, a) > -0.9 else d
            prefer = math.degrees(math.atan2(v[1], v[0]))
        within = 70.0 if near else None
        t = pl.place(p, _label_text(polygon, names, g, gi == 0), prefer=prefer, fontsize=st.font_size, zorder=7,
                     fontstyle="italic", within=within,
                     gid=f"label-{polygon.kind}-" + ("origin+" if gi == 0 else "") + "+".join(g))
        art.add("labels", t)
        for k in g:
            art.labels[k] = t

    # the reasons, where there is room (after the labels, which matter more)
    if show_reasons:
        for line in art.get("construction", []):
            ln = line._velpoly_line
            xs, ys = line.get_data()
            t = pl.place_along((xs[0], ys[0]), (xs[1], ys[1]), prose_tex(ln.reason), pad=8.0,
                               fontsize=st.small_size * 0.9, style="italic", zorder=6, gid=line.get_gid() + "-reason")
            if t is not None:
                art.add("reasons", t)

    units = m.units if m is not None else ""
    art.add("scale_bar", *scale_bar(ax, st, units, 1 if velocity else 2))
    return art


def _legend(ax, st, kinds) -> list:
    """The line styles of the vector kinds, in a free corner of the panel."""
    from matplotlib.lines import Line2D
    handles = []
    for k in kinds:
        ls, colour, f = st.kind_styles[k]
        handles.append(Line2D([], [], lw=st.arrow_lw * f, linestyle=ls, color=st.ink if colour is None else colour))
    pl = placer(ax)
    locs = ("upper right", "upper left", "lower right", "lower left", "center right", "center left",
            "upper center", "lower center")
    # the full legend, smaller, in two columns, both: the first free corner or side; else the first free
    # place of a grid over the panel, nearest its border first (a polygon filling every corner leaves room
    # elsewhere); else the place crossing the fewest marks, then lines
    variants = ((st.small_size, 1), (st.small_size * 0.85, 1), (st.small_size, 2), (st.small_size * 0.85, 2))
    geoms = np.array(pl.boxes + pl.hard + pl.soft, dtype=object)
    weights = np.array([10] * (len(pl.boxes) + len(pl.hard)) + [1] * len(pl.soft))
    inv = ax.transData.inverted()

    def make(size, ncol, at=(1.0, 1.0), loc="upper right", transform=None):
        return ax.legend(handles, [KIND_LABELS[k] for k in kinds], loc=loc, fontsize=size, ncol=ncol,
                         handlelength=3.2 if ncol == 1 else 2.4, borderaxespad=0.0, columnspacing=1.0,
                         bbox_to_anchor=at, bbox_transform=transform)

    vx0, vy0, vx1, vy1 = view_box(ax).bounds
    pp = per_point(ax)
    sizes = []
    for size, ncol in variants:   # measured once a variant
        leg = make(size, ncol)
        bb = leg.get_window_extent(pl.renderer)
        (x0, y0), (x1, y1) = inv.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
        sizes.append((size, ncol, abs(x1 - x0), abs(y1 - y0)))
    pc_ = per_cm(ax)
    paper = [(w / pc_, h / pc_) for _, _, w, h in sizes]   # the variants' sizes in cm of paper

    def spots(w, h, pad):
        named = []
        for loc in locs:
            v, u = loc.split()
            named.append(({"left": vx0 + pad, "right": vx1 - pad - w, "center": (vx0 + vx1 - w) / 2}[u],
                          {"lower": vy0 + pad, "upper": vy1 - pad - h, "center": (vy0 + vy1 - h) / 2}[v]))
        lo_x, hi_x, lo_y, hi_y = vx0 + pad, vx1 - pad - w, vy0 + pad, vy1 - pad - h
        grid = [(lo_x + (hi_x - lo_x) * i / 8, lo_y + (hi_y - lo_y) * j / 8) for i in range(9) for j in range(9)]
        grid.sort(key=lambda c: (round(min(c[0] - lo_x, hi_x - c[0], c[1] - lo_y, hi_y - c[1]) / max(pad, 1e-300)),
                                 -c[1], c[0]))
        return named, grid

    def hits_of(b):
        return int(np.dot(shapely.intersects(geoms, b), weights)) if len(geoms) else 0

    inside = view_box(ax).buffer(1e-9 * (vx1 - vx0))
    best = None
    pin = pl.pins.get("legend")
    if pin is not None:       # a step frame: where the finished construction has it
        size, ncol, (lx, ly) = pin[1], pin[2], pin[3]
        w, h = next((w, h) for s_, n_, w, h in sizes if (s_, n_) == (size, ncol))
        b = box(lx, ly, lx + w, ly + h)
        best = (hits_of(b), (size, ncol), b)
    for stage in (() if best is not None else (0, 1)):   # corners and sides of every variant, then the grids
        for size, ncol, w, h in sizes:
            pad = 0.3 * size * pp
            for lx, ly in spots(w, h, pad)[stage]:
                b = box(lx, ly, lx + w, ly + h)
                if not inside.contains(b):   # a legend wider than the panel
                    continue
                hits = hits_of(b)
                if best is None or hits < best[0]:
                    best = (hits, (size, ncol), b)
                if hits == 0:
                    break
            if best is not None and best[0] == 0:
                break
        if best is not None and best[0] == 0:
            break
    if best is None:   # wider than the panel in every variant: the smallest, at the upper right
        size, ncol, w, h = min(sizes, key=lambda v: v[2])
        b = box(vx1 - w, vy1 - h, vx1, vy1)
        best = (hits_of(b) + 1, (size, ncol), b)
    hits, (size, ncol), b = best
    leg = make(size, ncol, at=(b.bounds[0], b.bounds[1]), loc="lower left", transform=ax.transData)
    leg._velpoly_hits = hits
    leg._velpoly_paper = paper
    pl.placed["legend"] = ("legend", size, ncol, (float(b.bounds[0]), float(b.bounds[1])), tuple(kinds))
    pl.boxes.append(b)
    pl.texts.append(leg)
    return [leg]


def legend_room(ax, bounds, paper, margin: float, label: float = 0.0):
    """Bounds grown so that, fitted to ``ax`` with ``margin``, the polygon leaves a strip along the top or
    the right of the panel for a legend of ``paper`` = [(width, height) cm, ...] (its variants), and a
    label's room (``label`` pt of type) between them: the strip that draws the polygon largest.
    Returns (bounds, scale)."""
    from .canvas import axes_cm, nice_scale
    wcm, hcm = axes_cm(ax)
    x0, y0, x1, y1 = bounds
    gap = 0.2 + 1.6 * label / 72 * 2.54
    best = None
    for lw, lh in paper:
        for side in ("top", "right"):
            w_room = wcm * (1 - 2 * margin) - (lw + gap if side == "right" else 0.0)
            h_room = hcm * (1 - 2 * margin) - (lh + gap if side == "top" else 0.0)
            if w_room <= 0 or h_room <= 0 or (side == "top" and lw > wcm * (1 - margin)) or \
                    (side == "right" and lh > hcm * (1 - margin)):
                continue
            s = nice_scale(max((x1 - x0) / w_room, (y1 - y0) / h_room, 1e-300))
            grown = (x0, y0, x1 + (lw + gap) * s, y1) if side == "right" else (x0, y0, x1, y1 + (lh + gap) * s)
            if best is None or s < best[1]:
                best = (grown, s)
    return best if best is not None else (bounds, None)


def draw_velocity_polygon(sol, ax=None, *, style="textbook", options=None, polygon=None, scale=None,
                          upto=None) -> Artists:
    """Draw the velocity polygon of ``sol`` (from :func:`velpoly.polygons.velocity_polygon`).

    See :func:`draw_polygon` for the parameters and what is returned.
    """
    if polygon is None:
        from ..polygons import velocity_polygon
        polygon = velocity_polygon(sol)
    return draw_polygon(polygon, ax, mechanism=sol.mechanism, style=style, options=options, scale=scale, upto=upto)


def draw_acceleration_polygon(sol, ax=None, *, style="textbook", options=None, polygon=None, scale=None,
                              upto=None) -> Artists:
    """Draw the acceleration polygon of ``sol`` (from :func:`velpoly.polygons.acceleration_polygon`).

    Raises :class:`~velpoly.errors.InputError` when the mechanism has no
    accelerations (a contact given by its normal only).
    """
    if polygon is None:
        from ..polygons import acceleration_polygon
        polygon = acceleration_polygon(sol)
    return draw_polygon(polygon, ax, mechanism=sol.mechanism, style=style, options=options, scale=scale, upto=upto)
