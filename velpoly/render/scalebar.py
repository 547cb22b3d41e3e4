"""Scale bars: a round length of the panel's quantity, drawn to the panel's scale.

``units`` of the mechanism give the labels: a length (``m``), a velocity
(``m/s``), an acceleration (``m/s²``).
"""
from __future__ import annotations

import math

from shapely.geometry import box

from .canvas import nice_length, per_cm, per_point, view_box
from .labels import placer

__all__ = ["scale_bar", "unit_label", "scale_text"]

_POWERS = {0: "", 1: "/s", 2: "/s²"}


def unit_label(units: str, power: int) -> str:
    """The unit of a length (power 0), a velocity (1) or an acceleration (2)."""
    if not units:
        return ("", "s⁻¹", "s⁻²")[power]
    return units + _POWERS[power]


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
    corners = [(x0 + m, y0 + m + text_h * 0), (x1 - m - length, y0 + m), (x0 + m, y1 - m - h - text_h),
               (x1 - m - length, y1 - m - h - text_h)]
    chosen = corners[0]
    for c in corners:
        region = box(c[0] - 0.2 * pc, c[1] - 0.1 * pc, c[0] + length + 0.2 * pc, c[1] + h + text_h + 0.1 * pc)
        if pl.free(region, soft=True):
            chosen = c
            break
    bx, by = chosen
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
    unit = unit_label(units, power)
    kw = dict(fontsize=style.small_size, va="bottom", zorder=6)
    t0 = ax.text(bx, by + h + 1.5 * pp, "0", ha="center", **kw)
    t1 = ax.text(bx + length, by + h + 1.5 * pp, f"{length:g} {unit}".rstrip(), ha="center", **kw)
    out += [t0, t1]
    pl.add_obstacle(box(bx, by, bx + length, by + h))
    pl.add_box(t0)
    pl.add_box(t1)
    return out
