"""Sheets: the page layouts of ``velpoly draw``, the step frames, and the files written.

=================  =================================================================
sheet              shows
=================  =================================================================
``velocity``       the displacement diagram and the velocity polygon; results table
``acceleration``   the displacement diagram and the acceleration polygon; table
``poles``          the mechanism with every instant centre and the Kennedy lines,
                   the Kennedy circle; table
``full``           displacement diagram, velocity and acceleration polygons; table
``displacement``   the displacement diagram alone with the given data (lengths, frame
                   pivots, the driver's angle, ω and α): a problem handout, no answers
=================  =================================================================

A file's ``[drawing] sheet`` names the sheet drawn when none is asked for
(:func:`default_sheet`).

With ``steps`` the construction is built up one step per frame (the
polygons' steps, or the poles in order of discovery), each frame captioned
with the step's vector equation: a multi-page PDF, or numbered SVG/PNG files
``out-01.svg``, ``out-02.svg`` ... Every view is that of the finished
construction, so frames do not jump. Output is reproducible (fixed SVG hash
salt, no dates) and written atomically: a failed run leaves no file.
"""
from __future__ import annotations

import io
import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from ..fileio import atomic_path
from .canvas import equation_tex, fit_view, nice_scale, view_scale
from .constructions import Constructions, check_sheet as _check_sheet, constructions
from .displacement import draw_mechanism, equivalent_linkage_note, mark_auxiliary, mechanism_bounds
from .kennedy import draw_kennedy_circle, draw_poles, pole_label
from .labels import placer
from .options import SHEETS, drawing_options
from .polygon import draw_polygon, legend_room, polygon_bounds
from .scalebar import scale_text
from .style import get_style, rc_context
from ..reference import at_file_pose
from .table import draw_results_table, given_table

__all__ = ["SHEETS", "fit_width", "Constructions", "constructions", "render_sheet", "frames", "draw_to_file", "mechanism_svg",
           "equation_tex", "default_sheet"]
FORMATS = (".svg", ".png", ".pdf")


def default_sheet(m) -> str:
    """The sheet a mechanism draws when none is asked for: its ``[drawing] sheet``, else ``full``."""
    return drawing_options(m).sheet


# -- layouts (fractions of the page: left, bottom, width, height) ----------------------------------
_LAYOUTS = {
    "velocity": {"mechanism": (0.02, 0.31, 0.47, 0.545), "velocity": (0.51, 0.31, 0.47, 0.545),
                 "table": (0.05, 0.02, 0.9, 0.23)},
    "acceleration": {"mechanism": (0.02, 0.31, 0.47, 0.545), "acceleration": (0.51, 0.31, 0.47, 0.545),
                     "table": (0.05, 0.02, 0.9, 0.23)},
    # the poles' panel takes the full height left of the Kennedy circle, the table sits beneath the
    # circle; a table too wide for that column (its type would shrink, or rows be cut) goes to the bottom
    "poles": {"poles": (0.01, 0.03, 0.65, 0.83), "kennedy": (0.69, 0.5, 0.29, 0.34),
              "table": (0.68, 0.03, 0.31, 0.42)},
    "poles-wide-table": {"poles": (0.02, 0.31, 0.62, 0.545), "kennedy": (0.67, 0.36, 0.3, 0.375),
                         "table": (0.05, 0.02, 0.9, 0.23)},
    # a wide, flat mechanism (a far pole on the line of frame pivots): the whole width for it, the
    # Kennedy circle and the table beneath
    "poles-wide": {"poles": (0.01, 0.4, 0.98, 0.46), "kennedy": (0.02, 0.02, 0.28, 0.33),
                   "table": (0.33, 0.02, 0.65, 0.33)},
    # the problem's handout: the space diagram large, the given data beside it
    "displacement": {"mechanism": (0.02, 0.03, 0.63, 0.83), "table": (0.68, 0.03, 0.3, 0.83)},
    "full": {"mechanism": (0.01, 0.37, 0.33, 0.485), "velocity": (0.34, 0.37, 0.32, 0.485),
             "acceleration": (0.67, 0.37, 0.32, 0.485), "table": (0.05, 0.02, 0.9, 0.29)},
}
_CAPTIONS = {"mechanism": "Space diagram", "velocity": "Velocity polygon", "acceleration": "Acceleration polygon",
             "poles": "Instant centres", "kennedy": "Kennedy circle (order of discovery)"}


