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
from shapely.geometry import Point
from shapely.geometry import Polygon as SPolygon

from .canvas import (Artists, add_patch, arrow, box, fit_view, get_ax, per_cm, per_point, prose_tex, tex, view_box,
                     view_scale, wrap_caption)
from .labels import placer, segment
from .options import drawing_options
from .scalebar import scale_bar
from .style import KIND_LABELS, get_style, link_colour

__all__ = ["draw_polygon", "draw_velocity_polygon", "draw_acceleration_polygon", "polygon_bounds",
           "known_keys", "image_groups", "legend_room", "lying_along", "Beside", "APART", "HEADS_APART"]

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


def _label_names(polygon, names: dict, keys, with_origin: bool) -> list[str]:
    """The names a group's label lists (the origin's first, each once), as text for an italic Text."""
    labels = [polygon.origin_label] if with_origin else []
    for k in keys:
        lab = names.get(k, k)
        if lab not in labels:
            labels.append(lab)
    math = any(tex(lab).startswith("$") for lab in labels)   # primes beside mathtext go in mathtext too
    return [tex(lab, math=math) for lab in labels]


def _label_text(polygon, names: dict, keys, with_origin: bool) -> str:
    return ", ".join(_label_names(polygon, names, keys, with_origin))


def wrapped(names: list[str], lines: int) -> str:
    """The names of coinciding points listed in ``lines`` lines, as even as their order allows (the longer
    lines first), each line but the last ending in a comma: a long list beside the origin set as a block.

    >>> wrapped(["O", "a", "b", "c", "d"], 2)
    'O, a, b,\\nc, d'
    >>> wrapped(["O", "a", "b"], 1)
    'O, a, b'
    """
    lines = max(1, min(lines, len(names)))
    size, more = divmod(len(names), lines)
    out, i = [], 0
    for n in range(lines):
        j = i + size + (1 if n < more else 0)
        out.append(", ".join(names[i:j]))
        i = j
    return ",\n".join(out)


