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

__all__ = ["scale_bar", "unit_label", "scale_text", "scale_number"]

def unit_label(units: str, power: int) -> str:
    """The unit of a length (power 0), a velocity (1) or an acceleration (2)."""
    return literal(unit(units, power))   # velpoly.names: a file without units has "units/s", not "s⁻¹"


def scale_text(value: float, units: str, power: int) -> str:
    """``1 cm = 0.05 m`` for the caption of a panel."""
    return f"1 cm = {scale_number(value)} {unit_label(units, power)}".rstrip()


def scale_number(x: float) -> str:
    """A scale's or a bar's round number as the tables print numbers (:func:`velpoly.render.table.number`): no
    computer exponent, 20000 and 0.0025 as written, 2×10⁻⁹⁰ for a drawing of a driver at 1e-90 rad/s (was 2e-90)."""
    from .table import number
    return number(x, 6, floor=0.0)


BAR_GAP = 1.0   # cm of paper at least between the scale bars of two panels (they must not read as one bar)


def scale_bar(ax, style, units: str, power: int, *, target_cm: float = 2.5, gid: str = "scale-bar"):
    """Draw a segmented scale bar of a round length in a free corner; return its artists.

    The bar is the largest of 1, 2, 5 x 10^k units not longer than
    ``target_cm`` of paper. The returned list starts with the bar's outline
    (a Rectangle whose width is the length in data units) and holds the
    segments and the two labels; ``bar._velpoly_length`` is that length. It
    keeps :data:`BAR_GAP` from the scale bars of the figure's other panels.
    """
    pc, pp = per_cm(ax), per_point(ax)
    length = nice_length(target_cm * pc)
    h = 0.09 * pc
    unit = unit_label(units, power)
    kw = dict(fontsize=style.small_size, va="bottom", zorder=6)
    x0, y0 = view_box(ax).bounds[:2]
    t1 = ax.text(x0, y0, f"{scale_number(length)} {unit}".rstrip(), ha="center", **kw)
    t0 = ax.text(x0, y0, "0", ha="center", gid=f"{gid}-0", **kw)
    w0, w1 = placer(ax).text_size(t0, 0.0)[0], placer(ax).text_size(t1, 0.0)[0]
    # the end label over the bar's end, or beside the bar where "0" and it would run into each other
    beside = length < (w0 + w1) / 2 + 3.0 * pp
    right = length + 3.0 * pp + w1 + 0.1 * pc if beside else max(length + 0.2 * pc, length + w1 / 2 + 0.1 * pc)
    room = (right, h + style.small_size * pp * 1.6)   # the bar's and its labels' extent from its corner
    t1.set_gid(f"{gid}-end")
    if beside:
        t1.set_horizontalalignment("left")
        t1.set_verticalalignment("center")

    def put(bx, by):   # "0" over the bar's start, the end label over its end or beside it
        t0.set_position((bx, by + h + 1.5 * pp))
        t1.set_position((bx + length + 3.0 * pp, by + h / 2) if beside else (bx + length, by + h + 1.5 * pp))

    def parts():   # the bar's and its labels' boxes from its corner (where no room is free: the texts off the lines)
        put(0.0, 0.0)
        return [(0.0, 0.0, length, h)] + [placer(ax).box_of(t, 0.0).bounds for t in (t0, t1)]
    bx, by = _bar_corner(ax, _corners(ax, room), room, gid, parts)
    out = _bar_patches(ax, style, bx, by, length, h, gid)
    put(bx, by)
    t0.remove()
    ax.add_artist(t0)   # after the bar: the bar, "0", the end label, in this order
    t1.remove()
    ax.add_artist(t1)
    out += [t0, t1]
    pl = placer(ax)
    pl.add_obstacle(box(bx, by, bx + length, by + h))
    pl.add_box(t0)
    pl.add_box(t1)
    _register(ax, out)
    return out


def _corners(ax, room) -> list:
    """The places tried for the bar's lower left corner: along the bottom, the top, then the sides."""
    pc = per_cm(ax)
    x0, y0, x1, y1 = view_box(ax).bounds
    m = 0.35 * pc
    lo_x, hi_x = x0 + m, x1 - m - room[0]
    lo_y, hi_y = y0 + m, y1 - m - room[1]
    xs = [lo_x, hi_x] + [lo_x + (hi_x - lo_x) * f for f in (0.25, 0.5, 0.75, 0.125, 0.375, 0.625, 0.875)]
    corners = [(x, y) for y in (lo_y, hi_y) for x in xs]
    return corners + [(x, lo_y + (hi_y - lo_y) * f) for f in (0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875)
                      for x in (lo_x, hi_x)]


