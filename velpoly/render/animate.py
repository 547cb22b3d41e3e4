"""Animations of the motion with its polygons: ``velpoly animate`` (and ``velpoly sweep --gif``).

A frame shows the mechanism at the frame's driver angle beside the chosen
sheet's panels (the velocity polygon by default, the acceleration polygon,
both, or the instant centres on the mechanism), a live table of the driver's
position, each link's omega (alpha) and each point's speed (acceleration),
and the traced path of every coupler point, faint.

**The motion** (:func:`plan_frames`). A crank that turns round: one frame
every ``step`` degrees over a full turn, in the sense of its omega (the
closing pose, the first again, left out, so that the file loops smoothly).
A crank that cannot turn round (a toggle on either side) rocks: it runs from
one end of its reachable range to the other and back, never across a toggle,
each end kept ``step / 2`` short of it; on the way back the driver turns the
other way (omega reversed: the time-reversed motion, so every velocity is
reversed and every acceleration is the same). A slider driver runs its
stroke out and back likewise. Each frame says which way the driver turns and
the caption says the range: "rocks between -40.2° and 61.3°".

**Fixed for the whole animation.** The layout, each panel's scale (chosen so
that the panel is filled at its largest frame, with one exception: where the
frames come close to a toggle (a rocking crank, a slider's stroke, a sweep
stopped at a toggle), the frames within the toggle's surge, whose largest
vector is more than ``SURGE`` times the median frame's, are left out of it
rather than shrink every other frame's polygon to a dot: such a frame is drawn
at 1/2, 1/5, 1/10 ... of the scale, saying so, :func:`reduction`) and the scale bars.

**Fast.** The poses come from the vectorised sweep (:func:`velpoly.sweep`),
the polygons of each pose from :mod:`velpoly.polygons` (under a millisecond
a pose); one figure is built, its still parts drawn once, and each frame
only moves the artists that move (positions, arrow ends, label positions,
table values) and draws them over the still background (blitting). The
frames stream into the file one at a time (GIF and animated PNG are written
by this module chunk by chunk, each frame cropped to the region that
changed), so memory does not grow with the number of frames.

Formats by the output's suffix: ``.gif``, ``.png`` (animated PNG), ``.mp4``
(needs the optional ``imageio-ffmpeg``: ``pip install velpoly[video]``),
``.pdf`` (one page a frame, vector, for LaTeX's animate package).
"""
from __future__ import annotations

import dataclasses
import io
import math
import struct
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, PoseError
from ..tables import zero_floor
from .canvas import literal

__all__ = ["FramePlan", "mp4_writer", "plan_frames", "Animator", "write_animation", "FORMATS", "SHEETS", "SURGE",
           "DEFAULT_SIZE", "parse_size", "gallery_animation"]

SHEETS = ("velocity", "acceleration", "poles", "full")
FORMATS = (".gif", ".png", ".mp4", ".pdf")
DEFAULT_SIZE = (1920, 1080)
LEGEND_GAP = 12.0     # px (of a 1080 px frame) between the acceleration legend and the polygon's highest point
LEGEND_ROOM = 0.5     # the polygon keeps at least this share of its panel's height, whatever the legend's
SURGE = 4.0           # frames whose largest vector exceeds this times the median frame's: left out of the scale
MIN_SIZE = (320, 180)
MAX_SIZE = (7680, 4320)


# -- the motion ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class FramePlan:
    """The poses of an animation, in the order shown.

    ``legs``: one or two :class:`velpoly.Sweep` (out, and back with the driver
    reversed); ``frames``: ``(leg, index)`` per frame; ``angles``: each frame's
    driver position (degrees, or a slider's displacement); ``sense``: +1 where
    the driver moves as the file says, -1 on the way back; ``rocks``: the range
    ``(lo, hi)`` of a rocking crank or a slider's stroke (absolute), None for a
    full turn; ``caption``: what the motion is, in words.
    """

    mechanism: object
    legs: tuple
    frames: tuple
    angles: np.ndarray
    sense: np.ndarray
    rocks: tuple | None
    caption: str
    step: float
    near_toggle: bool = False    # the frames come close to a toggle (a rocking crank, a stroke's ends, a stopped sweep)

    def __len__(self) -> int:
        return len(self.frames)

    def solution(self, k: int):
        """The :class:`velpoly.Solution` of frame k (the reversed driver on the way back)."""
        from ..sweeps import solution_at
        leg, i = self.frames[k]
        sw = self.legs[leg]
        return solution_at(sw, sw.kinematics, i)

    def series(self, attr: str) -> dict:
        """``position``, ``velocity``, ``acceleration`` (key -> (N, 2)) or ``omega``, ``alpha``, ``angle``
        (link -> (N,)) over the frames, in frame order."""
        legs = [getattr(sw, attr) for sw in self.legs]
        out = {}
        for key in legs[0]:
            parts = [np.asarray(d[key])[[i for l_, i in self.frames if l_ == j]] for j, d in enumerate(legs)]
            out[key] = np.concatenate(parts)
        return out

    def rows(self, attr: str) -> list:
        """``sliders``, ``slots``, ``contacts``: per item a dict of arrays over the frames."""
        out = []
        for j, item in enumerate(self.legs[0].__getattribute__(attr)):
            d = {}
            for key in item:
                parts = [np.asarray(sw.__getattribute__(attr)[j][key])[[i for l_, i in self.frames if l_ == n]]
                         for n, sw in enumerate(self.legs)]
                d[key] = np.concatenate(parts)
            out.append(d)
        return out


def _reversed(m):
    """The mechanism with its driver turning (sliding) the other way: the time-reversed motion."""
    d = m.driver
    d = dataclasses.replace(d, speed=-d.speed) if d.is_slider else dataclasses.replace(d, omega=-d.omega)
    return dataclasses.replace(m, driver=d)


def _check_step(step) -> float:
    try:
        step = float(step)
    except (TypeError, ValueError):
        step = float("nan")
    if not math.isfinite(step) or step < 0.05 or step > 90:
        raise InputError(f"the step must be a number of degrees in [0.05, 90], got {step:g}", where="--step",
                         hint="e.g. --step 2 (180 frames a turn) or --step 5 (72 frames)")
    return step


def _grid(lo: float, hi: float, step: float) -> np.ndarray:
    """Positions from lo to hi, both included, at most ``step`` apart, evenly spread."""
    n = max(int(math.ceil((hi - lo) / step - 1e-9)), 1)
    return np.linspace(lo, hi, n + 1)


def plan_frames(m, step: float = 2.0) -> FramePlan:
    """The frames of ``m``'s animation (see the module's docstring); raises PoseError when fewer than two
    poses can be reached."""
    from ..driver import driver_label, driver_reference_angle, reachable_range
    from ..sweeps import cycle_angles, run_cycle
    from ..kinematics import prepare
    from ..sweeps import sweep
    from .table import position_text
    step = _check_step(step)
    kin = prepare(m)
    drv = m.driver
    if not drv.is_slider:
        turn = cycle_angles(m, step, kin)
        sw = sweep(m, turn, kin)
        if not sw.stopped and len(sw.angles) == len(turn):
            sense = "counter-clockwise" if drv.omega >= 0 else "clockwise"
            cap = f"full turn of link {drv.link} ({sense}), {step:g}° a frame"
            return FramePlan(m, (sw,), tuple((0, i) for i in range(len(turn))), np.asarray(sw.angles, float),
                             np.ones(len(turn)), None, cap, step)
        ref = driver_reference_angle(m)
        lo, hi = reachable_range(kin)
        lo, hi = ref + lo, ref + hi
        margin = min(step / 2, (hi - lo) / 8)
        span = (lo + margin, hi - margin)
        unit, what = "°", f"link {drv.link} rocks between {_deg(lo)} and {_deg(hi)} (a toggle at each end)"
    else:
        full = run_cycle(m, step, kin)
        if len(full.angles) < 2:
            raise PoseError("cannot animate: the slider cannot move from its reference position on this branch",
                            where="driver", file=m.source, hint="draw the mechanism away from the toggle")
        lo, hi = float(full.angles[0]), float(full.angles[-1])
        span = (lo, hi)
        unit = f" {m.units}" if m.units else ""
        what = f"slider {drv.slider} runs between {position_text(m, lo)}{unit} and {position_text(m, hi)}{unit} and back"
    if not span[1] > span[0]:
        raise PoseError("cannot animate: the driver cannot move on this branch without crossing a toggle",
                        where="driver", file=m.source, links=(),
                        hint="draw the mechanism in a pose away from the toggle")
    if drv.is_slider:
        h = (span[1] - span[0]) / max(int(math.ceil(360.0 / step - 1e-9)), 1)
    else:
        h = step
    grid = _grid(span[0], span[1], h)
    forward = (drv.speed if drv.is_slider else drv.omega) >= 0
    out = grid if forward else grid[::-1]
    back = out[::-1][1:-1]
    start = 0.0 if drv.is_slider else driver_reference_angle(m)
    w_out = _leg(m, kin, start, out, h)
    mr = _reversed(m)
    w_back = _leg(mr, prepare(mr), start, back, h)
    n_out, n_back = len(w_out.angles), len(w_back.angles)
    if n_out < len(out) or n_back < len(back):    # a toggle inside the range found: should not happen
        raise PoseError("cannot animate: a toggle inside the reachable range", where="driver", file=m.source,
                        hint="draw the mechanism in a pose away from the toggle")
    frames = tuple((0, i) for i in range(n_out)) + tuple((1, i) for i in range(n_back))
    angles = np.concatenate([w_out.angles, w_back.angles])
    sense = np.concatenate([np.ones(n_out), -np.ones(n_back)])
    name, _ = driver_label(m)
    cap = f"{what}: out and back, the driver reversed on the way back"
    return FramePlan(m, (w_out, w_back), frames, angles, sense, (lo, hi), cap, step, True)


def _leg(m, kin, start: float, positions, h: float):
    """The sweep of ``positions`` (in order), reached from the reference position ``start`` by walking
    there in steps of at most ``h`` (a range wider than half a turn is not crossed the shorter way round,
    through its toggle); the walk's own poses are left out."""
    from ..sweeps import sweep
    positions = np.asarray(positions, float)
    if not len(positions):
        return _take(sweep(m, [start], kin), np.arange(0))
    n = max(int(math.ceil(abs(positions[0] - start) / h - 1e-9)), 1)
    walk = np.linspace(start, positions[0], n + 1)[:-1]
    sw = sweep(m, np.concatenate([walk, positions]), kin)
    reached = len(sw.angles) - len(walk)
    return _take(sw, np.arange(len(walk), len(walk) + max(reached, 0)))


def _take(sw, idx):
    """The sweep's poses ``idx`` (any order), as a Sweep."""
    idx = np.asarray(idx, int)

    def pick(a):
        if isinstance(a, dict):
            return {k: pick(v) for k, v in a.items()}
        if isinstance(a, list):
            return [pick(x) for x in a]
        return np.asarray(a)[idx]
    kw = {}
    for f in dataclasses.fields(sw):
        v = getattr(sw, f.name)
        if f.name in ("mechanism", "stopped", "leaves", "kinematics"):
            kw[f.name] = v
        elif f.name == "known_condition":
            kw[f.name] = None if v is None else np.asarray(v)[idx]
        else:
            kw[f.name] = pick(v)
    if kw.get("kinematics") is None:
        from ..kinematics import prepare
        kw["kinematics"] = prepare(sw.mechanism)
    return type(sw)(**kw)


def _deg(x: float) -> str:
    return f"{x:.1f}°".replace("-", "−")


