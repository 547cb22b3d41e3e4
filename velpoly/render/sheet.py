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

import copy
import io
import re
from dataclasses import dataclass, replace
from pathlib import Path

from ..errors import InputError
from ..fileio import atomic_path, check_output, committed_together
from .canvas import equation_tex, fit_view, nice_scale, view_scale, wrap_caption
from .constructions import Constructions, check_sheet as _check_sheet, constructions
from .displacement import draw_mechanism, equivalent_linkage_note, mark_auxiliary, mechanism_bounds
from .kennedy import draw_kennedy_circle, draw_poles, pole_label
from .labels import placer
from .layout import MARGIN, arrange, cover, drawn_areas, fuller, share_row, shrinks
from .options import SHEETS, drawing_options
from .polygon import draw_polygon, legend_room, polygon_bounds
from .scalebar import scale_text
from .style import get_style, rc_context
from ..reference import at_file_pose
from .textcache import add_axes, new_canvas, share_rectangle_transforms
from .typeset import sheet_figure
from .table import cuts_the_book, draw_results_table, given_table, measure_results_table

__all__ = ["SHEETS", "fit_width", "wrap_caption", "Constructions", "constructions", "render_sheet", "render", "Rendered",
           "table_page", "frames",
           "draw_to_file", "mechanism_svg",
           "equation_tex", "default_sheet"]
FORMATS = (".svg", ".png", ".pdf")


def default_sheet(m) -> str:
    """The sheet a mechanism draws when none is asked for: its ``[drawing] sheet``, else ``full``."""
    return drawing_options(m).sheet


# -- layouts ----------------------------------------------------------------------------------------
_PANELS = {"velocity": ("mechanism", "velocity"), "acceleration": ("mechanism", "acceleration"),
           "poles": ("poles", "kennedy"), "full": ("mechanism", "velocity", "acceleration"),
           "displacement": ("mechanism",)}
# the problem's handout (fractions of the page: left, bottom, width, height): the space diagram large,
# the given data beside it
_LAYOUTS = {"displacement": {"mechanism": (0.02, 0.03, 0.63, 0.83), "table": (0.68, 0.03, 0.3, 0.83)}}
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
    table: bool = True   # the results table (a step before the last does not give the answers away)


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
    if not out:
        return [Frame()]
    return [replace(f, table=False) for f in out[:-1]] + out[-1:]


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
    if t.get_window_extent(r).width > 0.94 * fig.get_figwidth() * fig.dpi:   # too long: in two lines

        def width_of(text):
            t.set_text(text)
            return t.get_window_extent(r).width
        t.set_text(wrap_caption(caption, width_of))
    fit_width(fig, t, 0.94)
    # the room is that of two lines with sub- and superscripts at the full size, whatever this frame's
    # equation, so that every frame's panels are alike; the box's patch is laid out when drawn: the text's
    # box grown by the pad (0.3 of the type size)
    probe = fig.text(0.5, top, "Step 1: $A^{t}_{B_{3}}$ (Mg)\n$A^{t}_{B_{3}}$ (Mg)", ha="center", va="top",
                     fontsize=st.font_size * 1.1)
    bottom = min(probe.get_window_extent(r).y0, t.get_window_extent(r).y0)
    probe.remove()
    bottom -= (0.3 * st.font_size * 1.1 + st.thin_lw) * fig.dpi / 72
    return bottom / hpx - 0.008


def _page_cm(st) -> tuple[float, float]:
    return st.figsize[0] * 2.54, st.figsize[1] * 2.54


def _fit(ax, bounds, s: float | None) -> None:
    """The view of ``bounds`` at scale ``s`` (None: the round scale that fits), centred between the panel's
    margins (the scale bar's strip at the bottom is the widest)."""
    s = fit_view(ax, bounds, scale=s, margin=0.1)
    _, mt, mb = MARGIN
    y0, y1 = ax.get_ylim()
    d = (mb - mt) / 2 * s
    ax.set_ylim(y0 - d, y1 - d)


def _bounds(sol, cons: Constructions, name: str, reach: float | None = None):
    """What panel ``name`` draws, as a box in its own units (``reach``: the poles' view holds the poles within
    so many mechanism sizes, :func:`velpoly.render.kennedy.poles_bounds`)."""
    from .kennedy import poles_bounds
    if name == "mechanism":
        return _space_bounds(sol, cons)
    if name == "poles":
        return poles_bounds(sol, cons.poles, reach)
    if name == "kennedy":
        return (-1.3, -1.3, 1.3, 1.3)   # the circle and its links' labels
    return polygon_bounds(getattr(cons, name))


PAPER = (1e-4, 1e6)   # cm: a drawing a user's [drawing] scale makes smaller or larger than this is an input error


def _check_user_scales(sol, opts, cons) -> None:
    """A ``[drawing]`` scale that draws its panel's content within :data:`PAPER` (a scale written in the wrong unit,
    1e-20 or 1e300, drew nothing, hung or overflowed): else an InputError naming the key, with a scale that fits."""
    m = sol.mechanism
    for key, scale, bounds in (("scale", opts.scale, lambda: mechanism_bounds(sol)),
                               ("velocity_scale", opts.velocity_scale, lambda: polygon_bounds(cons.velocity)),
                               ("acceleration_scale", opts.acceleration_scale,
                                lambda: polygon_bounds(cons.acceleration))):
        if scale is None or (key != "scale" and getattr(cons, key.split("_")[0]) is None):
            continue
        x0, y0, x1, y1 = bounds()
        cm = max(x1 - x0, y1 - y0) / scale
        if not PAPER[0] <= cm <= PAPER[1]:
            raise InputError(f"at 1 cm = {scale:g} the drawing is {cm:.3g} cm across", where=f"drawing.{key}",
                             file=m.source, hint=f"a scale of {nice_scale(max(x1 - x0, y1 - y0) / 15):g} draws it "
                             f"15 cm across ({key}: units per cm of paper); or leave {key} out")


