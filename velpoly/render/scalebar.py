"""Scale bars: a round length of the panel's quantity, drawn to the panel's scale.

``units`` of the mechanism give the labels: a length (``m``), a velocity
(``m/s``), an acceleration (``m/s²``).
"""
from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import box

from ..names import unit
from .canvas import literal, nice_length, per_cm, per_point, view_box
from .labels import placer

__all__ = ["scale_bar", "unit_label", "scale_text"]

def unit_label(units: str, power: int) -> str:
    """The unit of a length (power 0), a velocity (1) or an acceleration (2)."""
    return literal(unit(units, power))   # velpoly.names: a file without units has "units/s", not "s⁻¹"


def scale_text(value: float, units: str, power: int) -> str:
    """``1 cm = 0.05 m`` for the caption of a panel."""
    return f"1 cm = {value:g} {unit_label(units, power)}".rstrip()


def scale_bar(ax, style, units: str, power: int, *, target_cm: float = 2.5, gid: str = "scale-bar"):
    """Draw a segmented scale bar of a round length in a free corner; return its artists.

    The bar is the largest of 1, 2, 5 x 10^k units not longer than
    ``target_cm`` of paper. The returned list starts with the bar's outline
    (a Rectangle whose width is the length in data units) and holds the
    segments and the two labels; ``bar._velpoly_length`` is that length.
    """
    from matplotlib.patches import Rectangle
    pc, pp = per_cm(ax), per_point(ax)
    length = nice_length(target_cm * pc)
    h = 0.09 * pc
    nseg = 5 if round(length / 10 ** math.floor(math.log10(length))) == 5 else 2
    pl = placer(ax)
    view = view_box(ax)
    x0, y0, x1, y1 = view.bounds
    m = 0.35 * pc
    text_h = style.small_size * pp * 1.6
    unit = unit_label(units, power)
    kw = dict(fontsize=style.small_size, va="bottom", zorder=6)
    t1 = ax.text(x0, y0, f"{length:g} {unit}".rstrip(), ha="center", **kw)
    w1 = pl.text_size(t1, 0.0)[0]
    t0 = ax.text(x0, y0, "0", ha="center", gid=f"{gid}-0", **kw)
    w0 = pl.text_size(t0, 0.0)[0]
    # the end label over the bar's end, or beside the bar where "0" and it would run into each other
    beside = length < (w0 + w1) / 2 + 3.0 * pp
    if beside:
        right = length + 3.0 * pp + w1 + 0.1 * pc
    else:
        right = max(length + 0.2 * pc, length + w1 / 2 + 0.1 * pc)   # the label reaches past the end
    lo_x, hi_x = x0 + m, x1 - m - right
    lo_y, hi_y = y0 + m, y1 - m - h - text_h
    xs = [lo_x, hi_x] + [lo_x + (hi_x - lo_x) * f for f in (0.25, 0.5, 0.75, 0.125, 0.375, 0.625, 0.875)]
    corners = [(x, y) for y in (lo_y, hi_y) for x in xs]
    corners += [(x, lo_y + (hi_y - lo_y) * f) for f in (0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875)
                for x in (lo_x, hi_x)]
    # the first place along the bottom, the top, then the sides, whose room (bar, labels) is free of everything
    # drawn; else the one crossing the fewest lines and no label, legend or arrowhead if it can
    geoms = np.array(pl.boxes + pl.hard + pl.soft, dtype=object)
    weights = np.array([10] * (len(pl.boxes) + len(pl.hard)) + [1] * len(pl.soft))
    best = None
    pin = pl.pins.get(gid)
    if pin is not None and pin[0] == "bar":   # a step frame: where the finished construction has it
        corners = [pin[1]]
    for c in corners:
        region = box(c[0] - 0.2 * pc, c[1] - 0.1 * pc, c[0] + right, c[1] + h + text_h + 0.1 * pc)
        hits = int(np.dot(shapely.intersects(geoms, region), weights)) if len(geoms) else 0
        if best is None or hits < best[0]:
            best = (hits, c)
        if hits == 0:
            break
    bx, by = best[1]
    pl.placed[gid] = ("bar", (float(bx), float(by)))
    out = []
    bar = Rectangle((bx, by), length, h, facecolor=style.paper, edgecolor=style.ink, lw=style.thin_lw * 1.4,
                    zorder=6, gid=gid)
    bar._velpoly_length = length
    ax.add_patch(bar)
    out.append(bar)
    seg = length / nseg
    for i in range(0, nseg, 2):
        r = Rectangle((bx + i * seg, by), seg, h, facecolor=style.ink, edgecolor=style.ink, lw=0, zorder=6)
        ax.add_patch(r)
        out.append(r)
    t0.remove()
    t0.set_position((bx, by + h + 1.5 * pp))
    ax.add_artist(t0)   # after the bar: the bar, "0", the end label, in this order
    t1.remove()
    t1.set_gid(f"{gid}-end")
    if beside:
        t1.set_position((bx + length + 3.0 * pp, by + h / 2))
        t1.set_horizontalalignment("left")
        t1.set_verticalalignment("center")
    else:
        t1.set_position((bx + length, by + h + 1.5 * pp))
    ax.add_artist(t1)
    out += [t0, t1]
    pl.add_obstacle(box(bx, by, bx + length, by + h))
    pl.add_box(t0)
    pl.add_box(t1)
    return out