def _space_bounds(sol, cons: Constructions):
    """The mechanism's box, grown to the auxiliary points of the constructions within reach."""
    import numpy as np
    from .kennedy import REACH
    x0, y0, x1, y1 = mechanism_bounds(sol)
    c = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
    for poly in (cons.velocity, cons.acceleration):
        for aux in (poly.auxiliary.values() if poly is not None else ()):
            p = np.asarray(aux.position, float)
            if float(np.hypot(*(p - c))) <= REACH * sol.mechanism.size:
                x0, y0, x1, y1 = min(x0, p[0]), min(y0, p[1]), max(x1, p[0]), max(y1, p[1])
    return x0, y0, x1, y1


@dataclass(frozen=True)
class Frame:
    """One picture of a sheet: how many steps of each construction, and the caption."""

    velocity: int | None = None
    acceleration: int | None = None
    poles: int | None = None
    caption: str = ""


def _pole_caption(p) -> str:
    """A pole's step in words (:func:`velpoly.poles.pole_caption`), its names in mathtext."""
    from ..poles import pole_caption
    parts = re.split(r"(\x00[^\x00]*\x00)", pole_caption(p, lambda key: f"\x00{key}\x00"))
    return "".join(pole_label(tuple(t[1:-1].split("-", 1))) if t.startswith("\x00") else equation_tex(t)
                   for t in parts)


def frames(sheet: str, cons: Constructions, steps: bool) -> list[Frame]:
    """The frames of a sheet: one (everything) without ``steps``, else one a construction step."""
    if not steps:
        return [Frame()]
    out = []
    vel, acc, ps = cons.velocity, cons.acceleration, cons.poles
    if sheet in ("velocity", "full") and vel is not None:
        for k, s in enumerate(vel.steps, 1):
            out.append(Frame(velocity=k, acceleration=0, caption=f"Step {k}: " + equation_tex(s.caption or s.equation)))
    if sheet in ("acceleration", "full") and acc is not None:
        for k, s in enumerate(acc.steps, 1):
            out.append(Frame(acceleration=k, caption=f"Step {len(out) + 1}: " + equation_tex(s.caption or s.equation)))
    if sheet == "poles" and ps is not None:
        found = sorted((p for p in ps.poles.values() if p.order > 0), key=lambda p: p.order)
        out.append(Frame(poles=0, caption="Poles known by inspection: pins, sliders, rolling contacts"))
        for p in found:
            out.append(Frame(poles=p.order, caption=f"Step {p.order}: " + _pole_caption(p)))
    return out or [Frame()]


def fit_width(fig, text, width: float, smallest: float = 0.7) -> None:
    """Shrink ``text``'s type until it is at most ``width`` (a fraction of the page) wide, down to
    ``smallest`` of its size (a long caption in large slide type would run into its neighbour)."""
    from .canvas import renderer_of
    r = renderer_of(fig)
    size = text.get_fontsize()
    w = text.get_window_extent(r).width / (fig.get_figwidth() * fig.dpi)
    if w > width:
        text.set_fontsize(max(size * width / w * 0.99, size * smallest))


def _page(fig, st, m, sol):
    """The page's title, typeset like a step's equation (``omega_2`` -> omega with subscript 2, ``30 deg``
    -> 30°) and shrunk to the page's width where it must be; return it."""
    title = equation_tex(m.title)
    if not at_file_pose(sol):   # drawn with --angle: say where the driver is
        title += f"  (driver at {sol.driver_angle:.4g}°)"
    t = fig.text(0.5, 0.975, title, ha="center", va="top", fontsize=st.title_size, gid="sheet-title")
    fit_width(fig, t, 0.96)
    return t


