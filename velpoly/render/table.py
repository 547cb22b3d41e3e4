"""The results table of a sheet: graphical, analytic, instant-centre and reference values.

:func:`results_table` gathers, for the quantities a sheet constructs, the
value read off the construction (the polygon's rates and images, the poles'
positions), the range a careful hand drawing would give
(:func:`velpoly.polygons.hand_drafting`: 95 % of drawings with lines within
±0.25° and points within ±0.25 mm), the analytic solve's, the
instant-centre method's (velocities) and the book's (``[reference]``, via :func:`velpoly.reference.compare`), with
the deviation of the book from the analytic value. Printed values that are
no row of the sheet (``V_BA``, ``R_BA`` ...) follow at the end. The drawn
table is booktabs-style (rules, no boxes) and keeps to the room it has:
the rows with a book's value come first, and rows that do not fit are
summarised in a last line. A printed value that the file's ``[reference]
note`` explains is marked († ‡ § ...) and its note is a footnote beneath
the table.
"""
from __future__ import annotations

import re

import numpy as np

from ..names import NAME, driver_index, key_text, link_of, polar, quantity_math, unit, vector_direction
from ..names import direction as fmt_direction
from ..compare import Value, key_floor, kind_floor, kind_scales, polygon_values
from ..report import Table, fmt
from ..tables import ZERO
from .canvas import Artists, equation_tex, get_ax, literal, renderer_of
from .style import get_style
from .textcache import kept_layout

__all__ = ["results_table", "draw_results_table", "given_table", "cuts_the_book", "number", "number_math", "position_text", "tens"]


_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _fmt(x, digits=5, floor=ZERO) -> str:
    """A number as a table prints it: ``digits`` significant digits, a minus sign (not a hyphen), no
    computer exponent: 1e+05 -> 100000, 1.3655e+05 -> 136550, 2.5e-09 -> 2.5×10⁻⁹; 0 below ``floor``
    (:func:`velpoly.compare.kind_floor`: a billionth of the largest value of its kind, as ``velpoly solve``)."""
    s = fmt(x, digits, floor)
    if "e" in s:
        mant, _, e = s.partition("e")
        e = int(e)
        if -5 <= e < 8:
            s = f"{float(s):.{max(digits - 1 - e, 0)}f}"
            if "." in s:
                s = s.rstrip("0").rstrip(".")
        else:
            s = f"{mant}×{tens(e)}"
    return s.replace("-", "−")


number = _fmt   # public: the animation's table prints a number beyond its fixed-point room as a sheet's does


def tens(power: int) -> str:
    """Ten to an integer power as the tables print it: ``10⁻⁹⁰``."""
    return "10" + str(power).translate(_SUPERSCRIPT)


_PLAIN = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")


def number_math(x, digits=5, floor=ZERO) -> str:
    r""":func:`number` for a text that mathtext typesets (one holding ``$\omega_{2}$``, whose fonts lack the
    superscript digits): its power of ten as math, ``$1{\times}10^{-90}$`` for 1×10⁻⁹⁰; any other number as
    :func:`number` prints it.

    >>> number_math(1e-90, 4, 0.0), number_math(6.2832, 4, 0.0)
    ('$1{\\times}10^{-90}$', '6.283')
    """
    s = number(x, digits, floor)
    mant, times, power = s.partition("×10")
    return rf"${mant.replace('−', '-')}{{\times}}10^{{{power.translate(_PLAIN)}}}$" if times else s


def position_text(m, x: float) -> str:
    """The driver's position as a figure prints it: a crank's angle (degrees, within a few turns) to four
    significant digits; a slider's displacement, a length at the mechanism's scale (1e-100 to 1e100), as the tables
    print numbers (:func:`number`: 1.5×10⁻⁹⁰ mm, not 1.5e-90)."""
    return number(x, 4, 0.0) if m.driver.is_slider else f"{x:.4g}"


def _vec(v, floor=ZERO, digits=5) -> str:
    v = np.asarray(v, float)
    if not np.all(np.isfinite(v)):
        return "–"
    mag = _fmt(float(np.hypot(*v)), digits, floor)
    return "0" if mag == "0" else polar(mag, vector_direction(v))


def _q(symbol: str, index: str, unit: str = "") -> str:
    """A quantity's name: ``$\\omega_{3}$ (rad/s)``, ``$V_{B}$``, ``$V_{P₂}$`` (``index``: names as plain
    text, :mod:`velpoly.names`); the cell is drawn piece by piece (:func:`_parts`), each piece as written,
    and a footnote typesets it (:func:`_math`). An index with a brace, ``$`` or backslash in it (a user's
    name) stays one plain piece: ``V_{x}``."""
    unit = f" ({unit})" if unit else ""
    if any(c in index for c in "{}$\\"):
        return f"{_SYMBOLS.get(symbol, symbol)}_{index}{unit}"
    return "$" + symbol + "_{" + index + "}$" + unit


def _pole(links: tuple[str, str]) -> str:
    """A relative pole's name, as :func:`velpoly.render.kennedy.pole_label` writes it."""
    i, j = links
    return _q("P", f"{i}{j}" if len(i) == 1 and len(j) == 1 else f"{i},{j}")


_GREEK = {"omega": r"\omega", "alpha": r"\alpha", "theta": r"\theta"}
_COMPONENT_MARK = {"n": "ⁿ", "t": "ᵗ", "c": "ᶜ", "s": "ˢ"}   # of the components A^n, A^t, A^c, A^s


def _key(key: str, m=None) -> str:
    """A reference key as a cell: ``V_B3/B4`` -> $V_{B₃/B₄}$ (with the mechanism ``m``: each point of a link
    with the link as its subscript, :func:`velpoly.reference.display_key`), ``omega_3`` -> $\\omega_{3}$,
    ``|V_B|``."""
    if m is not None:
        from ..reference import display_key
        key = display_key(m, key)
    bars = key.startswith("|") and key.endswith("|")
    body = key.strip("|")
    sym, sep, idx = body.partition("_")
    if sym[1:2] == "^" and sym[2:] in _COMPONENT_MARK:   # a component as books print it: A^c_B3/B4 -> Aᶜ_B3/B4
        sym = sym[0] + _COMPONENT_MARK[sym[2:]]
    if not sep or not idx or not sym.isalpha():
        return key
    out = _q(_GREEK.get(sym, sym), idx)
    return f"|{out}|" if bars else out


