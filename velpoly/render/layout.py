"""Page layouts that use the page: panels sized to what they draw (no matplotlib here, arithmetic only).

A sheet's panels stand side by side in a band, or in two bands, the results
table beneath them across the page, or in the page's bottom left corner with
the last panels beside it down to the page's bottom (:func:`arrange`'s
``notch``); or one panel stands in a column at the page's full height, the
others in bands beside it (:func:`arrange`). Each panel gets the share of the band's width that its drawing
needs at the band's height (a wide mechanism a wide panel, a tall polygon a
narrow one), every drawing at the same fraction of the band first; then each
scale is rounded (:func:`~velpoly.render.canvas.nice_scale`) and the width
the rounding frees goes to the panels that can then be drawn a round scale
larger. Arrangements are compared by :func:`cover` (the drawings' number
times the geometric mean of their areas). Every size is in centimetres of
paper.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

from .canvas import nice_scale

__all__ = ["MARGIN", "Row", "Band", "Bands", "share_row", "smaller_scale", "arrange", "fuller", "shrinks", "scales_of",
           "drawn_size", "drawn_areas", "cover"]

# paper kept about a drawing inside its panel (cm): each side, top, bottom (the scale bar's strip)
MARGIN = (0.5, 0.45, 1.05)
_ROUND = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0)


def smaller_scale(s: float) -> float:
    """The largest round scale below ``s`` (a drawing one step larger on paper).

    >>> smaller_scale(2.0), smaller_scale(1.0), smaller_scale(0.15)
    (1.5, 0.8, 0.1)
    """
    e = math.floor(math.log10(s))
    cands = [f * 10.0 ** k for k in (e - 1, e) for f in _ROUND]
    return float(f"{max(c for c in cands if c < s * (1 - 1e-9)):.12g}")


@dataclass(frozen=True)
class Row:
    """Panels side by side: each one's width (cm, margins included) and scale (units per cm), and the
    height (cm, margins included) the tallest drawing needs."""

    widths: tuple[float, ...]
    scales: tuple[float, ...]
    height: float


def _spans(spans):
    """Each drawing's (width, height), neither of them nothing (a drawing on a line keeps a height)."""
    out = []
    for w, h in spans:
        big = max(w, h, 1e-300)
        out.append((max(w, 1e-3 * big), max(h, 1e-3 * big)))
    return out


def share_row(spans, width: float, height: float, gap: float, scales=None, margin=MARGIN, least=None,
              extra=None) -> Row:
    """Share ``width`` cm between drawings of ``spans`` [(width, height) in their units] side by side in a
    band ``height`` cm tall, ``gap`` cm apart. ``scales``: a user's scale for a panel (None: chosen);
    ``least``: the width (cm) a panel needs whatever it draws (its caption's); ``extra``: the width (cm) it
    needs beside its drawing (a mechanism's labels, the driver's value beside its pivot).

    Every drawing first at the same fraction of the band's height (or of its share of the width), each scale
    then rounded up; the width freed goes, a round step at a time, to the drawing smallest on paper that can
    take the next larger size. What is left is shared out evenly."""
    spans = _spans(spans)
    n = len(spans)
    mx, mt, mb = margin
    inner_h = max(height - mt - mb, 0.5)
    avail = max(width - gap * (n - 1) - 2 * mx * n, 0.5 * n)
    scales = list(scales) if scales is not None else [None] * n
    floor = [max(q - 2 * mx, 0.0) for q in (least or [0.0] * n)]
    if sum(floor) > avail:   # the captions cannot all have their room: each its share (they are set smaller)
        floor = [f * avail / sum(floor) for f in floor]
    add = list(extra or [0.0] * n)
    ratios = [w / h for w, h in spans]
    room = max(avail - sum(add), 0.1 * avail)   # for the drawings themselves
    first = _first(ratios, [max(f - a, 0.0) for f, a in zip(floor, add)], room, inner_h)
    out = []
    for (w, h), room, user in zip(spans, first, scales):
        out.append(float(user) if user is not None else nice_scale(max(w / room, h / inner_h)))
    need = [max(min(w / s + a, avail), f) for (w, _), s, f, a in zip(spans, out, floor, add)]
    free = avail - sum(need)
    grown = True
    while grown:
        grown = False
        order = sorted(range(n), key=lambda i: (spans[i][0] / out[i]) * (spans[i][1] / out[i]))
        for i in order:
            if scales[i] is not None:
                continue
            s = smaller_scale(out[i])
            w, h = spans[i]
            more = max(w / s + add[i], floor[i]) - need[i]
            if h / s <= inner_h * (1 + 1e-9) and more <= free * (1 + 1e-9):
                free -= more
                need[i], out[i] = max(w / s + add[i], floor[i]), s
                grown = True
                break
    widths = tuple(w + max(free, 0.0) / n + 2 * mx for w in need)
    tallest = max(min(h / s, inner_h) for (_, h), s in zip(spans, out))
    return Row(widths, tuple(out), tallest + mt + mb)