def parse_size(text) -> tuple[int, int]:
    """``"1920x1080"`` -> (1920, 1080); InputError naming ``--size`` otherwise."""
    import re
    mo = re.fullmatch(r"([0-9]+)[xX×]([0-9]+)", str(text))   # plain ASCII digits, as FORMAT.md writes numbers
    if not mo:
        raise InputError(f"expected WIDTHxHEIGHT in pixels, got {text!r}", where="--size",
                         hint="e.g. --size 1920x1080 or --size 1280x720")
    w, h = int(mo.group(1)), int(mo.group(2))
    if not (MIN_SIZE[0] <= w <= MAX_SIZE[0] and MIN_SIZE[1] <= h <= MAX_SIZE[1]):
        raise InputError(f"the size {w}x{h} is outside {MIN_SIZE[0]}x{MIN_SIZE[1]} to {MAX_SIZE[0]}x{MAX_SIZE[1]}",
                         where="--size", hint="e.g. --size 1920x1080 or --size 1280x720")
    return w, h


# -- what each panel shows, over the frames -------------------------------------------------------------
def _box(pts) -> tuple:
    p = np.asarray(pts, float).reshape(-1, 2)
    p = p[np.isfinite(p).all(axis=1)]
    if not len(p):
        return (-1.0, -1.0, 1.0, 1.0)
    return (*p.min(axis=0), *p.max(axis=0))


def _surge_box(per_frame: list) -> tuple:
    """The box of the frames' points (each frame's an (n, 2) array, the origin included), leaving out the
    frames whose farthest point from the origin exceeds SURGE times the median frame's."""
    reach = np.array([float(np.nanmax(np.hypot(*p.T), initial=0.0)) for p in per_frame])
    keep = reach <= SURGE * np.median(reach) + 1e-300
    pts = [p for p, k in zip(per_frame, keep) if k]
    return _box(np.vstack(pts + [np.zeros((1, 2))]))


def reduction(points, limits: tuple) -> int:
    """The divisor n of the panel's scale at which a frame's polygon (its ``points``: images and vector ends, the
    origin O_v at (0, 0)) is drawn, at 1/n of it: 1 where it lies within the panel's ``limits`` (x0, x1, y0, y1,
    about the origin), else the least of 2, 5, 10, 20, 50 ... that brings it within 93 % of them (the 7 % margin of
    the panel's fit): near a toggle the speeds surge without bound, and such a frame is left out of the scale
    (:func:`_surge_box`)."""
    p = np.asarray(points, float).reshape(-1, 2)
    p = p[np.isfinite(p).all(axis=1)]
    x0, x1, y0, y1 = limits
    if not len(p) or (np.all((x0 <= p[:, 0]) & (p[:, 0] <= x1)) and np.all((y0 <= p[:, 1]) & (p[:, 1] <= y1))):
        return 1
    with np.errstate(divide="ignore", invalid="ignore"):   # the largest factor that keeps each coordinate within
        room = np.concatenate([np.where(p[:, 0] > 0, x1 / p[:, 0], np.where(p[:, 0] < 0, x0 / p[:, 0], np.inf)),
                               np.where(p[:, 1] > 0, y1 / p[:, 1], np.where(p[:, 1] < 0, y0 / p[:, 1], np.inf))])
    most = 0.93 * float(room.min())
    n = 1
    while most > 0 and 1.0 / n > most:
        n = n * 5 // 2 if str(n)[0] == "2" else n * 2   # 2, 5, 10, 20, 50 ...
    return n


def _polygon_points(poly) -> np.ndarray:
    pts = [np.zeros(2)] + [np.asarray(v, float) for v in poly.images.values()]
    for st in poly.steps:
        for v in st.vectors:
            pts += [np.asarray(v.tail, float), np.asarray(v.head, float)]
    return np.array(pts)


def _coupler_keys(m, keys) -> list:
    """Point keys on links not pinned to the frame (whose paths are not circles about a pivot) that
    no link pinned to the frame carries: the coupler points whose paths are traced."""
    frame = m.frame.name
    grounded = {lk for pin in m.pins if frame in pin.links for lk in pin.links if lk != frame}
    out = []
    for key in keys:
        p = key.split("@")[0]
        carriers = set(m.carriers.get(p, ()))
        if frame in carriers or carriers & grounded or not carriers:
            continue
        if any(s.point == p and s.guide == frame for s in m.sliders):   # a block on a frame guide: a line
            continue
        out.append(key)
    return out


def _name_tex(symbol: str, index: str, bars: bool = False) -> str:
    """``omega`` and ``3`` -> $\\omega_{3}$; ``V``, ``B`` with bars -> $|V_{B}|$; ``P@3`` -> P_{3}, ``P@cam``
    -> P with the subscript cam (:mod:`velpoly.names`; a user's name drawn as written)."""
    from ..names import key_text, quantity_math
    return quantity_math(symbol, index if symbol in ("omega", "alpha", "theta") else key_text(index), bars)


# -- the figure ----------------------------------------------------------------------------------------
_LAYOUTS = {   # fractions of the figure: panels, then the table's column
    "velocity": {"mechanism": (0.01, 0.04, 0.44, 0.80), "velocity": (0.46, 0.04, 0.33, 0.80)},
    "acceleration": {"mechanism": (0.01, 0.04, 0.44, 0.80), "acceleration": (0.46, 0.04, 0.33, 0.80)},
    "poles": {"mechanism": (0.01, 0.04, 0.78, 0.80)},
    "full": {"mechanism": (0.01, 0.04, 0.33, 0.80), "velocity": (0.35, 0.04, 0.215, 0.80),
             "acceleration": (0.575, 0.04, 0.215, 0.80)},
}
_TABLE = (0.805, 0.04, 0.185, 0.80)
_CAPTIONS = {"mechanism": "Space diagram", "velocity": "Velocity polygon", "acceleration": "Acceleration polygon"}


TYPE_FLOOR = 0.55    # below 1080 rows, sizes shrink with the height down to this fraction, no further


def _type_factor(fig_h_px: float) -> float:
    return max(fig_h_px / 1080.0, TYPE_FLOOR)


def _px(size_px: float, fig_h_px: float, dpi: float) -> float:
    """Points for a size of ``size_px`` pixels at 1080 rows, at the figure's height (never below
    TYPE_FLOOR of it, so that a small animation stays legible) and dpi."""
    return size_px * _type_factor(fig_h_px) * 72.0 / dpi


