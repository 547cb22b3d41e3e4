"""Outside check, audit 7: the animation's acceleration panel, frame by frame over a generated cycle.

- The legend of the vector kinds (still, in the panel's upper right corner) lay over the polygon in the
  frames where the polygon reached that corner: the arrows, their heads, the link images' shading and the
  image labels drawn under the legend's text (on 7c7c973, 180 of the frames of 40 specimens at 30 deg a
  frame). Now the polygon is fitted below the legend's band in every frame.
- Labels of coincident or crowded images (a pin's A@2 and A@3, a block's A@4 beside them) were placed on top
  of one another where none of the twelve directions beside the image was clear: now the twelve a label's size
  farther out are tried too.
The artists are read back where each frame puts them (display pixels), not the pixels.
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from shapely.geometry import LineString, Point, box

from velpoly.render.animate import Animator, plan_frames

from zoo import each

SIZE = (640, 360)


@pytest.fixture(scope="module")
def cycles():
    """Two generated specimens whose cycles put the polygon under the legend and images side by side: a six-bar
    with a floating guide that lists its slider's point (A@2, A@3, A@4) and a quick-return six-bar."""
    specimens = list(each(2026, 38))
    out = []
    for i, step in ((34, 30.0), (37, 40.0)):
        sp = specimens[i]
        out.append((sp.kind, Animator(plan_frames(sp.drawn.mechanism, step), "acceleration", "textbook", SIZE)))
    return out


def drawn_in_frame(anim, k: int):
    """Frame k's polygon artists in the acceleration panel, as drawn: (name, points in pixels) of each visible
    arrow shaft, head and link image, and each image label's box (x0, y0, x1, y1)."""
    anim.update(k)   # the artists where render draws them, not drawn (the frames 0.57 -> 0.30 CPU s)
    art = anim._poly_art["acceleration"]
    ax = art["ax"]
    shapes = []
    for key, (shaft, head) in art["arrows"].items():
        if shaft.get_visible():
            shapes.append((f"arrow {key}", ax.transData.transform(np.column_stack(shaft.get_data()))))
            shapes.append((f"head {key}", ax.transData.transform(np.asarray(head.get_xy()))))
    for lk, patch in art["shades"].items():
        if patch.get_visible():
            shapes.append((f"image of {lk}", ax.transData.transform(np.asarray(patch.get_xy()))))
    labels = {key: anim._box_px(ax, t) for key, t in art["labels"].items()}
    return shapes, labels


def test_the_legend_keeps_clear_of_the_polygon_and_labels_of_each_other_in_every_frame(cycles):
    frames = 0
    for kind, anim in cycles:
        ax = anim._poly_art["acceleration"]["ax"]
        legend = ax.get_legend()
        assert legend is not None and len(legend.get_texts()) >= 3, kind
        for k in range(anim.n):
            shapes, labels = drawn_in_frame(anim, k)
            bb = legend.get_window_extent(anim.fig.canvas.get_renderer())
            keep = box(bb.x0, bb.y0, bb.x1, bb.y1)
            for name, pts in shapes:
                g = LineString(pts) if len(pts) > 1 else Point(pts[0])
                assert not g.intersects(keep), (kind, k, name)
            for key, b in labels.items():
                assert not box(*b).intersects(keep), (kind, k, key)
            for (p, a), (q, b) in itertools.combinations(labels.items(), 2):
                assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1], (kind, k, p, q)
            frames += 1
    assert frames >= 20
    # the cycle has images that coincide (a pin's two keys) and the legend's corner is reached: what is checked
    kind, anim = cycles[0]
    assert {"A@2", "A@3"} <= set(anim._poly_art["acceleration"]["labels"]), kind