def _step_caption(fig, st, title, caption: str) -> float:
    """The frame's caption, boxed, under the title; return the height left above the panels (the
    fraction of the page where the panels' captions must end)."""
    from .canvas import renderer_of
    r = renderer_of(fig)
    hpx = fig.get_figheight() * fig.dpi
    top = title.get_window_extent(r).y0 / hpx - 0.012
    t = fig.text(0.5, top, caption, ha="center", va="top", fontsize=st.font_size * 1.1, gid="step-caption",
                 bbox=dict(boxstyle="round,pad=0.3", facecolor=st.paper, edgecolor=st.ink, lw=st.thin_lw))
    fit_width(fig, t, 0.94)
    # the room is that of a line with sub- and superscripts at the full size, whatever this frame's
    # equation, so that every frame's panels are alike; the box's patch is laid out when drawn: the text's
    # box grown by the pad (0.3 of the type size)
    probe = fig.text(0.5, top, r"Step 1: $A^{t}_{B_{3}}$ (Mg)", ha="center", va="top", fontsize=st.font_size * 1.1)
    bottom = min(probe.get_window_extent(r).y0, t.get_window_extent(r).y0)
    probe.remove()
    bottom -= (0.3 * st.font_size * 1.1 + st.thin_lw) * fig.dpi / 72
    return bottom / hpx - 0.008


def _poles_layout(sol, st, opts, cons: Constructions) -> str:
    """The poles sheet's layout that draws the mechanism largest (the first of equals, in order:
    table beside the panel, beneath it, panel across the page)."""
    from .kennedy import poles_bounds
    names = ["poles", "poles-wide-table", "poles-wide"]
    if opts.scale is not None or cons.poles is None:
        return names[0] if _fits_beside(sol, st, cons) else names[1]
    x0, y0, x1, y1 = poles_bounds(sol, cons.poles)
    w_in, h_in = st.figsize

    def scale(name):
        _, _, w, h = _LAYOUTS[name]["poles"]
        usable = 0.8     # draw_poles fits with a margin of 0.1 a side
        need = max((x1 - x0) / (w * w_in * 2.54 * usable), (y1 - y0) / (h * h_in * 2.54 * usable), 1e-300)
        return nice_scale(need)
    best = min(names, key=lambda n: (scale(n), names.index(n)))
    if best == "poles" and not _fits_beside(sol, st, cons):   # measured only when it would win
        best = min(names[1:], key=lambda n: (scale(n), names.index(n)))
    return best