def _user_scale(opts, name: str):
    return {"mechanism": opts.scale, "poles": opts.scale, "velocity": opts.velocity_scale,
            "acceleration": opts.acceleration_scale}.get(name)


@dataclass
class _Plan:
    """Where a sheet's panels go (rects in fractions of the page), their scales, and the table (measured for
    its room: :class:`velpoly.render.table.TableLayout`)."""

    rects: dict
    scales: dict
    table: object = None
    reach: float | None = None   # a crowded poles sheet's view: the poles within so many mechanism sizes (else None:
    #                              kennedy.REACH; kennedy.draw_poles' reach)
    crowded: bool = False        # a crowded poles sheet (_Planner.crowded): its step frames keep this plan


class _Planner:
    """Lays out one sheet's panels and table on its page (see :mod:`velpoly.render.layout`)."""

    def __init__(self, fig, sol, st, opts, cons, sheet, top: float, table: bool, lines: int = 1, cut: bool = False):
        self.lines = lines        # of the panels' captions
        self.cut = cut            # the whole table on the table page: this page's table in less room, cut
        self.fig, self.sol, self.st, self.opts, self.cons, self.sheet = fig, sol, st, opts, cons, sheet
        self.W, self.H = _page_cm(st)
        self.top = top            # cm from the page's bottom: where the panels' captions end
        self.want_table = table
        self.width = self.W - 2 * EDGE
        self.table_rows = None    # the table's rows, gathered once for every room it is measured in
        self.measured: dict = {}  # room (fractions of the page) -> the table measured there (:meth:`_measured`)
        self.reach = None         # the poles' view (None: kennedy.REACH; a crowded sheet's less, CROWD_REACHES)

    def rect(self, x: float, y: float, w: float, h: float) -> tuple:
        return (x / self.W, y / self.H, w / self.W, h / self.H)

    def spans(self, names):
        out = []
        for name in names:
            x0, y0, x1, y1 = _bounds(self.sol, self.cons, name, self.reach)
            out.append((x1 - x0, y1 - y0))
        return out

    def least(self, names):
        """Each panel's caption width (cm) with a scale as long as most: a panel no narrower than it."""
        from .canvas import renderer_of
        r = renderer_of(self.fig)
        out = []
        for name in names:
            t = self.fig.text(0, 0, _CAPTIONS[name] + ("   (1 cm = 20000 mm/s²)" if name != "kennedy" else ""),
                              fontsize=self.st.font_size, style="italic")
            out.append(t.get_window_extent(r).width / self.fig.dpi * 2.54 + 0.2)
            t.remove()
        return out

    def draw_table(self, x: float, width: float, room: float):
        """The table measured for a room ``width`` x ``room`` cm at ``x``, the page's bottom (drawn once the
        layout is chosen, :func:`render_sheet`); (the measured table, cm used, whether it shows every row at
        its full type size)."""
        art = self._measured(self.rect(x, EDGE, width, room))
        self.table_rows = art.table
        if art.whole * room < art.used * room - 0.3:   # in fewer rows of more blocks: less of the page's height
            room = art.whole * room
            art = self._measured(self.rect(x, EDGE, width, room))
        whole = art.size >= self.st.small_size - 1e-9 and art.shown == len(art.table.rows)
        self.shown = art.shown   # (the rows the table last drawn shows, of them those with a book's value)
        self.need = art.whole * room   # (cm: the height it would take to show every row at this width)
        ref = art.table.header.index("reference") if "reference" in art.table.header else None
        self.refs = sum(1 for r in art.table.rows if r[ref]) if ref is not None else 0
        return art, art.used * room, whole

    def _measured(self, rect: tuple):
        """The table measured for ``rect`` (:func:`_measure_table`), once a room: the layout's search asks for some
        rooms again (a crowded poles sheet's views, the corner's counts restored). A measure is the same in the
        same room of the same sheet; each asker gets a copy of its own (a plan moves its table's room, a sheet
        with a table page rewrites its last line: :meth:`TableLayout.set_position`, ``see_table_page``)."""
        got = self.measured.get(rect)
        if got is None:
            got = self.measured[rect] = _measure_table(self.sol, self.fig, rect, self.sheet, self.st, self.cons,
                                                       self.table_rows)
        return copy.copy(got)

    def row(self, names, x: float, width: float, height: float, bottom: float, least=None):
        """Panels ``names`` side by side in the band ``width`` x ``height`` cm at (x, bottom)."""
        users = [_user_scale(self.opts, n) for n in names]
        row = share_row(self.spans(names), width, height, GAP, users, least=least)
        rects, xs = {}, x
        for name, w in zip(names, row.widths):
            rects[name] = self.rect(xs, bottom, w, height)
            xs += w + GAP
        return rects, dict(zip(names, row.scales))

    def over_table(self, names) -> _Plan:
        """The table across the page's bottom in as few lines as its blocks take (at most
        :data:`TABLE_MOST` of the page; up to the last of :data:`TABLE_TALLER` where rows with a book's value
        are cut and the drawings keep :data:`TABLE_SHRINK` of their size), the panels above it in one row or
        two (:func:`arrange`); or the table in the page's corner (:meth:`table_in_corner`) or beside a
        panel (:meth:`table_beside`), whichever draws the panels largest."""
        spans = dict(zip(names, self.spans(names)))
        least = dict(zip(names, self.least(names)))
        users = {n: _user_scale(self.opts, n) for n in names}
        floor, tax, room = EDGE, None, (TABLE_CUT if self.cut else TABLE_MOST) * self.H
        if self.want_table:
            tax, used, _ = self.draw_table(EDGE, self.width, room)
            _move(tax, self, EDGE + used)
            floor = EDGE + used + TABLE_GAP
            need = self.need
        extra = {"mechanism": LABEL_ROOM * self.st.font_size / 10}
        caption = _caption_cm(self.st, self.lines)

        def panels(floor):
            return arrange(spans, names, self.width, self.top, floor, GAP, caption, users, least, extra)
        bands = panels(floor)
        size = _cover(spans, bands)
        if tax is not None and self.shown < self.refs and not self.cut:   # rows with a book's value cut
            tax, bands, room = self.taller_table(tax, bands, room, lambda b: _cover(spans, b), panels)
            size = _cover(spans, bands)
        corner = self.table_in_corner(tax, room, names, spans, least, users, extra) if tax is not None else None
        if corner is not None and corner[0] > size * (1 + 1e-9) and fuller(spans, corner[1], bands) and \
                not shrinks(corner[1], bands):   # (not one polygon shrunk to grow the other)
            size, bands, tax = corner
        rects, scales = {}, {}
        for band in bands:
            x = EDGE + band.left
            for name, w, s in zip(band.names, band.row.widths, band.row.scales):
                rects[name] = self.rect(x, band.bottom, w, band.height)
                scales[name] = s
                x += w + GAP
        plan = _Plan(rects, scales, tax)
        if tax is None or len(names) < 2:
            return plan
        # a column beside a panel is narrower than the page: no taller than the tallest such row, it cannot
        # show every row where the page's width cannot
        column = max(BESIDE_FRACTIONS) * (self.top - EDGE) + caption
        beside = self.table_beside(names, spans, least, users, extra, scales) if need <= column else None
        if beside is not None and beside[0] > size * (1 + 1e-9):
            return beside[1]
        return plan

    def taller_table(self, tax, bands, room, size, panels):
        """The table ``tax`` (``room`` cm tall, the panels' ``bands`` above it) taller, up to the last of
        :data:`TABLE_TALLER` of the page, while it then shows more rows and the drawings keep
        :data:`TABLE_SHRINK` of their size (``size``: how large bands' drawings are; ``panels``: the bands over a
        floor), until every row with a book's value shows: (the table, the bands, its room)."""
        shown, base = self.shown, size(bands)
        for frac in TABLE_TALLER:
            nax, used, _ = self.draw_table(EDGE, self.width, frac * self.H)
            more = self.shown > shown
            grown = panels(EDGE + used + TABLE_GAP) if more else None
            if not more or size(grown) < TABLE_SHRINK ** 2 * base:
                if more:
                    break
                continue
            _move(nax, self, EDGE + used)
            tax, bands, room, shown = nax, grown, frac * self.H, self.shown
            if shown >= self.refs:
                break
        self.shown = shown
        return tax, bands, room

    def table_in_corner(self, tax, room, names, spans, least, users, extra):
        """The table ``tax`` (drawn across the page) narrowed to the width its blocks take, in the page's
        bottom left corner, the last row's last panels beside it down to the page's bottom
        (:func:`arrange`'s notch): (the area the drawings cover, the bands, the table's axes), or None where
        the table leaves no room beside it or shows fewer rows so narrowed."""
        shown = self.shown
        tw = _drawn_width(tax, self) + 0.2
        if self.width - tw < CORNER_LEAST:
            return None
        nax, used, _ = self.draw_table(EDGE, tw, room)
        if self.shown < shown:
            return None
        narrow = _drawn_width(nax, self) + 0.2
        if narrow < tw - 0.5:   # so narrowed, its blocks stand one under another: narrower still
            again, more, _ = self.draw_table(EDGE, narrow, room)
            if self.shown >= shown and more <= used + 1e-6:
                tw, nax, used = narrow, again, more
            else:
                self.draw_table(EDGE, tw, room)   # (the planner's counts: those of the table kept)
        _move(nax, self, EDGE + used)
        bands = arrange(spans, names, self.width, self.top, EDGE, GAP, _caption_cm(self.st, self.lines), users,
                        least, extra, notch=(tw, used + TABLE_GAP))
        if bands.table_left:   # right of a column at the page's left
            _move(nax, self, EDGE + used, EDGE + bands.table_left)
        return _cover(spans, bands), bands, nax

    def table_beside(self, names, spans, least, users, extra, under):
        """One panel (the first, or the last) in a row with the table beside it, in a column as tall as that
        row, the other panels side by side in the other row (the first one's row above): (the area the
        drawings cover, the plan) of the one that draws them largest, every drawing at least as large as at
        the scales ``under`` (those with the table beneath), or None where none is (or the table shows not
        every row at its full size in any such column)."""
        total = self.top - EDGE
        caption = _caption_cm(self.st, self.lines)
        mx, mt, mb = MARGIN
        best = None
        for alone, others, f in [(names[0], names[1:], f) for f in BESIDE_FRACTIONS] + \
                                [(names[-1], names[:-1], f) for f in BESIDE_FRACTIONS]:
            first = alone == names[0]
            low = total * f
            high = total - low - caption
            (lw, lh) = spans[alone]
            need = lw / max(lh, 1e-300) * (low - mt - mb) + 2 * mx + extra.get(alone, 0.0)
            width = min(max(need, least.get(alone, 0.0)), 0.5 * self.width)
            bottom = self.top - low if first else EDGE        # the panel with the table beside it
            tax, used, whole = self.draw_table(EDGE + width + GAP, self.width - width - GAP, low + caption)
            if not whole:
                continue
            _move(tax, self, bottom + low + caption)
            row = share_row([spans[n] for n in others], self.width, high, GAP, [users.get(n) for n in others],
                            least=[least.get(n, 0.0) for n in others], extra=[extra.get(n, 0.0) for n in others])
            one = share_row([spans[alone]], width, low, 0.0, [users.get(alone)], least=[least.get(alone, 0.0)],
                            extra=[extra.get(alone, 0.0)])
            size = cover(drawn_areas([spans[n] for n in others], row) + drawn_areas([spans[alone]], one))
            smaller = any(s > under[n] * (1 + 1e-9) for n, s in zip(others + [alone], row.scales + one.scales))
            if smaller or (best is not None and size <= best[0] * (1 + 1e-9)):
                continue
            rects, x = {alone: self.rect(EDGE, bottom, width, low)}, EDGE
            for name, w in zip(others, row.widths):
                rects[name] = self.rect(x, EDGE if first else self.top - high, w, high)
                x += w + GAP
            best = (size, _Plan(rects, {**dict(zip(others, row.scales)), alone: one.scales[0]}, tax))
        return best

    def poles(self) -> _Plan:
        """The poles sheet: the mechanism at the full height with the Kennedy circle and the table in a
        column beside it, or across the page with them beneath it (whichever draws it larger), or, where
        the table is too wide for the column, the panels side by side over the table.

        A crowded panel (:meth:`crowded`: too little paper about its links for its labels) is drawn larger
        where it can be at least :data:`CROWD_GAIN` times as large: in the layout that draws it largest, the
        table cut to its room (its rows counted) rather than the drawing shrunk for it (but for the rows with a
        book's value); then, while still crowded, with a view that holds fewer far poles
        (:data:`CROWD_REACHES`: a pole out of view is an arrow at the border with its position)."""
        if not self.want_table:
            return self.over_table(["poles", "kennedy"])
        first = plan = self._poles_plan(False)
        if not self.crowded(plan):
            return plan
        for reach in CROWD_REACHES:
            self.reach = reach
            other = self._poles_plan(True)
            s = other.scales["poles"]
            if s < plan.scales["poles"] * (1 - 1e-9) and s * CROWD_GAIN <= first.scales["poles"] * (1 + 1e-9):
                plan = other
            if not self.crowded(plan):
                break
        return replace(plan, crowded=True)

    def crowded(self, plan) -> bool:
        """Whether the poles panel of ``plan`` gives its labels (a pole's and a point's each) less than
        :data:`CROWD_ROOM` cm² each of the paper about its links (their box at the plan's scale, each side at
        least half the other: a flat slider-crank's poles spread along it), at 10-pt type (a larger type
        needs more, as its square)."""
        from .displacement import mechanism_bounds
        x0, y0, x1, y1 = mechanism_bounds(self.sol)
        s = plan.scales["poles"]
        w, h = (x1 - x0) / s, (y1 - y0) / s
        n = len(self.cons.poles.poles) + len(self.sol.mechanism.points)
        return max(w, h / 2) * max(h, w / 2) < CROWD_ROOM * n * (self.st.font_size / 10) ** 2

    def _poles_plan(self, crowded: bool) -> _Plan:
        """The poles sheet beside or across (:meth:`poles`); ``crowded``: the table is cut to the room the
        drawing leaves it, the drawing shrunk only for the rows with a book's value."""
        total = self.top - EDGE
        (pw, ph), = self.spans(["poles"])
        user = _user_scale(self.opts, "poles")
        mx, mt, mb = MARGIN
        column = min(max(self.width - GAP - pw / ph * (total - mt - mb) - 2 * mx, 0.3 * self.W), 0.42 * self.W)
        wide = share_row([(pw, ph)], self.width, total - TABLE_GAP - TABLE_LEAST * self.H, 0.0, [user])
        column = self._column_keeping_type(column) if crowded else column
        if column is None:   # no column holds the table at its type size
            return self._poles_across(wide, crowded)
        beside = share_row([(pw, ph)], self.width - GAP - column, total, 0.0, [user])
        if beside.scales[0] > wide.scales[0]:
            return self._poles_across(wide, crowded)
        return self._poles_beside(column, beside, crowded) or self._poles_across(wide, crowded)

    def _column_keeping_type(self, column: float) -> float | None:
        """The narrowest column, from ``column`` cm wide up to 0.42 of the page's width (in fifths of the way),
        whose table (under the Kennedy circle) keeps :data:`CROWD_TYPE` of its type size, its rows cut to the
        room; None where none does (a crowded sheet's table is cut, not set too small to read from afar)."""
        total = self.top - EDGE
        most = 0.42 * self.W
        for w in (column + (most - column) * k / 5 for k in range(6)):
            tax, _, _ = self.draw_table(EDGE + self.width - w, w, total - min(w, 0.45 * total, KENNEDY_MOST) - TABLE_GAP)
            if tax.size >= CROWD_TYPE * self.st.small_size - 1e-9:
                return w
        return None

    def _poles_beside(self, column: float, row, cut: bool = False) -> _Plan | None:
        """The mechanism at the full height, the Kennedy circle and the table in a column beside it; None where
        the table does not show every row at its size there (``cut``: every row with a book's value, the others
        cut to the room)."""
        total = self.top - EDGE
        side = min(column, 0.45 * total, KENNEDY_MOST)
        x = EDGE + self.width - column
        tax, used, whole = self.draw_table(x, column, total - side - TABLE_GAP)
        if not (whole or cut and not cuts_the_book(tax)):
            return None
        _move(tax, self, self.top - side - TABLE_GAP)
        rects = {"poles": self.rect(EDGE, EDGE, row.widths[0], total),
                 "kennedy": self.rect(x + (column - side) / 2, self.top - side, side, side)}
        return _Plan(rects, {"poles": row.scales[0]}, tax, self.reach)

    def _poles_across(self, row, crowded: bool = False) -> _Plan:
        """The mechanism across the page, the Kennedy circle and the table beneath it; the mechanism a round
        scale or two smaller (down to :data:`TABLE_SHRINK` of its size) where the table then shows more rows
        (the largest that shows every row, else the largest that shows the most); ``crowded``: only where the
        table then shows more of the rows with a book's value."""
        total = self.top - EDGE

        cap = max(_caption_cm(self.st, 1) - TABLE_GAP, 0.0)   # the Kennedy circle's caption's room over it
        caption, = self.least(["kennedy"])                    # and its width: the table starts beside both

        def place(r):
            room = total - TABLE_GAP - r.height
            side = min(room - cap, KENNEDY_MOST)
            beside = max(side, caption)
            return room, side, self.draw_table(EDGE + beside + GAP, self.width - beside - GAP, room)
        most = None
        for r in [row, *(self._smaller(row, "poles", total) if not self.cut else ())]:
            room, side, (tax, used, whole) = place(r)
            if whole or (crowded and not cuts_the_book(tax)):
                break
            if most is None or self.shown > most[0]:
                most = (self.shown, r)
        else:   # no such scale shows every row: the largest drawing with the table showing the most rows
            r = most[1]
            room, side, (tax, used, whole) = place(r)
        _move(tax, self, EDGE + room)
        rects = {"poles": self.rect(EDGE, self.top - r.height, self.width, r.height),
                 "kennedy": self.rect(EDGE + max(caption - side, 0.0) / 2, EDGE + room - cap - side, side, side)}
        return _Plan(rects, {"poles": r.scales[0]}, tax, self.reach)

    def _smaller(self, row, name: str, height: float) -> list:
        """The one-panel ``row`` of panel ``name`` at each round scale smaller, down to :data:`TABLE_SHRINK` of its
        size (none for a user's scale), largest first: the room the table may take from a drawing to show
        its rows."""
        if _user_scale(self.opts, name) is not None:
            return []
        (w, h), = self.spans([name])
        out, s = [], row.scales[0]
        while True:
            s = nice_scale(s * 1.001)
            if row.scales[0] / s < TABLE_SHRINK - 1e-9:
                return out
            out.append(share_row([(w, h)], self.width, height, 0.0, [s]))


