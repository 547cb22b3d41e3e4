"""A whole driver cycle: ``velpoly sweep`` (plots, CSV, centrodes, animated GIF).

The cycle follows the drawn branch (:func:`velpoly.sweep`):

* a crank (driver link) turns from its reference angle through 360 degrees in
  the sense of its omega (counter-clockwise if omega >= 0), ``--step`` degrees
  apart: ``360 / step`` poses, the closing pose (the start again) left out;
* a slider driver runs over the whole stroke it can reach from its reference
  position on the drawn branch (at most two mechanism sizes either way), in
  ascending displacement, with steps of 1/(360/step) of the stroke (a unit-free
  step, so that the same ``--step`` serves millimetres and metres). Each end of
  the stroke is a toggle (the branches meet there), so the two halves are
  followed from the reference position outwards and the poses stop within one
  step of each end; this is the cycle, not an early stop.

A toggle on the way ends the cycle early: :attr:`Sweep.stopped` says so, the
command warns on stderr and still writes the reachable part (exit 3 when fewer
than two poses can be reached).

Centrodes (:func:`centrodes`): the pole W of a link k with the frame follows
from the link's velocity field, ``V_W = V_O + omega_k x (W - O) = 0``, so
``W = O + perp(V_O) / omega_k``. Its locus in frame coordinates is the fixed
centrode; expressed in the link's own coordinates (those of the reference pose)
it is the moving centrode, which rolls on the fixed one.

The kernel part of this module imports numpy only; matplotlib is imported
inside the functions that plot.
"""
from __future__ import annotations

import csv
import dataclasses
import io
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import InputError, PoseError
from .fileio import atomic_path, atomic_write_text
from .kinematics import Kinematics, prepare
from .model import Mechanism
from .names import key_text, place, quantity_math, relative, unit
from .report import Table, fmt, render_table
from .solution import driver_reference_angle
from .sweeps import MEMORY_BUDGET, Sweep, check_memory, memory_estimate, sweep

__all__ = ["cycle_angles", "run_cycle", "reachable_text", "Centrodes", "centrodes", "cycle_columns", "cycle_csv",
           "summary_table", "cycle_figure", "plot_cycle", "write_gif", "sweep_command", "SweepOutcome", "merge_series", "drawn_pose"]

FIGURE_SUFFIXES = (".svg", ".png", ".pdf")
GIF_FRAMES = 45            # at most this many frames in the animation (8 deg apart on a turn)
GIF_FRAME_MS = 120         # per frame: a 45-frame turn lasts under 6 s
GIF_SIZE = (960, 540)      # pixels
STROKE_REACH = 2.0         # a slider driver is searched this many mechanism sizes either way
STROKE_SAMPLES = 2000      # grid of that search (the stroke's ends are found to 1/1000 size)


# -- the cycle's driver positions -----------------------------------------------------------
def _check_step(step: float) -> float:
    step = float(step)
    if not math.isfinite(step) or step <= 0 or step > 180:
        raise InputError(f"the step must be a number of degrees in (0, 180], got {step:g}", where="--step",
                         hint="e.g. --step 1 (360 poses a turn) or --step 5")
    return step


def _slider_stroke(m: Mechanism, kin: Kinematics) -> tuple[float, float]:
    """The driver slider's reachable displacements (lo, hi) from its reference position."""
    grid = np.linspace(0.0, STROKE_REACH * m.size, STROKE_SAMPLES + 1)[1:]
    ends = []
    for sign in (-1.0, 1.0):
        w = sweep(m, sign * grid, kin)
        ends.append(float(w.angles[-1]) if len(w.angles) else 0.0)
    return ends[0], ends[1]