def _first(ratios, fixed, room: float, inner_h: float) -> list[float]:
    """Each drawing's width at the same fraction of the band's height, each at least its ``fixed`` width,
    all together ``room`` (what is left over shared evenly)."""
    n = len(ratios)
    base = [r * min(1.0, room / (sum(ratios) * inner_h)) * inner_h for r in ratios]
    k = 1.0
    for _ in range(8):   # shrink the drawings that are above their fixed width until all fit
        first = [max(k * b, f) for b, f in zip(base, fixed)]
        over = sum(first) - room
        free = sum(k * b for b, f in zip(base, fixed) if k * b > f)
        if over <= 1e-9 or free <= 0:
            break
        k *= max(1.0 - over / free, 0.0)
    if sum(first) > room:   # not even the fixed widths fit: all shrunk alike
        first = [w * room / sum(first) for w in first]
    return [w + (room - sum(first)) / n for w in first]


def drawn_areas(spans, row: Row) -> list[float]:
    """Each drawing's box's area on paper (cm²) in a row."""
    return [(w / s) * (h / s) for (w, h), s in zip(_spans(spans), row.scales)]


def drawn_size(spans, row: Row) -> float:
    """How much of the page a row's drawings take: the sum of their boxes' areas on paper (cm²)."""
    return sum(drawn_areas(spans, row))


def cover(areas) -> float:
    """How large drawings of these areas (cm²) are, all together: their number times their geometric mean
    (every drawing counts: one drawing grown at the cost of the others' shrinking alike gains nothing, and
    a polygon squeezed to a corner loses much)."""
    areas = [max(a, 1e-12) for a in areas]
    return len(areas) * math.exp(sum(math.log(a) for a in areas) / len(areas)) if areas else 0.0


@dataclass(frozen=True)
class Band:
    """Panels side by side: their names, widths and scales, the band's height, its bottom and its left
    (cm; the left from the arrangement's left edge)."""

    names: tuple[str, ...]
    row: Row
    height: float
    bottom: float
    left: float = 0.0


class Bands(list):
    """An arrangement: its :class:`Band` s, how large it draws (``score``: :func:`cover`, less the penalty of a
    second row or a column) and where the table's corner stands (``table_left``, cm from the arrangement's
    left edge: right of a column at the left)."""

    def __init__(self, bands=(), score: float = 0.0, table_left: float = 0.0):
        super().__init__(bands)
        self.score, self.table_left = score, table_left


COLUMN_PENALTY = 1.1   # a column beside rows must draw a tenth larger than rows alone (as a second row must)
COLUMN_FILL = 0.6      # of its height (within the margins): the least a column's drawing fills
POLYGONS = ("velocity", "acceleration")   # a column may not draw one smaller than the rows do to grow the other