EDGE = 0.3          # cm of paper kept free along the page's sides and bottom
GAP = 0.35          # cm between panels side by side
TABLE_GAP = 0.5     # cm between the panels and the table beneath them
TABLE_LEAST = 0.22  # of the page's height: the table's room at least, before the panels take theirs
TABLE_MOST = 0.4   # of the page's height: the table's room at most
TABLE_CUT = 0.35   # of a slide's height: the table's room at most where the whole table is on the table page
LABEL_ROOM = 2.0    # cm beside a mechanism for its labels (at 10 pt type)
KENNEDY_MOST = 8.0  # cm: the Kennedy circle's panel at most
TABLE_TALLER = (0.45, 0.5, 0.55)   # of the page's height: the table's room where rows with a book's value are cut
TABLE_SHRINK = 0.75  # a drawing shrunk to no less than this (its length) so that the table shows every row
CORNER_LEAST = 6.0  # cm beside the table in the page's corner: the least room for panels there
BESIDE_FRACTIONS = (0.4, 0.5)   # of the panels' height: the last row's, with the table beside its panel
CROWD_ROOM = 1.5    # cm² of paper about a poles panel's links for each pole's or point's label (10-pt type)
CROWD_GAIN = 1.25   # a crowded poles panel is laid out anew only where that draws it this much larger (its length)
CROWD_TYPE = 0.85   # of the table's type size: the least a crowded poles sheet's table in its column is set at
CROWD_REACHES = (2.5, 1.5, 1.0, 0.75)   # mechanism sizes: a crowded poles panel's view, tried in turn (kennedy.REACH first)


