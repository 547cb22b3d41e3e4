"""The drawing surface shared by every panel: views to scale, paper units, arrows.

A panel's data coordinates are the quantity it draws: lengths for the
mechanism, velocities for the velocity polygon (an image's position *is* its
velocity), accelerations for the acceleration polygon. :func:`fit_view` sets
an axes' limits so that one centimetre of paper stands for a round number of
units (the panel's *scale*, units per cm), with equal aspect; after that,
:func:`per_point` converts typographic points (1/72 inch) into data units so
that arrowheads, pins and gaps have the same size on paper in every panel.
"""
from __future__ import annotations

import math
import re

import numpy as np

from ..names import literal, math_literal  # noqa: F401  (user text drawn as written)
from ..names import index_math, link_math, name_math
from ..names import name_tex as _name_tex

__all__ = ["Artists", "add_patch", "axes_cm", "box", "nice_scale", "nice_length", "fit_view", "view_scale", "per_point",
           "per_cm", "view_box", "border_point", "tex", "prose_tex", "arrow", "get_ax", "renderer_of", "equation_tex",
           "wrap_caption"]

CM = 1 / 2.54  # inches


class Artists(dict):
    """What a drawing function returns: its artists by role, and its labels by key.

    ``artists["arrows"]`` is a list of matplotlib artists (likewise ``"links"``,
    ``"pins"``, ``"lines"`` ...); ``artists.labels`` maps each labelled key
    (a point key, an image's key, a pole's key) to its ``Text``;
    ``artists.ax`` is the axes drawn on.
    """

    def __init__(self, ax):
        super().__init__()
        self.ax = ax
        self.labels: dict = {}

    def add(self, role: str, *artists) -> None:
        self.setdefault(role, []).extend(a for a in artists if a is not None)

    def all(self) -> list:
        return [a for v in self.values() for a in v]

    def update_from(self, other: "Artists") -> "Artists":
        for role, v in other.items():
            self.add(role, *v)
        self.labels.update(other.labels)
        return self


def get_ax(ax):
    """``ax``, or pyplot's current axes (imported lazily, as shapely.plotting does)."""
    if ax is None:
        import matplotlib.pyplot as plt
        ax = plt.gca()
    return ax


def renderer_of(fig):
    """A renderer of the figure, to measure text (Agg, created if need be)."""
    canvas = fig.canvas
    get = getattr(canvas, "get_renderer", None)
    if get is not None:
        return get()
    return fig._get_renderer()


def nice_scale(x: float) -> float:
    """The smallest round scale >= x: 1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten.

    >>> nice_scale(0.065), nice_scale(1.1), nice_scale(3e-5)
    (0.08, 1.5, 3e-05)
    """
    if not math.isfinite(x) or x <= 0:
        return 1.0
    e = math.floor(math.log10(x))
    for f in (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0):
        v = f * 10.0 ** e
        if v >= x * (1 - 1e-12):
            return float(f"{v:.12g}")
    return 10.0 ** (e + 1)


def nice_length(x: float) -> float:
    """The largest of 1, 2, 5 times a power of ten that is <= x (a scale bar's length)."""
    if not math.isfinite(x) or x <= 0:
        return 1.0
    e = math.floor(math.log10(x))
    for f in (5.0, 2.0, 1.0):
        v = f * 10.0 ** e
        if v <= x * (1 + 1e-12):
            return v
    return 10.0 ** e


def axes_cm(ax) -> tuple[float, float]:
    fig = ax.figure
    pos = ax.get_position()
    w, h = fig.get_size_inches()
    return pos.width * w / CM, pos.height * h / CM


