"""Page layouts that use the page: panels sized to what they draw (no matplotlib here, arithmetic only).

A sheet's panels stand side by side in a band, the results table beneath
them across the page. Each panel gets the share of the band's width that
its drawing needs at the band's height (a wide mechanism a wide panel, a
tall polygon a narrow one), every drawing at the same fraction of the band
first; then each scale is rounded (:func:`~velpoly.render.canvas.nice_scale`)
and the width the rounding frees goes to the panels that can then be drawn a
round scale larger. What no drawing needs of the band's height goes to the
table, so that it shows more rows. Every size is in centimetres of paper.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .canvas import nice_scale

__all__ = ["MARGIN", "Row", "share_row", "smaller_scale"]

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


def share_row(spans, width: float, height: float, gap: float, scales=None, margin=MARGIN, least=None) -> Row:
    """Share ``width`` cm between drawings of ``spans`` [(width, height) in their units] side by side in a
    band ``height`` cm tall, ``gap`` cm apart. ``scales``: a user's scale for a panel (None: chosen);
    ``least``: the width (cm) a panel needs whatever it draws (its caption's).

    Every drawing first at the same fraction of the band's height (or of its share of the width), each scale
    then rounded up; the width freed goes, a round step at a time, to the drawing smallest on paper that can
    take the next larger size. What is left is shared out evenly."""
    spans = _spans(spans)
    n = len(spans)
    mx, mt, mb = margin
    inner_h = max(height - mt - mb, 0.5)
    avail = max(width - gap * (n - 1) - 2 * mx * n, 0.5 * n)
    scales = list(scales) if scales is not None else [None] * n
    ratios = [w / h for w, h in spans]
    fill = min(1.0, avail / (sum(ratios) * inner_h))
    first = [r * fill * inner_h for r in ratios]
    first = [w + (avail - sum(first)) / n for w in first]
    out = []
    for (w, h), room, user in zip(spans, first, scales):
        out.append(float(user) if user is not None else nice_scale(max(w / room, h / inner_h)))
    need = [min(w / s, avail) for (w, _), s in zip(spans, out)]
    free = avail - sum(need)
    grown = True
    while grown:
        grown = False
        order = sorted(range(n), key=lambda i: spans[i][0] * spans[i][1] / out[i] ** 2)
        for i in order:
            if scales[i] is not None:
                continue
            s = smaller_scale(out[i])
            w, h = spans[i]
            if h / s <= inner_h * (1 + 1e-9) and w / s - need[i] <= free * (1 + 1e-9):
                free -= w / s - need[i]
                need[i], out[i] = w / s, s
                grown = True
                break
    widths = _spread(need, free, [max(q - 2 * mx, 0.0) for q in (least or [0.0] * n)])
    widths = tuple(w + 2 * mx for w in widths)
    tallest = max(min(h / s, inner_h) for (_, h), s in zip(spans, out))
    return Row(widths, tuple(out), tallest + mt + mb)


def _spread(need, free: float, least) -> list[float]:
    """The widths ``need`` grown by ``free`` in all: first those short of their ``least``, then evenly."""
    out = list(need)
    short = [max(q - w, 0.0) for w, q in zip(out, least)]
    if sum(short) > 0:
        k = min(1.0, free / sum(short))
        out = [w + d * k for w, d in zip(out, short)]
        free -= sum(short) * k
    return [w + free / len(out) for w in out]