def _cover(spans, bands) -> float:
    """How large the bands' drawings are, all together (:func:`velpoly.render.layout.cover`)."""
    return cover([a for b in bands for a in drawn_areas([spans[n] for n in b.names], b.row)])


def _drawn_width(tab, planner) -> float:
    """The width (cm) the measured table ``tab``'s blocks, title and footnotes take in its room, from its left
    edge, as drawn there (:func:`velpoly.render.table.drawn_extent`: measured, not drawn)."""
    from .table import drawn_extent
    left, right = drawn_extent(tab, planner.fig)
    return (right - left) / planner.fig.dpi * 2.54


def _move(tax, planner, top: float, left: float | None = None) -> None:
    """Move the table's axes so that its top stands ``top`` cm from the page's bottom (and its left ``left`` cm
    from the page's left edge; its texts and rules are in axes coordinates: they move with it)."""
    x, _, w, h = tax.get_position().bounds
    tax.set_position((x if left is None else left / planner.W, top / planner.H - h, w, h))


def _measure_table(sol, fig, rect, sheet: str, st, cons: Constructions, table=None):
    """The sheet's table measured for ``rect`` (fractions of the page), not drawn: the layout tries it in
    several rooms (``table``: its rows gathered already)."""
    if sheet == "displacement":
        return measure_results_table(sol, (fig, rect), style=st, table=table or given_table(sol))
    shows = {"velocity": ("velocity",), "acceleration": ("acceleration",), "poles": (),
             "full": ("velocity", "acceleration")}[sheet]
    return measure_results_table(sol, (fig, rect), sheet=sheet, style=st, table=table,
                                 velocity=cons.velocity if "velocity" in shows else None,
                                 acceleration=cons.acceleration if "acceleration" in shows else None,
                                 poleset=cons.poles)