class Animator:
    """One figure, its still background drawn once, and the moving artists updated frame by frame.

    ``render(k)`` returns frame k as an (H, W, 3) uint8 array; ``draw_vector(k)``
    moves the artists to frame k and leaves the whole figure drawable (for a
    vector PDF page). The artists' data are the frame's: ``self.points[key]``
    (Line2D of the pins and points), ``self.images[kind][key]`` (the polygon
    arrows' tips), read back in the tests.
    """

    def __init__(self, plan: FramePlan, sheet: str = "velocity", style: str = "slides",
                 size: tuple[int, int] = DEFAULT_SIZE, centrodes=None):
        from matplotlib.figure import Figure
        from .style import get_style, rc_context
        from .textcache import new_canvas
        from .options import drawing_options
        if sheet not in SHEETS:
            raise InputError(f"unknown sheet {sheet!r}; valid sheets: " + ", ".join(SHEETS), where="--sheet")
        self.plan, self.sheet, self.size = plan, sheet, tuple(int(v) for v in size)
        self.st = st = get_style(style)
        self.m = m = plan.mechanism
        self.opts = drawing_options(m)
        self.n = len(plan)
        self.sols = [plan.solution(k) for k in range(self.n)]
        self.pos = plan.series("position")
        self.vel = plan.series("velocity")
        self.acc = plan.series("acceleration")
        self.omega = plan.series("omega")
        self.alpha = plan.series("alpha")
        self.slider_rows = plan.rows("sliders")
        self.slot_rows = plan.rows("slots")
        self.contact_rows = plan.rows("contacts")
        self.centrodes = centrodes
        has_acc = all(s.has_accelerations for s in self.sols[:1])
        if sheet == "acceleration" and not has_acc:
            from ..polygons import acceleration_polygon
            acceleration_polygon(self.sols[0])     # raises the InputError saying centres are needed
        self.kinds = {"velocity": sheet in ("velocity", "full"),
                      "acceleration": sheet == "acceleration" or (sheet == "full" and has_acc)}
        self.polys = {}
        if self.kinds["velocity"]:
            from ..polygons import velocity_polygon
            self.polys["velocity"] = [velocity_polygon(s) for s in self.sols]
        if self.kinds["acceleration"]:
            from ..polygons import acceleration_polygon
            self.polys["acceleration"] = [acceleration_polygon(s) for s in self.sols]
        self.poles = None
        if sheet == "poles":
            from ..poles import locate_poles
            self.poles = [locate_poles(s) for s in self.sols]
        w, h = self.size
        self.dpi = w / 16.0
        self._rc = rc_context(st)
        self._rc.__enter__()
        try:
            self.fig = Figure(figsize=(16.0, h / self.dpi), dpi=self.dpi)
            self.fig.patch.set_facecolor(st.paper)
            new_canvas(self.fig)   # (Agg, its text kept: velpoly.render.textcache)
            self.moving: list = []           # (axes or None, artist) drawn every frame
            self.texts: list = []            # (axes or None, Text) moving texts, pasted as sprites
            self._sprites: dict = {}
            self.points, self.images, self.values = {}, {}, {}
            self.band = {}                   # panel name -> the band (data units) kept free at its top (the legend's)
            self._build()
            self.canvas = self.fig.canvas
            self.canvas.draw()
            self.background = self.canvas.copy_from_bbox(self.fig.bbox)
        finally:
            self._rc.__exit__(None, None, None)

    # -- sizes ---------------------------------------------------------------------------------
    def pt(self, px: float) -> float:
        return _px(px, self.size[1], self.dpi)

    def _move(self, artist, ax=None):
        from matplotlib.text import Text
        artist.set_animated(True)
        if isinstance(artist, Text):     # drawn as a ready-made picture (a sprite) in raster frames
            self.texts.append((ax, artist))
        else:
            self.moving.append((ax, artist))
        return artist

    # -- building ------------------------------------------------------------------------------
    def _build(self) -> None:
        from .sheet import fit_width, equation_tex
        fig, st = self.fig, self.st
        layout = dict(_LAYOUTS[self.sheet])
        if self.sheet == "full" and not self.kinds["acceleration"]:
            layout = dict(_LAYOUTS["velocity"])
        title = fig.text(0.01, 0.975, equation_tex(self.m.title), ha="left", va="top", fontsize=self.pt(30),
                         fontweight="bold" if st.name == "slides" else "normal")
        fit_width(fig, title, 0.98, smallest=0.6)         # a long title shrinks to the frame's width
        cap = fig.text(0.01, 0.925, self._caption(), ha="left", va="top", fontsize=self.pt(20), color="0.3",
                       fontstyle="italic")
        fit_width(fig, cap, 0.98, smallest=0.7)
        self.axes = {}
        for name, rect in self._layout(layout).items():
            ax = fig.add_axes(rect, label=name)
            ax.set_axis_off()
            self.axes[name] = ax
            cap = _CAPTIONS.get(name, "")
            if self.sheet == "poles" and name == "mechanism":
                cap = "Instant centres on the space diagram"
            fig.text(rect[0] + rect[2] / 2, rect[1] + rect[3] + 0.008, cap, ha="center", va="bottom",
                     fontsize=self.pt(22), fontstyle="italic")
        self._mechanism(self.axes["mechanism"])
        for kind in ("velocity", "acceleration"):
            if kind in self.axes:
                self._polygon(self.axes[kind], kind)
        if self.poles is not None:
            self._poles(self.axes["mechanism"])
        self._table()

    def _boxes(self) -> dict:
        """Each panel's box over the whole animation (data coordinates)."""
        m = self.m
        pts = [p for p in self.pos.values()]
        for ci, c in enumerate(m.contacts):      # the contacts' profiles (circles small enough to draw whole)
            for lk, cn in zip(c.links, c.centres or ()):
                key = cn if cn in self.pos else f"{cn}@{lk}"
                if cn is None or key not in self.pos:
                    continue
                ctr = self.pos[key]
                rad = np.hypot(*(np.asarray(self.contact_rows[ci]["place"], float) - ctr).T)
                small = rad < 1.5 * m.size
                pts += [ctr[small] - rad[small, None], ctr[small] + rad[small, None]]
        pts = np.vstack(pts)
        box = _box(pts)
        if self.poles is not None:      # the poles near the mechanism: the view grown to hold them
            c = np.array([(box[0] + box[2]) / 2, (box[1] + box[3]) / 2])
            near = [p.position for ps in self.poles for p in ps.poles.values()
                    if p.position is not None and float(np.hypot(*(p.position - c))) <= 1.2 * m.size]
            if near:
                box = _box(np.vstack([pts, np.array(near)]))
        out = {"mechanism": box}
        for kind, polys in self.polys.items():
            pts = [_polygon_points(p) for p in polys]
            out[kind] = _surge_box(pts) if self.plan.near_toggle else _box(np.vstack(pts))
        return out

    def _layout(self, layout: dict) -> dict:
        """The panels in columns (the full sheet: the mechanism, then the two polygons one above the
        other), each column as wide as its boxes' shapes ask at their height (the widths shared out in that
        proportion), so that every panel is filled alike."""
        boxes = self.boxes = self._boxes()
        names = list(layout)
        columns = [["mechanism"], [n for n in names if n != "mechanism"]] if len(names) == 3 else [[n] for n in names]
        left, right, gap = 0.01, 0.79, 0.015
        bottom, height = 0.04, 0.80
        w_in, h_in = 16.0, self.size[1] / self.dpi
        need = []
        for col in columns:
            h = (height - 0.05 * (len(col) - 1)) / len(col)
            asp = []
            for n in col:
                x0, y0, x1, y1 = boxes[n]
                a = (x1 - x0) / max(y1 - y0, 1e-300 * max(abs(x1), 1.0))
                asp.append(min(max(a, 0.45), 3.0) * h * h_in / w_in)
            need.append((max(asp), h))
        avail = right - left - gap * (len(columns) - 1)
        total = sum(a for a, _ in need)
        shares = [a / total for a, _ in need]
        if len(shares) == 2:      # the polygons matter as much as the mechanism: neither under a third
            shares = [min(max(f, 0.36), 0.64) for f in shares]
        out, x = {}, left
        for col, (a, h), f in zip(columns, need, shares):
            w = avail * f
            for i, n in enumerate(col):
                out[n] = (x, bottom + (len(col) - 1 - i) * (h + 0.05), w, h)
            x += w + gap
        return out

    def _fit(self, ax, box, margin: float, top: float = 0.0) -> float:
        """Equal-aspect limits showing ``box`` as large as the panel allows (an exact scale, not a round
        one: the scale bar shows a round length), below a band ``top`` cm high kept free at the panel's top
        (the legend's); return the scale (units per cm)."""
        from .canvas import fit_view
        pos = ax.get_position()
        wcm = pos.width * 16.0 * 2.54
        hcm = pos.height * self.size[1] / self.dpi * 2.54
        x0, y0, x1, y1 = box
        usable = 1.0 - 2 * margin
        room = max(hcm * usable - top, LEGEND_ROOM * hcm * usable)   # a small animation's legend: half at most
        need = max((x1 - x0) / (wcm * usable), (y1 - y0) / room)
        if not (math.isfinite(need) and need > 0):
            self.band[ax.get_label()] = 0.0
            return fit_view(ax, box, scale=None, margin=margin)
        # the box grown upward by the band, centred: the band lies between the box and the panel's top
        band = min(top, hcm * usable - (y1 - y0) / need) * need
        self.band[ax.get_label()] = band   # (data units)
        return fit_view(ax, (x0, y0, x1, y1 + band), scale=need, margin=margin)

    def _caption(self) -> str:
        caption = literal(self.plan.caption)   # it names the driver (a user's name, drawn as written)
        return caption.replace("-", "−") if self.plan.rocks else caption

    # -- the space diagram -----------------------------------------------------------------------
    def _mechanism(self, ax) -> None:
        """The space diagram's panel: the still ground, guides and paths, and the moving parts (moved by
        :meth:`update`)."""
        self.mech_scale = self._fit(ax, self.boxes["mechanism"], margin=0.09)
        self._ground(ax)
        self._guides(ax)
        self._paths(ax)
        self._moving_parts(ax)
        self._pins_and_labels(ax)
        self._scale_bar(ax, 0)

    def _ground(self, ax) -> None:
        from matplotlib.lines import Line2D
        from matplotlib.patches import Polygon as MPolygon
        from .canvas import per_point
        m, st = self.m, self.st
        pp = per_point(ax)
        self.pp = pp
        # the ground: a hatched base under each frame pivot (still)
        frame = m.frame.name
        pivots = [pin.point for pin in m.pins if frame in pin.links]
        self.pivots = set(pivots)
        for p in dict.fromkeys(pivots):
            key = p if p in self.pos else f"{p}@{frame}"
            if key not in self.pos:
                continue
            xy = self.pos[key][0]
            s = 7.0 * pp * self.pt(1.0) / 0.6
            tri = MPolygon([xy, xy + [-s, -1.6 * s], xy + [s, -1.6 * s]], closed=True, facecolor=st.paper,
                           edgecolor=st.ink, lw=st.link_lw, zorder=2)
            ax.add_patch(tri)
            base = xy[1] - 1.6 * s
            ax.add_line(Line2D([xy[0] - 1.6 * s, xy[0] + 1.6 * s], [base, base], color=st.ink, lw=st.link_lw,
                               zorder=2))
            xs = np.linspace(xy[0] - 1.4 * s, xy[0] + 1.4 * s, 6)
            for x in xs:
                ax.add_line(Line2D([x, x - 0.6 * s], [base, base - 0.7 * s], color=st.ink, lw=st.thin_lw, zorder=2))

    def _guides(self, ax) -> None:
        from matplotlib.lines import Line2D
        from .canvas import per_cm
        m, st = self.m, self.st
        frame = m.frame.name
        pc = per_cm(ax)
        # frame guides of sliders: a line along the block's travel (still)
        for s, r in zip(m.sliders, self.slider_rows):
            if s.guide != frame or s.centre is not None:
                continue
            key = s.point if s.point in self.pos else f"{s.point}@{s.block}"
            p = self.pos[key]
            d = math.radians(float(r["direction"][0]))
            u = np.array([math.cos(d), math.sin(d)])
            t = p @ u
            L = st.block[0] * pc
            a = p[int(np.argmin(t))] - u * 1.2 * L
            b = p[int(np.argmax(t))] + u * 1.2 * L
            n = np.array([-u[1], u[0]])
            off = -n * st.block[1] * pc / 2
            ax.add_line(Line2D([a[0] + off[0], b[0] + off[0]], [a[1] + off[1], b[1] + off[1]], color=st.ink,
                               lw=st.link_lw, zorder=1.5))
            ax.add_line(Line2D([a[0], b[0]], [a[1], b[1]], color=st.ink, lw=st.thin_lw, zorder=1.4,
                               linestyle=(0, (8, 2, 1.5, 2))))
            k = max(int(np.hypot(*(b - a)) / (0.25 * pc)), 2)
            for f in np.linspace(0, 1, k):
                q = a + (b - a) * f + off
                e = q - n * 0.2 * pc - u * 0.15 * pc
                ax.add_line(Line2D([q[0], e[0]], [q[1], e[1]], color=st.ink, lw=st.thin_lw, zorder=1.5))

    def _paths(self, ax) -> None:
        from matplotlib.lines import Line2D
        m, st = self.m, self.st
        # traced paths of the coupler points (still, faint)
        for key in _coupler_keys(m, self.pos):
            xy = self.pos[key]
            closed = np.vstack([xy, xy[:1]]) if self.plan.rocks is None else xy
            ax.add_line(Line2D(closed[:, 0], closed[:, 1], color=st.palette[2] if st.coloured else "0.55",
                               lw=self.pt(2.0), alpha=0.45, zorder=1.2, gid=f"path-{key}"))
        # centrodes (the sweep's GIF): the fixed one still, the moving one carried
        self._centrode = None
        if self.centrodes is not None and self.centrodes[0].defined.any():
            from ..centrodes import break_at_infinity
            cen, sw = self.centrodes
            fixed = break_at_infinity(cen.fixed, sw.omega[cen.link])
            ax.add_line(Line2D(fixed[:, 0], fixed[:, 1], color="0.35", lw=self.pt(1.5), zorder=1.3))
            self._centrode = self._move(Line2D([], [], color="0.35", lw=self.pt(1.5), linestyle="--", zorder=1.3),
                                        ax)
            ax.add_line(self._centrode)

    def _moving_parts(self, ax) -> None:
        from matplotlib.patches import Circle, PathPatch, Polygon as MPolygon
        from matplotlib.lines import Line2D
        from .canvas import per_cm
        from .style import link_colour, link_fill
        m, st = self.m, self.st
        pc = per_cm(ax)
        # the moving parts
        self.bw = st.bar_width * pc
        self.bodies = {}
        tracked = {s.slot for s in m.slots} | {s.guide for s in m.sliders}
        crank = None if m.driver.is_slider or m.driver.link in tracked else m.driver.link
        for z, link in enumerate(m.moving_links):
            if len(link.points) < 2:
                continue
            colour = link_colour(m, self.opts, st, link.name)
            z = len(m.moving_links) if link.name == crank else z     # the crank over the links it drives
            patch = PathPatch(_empty_path(), facecolor=link_fill(m, self.opts, st, link.name),
                              edgecolor=colour if st.coloured else st.ink, lw=st.link_lw * 1.4, zorder=3 + 0.01 * z)
            ax.add_patch(patch)
            self.bodies[link.name] = self._move(patch, ax)
        self.blocks = {}
        for s in m.sliders:
            patch = MPolygon(np.zeros((4, 2)), closed=True, facecolor=link_fill(m, self.opts, st, s.block),
                             edgecolor=st.ink, lw=st.link_lw * 1.4, zorder=3.5)
            ax.add_patch(patch)
            self.blocks[(s.block, s.point)] = self._move(patch, ax)
        self.tracks = self._tracks()
        self.barred = self._barred()
        self.cuts = []
        for lk, _, _ in self.tracks:     # the cut just over its link's body
            cut = PathPatch(_empty_path(), facecolor=st.paper, edgecolor=st.ink, lw=st.thin_lw,
                            zorder=self.bodies[lk].get_zorder() + 0.005)
            ax.add_patch(cut)
            self.cuts.append(self._move(cut, ax))
        self.profiles = []
        self.flats = []
        for ci, c in enumerate(m.contacts):
            for lk, cn in zip(c.links, c.centres or ()):
                if m.link(lk).frame:
                    continue
                if cn is None:     # a flat profile on a moving link: a face along the common tangent
                    face = Line2D([], [], color=st.ink, lw=st.link_lw * 1.4, zorder=3.2, solid_capstyle="butt")
                    ax.add_line(face)
                    self.flats.append((ci, self._move(face, ax)))
                    continue
                circ = Circle((0, 0), 1.0, facecolor="none", edgecolor=st.ink, lw=st.link_lw * 1.4, zorder=3.2)
                ax.add_patch(circ)
                self.profiles.append((ci, lk, cn, self._move(circ, ax)))

    def _pins_and_labels(self, ax) -> None:
        from matplotlib.lines import Line2D
        from matplotlib.patches import Circle
        from .canvas import per_cm, tex
        m, st = self.m, self.st
        pc = per_cm(ax)
        pins = {pin.point for pin in m.pins} | {s.pin for s in m.slots}
        self.pin_names = [p for p in dict.fromkeys(k.split("@")[0] for k in self.pos) if p in pins]
        self.dot_names = [p for p in dict.fromkeys(k.split("@")[0] for k in self.pos) if p not in pins]
        r = st.pin_radius * pc
        self.pin_patches = {}
        for p in self.pin_names:
            circ = Circle((0, 0), r, facecolor=st.paper, edgecolor=st.ink, lw=st.link_lw * 1.2, zorder=5)
            ax.add_patch(circ)
            self.pin_patches[p] = self._move(circ, ax)
        dots = Line2D([], [], linestyle="", marker="o", markersize=self.pt(7), color=st.ink, zorder=5)
        ax.add_line(dots)
        self.dots = self._move(dots, ax)
        # labels beside the points
        wanted = self.opts.label_points
        self.point_labels = {}
        for p in self.pin_names + self.dot_names:
            if wanted is not None and p not in wanted:
                continue
            if not any(k.split("@")[0] == p and np.ptp(self.pos[k], axis=0).max() >= 0 for k in self.pos):
                continue
            t = ax.annotate(tex(p), (0, 0), xytext=(0, 0), textcoords="offset points", ha="center", va="center",
                            fontsize=self.pt(24), fontstyle="italic", zorder=7)
            self.point_labels[p] = self._move(t, ax)
        # link numbers
        self.link_numbers = {}
        if self.opts.link_numbers != "none":
            for link in m.moving_links:
                kw = {}
                if self.opts.link_numbers == "circled":
                    kw["bbox"] = dict(boxstyle="circle,pad=0.2", facecolor=st.paper, edgecolor=st.ink, lw=st.thin_lw * 2)
                t = ax.annotate(literal(link.name), (0, 0), xytext=(0, 0), textcoords="offset points", ha="center",
                                va="center", fontsize=self.pt(17), zorder=6.5, **kw)
                self.link_numbers[link.name] = self._move(t, ax)

    def _scale_bar(self, ax, power) -> None:
        from .labels import placer
        from .scalebar import scale_bar
        import dataclasses as dc
        st = dc.replace(self.st, small_size=self.pt(17), thin_lw=self.pt(1.5))
        placer(ax)
        wcm = ax.get_position().width * 16.0 * 2.54
        scale_bar(ax, st, self.m.units, power, target_cm=min(0.3 * wcm, 6.0))

    # -- a polygon panel ---------------------------------------------------------------------------
    def _polygon(self, ax, kind: str) -> None:
        from matplotlib.patches import Circle
        from .canvas import fit_view, per_cm, per_point, tex
        from .labels import placer
        from shapely.geometry import MultiPoint
        polys = self.polys[kind]
        box = self.boxes[kind]
        # every vector kind drawn in any frame: the legend (acceleration components) is still
        kinds = []
        for poly in polys:
            for stp in poly.steps:
                for v in stp.vectors:
                    if v.kind not in kinds:
                        kinds.append(v.kind)
        band = self._legend_band(ax, kinds) if kind == "acceleration" else 0.0
        scale = self._fit(ax, box, margin=0.07, top=band)
        setattr(self, f"{kind}_scale", scale)
        pc, pp = per_cm(ax), per_point(ax)
        st = self.st
        self._scale_bar(ax, 1 if kind == "velocity" else 2)      # in the lower left corner, in every frame
        # the origin and its label (still)
        ax.add_patch(Circle((0, 0), self.pt(4) * pp, facecolor=st.ink, edgecolor="none", zorder=6))
        origin = polys[0].origin_label
        o = ax.annotate(tex(origin), (0, 0), xytext=(-self.pt(14), -self.pt(14)), textcoords="offset points",
                        ha="right", va="top", fontsize=self.pt(24), fontstyle="italic", zorder=7)
        bb = o.get_window_extent(self.fig.canvas.get_renderer())
        self._origin_box = getattr(self, "_origin_box", {})
        self._origin_box[kind] = (bb.x0, bb.y0, bb.x1, bb.y1)
        from .style import link_colour
        from matplotlib.patches import Polygon as MPolygon
        shades = {}
        for z, lk in enumerate(polys[0].link_images):
            if len(polys[0].link_images[lk]) >= 3 and not self.m.link(lk).frame:
                patch = MPolygon(np.zeros((3, 2)), closed=True, facecolor=link_colour(self.m, self.opts, st, lk),
                                 alpha=st.image_alpha, edgecolor="none", zorder=1)
                ax.add_patch(patch)
                shades[lk] = self._move(patch, ax)
        arrows, labels = {}, {}
        self.images[kind] = {}
        for key, lab in polys[0].labels.items():
            if all(float(np.hypot(*p.images[key])) == 0.0 for p in polys[:1]) and \
                    all(float(np.hypot(*p.images[key])) <= 1e-12 * max(1.0, float(np.abs(box).max())) for p in polys):
                continue    # a frame point: its image stays at the origin
            t = ax.annotate(tex(lab), (0, 0), xytext=(0, 0), textcoords="offset points", ha="center",
                            va="center", fontsize=self.pt(24), fontstyle="italic", zorder=7)
            labels[key] = self._move(t, ax)
        self._poly_art = getattr(self, "_poly_art", {})
        self._poly_art[kind] = {"shades": shades, "arrows": arrows, "labels": labels, "ax": ax,
                                "head": st.head_length * 1.6 * pp, "lw": self.pt(3.0), "pp": pp,
                                "note": self._reduced(ax, kind, self.band[kind])}

    def _legend_band(self, ax, kinds: list) -> float:
        """The height (cm) of the band the acceleration legend (:meth:`_legend`) takes at the panel's top, and a
        gap: the polygon is fitted below it in every frame. In as few columns as leave the polygon LEGEND_ROOM of
        the panel, where the panel is wide enough; 0 without a legend."""
        band = 0.0
        pos = ax.get_position()
        for columns in (1, 2, 3):
            legend = self._legend(ax, kinds, columns)
            if legend is None:
                break
            bb = legend.get_window_extent(self.fig.canvas.get_renderer())
            band = (bb.height / self.dpi + self.pt(LEGEND_GAP) / 72.0) * 2.54
            self._legend_box = (bb.x0, bb.y0, bb.x1, bb.y1)
            if band <= (1 - LEGEND_ROOM) * 0.86 * pos.height * self.size[1] / self.dpi * 2.54 or \
                    bb.width * (columns + 1) / columns > pos.width * self.size[0]:
                break
        return band

    def _legend(self, ax, kinds: list, columns: int = 1):
        """The acceleration panel's legend of the vector kinds drawn (``kinds``) in ``columns``, in its upper
        right corner (still: the polygon is fitted below it, :meth:`_fit`); None where only absolute vectors
        are drawn."""
        from matplotlib.lines import Line2D
        from .style import KIND_LABELS
        st = self.st
        if not [k for k in kinds if k != "absolute"]:
            return None
        shown = [k for k in st.kind_styles if k in kinds or k == "absolute"]
        handles = []
        for k in shown:
            ls, colour, f = st.kind_styles[k]
            handles.append(Line2D([], [], lw=self.pt(3.0) * f, linestyle=ls, color=st.ink if colour is None else colour))
        return ax.legend(handles, [KIND_LABELS[k] for k in shown], loc="upper right", fontsize=self.pt(16),
                         handlelength=3.0, borderaxespad=0.0, frameon=False, ncols=columns)

    def _reduced(self, ax, kind: str, band: float = 0.0):
        """Each frame's divisor of the panel's scale (``self.reduction[kind]``, :func:`reduction`: a frame whose
        polygon the panel cannot hold at the scale, a toggle's surge, is drawn at 1/n of it, below the top
        ``band`` (data units) the legend keeps) and the note, beside the scale bar, that says so in such a frame
        (returned)."""
        limits = (*ax.get_xlim(), ax.get_ylim()[0], ax.get_ylim()[1] - band)
        self.reduction = getattr(self, "reduction", {})
        self.reduction[kind] = [reduction(_polygon_points(p), limits) for p in self.polys[kind]]
        note = ax.text(0.99, 0.01, "", transform=ax.transAxes, ha="right", va="bottom", fontsize=self.pt(18),
                       color="0.3", fontstyle="italic", zorder=8)
        return self._move(note, ax)

    def _arrow(self, kind: str, key, vkind: str):
        """The pooled arrow ``key`` of the polygon panel ``kind`` (made on first use)."""
        from matplotlib.lines import Line2D
        from matplotlib.patches import Polygon as MPolygon
        art = self._poly_art[kind]
        a = art["arrows"].get(key)
        if a is None:
            ls, colour, f = self.st.kind_styles.get(vkind, self.st.kind_styles["relative"])
            colour = self.st.ink if colour is None else colour
            z = 3 if vkind == "absolute" else 3.5
            shaft = Line2D([], [], lw=art["lw"] * f * (1.0 if vkind == "absolute" else 0.75), color=colour,
                           linestyle=ls, solid_capstyle="butt", zorder=z)
            head = MPolygon(np.zeros((3, 2)), closed=True, facecolor=colour, edgecolor=colour, lw=0.3, zorder=z + 0.1)
            art["ax"].add_line(shaft)
            art["ax"].add_patch(head)
            a = (self._move(shaft, art["ax"]), self._move(head, art["ax"]))
            art["arrows"][key] = a
        return a

    # -- instant centres ----------------------------------------------------------------------------
    def _poles(self, ax) -> None:
        from matplotlib.lines import Line2D
        from .kennedy import pole_label
        st = self.st
        self.pole_art = {}
        for key, p in self.poles[0].poles.items():
            if p.how == "pin":
                continue       # a pin's pole is the pin, labelled already
            dot = Line2D([], [], linestyle="", marker="o", markersize=self.pt(9), markerfacecolor=st.paper,
                         markeredgecolor=st.ink, markeredgewidth=self.pt(2), zorder=6)
            ax.add_line(dot)
            t = ax.annotate(pole_label(p.links), (0, 0), xytext=(self.pt(10), self.pt(10)), textcoords="offset points",
                            ha="left", va="bottom", fontsize=self.pt(20), zorder=7)
            self.pole_art[key] = (self._move(dot, ax), self._move(t, ax))

    # -- the live table -------------------------------------------------------------------------------
    def _table(self) -> None:
        from ..driver import driver_label
        fig, m, st = self.fig, self.m, self.st
        x0, y0, w, h = _TABLE
        rows = []       # (name, values over frames, unit)
        drv = m.driver
        if drv.is_slider:
            rows.append((_name_tex("s", drv.slider), self.plan.angles, literal(m.units)))
        else:
            wrapped = (np.asarray(self.plan.angles, float) + 180.0) % 360.0 - 180.0
            wrapped[wrapped == -180.0] = 180.0          # (-180, 180], as in the JSON
            rows.append((_name_tex("theta", drv.link), wrapped, "°"))
        u = m.units
        vel = self.sheet in ("velocity", "full", "poles")
        acc = self.sheet == "acceleration" or (self.sheet == "full" and self.kinds["acceleration"])
        from .scalebar import unit_label
        if vel:
            for k in m.moving_links:
                rows.append((_name_tex("omega", k.name), self.omega[k.name], "rad/s"))
        if acc:
            for k in m.moving_links:
                rows.append((_name_tex("alpha", k.name), self.alpha[k.name], "rad/s²"))
        keys = [k for k in self.pos if np.ptp(self.pos[k], axis=0).max() > 1e-12 * m.size]
        wanted = self.opts.label_points
        if wanted is not None:
            keys = [k for k in keys if k.split("@")[0] in wanted]
        if vel:
            for k in keys:
                rows.append((_name_tex("V", k, bars=True), np.hypot(*self.vel[k].T), unit_label(u, 1)))
        if acc:
            for k in keys:
                rows.append((_name_tex("A", k, bars=True), np.hypot(*self.acc[k].T), unit_label(u, 2)))
        H = self.size[1]
        f = _type_factor(H)
        room = h * H / f                # pixels at 1080 rows
        line = min(34.0, room / max(len(rows) + 1.5, 1))
        shown = rows
        if line < 17.0:                 # type at least 14 px: the rows that fit, the rest left out
            line = 17.0
            shown = rows[:int(room / line) - 2]
        size = self.pt(max(14.5, min(22.0, line * 0.66)))
        line *= f                       # pixels
        top = y0 + h
        fig.text(x0, top, "ccw positive" if vel or acc else "", fontsize=self.pt(15), color="0.35", va="top",
                 fontstyle="italic")
        self.table, self.table_floor = {}, {}
        self.table_rows = shown
        kind = _largest_of_kind(rows)
        for i, (name, vals, unit) in enumerate(shown):
            y = top - (i + 1.4) * line / H
            fig.text(x0, y, name, fontsize=size, va="baseline", ha="left")
            dec = 1 if unit == "°" else _decimals(_largest(vals), kind[unit])
            self.table_floor[name] = zero_floor([kind[unit]])   # the tables' rule (compare.kind_floor)
            t = fig.text(x0 + 0.64 * w, y, "", fontsize=size, va="baseline", ha="right")
            t._velpoly_chars = True
            self.table[name] = (self._move(t), np.asarray(vals, float), dec)
            fig.text(x0 + 0.67 * w, y, unit, fontsize=size * 0.85, va="baseline", ha="left", color="0.3")
        if len(shown) < len(rows):
            fig.text(x0, top - (len(shown) + 1.4) * line / H, f"(+{len(rows) - len(shown)} rows in velpoly solve)",
                     fontsize=self.pt(14.5), color="0.35", va="baseline")

    # -- a frame ------------------------------------------------------------------------------------
    def update(self, k: int) -> None:
        """Move every moving artist to frame k."""
        sol = self.sols[k]
        pos = {key: v[k] for key, v in self.pos.items()}
        self._update_bodies(k, sol)
        first = {}
        for key, p in pos.items():
            first.setdefault(key.split("@")[0], p)
        for p, circ in self.pin_patches.items():
            circ.center = tuple(first[p])
        dots = np.array([first[p] for p in self.dot_names]).reshape(-1, 2)
        self.dots.set_data(dots[:, 0], dots[:, 1])
        self.points = first
        taken = self._update_link_numbers(sol, pos)   # boxes (pixels) of the link numbers: labels keep clear
        self._update_point_labels(sol, first, taken)
        if self._centrode is not None:
            cen, sw = self.centrodes
            from ..centrodes import break_at_infinity
            leg, i = self.plan.frames[k]
            xy = break_at_infinity(cen.carried(sw, sw.kinematics, i), sw.omega[cen.link])
            self._centrode.set_data(xy[:, 0], xy[:, 1])
        for kind in self.polys:
            self._update_polygon(kind, self.polys[kind][k], self.reduction[kind][k])
        if self.poles is not None:
            self._update_poles(k)
        for name, (t, vals, dec) in self.table.items():
            v = vals[k]
            t.set_text(_value_text(v, dec, self.table_floor[name]))

    def _barred(self) -> set:
        """The links drawn as bars (a bell-crank's arms, joined) in every frame: those whose plate (the hull of
        their points, or of their body and tracks) covers another link's pivot or pin in the first frame (the
        drawn pose: the sheet's choice). A rigid body keeps one shape for the whole animation."""
        from shapely.geometry import MultiPoint
        from shapely.ops import unary_union
        from .displacement import covers, foreign_points, joints, link_bodies, on_body
        m, sol, out = self.m, self.sols[0], set()
        links = [k.name for k in m.moving_links if len(k.points) >= 2 and len(joints(m, k.name)) >= 3]
        bodies = None
        for lk in links:
            shape = MultiPoint([tuple(sol.place(lk, p)) for p in m.link(lk).points]).convex_hull
            tracks = [track(0)[0] for name, _, track in self.tracks if name == lk]
            if tracks:   # as the sheet's whole_body: the hull of the body and its tracks
                bodies = link_bodies(sol, self.bw, set(links)) if bodies is None else bodies
                shape = unary_union([bodies[lk]] + tracks).convex_hull
            if covers(shape, foreign_points(sol, lk, on_body(m, lk)), self.bw / 2 if tracks else self.bw):
                out.add(lk)
        return out

    def _tracks(self) -> list:
        """The slots and guides cut in moving links: (link, frame k -> (centre line, width)), each long enough for
        its pin's (block's) whole travel in the animation, as the link carries it (its place in the link's own
        axes is taken in every frame: a straight track's offset and direction, a circular one's centre and
        radius are fixed in the link). A track whose link has no other point to carry it is left out."""
        m, pc = self.m, self.bw / self.st.bar_width
        items = [(s.slot, s.link, s.pin, s.centre, 2.6 * self.st.pin_radius * pc, self.slot_rows[j])
                 for j, s in enumerate(m.slots) if not m.link(s.slot).frame]
        items += [(s.guide, s.block, s.point, s.centre, 0.6 * self.st.block[1] * pc, self.slider_rows[j])
                  for j, s in enumerate(m.sliders) if not m.link(s.guide).frame]
        out = []
        for lk, mover, point, centre, width, rows in items:
            base = next((q for q in m.link(lk).points if q != point), None)
            if base is None:
                continue
            out.append((lk, point, self._track(lk, base, mover, point, centre, width, rows)))
        return out

    def _track(self, lk, base, mover, point, centre, width, rows):
        """One track of :meth:`_tracks`: its centre line at frame k from the link's ``base`` point and angle, over
        the mover's travel in the link's axes plus a block's length at each end."""
        from shapely.geometry import LineString
        th = np.radians(self.plan.series("angle")[lk])
        q = np.array([s.place(lk, base) for s in self.sols], float)
        p = np.array([s.place(mover, point) for s in self.sols], float)

        def local(v):   # world vectors (N, 2) in the link's own axes
            c, s_ = np.cos(th), np.sin(th)
            return np.stack([c * v[:, 0] + s_ * v[:, 1], -s_ * v[:, 0] + c * v[:, 1]], axis=1)

        def world(k, v):
            c, s_ = math.cos(th[k]), math.sin(th[k])
            return q[k] + np.stack([c * v[..., 0] - s_ * v[..., 1], s_ * v[..., 0] + c * v[..., 1]], axis=-1)

        margin = self.st.block[0] * self.bw / self.st.bar_width
        if centre is None:
            d0 = math.radians(float(rows["direction"][0]))
            d = local(np.array([[math.cos(d0), math.sin(d0)]]))[0]
            at = local(p - q)
            t, off = at @ d, float((at[0] @ np.array([-d[1], d[0]])))
            ts = np.array([t.min() - margin, t.max() + margin])
            ends = off * np.array([-d[1], d[0]]) + ts[:, None] * d
            return lambda k: (LineString(world(k, ends)), width)
        kc = local(np.array([s.place(lk, centre) for s in self.sols], float) - q)[0]
        at = local(p - q) - kc
        rad = float(np.hypot(*at[0]))
        phi = np.unwrap(np.arctan2(at[:, 1], at[:, 0]))
        span = margin / max(rad, 1e-300)
        a = np.linspace(phi.min() - span, phi.max() + span, 48)
        arc = kc + rad * np.stack([np.cos(a), np.sin(a)], axis=1)
        return lambda k: (LineString(world(k, arc)), width)

    def _update_bodies(self, k: int, sol) -> None:
        """The links' bodies (a link of three or more points as one plate with its corners at its points, as
        the space diagram draws it), the slider blocks and the contact profiles at frame k."""
        from shapely.ops import unary_union
        from .displacement import joints, link_bodies, plain_links, plate_fill, plate_outline, shape_patch, whole_body
        from .style import link_fill
        m, st = self.m, self.st
        bodies = link_bodies(sol, self.bw, self.barred)
        plain = plain_links(m)
        webs, pc = {}, self.bw / st.bar_width
        for (lk, point, track), cut in zip(self.tracks, self.cuts):
            path, width = track(k)
            webs.setdefault(lk, []).append(path.buffer(width / 2 + 0.12 * pc, cap_style="round"))
            cut.set_path(shape_patch(path.buffer(width / 2, cap_style="round")).get_path())
        for lk, patch in self.bodies.items():
            plate = plate_outline(sol, lk, self.bw) if lk in plain and lk not in self.barred else None
            g = plate if plate is not None else bodies.get(lk)
            whole = g is not None and plate is None and len(joints(m, lk)) >= 3
            if g is not None and (lk in webs or whole):   # one piece with its tracks, as the sheet draws it
                g = unary_union([g] + webs.get(lk, []))
                g = whole_body(g, (), self.bw, lk in self.barred) if whole else g
            patch.set_path(shape_patch(g).get_path() if g is not None else _empty_path())
            fill = link_fill(m, self.opts, st, lk)
            patch.set_facecolor(plate_fill(fill, st) if plate is not None or whole else fill)
        for (block, point), patch in self.blocks.items():
            j = [i for i, s in enumerate(m.sliders) if s.block == block and s.point == point][0]
            d = math.radians(float(self.slider_rows[j]["direction"][k]))
            u = np.array([math.cos(d), math.sin(d)])
            n = np.array([-u[1], u[0]])
            p = sol.place(block, point)
            L, H = st.block[0] * pc / 2, st.block[1] * pc / 2
            patch.set_xy(np.array([p - u * L - n * H, p + u * L - n * H, p + u * L + n * H, p - u * L + n * H]))
        for ci, face in self.flats:
            place = np.asarray(self.contact_rows[ci]["place"][k], float)
            d = math.radians(float(self.contact_rows[ci]["normal"][k]) + 90.0)
            t = np.array([math.cos(d), math.sin(d)]) * 2.4 * pc
            face.set_data([place[0] - t[0], place[0] + t[0]], [place[1] - t[1], place[1] + t[1]])
        for ci, lk, cn, circ in self.profiles:
            place = np.asarray(self.contact_rows[ci]["place"][k], float)
            ctr = sol.place(lk, cn)
            circ.center = tuple(ctr)
            circ.set_radius(float(np.hypot(*(place - ctr))))

    def _update_link_numbers(self, sol, pos) -> list:
        """The link numbers beside their links, away from the mechanism's middle; their boxes (pixels)."""
        taken = []
        if not self.link_numbers:
            return taken
        centre = np.mean(np.array(list(pos.values())), axis=0)
        for lk, t in self.link_numbers.items():
            link = self.m.link(lk)
            ps = [sol.place(lk, q) for q in link.points]
            if len(ps) >= 2:
                a, b = ps[0], ps[1]
                anchor = (a + b) / 2 if len(ps) == 2 else np.mean(ps, axis=0)
                nvec = np.array([-(b - a)[1], (b - a)[0]]) / max(float(np.hypot(*(b - a))), 1e-300)
                if np.dot(nvec, anchor - centre) < 0:
                    nvec = -nvec
                off = (self.bw / 2) / self.pp + self.pt(14.0)
                t.xy = tuple(anchor)
                t.set_position(tuple(nvec * off) if len(ps) == 2 else (0.0, 0.0))
            else:
                t.xy = tuple(ps[0])
                t.set_position((0.0, 0.0))
            taken.append(self._box_px(self.axes["mechanism"], t, pad=4.0))
        return taken

    def _update_point_labels(self, sol, first, taken) -> None:
        """Each point's label away from its links, clear of the links, ground, blocks and ``taken``."""
        from .displacement import away_from, neighbours
        m = self.m
        ax = self.axes["mechanism"]
        segs = []
        for link in m.moving_links:
            ps = [sol.place(link.name, q) for q in link.points]
            segs += [(a, b) for i, a in enumerate(ps) for b in ps[i + 1:]]
        for p in self.pivots:         # the ground beneath a frame pivot
            if p in first:
                segs.append((first[p], first[p] + np.array([0.0, -3.0 * self.bw])))
        for patch in self.blocks.values():      # the blocks' outlines, and across them
            xy = np.asarray(patch.get_xy(), float)[:4]
            segs += [(xy[i], xy[(i + 1) % 4]) for i in range(4)] + [(xy[0], xy[2]), (xy[1], xy[3])]
        pts = self._seg_points(ax, segs)
        for p, t in self.point_labels.items():
            xy = first[p]
            others = neighbours(sol, p, m.carriers.get(p, ()))
            if p in self.pivots:
                others = others + [xy + np.array([0.0, -1.0]) * max(self.bw, 1e-300) * 3]
            ang = away_from(xy, others, default=45.0)
            t.xy = tuple(xy)
            t.set_position(self._clear_offset(ax, t, xy, ang, 9.0, pts, taken))

    def _update_poles(self, k: int) -> None:
        """The poles at frame k, those inside the mechanism's view."""
        ps = self.poles[k]
        x0, x1 = self.axes["mechanism"].get_xlim()
        y0, y1 = self.axes["mechanism"].get_ylim()
        for key, (dot, t) in self.pole_art.items():
            p = ps.poles[key].position
            inside = p is not None and x0 <= p[0] <= x1 and y0 <= p[1] <= y1
            dot.set_visible(inside)
            t.set_visible(inside)
            if inside:
                dot.set_data([p[0]], [p[1]])
                t.xy = tuple(p)

    @staticmethod
    def _seg_points(ax, segs) -> np.ndarray:
        """Points along the segments (data coordinates), in display pixels: what labels keep clear of."""
        if not segs:
            return np.zeros((0, 2))
        ends = ax.transData.transform(np.array([e for sg in segs for e in sg], float)).reshape(-1, 2, 2)
        f = np.linspace(0.0, 1.0, 9)[None, :, None]
        return (ends[:, :1] + (ends[:, 1:] - ends[:, :1]) * f).reshape(-1, 2)

    def _clear_offset(self, ax, text, anchor, prefer: float, gap_px: float, pts, taken: list) -> tuple:
        """The offset (points) of ``text`` beside ``anchor``: of twelve directions (``prefer`` first, then
        alternately either side), the one whose box keeps farthest from the segments drawn (links, or the
        polygon's vectors) and the labels already placed (``taken``: boxes in pixels, appended to), up to a
        clearance of 6 pixels, where nearer ``prefer`` wins; where none is clear (labels of coincident or
        crowded points), the same twelve a label's size farther out are tried too."""
        a = ax.transData.transform(np.asarray(anchor, float))
        self._offset(text, prefer, gap_px)            # measures the text once
        k = self.dpi / 72.0
        w, h = text._velpoly_wh[0] * k, text._velpoly_wh[1] * k
        ang = np.radians(prefer + _TURNS)
        u = np.stack([np.cos(ang), np.sin(ang)], axis=1)
        with np.errstate(divide="ignore"):
            half = np.minimum(np.where(np.abs(u[:, 0]) > 1e-12, (w / 2) / np.abs(u[:, 0]), np.inf),
                              np.where(np.abs(u[:, 1]) > 1e-12, (h / 2) / np.abs(u[:, 1]), np.inf))
        near = self.pt(gap_px) * k + half
        off = np.concatenate([u * near[:, None], u * (near + 2 * half)[:, None]])   # the second ring: a label out
        c = a[None, :] + off
        clear = np.full(len(c), 6.0)
        if len(pts):
            dx = np.maximum(np.abs(pts[None, :, 0] - c[:, None, 0]) - w / 2, 0.0)
            dy = np.maximum(np.abs(pts[None, :, 1] - c[:, None, 1]) - h / 2, 0.0)
            clear = np.minimum(clear, np.hypot(dx, dy).min(axis=1))
        if taken:
            t = np.asarray(taken, float)
            gx = np.maximum(np.maximum(t[None, :, 0] - (c[:, None, 0] + w / 2), (c[:, None, 0] - w / 2) - t[None, :, 2]), 0)
            gy = np.maximum(np.maximum(t[None, :, 1] - (c[:, None, 1] + h / 2), (c[:, None, 1] - h / 2) - t[None, :, 3]), 0)
            d = np.hypot(gx, gy) - np.where((gx == 0) & (gy == 0), 6.0, 0.0)
            clear = np.minimum(clear, d.min(axis=1))
        good = np.flatnonzero(clear >= 6.0)
        i = int(good[0]) if len(good) else int(np.argmax(clear))   # the first ring first: it comes first
        cx, cy = c[i]
        taken.append((cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2))
        return (float(off[i, 0] / k), float(off[i, 1] / k))

    def _box_px(self, ax, t, pad: float = 0.0) -> tuple:
        """The text's box in display pixels (y up) where the frame puts it, grown by ``pad`` pixels."""
        wh = getattr(t, "_velpoly_wh", None)
        if wh is None:
            bb = t.get_window_extent(self.fig.canvas.get_renderer())
            wh = t._velpoly_wh = (bb.width * 72 / self.dpi, bb.height * 72 / self.dpi)
        x, y = ax.transData.transform(np.asarray(t.xy, float))
        dx, dy = t.get_position()
        x, y = x + dx * self.dpi / 72.0, y + dy * self.dpi / 72.0
        w, h = wh[0] * self.dpi / 72.0 / 2 + pad, wh[1] * self.dpi / 72.0 / 2 + pad
        return (x - w, y - h, x + w, y + h)

    def _offset(self, text, ang: float, gap_px: float) -> tuple:
        """The offset (points) that puts ``text``'s box ``gap_px`` beside its anchor in direction ``ang``."""
        from .labels import half_extent
        wh = getattr(text, "_velpoly_wh", None)
        if wh is None:
            bb = text.get_window_extent(self.fig.canvas.get_renderer())
            wh = (bb.width * 72 / self.dpi, bb.height * 72 / self.dpi)
            text._velpoly_wh = wh
        u = np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
        r = self.pt(gap_px) + half_extent(wh[0], wh[1], u)
        return (float(u[0] * r), float(u[1] * r))

    def _update_polygon(self, kind: str, poly, divisor: int = 1) -> None:
        """The polygon panel ``kind`` at the frame of ``poly``, drawn at 1/``divisor`` of the panel's scale (1 but
        where the panel cannot hold it: :func:`reduction`), which its note then says."""
        from shapely.geometry import MultiPoint
        from .polygon import ALONG, APART, Beside
        art = self._poly_art[kind]
        art["note"].set_text("" if divisor == 1 else f"drawn at 1/{divisor} scale")
        reduced = 1.0 / divisor
        images = {k: reduced * np.asarray(v, float) for k, v in poly.images.items()}
        for lk, patch in art["shades"].items():
            pts = [tuple(images[q]) for q in poly.link_images[lk]]
            hull = MultiPoint(pts).convex_hull
            if hull.geom_type == "Polygon":
                patch.set_xy(np.asarray(hull.exterior.coords))
                patch.set_visible(True)
            else:
                patch.set_visible(False)
        used = set()
        tol = 1e-9 * max((float(np.hypot(*v)) for v in images.values()), default=1.0) or 1e-300
        vectors = [("absolute", np.zeros(2), images[key], "abs-" + key) for key in art["labels"]]
        for stp in poly.steps:
            for v in stp.vectors:
                if v.kind == "absolute":
                    continue
                vectors.append((v.kind, reduced * np.asarray(v.tail, float), reduced * np.asarray(v.head, float),
                                v.kind + "-" + v.label))
        seen, drawn = set(), []
        centre = np.array([np.zeros(2)] + list(images.values())).mean(axis=0)
        beside = Beside(APART * art["head"], ALONG * art["pp"])   # vectors on one line drawn apart, as on a sheet
        for vkind, tail, head, key in vectors:
            sig = tuple(np.round(np.r_[tail, head] / tol).astype(np.int64))
            if float(np.hypot(*(head - tail))) <= tol or sig in seen:
                continue
            seen.add(sig)
            shift = beside.add(tail, head, centre, vkind)
            shaft, tip = self._arrow(kind, key, vkind)
            _set_arrow(shaft, tip, tail + shift, head + shift, art["head"])
            shaft.set_visible(True)
            tip.set_visible(True)
            used.add(key)
            drawn.append((tail + shift, head + shift))
        for key, (shaft, tip) in art["arrows"].items():
            if key not in used:
                shaft.set_visible(False)
                tip.set_visible(False)
        self.images[kind] = images
        pts = self._seg_points(art["ax"], drawn)
        taken = [self._origin_box.get(kind)] if self._origin_box.get(kind) is not None else []
        if kind == "acceleration" and getattr(self, "_legend_box", None) is not None:   # and of the legend
            taken.append(self._legend_box)
        if divisor != 1:   # the labels keep clear of the note
            bb = art["note"].get_window_extent(self.fig.canvas.get_renderer())
            taken.append((bb.x0, bb.y0, bb.x1, bb.y1))
        for key, t in art["labels"].items():
            p = images[key]
            away = p - centre
            ang = math.degrees(math.atan2(away[1], away[0])) if np.hypot(*away) > tol else -135.0
            t.xy = tuple(p)
            t.set_position(self._clear_offset(art["ax"], t, p, ang, 7.0, pts, taken))

    # -- output -------------------------------------------------------------------------------------
    def render(self, k: int) -> np.ndarray:
        """Frame k as an (H, W, 4) uint8 RGBA array (opaque): the still background, the moving lines and patches drawn
        over it, then the moving texts pasted as pictures rendered once (a label's picture is the same in
        every frame; a table value is put together from its characters' pictures)."""
        self.update(k)
        self.canvas.restore_region(self.background)
        for ax, a in self._order:
            if a.get_visible():
                (ax or self.fig).draw_artist(a)
        w, h = self.size
        rgba = np.frombuffer(self.canvas.buffer_rgba(), np.uint8).reshape(h, w, 4).copy()
        for ax, t in self.texts:
            if t.get_visible() and t.get_text():
                self._paste_text(rgba, ax, t)
        return rgba

    @property
    def _order(self):
        order = getattr(self, "_order_cache", None)
        if order is None:
            order = self._order_cache = sorted(self.moving, key=lambda t: t[1].get_zorder())
        return order

    def _anchor_px(self, ax, t) -> tuple[float, float]:
        """The text's anchor in pixels from the top left (x right, y down)."""
        from matplotlib.text import Annotation
        if isinstance(t, Annotation):
            x, y = ax.transData.transform(t.xy)
            dx, dy = t.get_position()
            x, y = x + dx * self.dpi / 72.0, y + dy * self.dpi / 72.0
        else:
            x, y = t.get_transform().transform(t.get_position())
        return x, self.size[1] - y

    def _paste_text(self, rgb, ax, t) -> None:
        x, y = self._anchor_px(ax, t)
        s = t.get_text()
        if getattr(t, "_velpoly_chars", False):        # a number: its characters' pictures, right-aligned
            for ch in reversed(s):
                spr, dx, dy, adv = self._sprite(t, ch, per_char=True)
                x -= adv
                _paste(rgb, spr, x + dx, y + dy)
            return
        spr, dx, dy, _ = self._sprite(t, s)
        _paste(rgb, spr, x + dx, y + dy)

    def _sprite(self, t, s: str, per_char: bool = False):
        """The picture of ``s`` in ``t``'s type (float RGBA, straight alpha), its top left's offset from the
        anchor in pixels, and (per character) its advance."""
        key = (s, t.get_fontsize(), t.get_fontstyle(), str(t.get_color()), t.get_ha() if not per_char else "left",
               t.get_va(), id(t.get_bbox_patch()) if t.get_bbox_patch() else None, per_char)
        hit = self._sprites.get(key)
        if hit is not None:
            return hit
        from matplotlib.figure import Figure
        from .textcache import new_canvas
        sc = getattr(self, "_scratch", None)
        if sc is None:
            sc = self._scratch = Figure(figsize=(800 / self.dpi, 300 / self.dpi), dpi=self.dpi)
            sc.patch.set_alpha(0.0)
            new_canvas(sc)   # (Agg, its glyphs kept: velpoly.render.textcache)
        kw = dict(fontproperties=t.get_fontproperties(), color=t.get_color(),
                  ha="left" if per_char else t.get_ha(), va=t.get_va())
        bb = t.get_bbox_patch()
        if bb is not None:
            kw["bbox"] = dict(boxstyle=bb.get_boxstyle(), facecolor=bb.get_facecolor(), edgecolor=bb.get_edgecolor(),
                              lw=bb.get_linewidth())
        tx = sc.text(0.5, 0.5, s, **kw)
        sc.canvas.draw()
        buf = np.asarray(sc.canvas.buffer_rgba())
        adv = tx.get_window_extent(sc.canvas.get_renderer()).width if per_char else 0.0
        tx.remove()
        alpha = buf[..., 3]   # (a byte over 255 is above zero where the byte is: the ink's rows and columns)
        rows, cols = np.flatnonzero(alpha.any(axis=1)), np.flatnonzero(alpha.any(axis=0))
        if not len(rows):
            out = (np.zeros((1, 1, 4), np.float32), 0, 0, adv)
        else:   # only the ink's rectangle made float (each value as the whole picture's would be)
            spr = buf[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1].astype(np.float32) / 255.0
            out = (spr, cols[0] - 400.0, rows[0] - 150.0, adv)
        self._sprites[key] = out
        return out

    def _rc_ctx(self):
        from .style import rc_context
        return rc_context(self.st)