_RICH = re.compile(r"^(\|?)\$(\\?[A-Za-z]+[ⁿᵗᶜˢ]?)_\{([^}$]*)\}\$(\|?)(.*)$")
_SYMBOLS = {r"\omega": "ω", r"\alpha": "α", r"\theta": "θ"}
_SUB, _SUBSUB = (0.72, -0.28), (0.56, -0.48)   # a subscript's size and baseline shift (ems); a subscript's own


def _index_parts(sym: str, sub: str) -> list[tuple[str, float, float, str]] | None:
    """A subscript's pieces: each name's letters and digits as a subscript, its link (P₂, P(cam)) a
    subscript of that (:mod:`velpoly.names`); a rate's link upright unless one letter; None where the
    subscript is not made of names."""
    if sym in _SYMBOLS or sub.isdigit():
        return [(literal(sub), *_SUB, "italic" if len(sub) == 1 and sub.isalpha() else "normal")]
    out, end = [], 0
    for mo in NAME.finditer(sub):
        if mo.start() != end and sub[end:mo.start()] != "/":
            return None
        if mo.start() != end:
            out.append(("/", *_SUB, "normal"))
        base, digits, link, primes = mo.groups()
        out.append((literal(base + digits + "′" * len(primes)), *_SUB, "italic"))
        if link:
            lk = link_of(link)
            out.append((literal(lk), *_SUBSUB, "italic" if len(lk) == 1 and lk.isalpha() else "normal"))
        end = mo.end()
    return out if end == len(sub) else None


def _parts(cell: str) -> list[tuple[str, float, float, str]]:
    """A cell as pieces (text, size factor, baseline shift in ems, font style): ``$V_{B}$`` -> V, B lowered;
    ``$V_{P₂}$`` -> V, P lowered, 2 lowered again."""
    m = _RICH.match(cell)
    if not m:
        return [(literal(cell), 1.0, 0.0, "normal")]
    bar, sym, sub, bar2, rest = m.groups()
    index = _index_parts(sym, sub) or [(literal(sub), *_SUB, "normal" if sub[:1].isdigit() else "italic")]
    return [(literal(bar + _SYMBOLS.get(sym, sym)), 1.0, 0.0, "italic"), *index,
            (literal(bar2 + rest), 1.0, 0.0, "normal")]


def _math(cell: str) -> str:
    """A quantity's cell as mathtext (a footnote's): ``$V_{P₂}$`` -> $V_{P_{2}}$."""
    m = _RICH.match(cell)
    if not m:
        return literal(cell)
    bar, sym, sub, bar2, rest = m.groups()
    mark = {v: k for k, v in _COMPONENT_MARK.items()}.get(sym[-1:], "")
    body = quantity_math(sym[:-1] if mark else sym, sub, sup=mark)
    return (body[:1] + bar + body[1:-1] + bar2 + body[-1:]) + literal(rest)


def _num(x, floor=ZERO, digits=5) -> str:
    return "–" if x is None else _fmt(x, digits, floor)


NOTED = "†"   # marks a deviation that the file's [reference] note explains (a misprint, a rounded value)
MARKS = ("†", "‡", "§", "¶", "‖")   # the footnotes' marks in turn; then doubled, tripled ...