def _draw_table(sol, fig, sheet: str, st, layout):
    """The table measured (:func:`_measure_table`) drawn in an axes made at its room."""
    art = draw_results_table(sol, add_axes(fig, layout.rect, label="table"), style=st, layout=layout)
    if sheet == "displacement":
        for t in art.get("title"):
            t.set_gid("data-table")
    return art


def _panel_names(sheet: str, cons: Constructions) -> list[str]:
    if sheet == "full" and cons.acceleration is None:
        return list(_PANELS["velocity"])
    return list(_PANELS[sheet])


def _plan(fig, sol, st, opts, cons, sheet: str, top: float, table: bool, cut: bool = False) -> _Plan:
    """Where the sheet's panels and table go (the table is measured: its height decides the panels'); ``cut``:
    the whole table is on the sheet's table page, this page's table has less room (:data:`TABLE_CUT`)."""
    if sheet == "displacement":
        H = _page_cm(st)[1]
        rects = {k: (l, b, w, min(h, top / H - b)) for k, (l, b, w, h) in _LAYOUTS["displacement"].items()}
        tab = _measure_table(sol, fig, rects.pop("table"), sheet, st, cons)
        return _Plan(rects, {"mechanism": opts.scale}, tab)
    two = bool(equivalent_linkage_note(sol.mechanism)) and sheet != "poles"
    planner = _Planner(fig, sol, st, opts, cons, sheet, top, table and opts.table, 2 if two else 1, cut=cut)
    if sheet == "poles":
        return planner.poles()
    return planner.over_table(_panel_names(sheet, cons))