def _paste(rgb: np.ndarray, spr: np.ndarray, x: float, y: float) -> None:
    """Blend the sprite (float RGBA, straight alpha) over ``rgb`` with its top left at pixel (x, y)."""
    x, y = int(round(x)), int(round(y))
    h, w = spr.shape[:2]
    H, W = rgb.shape[:2]
    x0, y0, x1, y1 = max(x, 0), max(y, 0), min(x + w, W), min(y + h, H)
    if x0 >= x1 or y0 >= y1:
        return
    s = spr[y0 - y:y1 - y, x0 - x:x1 - x]
    a = s[..., 3:4]
    dst = rgb[y0:y1, x0:x1, :3].astype(np.float32)
    rgb[y0:y1, x0:x1, :3] = (dst * (1.0 - a) + s[..., :3] * 255.0 * a + 0.5).astype(np.uint8)


_TURNS = np.array([0, 30, -30, 60, -60, 90, -90, 120, -120, 150, -150, 180], float)   # label directions tried


def _empty_path():
    from matplotlib.path import Path as MPath
    return MPath(np.zeros((1, 2)))


def _set_arrow(shaft, head, tail, tip, head_len) -> None:
    """An arrow from ``tail`` to ``tip`` whose head (``head_len`` long, data units) ends exactly at tip."""
    d = tip - tail
    length = float(np.hypot(*d))
    u = d / length
    n = np.array([-u[1], u[0]])
    hl = min(head_len, 0.6 * length)
    hw = 0.32 * hl
    base = tip - u * hl
    head.set_xy(np.array([tip, base + n * hw, base + u * 0.18 * hl, base - n * hw]))
    end = base + u * 0.2 * hl
    shaft.set_data([tail[0], end[0]], [tail[1], end[1]])