def arrange(spans: dict, names, width: float, top: float, bottom: float, gap: float, caption: float,
            scales: dict, least: dict, extra: dict | None = None, notch: tuple[float, float] | None = None
            ) -> Bands:
    """The panels ``names`` laid out between ``bottom`` and ``top`` (cm) in ``width``: in rows
    (:func:`_in_rows`), or with the last panel (or the first) in a column at the page's right (left) from
    ``bottom`` to ``top``, the others in rows beside it (over the table's ``notch``, which then stands
    beside the column: a tall acceleration polygon at the full height beside the mechanism, the velocity
    polygon and the table; or the column and the rows both over the table), whichever draws them largest (:func:`cover`; a column must draw a tenth more).
    The column is as wide as its drawing needs at one of the round scales it can take at that height, and
    taken only where its drawing fills :data:`COLUMN_FILL` of that height (a wide drawing in a column wastes
    it), where the drawings cover as much paper as in the rows (:func:`fuller`) and where no polygon is drawn
    smaller than in the rows to draw the other larger (:func:`shrinks`)."""
    extra = extra or {}
    best = rows = _in_rows(spans, names, width, top, bottom, gap, caption, scales, least, extra, notch)
    if len(names) < 2:
        return best
    mx, mt, mb = MARGIN
    # the column down to the bottom beside the table's corner, or (the same as without a corner) over the table
    grounds = [(bottom, notch)] + ([(bottom + notch[1], None)] if notch is not None else [])
    for (bottom, notch), first in itertools.product(grounds, (False, True)):
        height = top - bottom
        nw, nh = notch if notch is not None else (0.0, 0.0)
        col, rest = (names[:1], list(names[1:])) if first else (names[-1:], list(names[:-1]))
        (name,) = col
        for cw in _column_widths(spans[name], height, least.get(name, 0.0), extra.get(name, 0.0), scales.get(name)):
            rw = width - cw - gap
            need = sum(least.get(n, 0.0) for n in rest) + gap * (len(rest) - 1)
            if rw < max(need, nw + 1e-9 if notch is not None else 0.0) or cw > 0.6 * width:
                continue
            if notch is not None and nw < rw - 2 * mx - 1.0:   # room beside the table within the rows
                sub = _in_rows(spans, rest, rw, top, bottom, gap, caption, scales, least, extra, notch)
            else:
                sub = _in_rows(spans, rest, rw, top, bottom + nh, gap, caption, scales, least, extra)
            row = share_row([spans[name]], cw, height, 0.0, [scales.get(name)], least=[least.get(name, 0.0)],
                            extra=[extra.get(name, 0.0)])
            if _spans([spans[name]])[0][1] / row.scales[0] < COLUMN_FILL * (height - mt - mb):
                continue   # a column is for a tall drawing: one that does not fill its height wastes it
            shift = cw + gap if first else 0.0
            bands = [Band(b.names, b.row, b.height, b.bottom, b.left + shift) for b in sub]
            bands.append(Band(tuple(col), row, height, bottom, 0.0 if first else rw + gap))
            score = cover([a for b in bands for a in drawn_areas([spans[n] for n in b.names], b.row)]) / COLUMN_PENALTY
            if score > best.score + 1e-9 and fuller(spans, bands, rows) and not shrinks(bands, rows):
                best = Bands(bands, score=score, table_left=shift if notch is not None else 0.0)
    return best


def scales_of(bands) -> dict:
    """Each panel's scale (units per cm) in an arrangement."""
    return {n: s for b in bands for n, s in zip(b.names, b.row.scales)}


def shrinks(bands, base, names=POLYGONS) -> bool:
    """Whether the arrangement ``bands`` draws one of the panels ``names`` (the polygons) smaller than ``base``
    does (at a larger scale) while it draws another of them larger: a column that doubles the velocity polygon
    while it halves the acceleration polygon beside it (Problem 1.4.4's full sheet) is no gain for a reader
    of both. (A column that grows the space diagram at the cost of a polygon may be: the cam's.)"""
    new, old = scales_of(bands), scales_of(base)
    both = [n for n in names if n in new and n in old]
    return any(new[n] > old[n] * (1 + 1e-9) for n in both) and any(new[n] < old[n] * (1 - 1e-9) for n in both)


def fuller(spans: dict, bands, base) -> bool:
    """Whether the arrangement ``bands`` covers at least as much paper with its drawings as ``base`` does (the
    sum of their boxes' areas): one that draws larger by :func:`cover` is taken only where it also uses as
    much of the page (a drawing grown into a column or beside the table, while another shrinks and leaves
    its room blank, does not)."""
    def paper(bs):
        return sum(a for b in bs for a in drawn_areas([spans[n] for n in b.names], b.row))
    return paper(bands) >= paper(base) * (1 - 1e-9)


def _column_widths(span, height: float, least: float, extra: float, user) -> list[float]:
    """The widths (cm) a column ``height`` cm tall takes to draw ``span`` at the largest round scales that fit
    that height (the largest first, three of them; one at a user's scale)."""
    mx, mt, mb = MARGIN
    (w, h), = _spans([span])
    s = float(user) if user is not None else nice_scale(h / max(height - mt - mb, 0.5))
    out = []
    for _ in range(1 if user is not None else 3):
        out.append(max(w / s + 2 * mx + extra, least))
        s = nice_scale(s * 1.001)
    return out