def _caption_cm(st, lines: int) -> float:
    """The height (cm) a panel's caption of ``lines`` lines takes over it."""
    return lines * 1.3 * st.font_size / 72 * 2.54 + 0.15


def _top(fig, st, title, caption: str, two_lines: bool) -> float:
    """Where the panels end at the top (cm from the page's bottom): under the title (and the frame's
    caption), room left for the panels' captions."""
    from .canvas import renderer_of
    H = _page_cm(st)[1]
    if caption:
        limit = _step_caption(fig, st, title, caption)
    else:
        limit = title.get_window_extent(renderer_of(fig)).y0 / (fig.get_figheight() * fig.dpi) - 0.01
    return limit * H - _caption_cm(st, 2 if two_lines else 1)


def _draw_mechanism_panel(sol, ax, st, opts, cons, sheet, scale):
    _fit(ax, _space_bounds(sol, cons), scale)
    ax.set_axis_off()
    draw_mechanism(sol, ax, style=st, options=opts)
    for poly in (cons.velocity, cons.acceleration):
        if poly is not None and (sheet != "full" or poly is cons.velocity):
            mark_auxiliary(sol, ax, poly, style=st)
    return scale_text(view_scale(ax), sol.mechanism.units, 0)


def _draw_polygon_panel(sol, ax, st, opts, poly, upto, scale, power: int, pinned):
    """A polygon in its panel at ``scale`` (a step frame: the finished construction's view, ``pinned``);
    a legend that finds no free place gets a strip kept for it, else a round scale smaller."""
    m = sol.mechanism
    user = opts.velocity_scale if power == 1 else opts.acceleration_scale
    _fit(ax, polygon_bounds(poly), scale if pinned is None else pinned[1])
    s = view_scale(ax)
    if pinned is not None:   # the finished construction's view (it may leave a strip for the legend)
        ax.set_xlim(*pinned[2])
        ax.set_ylim(*pinned[3])
    ax.set_axis_off()
    art = draw_polygon(poly, ax, mechanism=m, style=st, options=opts, upto=upto)
    for attempt in range(3 if user is None and pinned is None else 0):
        leg = art.get("legend")
        if not leg or getattr(leg[0], "_velpoly_hits", 0) == 0:
            break
        bounds, room = polygon_bounds(poly), None
        if attempt == 0:
            bounds, room = legend_room(ax, bounds, leg[0]._velpoly_paper, 0.08, label=st.font_size)
        pos = ax.get_position(original=True)
        ax.cla()   # (its limits then square: the box must not shrink to them, as an equal aspect would)
        share_rectangle_transforms(ax)   # (cla made a new background Rectangle)
        ax.set_aspect("auto")
        ax.set_position(pos)
        del ax._velpoly_placer
        s = fit_view(ax, bounds, scale=room if room is not None else nice_scale(s * 1.001), margin=0.08)
        ax.set_axis_off()
        art = draw_polygon(poly, ax, mechanism=m, style=st, options=opts, upto=upto)
    s = view_scale(ax)   # (a detail with no room at the planned scale made it coarser)
    placer(ax).placed["_scale"] = ("scale", s, tuple(ax.get_xlim()), tuple(ax.get_ylim()))
    return scale_text(s, m.units, power)


def _draw_panels(sol, axes, st, opts, cons, sheet, frame, plan, pins) -> dict:
    """Draw every panel; return each one's scale text (for its caption)."""
    captions = {}
    if "mechanism" in axes:
        captions["mechanism"] = _draw_mechanism_panel(sol, axes["mechanism"], st, opts, cons, sheet,
                                                      plan.scales.get("mechanism"))
    if "poles" in axes:
        ax = axes["poles"]
        from .kennedy import poles_bounds
        _fit(ax, poles_bounds(sol, cons.poles, plan.reach), plan.scales["poles"])
        ax.set_axis_off()
        draw_poles(sol, ax, style=st, options=opts, poleset=cons.poles, upto=frame.poles, reach=plan.reach)
        captions["poles"] = scale_text(view_scale(ax), sol.mechanism.units, 0)
    if "kennedy" in axes:
        draw_kennedy_circle(sol, axes["kennedy"], style=st, options=opts, poleset=cons.poles, upto=frame.poles)
    for kind, poly, upto, power in (("velocity", cons.velocity, frame.velocity, 1),
                                    ("acceleration", cons.acceleration, frame.acceleration, 2)):
        if kind in axes and poly is not None:
            captions[kind] = _draw_polygon_panel(sol, axes[kind], st, opts, poly, upto, plan.scales[kind], power,
                                                 pins.get(kind, {}).get("_scale"))
    return captions