# -- writers ------------------------------------------------------------------------------------------
class _Palette:
    """256 colours from sample frames (octree), and a lookup table from 5-bit-a-channel colours to the
    nearest of them: a frame is mapped to the palette with a few numpy passes."""

    def __init__(self, frames: list):
        from PIL import Image
        strip = np.concatenate([f[..., :3] for f in frames], axis=0)
        q = Image.fromarray(np.ascontiguousarray(strip)).quantize(colors=256, method=Image.Quantize.FASTOCTREE)
        pal = np.array(q.getpalette()[:768], np.int64)
        pal = np.concatenate([pal, np.zeros(768 - len(pal), np.int64)]).reshape(256, 3)
        used = len(set(np.asarray(q).ravel().tolist()))
        self.colours = pal
        self.flat = pal.astype(np.uint8).ravel().tolist()
        cells = np.arange(32768)
        rgb = np.stack([(cells >> 10) & 31, (cells >> 5) & 31, cells & 31], axis=1) * 8 + 4
        cand = pal[:max(used, 1)].astype(np.float32)
        x = rgb.astype(np.float32)
        # |x - p|^2 = |p|^2 - 2 x.p (+ |x|^2, the same for every p): one matrix product
        d = (cand ** 2).sum(axis=1)[None, :] - 2.0 * (x @ cand.T)
        lut = d.argmin(axis=1).astype(np.uint8)
        self.lut = lut

    def indices(self, rgba: np.ndarray) -> np.ndarray:
        c = rgba.astype(np.uint16)
        code = ((c[..., 0] >> 3) << 10) | ((c[..., 1] >> 3) << 5) | (c[..., 2] >> 3)
        return self.lut[code]