def _others(ax) -> list:
    """The other panels' scale bars (their bars and labels) in this axes' data coordinates, grown by
    :data:`BAR_GAP`."""
    grow = BAR_GAP * per_cm(ax)
    inv = ax.transData.inverted()
    out = []
    for other, bb in getattr(ax.figure, "_velpoly_bars", ()):
        if other is ax:
            continue
        (a, b), (c, d) = inv.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
        out.append(box(min(a, c), min(b, d), max(a, c), max(b, d)).buffer(grow))
    return out


def _bar_corner(ax, corners, room, gid: str, parts=None):
    """The first corner whose room (bar, labels) is free of everything drawn and of the other panels' bars;
    else, of those corners and a grid over the view (:func:`_grid`), the one whose labels meet the fewest lines,
    labels, marks and other bars, then whose bar meets the fewest (a number on a vector's shaft reads as the
    vector's; a bar across it does not; ``parts()``: the bar's box from the corner, then its labels'). A step
    frame: where the finished construction has it."""
    pc = per_cm(ax)
    pl = placer(ax)
    others = _others(ax)
    geoms = np.array(pl.boxes + pl.hard + others + pl.soft, dtype=object)
    weights = np.array([10] * (len(pl.boxes) + len(pl.hard)) + [100] * len(others) + [1] * len(pl.soft))
    pin = pl.pins.get(gid)
    if pin is not None and pin[0] == "bar":
        corners = [pin[1]]
    best = None
    for c in corners:
        region = box(c[0] - 0.2 * pc, c[1] - 0.1 * pc, c[0] + room[0], c[1] + room[1] + 0.1 * pc)
        hits = int(np.dot(shapely.intersects(geoms, region), weights)) if len(geoms) else 0
        if best is None or hits < best[0]:
            best = (hits, c)
        if hits == 0:
            break
    free = best[0] == 0   # its room free (a detail's make_room makes the scale coarser until it is)
    if not free and parts is not None and len(corners) > 1 and len(geoms):
        best = (best[0], _least_on_texts(ax, corners + _grid(ax, room), parts(), geoms, weights))
    pl.placed[gid] = ("bar", (float(best[1][0]), float(best[1][1])), free)
    return best[1]


def _grid(ax, room) -> list:
    """Corners every 1 mm over the view, 0.35 cm in from its edges, the room kept inside."""
    pc = per_cm(ax)
    x0, y0, x1, y1 = view_box(ax).bounds
    m = 0.35 * pc
    xs = np.arange(x0 + m, x1 - m - room[0] + 1e-9 * pc, 0.1 * pc)
    ys = np.arange(y0 + m, y1 - m - room[1] + 1e-9 * pc, 0.1 * pc)
    return [(float(x), float(y)) for y in ys for x in xs]


def _least_on_texts(ax, corners, parts, geoms, weights):
    """Of ``corners``, the first whose parts' boxes (1 pt grown) meet least (weighted, ``weights`` of
    ``geoms``): the labels' first, then the bar's."""
    pp = per_point(ax)
    tree = shapely.STRtree(geoms)
    xy = np.asarray(corners, float)
    score = np.zeros((len(xy), 2))
    for k, (a, b, c, d) in enumerate(parts):
        boxes = shapely.box(xy[:, 0] + a - pp, xy[:, 1] + b - pp, xy[:, 0] + c + pp, xy[:, 1] + d + pp)
        which, hit = tree.query(boxes, predicate="intersects")
        np.add.at(score[:, 0 if k else 1], which, weights[hit])
    return tuple(xy[np.lexsort((score[:, 1], score[:, 0]))[0]])


def _bar_patches(ax, style, bx: float, by: float, length: float, h: float, gid: str) -> list:
    """The bar's outline and its black segments (five for a length of 5 x 10^k, else two)."""
    from matplotlib.patches import Rectangle
    nseg = 5 if round(length / 10 ** math.floor(math.log10(length))) == 5 else 2
    bar = Rectangle((bx, by), length, h, facecolor=style.paper, edgecolor=style.ink, lw=style.thin_lw * 1.4,
                    zorder=6, gid=gid)
    bar._velpoly_length = length
    ax.add_patch(bar)
    out = [bar]
    seg = length / nseg
    for i in range(0, nseg, 2):
        r = Rectangle((bx + i * seg, by), seg, h, facecolor=style.ink, edgecolor=style.ink, lw=0, zorder=6)
        ax.add_patch(r)
        out.append(r)
    return out


def _register(ax, artists) -> None:
    """Keep the bar's extent (display coordinates) on the figure, for the other panels' bars."""
    from matplotlib.transforms import Bbox
    from .canvas import renderer_of
    r = renderer_of(ax.figure)
    bb = Bbox.union([a.get_window_extent(r) for a in artists])
    kept = [(other, b) for other, b in getattr(ax.figure, "_velpoly_bars", ()) if other is not ax]
    ax.figure._velpoly_bars = kept + [(ax, bb)]   # a panel drawn again (a polygon given its legend's strip): once