def _draw_captions(fig, st, m, axes, captions) -> None:
    """Each panel's caption over it with its scale, all in one size (that of the one that shrank most)."""
    caps = []
    for name, ax in axes.items():
        pos = ax.get_position()
        text = _CAPTIONS[name] + (f"   ({captions[name]})" if name in captions else "")
        if name == "mechanism" and equivalent_linkage_note(m):   # a second line: the dashed linkage
            text += "\n" + equivalent_linkage_note(m)
        cap = fig.text(pos.x0 + pos.width / 2, pos.y1 + 0.004, text, ha="center", va="bottom",
                       fontsize=st.font_size, style="italic", gid=f"caption-{name}")
        fit_width(fig, cap, pos.width + 0.008)   # within its column: clear of its neighbours and the page's edge
        caps.append(cap)
    size = min((c.get_fontsize() for c in caps), default=st.font_size)
    from .canvas import renderer_of
    r, wpx = renderer_of(fig), fig.get_figwidth() * fig.dpi
    for cap in caps:   # the sheet's captions in one size; one wider than its panel kept on the page
        cap.set_fontsize(size)
        bb = cap.get_window_extent(r)
        shift = max(0.004 * wpx - bb.x0, 0.0) + min(0.996 * wpx - bb.x1, 0.0)
        cap.set_x(cap.get_position()[0] + shift / wpx)


@dataclass(frozen=True)
class Rendered:
    """One sheet drawn (:func:`render`): its matplotlib ``figure`` and whether its results table goes on a page
    of its own as well (``table_page``: the table on the sheet cuts a row with a book's value or a footnote;
    :func:`table_page` draws that page, :func:`draw_to_file` writes it)."""

    figure: object
    table_page: bool


def render_sheet(sol, sheet: str = "full", style="textbook", *, cons: Constructions | None = None,
                 frame: Frame | None = None, pins: dict | None = None):
    """The matplotlib Figure of one sheet (one frame of it); no pyplot involved (:func:`render`'s figure).

    Call inside :func:`velpoly.render.style.rc_context` for the style's fonts
    (:func:`draw_to_file` does). ``pins``: the ``_velpoly_pins`` of the
    finished construction's figure (every figure has them): a step frame
    then has its labels, scale bars, legend and scales where the finished
    construction has them, so that nothing jumps from frame to frame. The
    panels are laid out to fill the page (:mod:`velpoly.render.layout`); a
    frame without the table (a step before the last) is laid out as if it had it.
    """
    return render(sol, sheet, style, cons=cons, frame=frame, pins=pins).figure


def render(sol, sheet: str = "full", style="textbook", *, cons: Constructions | None = None,
           frame: Frame | None = None, pins: dict | None = None) -> Rendered:
    """One sheet (one frame of it) drawn, and whether it has a table page (:class:`Rendered`); the arguments
    as :func:`render_sheet`'s."""
    _check_sheet(sheet)
    st = get_style(style)
    m = sol.mechanism
    opts = drawing_options(m)
    cons = cons if cons is not None else constructions(sol, sheet)
    _check_user_scales(sol, opts, cons)
    frame = frame or Frame()
    fig = sheet_figure(st.figsize, st.dpi)   # laid out at 72 dpi; its texts set as its PNG sets them, in every format
    title = _page(fig, st, m, sol)
    two = bool(equivalent_linkage_note(m)) and sheet != "poles"
    if frame.caption and sheet == "poles":
        plan, own_page = _poles_frame(fig, sol, st, opts, cons, title, frame)
    else:
        plan, own_page = _laid_out(fig, sol, st, opts, cons, sheet, _top(fig, st, title, frame.caption, two))
    if own_page:
        plan.table.see_table_page()
    if plan.table is not None and frame.table:   # a step before the last: the answers not yet given
        _draw_table(sol, fig, sheet, st, plan.table)
    axes = {name: add_axes(fig, rect, label=name) for name, rect in plan.rects.items()}
    pins = pins or {}
    for name, ax in axes.items():
        placer(ax).pins = pins.get(name, {})
    captions = _draw_panels(sol, axes, st, opts, cons, sheet, frame, plan, pins)
    if pins:   # a step frame: every label whose finished place (and size) is free here goes there
        for ax in axes.values():
            placer(ax).settle()
    _draw_captions(fig, st, m, axes, captions)
    fig._velpoly_pins = {name: dict(placer(ax).placed) for name, ax in axes.items()}
    if not pins:   # the finished construction: which labels stand on lines there (they may in a frame too)
        for name, ax in axes.items():
            fig._velpoly_pins[name]["_crowded"] = ("crowded", placer(ax).crowded())
    return Rendered(fig, own_page)


def _laid_out(fig, sol, st, opts, cons, sheet: str, top: float) -> tuple:
    """The sheet's plan (:func:`_plan`) under ``top`` and whether its table has a page of its own (the book's rows
    or notes cut: every one of them on that page, as the table's last line says); a slide's then laid out
    again for its drawings, its table in less room (its height goes to the drawings; a page, read closer, keeps
    the rows it has room for)."""
    plan = _plan(fig, sol, st, opts, cons, sheet, top, True)
    own_page = plan.table is not None and cuts_the_book(plan.table)
    if own_page and st.name == "slides":
        plan = _plan(fig, sol, st, opts, cons, sheet, top, True, cut=True)
    return plan, own_page


def _poles_frame(fig, sol, st, opts, cons, title, frame) -> tuple:
    """A poles sheet's step frame's plan and whether its table has a page of its own (:func:`_laid_out`). A
    crowded sheet's frames (crowded as the plain sheet is laid out, or as a frame would be under its caption)
    keep the plain sheet's layout: its drawing's scale, view and panels where the sheet without ``--steps`` has
    them (a lecturer flips from the steps to the finished sheet and sees the same drawing), the step's caption
    at the top of the table's room (which a frame before the last leaves empty), the last frame's table
    under it (:func:`_caption_over_table`). Any other sheet's frames (or one whose caption the table's room
    cannot hold) are laid out under their caption."""
    plain, own_page = _laid_out(fig, sol, st, opts, cons, "poles", _top(fig, st, title, "", False))
    plan, own = _laid_out(fig, sol, st, opts, cons, "poles", _top(fig, st, title, frame.caption, False))
    if plain.table is None or not (plain.crowded or plan.crowded):
        return plan, own
    under_title = [t for t in fig.texts if t.get_gid() == "step-caption"]
    got = _caption_over_table(fig, sol, st, cons, plain, own_page, frame)
    if got is None:
        return plan, own
    for t in under_title:
        t.remove()
    return got