def _fits_beside(sol, st, cons: Constructions) -> bool:
    """Whether the poles sheet's table fits the column beneath the Kennedy circle at its full type size."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=st.figsize, dpi=72)
    FigureCanvasAgg(fig)
    ax = fig.add_axes(_LAYOUTS["poles"]["table"])
    art = draw_results_table(sol, ax, sheet="poles", style=st, poleset=cons.poles)
    return art.size >= st.small_size - 1e-9 and art.shown == len(art.table.rows)


def render_sheet(sol, sheet: str = "full", style="textbook", *, cons: Constructions | None = None,
                 frame: Frame | None = None, pins: dict | None = None):
    """The matplotlib Figure of one sheet (one frame of it); no pyplot involved.

    Call inside :func:`velpoly.render.style.rc_context` for the style's fonts
    (:func:`draw_to_file` does). ``pins``: the ``_velpoly_pins`` of the
    finished construction's figure (every figure has them): a step frame
    then has its labels, scale bars, legend and scales where the finished
    construction has them, so that nothing jumps from frame to frame.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    _check_sheet(sheet)
    st = get_style(style)
    m = sol.mechanism
    opts = drawing_options(m)
    cons = cons if cons is not None else constructions(sol, sheet)
    frame = frame or Frame()
    layout = dict(_LAYOUTS[sheet])
    if sheet == "poles" and opts.table:
        layout = dict(_LAYOUTS[_poles_layout(sol, st, opts, cons)])
    if sheet == "full" and cons.acceleration is None:
        layout = dict(_LAYOUTS["velocity"])
    if not opts.table and sheet != "displacement":   # the handout's table is the problem's data
        layout.pop("table")
        for k, (l, b, w, h) in layout.items():
            layout[k] = (l, b - 0.24 if b >= 0.3 else b, w, h + 0.24) if b >= 0.3 else (l, b, w, h)
    fig = Figure(figsize=st.figsize, dpi=72)   # text is measured at the dpi vector output is written at
    FigureCanvasAgg(fig)
    title = _page(fig, st, m, sol)
    if frame.caption:
        # the frame's caption takes its own room under the title: the panels beneath it, their captions
        # clear of it (the panels of every frame alike, so that frames do not jump)
        limit = _step_caption(fig, st, title, frame.caption) - 1.35 * st.font_size / (72 * st.figsize[1]) - 0.004
        for k, (l, b, w, h) in layout.items():
            if k != "table" and b + h > limit:
                layout[k] = (l, b, w, limit - b)
    axes = {name: fig.add_axes(rect, label=name) for name, rect in layout.items()}
    pins = pins or {}
    for name, ax in axes.items():
        placer(ax).pins = pins.get(name, {})
    captions = {}
    if "mechanism" in axes:
        ax = axes["mechanism"]
        s = fit_view(ax, _space_bounds(sol, cons), scale=opts.scale, margin=0.1)
        ax.set_axis_off()
        draw_mechanism(sol, ax, style=st, options=opts)
        for poly in (cons.velocity, cons.acceleration):
            if poly is not None and (sheet != "full" or poly is cons.velocity):
                mark_auxiliary(sol, ax, poly, style=st)
        captions["mechanism"] = scale_text(s, m.units, 0)
    if "poles" in axes:
        ax = axes["poles"]
        draw_poles(sol, ax, style=st, options=opts, poleset=cons.poles, upto=frame.poles)
        captions["poles"] = scale_text(view_scale(ax), m.units, 0)
    if "kennedy" in axes:
        draw_kennedy_circle(sol, axes["kennedy"], style=st, options=opts, poleset=cons.poles, upto=frame.poles)
    for kind, poly, upto, power in (("velocity", cons.velocity, frame.velocity, 1),
                                    ("acceleration", cons.acceleration, frame.acceleration, 2)):
        if kind not in axes or poly is None:
            continue
        ax = axes[kind]
        user = opts.velocity_scale if kind == "velocity" else opts.acceleration_scale
        pinned = pins.get(kind, {}).get("_scale")
        s = fit_view(ax, polygon_bounds(poly), scale=user if pinned is None else pinned[1], margin=0.08)
        if pinned is not None:   # the finished construction's view (it may leave a strip for the legend)
            ax.set_xlim(*pinned[2])
            ax.set_ylim(*pinned[3])
        ax.set_axis_off()
        art = draw_polygon(poly, ax, mechanism=m, style=st, options=opts, upto=upto)
        for attempt in range(3 if user is None and pinned is None else 0):
            # a legend that finds no free place: the polygon fitted beside a strip kept for it (along the
            # top or the right, whichever draws the polygon larger); else a round scale smaller
            leg = art.get("legend")
            if not leg or getattr(leg[0], "_velpoly_hits", 0) == 0:
                break
            bounds, room = polygon_bounds(poly), None
            if attempt == 0:
                bounds, room = legend_room(ax, bounds, leg[0]._velpoly_paper, 0.08, label=st.font_size)
            ax.cla()
            del ax._velpoly_placer
            s = fit_view(ax, bounds, scale=room if room is not None else nice_scale(s * 1.001), margin=0.08)
            ax.set_axis_off()
            art = draw_polygon(poly, ax, mechanism=m, style=st, options=opts, upto=upto)
        placer(ax).placed["_scale"] = ("scale", s, tuple(ax.get_xlim()), tuple(ax.get_ylim()))
        captions[kind] = scale_text(s, m.units, power)
    caps = []
    for name, ax in axes.items():
        if name == "table":
            continue
        pos = ax.get_position()
        text = _CAPTIONS[name] + (f"   ({captions[name]})" if name in captions else "")
        if name == "mechanism" and equivalent_linkage_note(m):   # a second line: the dashed linkage
            text += "\n" + equivalent_linkage_note(m)
        cap = fig.text(pos.x0 + pos.width / 2, pos.y1 + 0.004, text, ha="center", va="bottom",
                       fontsize=st.font_size, style="italic", gid=f"caption-{name}")
        fit_width(fig, cap, pos.width + 0.008)   # within its column: clear of its neighbours and the page's edge
        caps.append(cap)
    for cap in caps:   # the captions of a sheet in one size, that of the one that had to shrink most
        cap.set_fontsize(min(c.get_fontsize() for c in caps))
    fig._velpoly_pins = {name: dict(placer(ax).placed) for name, ax in axes.items()}
    if "table" in axes and sheet == "displacement":
        art = draw_results_table(sol, axes["table"], style=st, table=given_table(sol))
        for t in art.get("title"):
            t.set_gid("data-table")
    elif "table" in axes:
        shows = {"velocity": ("velocity",), "acceleration": ("acceleration",), "poles": (),
                 "full": ("velocity", "acceleration")}[sheet]
        draw_results_table(sol, axes["table"], sheet=sheet, style=st,
                           velocity=cons.velocity if "velocity" in shows else None,
                           acceleration=cons.acceleration if "acceleration" in shows else None,
                           poleset=cons.poles)
    return fig