def _splits(names):
    """The panels in one row, or in two (the first ones above): the arrangements tried, in this order."""
    yield (tuple(names),)
    for k in range(1, len(names)):
        yield tuple(names[:k]), tuple(names[k:])


def _notched(rows):
    """Each arrangement's last row split in two (the panels over the table, those beside it), the row
    whole first (None: nothing beside the table); of two rows, the last one may stand beside the table
    alone (nothing over it: the first row takes the height above the table)."""
    yield None
    for k in range(0 if len(rows) > 1 else 1, len(rows[-1])):
        yield rows[-1][:k], rows[-1][k:]


def _in_rows(spans: dict, names, width: float, top: float, bottom: float, gap: float, caption: float,
             scales: dict, least: dict, extra: dict | None = None, notch: tuple[float, float] | None = None
             ) -> list[Band]:
    """The panels ``names`` in one row or two between ``bottom`` and ``top`` (cm), whichever draws them
    largest (:func:`cover`; one row unless two cover a tenth more): a wide mechanism
    across the page above its polygons. ``caption``: the height (cm) of a second row's captions. Each row is as tall
    as its drawings need; the height left over is shared out between the rows.

    ``notch``: (width, height) cm at the bottom's left kept for the table (narrower than ``width``). The
    rows then stand over it, or the last row's first panels stand over it and its others beside it, down
    to ``bottom`` (a narrow table in the page's corner, the last polygon at the height the table leaves),
    or, of two rows, the last one beside the table alone."""
    best, extra = None, extra or {}
    nw, nh = notch if notch is not None else (0.0, 0.0)

    def share(r, w, h):
        return share_row([spans[n] for n in r], w, h, gap, [scales.get(n) for n in r],
                         least=[least.get(n, 0.0) for n in r], extra=[extra.get(n, 0.0) for n in r])
    def _room_for(part, w):
        return sum(least.get(n, 0.0) for n in part) + gap * max(len(part) - 1, 0) <= w + 1e-9
    for rows in _splits(list(names)):
        room = top - bottom - nh - caption * (len(rows) - 1)
        for split in (_notched(rows) if notch is not None else (None,)):
            alone = split is not None and not split[0]   # the last row beside the table, nothing over it
            fracs = (1.0,) if len(rows) == 1 or alone else tuple(0.3 + 0.05 * i for i in range(9))
            for f in fracs:
                heights = (room,) if len(rows) == 1 else (room * f, room * (1 - f))
                made = [share(r, width, h) for r, h in zip(rows[:-1] if split else rows, heights)]
                if split is not None:
                    over, beside = split
                    if not (_room_for(over, nw) and _room_for(beside, width - nw - gap)):
                        break   # a caption would not fit its column
                    made += [share(over, nw, heights[-1])] if over else []
                    made += [share(beside, width - nw - gap, heights[-1] + nh)]
                parts = rows[:-1] + ((rows[-1],) if split is None else tuple(r for r in split if r))
                score = cover([a for r, m in zip(parts, made) for a in drawn_areas([spans[n] for n in r], m)])
                score /= 1.0 if len(rows) == 1 else 1.1
                if best is None or score > best[0] + 1e-9:
                    best = (score, rows, parts, made, split)
    score, rows, parts, made, split = best
    alone = split is not None and not split[0]
    heights = [m.height for m in made[:len(rows)]]
    if alone:   # the rows over the table take its height; the last one beside it is as tall as the table
        heights = heights[:-1] + [0.0]
    elif split is not None:   # the last row's height: that of the taller part (the part beside less the notch)
        heights[-1] = max(made[-2].height, made[-1].height - nh)
    slack = max(top - bottom - nh - caption * (len(rows) - 1) - sum(heights), 0.0) / (len(rows) - alone)
    out, y = [], top
    for i, r in enumerate(rows):
        h = heights[i] + (slack if not (alone and i == len(rows) - 1) else 0.0)
        if split is not None and i == len(rows) - 1:
            if split[0]:
                out.append(Band(split[0], made[-2], h, y - h))
            out.append(Band(split[1], made[-1], h + nh, y - h - nh, nw + gap))
        else:
            out.append(Band(r, made[i], h, y - h))
        y -= h + caption
    return Bands(out, score=score)