def note_mark(k: int) -> str:
    """The ``k``-th footnote's mark (from 0): † ‡ § ¶ ‖ †† ‡‡ ..."""
    return MARKS[k % len(MARKS)] * (k // len(MARKS) + 1)


def _dev(row) -> str:
    if row is None:
        return ""
    parts = []
    if row.deviation is not None:
        pct = 100 * row.deviation
        parts.append("< 0.001 %" if pct < 1e-3 else (f"{pct:.0f} %" if pct >= 10 else f"{pct:.2g} %"))
    if row.angle_error is not None and row.angle_error > 5e-4:
        e = row.angle_error
        parts.append(f"{e:.0f}°" if e >= 10 else f"{e:.2g}°")
    at_infinity = getattr(row, "computed", 0) is None   # a printed pole found at infinity: no deviation
    shown = "-" if at_infinity else ", ".join(parts) or "0"
    return shown + (f" {NOTED}" if row.note else "")


def _printed(row) -> str:
    if row is None:
        return ""
    v = row.printed
    if isinstance(v, tuple):   # the book's value as printed, however small (velpoly.compare's book column)
        if row.key.startswith("P"):
            return f"({_fmt(v[0], 5, 0.0)}, {_fmt(v[1], 5, 0.0)})"
        return polar(_fmt(v[0], 5, 0.0), v[1])
    return _num(v, 0.0)


class _Rows:
    """The rows of a results table as they are gathered: each row with its ``[reference]`` comparison (or
    None), the reference rows not yet shown, and the hand-drafted ranges."""

    def __init__(self, sol, sheet, velocity, acceleration, poleset):
        from ..reference import at_file_pose, compare
        from ..report import pinned_keys
        self.sol, self.m, self.sheet = sol, sol.mechanism, sheet
        # the book's values belong to the pose the file describes, not to another driver angle
        self.refs = {r.key: r for r in compare(sol)} if self.m.reference and at_file_pose(sol) else {}
        self.used = set()
        self.ic = None
        if poleset is not None and sheet in ("velocity", "poles", "full"):
            from ..poles import instant_centre_velocities
            self.ic = instant_centre_velocities(sol, poleset)
        self.rows, self.noted = [], []   # noted: each row's reference comparison (None: none), in step
        self.hd = None
        if velocity is not None or acceleration is not None:
            from ..polygons import hand_drafting
            self.hd = hand_drafting(sol)
        self.pinned = pinned_keys(self.m)   # a point of links pinned together: one row "V_B (on 2 and 3)"
        self.scales = kind_scales(sol)

    def floor(self, kind: str) -> float:
        """Below what a value of ``kind`` prints as 0, as in ``velpoly solve``'s tables
        (:func:`velpoly.compare.kind_floor`)."""
        return kind_floor(self.scales, kind)

    def add(self, row, r) -> None:
        self.rows.append(row + (_printed(r), _dev(r)))
        self.noted.append(r)

    def ref_for(self, *keys):
        for k in keys:
            if k in self.refs:
                self.used.add(k)
                return self.refs[k]
        return None

    def drafted(self, level, table, key) -> str:
        if self.hd is None or self.hd.get(level) is None or key not in self.hd[level][table]:
            return ""
        lo, hi = self.hd[level][table][key]
        if lo == hi:
            return "exact"
        floor = self.floor({"speed": "V", "magnitude": "A"}.get(table, table))
        return f"{_num(lo, floor, 4)} … {_num(hi, floor, 4)}"

    def spelt(self, key) -> list[str]:
        """The ways a reference names the point key: B, B@3 as B3, and a pinned pair by either link."""
        names = [key, key.replace("@", "")]
        if self.pinned.get(key):
            names += [f"{self.pinned[key][0]}{lk}" for lk in self.pinned[key][1]]
        elif "@" not in key:   # one key: every link that carries it moves it alike
            names += [f"{key}{lk}" for lk in self.m.carriers.get(key, ())]
        return names

    def point_label(self, symbol, key) -> str:
        """``V_P₂``, ``V_P(cam)`` (:mod:`velpoly.names`); a pinned group's one row ``V_B (on 2 and 3)``."""
        from ..report import on_links
        if key not in self.pinned:
            return _q(symbol, key_text(key))
        return _q(symbol, key_text(self.pinned[key][0])) + f" (on {on_links(self.pinned[key][1])})"

    def shown(self, key) -> bool:
        """A key with a row of its own (not a pinned group's second key)."""
        return key not in self.pinned or self.pinned[key] is not None


def _rate_rows(t: _Rows, level: str, poly) -> None:
    """ω (α) of each moving link that turns, or that the book prints."""
    sol = t.sol
    rate, sym, unit_, name = ((sol.omega, r"\omega", "rad/s", "omega") if level == "velocity"
                              else (sol.alpha, r"\alpha", "rad/s²", "alpha"))
    # each rate graphical beside analytic (velpoly.compare); the poles sheet's omegas without a polygon
    values = (polygon_values(sol, poly)[0] if poly is not None else
              [Value(k.name, None, rate[k.name]) for k in t.m.moving_links])
    floor = t.floor(name)
    for v in values:
        lk, g = v.key, v.graphical
        r = t.ref_for(f"{name}_{lk}")
        if _num(v.analytic, floor) == "0" and (g is None or _num(g, floor) == "0") and r is None:
            continue   # a translating link (a block on a fixed guide): nothing to show
        ic = (_num(t.ic["omega"][lk], floor) if t.ic else "") if level == "velocity" else ""
        t.add((_q(sym, lk, unit_), "" if g is None else _num(g, floor), t.drafted(level, name, lk),
               _num(v.analytic, floor), ic), r)


def _point_rows(t: _Rows, level: str, poly) -> None:
    """V (A) of each point the polygon images, read off it, beside the analytic value."""
    vel = level == "velocity"
    floor = t.floor("V" if vel else "A")
    for pv in polygon_values(t.sol, poly)[1]:
        key, v = pv.key, pv.analytic
        if v is None or not np.all(np.isfinite(v)) or float(np.hypot(*v)) == 0 or not t.shown(key):
            continue
        if vel:
            r = t.ref_for(*(k for name in t.spelt(key) for k in (f"V_{name}", f"|V_{name}|")))
            ic = _vec(t.ic["velocity"][key], floor) if t.ic and key in t.ic["velocity"] else ""
        else:
            r = t.ref_for(*(f"A_{name}" for name in t.spelt(key)))
            ic = ""
        t.add((t.point_label("V" if vel else "A", key), _vec(pv.graphical, floor),
               t.drafted(level, "speed" if vel else "magnitude", key), _vec(v, floor), ic), r)


def _pole_rows(t: _Rows, poleset) -> None:
    """The poles found (not by inspection), in order of discovery, then the undefined ones (two links moving
    alike, FORMAT.md section 5: drawn nowhere, so the table says so, "undefined" in both columns)."""
    from ..reference import relative_pole
    found = sorted((p for p in poleset.poles.values() if p.order > 0), key=lambda p: p.order)
    for p in found + [p for p in poleset.poles.values() if p.undefined]:
        pos, direction = (None, None) if p.undefined else relative_pole(t.sol, *p.links)
        r = t.ref_for(f"P_{p.links[0]}{p.links[1]}", f"P{p.links[0]}{p.links[1]}")
        t.add((_pole(p.links) + (f"  ({p.order})" if p.order else ""), _where(p.position, p.direction, t.floor("P")), "",
               _where(pos, direction, t.floor("P")), ""), r)


def _other_rows(t: _Rows) -> None:
    """The book's other values this sheet is about, against the analytic solve."""
    related = {"velocity": ("V", "|V", "omega"), "acceleration": ("A", "alpha"), "poles": ("P", "V_P", "omega"),
               "full": ("V", "|V", "omega", "A", "alpha")}[t.sheet]
    for key, r in t.refs.items():
        if key in t.used or not key.startswith(related):
            continue
        comp, floor = r.computed, key_floor(t.m, key, t.scales)
        shown = "at infinity" if comp is None else (
            polar(_fmt(comp[0], 5, floor), comp[1]) if isinstance(comp, tuple) and not key.startswith("P")
            else (_where(comp, None, floor) if isinstance(comp, tuple) else _num(comp, floor)))
        t.add((_key(key, t.m), "", "", shown, ""), r)


def results_table(sol, sheet: str = "full", *, velocity=None, acceleration=None, poleset=None) -> Table:
    """The rows of a sheet's results table (a :class:`velpoly.report.Table`).

    ``velocity`` / ``acceleration``: the sheet's Polygon objects (rows of
    omega and V, alpha and A); ``poleset``: its PoleSet (the instant-centre
    column, and rows of the poles found on a poles sheet). Columns:
    quantity, graphical, analytic, instant centres (when poles are given),
    reference and its deviation from the analytic value (when the file has
    a ``[reference]``). Names as :mod:`velpoly.names` writes them.
    """
    t = _Rows(sol, sheet, velocity, acceleration, poleset)
    if velocity is not None or (t.ic is not None and sheet == "poles"):
        _rate_rows(t, "velocity", velocity)
    if velocity is not None:
        _point_rows(t, "velocity", velocity)
    if acceleration is not None:
        _rate_rows(t, "acceleration", acceleration)
        _point_rows(t, "acceleration", acceleration)
    if poleset is not None and sheet == "poles":
        _pole_rows(t, poleset)
    _other_rows(t)
    return _finish(t)


def _finish(t: _Rows) -> Table:
    """The table: no empty column; the rows the book gives first (those a ``[reference]`` note explains
    ahead of the rest, each group in its order), so that a table cut to its room shows them; each row
    whose printed value a note explains gets its own mark, and the note is a footnote."""
    m, rows = t.m, t.rows
    columns = [(0, "quantity"), (1, "graphical"), (2, "hand-drawn, 95 %"), (3, "analytic"),
               (4, "instant centres"), (5, "reference"), (6, "deviation")]
    columns = [(i, name) for i, name in columns if i == 0 or any(r[i] for r in rows)]   # no empty column
    header = [name for _, name in columns]
    rows = [tuple(r[i] for i, _ in columns) for r in rows]
    ref_col = header.index("reference") if "reference" in header else None
    noted = [r if r is not None and r.note else None for r in t.noted]
    title = "Results: graphical construction against the analytic solve"
    if t.refs and m.reference.source:
        title += f"; reference values: {m.reference.source}"
    elif m.reference and not t.refs:
        title += f"; no reference values at this driver angle ({t.sol.driver_angle:.4g}°)"
    order = (sorted(range(len(rows)), key=lambda i: (not rows[i][ref_col], noted[i] is None))
             if ref_col is not None else range(len(rows)))
    rows = [rows[i] for i in order]
    noted = [noted[i] for i in order]
    notes = []
    for i, r in enumerate(noted):
        if r is not None:
            mark = note_mark(len(notes))
            rows[i] = rows[i][:-1] + (rows[i][-1][:-len(NOTED)] + mark,)
            notes.append((mark, r.key, str(r.note)))
    if notes:
        title += f"; {NOTED} the book's value is explained in a footnote"
    return Table(title, tuple(header), tuple(rows), tuple(notes))


def _link_lengths(sol) -> list[tuple[str, str]]:
    """Each moving link's lengths between its points (a plate of more than four points around its
    outline; not to a point that slides on the link)."""
    m, pos = sol.mechanism, sol.position
    # a point that slides on a link (a slider on its guide, a pin in its slot, a contact) has no fixed
    # distance from that link's other points
    sliding = {(s.point, s.guide) for s in m.sliders} | {(s.pin, s.slot) for s in m.slots} | \
        {(c.point, lk) for c in m.contacts for lk in c.links}

    def at(p, link):
        return np.asarray(pos.get(f"{p}@{link}", pos.get(p, m.position(p))), float)
    rows, floor = [], kind_floor(kind_scales(sol), "P")
    for link in m.moving_links:
        ps = [p for p in dict.fromkeys(link.points) if (p, link.name) not in sliding]
        if len(ps) <= 4:
            pairs = [(a, b) for i, a in enumerate(ps) for b in ps[i + 1:]]
        else:
            pairs = list(zip(ps, ps[1:] + ps[:1]))
        for a, b in pairs:
            d = float(np.hypot(*(at(b, link.name) - at(a, link.name))))
            rows.append((f"{a}{b} (link {link.name})", f"{_fmt(d, 5, floor)} {m.units}".rstrip()))
    return rows


def given_table(sol) -> Table:
    """The data of the displacement sheet (a problem handout): what the problem gives, no answers.

    Rows: the driver's angle, ω and α (a slider driver's speed and
    acceleration), each frame point's position, and the lengths of each moving
    link (its points pairwise; a plate of more than four points around its
    outline; not a point that slides on it). All are the file's own data: nothing here is computed by an
    analysis of the motion.
    """
    m = sol.mechanism
    drv = m.driver
    rows = []
    if drv.is_slider:
        index = driver_index(m)   # the slip V_A₃/A₄ along a moving guide's path, V_A along the frame's
        rows.append((_q("V", index), f"{_fmt(abs(drv.speed), 5, 0.0)} {unit(m.units, 1)}"))
        rows.append((_q("A", index), f"{_fmt(drv.accel, 5, 0.0)} {unit(m.units, 2)}"))
    else:
        lk = drv.link
        if sol.driver_angle is not None:
            rows.append((_q(r"\theta", lk), f"{_fmt(sol.driver_angle, 5)}°"))

        def sense(x):   # as the space diagram writes it: a magnitude and its sense
            return _fmt(abs(x), 5, 0.0) + ("" if x == 0 else (" ccw" if x > 0 else " cw"))
        rows.append((_q(r"\omega", lk, "rad/s"), sense(drv.omega)))
        rows.append((_q(r"\alpha", lk, "rad/s²"), sense(drv.alpha)))
    for p in m.frame.points:
        x, y = np.asarray(sol.position.get(f"{p}@{m.frame.name}", sol.position.get(p, m.position(p))), float)
        rows.append((f"{p} (frame)", _where((x, y), None, kind_floor(kind_scales(sol), "P")) + (f" {m.units}" if m.units else "")))
    rows += _link_lengths(sol)
    return Table("Given data", ("quantity", "value"), tuple(rows))


def _where(pos, direction, floor=ZERO) -> str:
    if pos is None:
        return "undefined" if direction is None else f"∞ at {fmt_direction(direction)}°"
    return f"({_fmt(pos[0], 5, floor)}, {_fmt(pos[1], 5, floor)})"


_WIDTHS: dict = {}   # measured widths of the table's texts (points), by font, size and text: they never change


def _box(ax) -> tuple[float, float]:
    """The table's axes, bare, with (0, 1) limits: its (width, height) in points."""
    ax.set_axis_off()
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    pos = ax.get_position()
    w_in, h_in = ax.figure.get_size_inches()
    return pos.width * w_in * 72, pos.height * h_in * 72


class _Room:
    """Where a table is measured: an axes (bare, (0, 1) limits: :func:`_box`), or a rectangle of a figure
    (fractions of the page) where no axes is made yet. Its texts are measured as that axes would lay them
    out (the same transform, to the bit), by probe texts that are never drawn: a sheet's layout tries a
    table in several rooms and draws it once, in the room chosen."""

    def __init__(self, fig, rect=None, ax=None):
        from matplotlib.transforms import Bbox, BboxTransformTo, TransformedBbox
        self.figure = fig
        if ax is not None:
            self.width_pt, self.height_pt = _box(ax)
            self.bbox, self.trans = ax.bbox, ax.transData
        else:   # what an axes made at ``rect`` would have: its box and its transAxes (= its transData at (0, 1))
            pos = Bbox.from_bounds(*rect)
            w_in, h_in = fig.get_size_inches()
            self.width_pt, self.height_pt = pos.width * w_in * 72, pos.height * h_in * 72
            self.bbox = TransformedBbox(pos, fig.transSubfigure)
            self.trans = BboxTransformTo(self.bbox)
        self.renderer = renderer_of(fig)
        self.settings = None   # what a text's layout depends on besides the text (:meth:`extent`), once asked

    def extent(self, x: float, y: float, s: str, **kw):
        """The window extent (pixels) of the text ``s`` at (x, y) as ``ax.text(x, y, s, **kw)`` draws it.

        ``Text.get_window_extent`` is the text's layout box (``Text._get_layout``: its lines measured and
        aligned at the origin), a function of the text and its properties, the settings in force, the dpi and
        the renderer, translated to where the text's transform puts its position. Such a box is kept
        (:func:`~velpoly.render.textcache.kept_layout`), and translated here as matplotlib translates it (the
        same float sums), without a text made where it is kept: the extent
        is matplotlib's, to the bit (tests/test_drawspeed.py). Where matplotlib has no such method (another
        version), or the text is empty (its extent a point), the text is measured as it is."""
        from matplotlib.text import Text
        if self.settings is None:
            import matplotlib
            rc = matplotlib.rcParams
            self.settings = (tuple(str(rc[k]) for k in sorted(rc) if k.startswith(("font.", "mathtext.", "text."))),
                             self.figure.dpi, type(self.renderer))

        def make():
            t = Text(x, y, s, **{"verticalalignment": "baseline", "horizontalalignment": "left",
                                 "transform": self.trans, "clip_on": False, **kw})
            t.set_figure(self.figure)
            return t
        if not s or not hasattr(Text, "_get_layout"):
            return make().get_window_extent(self.renderer)
        box = kept_layout(("table room", self.settings, s, tuple(kw.items())), make, self.renderer)
        return box.translated(*self.trans.transform((float(x), float(y))))

    def points(self, pixels: float) -> float:
        return pixels * 72 / self.figure.dpi


def _sheet_table(sol, sheet, velocity, acceleration, poleset, table) -> Table:
    """The table to draw: ``table``, else :func:`results_table` of the constructions given, else (none
    given) of those the sheet named builds."""
    if table is not None:
        return table
    if velocity is None and acceleration is None and poleset is None:
        from .constructions import constructions
        cons = constructions(sol, sheet)
        shows = {"velocity": (1, 0), "acceleration": (0, 1), "poles": (0, 0), "full": (1, 1)}[sheet]
        velocity = cons.velocity if shows[0] else None
        acceleration = cons.acceleration if shows[1] else None
        poleset = cons.poles
    return results_table(sol, sheet, velocity=velocity, acceleration=acceleration, poleset=poleset)


class _Widths:
    """The widths (points) of a table's cells, each piece measured once at the style's small size (widths
    scale with the type size), cached across tables (:data:`_WIDTHS`)."""

    def __init__(self, room: _Room, st, t: Table):
        self.room, self.st, self.t = room, st, t
        self.at: dict = {}   # cell -> its pieces' widths

    def part(self, text, scale, style) -> float:
        import matplotlib
        rc = matplotlib.rcParams   # the fonts in force (the style's, inside rc_context)
        key = (tuple(rc["font.family"]), tuple(rc.get(f"font.{rc['font.family'][0]}", ())),
               rc["mathtext.fontset"], self.st.small_size, self.room.figure.dpi, text, scale, style)
        w = _WIDTHS.get(key)
        if w is None:
            box = self.room.extent(0, 0, text, fontsize=self.st.small_size * scale, fontstyle=style)
            w = _WIDTHS[key] = self.room.points(box.width)
        return w

    def columns(self, size, rows=None, cols=None) -> list[float]:
        """Column widths (points) at ``size`` of ``rows`` (all) in the columns ``cols`` (all)."""
        t = self.t
        if not self.at:
            for row in (t.header, *t.rows):
                for cell in row:
                    if cell not in self.at:
                        self.at[cell] = [self.part(*p[:2], p[3]) for p in _parts(cell)]
        rows = t.rows if rows is None else rows
        cols = range(len(t.header)) if cols is None else cols
        f = size / self.st.small_size
        return [max(sum(self.at[row[i]]) for row in (t.header, *rows)) * f for i in cols]


    def fit(self, width_pt: float) -> tuple:
        """(type size, column widths, the table's width, the gap between columns) that fit ``width_pt``:
        the style's small size, shrunk (down to 5 pt) where the widest row needs it."""
        size = self.st.small_size
        gap = 1.6 * size   # between columns, points
        widths = self.columns(size)
        need = sum(widths) + gap * (len(widths) - 1)
        if need > width_pt:   # every width and gap in proportion to the type
            size = max(5.0, size * width_pt / need)
            gap = 1.6 * size
            widths = self.columns(size)
            need = sum(widths) + gap * (len(widths) - 1)
        return size, widths, need, gap


def _layout(rows, room, fits):
    """(blocks, rows a block, rows shown) when a block has room for ``room`` rows: side by side, as many
    blocks as the width takes (three at most; ``fits(blocks, per, shown)``: whether ``blocks`` blocks of
    ``per`` of the rows ``shown`` stand side by side in it), the rows shared evenly between them."""
    blocks = max(1, min(3, -(-len(rows) // room))) if len(rows) > room else 1
    while True:
        per = min(room, -(-len(rows) // blocks))
        shown = rows if len(rows) <= per * blocks else rows[:per * blocks - 1]
        if blocks == 1 or fits(blocks, per, shown):
            return blocks, per, shown
        blocks -= 1


def _block_columns(header, chunk, blocks: int) -> list[int]:
    """The columns a block of the rows ``chunk`` shows: those with values in its rows (the quantity always),
    so that a second block of poles' positions prints no empty "instant centres" or "reference" beside them;
    one block, every column of the table."""
    if blocks == 1:
        return list(range(len(header)))
    return [i for i in range(len(header)) if i == 0 or any(row[i] for row in chunk)]


def _fits(widths_of, size, gap, bgap, width_pt):
    """Whether ``blocks`` blocks of ``per`` of the rows ``shown`` stand side by side within ``width_pt``
    (points), each as wide as its own columns (:func:`_block_columns`) at ``size``: a block of velocities
    and one of accelerations side by side where the page has their width, not only where it has twice the
    width of the whole table's columns."""
    def fits(blocks, per, shown):
        chunks = [c for c in (shown[b * per:(b + 1) * per] for b in range(blocks)) if c]
        total = bgap * (len(chunks) - 1)
        for chunk in chunks:
            wb = widths_of.columns(size, chunk, _block_columns(widths_of.t.header, chunk, blocks))
            total += sum(wb) + gap * (len(wb) - 1)
        return total <= width_pt * (1 + 1e-9)
    return fits


def _foot_height(shown, foot, size, foot_size) -> float:
    """The height (points) of the footnotes of the rows ``shown``, with the gap above them."""
    marks = {(row[-1].split() or [""])[-1] for row in shown}
    n = sum(len(lines) for mark, lines in foot.items() if mark in marks)
    return 0.5 * size + n * 1.3 * foot_size if n else 0.0


def _room(rows, top, line_h, foot, size, foot_size, fits):
    """The most rows a block has room for beside the footnotes of the rows it then shows (the rows a note
    explains come first, so the footnotes kept are theirs), and the layout it gives."""
    def foot_height(shown):
        return _foot_height(shown, foot, size, foot_size)
    room = max(int((top - 1.9 * line_h) // line_h), 1)
    while room > 1 and (1.9 + room) * line_h + foot_height(_layout(rows, room, fits)[2]) > top:
        room -= 1
    return _layout(rows, room, fits)


class TableLayout:
    """A results table measured for its room, not drawn yet (:func:`measure_results_table`): where every
    rule and text goes, and what the sheet's layout asks of it; :func:`draw_results_table` draws it.

    ``used`` is the share of the room's height (from its top) the table takes, ``whole`` the share it
    would take to show every row (in as many blocks as the width takes), ``size`` its type size
    (points, after any shrinking), ``shown`` the number of rows drawn, ``table`` the Table, ``notes``
    the footnotes drawn, ``blocks`` each block's column names. ``rect`` is the room (fractions of the
    page); :meth:`set_position` moves it (the table's texts and rules are in the room's own coordinates).
    """

    def __init__(self, table: Table, rect, box):
        self.table, self.rect = table, rect
        self.width_pt, self.height_pt = box
        self.rules: list = []        # (x0, y, line width, length), points from the room's bottom left
        self.cells: list = []        # (x, y, text, size, style or None), points
        self.footnotes: list = []    # (y, line, size, gid or None), points
        self.blocks: list = []
        self.notes: list = []
        self.title = ""              # as drawn (wrapped), with its type size
        self.title_size = 0.0
        self.shown = 0
        self.size = self.used = self.whole = 0.0
        self.overflows = False

    def see_table_page(self) -> None:
        """The last line, that counts the rows left out, sends the reader to the table page (where the sheet has
        one: every row with a book's value and every footnote there)."""
        self.cells = [(x, y, re.sub(r": velpoly solve FILE$", ", every book's value and note: on the table page",
                                    text), size, style) if style == "italic" else (x, y, text, size, style)
                      for x, y, text, size, style in self.cells]

    def get_position(self):
        from matplotlib.transforms import Bbox
        return Bbox.from_bounds(*self.rect)

    def set_position(self, rect) -> None:
        self.rect = tuple(rect)


def _blocks(lay: TableLayout, st, widths_of: _Widths, layout, size, top, spacing) -> float:
    """The table's blocks side by side, each between rules: ``layout`` = (rows, rows shown, blocks, rows a
    block), ``spacing`` = (the one block's column widths, the gap between columns, between blocks); their
    rules and cells into ``lay``; return the lowest rule's height (points)."""
    t = widths_of.t
    rows, shown, blocks, per = layout
    widths, gap, bgap = spacing
    line_h = 1.45 * size
    bottom = top
    x0 = 0.0
    for b in range(blocks):
        chunk = shown[b * per:(b + 1) * per]
        if not chunk and b:
            break
        cols = _block_columns(t.header, chunk, blocks)
        wb = widths_of.columns(size, chunk, cols) if blocks > 1 else widths
        xs = np.cumsum([0.0] + [w + gap for w in wb[:-1]])
        total = min(sum(wb) + gap * (len(wb) - 1), lay.width_pt)
        lay.blocks.append(tuple(t.header[i] for i in cols))
        y = top
        lay.rules.append((x0, y, st.link_lw, total))
        y -= line_h
        lay.cells += [(x0 + x, y, t.header[i], size, None) for x, i in zip(xs, cols)]
        y -= 0.45 * size
        lay.rules.append((x0, y, st.thin_lw, total))
        for row in chunk:
            y -= line_h
            lay.cells += [(x0 + x, y, row[i], size, None) for x, i in zip(xs, cols)]
        if b == blocks - 1 and len(shown) < len(rows):
            y -= line_h
            lay.cells.append((x0, y, f"… {len(rows) - len(shown)} more rows: velpoly solve FILE", size, "italic"))
        y -= 0.6 * size
        bottom = min(bottom, y)
        lay.rules.append((x0, y, st.link_lw, total))
        x0 += total + bgap
    return bottom


def _footnotes(lay: TableLayout, shown, foot, bottom, size, foot_size) -> float:
    """The footnotes of the rows shown beneath the table into ``lay`` (``lay.notes``); return the last one's
    baseline (points; the table's lowest rule less a gap where there is none)."""
    marks = {row[-1].split()[-1] for row in shown if row[-1]}
    lay.notes = [n for n in lay.table.notes if n[0] in marks]   # the footnotes of the rows shown
    y = bottom - 0.5 * size
    for k, (mark, key, _) in enumerate(lay.notes):
        for i, line in enumerate(foot[mark]):
            y -= 1.3 * foot_size
            lay.footnotes.append((y, line, foot_size, f"footnote-{k}" if i == 0 else None))
    return y


class _Title:
    """The results table's title (italic, at 1.1 times the table's type), wrapped to the table's width
    ``wrap_pt`` (points) where it is longer (a long source wraps)."""

    def __init__(self, room: _Room, text: str, size: float, wrap_pt: float):
        self.room, self.size, self.wrap_pt = room, size, wrap_pt
        self.kw = dict(fontsize=size * 1.1, va="top", ha="left", style="italic")
        self.lines = self.wrap(text)

    def width(self, line: str) -> float:
        """A line's width (points) as the title sets it."""
        return self.room.points(self.room.extent(0, 1, literal(line), **self.kw).width)

    def wrap(self, text: str) -> int:
        """Set ``text``, wrapped; the number of its lines."""
        wrapped = _wrapped(text, self.width, self.wrap_pt, indent="", fill=0.97)
        self.text = literal("\n".join(wrapped))
        return len(wrapped)

    def rule_at(self, height_pt: float, size: float) -> float:
        """The height (points, in a room ``height_pt`` tall) of the table's first rule: under the title's
        last line as drawn (its descenders), never through it."""
        top = height_pt - 1.6 * size * 1.1 - (self.lines - 1) * 1.4 * size * 1.1
        drawn = self.room.points(self.room.extent(0, 1, self.text, **self.kw).y0 - self.room.bbox.y0)
        return min(top, drawn - 0.35 * size)


def measure_results_table(sol, room, *, sheet: str = "full", style="textbook", velocity=None, acceleration=None,
                          poleset=None, table: Table | None = None) -> TableLayout:
    """The results table laid out in ``room`` (an axes, or ``(figure, rect)``: a rectangle of the page in
    fractions of it, where no axes need exist), measured and not drawn (:class:`TableLayout`); the
    arguments as :func:`draw_results_table`'s, which draws what this measures."""
    st = get_style(style)
    t = _sheet_table(sol, sheet, velocity, acceleration, poleset, table)
    where = _Room(room.figure, ax=room) if hasattr(room, "transAxes") else _Room(*room)
    width_pt, height_pt = where.width_pt, where.height_pt
    rect = None if hasattr(room, "transAxes") else tuple(room[1])
    lay = TableLayout(t, rect, (width_pt, height_pt))
    widths_of = _Widths(where, st, t)
    size, widths, need, gap = widths_of.fit(width_pt)
    line_h = 1.45 * size
    title = _Title(where, t.title, size, min(width_pt, max(need, 0.6 * width_pt)))   # not less than 0.6 of the room
    top = title.rule_at(height_pt, size)
    # the footnotes (the [reference] notes of the marked rows) beneath the table, across its room: their
    # lines are kept free of rows
    foot_size = 0.9 * size
    foot = _footnote_lines(where, t.notes, width_pt, foot_size, sol.mechanism)
    rows = list(t.rows)
    bgap = 3.0 * size
    fits = _fits(widths_of, size, gap, bgap, width_pt)
    blocks, per, shown = _room(rows, top, line_h, foot, size, foot_size, fits)
    # the height that would show every row in as many blocks as the width takes (the sheet's layout asks)
    most = next(k for k in (3, 2, 1) if k == 1 or fits(k, -(-len(rows) // k), rows))
    lay.whole = (height_pt - top + (1.9 + -(-len(rows) // most)) * line_h + _foot_height(rows, foot, size, foot_size)
                 + 0.9 * size) / height_pt
    lay.widths_of = widths_of
    bottom = _blocks(lay, st, widths_of, (rows, shown, blocks, per), size, top, (widths, gap, bgap))
    y = _footnotes(lay, shown, foot, bottom, size, foot_size)
    if t.notes and not lay.notes:   # the title promises no footnote that the rows shown do not have
        title.wrap(t.title.replace(f"; {NOTED} the book's value is explained in a footnote", ""))
    lay.title, lay.title_size = title.text, title.kw["fontsize"]
    lay.shown = len(shown)
    lay.size = size
    lay.used = min(1.0, (height_pt - y + 0.4 * size) / height_pt)   # the share of the room's height drawn in
    lay.overflows = (y - 0.25 * foot_size if lay.notes else bottom) < -1e-6   # (its last line runs out of the room)
    return lay


def cuts_the_book(lay: TableLayout) -> bool:
    """Whether the measured table ``lay`` leaves out a row with a book's value or a footnote (or runs its
    footnotes out of its room): the sheet then has its table on a page of its own, in the room a page
    gives it (:func:`velpoly.render.sheet.table_page`)."""
    t = lay.table
    if "reference" not in t.header:
        return False
    ref = t.header.index("reference")
    refs = sum(1 for row in t.rows if row[ref])
    return lay.shown < refs or len(lay.notes) < len(t.notes) or lay.overflows


def _texts(lay: TableLayout):
    """The measured table's texts as :func:`_paint` draws them, the title first: (role, x, y, text, keywords of
    ``ax.text``, whether x and y are in the axes' box (``transform=ax.transAxes``) rather than its data (0-1
    limits: the same place))."""
    yield "title", 0, 1, lay.title, dict(fontsize=lay.title_size, va="top", ha="left", style="italic",
                                         gid="results-table"), False
    width_pt, height_pt = lay.width_pt, lay.height_pt
    small = lay.widths_of.st.small_size
    for x, y, text, size, style in lay.cells:
        # a quantity's subscripts set as smaller, lowered texts (no mathtext: fast)
        parts = _parts(text)
        ws = lay.widths_of.at.get(text) or [0.0] * len(parts)
        for (piece, scale, dy, st_), w in zip(parts, ws):
            if piece:
                yield "cells", x / width_pt, (y + 0.3 * size + dy * size) / height_pt, piece, \
                    dict(fontsize=size * scale, fontstyle=style or st_, va="baseline", ha="left"), True
            x += w * size / small
    for y, line, size, gid in lay.footnotes:
        yield "footnotes", 0, y / height_pt, line, dict(fontsize=size, va="baseline", ha="left", gid=gid), False


def _rules(lay: TableLayout):
    """The measured table's rules as :func:`_paint` draws them: (x data, y data, line width), in the axes' box."""
    width_pt, height_pt = lay.width_pt, lay.height_pt
    for x0, y, lw, total in lay.rules:
        yield [x0 / width_pt, (x0 + total) / width_pt], [y / height_pt] * 2, lw


def _paint(lay: TableLayout, ax, st) -> Artists:
    """Draw the measured table ``lay`` in ``ax`` (made at its room); return the Artists."""
    from matplotlib.lines import Line2D
    _box(ax)
    art = Artists(ax)
    texts = _texts(lay)
    for role, x, y, text, kw, boxed in texts:   # the title, then the rules, then the cells and footnotes
        art.add(role, ax.text(x, y, text, **kw, **({"transform": ax.transAxes} if boxed else {})))
        if role == "title":
            for xs, ys, lw in _rules(lay):
                ln = Line2D(xs, ys, lw=lw, color=st.ink, transform=ax.transAxes)
                ax.add_line(ln)
                art.add("rules", ln)
    art.table, art.notes, art.shown, art.size, art.blocks = lay.table, lay.notes, lay.shown, lay.size, lay.blocks
    art.used, art.whole = lay.used, lay.whole
    return art


def drawn_extent(lay: TableLayout, fig) -> tuple[float, float]:
    """(left, right): the pixels of ``fig`` (at its dpi) where an axes made at the measured table's room
    (``lay.rect``) starts and where the rightmost of the texts and rules :func:`_paint` would draw in it ends, to
    the bit, without an axes or an artist: each text's extent as :meth:`_Room.extent` measures it, in the room's
    coordinates (:class:`_Room`: its transform is the axes' box's, and the axes' data at 0-1 limits is the same
    transform)."""
    room = _Room(fig, lay.rect)
    ends = [room.extent(x, y, text, **{k: v for k, v in kw.items() if k != "gid"}).x1
            for _, x, y, text, kw, _ in _texts(lay)]
    for xs, ys, _ in _rules(lay):
        ends.append(room.trans.transform(np.column_stack([xs, ys]))[:, 0].max())
    left = room.bbox.x0
    return left, max(ends, default=left)


def draw_results_table(sol, ax=None, *, sheet: str = "full", style="textbook", velocity=None,
                       acceleration=None, poleset=None, table: Table | None = None,
                       layout: TableLayout | None = None) -> Artists:
    """Draw the sheet's results table in ``ax`` (booktabs style); return the Artists.

    The table is :func:`results_table` unless ``table`` is given; without
    constructions given, those of ``sheet`` are built. It fills the
    axes' width at most; type shrinks (down to 5 pt) to fit the widest row,
    and rows that do not fit the height are summarised in a last line.
    ``layout``: the table measured already (:func:`measure_results_table`) for a room where ``ax`` is
    made (a sheet's layout measures a table in several rooms and draws it once).

    Returns
    -------
    Artists
        Roles ``title``, ``rules``, ``cells`` (Texts, row by row) and ``footnotes``
        (the ``[reference]`` notes of the marked rows shown, ``artists.notes``);
        ``artists.table`` is the Table drawn, ``artists.shown`` the number of
        its rows drawn, ``artists.size`` its type size (points, after any shrinking),
        ``artists.blocks`` each block's column names, ``artists.used`` the share of the axes'
        height (from its top) the table takes, ``artists.whole`` the share it would take to show
        every row (in as many blocks as the width takes).
    """
    ax = get_ax(ax)
    st = get_style(style)
    if layout is None:
        layout = measure_results_table(sol, ax, sheet=sheet, style=st, velocity=velocity, acceleration=acceleration,
                                       poleset=poleset, table=table)
    return _paint(layout, ax, st)


def _footnote_lines(room: _Room, notes, width_pt: float, size: float, m=None) -> dict:
    """Each footnote ``(mark, key, text)`` as the lines it takes at ``size`` within ``width_pt``:
    ``{mark: [line, ...]}``, the first line starting with the mark and the quantity it explains (named
    as the table names it, with the mechanism ``m``)."""
    def width(line):
        return room.points(room.extent(0, 0, line, fontsize=size).width)
    out = {}
    for mark, key, text in notes:
        # typeset as the sheet's equations are (omega_5 -> omega with subscript 5, 400 x 2 -> 400 × 2), a minus
        # sign for a negative number's hyphen
        full = f"{mark} {_math(_key(key, m))}: " + re.sub(r"(?<![\w.])-(?=[0-9.])", "−", equation_tex(text))
        out[mark] = _wrapped(full, width, width_pt)
    return out


def _wrapped(text: str, width, width_pt: float, indent: str = "   ", fill: float = 0.95) -> list[str]:
    """``text`` in lines no wider than ``width_pt`` by ``width`` (points), the lines after the first set in by
    ``indent``: wrapped at ``fill`` of the characters a line holds at the text's mean letter width (20 at
    least), and shorter while a line of wider letters runs past ``width_pt`` (a word is never broken: one wider
    than the line stands alone on it)."""
    import textwrap
    w = width(text)
    if w <= width_pt:
        return [text]
    longest = len(indent) + max(len(word) for word in text.split())
    chars = max(20, int(len(text) * width_pt / w * fill))
    while True:
        lines = textwrap.wrap(text, chars, subsequent_indent=indent, break_long_words=False)
        if chars <= longest or all(width(line) <= width_pt for line in lines):
            return lines
        chars = max(longest, int(chars * 0.9))
