"""A table and the formats of its cells: :class:`Table`, :func:`fmt`, :func:`polar`, :func:`magnitude_angle`,
:func:`coordinates`, :func:`render_table`.

The bottom of the reporting layer: :mod:`velpoly.compare` and :mod:`velpoly.report`
build Tables, :func:`render_table` writes them as text, Markdown, LaTeX or CSV;
the figures' tables (:mod:`velpoly.render.table`) format their cells with the same
rules. Imports numpy only.
"""
from __future__ import annotations

import csv
import io
import math
import re
from dataclasses import dataclass

import numpy as np

from .names import polar as _angle_text

ZERO = 1e-9   # below this a value of order one prints as 0: rounding noise (fmt)

__all__ = ["Table", "fmt", "zero_floor", "angle", "polar", "magnitude_angle", "coordinates", "magnitude_direction", "render_table", "md_text",
           "tex_text"]


@dataclass(frozen=True)
class Table:
    """A titled table: column headers and rows of strings; ``notes``: its footnotes, ``(mark, key, text)``
    for each mark in its rows (a drawn results table prints them beneath it)."""

    title: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    notes: tuple[tuple[str, str, str], ...] = ()


def fmt(x, digits: int = 6, floor: float = ZERO) -> str:
    """A number to ``digits`` significant digits; '-' for None or NaN; '0' below ``floor`` (rounding noise:
    :data:`ZERO` for values of order one, :func:`zero_floor` for those of a slow or small mechanism)."""
    if x is None:
        return "-"
    x = float(x)
    if not math.isfinite(x):
        return "-"
    if x == 0:
        return "0"
    if abs(x) < 1e-12 * 10 ** digits and abs(x) < floor:
        return "0"
    return f"{x:.{digits}g}"


def zero_floor(values) -> float:
    """Below what a column of ``values`` (numbers or vectors) prints as 0: :data:`ZERO`, or a billionth of the
    column's largest magnitude where that is smaller. The accelerations of a clock's hands (1e-10 m/s^2) are
    values, not rounding noise, and print as such; the noise of a solve (1e-16 of the largest) still prints 0.

    >>> zero_floor([1.0, 30.0]), zero_floor([[3e-10, 4e-10], None])
    (1e-09, 5e-19)
    """
    sizes = [float(np.hypot(*np.ravel(v))) if np.ndim(v) else abs(float(v)) for v in values if v is not None]
    big = max((x for x in sizes if math.isfinite(x)), default=1.0)
    return min(ZERO, ZERO * big) or ZERO


def angle(deg: float, decimals: int = 4) -> str:
    """A link's (or the driver's) angle in degrees as the tables print it: rounded, in (-180, 180] as the
    JSON gives it, never -0.0000 (a coupler along the frame after re-assembly, -2.8e-14 deg) nor -180.0000.

    >>> angle(-2.8e-14), angle(-179.99999999), angle(30.0)
    ('0.0000', '180.0000', '30.0000')
    """
    d = round(float(deg), decimals) + 0.0
    return f"{180.0 if d <= -180.0 else d:.{decimals}f}"


def magnitude_direction(v) -> tuple[float, float] | None:
    """A vector as (magnitude, direction in degrees in [0, 360)); None if it is None or not finite."""
    if v is None:
        return None
    v = np.asarray(v, float)
    if not np.all(np.isfinite(v)):
        return None
    return float(np.hypot(*v)), math.degrees(math.atan2(v[1], v[0])) % 360.0


def polar(v, floor: float = ZERO) -> str:
    """A vector as ``magnitude ∠ direction°`` (direction in [0, 360)); '-' if undefined, '0' if it prints as zero
    (below ``floor``, as :func:`fmt`)."""
    md = magnitude_direction(v)
    if md is None:
        return "-"
    if fmt(md[0], floor=floor) == "0":   # no direction for a zero vector, nor for one that prints as zero (1e-17)
        return "0"
    return magnitude_angle(*md, floor)


