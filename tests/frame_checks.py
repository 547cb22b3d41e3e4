"""Data-level checks of a polygon panel's detail frame (issue 17, item 3): what the frame covers of the
panel's own drawing, read back from the artists (lines and patches in data coordinates, texts by their
boxes on the canvas), and whether it stays in its panel and on its page."""
from __future__ import annotations

import numpy as np
from shapely.geometry import LineString, Polygon, box

from velpoly.render.canvas import per_cm, renderer_of, view_box


def _to_data(ax, xy):
    return ax.transData.inverted().transform(np.asarray(xy, float))


def _shape(ax, a, renderer):
    """An artist of the panel as a shapely geometry in its data coordinates (None: nothing drawn)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    from matplotlib.text import Text
    if not a.get_visible():
        return None
    if isinstance(a, Line2D):
        xy = np.column_stack(a.get_data())
        return LineString(xy) if len(xy) >= 2 else None
    if isinstance(a, Patch):
        xy = _to_data(ax, a.get_verts())
        return Polygon(xy).buffer(0) if len(xy) >= 3 else None
    if isinstance(a, Text) and not a.get_text():
        return None
    bb = a.get_window_extent(renderer)
    (x0, y0), (x1, y1) = _to_data(ax, [[bb.x0, bb.y0], [bb.x1, bb.y1]])
    return box(min(x0, x1), min(y0, y1), max(x0, x1), max(y0, y1))


def frame_clashes(ax) -> list[str]:
    """What the detail's frame on a polygon's panel ``ax`` covers of the panel's own drawing (every line,
    patch, text and legend of the panel but the detail's own marks: link images, construction lines, vectors,
    the origin, labels, reasons, legend, scale bar), the marked region among them, and whether it leaves its
    panel or the page: one line each (empty: none)."""
    from matplotlib.legend import Legend
    frame_patch = next(p for p in ax.patches if p.get_gid() == "detail-frame")
    region_patch = next(p for p in ax.patches if p.get_gid() == "detail-region")
    x0, y0, w, h = frame_patch.get_bbox().bounds
    frame = box(x0, y0, x0 + w, y0 + h)
    x0, y0, w, h = region_patch.get_bbox().bounds
    region = box(x0, y0, x0 + w, y0 + h)
    pc = per_cm(ax)
    inner = frame.buffer(-1e-6 * pc)
    out = []
    if not view_box(ax).buffer(1e-6 * pc).contains(frame):
        out.append("the frame leaves its panel")
    x0, y0, w, h = ax.get_position().bounds
    if x0 < 0 or y0 < 0 or x0 + w > 1 + 1e-9 or y0 + h > 1 + 1e-9:
        out.append("the panel leaves the page")
    if inner.intersects(region):
        out.append("the frame covers the region it enlarges")
    r = renderer_of(ax.figure)
    for a in list(ax.lines) + list(ax.patches) + list(ax.texts) + [c for c in ax.get_children() if isinstance(c, Legend)]:
        if (a.get_gid() or "").startswith("detail-"):
            continue
        g = _shape(ax, a, r)
        if g is not None and inner.intersects(g):
            out.append(a.get_gid() or type(a).__name__)
    return out
