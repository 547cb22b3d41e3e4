"""Readable tables of a solution: links, points, joints, reference values.

Each table is a list of rows (:class:`Table`), rendered as aligned text,
Markdown, LaTeX or CSV by :func:`render_table`. ``velpoly solve`` prints
:func:`solution_report`; the figures' results tables use the same rows.
"""
from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass

import numpy as np

from .names import direction, key_text, vector_direction
from .reference import at_file_pose, compare, file_pose_angle

__all__ = ["Table", "render_table", "solution_tables", "solution_report", "fmt", "polar", "SECTIONS",
           "pinned_keys", "on_links", "solution_html"]


@dataclass(frozen=True)
class Table:
    """A titled table: column headers and rows of strings; ``notes``: its footnotes, ``(mark, key, text)``
    for each mark in its rows (a drawn results table prints them beneath it)."""

    title: str
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    notes: tuple[tuple[str, str, str], ...] = ()


def fmt(x, digits: int = 6) -> str:
    """A number to ``digits`` significant digits; '-' for None or NaN."""
    if x is None:
        return "-"
    x = float(x)
    if not math.isfinite(x):
        return "-"
    if x == 0:
        return "0"
    if abs(x) < 1e-12 * 10 ** digits and abs(x) < 1e-9:
        return "0"
    return f"{x:.{digits}g}"


def polar(v) -> str:
    """A vector as ``magnitude ∠ direction°`` (direction in [0, 360))."""
    if v is None:
        return "-"
    v = np.asarray(v, float)
    if not np.all(np.isfinite(v)):
        return "-"
    mag = float(np.hypot(*v))
    if mag == 0:
        return "0"
    return f"{fmt(mag)} ∠ {direction(vector_direction(v), 3)}°"


def _links(sol) -> Table:
    rows = []
    for k in sol.mechanism.links:
        rows.append((k.name + (" (frame)" if k.frame else ""), f"{sol.angle[k.name]:.4f}",
                     fmt(sol.omega[k.name]), fmt(sol.alpha[k.name])))
    return Table("Links", ("link", "angle (deg)", "omega (rad/s)", "alpha (rad/s^2)"), tuple(rows))


def pinned_keys(m) -> dict:
    """How tables show each point key: ``{key: (point, links)}`` for keys ``P@a`` of links pinned together
    at P (two or more, so one row "P (on a and b)" stands for them all: they move alike), the first
    key of each such group only; other keys are absent (the key itself is shown) or map to None (a
    pinned key after the first: no row of its own). JSON keys stay as FORMAT.md section 5 says."""
    out: dict = {}
    for p in m.point_order:
        carriers = m.carriers.get(p, ())
        groups = [{lk} for lk in carriers]
        for pin in m.pins:
            if pin.point != p:
                continue
            hit = [g for g in groups if g & set(pin.links)]
            if len(hit) == 2:
                groups.remove(hit[1])
                hit[0] |= hit[1]
        if len(groups) < 2:
            continue   # one key P: pinned alike by structure
        for g in groups:
            if len(g) < 2:
                continue
            links = [lk for lk in carriers if lk in g]
            out[f"{p}@{links[0]}"] = (p, tuple(links))
            out.update({f"{p}@{lk}": None for lk in links[1:]})
    return out


def on_links(links) -> str:
    """``2 and 3``, ``2, 3 and 5``."""
    return " and ".join(links) if len(links) < 3 else ", ".join(links[:-1]) + " and " + links[-1]


def _points(sol) -> Table:
    rows = []
    pinned = pinned_keys(sol.mechanism)
    for key, p in sol.position.items():
        if key in pinned and pinned[key] is None:
            continue   # shown with the first key of its pinned group
        label = f"{pinned[key][0]} (on {on_links(pinned[key][1])})" if key in pinned else key_text(key)
        rows.append((label, f"({fmt(p[0])}, {fmt(p[1])})", polar(sol.velocity[key]), polar(sol.acceleration[key])))
    u = sol.mechanism.units or "units"
    return Table("Points", ("point", f"position ({u})", f"velocity ({u}/s)", f"acceleration ({u}/s^2)"),
                 tuple(rows))


