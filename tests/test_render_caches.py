"""What velpoly/render keeps to draw with less CPU (issue 19 item 7) gives what computing it again gives, and is
never stale.

* canvas.per_point keeps its value on the axes with everything applying the aspect reads: on generated
  mechanisms' drawings it is the value computed afresh, and after any of those inputs changes (limits, figure
  size and dpi, position, aspect, anchor) it is computed again; where applying the aspect may move the
  limits nothing is kept.
"""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import zoo
from mechanisms import shapes_only
from velpoly.render.canvas import _aspect_key, axes_cm, per_point
from velpoly.render.displacement import draw_mechanism
from velpoly.render.style import get_style, rc_context


def _afresh(ax) -> float:
    """per_point's value computed without what it keeps (axes_cm applies the aspect itself)."""
    x0, x1 = ax.get_xlim()
    wcm, _ = axes_cm(ax)
    return abs(x1 - x0) / wcm * (2.54 / 72.0)


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_per_point_kept_is_per_point_computed_and_never_stale(style):
    """Generated mechanisms' drawings, every kind in textbook, the six-bar in slides (the kept value and the
    value afresh read the same axes whatever the style: the other three kinds in slides were cut by issue 19
    item 7)."""
    st = get_style(style)
    rng = np.random.default_rng(19 if style == "textbook" else 7)
    changes = [
        ("xlim", lambda fig, ax: ax.set_xlim(ax.get_xlim()[0], ax.get_xlim()[1] * 1.5 + 1.0)),
        ("ylim", lambda fig, ax: ax.set_ylim(ax.get_ylim()[0] - 3.0, ax.get_ylim()[1])),
        ("size", lambda fig, ax: fig.set_size_inches(9.0, 4.0)),
        ("dpi", lambda fig, ax: fig.set_dpi(100)),
        ("position", lambda fig, ax: ax.set_position((0.1, 0.2, 0.3, 0.7))),
        ("anchor", lambda fig, ax: ax.set_anchor("SW")),
        ("aspect", lambda fig, ax: ax.set_aspect("auto")),
        ("aspect", lambda fig, ax: ax.set_aspect(2.0)),
    ]
    with rc_context(st):
        for kind in ("four-bar", "six-bar", "slot", "contact") if style == "textbook" else ("six-bar",):
            sol = zoo.specimen(rng, kind).drawn
            fig = Figure(figsize=st.figsize, dpi=72)
            FigureCanvasAgg(fig)
            ax = fig.add_axes((0.05, 0.05, 0.6, 0.9))
            # (asks per_point hundreds of times; the shapes only: the axes' view is the same with the labels)
            draw_mechanism(sol, ax, style=st, options=shapes_only(sol.mechanism))
            assert getattr(ax, "_velpoly_per_point", None) is not None, kind
            assert per_point(ax) == _afresh(ax), kind
            for what, change in changes:
                before = per_point(ax)
                change(fig, ax)
                got = per_point(ax)
                assert got == _afresh(ax), (kind, what)
                if what in ("xlim", "size", "position"):
                    assert got != before, (kind, what)
            # where applying the aspect may move the limits (adjustable datalim, a box aspect): nothing kept
            for change in (lambda: ax.set_aspect("equal", adjustable="datalim"), lambda: ax.set_box_aspect(0.4)):
                change()
                assert _aspect_key(ax) is None, kind
