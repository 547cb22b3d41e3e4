"""A placer's trial put aside and come back to is the drawing as the trial left it (render/labels.py:
``LabelPlacer.trial(aside)`` keeps the trial's end as a ``Moment``, ``LabelPlacer.back_to`` restores it).

The space diagram keeps what a pass drew aside and puts it back rather than drawing it again (a driver's plan as
drawn to score it, the first pass of the marks where the later passes are no better: render/displacement.py). On
generated mechanisms, a space diagram drawn in a trial (over another: a four-bar's over its own) and put back
equals, artist by artist (each text, line, patch and collection's data, in the axes' order) and in the placer's
state (labels, boxes, leaders, obstacles, where each label went), the drawing as the trial left it, and so does
the SVG written.
"""
from __future__ import annotations

import io

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import Collection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.text import Text

import zoo
from velpoly.render.displacement import draw_mechanism
from velpoly.render.labels import placer
from velpoly.render.style import get_style, rc_context


def _artist(a) -> tuple:
    """What an artist draws: its kind, gid, zorder and data."""
    head = (type(a).__name__, a.get_gid(), a.get_zorder(), a.get_visible())
    if isinstance(a, Text):
        return head + (a.get_text(), tuple(map(float, a.get_position())), a.get_fontsize(), a.get_rotation(),
                       a.get_bbox_patch() is not None)
    if isinstance(a, Line2D):
        return head + (np.asarray(a.get_xydata(), float).tobytes(),)
    if isinstance(a, Patch):
        path = a.get_path()
        return head + (np.asarray(path.vertices).tobytes(), a.get_facecolor(), a.get_linewidth())
    if isinstance(a, Collection):
        return head + tuple(np.asarray(p.vertices).tobytes() for p in a.get_paths())
    return head


def _state(ax) -> tuple:
    """The axes' artists in their order and the placer's state."""
    pl = placer(ax)
    wkb = lambda gs: tuple(None if g is None else g.wkb for g in gs)   # noqa: E731
    return (tuple(_artist(a) for a in ax.get_children() if isinstance(a, (Text, Line2D, Patch, Collection))),
            tuple(_artist(p.text) for p in pl.labels), wkb(pl.boxes), wkb(p.leader_geom for p in pl.labels),
            wkb(pl.hard), wkb(pl.soft), len(pl.overlapping), tuple(pl.placed.items()))


def _svg(ax) -> bytes:
    buf = io.BytesIO()
    ax.figure.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue()


def test_a_trial_come_back_to_is_the_trial_drawing():
    sols = [zoo.zoo(2026, 1)[0].drawn,   # a four-bar, drawn twice over; a quick-return crank (its plate beneath
            zoo.specimen(np.random.default_rng(3), "six-bar", "quick-return crank").drawn]   # its crank)
    for k, sol in enumerate(sols):
        style = get_style("slides" if k else "textbook")
        ax = Figure(figsize=(4, 3), dpi=72).add_axes((0.02, 0.02, 0.96, 0.96))
        FigureCanvasAgg(ax.figure)
        with rc_context(style):
            if not k:   # (put back over a drawing, as a pass of the marks is)
                draw_mechanism(sol, ax, style=style)
            before, aside = _state(ax), []
            with placer(ax).trial(aside):   # a drawing thrown away
                draw_mechanism(sol, ax, style=style)
                drawn, svg = _state(ax), _svg(ax)
            assert _state(ax) == before != drawn, k
            placer(ax).back_to(aside[0])
            assert _state(ax) == drawn, k
            assert _svg(ax) == svg, k