def _joints(sol) -> list[Table]:
    m = sol.mechanism
    mo = sol.motion
    out = []
    if m.sliders:
        out.append(Table("Sliders", ("block on guide", "point", "slip velocity", "slip acceleration", "Coriolis"),
                         tuple((f"{s.block} on {s.guide}", s.point, fmt(r["slip_velocity"][0]),
                                fmt(r["slip_acceleration"][0]), polar(r["coriolis"][0]))
                               for s, r in zip(m.sliders, mo.sliders))))
    if m.slots:
        out.append(Table("Pins in slots", ("pin of link in slot", "point", "slip velocity", "slip acceleration",
                                           "Coriolis"),
                         tuple((f"{s.link} in {s.slot}", s.pin, fmt(r["slip_velocity"][0]),
                                fmt(r["slip_acceleration"][0]), polar(r["coriolis"][0]))
                               for s, r in zip(m.slots, mo.slots))))
    if m.contacts:
        out.append(Table("Contacts", ("links", "point", "kind", "slip velocity", "slip acceleration"),
                         tuple((f"{c.links[0]}, {c.links[1]}", c.point, c.kind, fmt(r["slip_velocity"][0]),
                                fmt(r["slip_acceleration"][0])) for c, r in zip(m.contacts, mo.contacts))))
    return out


def _show_value(v) -> str:
    if v is None:
        return "at infinity"
    if isinstance(v, tuple):
        if len(v) == 2:
            return f"{fmt(v[0])} ∠ {direction(v[1], 3)}°"
    return fmt(v)


def _compass(sol) -> Table | None:
    """Each compass construction of the file: the intersection it takes and the other one (the branch
    the drawing is on, and what to write for the other)."""
    cons = sol.mechanism.constructions
    if not cons:
        return None

    def xy(p):
        return f"({fmt(p[0])}, {fmt(p[1])})"
    rows = tuple((c.point, c.given, xy(c.chosen) + (f" {c.side}" if c.side else ""),
                  "-" if c.other is None else xy(c.other) + (f" {'right' if c.side == 'left' else 'left'}"
                                                             if c.side else ""),
                  c.rule, c.switch or "(the two touch: one point)") for c in cons)
    return Table("Compass constructions of the file (reference pose): the intersection taken and the other one; "
                 "left/right of the line from the first centre to the second",
                 ("point", "construction", "taken", "other", "picked by", "for the other write"), rows)


def _is_pole(r) -> bool:
    """A pole's position, printed as [x, y] (P_13 or P13)."""
    return r.key.startswith("P") and isinstance(r.printed, tuple) and r.key[1:2] in ("_", *"0123456789")


def _pole_text(xy) -> str:
    return "at infinity" if xy is None else f"({fmt(xy[0])}, {fmt(xy[1])})"


def _reference(sol) -> Table | None:
    m = sol.mechanism
    if not m.reference:
        return None
    title = "Reference values" + (f" ({m.reference.source})" if m.reference.source else "")
    if not at_file_pose(sol):   # the book's values are for the file's pose: list them, compare nothing
        pose = file_pose_angle(m)
        rows = tuple((r.key, _pole_text(r.printed) if _is_pole(r) else _show_value(r.printed), r.note)
                     for r in compare(sol))
        return Table(f"{title}: printed for the file's pose (driver at {pose:g} deg), not compared at "
                     f"{sol.driver_angle:g} deg", ("quantity", "printed", "note"), rows)
    rows = []
    for r in compare(sol):
        if _is_pole(r):
            printed, computed = _pole_text(r.printed), _pole_text(r.computed)
        else:
            printed, computed = _show_value(r.printed), _show_value(r.computed)
        dev = [] if r.deviation is None else [f"{100 * r.deviation:.3g}%"]
        if r.angle_error is not None:
            dev.append(f"{r.angle_error:.3g}°")
        rows.append((r.key, printed, computed, " ".join(dev) or "-", r.note))
    return Table(title, ("quantity", "printed", "analytic", "deviation", "note"), tuple(rows))


# Further sections (function(solution) -> Table | list[Table] | None), added by the poles and
# polygons modules so that this module does not import them.
SECTIONS: list = []


