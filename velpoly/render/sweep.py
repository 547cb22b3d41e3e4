"""The figures of a whole cycle (``velpoly sweep -o``, ``--gif``): the rates and speeds over the cycle,
the centrodes, and the animated GIF (drawn by :mod:`velpoly.render.animate`).

The data come from the kernel (:func:`velpoly.sweeps.run_cycle`,
:func:`velpoly.centrodes.centrodes`); nothing here computes kinematics.
"""
from __future__ import annotations

import dataclasses
import math
import re
import textwrap
from pathlib import Path

import matplotlib
import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import ScalarFormatter

from ..centrodes import Centrodes, break_at_infinity
from ..driver import driver_label
from ..fileio import atomic_path
from ..kinematics import Kinematics, prepare
from ..model import Mechanism
from ..names import key_text, quantity_math, unit
from ..reference import file_pose_angle
from ..report import moving_keys
from ..sweeps import Sweep
from .canvas import literal
from .table import number, position_text, tens

__all__ = ["cycle_figure", "plot_cycle", "write_gif", "merge_series", "drawn_pose", "TablesPower",
           "GIF_FRAMES", "GIF_FRAME_MS", "GIF_SIZE", "COINCIDE"]

GIF_FRAMES = 45            # at most this many frames in the animation (8 deg apart on a turn)
GIF_FRAME_MS = 120         # per frame: a 45-frame turn lasts under 6 s
GIF_SIZE = (960, 540)      # pixels


# -- plots -----------------------------------------------------------------------------------
def _style_rc(style: str) -> dict:
    rc = {"svg.hashsalt": "velpoly", "svg.fonttype": "path", "axes.grid": True, "grid.alpha": 0.4}
    if style == "slides":
        rc.update({"font.size": 13, "axes.titlesize": 15, "axes.labelsize": 13, "lines.linewidth": 2.0})
    else:
        rc.update({"font.family": "serif", "mathtext.fontset": "dejavuserif", "font.size": 9, "lines.linewidth": 1.1})
    return rc


_LINESTYLES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 2)), (0, (8, 3)))
_MARKERS = ("", "o", "s", "^", "v", "D", "x", "+")