def _slider_positions(lo: float, hi: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Displacements from the reference (0) down towards ``lo`` and up towards ``hi``, (hi - lo) / n
    apart: the multiples of the step inside the stroke (an end itself is a toggle, left out)."""
    d = (hi - lo) / n if hi > lo else 1.0
    down = -d * np.arange(int(math.floor(-lo / d + 1e-9)) + 1)
    up = d * np.arange(int(math.floor(hi / d + 1e-9)) + 1)
    return down, up


def cycle_angles(m: Mechanism, step: float = 1.0, kin: Kinematics | None = None) -> np.ndarray:
    """The driver positions of one cycle (module docstring): degrees, or displacements for a slider."""
    step = _check_step(step)
    n = max(int(math.ceil(360.0 / step - 1e-9)), 1)
    if m.driver.is_slider:
        down, up = _slider_positions(*_slider_stroke(m, kin or prepare(m)), n)
        return np.concatenate([down[::-1], up[1:]])
    ref = driver_reference_angle(m)
    sense = -1.0 if m.driver.omega < 0 else 1.0
    return ref + sense * step * np.arange(n)


def _join(down: Sweep, up: Sweep) -> Sweep:
    """One sweep from two that start at the reference pose: ``down`` reversed, then ``up`` (its
    first pose, the reference, once). Arrays, dicts of arrays and lists of such dicts are joined
    pose by pose; the mechanism is kept and the stop messages are combined."""
    def cat(a, b):
        if isinstance(a, dict):
            return {k: cat(a[k], b[k]) for k in a}
        if isinstance(a, list):
            return [cat(x, y) for x, y in zip(a, b)]
        return np.concatenate([np.asarray(a)[::-1], np.asarray(b)[1:]])
    joined = {}
    for f in dataclasses.fields(Sweep):
        a, b = getattr(down, f.name), getattr(up, f.name)
        if f.name == "stopped":
            joined[f.name] = "; ".join(x for x in (a, b) if x)
        elif isinstance(a, (np.ndarray, dict, list)) and type(a) is type(b):
            joined[f.name] = cat(a, b)
        elif isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
            joined[f.name] = None          # known on one side only (a cache): recomputed on use
        else:
            joined[f.name] = b
    return Sweep(**joined)


def run_cycle(m: Mechanism, step: float = 1.0, kin: Kinematics | None = None) -> Sweep:
    """One driver cycle on the drawn branch (see the module docstring).

    A slider driver's stroke is followed from the reference position down to
    its lower end and up to its upper end (two continuations, never turning
    round at an end, where the branches meet), and returned in ascending order.
    """
    kin = kin or prepare(m)
    step = _check_step(step)
    if not m.driver.is_slider:
        return sweep(m, cycle_angles(m, step, kin), kin)
    n = max(int(math.ceil(360.0 / step - 1e-9)), 1)
    down, up = _slider_positions(*_slider_stroke(m, kin), n)
    w_down, w_up = sweep(m, down, kin), sweep(m, up, kin)
    if not len(w_up.angles):
        return w_up
    if not len(w_down.angles):
        return w_down
    # the stroke ends where it cannot go on: not a stop to warn about
    return dataclasses.replace(_join(w_down, w_up), stopped="")


def driver_label(m: Mechanism) -> tuple[str, str]:
    """(axis name, unit) of the driver's position."""
    if m.driver.is_slider:
        return f"slider {m.driver.slider} displacement", m.units
    return f"driver angle (link {m.driver.link})", "deg"


# -- centrodes ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Centrodes:
    """The fixed and moving centrodes of ``link`` over a sweep, one row per pose.

    ``fixed`` (N, 2): the pole of the link with the frame, in frame coordinates;
    ``moving`` (N, 2): the same pole in the link's own coordinates (those of the
    reference pose). Rows are NaN where the link does not turn (omega ~ 0: the
    pole is at infinity, or farther than 1e9 mechanism sizes).
    """

    link: str
    fixed: np.ndarray
    moving: np.ndarray

    @property
    def defined(self) -> np.ndarray:
        return np.isfinite(self.fixed[:, 0])

    def carried(self, sw: Sweep, kin: Kinematics, i: int) -> np.ndarray:
        """The moving centrode where the link carries it at pose i (frame coordinates)."""
        k = kin.system.index[self.link]
        th = sw.q[i, 3 * k + 2]
        c, s = math.cos(th), math.sin(th)
        rot = np.array([[c, -s], [s, c]])
        return sw.q[i, 3 * k:3 * k + 2] + self.moving @ rot.T


def centrodes(sw: Sweep, link: str, kin: Kinematics | None = None) -> Centrodes:
    """The fixed and moving centrodes of ``link``: ``W = O + perp(V_O) / omega``.

    O is the link's body point that was at the world origin in the reference
    pose (so its place and velocity are the link's coordinates q and q').
    """
    m = sw.mechanism
    kin = kin or prepare(m)
    if link not in m.link_names:
        raise InputError(f"unknown link {link!r}", where="--centrodes", file=m.source,
                         hint="choose one of the moving links: " + ", ".join(k.name for k in m.moving_links))
    if link == m.frame.name:
        raise InputError(f"link {link!r} is the frame: its centrodes are points", where="--centrodes",
                         file=m.source, hint="choose one of the moving links: "
                         + ", ".join(k.name for k in m.moving_links))
    k = kin.system.index[link]
    o = sw.q[:, 3 * k:3 * k + 2]
    th = sw.q[:, 3 * k + 2]
    vo = sw.qd[:, 3 * k:3 * k + 2]
    om = sw.qd[:, 3 * k + 2]
    perp = np.stack([-vo[:, 1], vo[:, 0]], axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = perp / om[:, None]
    far = ~(np.hypot(r[:, 0], r[:, 1]) <= 1e9 * m.size)        # omega ~ 0 (or exactly 0, or NaN)
    r[far] = np.nan
    fixed = o + r
    c, s = np.cos(th), np.sin(th)
    moving = np.stack([c * r[:, 0] + s * r[:, 1], -s * r[:, 0] + c * r[:, 1]], axis=-1)  # R(-theta) r
    return Centrodes(link, fixed, moving)


def _break_at_infinity(xy: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """A copy of a centrode with NaN rows inserted where the pole passes through infinity.

    (omega changes sign between two poses), so that a plotted line does not
    cross the figure.
    """
    rows = []
    for i in range(len(xy)):
        if i and np.sign(omega[i]) != np.sign(omega[i - 1]):
            rows.append([np.nan, np.nan])
        rows.append(xy[i])
    return np.array(rows, float).reshape(-1, 2)


# -- the CSV ---------------------------------------------------------------------------------
def cycle_columns(sw: Sweep, cen: Centrodes | None = None) -> list[tuple[str, np.ndarray]]:
    """Every quantity over the cycle as named columns (docs/sweep.md lists them).

    ``driver`` (degrees, or the slider's displacement), then for each link
    ``theta_L``, ``omega_L``, ``alpha_L``; for each point key ``x_P``, ``y_P``,
    ``vx_P``, ``vy_P``, ``ax_P``, ``ay_P``; for each slider, slot and contact its
    slip velocity and acceleration; the centrodes if given.
    """
    m = sw.mechanism
    cols = [("driver", sw.angles)]
    for lk in m.link_names:
        cols += [(f"theta_{lk}", sw.angle[lk]), (f"omega_{lk}", sw.omega[lk]), (f"alpha_{lk}", sw.alpha[lk])]
    for key in sw.position:
        p, v, a = sw.position[key], sw.velocity[key], sw.acceleration[key]
        cols += [(f"x_{key}", p[:, 0]), (f"y_{key}", p[:, 1]), (f"vx_{key}", v[:, 0]), (f"vy_{key}", v[:, 1]),
                 (f"ax_{key}", a[:, 0]), (f"ay_{key}", a[:, 1])]
    for s, r in zip(m.sliders, sw.sliders):
        tag = f"{s.point}_{s.block}/{s.guide}"
        cols += [(f"slip_velocity_{tag}", r["slip_velocity"]), (f"slip_acceleration_{tag}", r["slip_acceleration"])]
    for s, r in zip(m.slots, sw.slots):
        tag = f"{s.pin}_{s.link}/{s.slot}"
        cols += [(f"slip_velocity_{tag}", r["slip_velocity"]), (f"slip_acceleration_{tag}", r["slip_acceleration"])]
    for c, r in zip(m.contacts, sw.contacts):
        tag = f"{c.point}_{c.links[0]}/{c.links[1]}"
        cols += [(f"slip_velocity_{tag}", r["slip_velocity"]), (f"slip_acceleration_{tag}", r["slip_acceleration"])]
    if cen is not None:
        lk = cen.link
        cols += [(f"fixed_centrode_x_{lk}", cen.fixed[:, 0]), (f"fixed_centrode_y_{lk}", cen.fixed[:, 1]),
                 (f"moving_centrode_x_{lk}", cen.moving[:, 0]), (f"moving_centrode_y_{lk}", cen.moving[:, 1])]
    return cols


def _cell(x: float) -> str:
    x = float(x)
    if not math.isfinite(x):
        return ""
    if x == 0:
        return "0"
    return f"{x:.12g}"


def cycle_csv(sw: Sweep, cen: Centrodes | None = None) -> str:
    """The CSV text: a header row of column names, one row per pose; empty cells are undefined values."""
    cols = cycle_columns(sw, cen)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([name for name, _ in cols])
    data = np.column_stack([np.asarray(c, float) for _, c in cols]) if len(sw.angles) else np.zeros((0, len(cols)))
    for row in data:
        w.writerow([_cell(x) for x in row])
    return buf.getvalue()


# -- the summary table -----------------------------------------------------------------------
def _moving_keys(sw: Sweep) -> list[str]:
    """Point keys that move during the cycle (fixed points have zero speed throughout)."""
    out = []
    for key, v in sw.velocity.items():
        if np.nanmax(np.hypot(v[:, 0], v[:, 1]), initial=0.0) > 0 or np.ptp(sw.position[key], axis=0).max() > 0:
            out.append(key)
    return out


def _extremes(name: str, unit: str, values: np.ndarray, at: np.ndarray):
    good = np.isfinite(values)
    if not good.any():
        return (name, unit, "-", "-", "-", "-")
    v = np.where(good, values, np.nan)
    i, j = int(np.nanargmin(v)), int(np.nanargmax(v))
    return (name, unit, fmt(v[i]), f"{at[i]:.6g}", fmt(v[j]), f"{at[j]:.6g}")


def summary_table(sw: Sweep, points=None) -> Table:
    """Min and max of each link's omega and alpha, each point's speed and acceleration (``points``:
    point keys, default every moving point) and each slider's slip velocity over the cycle, with
    the driver positions where they occur."""
    m = sw.mechanism
    u = m.units or "units"
    at = sw.angles
    rows = []
    for k in m.moving_links:
        rows.append(_extremes(f"omega_{k.name}", "rad/s", sw.omega[k.name], at))
    for k in m.moving_links:
        rows.append(_extremes(f"alpha_{k.name}", "rad/s^2", sw.alpha[k.name], at))
    keys = list(points) if points else _moving_keys(sw)
    for key in keys:
        v = sw.velocity[key]
        rows.append(_extremes(f"|V_{key_text(key)}|", f"{u}/s", np.hypot(v[:, 0], v[:, 1]), at))
    for key in keys:
        a = sw.acceleration[key]
        rows.append(_extremes(f"|A_{key_text(key)}|", f"{u}/s^2", np.hypot(a[:, 0], a[:, 1]), at))
    for s, r in zip(m.sliders, sw.sliders):
        slip = relative(place(s.point, s.block), place(s.point, s.guide))
        rows.append(_extremes(f"slip V_{slip}", f"{u}/s", r["slip_velocity"], at))
    _, unit = driver_label(m)
    return Table(f"Over the cycle ({len(at)} poses)",
                 ("quantity", "unit", "min", f"at ({unit})", "max", f"at ({unit})"), tuple(rows))


def summary_text(sw: Sweep, points=None) -> str:
    m = sw.mechanism
    name, unit = driver_label(m)
    if len(sw.angles) > 1:
        span = f"{name} from {sw.angles[0]:.6g} to {sw.angles[-1]:.6g} {unit}"
    else:
        span = f"{name} {sw.angles[0]:.6g} {unit}"
    head = f"{m.title}\n{span}\n\n"
    return head + render_table(summary_table(sw, points), "text")


# -- progress on a terminal ------------------------------------------------------------------
class _Progress:
    """A one-line progress bar on stderr, shown only when stderr is a terminal."""

    def __init__(self, total: int, label: str, stream=None, min_total: int = 1):
        self.stream = stream or sys.stderr
        self.total = max(int(total), 1)
        self.label = label
        self.on = bool(getattr(self.stream, "isatty", lambda: False)()) and total >= min_total
        self.done = 0

    def advance(self, k: int = 1) -> None:
        if not self.on:
            return
        self.done = min(self.done + k, self.total)
        width = 30
        filled = int(width * self.done / self.total)
        self.stream.write(f"\r{self.label} [{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total}")
        self.stream.flush()

    def close(self) -> None:
        if self.on:
            self.stream.write("\n")
            self.stream.flush()


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


def _literal(text: str) -> str:
    """A text with the user's names drawn as written (no mathtext from a name): see render.canvas.literal."""
    from .render.canvas import literal
    return literal(text)


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
    from .reference import file_pose_angle
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
    from matplotlib.figure import Figure
    import matplotlib

    m = sw.mechanism
    u = m.units or "units"
    keys = list(points) if points else _moving_keys(sw)
    x = sw.angles
    xname, xunit = driver_label(m)
    n_rows = 3 if cen is not None else 2
    size = (13.3, 7.5 if cen is None else 10.5) if style == "slides" else (10.0, 6.2 if cen is None else 9.0)
    with matplotlib.rc_context(_style_rc(style)):
        fig = Figure(figsize=size, layout="constrained")
        axes = fig.subplots(n_rows, 2, squeeze=False)
        panels = [
            (axes[0, 0], "Angular velocities", r"$\omega$ (rad/s)",
             [(_quantity(r"\omega", k.name), sw.omega[k.name]) for k in m.moving_links]),
            (axes[0, 1], "Angular accelerations", r"$\alpha$ (rad/s²)",
             [(_quantity(r"\alpha", k.name), sw.alpha[k.name]) for k in m.moving_links]),
            (axes[1, 0], "Speeds", _literal(f"|V| ({unit(m.units, 1)})"),
             [(_quantity("V", k, "|"), np.hypot(*sw.velocity[k].T)) for k in keys]),
            (axes[1, 1], "Accelerations", _literal(f"|A| ({unit(m.units, 2)})"),
             [(_quantity("A", k, "|"), np.hypot(*sw.acceleration[k].T)) for k in keys]),
        ]
        drawn = drawn_pose(sw)
        for n, (ax, title, ylabel, series) in enumerate(panels):
            curves, zero = merge_series(series)
            for i, (label, y) in enumerate(curves):
                ax.plot(x, y, label=label, gid=f"curve-{i}", **_series_style(i, len(x), style))
            if zero:   # said in the legend, not drawn: a flat line on the axis tells nothing
                ax.plot([], [], linestyle="none", gid="zero-note",
                        label=", ".join(zero) + (" are" if len(zero) > 1 else " is") + " zero throughout (not drawn)")
            if drawn is not None:   # where the sheets are drawn (the file's pose)
                ax.axvline(drawn, color="0.45", linestyle=(0, (4, 2)), linewidth=0.9, zorder=1.5, gid="drawn-pose",
                           label=_literal(f"drawn pose, {xname} = {drawn:.4g} {xunit}") if n == 0 else None)
            ax.set_title(title)
            ax.set_xlabel(_literal(f"{xname} ({xunit})"))
            ax.set_ylabel(ylabel)
            ax.grid(True)
            if series or drawn is not None:
                ax.legend(fontsize="small", ncols=2 if len(curves) > 4 else 1)
            if xunit == "deg" and len(x) > 1 and abs(x[-1] - x[0]) >= 90:
                lo, hi = sorted((x[0], x[-1]))
                ax.set_xticks(np.arange(math.ceil(lo / 45) * 45, hi + 1e-9, 45))
        if cen is not None:
            _plot_centrodes(sw, cen, axes[2, 0], axes[2, 1], style, kin or prepare(m))
        title_pt = 1.2 * float(matplotlib.rcParams["font.size"])      # suptitle: "large"
        fig.suptitle(_wrapped_title(m.title, sw.stopped, size[0], title_pt))
    return fig


def _wrapped_title(title: str, stopped: str, width_in: float, font_pt: float) -> str:
    """The figure's title, and the stop message on lines of its own, wrapped to the figure's width
    (a character taken as 0.6 em wide, a safe bound for the serif and sans-serif fonts used)."""
    import textwrap
    width = max(int(width_in * 72.0 / (0.6 * font_pt)), 40)
    lines = textwrap.wrap(title, width) or [""]
    if stopped:
        lines += textwrap.wrap(f"[{stopped}]", width)
    return _literal("\n".join(lines))


def plot_cycle(sw: Sweep, out, points=None, cen: Centrodes | None = None, style: str = "textbook",
               kin: Kinematics | None = None) -> Path:
    """:func:`cycle_figure` written atomically to ``out`` (SVG, PNG or PDF by its suffix)."""
    import matplotlib
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
    fixed = _break_at_infinity(cen.fixed, om)
    moving = _break_at_infinity(cen.moving, om)
    # the mechanism at the first pose, for orientation, and the view: the mechanism's motion
    _draw_lines(ax_fixed, sw, 0, style, labels=True)
    ax_fixed.plot(fixed[:, 0], fixed[:, 1], label=_literal(f"fixed centrode of link {lk}"), **line)
    if cen.defined[0]:
        ax_fixed.plot(*cen.fixed[0], "o", color=line["color"], markersize=4,
                      label=quantity_math("P", _pole_name(m, lk)) + " at the first pose")
        carried = _break_at_infinity(cen.carried(sw, kin, 0), om)
        ax_fixed.plot(carried[:, 0], carried[:, 1], linestyle="--", color=line["color"], linewidth=0.8,
                      label="moving centrode (carried by the link)")
    _view(ax_fixed, _motion_box(sw), margin=0.35)
    ax_fixed.set_title(_literal(f"Fixed centrode of link {lk} (frame coordinates)"))
    ax_fixed.set_xlabel(_literal(f"x ({u})"))
    ax_fixed.set_ylabel(_literal(f"y ({u})"))
    ax_fixed.legend(fontsize="small")
    # the moving centrode in the link's own coordinates, with the link's outline (reference pose)
    link = m.link(lk)
    pts = np.array([m.position(p) for p in link.points])
    if len(pts) >= 2:
        ax_moving.fill(pts[:, 0], pts[:, 1], facecolor="0.85", edgecolor="black", linewidth=1.0)
    for p, xy in zip(link.points, pts):
        ax_moving.plot(*xy, "o", markerfacecolor="white", markeredgecolor="black", markersize=5)
        ax_moving.annotate(_literal(p), xy, xytext=(4, 4), textcoords="offset points")
    ax_moving.plot(moving[:, 0], moving[:, 1], label=_literal(f"moving centrode of link {lk}"), **line)
    box = _box(np.vstack([pts, cen.moving[cen.defined]]) if cen.defined.any() else pts)
    size = max(box[2] - box[0], box[3] - box[1], m.size * 0.1)
    c = pts.mean(axis=0)
    _view(ax_moving, (c[0] - size, c[1] - size, c[0] + size, c[1] + size), margin=0.0, cap=(pts, 3 * m.size))
    ax_moving.set_title(_literal(f"Moving centrode of link {lk} (its own coordinates)"))
    ax_moving.set_xlabel(_literal(f"x ({u})"))
    ax_moving.set_ylabel(_literal(f"y ({u})"))
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


def _nice(x: float) -> float:
    """The round number (1, 2 or 5 times a power of ten) at most x."""
    e = 10.0 ** math.floor(math.log10(x))
    return max(k * e for k in (1.0, 2.0, 5.0) if k * e <= x * (1 + 1e-12))


def _scale_bar(ax, unit: str) -> list:
    """A scale bar in the lower left corner of a drawing whose axes are hidden."""
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    length = _nice(0.25 * (x1 - x0))
    x, y = x0 + 0.04 * (x1 - x0), y0 + 0.05 * (y1 - y0)
    tick = 0.012 * (y1 - y0)
    out = ax.plot([x, x + length], [y, y], "-", color="black", linewidth=1.2)
    out += ax.plot([x, x, np.nan, x + length, x + length], [y - tick, y + tick, np.nan, y - tick, y + tick], "-",
                   color="black", linewidth=1.0)
    out.append(ax.annotate(_literal(f"{length:g} {unit}".strip()), (x + length / 2, y), xytext=(0, 3),
                           textcoords="offset points", ha="center", va="bottom", fontsize="small"))
    return out


def _save(fig, out: Path) -> None:
    fmt_ = out.suffix.lower().lstrip(".")
    meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}, "png": {"Software": None}}
    with atomic_path(out) as tmp:
        fig.savefig(tmp, format=fmt_, metadata=meta.get(fmt_), dpi=120 if fmt_ == "png" else None)


# -- the mechanism and its velocity polygon, one pose ---------------------------------------
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
                artists.append(ax.annotate(_literal(p), xy, xytext=(4, 4), textcoords="offset points", fontsize="small"))
    return artists


def solution_at(sw: Sweep, kin: Kinematics, i: int):
    """The :class:`velpoly.Solution` of pose i of the sweep (for the figure functions)."""
    from .motion import evaluate_motion
    from .solution import Solution
    q, qd, qdd = sw.q[i:i + 1], sw.qd[i:i + 1], sw.qdd[i:i + 1]
    mo = evaluate_motion(sw.mechanism, kin.system.index, q, qd, qdd)
    angle = None if sw.mechanism.driver.is_slider else float(sw.angles[i])
    if angle is not None:
        angle = float((angle + 180.0) % 360.0 - 180.0) or 0.0
    return Solution(sw.mechanism, kin, q[0], qd[0], qdd[0], float(sw.condition[i]), mo, angle)


def write_gif(sw: Sweep, out, kin: Kinematics | None = None, style: str = "textbook",
              cen: Centrodes | None = None, max_frames: int = GIF_FRAMES, progress: bool = True) -> Path:
    """An animated GIF of the sweep's poses (at most ``max_frames``, evenly spread) drawn by
    ``velpoly animate``'s renderer (:mod:`velpoly.render.animate`): the mechanism beside its velocity
    polygon and the live table, at GIF_SIZE pixels. With ``cen``, the fixed centrode is drawn and the
    moving centrode rides with the link."""
    from .render.animate import Animator, FramePlan, write_animation
    out = Path(out)
    m = sw.mechanism
    n = len(sw.angles)
    frames = np.unique(np.linspace(0, n - 1, min(n, max_frames)).round().astype(int))
    xname, xunit = driver_label(m)
    caption = f"{xname} from {sw.angles[frames[0]]:.4g} to {sw.angles[frames[-1]]:.4g} {xunit}" + \
        (f" [{sw.stopped}]" if sw.stopped else "")
    if sw.kinematics is None:
        sw = dataclasses.replace(sw, kinematics=kin or prepare(m))
    plan = FramePlan(m, (sw,), tuple((0, int(i)) for i in frames), np.asarray(sw.angles, float)[frames],
                     np.ones(len(frames)), None, caption, 0.0, bool(sw.stopped) or m.driver.is_slider)
    anim = Animator(plan, "velocity", style, GIF_SIZE, centrodes=(cen, sw) if cen is not None else None)
    bar = _Progress(len(frames), "velpoly sweep: GIF", min_total=2) if progress else None
    write_animation(anim, out, 1000.0 / GIF_FRAME_MS, (lambda done, total: bar.advance()) if bar else None)
    if bar:
        bar.close()
    return out


# -- the command -----------------------------------------------------------------------------
def _parse_points(sw: Sweep, text: str | None) -> list[str] | None:
    if not text:
        return None
    keys = list(sw.position)
    out = []
    for tok in (t.strip() for t in text.split(",")):
        if not tok:
            continue
        if tok in sw.position:
            found = [tok]
        else:
            found = [k for k in keys if k.split("@")[0] == tok]
        if not found:
            raise InputError(f"unknown point {tok!r}", where="--points", file=sw.mechanism.source,
                             hint="choose from: " + ", ".join(keys))
        out += [k for k in found if k not in out]
    if not out:
        raise InputError("no point given", where="--points", file=sw.mechanism.source,
                         hint="e.g. --points B,C")
    return out


def _check_suffix(path: str | None, allowed, option: str) -> Path | None:
    if not path:
        return None
    p = Path(path)
    if p.suffix.lower() not in allowed:
        raise InputError(f"unknown file type {p.suffix or '(none)'!r}", where=option, file=str(p),
                         hint="end the name with " + " or ".join(allowed))
    return p


def _toggle_links(kin: Kinematics, q_last) -> tuple[str, ...]:
    """The links moving in the near-null direction at the last reached pose (those coming into line)."""
    from .kinematics import involved_links  # the kernel's own rule, shared with its singular-pose errors
    return involved_links(kin, q_last)


def reachable_text(m: Mechanism, kin: Kinematics) -> str:
    """``reachable on this branch: LO to HI deg`` for a crank driver (absolute driver angles, to
    0.01 degree, each toggle approached from the reference pose); empty for a slider driver, whose
    stroke is the cycle."""
    if m.driver.is_slider:
        return ""
    from .solution import reachable_range
    lo, hi = reachable_range(kin)
    ref = driver_reference_angle(m)
    return f"reachable on this branch: {ref + lo:g} to {ref + hi:g} deg"


@dataclass(frozen=True)
class SweepOutcome:
    """What ``velpoly sweep`` did, for cli.py to report: ``warnings`` (lines for standard error, in
    the order found), ``written`` (the files), ``summary`` (the cycle's table when no file was asked
    for, else "")."""

    warnings: tuple
    written: tuple
    summary: str


def sweep_command(args) -> SweepOutcome:
    """``velpoly sweep FILE [--step DEG] [-o OUT] [--csv CSV] [--points P,Q] [--centrodes LINK]
    [--gif GIF] [--style]``: see docs/sweep.md."""
    from . import load
    plot_out = _check_suffix(getattr(args, "output", None), FIGURE_SUFFIXES, "-o")
    gif_out = _check_suffix(getattr(args, "gif", None), (".gif",), "--gif")
    csv_out = Path(args.csv) if getattr(args, "csv", None) else None
    style = getattr(args, "style", "textbook") or "textbook"
    step = _check_step(getattr(args, "step", 1.0))
    m = load(args.file)
    kin = prepare(m)
    poses = max(int(math.ceil(360.0 / step - 1e-9)), 1)   # as cycle_angles: a turn, or each half-stroke
    check_memory(m, kin, poses, where="--step",
                 hint=f"use a coarser --step: {360 * memory_estimate(m, kin, poses) / poses / MEMORY_BUDGET:.2g} "
                      "deg or more for this mechanism")
    long = 360.0 / step >= 2000 or gif_out is not None or m.driver.is_slider
    bar = _Progress(1, "velpoly sweep: solving", min_total=1 if long else 10 ** 9)
    bar.advance(0)
    sw = run_cycle(m, step, kin)
    bar.advance()
    bar.close()
    if len(sw.angles) < 2 and sw.leaves is not None:
        sl = next(s for s in m.slots if s.pin == sw.leaves[0] and s.slot == sw.leaves[1])
        raise PoseError(f"cannot sweep: {len(sw.angles)} pose(s) reachable from the reference pose ({sw.stopped})",
                        where="driver", file=m.source, links=(sl.link, sl.slot),
                        hint="draw the pin inside its slot, away from the slot's ends")
    if len(sw.angles) < 2:
        links = _toggle_links(kin, sw.q[-1] if len(sw.q) else np.zeros(kin.system.nq))
        reach = reachable_text(m, kin)
        raise PoseError(f"cannot sweep: {len(sw.angles)} pose(s) reachable from the reference pose"
                        + (f" ({sw.stopped})" if sw.stopped else "") + (f"; {reach}" if reach else ""),
                        where="driver", file=m.source,
                        links=links, hint="links " + ", ".join(links) + " come into line: draw the mechanism "
                        "in a pose away from the toggle")
    warnings = []
    if sw.stopped and sw.leaves is not None:
        reach = reachable_text(m, kin).replace("reachable on this branch:", "the pin is in its slot from")
        warnings.append(f"warning: {m.source}: {sw.stopped}" + (f"; {reach}" if reach else "") +
                        "; the outputs hold the part before")
    elif sw.stopped:
        links = _toggle_links(kin, sw.q[-1])
        reach = reachable_text(m, kin)
        warnings.append(f"warning: {m.source}: {sw.stopped} (links {', '.join(links)} come into line); "
                        + (f"{reach}; " if reach else "") + "the outputs hold the reachable part")
    points = _parse_points(sw, getattr(args, "points", None))
    cen = None
    if getattr(args, "centrodes", None):
        cen = centrodes(sw, str(args.centrodes), kin)
        if not cen.defined.any():
            warnings.append(f"warning: {m.source}: link {cen.link} does not turn: its pole with the frame "
                            f"stays at infinity, no centrode")
    written = []
    if csv_out:
        written.append(atomic_write_text(csv_out, cycle_csv(sw, cen)))
    if plot_out:
        written.append(plot_cycle(sw, plot_out, points, cen, style, kin))
    if gif_out:
        written.append(write_gif(sw, gif_out, kin, style, cen))
    summary = ""
    if not written:
        summary = summary_text(sw, points)
        if cen is not None:
            warnings.append("note: the centrodes are drawn with -o or --gif and listed with --csv")
    return SweepOutcome(tuple(warnings), tuple(written), summary)
