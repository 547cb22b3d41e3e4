"""The labels of a polygon's detail stay inside its frame and off its lines (issue 17, items 3 and 4).

A detail (render/detail.py) enlarges the crowd about the origin; its labels are those of the images in the marked
region and the origin's, which lists every point at rest ("O_a, o′₂, o′₄, o′₆, o′₈" in an eight-bar). Read back
from the drawn artists on the canvas (:func:`label_clashes`): every label of the detail, its outline shrunk by a
pixel, lies inside the inset and off the frame's rule as drawn, on no vector (shaft or head) and no construction
line of the detail (as drawn, clipped to the inset), and on no other text of the panel or the detail.

Checked on generated mechanisms (seeded): six- and eight-bars and a slotted six-bar with a point far out on one
link (its image far longer than the rest, tests/test_detail.py's ``_far_point``), drawn alone in panels of several
shapes in both styles. On 62b1aef each of the three failed (the eight-bars' origin labels in one line across two
to five lines, the slotted six-bar's image label on a vector's shaft). The brief's examples, ``zoo(2026, 60)``'s
eight-bar (55: its acceleration detail's origin label across nine lines on its slide) and six-bar (32), are
measured with the others by benchmarks/detail_labels.py (too dear for the suite: the zoo alone is 0.8 CPU s).
"""
from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Polygon as MPolygon
from shapely.geometry import LineString, Polygon, box

import velpoly
import zoo
from test_text_apart import outline
from velpoly.polygons import acceleration_polygon, velocity_polygon
from velpoly.render.canvas import fit_view
from velpoly.render.labels import placer
from velpoly.render.polygon import draw_polygon, polygon_bounds
from velpoly.render.style import get_style, rc_context

LABELS = ("label-", "detail-label-")


def drawn_lines(ax, clip) -> list:
    """(gid, geometry on the canvas) of the vectors' shafts and heads and the construction lines of ``ax``, as
    drawn within ``clip`` (leaders, the detail's marks and the scale bar left out)."""
    out = []
    for ln in ax.lines:
        gid = ln.get_gid() or ""
        if not ln.get_visible() or gid.endswith("-leader") or gid.startswith(("detail-", "scale-bar")):
            continue
        xy = ln.get_transform().transform(ln.get_xydata())
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        if len(xy) >= 2:
            g = LineString(xy).intersection(clip)
            if not g.is_empty:
                out.append((gid, g))
    for p in ax.patches:
        gid = p.get_gid() or ""
        if isinstance(p, MPolygon) and len(p.get_xy()) <= 5 and not gid.startswith(("image", "detail", "origin")):
            g = Polygon(p.get_transform().transform(p.get_xy())).buffer(0).intersection(clip)
            if not g.is_empty:
                out.append((gid, g))
    return out


def label_clashes(ax) -> dict:
    """What the labels of the polygon panel ``ax`` and of its detail meet, on the canvas: ``line`` (label, the
    vector or construction line of its own axes it lies on, its own leader excepted), ``cut`` (label, the edge of
    its axes or the detail's frame: a panel's label on or in the frame, a detail's on the frame's rule as drawn),
    ``text`` (label, another text of the panel or the detail it meets); and the labels counted."""
    fig = ax.figure
    r = fig.canvas.get_renderer()
    frame = next((p for p in ax.patches if p.get_gid() == "detail-frame"), None)
    frame_box = None if frame is None else box(*frame.get_window_extent(r).extents)
    # the frame's rule as drawn, and a pixel more (the outlines are a pixel in): a glyph touching it reads as cut
    stroke = None if frame is None else frame_box.exterior.buffer(frame.get_linewidth() / 2 * fig.dpi / 72 + 2.0)
    out = {"line": [], "cut": [], "text": [], "labels": 0, "detail_labels": 0}
    texts = []
    for a in [ax] + list(ax.child_axes):
        edge = box(*a.get_window_extent(r).extents)
        lines = drawn_lines(a, edge)
        pl = placer(a)
        for t in a.texts:
            if not t.get_visible() or not t.get_text().strip():
                continue
            o = outline(t, r)
            texts.append((t, o))
            gid = t.get_gid() or ""
            if not gid.startswith(LABELS):
                continue
            out["detail_labels" if a is not ax else "labels"] += 1
            own = pl.of(t)
            leader = own.leader.get_gid() if own is not None and own.leader is not None else None
            out["line"] += [(gid, g) for g, ln in lines if g != leader and ln.intersects(o)]
            if not edge.contains(o):
                out["cut"].append((gid, "edge"))
            elif frame_box is not None and (stroke.intersects(o) if a is not ax else frame_box.intersects(o)):
                out["cut"].append((gid, "detail-frame"))
    for i, (t, o) in enumerate(texts):
        if (t.get_gid() or "").startswith(LABELS):
            out["text"] += [(t.get_gid(), u.get_gid() or u.get_text()) for j, (u, p) in enumerate(texts)
                            if j != i and o.intersects(p) and not (j < i and (u.get_gid() or "").startswith(LABELS))]
    return out