def _series_style(i: int, n_points: int, style: str) -> dict:
    """Line style of the i-th series: black dashes and markers in textbook style, colour on slides."""
    if style == "slides":
        return {"color": f"C{i % 10}", "linestyle": "-" if i < 10 else "--"}
    every = max(n_points // 12, 1)
    return {"color": "black", "linestyle": _LINESTYLES[i % len(_LINESTYLES)],
            "marker": _MARKERS[(i // len(_LINESTYLES)) % len(_MARKERS)], "markevery": every, "markersize": 3.5}


def _quantity(symbol: str, index: str, bars: str = "") -> str:
    """A curve's label as a book prints it (:mod:`velpoly.names`): ``omega_3`` as omega with subscript 3,
    ``|V_B|`` with subscript B, ``|V_P@2|`` as V with subscript P₂; a user's name drawn as written."""
    sym = {r"\omega": "omega", r"\alpha": "alpha"}.get(symbol, symbol)
    return quantity_math(sym, index if sym in ("omega", "alpha") else key_text(index), bars == "|")


COINCIDE = 1e-9   # curves within this (relative to the panel's largest value) at every pose are one curve


def merge_series(series, tol: float = COINCIDE):
    """A panel's curves as drawn: ``(curves, zero)``. Curves equal at every pose (omega_3 = omega_4 for a
    block on its guide) are one curve labelled "omega_3 = omega_4" (the first's values); curves zero at
    every pose are left out, their labels in ``zero``. Equal means within ``tol`` of the panel's largest
    value, undefined (NaN) at the same poses."""
    finite = [np.abs(y[np.isfinite(y)]) for _, y in series]
    big = max((float(v.max()) for v in finite if v.size), default=0.0)
    eps = tol * max(big, 1e-300)
    zero, groups = [], []
    for label, y in series:
        y = np.asarray(y, float)
        ok = np.isfinite(y)
        if ok.any() and np.all(np.abs(y[ok]) <= eps):
            zero.append(label)
            continue
        for g in groups:
            z = g[1]
            same = np.array_equal(np.isfinite(z), ok) and np.all(np.abs(z[ok] - y[ok]) <= eps)
            if same:
                g[0].append(label)
                break
        else:
            groups.append(([label], y))
    return [(" = ".join(labels), y) for labels, y in groups], zero


def drawn_pose(sw: Sweep) -> float | None:
    """The driver position of the file's pose (the one the sheets draw) on the sweep's axis, or None
    where the sweep does not reach it: a crank's angle (turned by whole turns into the swept range),
    a slider driver's displacement 0."""
    x = np.asarray(sw.angles, float)
    if not x.size:
        return None
    lo, hi = float(np.nanmin(x)), float(np.nanmax(x))
    a = file_pose_angle(sw.mechanism)
    if a is None:
        a = 0.0
    else:
        a = lo + (a - lo) % 360.0
        if a - lo > 360.0 - 1e-9:   # the start itself, rounded up a turn
            a = lo
    return a if lo - 1e-9 <= a <= hi + 1e-9 else None


def cycle_figure(sw: Sweep, points=None, cen: Centrodes | None = None, style: str = "textbook",
                 kin: Kinematics | None = None):
    """The figure of the cycle (a matplotlib Figure, not attached to pyplot).

    Panels: omega and alpha of every moving link, the speeds and accelerations
    of ``points`` (point keys; default: every moving point) against the
    driver's position, and, with ``cen``, the fixed centrode (frame
    coordinates, the mechanism drawn at the first pose) and the moving
    centrode (the link's own coordinates). Each curve's label is its
    quantity, typeset (omega with subscript 3, |V_B| with subscript B; the CSV's columns
    are named ``omega_3``, ``|V_B|``). Curves that coincide over the cycle are
    one curve with one label, "omega_3 = omega_4"; curves zero throughout are
    not drawn, the legend says so (:func:`merge_series`). A dashed vertical
    line marks the drawn pose (:func:`drawn_pose`).
    """
    m = sw.mechanism
    n_rows = 3 if cen is not None else 2
    size = (13.3, 7.5 if cen is None else 10.5) if style == "slides" else (10.0, 6.2 if cen is None else 9.0)
    with matplotlib.rc_context(_style_rc(style)):
        fig = Figure(figsize=size, layout="constrained")
        axes = fig.subplots(n_rows, 2, squeeze=False)
        drawn = drawn_pose(sw)
        for n, (title, ylabel, series) in enumerate(_panels(sw, points)):
            _plot_panel(axes[n // 2, n % 2], sw, title, ylabel, series, style, drawn, legend_drawn=n == 0)
        if cen is not None:
            _plot_centrodes(sw, cen, axes[2, 0], axes[2, 1], style, kin or prepare(m))
        title_pt = 1.2 * float(matplotlib.rcParams["font.size"])      # suptitle: "large"
        fig.suptitle(_wrapped_title(m.title, sw.stopped, size[0], title_pt))
    return fig


class TablesPower(ScalarFormatter):
    """matplotlib's tick labels; the axis's power of ten and offset (its offset text) as the tables print numbers
    (:func:`velpoly.render.table.number`, ``tens``): ``×10⁹⁰`` and ``+1000``, where matplotlib prints ``1e90`` and
    ``+1e3`` (a cycle of a driver at 1e90 rad/s). The ticks read value = tick × 10^power + offset, as matplotlib's."""

    def get_offset(self) -> str:
        # matplotlib's text: the power first ("1e90", "1e−6"), then the signed offset ("+1e3"), each as "%e" writes it
        return _EXPONENT.sub(lambda e: "×" + tens(int(e[2].replace("−", "-"))) if e.start() == 0 else
                             number(float(e[0].replace("−", "-")), 10, 0.0).lstrip("−"), super().get_offset())


_EXPONENT = re.compile(r"([0-9.]+)e([−-]?[0-9]+)")


def _panels(sw: Sweep, points=None) -> list:
    """The four panels over the cycle, row by row: (title, y label, [(curve label, values)])."""
    m = sw.mechanism
    keys = list(points) if points else moving_keys(sw)
    return [
        ("Angular velocities", r"$\omega$ (rad/s)",
         [(_quantity(r"\omega", k.name), sw.omega[k.name]) for k in m.moving_links]),
        ("Angular accelerations", r"$\alpha$ (rad/s²)",
         [(_quantity(r"\alpha", k.name), sw.alpha[k.name]) for k in m.moving_links]),
        ("Speeds", literal(f"|V| ({unit(m.units, 1)})"), [(_quantity("V", k, "|"), np.hypot(*sw.velocity[k].T)) for k in keys]),
        ("Accelerations", literal(f"|A| ({unit(m.units, 2)})"),
         [(_quantity("A", k, "|"), np.hypot(*sw.acceleration[k].T)) for k in keys]),
    ]


def _plot_panel(ax, sw: Sweep, title: str, ylabel: str, series, style: str, drawn, legend_drawn: bool) -> None:
    """One panel: its curves against the driver's position (coinciding ones merged, zero ones named in
    the legend), the drawn pose's dashed line (in the legend of the first panel only)."""
    x = sw.angles
    xname, xunit = driver_label(sw.mechanism)
    curves, zero = merge_series(series)
    for i, (label, y) in enumerate(curves):
        ax.plot(x, y, label=label, gid=f"curve-{i}", **_series_style(i, len(x), style))
    if zero:   # said in the legend, not drawn: a flat line on the axis tells nothing
        ax.plot([], [], linestyle="none", gid="zero-note",
                label=", ".join(zero) + (" are" if len(zero) > 1 else " is") + " zero throughout (not drawn)")
    if drawn is not None:   # where the sheets are drawn (the file's pose)
        ax.axvline(drawn, color="0.45", linestyle=(0, (4, 2)), linewidth=0.9, zorder=1.5, gid="drawn-pose",
                   label=literal(f"drawn pose, {xname} = {position_text(sw.mechanism, drawn)} {xunit}")
                   if legend_drawn else None)
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(TablesPower())
    ax.set_title(title)
    ax.set_xlabel(literal(f"{xname} ({xunit})"))
    ax.set_ylabel(ylabel)
    ax.grid(True)
    if series or drawn is not None:
        ax.legend(fontsize="small", ncols=2 if len(curves) > 4 else 1)
    if xunit == "deg" and len(x) > 1 and abs(x[-1] - x[0]) >= 90:
        lo, hi = sorted((x[0], x[-1]))
        ax.set_xticks(np.arange(math.ceil(lo / 45) * 45, hi + 1e-9, 45))


def _wrapped_title(title: str, stopped: str, width_in: float, font_pt: float) -> str:
    """The figure's title, and the stop message on lines of its own, wrapped to the figure's width
    (a character taken as 0.6 em wide, a safe bound for the serif and sans-serif fonts used)."""
    width = max(int(width_in * 72.0 / (0.6 * font_pt)), 40)
    lines = textwrap.wrap(title, width) or [""]
    if stopped:
        lines += textwrap.wrap(f"[{stopped}]", width)
    return literal("\n".join(lines))


def plot_cycle(sw: Sweep, out, points=None, cen: Centrodes | None = None, style: str = "textbook",
               kin: Kinematics | None = None) -> Path:
    """:func:`cycle_figure` written atomically to ``out`` (SVG, PNG or PDF by its suffix)."""
    out = Path(out)
    with matplotlib.rc_context(_style_rc(style)):
        _save(cycle_figure(sw, points, cen, style, kin), out)
    return out


def _plot_centrodes(sw: Sweep, cen: Centrodes, ax_fixed, ax_moving, style: str, kin: Kinematics) -> None:
    m = sw.mechanism
    u = m.units or "units"
    lk = cen.link
    om = sw.omega[lk]
    line = {"color": "black" if style != "slides" else "C3"}
    fixed = break_at_infinity(cen.fixed, om)
    moving = break_at_infinity(cen.moving, om)
    # the mechanism at the first pose, for orientation, and the view: the mechanism's motion
    _draw_lines(ax_fixed, sw, 0, style, labels=True)
    ax_fixed.plot(fixed[:, 0], fixed[:, 1], label=literal(f"fixed centrode of link {lk}"), **line)
    if cen.defined[0]:
        ax_fixed.plot(*cen.fixed[0], "o", color=line["color"], markersize=4,
                      label=quantity_math("P", _pole_name(m, lk)) + " at the first pose")
        carried = break_at_infinity(cen.carried(sw, kin, 0), om)
        ax_fixed.plot(carried[:, 0], carried[:, 1], linestyle="--", color=line["color"], linewidth=0.8,
                      label="moving centrode (carried by the link)")
    _view(ax_fixed, _motion_box(sw), margin=0.35)
    ax_fixed.set_title(literal(f"Fixed centrode of link {lk} (frame coordinates)"))
    ax_fixed.set_xlabel(literal(f"x ({u})"))
    ax_fixed.set_ylabel(literal(f"y ({u})"))
    ax_fixed.legend(fontsize="small")
    # the moving centrode in the link's own coordinates, with the link's outline (reference pose)
    link = m.link(lk)
    pts = np.array([m.position(p) for p in link.points])
    if len(pts) >= 2:
        ax_moving.fill(pts[:, 0], pts[:, 1], facecolor="0.85", edgecolor="black", linewidth=1.0)
    for p, xy in zip(link.points, pts):
        ax_moving.plot(*xy, "o", markerfacecolor="white", markeredgecolor="black", markersize=5)
        ax_moving.annotate(literal(p), xy, xytext=(4, 4), textcoords="offset points")
    ax_moving.plot(moving[:, 0], moving[:, 1], label=literal(f"moving centrode of link {lk}"), **line)
    box = _box(np.vstack([pts, cen.moving[cen.defined]]) if cen.defined.any() else pts)
    size = max(box[2] - box[0], box[3] - box[1], m.size * 0.1)
    c = pts.mean(axis=0)
    _view(ax_moving, (c[0] - size, c[1] - size, c[0] + size, c[1] + size), margin=0.0, cap=(pts, 3 * m.size))
    ax_moving.set_title(literal(f"Moving centrode of link {lk} (its own coordinates)"))
    ax_moving.set_xlabel(literal(f"x ({u})"))
    ax_moving.set_ylabel(literal(f"y ({u})"))
    ax_moving.legend(fontsize="small")


def _pole_name(m: Mechanism, lk: str) -> str:
    names = m.link_names
    a, b = sorted((m.frame.name, lk), key=names.index)
    return f"{a}{b}" if len(a) == len(b) == 1 else f"{a}-{b}"


def _box(xy: np.ndarray):
    xy = np.asarray(xy, float).reshape(-1, 2)
    xy = xy[np.isfinite(xy).all(axis=1)]
    if not len(xy):
        return (-1.0, -1.0, 1.0, 1.0)
    return (*xy.min(axis=0), *xy.max(axis=0))


def _motion_box(sw: Sweep):
    return _box(np.vstack([v for v in sw.position.values()]))


def _view(ax, box, margin=0.1, cap=None) -> None:
    x0, y0, x1, y1 = box
    if cap is not None:  # never wider than `cap` around some points (a centrode running to infinity)
        pts, r = cap
        c = np.asarray(pts, float).mean(axis=0)
        x0, y0, x1, y1 = max(x0, c[0] - r), max(y0, c[1] - r), min(x1, c[0] + r), min(y1, c[1] + r)
    w, h = x1 - x0, y1 - y0
    s = max(w, h, 1e-12)
    ax.set_xlim(x0 - margin * s, x1 + margin * s)
    ax.set_ylim(y0 - margin * s, y1 + margin * s)
    ax.set_aspect("equal", adjustable="box")


def _save(fig, out: Path) -> None:
    fmt_ = out.suffix.lower().lstrip(".")
    meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}, "png": {"Software": None}}
    with atomic_path(out) as tmp:
        fig.savefig(tmp, format=fmt_, metadata=meta.get(fmt_), dpi=120 if fmt_ == "png" else None)


# -- the mechanism at one pose --------------------------------------------------------------
def _key_on(m: Mechanism, sw: Sweep, p: str, lk: str) -> str:
    return p if p in sw.position else f"{p}@{lk}"


def _draw_lines(ax, sw: Sweep, i: int, style: str, labels: bool = True) -> list:
    """A line diagram of the mechanism at pose i: bars, plates, pins, ground pivots, slider blocks."""
    m = sw.mechanism
    artists = []
    colour = (lambda j: "black") if style != "slides" else (lambda j: f"C{j % 10}")
    pos = {k: v[i] for k, v in sw.position.items()}
    frame = m.frame.name
    for j, link in enumerate(m.moving_links):
        xy = np.array([pos[_key_on(m, sw, p, link.name)] for p in link.points])
        if len(xy) >= 3:
            artists += ax.fill(xy[:, 0], xy[:, 1], facecolor=colour(j), alpha=0.15, edgecolor=colour(j))
        if len(xy) >= 2:
            artists += ax.plot(xy[:, 0], xy[:, 1], "-", color=colour(j), linewidth=2.0, solid_capstyle="round")
    # slider blocks on their paths, the frame's guides as long thin lines
    box = _motion_box(sw)
    reach = max(box[2] - box[0], box[3] - box[1])
    for s, r in zip(m.sliders, sw.sliders):
        p = pos[_key_on(m, sw, s.point, s.block)]
        d = math.radians(float(r["direction"][i]))
        u = np.array([math.cos(d), math.sin(d)])
        if s.guide == frame and s.centre is None:
            a, b = p - reach * u, p + reach * u
            artists += ax.plot([a[0], b[0]], [a[1], b[1]], "-", color="0.5", linewidth=0.8)
        artists += ax.plot(*p, marker=(4, 0, math.degrees(d) + 45), markersize=13, markerfacecolor="white",
                           markeredgecolor="black", linestyle="")
    # ground pivots and pins
    pins = {pin.point for pin in m.pins}
    for p in m.frame.points:
        if p in pins:
            xy = pos[_key_on(m, sw, p, frame)]
            artists += ax.plot(*xy, marker="^", markersize=10, markerfacecolor="0.8", markeredgecolor="black",
                               linestyle="")
    for p in pins:
        for key in (p, *(k for k in pos if k.startswith(p + "@"))):
            if key in pos:
                artists += ax.plot(*pos[key], "o", markersize=4.5, markerfacecolor="white",
                                   markeredgecolor="black")
                break
    if labels:
        named = set()
        for key, xy in pos.items():
            p = key.split("@")[0]
            if p not in named:
                named.add(p)
                artists.append(ax.annotate(literal(p), xy, xytext=(4, 4), textcoords="offset points", fontsize="small"))
    return artists


def write_gif(sw: Sweep, out, kin: Kinematics | None = None, style: str = "textbook",
              cen: Centrodes | None = None, max_frames: int = GIF_FRAMES, progress=None) -> Path:
    """An animated GIF of the sweep's poses (at most ``max_frames``, evenly spread) drawn by
    ``velpoly animate``'s renderer (:mod:`velpoly.render.animate`): the mechanism beside its velocity
    polygon and the live table, at GIF_SIZE pixels. With ``cen``, the fixed centrode is drawn and the
    moving centrode rides with the link. ``progress(done, total)`` is called after each frame."""
    from .animate import Animator, FramePlan, write_animation   # only a GIF needs the animation renderer
    out = Path(out)
    m = sw.mechanism
    n = len(sw.angles)
    frames = np.unique(np.linspace(0, n - 1, min(n, max_frames)).round().astype(int))
    xname, xunit = driver_label(m)
    first, last = (position_text(m, sw.angles[k]) for k in (frames[0], frames[-1]))
    caption = f"{xname} from {first} to {last} {xunit}" + \
        (f" [{sw.stopped}]" if sw.stopped else "")
    if sw.kinematics is None:
        sw = dataclasses.replace(sw, kinematics=kin or prepare(m))
    plan = FramePlan(m, (sw,), tuple((0, int(i)) for i in frames), np.asarray(sw.angles, float)[frames],
                     np.ones(len(frames)), None, caption, 0.0, bool(sw.stopped) or m.driver.is_slider)
    anim = Animator(plan, "velocity", style, GIF_SIZE, centrodes=(cen, sw) if cen is not None else None)
    write_animation(anim, out, 1000.0 / GIF_FRAME_MS, progress)
    return out