def most_lines(n: int) -> int:
    """The most lines a list of ``n`` names is set in: at least two names a line, at most three lines."""
    return max(1, min(3, (n + 1) // 2))


class _PolygonDrawing:
    """One polygon being drawn on one axes (the panel, or its detail): what is known and where."""

    # what the detail (velpoly.render.detail, which must not import this module back) uses of a drawing
    def bounds(self) -> tuple[float, float, float, float]:
        return polygon_bounds(self.polygon)

    @staticmethod
    def spots(bounds, w: float, h: float, pad: float) -> tuple[list, list]:
        return spots(bounds, w, h, pad)

    @staticmethod
    def hit_counter(pl):
        return hit_counter(pl)

    def __init__(self, polygon, ax, st, opts, mechanism, upto):
        self.polygon, self.ax, self.st, self.opts, self.m = polygon, ax, st, opts, mechanism
        self.velocity = polygon.kind == "velocity"
        self.art = Artists(ax)
        self.art.arrows = []
        self.pl = placer(ax)
        self.pc, self.pp = per_cm(ax), per_point(ax)
        self.keys = known_keys(polygon, upto)
        self.known = set(self.keys)
        self.upto = upto
        self.steps = polygon.steps if upto is None else polygon.steps[:upto]
        # auxiliary points (a guide's point under a block, an auxiliary point of a link) located so far
        self.aux = aux = getattr(polygon, "auxiliary", None) or {}
        aux_keys = [a for st_ in self.steps for a in getattr(st_, "auxiliary", ()) if a in aux]
        self.points = {k: np.asarray(polygon.images[k], float) for k in self.keys}
        self.points.update({a: np.asarray(aux[a].image, float) for a in aux_keys})
        self.names = dict(polygon.labels)
        self.names.update({a: aux[a].label for a in aux_keys})
        self.tol = _REL_TOL * _size(polygon)
        self.drawn: set = set()

    def shade_images(self):
        """Each link's image, the hull of its points' images, shaded in the link's colour."""
        from matplotlib.patches import Polygon as MPolygon
        polygon, st, m = self.polygon, self.st, self.m
        for z, (lk, img_keys) in enumerate(polygon.link_images.items()):
            if len(img_keys) < 3 or not all(k in self.known for k in img_keys):
                continue
            # the image is similar to the link, whose body is the hull of its points (a plate): the hull
            # of the images, not the images in file order (A, B, E, F with E on AB would shade a, e, f)
            hull = shapely.MultiPoint([tuple(map(float, polygon.images[k])) for k in img_keys]).convex_hull
            if hull.geom_type != "Polygon" or hull.area <= (1e-9 * _size(polygon)) ** 2:
                continue
            pts = [tuple(map(float, xy)) for xy in hull.exterior.coords[:-1]]
            colour = link_colour(m, self.opts, st, lk) if m is not None else st.palette[z % len(st.palette)]
            patch = MPolygon(pts, closed=True, facecolor=colour, alpha=st.image_alpha, edgecolor="none",
                             zorder=1, gid=f"image-{lk}")
            add_patch(self.ax, patch)
            self.art.add("images", patch)

    def construction_lines(self):
        """The dashed lines of each step, extended past their intersection (the current step's heavier)."""
        view = view_box(self.ax)
        for si, step in enumerate(self.steps):
            located = list(step.found) + [a for a in getattr(step, "auxiliary", ()) if a in self.aux]
            hit = self.points[located[0]] if located else None
            current = self.upto is not None and si == len(self.steps) - 1
            for li, ln in enumerate(step.lines):
                self._construction_line(step, li, ln, hit, current, view)

    def _construction_line(self, step, li, ln, hit, current, view):
        from matplotlib.lines import Line2D
        st = self.st
        base = np.asarray(ln.base, float)
        d = np.asarray(ln.direction, float)
        d = d / max(float(np.hypot(*d)), 1e-300)
        t_hit = float(np.dot(hit - base, d)) if hit is not None else 0.0
        ext = 0.9 * self.pc
        a = base + d * (min(0.0, t_hit) - ext)
        b = base + d * (max(0.0, t_hit) + ext)
        seg = segment(a, b).intersection(view)
        if seg.is_empty or seg.geom_type != "LineString":
            return
        (x0, y0), (x1, y1) = seg.coords[0], seg.coords[-1]
        trial = li >= 2     # a trial solution's own lines, beyond the two intersected
        heavy = 1.6 if current and not trial else 1.0   # the current step's lines; dashes as long as the others'
        line = Line2D([x0, x1], [y0, y1], lw=st.thin_lw * heavy, color=st.ink,
                      linestyle=(0, (1, 2)) if trial else (0, (6 / heavy, 3 / heavy)), zorder=1.5,
                      gid=f"construction-{step.index}-{li}-{ln.base_label}")
        line._velpoly_line = ln
        self.ax.add_line(line)
        self.art.add("construction", line)
        self.pl.add_obstacle(segment((x0, y0), (x1, y1)), hard=False)

    def _key(self, tail, head) -> tuple | None:
        """The vector's ends rounded to the polygon's tolerance (one arrow a key); None for a null vector."""
        if float(np.hypot(*(head - tail))) <= self.tol:
            return None
        return tuple(np.round(np.r_[tail, head] / self.tol).astype(np.int64))

    def _all_vectors(self) -> list:
        """(kind, tail, head, label) of every vector of the finished construction, in the order they are drawn:
        the absolute vector of each image, then the steps' others."""
        out = [("absolute", np.zeros(2), np.asarray(self.polygon.images[k], float), k) for k in self.polygon.images]
        return out + [(v.kind, np.asarray(v.tail, float), np.asarray(v.head, float), v.label)
                      for step in self.polygon.steps for v in step.vectors]

    def shifts(self) -> dict:
        """Where each vector of the finished construction is drawn: its key's shift (data units), zero for one on its
        own line, else the offset that draws it beside the vectors drawn before it (:func:`beside`). Planned on
        the finished construction, so that a step frame draws each vector where the last frame has it."""
        drawn, out = Beside(APART * self.st.head_length * self.pp, ALONG * self.pp), {}
        centre = np.mean(np.array([np.zeros(2)] + list(self.polygon.images.values()), float), axis=0)
        for kind, tail, head, _ in self._all_vectors():
            key = self._key(tail, head)
            if key is not None and key not in out:
                out[key] = drawn.add(tail, head, centre, kind)
        return out

    def vector(self, kind, tail, head, label="", shift=None):
        """Draw the vector unless it is null or already drawn, moved by ``shift`` (beside another vector on its
        line: :meth:`shifts`); whether it was drawn."""
        st = self.st
        tail, head = np.asarray(tail, float), np.asarray(head, float)
        key = self._key(tail, head)
        if key is None or key in self.drawn:   # one arrow a vector: an absolute one that is also relative stays absolute
            return False
        self.drawn.add(key)
        shift = np.zeros(2) if shift is None else shift
        ls, colour, f = st.kind_styles.get(kind, st.kind_styles["relative"])
        colour = st.ink if colour is None else colour
        gid = f"{kind}-{label}" if label else None
        sh, hd, poly = arrow(self.ax, tail + shift, head + shift, lw=st.arrow_lw * f, head_length=st.head_length,
                             colour=colour, linestyle=ls, zorder=3 if kind == "absolute" else 3.5, gid=gid)
        sh._velpoly_shift = hd._velpoly_shift = shift
        self.art.add("shafts", sh)
        self.art.add("arrows", hd)
        self.art.arrows.append((kind, tail, head, hd))
        self.pl.add_obstacle(poly)
        self.pl.add_obstacle(segment(tail + shift, head + shift).buffer(0.6 * self.pp), hard=False)
        return True

    def vectors(self) -> set:
        """Absolute vectors from the origin to each known image, then the steps' others, each where
        :meth:`shifts` puts it; the kinds drawn."""
        shifts = self.shifts()
        for k in self.keys:
            img = np.asarray(self.polygon.images[k], float)
            self.vector("absolute", np.zeros(2), img, label=k, shift=shifts.get(self._key(np.zeros(2), img)))
        kinds = {"absolute"}
        for step in self.steps:
            for v in step.vectors:
                # the legend lists the kinds drawn: a component that is also an absolute vector (the slip of a
                # block on the frame, the normal acceleration of a crank) is drawn, and listed, as absolute
                tail, head = np.asarray(v.tail, float), np.asarray(v.head, float)
                if self.vector(v.kind, tail, head, label=v.label, shift=shifts.get(self._key(tail, head))):
                    kinds.add(v.kind)
        return kinds

    def origin(self):
        from .displacement import shape_patch
        st = self.st
        o = Point(0, 0).buffer(0.05 * self.pc, quad_segs=8)
        op = shape_patch(o, facecolor=st.ink, edgecolor=st.ink, lw=0, zorder=4, gid=f"origin-{self.polygon.kind}")
        add_patch(self.ax, op)
        self.art.add("origin", op)
        self.pl.add_obstacle(o)

    def legend(self, kinds):
        """The legend of the kinds drawn (a step frame: the finished construction's), before the labels."""
        pinned = self.pl.pins.get("legend")
        if pinned is not None:    # a step frame: the finished construction's legend, so that it does not change
            kinds = set(pinned[4])
        # a velocity polygon's absolute and relative vectors read apart by their weight (and colour) and labels;
        # one that also draws a block's slip along its guide lists its kinds, as an acceleration polygon does
        if len(kinds) > 1 and (not self.velocity or kinds - {"absolute", "relative"}):
            self.art.add("legend", *_legend(self.ax, self.st, [k for k in self.st.kind_styles if k in kinds]))

    def labels(self, within=None, gid_prefix="label", every: bool = False):
        """One label per group of coinciding images (the origin's group labelled with the origin); only the
        groups whose image lies in ``within`` (a shapely geometry), if given. The origin's label (``every``:
        each label, as a detail's are) is kept off the lines where any of its forms finds room
        (:meth:`_off_lines`)."""
        at_origin, groups = image_groups(self.polygon, self.points)
        cx, cy = np.mean(np.array([np.zeros(2)] + list(self.points.values())), axis=0)
        for gi, g in enumerate([at_origin] + groups):
            p = np.zeros(2) if gi == 0 else self.points[g[0]]
            if within is not None and not within.contains(Point(*p)):
                continue
            prefer, near = self._label_side(p, np.array([cx, cy]), groups)
            kw = dict(prefer=prefer, zorder=7, fontstyle="italic", within=70.0 if near else None, clear=True,
                      gid=f"{gid_prefix}-{self.polygon.kind}-" + ("origin+" if gi == 0 else "") + "+".join(g))
            if gi == 0 or every:
                t = self._off_lines(p, _label_names(self.polygon, self.names, g, gi == 0), kw)
            else:
                t = self.pl.place(p, _label_text(self.polygon, self.names, g, False), fontsize=self.st.font_size, **kw)
            self.art.add("labels", t)
            for k in g:
                self.art.labels[k] = t

    def _off_lines(self, p, names, kw):
        """A label (``names``: the point's and its coinciding points', the origin's first) where its box lies on
        no line and no other label: in one line at its size, else in two or three (:func:`wrapped`: a long
        list beside the origin stacked into a block that finds room between the vectors), else smaller
        (:data:`~velpoly.render.displacement.SMALLER`), one to three lines at each size; each form first as the
        placer's search puts it, then hugging its point (:meth:`_hug`: a wide box beside a point whose
        vectors all leave on one side). Where no form finds such a place (a polygon crushed flat: every place
        near the origin is on a vector's shaft), the form whose place meets the fewest labels, then lines (the
        larger and the fewer lines first among equals). A step frame tries the finished construction's form
        first."""
        from .displacement import SMALLER
        forms = [(f, n) for f in (1.0,) + SMALLER for n in range(1, most_lines(len(names)) + 1)]
        pinned = self.pl.pins.get(kw["gid"] + ":form")
        if pinned is not None and tuple(pinned[1]) in forms:
            forms.remove(tuple(pinned[1]))
            forms.insert(0, tuple(pinned[1]))
        best = None
        for f, n in forms:
            with self.pl.trial():
                before = len(self.pl.overlapping)
                t = self._form_text(p, names, f, n, kw)
                score = (len(self.pl.overlapping) - before, self.pl.soft_hits(self.pl.box_of(t, pad=0.0)))
                self.pl.keep = score == (0, 0)
            if self.pl.of(t) is not None:
                return t
            t = self._form_text(p, names, f, n, kw, hug=True)
            if t is not None:
                return t
            if best is None or score < best[0]:
                best = (score, f, n)
        return self._form_text(p, names, best[1], best[2], kw)

    def _form_text(self, p, names, f: float, n: int, kw, hug: bool = False):
        """The label placed at ``f`` of the type size in ``n`` lines (its form kept for the step frames); ``hug``:
        only beside its point, off every line (:meth:`_hug`), else None."""
        text, gid = wrapped(names, n), kw["gid"]
        size = self.st.font_size * f
        if hug:
            t = self._hug(p, text, size, kw)
        else:
            t = self.pl.place(p, text, fontsize=size, multialignment="left", **kw)
        if t is not None:
            self.pl.placed[gid + ":form"] = ("form", (f, n))
        return t

    def _hug(self, p, text, size: float, kw):
        """The label beside its point ``p``, touching the point's ring of 2.5, 5 or 9 pt anywhere along its
        outline (:func:`hugging`: the nearest and the preferred side first), at the first place free of every
        label, mark and line; None where none is."""
        pl, pp = self.pl, self.pp
        probe = self.ax.text(0, 0, text, fontsize=size, fontstyle="italic", multialignment="left")
        w, h = pl.text_size(probe, 1.0, pp)
        probe.remove()
        cands = hugging(w, h, [g * pp for g in (2.5, 5.0, 9.0)], kw["prefer"])
        return pl.place_at([p + c for c in cands], text, gid=kw["gid"], soft=True, anchor=p,
                           fontsize=size, fontstyle="italic", multialignment="left", zorder=kw["zorder"])

    def _label_side(self, p, centre, groups):
        """The preferred direction of an image's label (away from the polygon's centre, or from an image
        close to it), and whether an image is that close."""
        tol, pc = self.tol, self.pc
        away = p - centre
        prefer = math.degrees(math.atan2(away[1], away[0])) if np.hypot(*away) > tol else -135.0
        # an image close to another (a short relative velocity): its label on the side away from the
        # other, so that the two labels do not read as one ("e f" over two images a millimetre apart)
        near = [q for q in [np.zeros(2)] + [self.points[h[0]] for h in groups]
                if tol < float(np.hypot(*(q - p))) < 1.0 * pc]
        if near:
            q = min(near, key=lambda q: float(np.hypot(*(q - p))))
            d = (p - q) / float(np.hypot(*(p - q)))
            a = np.array([math.cos(math.radians(prefer)), math.sin(math.radians(prefer))])
            v = d + 0.35 * a if np.dot(d, a) > -0.9 else d
            prefer = math.degrees(math.atan2(v[1], v[0]))
        return prefer, bool(near)

    def reasons(self):
        """The construction lines' reasons, where there is room (after the labels, which matter more)."""
        if self.opts is not None and not self.opts.reasons:
            return
        for group in _collinear(self.art.get("construction", [])):
            # lines drawn along one line (the paths of two blocks on one guide): one text, along the longest
            line = max(group, key=lambda g: float(np.hypot(*np.diff(np.asarray(g.get_data(), float), axis=1).ravel())))
            xs, ys = line.get_data()
            reason = joined_reasons([g._velpoly_line.reason for g in group])
            # a vector moved off the line (drawn beside another on it) takes the reason's room there: the reason
            # then stands beyond it, where there is room
            offsets = (1.5, 2.5 + APART * self.st.head_length) if self._moved_along(xs, ys) else (1.5,)
            for offset in offsets:
                t = self.pl.place_along((xs[0], ys[0]), (xs[1], ys[1]), prose_tex(reason), pad=8.0, offset=offset,
                                        fontsize=self.st.small_size * 0.9, style="italic", zorder=6,
                                        gid=line.get_gid() + "-reason")
                if t is not None:
                    self.art.add("reasons", t)
                    break

    def _moved_along(self, xs, ys) -> bool:
        """Whether a vector drawn beside another lies (where it belongs) along the line through ``xs``, ``ys``."""
        moved = [(tail, head) for _, tail, head, hd in self.art.arrows if np.any(hd._velpoly_shift)]
        line = np.array([[xs[0], ys[0]], [xs[1], ys[1]]], float)
        return any(lying_along(tail, head, line[:1], line[1:], near=0.5 * APART * self.st.head_length * self.pp,
                               along=ALONG * self.pp)[0] for tail, head in moved)


# vectors on one line drawn apart: the offset, in the style's arrowhead lengths (1.5 mm on a textbook page: two
# arrowheads side by side clear of each other); and what lies on one line: nearer parallel than ONE_LINE degrees,
# within half the offset of each other's line over more than ALONG points; two vectors of one kind from one tail in
# one sense stay on their line (as books draw O-a' and O-b' on one ray) where their heads are HEADS_APART arrowhead
# lengths apart or more: the shorter one's arrowhead then stands clear on the longer one's shaft
APART = 0.7
ONE_LINE = 1.5
ALONG = 3.0
HEADS_APART = 2.0


def lying_along(p, q, tails, heads, near: float, along: float, degrees: float = ONE_LINE) -> np.ndarray:
    """Which of the segments ``tails[i]`` -> ``heads[i]`` the segment ``p`` -> ``q`` lies along: parallel to it within
    ``degrees`` (either sense) and within ``near`` of its line over a stretch of it longer than ``along``.

    >>> t, h = np.array([[0.0, 0.0], [0.0, 1.0]]), np.array([[10.0, 0.0], [10.0, 1.0]])
    >>> lying_along(np.array([8.0, 0.1]), np.array([2.0, 0.1]), t, h, near=0.5, along=1.0).tolist()
    [True, False]
    >>> lying_along(np.array([9.5, 0.0]), np.array([12.0, 0.0]), t, h, near=0.5, along=1.0).tolist()
    [False, False]
    """
    tails, heads = np.asarray(tails, float).reshape(-1, 2), np.asarray(heads, float).reshape(-1, 2)
    d = heads - tails
    size = np.hypot(d[:, 0], d[:, 1])
    u = d / np.maximum(size, 1e-300)[:, None]
    e = np.asarray(q, float) - np.asarray(p, float)
    sine = np.abs(u[:, 0] * e[1] - u[:, 1] * e[0]) / max(float(np.hypot(*e)), 1e-300)
    rp, rq = np.asarray(p, float) - tails, np.asarray(q, float) - tails
    dp, dq = u[:, 0] * rp[:, 1] - u[:, 1] * rp[:, 0], u[:, 0] * rq[:, 1] - u[:, 1] * rq[:, 0]   # distances from the line
    tp, tq = np.sum(u * rp, axis=1), np.sum(u * rq, axis=1)                                   # places along it
    slope = dq - dp
    flat = np.abs(slope) <= 1e-12 * max(near, 1e-300)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        l1, l2 = (-near - dp) / slope, (near - dp) / slope
    lo = np.where(flat, np.where(np.abs(dp) <= near, 0.0, 1.0), np.clip(np.minimum(l1, l2), 0.0, 1.0))
    hi = np.where(flat, np.where(np.abs(dp) <= near, 1.0, 0.0), np.clip(np.maximum(l1, l2), 0.0, 1.0))
    a, b = tp + lo * (tq - tp), tp + hi * (tq - tp)
    overlap = np.minimum(np.maximum(a, b), size) - np.maximum(np.minimum(a, b), 0.0)
    return (sine <= math.sin(math.radians(degrees))) & (hi > lo) & (overlap > along)


class Beside:
    """The vectors of a polygon drawn so far, each where it is drawn; :meth:`add` puts the next one beside those it
    would lie along (:func:`lying_along` over more than ``along``), ``apart`` (data units) to one side, or twice
    that, ... ."""

    def __init__(self, apart: float, along: float):
        self.apart, self.along = apart, along
        self.tails: list = []
        self.heads: list = []
        self.kinds: list = []

    def add(self, tail, head, centre, kind=None) -> np.ndarray:
        """The shift of the vector ``tail`` -> ``head`` (of line style ``kind``): none where it lies along no vector
        drawn, or only along vectors of its kind from its tail in its sense whose heads stand HEADS_APART arrowhead
        lengths from its own (both arrowheads seen on one line, as books draw two images on one ray from O); else
        the nearest offset, at right angles to it, whose copy lies along none (of the two sides, the one whose copy
        crosses fewer vectors, then the one away from ``centre``, the polygon's middle). It is drawn there."""
        along = self._along(tail, head)
        if np.any(along) and kind is not None:
            along &= ~self._nested(tail, head, kind)
        shift = self._beside(tail, head, centre) if np.any(along) else np.zeros(2)
        self.tails.append(tail + shift)
        self.heads.append(head + shift)
        self.kinds.append(kind)
        return shift

    def _nested(self, tail, head, kind) -> np.ndarray:
        """Which vectors drawn are of ``kind``, start where ``tail`` -> ``head`` starts, point its way and end
        HEADS_APART arrowhead lengths (``apart / APART`` each) or more from its head."""
        tails, heads = np.asarray(self.tails, float), np.asarray(self.heads, float)
        same = np.array([k == kind for k in self.kinds], bool)
        near = np.hypot(*(tails - tail).T) <= 0.5 * self.apart
        sense = (heads - tails) @ (head - tail) > 0
        clear = np.hypot(*(heads - head).T) >= HEADS_APART * self.apart / APART
        return same & near & sense & clear

    def _beside(self, tail, head, centre) -> np.ndarray:
        """:meth:`add`'s shift of a vector that lies along one drawn (else the one whose copy lies along fewest)."""
        d = head - tail
        n = np.array([-d[1], d[0]]) / float(np.hypot(*d))
        side = 1.0 if float(np.dot(n, 0.5 * (tail + head) - centre)) >= 0 else -1.0
        best = None
        for k in range(0, 5):
            shifts = [np.zeros(2)] if k == 0 else [side * k * self.apart * n, -side * k * self.apart * n]
            for s in shifts:
                hits = int(np.sum(self._along(tail + s, head + s)))
                score = (hits, self._crossings(tail + s, head + s))
                if best is None or score < best[0]:
                    best = (score, s)
            if best[0][0] == 0:
                break
        return best[1]

    def _along(self, p, q) -> np.ndarray:
        if not self.tails:
            return np.zeros(0, bool)
        return lying_along(p, q, self.tails, self.heads, near=0.5 * self.apart, along=self.along)

    def _crossings(self, p, q) -> int:
        """How many vectors drawn the segment ``p`` -> ``q`` crosses."""
        if not self.tails:
            return 0
        return int(np.sum(shapely.intersects(shapely.linestrings(np.stack([self.tails, self.heads], axis=1)),
                                             segment(p, q))))


def hugging(w: float, h: float, gaps, prefer: float, k: int = 6) -> list:
    """The centres (about a point at 0) of a ``w`` x ``h`` box whose outline passes ``gap`` from the point, for
    each of ``gaps``: the point beside each corner (diagonally) and beside ``k`` places along each side, the
    nearer gaps first, and in each the places whose direction is nearest ``prefer`` (degrees) first.

    >>> [tuple(round(float(v), 2) + 0.0 for v in c) for c in hugging(4.0, 2.0, [1.0], 0.0, k=1)][:3]
    [(3.0, 0.0), (2.71, 1.71), (2.71, -1.71)]
    """
    out = []
    for g in gaps:
        d = g / math.sqrt(2.0)
        rows = [(sx * (w / 2 + d), sy * (h / 2 + d)) for sx in (1, -1) for sy in (1, -1)]
        for f in np.linspace(-0.5, 0.5, k + 2)[1:-1] if k > 1 else [0.0]:
            rows += [(w / 2 + g, -f * h), (-(w / 2 + g), -f * h), (-f * w, h / 2 + g), (-f * w, -(h / 2 + g))]
        a = math.radians(prefer)
        rows.sort(key=lambda c: -math.cos(math.atan2(c[1], c[0]) - a))
        out += [np.array(c, float) for c in rows]
    return out


def _collinear(lines) -> list[list]:
    """The construction lines (Line2D, two points each) in groups that lie along one line, in drawing order."""
    groups: list[list] = []
    for line in lines:
        (x0, x1), (y0, y1) = (np.asarray(v, float) for v in line.get_data())
        p, d = np.array([x0, y0]), np.array([x1 - x0, y1 - y0])
        for g in groups:
            (a0, a1), (b0, b1) = (np.asarray(v, float) for v in g[0].get_data())
            q, e = np.array([a0, b0]), np.array([a1 - a0, b1 - b0])
            size = max(float(np.hypot(*d)), float(np.hypot(*e)), 1e-300)
            r = p - q
            if abs(d[0] * e[1] - d[1] * e[0]) <= 1e-9 * size ** 2 and abs(e[0] * r[1] - e[1] * r[0]) <= 1e-9 * size ** 2:
                g.append(line)
                break
        else:
            groups.append([line])
    return groups


def joined_reasons(reasons: list[str]) -> str:
    """The reasons of lines along one line as one text: the same once; two that differ in one word, that word
    joined ("parallel to the path of E and F on 1", "perpendicular to DE and GF"); else one after the other.

    >>> joined_reasons(["parallel to the path of E on 1", "parallel to the path of F on 1"])
    'parallel to the path of E and F on 1'
    >>> joined_reasons(["perpendicular to AB", "perpendicular to AB"])
    'perpendicular to AB'
    """
    unique = list(dict.fromkeys(reasons))
    words = [r.split(" ") for r in unique]
    if len(unique) > 1 and len({len(w) for w in words}) == 1:
        differ = [i for i in range(len(words[0])) if len({w[i] for w in words}) > 1]
        if len(differ) == 1:
            i = differ[0]
            names = [w[i] for w in words]
            joined = ", ".join(names[:-1]) + " and " + names[-1]
            return " ".join(words[0][:i] + [joined] + words[0][i + 1:])
    return "; ".join(unique)


def draw_polygon(polygon, ax=None, *, mechanism=None, style="textbook", options=None, scale: float | None = None,
                 upto: int | None = None) -> Artists:
    """Draw a velocity or acceleration :class:`~velpoly.polygons.Polygon`; return its Artists.

    Parameters
    ----------
    polygon : Polygon
        From :func:`velpoly.polygons.velocity_polygon` or ``acceleration_polygon``.
    ax : matplotlib Axes, optional
        pyplot's current axes if None; an axes with a velpoly view keeps its scale, unless the
        polygon's detail finds no room at it (then a round step or more coarser, see
        :func:`velpoly.render.detail.make_room`; ``view_scale(ax)`` tells) and no scale was given.
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
        ``shafts``, ``origin``, ``labels``, ``legend``, ``scale_bar``, ``detail`` (the detail's frame, its
        mark on the polygon and its leader);
        ``.labels`` maps every image's key (and every auxiliary point's) to its label, ``.arrows`` lists
        ``(kind, tail, head, patch)`` for every vector drawn; ``.detail`` is the enlarged detail of a
        crushed polygon (:class:`velpoly.render.detail.Detail`) or None.
    """
    ax = get_ax(ax)
    st = get_style(style)
    m = mechanism
    opts = options if options is not None else (drawing_options(m) if m is not None else None)
    user = None if opts is None else (opts.velocity_scale if polygon.kind == "velocity" else
                                      opts.acceleration_scale)
    if view_scale(ax) is None:
        fit_view(ax, polygon_bounds(polygon), scale=scale if scale is not None else user, margin=0.08)
        ax.set_axis_off()
    from .detail import make_room     # a detail with no room: the scale a round step coarser

    def draw():
        return _draw(polygon, ax, st, opts, m, upto)
    make_room(polygon, ax, draw, fixed=scale is not None or user is not None)
    return draw()


def _draw(polygon, ax, st, opts, m, upto) -> Artists:
    """The polygon on ``ax`` at its view (:func:`draw_polygon`)."""
    from .detail import draw_detail
    d = _PolygonDrawing(polygon, ax, st, opts, m, upto)
    d.shade_images()
    d.construction_lines()
    kinds = d.vectors()
    d.origin()
    detail = draw_detail(d)     # before the legend and the labels, which keep clear of it
    d.legend(kinds)
    d.labels(within=None if detail is None else detail.outside)
    d.reasons()
    art = d.art
    art.detail = detail
    if detail is not None:
        art.add("detail", *detail.marks)
        art.labels.update(detail.art.labels)
    art.add("scale_bar", *scale_bar(ax, st, m.units if m is not None else "", 1 if d.velocity else 2))
    return art


_LOCS = ("upper right", "upper left", "lower right", "lower left", "center right", "center left", "upper center",
         "lower center")


def spots(bounds, w: float, h: float, pad: float) -> tuple[list, list]:
    """Where a box ``w`` x ``h`` may go within ``bounds`` (its lower left corners), ``pad`` from the border:
    the corners and sides (upper right first), and a 9 x 9 grid over the panel, nearest the border first."""
    vx0, vy0, vx1, vy1 = bounds
    named = []
    for loc in _LOCS:
        v, u = loc.split()
        named.append(({"left": vx0 + pad, "right": vx1 - pad - w, "center": (vx0 + vx1 - w) / 2}[u],
                      {"lower": vy0 + pad, "upper": vy1 - pad - h, "center": (vy0 + vy1 - h) / 2}[v]))
    lo_x, hi_x, lo_y, hi_y = vx0 + pad, vx1 - pad - w, vy0 + pad, vy1 - pad - h
    grid = [(lo_x + (hi_x - lo_x) * i / 8, lo_y + (hi_y - lo_y) * j / 8) for i in range(9) for j in range(9)]
    grid.sort(key=lambda c: (round(min(c[0] - lo_x, hi_x - c[0], c[1] - lo_y, hi_y - c[1]) / max(pad, 1e-300)),
                             -c[1], c[0]))
    return named, grid


def hit_counter(pl):
    """A function counting what a box meets of the placer's labels and marks (10 each) and lines (1 each)."""
    geoms = np.array(pl.boxes + pl.hard + pl.soft, dtype=object)
    weights = np.array([10] * (len(pl.boxes) + len(pl.hard)) + [1] * len(pl.soft))

    def hits_of(b):
        return int(np.dot(shapely.intersects(geoms, b), weights)) if len(geoms) else 0
    return hits_of


NARROW = 0   # the columns of the legend's narrow variant: one column, each entry in two lines
# the legend's variants, in the order tried: (type size, of the style's small size; columns)
LEGEND_VARIANTS = ((1.0, 1), (0.85, 1), (1.0, 2), (0.85, 2), (1.0, NARROW), (0.85, NARROW))


def _legend_sizes(ax, pl, make, st) -> list:
    """(size, columns, width, height in data units) of the legend's variants (:data:`LEGEND_VARIANTS`): the full
    legend, smaller, in two columns, both; then narrow (:data:`NARROW`: each entry in two lines, a tall legend
    beside a polygon in a wide, low panel, as a slide's is: Example 3.3's five kinds), at both sizes."""
    return list(_Variants(ax, pl, make, st))


class _Variants:
    """:func:`_legend_sizes`, each variant measured when it is first asked for (iterating measures them in
    order, as far as the caller reads): a legend is measured by making it (``make``, a Legend of the axes,
    which replaces the one made before), and the first variant often has a free corner, where
    :func:`_legend_spot` reads no other. A variant's size is that of its legend alone, whichever were made
    before it, so the sizes read are :func:`_legend_sizes`'s (tests/test_drawspeed.py)."""

    def __init__(self, ax, pl, make, st):
        self.inv = ax.transData.inverted()   # (as _legend_sizes takes it: before any variant is made)
        self.pl, self.make, self.st = pl, make, st
        self.sizes: list = []

    def __iter__(self):
        for i in range(len(LEGEND_VARIANTS)):
            yield self[i]

    def __getitem__(self, i: int) -> tuple:
        while len(self.sizes) <= i:
            f, ncol = LEGEND_VARIANTS[len(self.sizes)]
            size = self.st.small_size * f
            bb = self.make(size, ncol).get_window_extent(self.pl.renderer)
            (x0, y0), (x1, y1) = self.inv.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
            self.sizes.append((size, ncol, abs(x1 - x0), abs(y1 - y0)))
        return self.sizes[i]


def _legend_spot(ax, sizes, hits_of):
    """(hits, (size, columns), box) of the legend: the first free corner or side of any variant, else the
    first free place of a grid over the panel, nearest its border first (a polygon filling every corner
    leaves room elsewhere), else the place crossing the fewest marks, then lines."""
    view = view_box(ax)
    inside = view.buffer(1e-9 * (view.bounds[2] - view.bounds[0]))
    pp = per_point(ax)
    best = None
    for stage in (0, 1):
        for size, ncol, w, h in sizes:
            for lx, ly in spots(view.bounds, w, h, 0.3 * size * pp)[stage]:
                b = box(lx, ly, lx + w, ly + h)
                if not inside.contains(b):   # a legend wider than the panel
                    continue
                hits = hits_of(b)
                if best is None or hits < best[0]:
                    best = (hits, (size, ncol), b)
                if hits == 0:
                    return best
    if best is None:   # wider than the panel in every variant: the smallest, at the upper right
        size, ncol, w, h = min(sizes, key=lambda v: v[2])
        vx0, vy0, vx1, vy1 = view.bounds
        b = box(vx1 - w, vy1 - h, vx1, vy1)
        best = (hits_of(b) + 1, (size, ncol), b)
    return best


def _legend(ax, st, kinds) -> list:
    """The line styles of the vector kinds, in a free place of the panel (see :func:`_legend_spot`)."""
    from matplotlib.lines import Line2D
    handles = []
    for k in kinds:
        ls, colour, f = st.kind_styles[k]
        handles.append(Line2D([], [], lw=st.arrow_lw * f, linestyle=ls, color=st.ink if colour is None else colour))
    pl = placer(ax)

    def make(size, ncol, at=(1.0, 1.0), loc="upper right", transform=None):
        texts = [wrap_caption(KIND_LABELS[k]) if ncol == NARROW else KIND_LABELS[k] for k in kinds]
        return ax.legend(handles, texts, loc=loc, fontsize=size, ncol=max(ncol, 1),
                         handlelength={1: 3.2, 2: 2.4, NARROW: 2.0}[ncol], borderaxespad=0.0, columnspacing=1.0,
                         bbox_to_anchor=at, bbox_transform=transform)

    sizes = _Variants(ax, pl, make, st)   # each variant measured once, where it is read
    hits_of = hit_counter(pl)
    pin = pl.pins.get("legend")
    if pin is not None:       # a step frame: where the finished construction has it
        size, ncol, (lx, ly) = pin[1], pin[2], pin[3]
        w, h = next((w, h) for s_, n_, w, h in sizes if (s_, n_) == (size, ncol))
        b = box(lx, ly, lx + w, ly + h)
        best = (hits_of(b), (size, ncol), b)
    else:
        best = _legend_spot(ax, sizes, hits_of)
    hits, (size, ncol), b = best
    # the variants' sizes in cm, where the legend finds no free place (the sheet then keeps a strip for one of
    # them: velpoly.render.sheet); measured before the legend drawn is made (a variant made replaces it)
    paper = [(w / per_cm(ax), h / per_cm(ax)) for _, _, w, h in sizes] if hits else None
    leg = make(size, ncol, at=(b.bounds[0], b.bounds[1]), loc="lower left", transform=ax.transData)
    leg._velpoly_hits = hits
    leg._velpoly_paper = paper
    pl.placed["legend"] = ("legend", size, ncol, (float(b.bounds[0]), float(b.bounds[1])), tuple(kinds))
    pl.add_box(leg, b)
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