def fit_view(ax, bounds, scale: float | None = None, margin: float = 0.06) -> float:
    """Set equal-aspect limits showing ``bounds`` = (xmin, ymin, xmax, ymax), centred.

    The scale (units per cm of paper) is ``scale`` if given, else the smallest
    round scale (:func:`nice_scale`) at which the bounds, grown by ``margin``
    of the panel on every side, fit. Returns the scale; it is kept on the axes
    (:func:`view_scale`) so that later drawings on the same axes keep it.
    """
    wcm, hcm = axes_cm(ax)
    x0, y0, x1, y1 = (float(b) for b in bounds)
    if not all(map(math.isfinite, (x0, y0, x1, y1))):
        x0 = y0 = -1.0
        x1 = y1 = 1.0
    span_x, span_y = max(x1 - x0, 0.0), max(y1 - y0, 0.0)
    usable = 1.0 - 2 * margin
    need = max(span_x / (wcm * usable), span_y / (hcm * usable))
    if need <= 0:
        need = max(abs(x0), abs(y0), abs(x1), abs(y1), 1e-12) / min(wcm, hcm)
    s = float(scale) if scale is not None else nice_scale(need)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    ax.set_xlim(cx - wcm * s / 2, cx + wcm * s / 2)
    ax.set_ylim(cy - hcm * s / 2, cy + hcm * s / 2)
    ax.set_aspect("equal", adjustable="box")
    ax.set_autoscale_on(False)
    ax._velpoly_scale = s
    return s


def view_scale(ax) -> float | None:
    """The scale (units per cm) :func:`fit_view` set on the axes, or None."""
    return getattr(ax, "_velpoly_scale", None)


def per_point(ax) -> float:
    """Data units per typographic point (1/72 inch) on the axes, at its current limits.

    ``|x1 - x0| / w * (2.54 / 72)``, w the axes' width in cm of paper after its aspect is applied
    (``get_position`` applies it: a millisecond, and label placement asks thousands of times on one drawing).
    The value is kept on the axes with what it was computed from (:func:`_aspect_key`: the limits, scales,
    positions, aspect, adjustable, anchor and box aspect, the figure's size in inches and pixels): where all
    of these are as they were after the last computation, applying the aspect again changes nothing (it
    depends on the original position, never on the active one it sets) and the same numbers give the same
    value, so it is returned as it is."""
    key = _aspect_key(ax)
    kept = getattr(ax, "_velpoly_per_point", None)
    if key is not None and kept is not None and kept[0] == key:
        return kept[1]
    x0, x1 = ax.get_xlim()
    wcm, _ = axes_cm(ax)
    value = abs(x1 - x0) / wcm * (2.54 / 72.0)
    key = _aspect_key(ax)   # as applied
    if key is not None:
        ax._velpoly_per_point = (key, value)
    return value


def _aspect_key(ax):
    """What the axes' applied position and :func:`per_point` depend on, or None where matplotlib's aspect
    handling may change the limits or depend on more (a locator, twinned axes, ``adjustable='datalim'``)."""
    aspect, adjustable = getattr(ax, "_aspect", None), getattr(ax, "_adjustable", None)
    if ax.get_axes_locator() is not None or ax in ax._twinned_axes or not (
            adjustable == "box" or (aspect == "auto" and ax._box_aspect is None)):
        return None
    fig = ax.figure
    return (ax.get_xlim(), ax.get_ylim(), ax.xaxis.get_scale(), ax.yaxis.get_scale(),
            ax._originalPosition.bounds, ax._position.bounds, aspect, adjustable, ax._anchor, ax._box_aspect,
            tuple(fig.get_size_inches()), fig.bbox.bounds, fig.transSubfigure.get_matrix().tobytes())


def per_cm(ax) -> float:
    """Data units per centimetre of paper."""
    return per_point(ax) * 72.0 / 2.54


def view_box(ax):
    """The axes' view as a shapely box."""
    x0, x1 = sorted(ax.get_xlim())
    y0, y1 = sorted(ax.get_ylim())
    return box(x0, y0, x1, y1)


def box(x0: float, y0: float, x1: float, y1: float):
    """``shapely.geometry.box(x0, y0, x1, y1)``, the same ring, in a tenth of its time (shapely's compiled
    constructor; the Python one builds a Polygon from a list: 80 us a box here, and label placement tries
    hundreds); a box with a NaN corner as the Python one makes it."""
    import shapely
    b = shapely.box(x0, y0, x1, y1)
    if b is None:
        from shapely.geometry import box as slow
        return slow(x0, y0, x1, y1)
    return b