def _save(fig, target, fmt: str, st) -> None:
    if fmt == "png":   # the pixels savefig draws, encoded in a third of its time (velpoly.render.pngfile)
        from .pngfile import save_png
        return save_png(fig, target, st.dpi)
    meta = {"svg": {"Date": None}, "pdf": {"CreationDate": None, "ModDate": None}}[fmt]
    fig.savefig(target, format=fmt, metadata=meta, dpi=st.dpi if fmt == "png" else 72)


def _numbered(out: Path, i: int, n: int) -> Path:
    width = max(2, len(str(n)))
    return out.with_name(f"{out.stem}-{i:0{width}d}{out.suffix}")


def draw_to_file(sol, out, sheet: str = "full", style: str = "textbook", steps: bool = False, *,
                 cons: Constructions | None = None) -> list[Path]:
    """Draw ``sheet`` of ``sol`` into ``out`` (SVG, PNG or PDF by its suffix); return the paths written.

    With ``steps``: a PDF gets one page a frame; SVG and PNG one file a frame,
    ``out-01.svg``, ``out-02.svg`` ... Every frame is drawn before any file
    is written, and each file is written atomically, so a failure leaves no
    file behind.
    """
    out = Path(out)
    fmt = out.suffix.lower()
    if fmt not in FORMATS:
        raise InputError(f"unknown figure type {out.suffix or '(none)'!r}", where="-o", file=str(out),
                         hint="end the output's name with .svg, .png or .pdf")
    fmt = fmt[1:]
    _check_sheet(sheet)
    st = get_style(style)
    drawing_options(sol.mechanism)   # bad [drawing] keys fail before anything is drawn
    cons = cons if cons is not None else constructions(sol, sheet)
    pictures = frames(sheet, cons, steps)
    with rc_context(st):
        # the finished construction first: every frame then puts things where it has them
        last = render_sheet(sol, sheet, st, cons=cons, frame=pictures[-1])

        def figures():
            for fr in pictures[:-1]:
                yield render_sheet(sol, sheet, st, cons=cons, frame=fr, pins=last._velpoly_pins)
            yield last
        if steps and fmt == "pdf":
            from matplotlib.backends.backend_pdf import PdfPages
            with atomic_path(out) as tmp:
                with PdfPages(tmp, metadata={"CreationDate": None, "ModDate": None}) as pdf:
                    for fig in figures():
                        pdf.savefig(fig)
            return [out]
        blobs = []
        for fig in figures():
            buf = io.BytesIO()
            _save(fig, buf, fmt, st)
            blobs.append(buf.getvalue())
    targets = [out] if not steps else [_numbered(out, i, len(blobs)) for i in range(1, len(blobs) + 1)]
    written = []
    try:
        for target, data in zip(targets, blobs):
            with atomic_path(target) as tmp:
                tmp.write_bytes(data)
            written.append(target)
    except BaseException:
        for p in written:   # the frames written so far: regular files only (never a FIFO or a device)
            if p.is_file() and not p.is_symlink():
                p.unlink(missing_ok=True)
        raise
    return written


def mechanism_svg(m, style: str = "textbook") -> str:
    """The displacement diagram of a Mechanism at its reference pose as SVG text (Jupyter's view)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from ..solution import solve
    sol = solve(m)
    st = get_style(style)
    x0, y0, x1, y1 = mechanism_bounds(sol)
    aspect = (y1 - y0) / max(x1 - x0, 1e-300)
    w = 6.0
    h = min(max(w * aspect, 3.0), 6.0)
    with rc_context(st):
        fig = Figure(figsize=(w, h), dpi=72)
        FigureCanvasAgg(fig)
        ax = fig.add_axes((0, 0, 1, 1))
        fit_view(ax, (x0, y0, x1, y1), scale=drawing_options(m).scale, margin=0.1)
        ax.set_axis_off()
        draw_mechanism(sol, ax, style=st)
        buf = io.StringIO()
        fig.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue()