def _changed_box(prev, cur):
    """The box (x0, y0, x1, y1) of the pixels that differ (RGBA frames); None if none does."""
    if prev is None:
        return (0, 0, cur.shape[1], cur.shape[0])
    diff = prev.view(np.uint32)[..., 0] != cur.view(np.uint32)[..., 0]
    rows = np.flatnonzero(diff.any(axis=1))
    if not len(rows):
        return None
    cols = np.flatnonzero(diff.any(axis=0))
    return (int(cols[0]), int(rows[0]), int(cols[-1]) + 1, int(rows[-1]) + 1)


class _GifWriter:
    """An animated GIF written frame by frame: each frame (quantised to one palette) cropped to what
    changed and kept in place for the next (disposal 1), looping for ever."""

    def __init__(self, fp, size, fps: float, comment: str = ""):
        self.fp, self.size = fp, size
        self.delay = max(int(round(100.0 / fps)), 2)       # hundredths of a second
        self.prev = None
        self.head = False
        self.comment = comment

    def add(self, rgba: np.ndarray, pal: "_Palette") -> None:
        from PIL import Image
        w, h = self.size
        if not self.head:
            self.fp.write(b"GIF89a" + struct.pack("<HHBBB", w, h, 0, 0, 0))
            self.fp.write(b"\x21\xff\x0bNETSCAPE2.0\x03\x01\x00\x00\x00")      # loop for ever
            if self.comment:
                data = self.comment.encode("utf-8")[:255 * 20]
                self.fp.write(b"\x21\xfe" + b"".join(bytes([len(data[i:i + 255])]) + data[i:i + 255]
                                                     for i in range(0, len(data), 255)) + b"\x00")
            self.head = True
        box = _changed_box(self.prev, rgba)
        if box is None:
            box = (0, 0, 1, 1)
        x0, y0, x1, y1 = box
        crop = Image.fromarray(np.ascontiguousarray(pal.indices(rgba[y0:y1, x0:x1])), mode="P")
        crop.putpalette(pal.flat)
        buf = io.BytesIO()
        crop.save(buf, format="GIF", optimize=False, interlace=False)
        table, data, interlaced = _gif_image(buf.getvalue())
        self.fp.write(b"\x21\xf9\x04" + struct.pack("<BHBB", 0b00000100, self.delay, 0, 0))   # disposal 1
        flags = (0x80 | ((len(table) // 3).bit_length() - 2) if table else 0) | (0x40 if interlaced else 0)
        self.fp.write(b"\x2c" + struct.pack("<HHHHB", x0, y0, x1 - x0, y1 - y0, flags) + table + data)
        self.prev = rgba

    def close(self) -> None:
        self.fp.write(b"\x3b")


def _gif_image(gif: bytes) -> tuple[bytes, bytes, bool]:
    """A one-frame GIF's colour table (global or local), its image data (LZW size and sub-blocks) and
    whether it is interlaced."""
    flags = gif[10]
    pos = 13
    table = b""
    if flags & 0x80:
        n = 3 * (2 << (flags & 7))
        table, pos = gif[pos:pos + n], pos + n
    while pos < len(gif):
        b = gif[pos]
        if b == 0x21:                       # an extension: skip its sub-blocks
            pos += 2
            while gif[pos]:
                pos += gif[pos] + 1
            pos += 1
        elif b == 0x2C:
            lflags = gif[pos + 9]
            pos += 10
            if lflags & 0x80:
                n = 3 * (2 << (lflags & 7))
                table, pos = gif[pos:pos + n], pos + n
            start = pos
            pos += 1
            while gif[pos]:
                pos += gif[pos] + 1
            return table, gif[start:pos + 1], bool(lflags & 0x40)
        else:
            break
    raise ValueError("no image in the GIF written by Pillow")


def _chunk(tag: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)


def _png_chunks(png: bytes):
    pos = 8
    while pos < len(png):
        n, = struct.unpack(">I", png[pos:pos + 4])
        tag = png[pos + 4:pos + 8]
        yield tag, png[pos + 8:pos + 8 + n]
        pos += 12 + n


class _ApngWriter:
    """An animated PNG written frame by frame (palette colour, each frame cropped to what changed)."""

    def __init__(self, fp, size, fps: float, n_frames: int, comment: str = ""):
        self.fp, self.size, self.n = fp, size, n_frames
        self.num, self.den = max(int(round(1000.0 / fps)), 1), 1000     # delay = num / den seconds
        self.seq = 0
        self.prev = None
        self.comment = comment

    def add(self, rgba: np.ndarray, pal: "_Palette") -> None:
        from PIL import Image
        w, h = self.size
        box = _changed_box(self.prev, rgba) or (0, 0, 1, 1)
        x0, y0, x1, y1 = box
        crop = Image.fromarray(np.ascontiguousarray(pal.indices(rgba[y0:y1, x0:x1])), mode="P")
        crop.putpalette(pal.flat)
        buf = io.BytesIO()
        crop.save(buf, format="PNG", compress_level=6, bits=8)
        chunks = list(_png_chunks(buf.getvalue()))
        ihdr = dict(chunks)[b"IHDR"]
        if self.prev is None:
            self.fp.write(b"\x89PNG\r\n\x1a\n")
            self.fp.write(_chunk(b"IHDR", struct.pack(">II", w, h) + ihdr[8:]))
            self.ihdr_rest = ihdr[8:]
            self.fp.write(_chunk(b"acTL", struct.pack(">II", self.n, 0)))
            for tag, data in chunks:
                if tag in (b"PLTE", b"tRNS"):
                    self.fp.write(_chunk(tag, data))
            if self.comment:
                self.fp.write(_chunk(b"tEXt", b"Comment\x00" + self.comment.encode("latin-1", "replace")))
        elif ihdr[8:] != self.ihdr_rest:
            raise ValueError("the frames of an animated PNG must share their colour type")
        self.fp.write(_chunk(b"fcTL", struct.pack(">IIIIIHHBB", self.seq, x1 - x0, y1 - y0, x0, y0,
                                                  self.num, self.den, 0, 0)))
        self.seq += 1
        for tag, data in chunks:
            if tag != b"IDAT":
                continue
            if self.prev is None:
                self.fp.write(_chunk(b"IDAT", data))
            else:
                self.fp.write(_chunk(b"fdAT", struct.pack(">I", self.seq) + data))
                self.seq += 1
        self.prev = rgba

    def close(self) -> None:
        self.fp.write(_chunk(b"IEND", b""))


class _PdfWriter:
    """A PDF of one page a frame, each page the frame's picture (256 colours, deflated), written page by
    page: the pages for LaTeX's animate package (``\\animategraphics``)."""

    def __init__(self, fp, size, n_frames: int, comment: str = ""):
        self.fp, self.size, self.n = fp, size, n_frames
        self.offsets = {}
        self.pages = []
        self.comment = comment
        self.next_id = 5          # 1 catalog, 2 pages, 3 colour space, 4 info
        fp.write(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")

    def _obj(self, num: int, body: bytes, stream: bytes | None = None) -> None:
        self.offsets[num] = self.fp.tell()
        self.fp.write(b"%d 0 obj\n" % num + body)
        if stream is not None:
            self.fp.write(b"\nstream\n" + stream + b"\nendstream")
        self.fp.write(b"\nendobj\n")

    def add(self, rgba: np.ndarray, pal: "_Palette") -> None:
        w, h = self.size
        if not self.offsets:
            self._obj(3, b"[/Indexed /DeviceRGB 255 <" + bytes(pal.flat).hex().encode() + b">]")
        img, content, page = self.next_id, self.next_id + 1, self.next_id + 2
        self.next_id += 3
        data = zlib.compress(pal.indices(rgba).tobytes(), 6)
        self._obj(img, b"<< /Type /XObject /Subtype /Image /Width %d /Height %d /ColorSpace 3 0 R "
                       b"/BitsPerComponent 8 /Filter /FlateDecode /Length %d >>" % (w, h, len(data)), data)
        pw, ph = w * 0.75, h * 0.75      # 96 pixels to the inch
        ops = b"q %.4f 0 0 %.4f 0 0 cm /Im0 Do Q" % (pw, ph)
        self._obj(content, b"<< /Length %d >>" % len(ops), ops)
        self._obj(page, b"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 %.4f %.4f] /Contents %d 0 R "
                        b"/Resources << /XObject << /Im0 %d 0 R >> >> >>" % (pw, ph, content, img))
        self.pages.append(page)

    def close(self) -> None:
        kids = b" ".join(b"%d 0 R" % p for p in self.pages)
        self._obj(2, b"<< /Type /Pages /Kids [%s] /Count %d >>" % (kids, len(self.pages)))
        self._obj(1, b"<< /Type /Catalog /Pages 2 0 R >>")
        subject = self.comment.encode("latin-1", "replace").replace(b"\\", b"\\\\").replace(b"(", b"\\(") \
            .replace(b")", b"\\)")
        self._obj(4, b"<< /Producer (velpoly) /Subject (%s) >>" % subject)
        start = self.fp.tell()
        n = self.next_id
        self.fp.write(b"xref\n0 %d\n0000000000 65535 f \n" % n)
        for i in range(1, n):
            self.fp.write(b"%010d 00000 n \n" % self.offsets.get(i, 0))
        self.fp.write(b"trailer\n<< /Size %d /Root 1 0 R /Info 4 0 R >>\nstartxref\n%d\n%%%%EOF\n" % (n, start))


def write_animation(anim: Animator, out, fps: float = 15.0, progress=None) -> Path:
    """Write every frame of ``anim`` into ``out`` (GIF, animated PNG, MP4 or PDF by its suffix), atomically:
    a failure (or Ctrl-C) leaves no file and no temporary file. ``progress(done, total)`` is called after
    each frame."""
    from ..fileio import atomic_path
    out = Path(out)
    fmt = out.suffix.lower()
    if fmt not in FORMATS:
        raise InputError(f"unknown animation type {out.suffix or '(none)'!r}", where="-o", file=str(out),
                         hint="end the output's name with .gif, .png (animated PNG), .mp4, .pdf or .html")
    if not (math.isfinite(fps) and 0.5 <= fps <= 60):
        raise InputError(f"the frame rate must be 0.5 to 60 frames a second, got {fps:g}", where="--fps",
                         hint="e.g. --fps 15")
    n = anim.n
    comment = f"velpoly animate: {anim.m.title}: {anim.plan.caption}"
    if fmt == ".mp4":
        writer = mp4_writer()        # before anything is written: exit 2 naming the extra when missing
    with atomic_path(out) as tmp:
        if fmt in (".gif", ".png", ".pdf"):
            sample = [anim.render(0)]
            if n > 2:
                sample.append(anim.render(n // 2))
            pal = _Palette(sample)
            with open(tmp, "wb") as fp:
                w = _GifWriter(fp, anim.size, fps, comment) if fmt == ".gif" else \
                    _ApngWriter(fp, anim.size, fps, n, comment) if fmt == ".png" else \
                    _PdfWriter(fp, anim.size, n, comment)
                for k in range(n):
                    w.add(sample[0] if k == 0 else anim.render(k), pal)
                    if progress:
                        progress(k + 1, n)
                w.close()
        else:
            gen = writer(str(tmp), anim.size, fps=fps, codec="libx264", pix_fmt_in="rgba", quality=7,
                         macro_block_size=1, ffmpeg_log_level="error", output_params=["-f", "mp4"])
            gen.send(None)
            try:
                for k in range(n):
                    gen.send(np.ascontiguousarray(anim.render(k)))
                    if progress:
                        progress(k + 1, n)
            finally:
                gen.close()
    return out


def mp4_writer():
    try:
        import imageio_ffmpeg
    except ImportError:
        raise InputError("writing MP4 needs imageio-ffmpeg, which is not installed", where="-o",
                         hint="pip install 'velpoly[video]' (or imageio-ffmpeg), or write .gif, .png or .pdf") from None
    return imageio_ffmpeg.write_frames


# -- the gallery's animations ---------------------------------------------------------------------------
GALLERY_FAMILIES = (   # (family, example file's stem): one animation a mechanism family
    ("Four-bar", "ex3_6_fourbar"),
    ("Slider-crank", "ex3_5_slider_crank"),
    ("Inverted slider-crank", "ex3_3_inverted_slider"),
    ("Quick return (slotted lever)", "crank_shaper"),
    ("Six-bar", "problem_1_4_4_sixbar"),
    ("Cam and roller follower", "cam_roller_follower"),
    ("Rolling contact", "wheel_rolling"),
)
GALLERY_SIZE = (640, 360)
GALLERY_STEP = 8.0


def gallery_animation(m, out, size=None, step: float | None = None, fps: float = 12.0) -> Path:
    """A small animation for the gallery's README (GIF or animated PNG by ``out``'s suffix): the
    velocity sheet at ``size`` (GALLERY_SIZE), one frame every ``step`` degrees (GALLERY_STEP)."""
    plan = plan_frames(m, GALLERY_STEP if step is None else step)
    anim = Animator(plan, "velocity", "slides", GALLERY_SIZE if size is None else size)
    return write_animation(anim, out, fps)


def _animations_here(todo: list) -> list:
    """Each ``(file, out)`` of gallery_animations animated in this process: its path, or the exception."""
    from .. import load
    made = []
    for path, out in todo:
        try:
            made.append(gallery_animation(load(path), out))
        except Exception as e:
            made.append(e)
    return made


def gallery_animations(source, figures, log=None, names=None, run=None) -> tuple[list, str]:
    """One animation for each mechanism family of GALLERY_FAMILIES found in ``source`` (a folder of
    ``*.toml`` files), written as ``figures/animate-NAME.gif``; returns the files written and the
    README's section (empty if none was made). A family whose example is missing, or not among
    ``names`` (file stems; None: every family) when the gallery builds only those, is left out; one
    that fails is reported to ``log`` and left out. ``run`` (the gallery's worker processes) makes
    ``[(file, out), ...]``: each one's written path or the exception it raised, in order."""
    source, figures = Path(source), Path(figures)
    todo = [(family, stem, source / f"{stem}.toml") for family, stem in GALLERY_FAMILIES
            if (source / f"{stem}.toml").exists() and (names is None or stem in names)]
    made = (run or _animations_here)([(path, figures / f"animate-{stem}.gif") for _, stem, path in todo])
    written, rows = [], []
    for (family, stem, path), out in zip(todo, made):
        if isinstance(out, BaseException):     # one animation's failure must not stop the gallery
            if log:
                log(f"{path.name}: animation: {type(out).__name__}: {out}")
            continue
        written.append(out)
        rows.append((family, stem, out))
    if not rows:
        return written, ""
    lines = ["## Animations", "",
             "One mechanism of each family over its cycle, beside its velocity polygon (`velpoly animate "
             "FILE -o OUT.gif`, here at 640 x 360 and one frame every 8 degrees; the command's default is "
             "1920 x 1080, 2 degrees):", ""]
    for family, stem, out in rows:
        lines += [f"### {family}", "", f"![{family}: {stem}](figures/{out.name})", ""]
    return written, "\n".join(lines)


# a table whose values of one kind (unit) reach at most a largest in this band prints them in fixed point (three
# significant digits of each column's largest); beyond it (a driver at 1e90 or 1e-90 rad/s) as a sheet's table
# prints them, 1.0583×10⁸⁷, not 91 digits or 0.000000
FIXED_BAND = (1e-4, 1e8)


def _largest(vals) -> float:
    finite = np.abs(np.asarray(vals, float))
    finite = finite[np.isfinite(finite)]
    return float(finite.max()) if len(finite) else 1.0


def _largest_of_kind(rows) -> dict:
    """The largest value of each kind (unit) among the table's ``rows`` (name, values, unit)."""
    kind: dict = {}
    for _, vals, unit in rows:
        kind[unit] = max(kind.get(unit, 0.0), _largest(vals))
    return kind


def _decimals(big: float, kind: float) -> int | None:
    """The decimals a column whose largest value is ``big`` prints with: 3 significant digits of it, at most 6;
    None where the largest of its kind, ``kind``, lies beyond :data:`FIXED_BAND` (each value then as
    :func:`velpoly.render.table.number` prints it)."""
    if kind > 0 and not FIXED_BAND[0] <= kind < FIXED_BAND[1]:
        return None
    return max(0, min(6, 3 - int(math.floor(math.log10(big))) if big > 0 else 3))


def _value_text(v: float, dec: int | None, floor: float) -> str:
    """One value as a frame prints it: a dash where it is not finite; with ``dec`` decimals; else as a sheet's
    table, 0 below ``floor`` (:func:`velpoly.tables.zero_floor` of the largest of its kind, as the tables)."""
    if not math.isfinite(v):
        return "–"
    if dec is not None:
        return f"{v:.{dec}f}".replace("-", "−")
    from .table import number
    return "0" if abs(v) < floor else number(v, 5, floor=floor)