def magnitude_angle(magnitude, deg, floor: float = ZERO) -> str:
    """A magnitude and a direction in degrees as a cell: ``12.5 ∠ 30.000°`` (the direction in [0, 360))."""
    return _angle_text(fmt(magnitude, floor=floor), deg, 3)


def coordinates(p, floor: float = ZERO) -> str:
    """A position as a cell: ``(0.1, -2.5)`` (each coordinate as :func:`fmt`, 0 below ``floor``)."""
    return f"({fmt(p[0], floor=floor)}, {fmt(p[1], floor=floor)})"


_TEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_", "{": r"\{",
        "}": r"\}", "~": r"\textasciitilde{}", "^": r"\^{}", "|": r"\textbar{}", "<": r"\textless{}",
        ">": r"\textgreater{}", "∠": r"$\angle$", "°": r"$^\circ$"}


def tex_text(s) -> str:
    r"""Text as LaTeX typesets it as written, in one pass (a replacement never escapes another's output): TeX's
    special characters escaped, ∠ and ° as math.

    >>> print(tex_text("V_B: 12.5 ∠ 30.000°, rad/s^2, $c$ {r} 50%"))
    V\_B: 12.5 $\angle$ 30.000$^\circ$, rad/s\^{}2, \$c\$ \{r\} 50\%
    """
    return "".join(_TEX.get(c, c) for c in str(s))


_MD_SPECIAL = re.compile(r"([\\`*_\[\]<>|#])")
_MD_INNER = re.compile(r"([\\`*\[\]<>|#]|(?<![^\W_])_|_(?![^\W_]))")   # ... an underscore not within a word


def md_text(s, words: bool = True) -> str:
    r"""Text as Markdown shows it as written, in prose or a table cell: every character that would start
    emphasis, code, a link, an HTML tag, a heading or a cell escaped with a backslash. With ``words``, an
    underscore between two letters or digits is left as it is (CommonMark and GitHub take it literally:
    omega_2, P_13, a_b_c); without, every underscore is escaped (the gallery's README).

    >>> print(md_text("a_b_c _x_ *y* `z` [l](u) <b> |"))
    a_b_c \_x\_ \*y\* \`z\` \[l\](u) \<b\> \|
    >>> print(md_text("omega_2", words=False))
    omega\_2
    """
    return (_MD_INNER if words else _MD_SPECIAL).sub(r"\\\1", str(s))


def render_table(t: Table, style: str = "text") -> str:
    """A table as ``text`` (aligned columns), ``markdown``, ``latex`` or ``csv``."""
    if style == "csv":
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(t.header)
        w.writerows(t.rows)
        return buf.getvalue()
    if style == "markdown":
        lines = [f"**{md_text(t.title)}**", "", "| " + " | ".join(map(md_text, t.header)) + " |",
                 "|" + "|".join("---" for _ in t.header) + "|"]
        lines += ["| " + " | ".join(map(md_text, r)) + " |" for r in t.rows]
        return "\n".join(lines) + "\n"
    if style == "latex":
        cols = "l" * len(t.header)
        lines = [r"\noindent\textbf{" + tex_text(t.title) + r"}\par", r"\begin{tabular}{" + cols + "}", r"\hline",
                 " & ".join(map(tex_text, t.header)) + r" \\", r"\hline"]
        lines += [" & ".join(map(tex_text, r)) + r" \\" for r in t.rows]
        lines += [r"\hline", r"\end{tabular}"]
        return "\n".join(lines) + "\n"
    widths = [max(len(str(x)) for x in col) for col in zip(t.header, *t.rows)]
    lines = [t.title, "  ".join(h.ljust(w) for h, w in zip(t.header, widths)).rstrip(),
             "  ".join("-" * w for w in widths)]
    lines += ["  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip() for r in t.rows]
    return "\n".join(lines) + "\n"