def tex(label: str, math: bool = False) -> str:
    """A textbook label as text for an italic Text: ``b4`` -> $b_{4}$, ``c'`` -> c′, ``O_v`` -> $O_{v}$,
    ``p₂`` -> $p_{2}$, ``p(cam)`` -> p with the subscript cam (:func:`velpoly.names.name_tex`).

    >>> tex("b4"), tex("c'"), tex("P_13"), tex("F@5"), tex("B")
    ('$b_{4}$', 'c′', '$P_{13}$', 'F@5', 'B')
    """
    return _name_tex(label, math)


_POINT_NAME = re.compile(r"(?<![a-z$])([A-Z])_?([0-9]+)")
_ON_LINK = re.compile(r"(?<![a-z$])([A-Z][0-9]*(?:[₀-₉]+|\([^()\s$\\]+\)))")   # S₃, S(cam): velpoly.names


def prose_tex(s: str) -> str:
    """Words naming points, with the points' subscripts: ``perpendicular to O4B`` -> ``perpendicular to
    $O_{4}$B``, a point of a link ``S₃``, ``S(cam)`` with the link as its subscript (a link's number,
    ``on 1``, stays as it is).

    >>> prose_tex("perpendicular to O4B"), prose_tex("parallel to the path of B on 1"), prose_tex("BS₃")
    ('perpendicular to $O_{4}$B', 'parallel to the path of B on 1', 'B$S_{3}$')
    """
    s = literal(s)
    parts = _ON_LINK.split(s)   # the names of points of links, then the rest as before
    return "".join("$" + name_math(p) + "$" if i % 2 else
                   _POINT_NAME.sub(lambda mo: "$" + mo.group(1) + "_{" + mo.group(2) + "}$", p)
                   for i, p in enumerate(parts))


def add_patch(ax, patch):
    """``ax.add_patch(patch)``, without growing the data limits where the view is fixed (:func:`fit_view`
    turns autoscaling off): matplotlib takes every patch's Bézier extents for autoscaling, a millisecond a
    patch; the patch is drawn the same (clipped to the axes, in the order added). Returns the patch."""
    if ax.get_autoscale_on():
        return ax.add_patch(patch)
    return ax.add_artist(patch)