def solution_tables(sol) -> list[Table]:
    """Every table of the solution, in reading order."""
    from .solution import load_sections
    load_sections()
    out = [_links(sol), _points(sol), *_joints(sol)]
    compass = _compass(sol)
    if compass is not None:
        out.append(compass)
    for fn in SECTIONS:
        t = fn(sol)
        if t is None:
            continue
        out.extend(t if isinstance(t, list) else [t])
    ref = _reference(sol)
    if ref is not None:
        out.append(ref)
    return out


def render_table(t: Table, style: str = "text") -> str:
    """A table as ``text`` (aligned columns), ``markdown``, ``latex`` or ``csv``."""
    if style == "csv":
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(t.header)
        w.writerows(t.rows)
        return buf.getvalue()
    if style == "markdown":
        def esc(s):
            return str(s).replace("|", "\\|")
        lines = [f"**{t.title}**", "", "| " + " | ".join(map(esc, t.header)) + " |",
                 "|" + "|".join("---" for _ in t.header) + "|"]
        lines += ["| " + " | ".join(map(esc, r)) + " |" for r in t.rows]
        return "\n".join(lines) + "\n"
    if style == "latex":
        def tex(s):
            s = str(s)
            for a, b in (("\\", r"\textbackslash{}"), ("&", r"\&"), ("%", r"\%"), ("_", r"\_"), ("#", r"\#"),
                         ("∠", r"$\angle$"), ("°", r"$^\circ$"), ("^", r"\^{}")):
                s = s.replace(a, b)
            return s
        cols = "l" * len(t.header)
        lines = [r"\begin{tabular}{" + cols + "}", r"\hline", " & ".join(map(tex, t.header)) + r" \\", r"\hline"]
        lines += [" & ".join(map(tex, r)) + r" \\" for r in t.rows]
        lines += [r"\hline", r"\end{tabular}"]
        return "\n".join(lines) + "\n"
    widths = [max(len(str(x)) for x in col) for col in zip(t.header, *t.rows)]
    lines = [t.title, "  ".join(h.ljust(w) for h, w in zip(t.header, widths)).rstrip(),
             "  ".join("-" * w for w in widths)]
    lines += ["  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip() for r in t.rows]
    return "\n".join(lines) + "\n"


def _head(sol) -> tuple[str, str]:
    """The report's title and its driver's line."""
    m = sol.mechanism
    if m.driver.is_slider:
        return m.title, (f"driver: slider {m.driver.slider}, speed {fmt(m.driver.speed)} {m.units or 'units'}/s, "
                         f"accel {fmt(m.driver.accel)} {m.units or 'units'}/s^2")
    return m.title, (f"driver: link {m.driver.link} at {sol.driver_angle:.4f} deg, omega {fmt(m.driver.omega)} "
                     f"rad/s, alpha {fmt(m.driver.alpha)} rad/s^2")


def _html_table(t: Table) -> str:
    from html import escape
    head = "".join(f"<th>{escape(str(h))}</th>" for h in t.header)
    body = "".join("<tr>" + "".join(f"<td>{escape(str(c))}</td>" for c in r) + "</tr>" for r in t.rows)
    return (f"<table><caption style=\"text-align:left\">{escape(t.title)}</caption><thead><tr>{head}</tr>"
            f"</thead><tbody>{body}</tbody></table>")


def solution_html(sol) -> str:
    """The report of ``velpoly solve`` as HTML: what a notebook shows for a Solution."""
    from html import escape
    title, driver = _head(sol)
    out = [f"<h4>{escape(title)}</h4>", f"<p>{escape(driver)}</p>"]
    out += [_html_table(t) for t in solution_tables(sol)]
    out += [f"<p>warning: {escape(w)}</p>" for w in sol.warnings]
    return "\n".join(out)


def solution_report(sol, style: str = "text") -> str:
    """The whole readable report of ``velpoly solve``."""
    out = "\n".join(_head(sol)) + "\n\n" + "\n".join(render_table(t, style) for t in solution_tables(sol))
    for w in sol.warnings:
        out += f"\nwarning: {w}\n"
    return out
