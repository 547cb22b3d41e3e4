"""velpoly.render.panelaxes: a panel's axes make their ticks only when asked for, and draw what matplotlib's draw.

A sheet's panels (textcache.add_axes) are PanelAxes: creating one makes no tick (a third of the cost of a
matplotlib Axes), and an axis drawn from one (ticks, grid, minor ticks, tick settings given before and after the
ticks exist, the axis turned off and on again) is the same SVG and PNG bytes as from matplotlib's own Axes, on
generated sequences of such calls.
"""
from __future__ import annotations

import io
import random

import matplotlib
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from velpoly.render.panelaxes import PanelAxes
from velpoly.render.textcache import add_axes, new_canvas


def _calls(seed: int) -> list:
    """A generated sequence of calls on an axes (each a function of the axes), some of them before its first
    draw or read of its ticks, some after."""
    rng = random.Random(seed)
    pool = [
        lambda ax: ax.grid(True),
        lambda ax: ax.grid(True, which="both", color="0.8", lw=0.4),
        lambda ax: ax.minorticks_on(),
        lambda ax: ax.tick_params(direction="in", labelsize=6, top=True, right=True),
        lambda ax: ax.tick_params(which="minor", length=4, color="r"),
        lambda ax: ax.tick_params(axis="y", labelrotation=30, pad=6),
        lambda ax: ax.tick_params(reset=True, which="major", length=7),
        lambda ax: ax.set_xticks([-0.5, 0.5, 1.5, 2.5]),
        lambda ax: ax.xaxis.set_ticks_position("top"),
        lambda ax: ax.yaxis.set_ticks_position("right"),
        lambda ax: ax.set_title("title"),
        lambda ax: ax.set_xlabel("x (m)"),
        lambda ax: ax.set_axis_off(),
        lambda ax: ax.set_axis_on(),
        lambda ax: ax.set_ylim(-3.0, 9.0),
        lambda ax: ax.xaxis.get_major_ticks(),
        lambda ax: ax.set_clip_path(ax.patch),
    ]
    return rng.sample(pool, rng.randint(2, 6))


def _drawn(axes_class, calls, fmt: str) -> bytes:
    with matplotlib.rc_context({"svg.hashsalt": "panel-axes"}):
        fig = Figure(figsize=(2.4, 1.6), dpi=60)
        FigureCanvasAgg(fig)
        ax = fig.add_axes((0.2, 0.2, 0.7, 0.65), axes_class=axes_class)
        ax.plot([0.0, 1.0, 2.0], [0.0, 1.0, 4.0])
        for call in calls:
            call(ax)
        buf = io.BytesIO()
        fig.savefig(buf, format=fmt, metadata={"Date": None} if fmt == "svg" else None)
    return buf.getvalue()


def test_an_axis_drawn_from_panel_axes_is_matplotlibs_to_the_byte():
    differ = []
    for seed in range(14):
        calls = _calls(seed)
        for fmt in ("svg", "png") if seed % 3 == 0 else ("svg",):
            if _drawn(Axes, calls, fmt) != _drawn(PanelAxes, calls, fmt):
                differ.append((seed, fmt))
    assert not differ


def test_a_panel_makes_no_tick_until_asked():
    fig = Figure(figsize=(3.0, 2.0), dpi=72)
    new_canvas(fig)
    ax = add_axes(fig, (0.1, 0.1, 0.8, 0.8), label="panel")
    ax.set_axis_off()
    ax.plot([0.0, 1.0], [0.0, 1.0])
    fig.canvas.draw()
    assert isinstance(ax, PanelAxes)
    made = [name for axis in (ax.xaxis, ax.yaxis) for name in ("majorTicks", "minorTicks") if name in vars(axis)]
    assert made == []
    tick = ax.xaxis.get_major_ticks(1)[0]   # asked for: made, clipped as matplotlib clips its axes' ticks
    assert tick.get_clip_box() is not None and tick.gridline.get_clip_box() is not None