def _caption_over_table(fig, sol, st, cons, plan, own_page: bool, frame) -> tuple | None:
    """The step's caption, boxed as :func:`_step_caption`'s, at the top of the table's room in ``plan`` (a crowded
    poles sheet's plain layout), in as many lines as that width takes; the last frame's table measured in the
    room under it (its rows cut to it): the plan and whether the table has a page of its own (None, the
    caption taken off again, where the room cannot hold it)."""
    from .canvas import renderer_of
    r = renderer_of(fig)
    x, y, w, h = plan.table.rect
    t = fig.text(x + w / 2, y + h, "", ha="center", va="top", fontsize=st.font_size * 1.1, gid="step-caption",
                 bbox=dict(boxstyle="round,pad=0.3", facecolor=st.paper, edgecolor=st.ink, lw=st.thin_lw))
    pad = (0.3 * st.font_size * 1.1 + st.thin_lw) / 72   # inches: the box's pad and its outline
    room = w * fig.get_figwidth() * fig.dpi - 2 * pad * fig.dpi

    def width_of(text):
        t.set_text(text)
        return t.get_window_extent(r).width
    t.set_text("\n".join(_lines(frame.caption, width_of, room)))
    fit_width(fig, t, w - 2 * pad / fig.get_figwidth())
    t.set_y(y + h - pad / fig.get_figheight())
    bottom = (t.get_window_extent(r).y0 / fig.dpi - pad) / fig.get_figheight()
    if bottom < y:
        t.remove()
        return None
    if not frame.table:
        return plan, own_page
    bottom -= TABLE_GAP / _page_cm(st)[1]
    table = _measure_table(sol, fig, (x, y, w, max(bottom - y, 1e-3)), "poles", st, cons, plan.table.table)
    return replace(plan, table=table), own_page or cuts_the_book(table)


def _lines(text: str, width_of, room: float) -> list[str]:
    """``text`` broken at spaces outside mathtext ($...$) into lines no wider than ``room`` (``width_of``: a
    text's width, in its units), each as full as it can be (a word wider than the line stands alone on it)."""
    from .canvas import breaks
    cuts = [-1] + breaks(text) + [len(text)]
    words, lines = [text[a + 1:b] for a, b in zip(cuts[:-1], cuts[1:])], []
    for word in words:
        if lines and width_of(lines[-1] + " " + word) <= room:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return lines


def table_page(sol, sheet: str = "full", style="textbook", *, cons: Constructions | None = None):
    """The sheet's results table on a page of its own, under the page's title, every row the book gives and
    its footnotes (the page a sheet adds where its drawings and its table cannot share one page with them:
    :func:`render`'s ``table_page``). Call inside the style's rc_context."""
    st = get_style(style)
    cons = cons if cons is not None else constructions(sol, sheet)
    fig = sheet_figure(st.figsize, st.dpi)
    title = _page(fig, st, sol.mechanism, sol)
    W, H = _page_cm(st)
    top = _top(fig, st, title, "", False) + _caption_cm(st, 1) - EDGE
    rect = (EDGE / W, EDGE / H, 1 - 2 * EDGE / W, (top - EDGE) / H)
    # at the body's type size where that shows every row the book gives, else smaller, down to 0.72 of the
    # table's own size (a book that prints some thirty answers with their notes, on a slide)
    for size in (st.font_size, (st.font_size + st.small_size) / 2, st.small_size, 0.85 * st.small_size,
                 0.72 * st.small_size):
        big = replace(st, small_size=size)
        lay = _measure_table(sol, fig, rect, sheet, big, cons)
        if not cuts_the_book(lay):
            break
    _draw_table(sol, fig, sheet, big, lay)
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
    for target in [out] if not steps or fmt == "pdf" else [_numbered(out, i, len(pictures)) for i in
                                                            range(1, len(pictures) + 1)]:
        check_output(target)   # an input among the numbered frames is refused before any drawing
    with rc_context(st):
        # the finished construction first: every frame then puts things where it has them
        done = render(sol, sheet, st, cons=cons, frame=pictures[-1])
        last = done.figure
        # the table page (every row the book gives, with its notes): the PDF's last page, else OUT-table.svg
        extra = table_page(sol, sheet, st, cons=cons) if done.table_page else None

        def figures():
            for fr in pictures[:-1]:
                yield render_sheet(sol, sheet, st, cons=cons, frame=fr, pins=last._velpoly_pins)
            yield last
            if extra is not None:
                yield extra
        if fmt == "pdf" and (steps or extra is not None):
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
    frames_n = len(blobs) - (extra is not None)
    targets = [out] if not steps else [_numbered(out, i, frames_n) for i in range(1, frames_n + 1)]
    targets += [out.with_name(f"{out.stem}-table{out.suffix}")] if extra is not None else []
    with committed_together():   # all frames or none: a refused or failed frame leaves every target as it was
        for target, data in zip(targets, blobs):
            with atomic_path(target) as tmp:
                tmp.write_bytes(data)
    return targets[:len(blobs)]


def mechanism_svg(m, style: str = "textbook") -> str:
    """The displacement diagram of a Mechanism at its reference pose as SVG text (Jupyter's view)."""
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
        new_canvas(fig)
        ax = add_axes(fig, (0, 0, 1, 1))
        fit_view(ax, (x0, y0, x1, y1), scale=drawing_options(m).scale, margin=0.1)
        ax.set_axis_off()
        draw_mechanism(sol, ax, style=st)
        buf = io.StringIO()
        fig.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue()