def arrow(ax, tail, head, *, lw: float, head_length: float, colour, linestyle="-", zorder=3,
          gid: str | None = None, open_head: bool = False):
    """A straight arrow whose head's tip is exactly at ``head``.

    ``head_length`` in points. Returns ``(shaft, head_patch, head_polygon)``:
    a Line2D from ``tail`` to the head's base, the head as a Polygon patch,
    and the head as a shapely polygon (an obstacle for labels). A vector
    shorter than the head gets a head shrunk to fit it.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Polygon as MPolygon
    from shapely.geometry import Polygon as SPolygon
    tail = np.asarray(tail, float)
    head = np.asarray(head, float)
    d = head - tail
    length = float(np.hypot(*d))
    if length == 0:
        return None, None, None
    u = d / length
    n = np.array([-u[1], u[0]])
    hl = min(head_length * per_point(ax), 0.6 * length)
    hw = 0.32 * hl
    base = head - u * hl
    tri = np.array([head, base + n * hw, base + u * 0.18 * hl - 0 * n, base - n * hw]) if not open_head else \
        np.array([head, base + n * hw, base - n * hw])
    shaft = Line2D([tail[0], (base + u * 0.2 * hl)[0]], [tail[1], (base + u * 0.2 * hl)[1]], lw=lw,
                   color=colour, linestyle=linestyle, solid_capstyle="butt", dash_capstyle="butt",
                   zorder=zorder)
    patch = MPolygon(tri, closed=True, facecolor=colour, edgecolor=colour, lw=0.3, zorder=zorder + 0.1)
    if gid:
        shaft.set_gid(gid + "-shaft")
        patch.set_gid(gid)
    ax.add_line(shaft)
    add_patch(ax, patch)
    return shaft, patch, SPolygon(tri)


def border_point(view, c, d, inset: float) -> np.ndarray:
    """Where the ray from c along d leaves the view, moved ``inset`` back inside."""
    x0, y0, x1, y1 = view.bounds
    x0, y0, x1, y1 = x0 + inset, y0 + inset, x1 - inset, y1 - inset
    ts = []
    for lo, hi, cc, dd in ((x0, x1, c[0], d[0]), (y0, y1, c[1], d[1])):
        if abs(dd) > 1e-12:
            ts.append(((hi if dd > 0 else lo) - cc) / dd)
    t = max(min(ts), 0.0) if ts else 0.0
    return c + d * t


# -- equations ---------------------------------------------------------------------------------------
_NAMES = r"(?:[A-Za-z0-9]|[₀-₉]+|\([^()\s$\\]*\))+"   # point names as velpoly.names writes them: B, O2, P₂, P(cam)
_QUANTITY = re.compile(r"(?<![A-Za-z\\])(omega|alpha|theta|[VARP])(\^[nt])?_(" + _NAMES + "(?:/" + _NAMES + r")?)(\^[0-9])?")
_DIGITS = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")


def equation_tex(eq: str) -> str:
    """A step's vector equation in mathtext: ``V_CB`` -> $V_{CB}$, ``omega_3 x R`` -> $\\omega_{3}$ × R,
    ``omega_2^2 R_AO2`` -> $\\omega_{2}^{2}$ $R_{AO_{2}}$, ``V_B₃/B₄`` -> $V_{B_{3}/B_{4}}$ (a subscript's
    names by :func:`velpoly.names.index_math`), a caption's O₂ -> O$_{2}$, `` - `` -> `` − ``, ``deg`` -> °."""
    def sub(mo):
        name, sup, index, power = mo.groups()
        greek = {"omega": r"\omega", "alpha": r"\alpha", "theta": r"\theta"}.get(name)
        out = "$" + (greek or name) + ("^{" + sup[1:] + "}" if sup else "") + "_{" + (
            link_math(index) if greek else index_math(index)) + "}"
        if power and not sup:
            return out + "^{" + power[1:] + "}$"
        return out + "$" + (power or "")
    s = literal(eq)   # a user's name or title in it is drawn as written
    s = _QUANTITY.sub(sub, s)
    s = re.sub(r"\bO_([av])\b", r"$O_{\1}$", s)   # the polygons' origins O_v, O_a
    s = re.sub("[₀-₉]+", lambda mo: "$_{" + mo.group().translate(_DIGITS) + "}$", s)   # a caption's O₂
    s = re.sub(r"\bomega\b", r"$\\omega$", s)
    s = re.sub(r"\balpha\b", r"$\\alpha$", s)
    s = re.sub(r"([0-9]) deg\b", "\\1°", s)
    return s.replace(" x ", " × ").replace(" - ", " − ")


def breaks(text: str) -> list[int]:
    """Where ``text`` may be broken into lines: the indices of its spaces outside mathtext ($...$).

    >>> breaks("Step 2: $V_B = V_A$, along")
    [4, 7, 20]
    """
    out, inside = [], False
    for i, ch in enumerate(text):
        if ch == "$":
            inside = not inside
        elif ch == " " and not inside:
            out.append(i)
    return out


def wrap_caption(caption: str, width_of=len) -> str:
    """``caption`` in two lines, broken at a space outside mathtext ($...$) where its first line is as wide as
    its second (``width_of``: a text's width; by default its number of characters).

    >>> wrap_caption("Step 2: $V_B = V_A + V_{BA}$, along the path of B, perpendicular to AB")
    'Step 2: $V_B = V_A + V_{BA}$, along\\nthe path of B, perpendicular to AB'
    """
    spaces = breaks(caption)
    if not spaces:
        return caption
    half = width_of(caption) / 2
    lo, hi = 0, len(spaces) - 1   # the first space whose first line is at least half the width (widths grow)
    while lo < hi:
        mid = (lo + hi) // 2
        if width_of(caption[:spaces[mid]]) >= half:
            hi = mid
        else:
            lo = mid + 1
    cands = spaces[max(lo - 1, 0):lo + 1]
    k = min(cands, key=lambda c: max(width_of(caption[:c]), width_of(caption[c + 1:])))
    return caption[:k] + "\n" + caption[k + 1:]