def _panel(style, rect):
    st = get_style(style)
    fig = Figure(figsize=st.figsize, dpi=72)
    FigureCanvasAgg(fig)
    return fig.add_axes(rect)


def _drawn(sol, poly, style, rect, scale=None):
    """``poly`` drawn alone in a panel at ``rect`` of the style's page (at ``scale``, else fitted), laid out."""
    ax = _panel(style, rect)
    fit_view(ax, polygon_bounds(poly), scale=scale, margin=0.08)
    ax.set_axis_off()
    with rc_context(get_style(style)):
        art = draw_polygon(poly, ax, mechanism=sol.mechanism, style=style)
        ax.figure.draw_without_rendering()
    return ax, art


def _detail_clashes(ax) -> list:
    got = label_clashes(ax)
    return [c for k in ("line", "cut", "text") for c in got[k] if c[0].startswith("detail-label-")]


# seed 1777's six- and eight-bars and slotted six-bar in turn, one link given a point 8 to 30 sizes out; the
# polygon and style drawn of each (None: that specimen is drawn from the generator only, for the next); on 62b1aef
# the eight-bars' velocity details had the origin's label across two to five lines, the slotted six-bar's an
# image's label on a vector's shaft. (Of the 24 details of those six specimens' two polygons in both styles, 11
# had a label on a line on 62b1aef, 2 now: benchmarks/detail_labels.py --far.)
GENERATED = ((("eight-bar", "stephenson III + dyad"), ("velocity", "textbook")), (("six-bar", None), None),
             (("eight-bar", "watt II + dyad"), ("velocity", "slides")), (("slot", "straight six-bar"), ("velocity", "slides")))


def test_generated_details_labels_inside_and_off_the_lines():
    """Seeded generated mechanisms (:data:`GENERATED`) drawn in panels of several shapes: the detail's origin
    label lists every point at rest, and every label of the detail lies inside its frame, off its rule, on no
    vector or construction line and on no other text."""
    from test_detail import PANELS, _far_point
    rng = np.random.default_rng(1777)
    drawn = 0
    for n, ((kind, variant), what) in enumerate(GENERATED):
        sp = zoo.specimen(rng, kind, variant)
        mech = _far_point(sp.mech, rng, far=(8.0, 15.0, 30.0))
        if what is None:
            continue
        sol = velpoly.solve(velpoly.load(mech))
        poly = velocity_polygon(sol) if what[0] == "velocity" else acceleration_polygon(sol)
        ax, art = _drawn(sol, poly, what[1], PANELS[n % len(PANELS)])
        assert art.detail is not None, (n, sp.kind)
        assert not _detail_clashes(ax), (n, sp.kind, what, _detail_clashes(ax))
        origin = [t for t in art.detail.art["labels"] if "origin+" in (t.get_gid() or "")]
        size = max(float(np.hypot(*v)) for v in poly.images.values())
        at_rest = {k for k, v in poly.images.items() if float(np.hypot(*v)) <= 1e-9 * size}
        assert len(origin) == 1 and at_rest <= set(origin[0].get_gid().split("origin+")[1].split("+")), (n, sp.kind)
        drawn += 1
    assert drawn == 3


def test_wrapped_lists_keep_every_name_in_order():
    """A list of names set in one to three lines keeps every name once, in order, the lines as even as they go."""
    from velpoly.render.polygon import wrapped
    names = [f"n{i}" for i in range(7)]
    for lines in (1, 2, 3):
        got = wrapped(names, lines)
        assert got.replace(",\n", ", ").split(", ") == names
        rows = [row.rstrip(",").split(", ") for row in got.split("\n")]
        assert len(rows) == lines and max(map(len, rows)) - min(map(len, rows)) <= 1
