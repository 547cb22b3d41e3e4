"""Readable tables: of a solution (links, points, joints, poles, polygons, reference values) and of a
cycle (a :class:`velpoly.Sweep`: its CSV and summary table).

Each table is a list of rows (:class:`Table`), rendered as aligned text,
Markdown, LaTeX or CSV by :func:`render_table`. ``velpoly solve`` prints
:func:`solution_report`; the figures' results tables use the same rows.
``velpoly sweep`` writes :func:`cycle_csv` and prints :func:`summary_text`.
This module draws nothing and prints nothing.
"""
from __future__ import annotations

import csv
import io
import math

import numpy as np

from .compare import key_floor, kind_floor, kind_scales, polygon_values
from .driver import driver_label
from .names import direction, key_text, place, relative
from .tables import Table, angle, coordinates, fmt, magnitude_angle, zero_floor, magnitude_direction, polar, render_table, tex_text, md_text   # re-exported: the tables' primitives
from .reference import at_file_pose, compare, file_pose_angle

__all__ = ["Table", "render_table", "solution_tables", "solution_report", "fmt", "polar", "magnitude_direction", "poles_tables", "polygon_tables",
           "pinned_keys", "on_links", "solution_html",
           "cycle_columns", "cycle_csv", "moving_keys", "summary_table", "summary_text"]


def _floors(sol, *kinds) -> list[float]:
    """Below what a value of each kind prints as 0 (:func:`velpoly.compare.kind_floor`, as the drawn tables):
    a billionth of the largest of its kind in the mechanism (alpha at least omega^2, an acceleration at least
    speed^2 / size), at most 1e-9. A column's own largest value would not do: a parallelogram's alphas at a
    constant omega are all rounding noise (2.2e-14), and printed as values."""
    scales = kind_scales(sol)
    return [kind_floor(scales, k) for k in kinds]


def _links(sol) -> Table:
    rows = []
    zw, za = _floors(sol, "omega", "alpha")   # rounding noise prints 0, a slow mechanism's values as they are
    for k in sol.mechanism.links:
        rows.append((k.name + (" (frame)" if k.frame else ""), angle(sol.angle[k.name]),
                     fmt(sol.omega[k.name], floor=zw), fmt(sol.alpha[k.name], floor=za)))
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
    zp, zv, za = _floors(sol, "P", "V", "A")
    for key, p in sol.position.items():
        if key in pinned and pinned[key] is None:
            continue   # shown with the first key of its pinned group
        label = f"{pinned[key][0]} (on {on_links(pinned[key][1])})" if key in pinned else key_text(key)
        rows.append((label, coordinates(p, zp), polar(sol.velocity[key], zv), polar(sol.acceleration[key], za)))
    u = sol.mechanism.units or "units"
    return Table("Points", ("point", f"position ({u})", f"velocity ({u}/s)", f"acceleration ({u}/s^2)"),
                 tuple(rows))


def _joints(sol) -> list[Table]:
    m = sol.mechanism
    mo = sol.motion
    out = []
    zv, za = _floors(sol, "V", "A")   # as the points table
    if m.sliders:
        out.append(Table("Sliders", ("block on guide", "point", "slip velocity", "slip acceleration", "Coriolis"),
                         tuple((f"{s.block} on {s.guide}", s.point, fmt(r["slip_velocity"][0], floor=zv),
                                fmt(r["slip_acceleration"][0], floor=za), polar(r["coriolis"][0], za))
                               for s, r in zip(m.sliders, mo.sliders))))
    if m.slots:
        out.append(Table("Pins in slots", ("pin of link in slot", "point", "slip velocity", "slip acceleration",
                                           "Coriolis"),
                         tuple((f"{s.link} in {s.slot}", s.pin, fmt(r["slip_velocity"][0], floor=zv),
                                fmt(r["slip_acceleration"][0], floor=za), polar(r["coriolis"][0], za))
                               for s, r in zip(m.slots, mo.slots))))
    if m.contacts:
        out.append(Table("Contacts", ("links", "point", "kind", "slip velocity", "slip acceleration"),
                         tuple((f"{c.links[0]}, {c.links[1]}", c.point, c.kind, fmt(r["slip_velocity"][0], floor=zv),
                                fmt(r["slip_acceleration"][0], floor=za)) for c, r in zip(m.contacts, mo.contacts))))
    return out


def _show_value(v, floor: float = 0.0) -> str:
    """A printed (floor 0: as given) or computed value of the reference table."""
    if v is None:
        return "at infinity"
    if isinstance(v, tuple):
        if len(v) == 2:
            return magnitude_angle(v[0], v[1], floor)
    return fmt(v, floor=floor)


def _compass(sol) -> Table | None:
    """Each compass construction of the file: the intersection it takes and the other one (the branch
    the drawing is on, and what to write for the other)."""
    cons = sol.mechanism.constructions
    if not cons:
        return None
    rows = tuple((c.point, c.given, coordinates(c.chosen) + (f" {c.side}" if c.side else ""),
                  "-" if c.other is None else coordinates(c.other) + (f" {'right' if c.side == 'left' else 'left'}"
                                                             if c.side else ""),
                  c.rule, c.switch or "(the two touch: one point)") for c in cons)
    return Table("Compass constructions of the file (reference pose): the intersection taken and the other one; "
                 "left/right of the line from the first centre to the second",
                 ("point", "construction", "taken", "other", "picked by", "for the other write"), rows)


def _is_pole(r) -> bool:
    """A pole's position, printed as [x, y] (P_13 or P13)."""
    return r.key.startswith("P") and isinstance(r.printed, tuple) and r.key[1:2] in ("_", *"0123456789")


def _pole_text(xy) -> str:
    return "at infinity" if xy is None else coordinates(xy)


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
    scales = kind_scales(sol)
    for r in compare(sol):
        if _is_pole(r):
            printed, computed = _pole_text(r.printed), _pole_text(r.computed)
        else:
            printed, computed = _show_value(r.printed), _show_value(r.computed, key_floor(m, r.key, scales))
        dev = [] if r.deviation is None else [f"{100 * r.deviation:.3g}%"]
        if r.angle_error is not None:
            dev.append(f"{r.angle_error:.3g}°")
        rows.append((r.key, printed, computed, " ".join(dev) or "-", r.note))
    return Table(title, ("quantity", "printed", "analytic", "deviation", "note"), tuple(rows))


# -- the constructions' tables (velpoly.poles, velpoly.polygons) -----------------------------------
def _pole_where(p) -> str:
    if p.undefined:
        return "undefined (links move alike)"
    if p.position is None:
        return f"at infinity, {direction(p.direction, 3)}°"
    return coordinates(p.position)


def _pole_found(p, compact: bool) -> str:
    from .poles import pole_label
    if p.how not in ("kennedy", "normals"):
        return p.note or p.how
    lines = []
    for ln in p.lines:
        lines.append(f"{pole_label(ln[0], compact)}-{pole_label(ln[1], compact)}" if "-" in ln[0]
                     else f"{ln[0]} at {ln[1]}")
    return " x ".join(lines)


def poles_tables(sol) -> list[Table]:
    """The instant centres' tables: every pole, and the instant-centre omegas beside the analytic ones."""
    from .poles import instant_centre_velocities, locate_poles, pole_label
    ps = locate_poles(sol)
    compact = all(len(lk) == 1 for lk in ps.links)
    rows = tuple((pole_label(p.key, compact), _pole_where(p), "inspection" if p.by_inspection else p.how,
                  str(p.order) if p.order else "-", _pole_found(p, compact)) for p in ps.poles.values())
    units = sol.mechanism.units
    t1 = Table(f"Instant centres ({len(ps.poles)} poles, order of discovery on the Kennedy circle)",
               ("pole", f"position ({units})" if units else "position", "found by", "order", "how"), rows)
    ic = instant_centre_velocities(sol, ps)
    via = {lk: (frm, key) for lk, frm, key in ic["path"]}
    rows2 = []
    for lk in ps.links:
        if lk == ps.frame:
            continue
        w, wa = ic["omega"][lk], sol.omega[lk]
        frm, key = via[lk]
        if key == "velocity":
            how = "from the velocity solution"
        elif frm is None:
            how = "driver"
        else:
            how = f"from {frm} through {pole_label(key, compact)}"
        rows2.append((lk, _pole_where(ps.pole(ps.frame, lk)), fmt(w), fmt(wa), fmt(abs(w - wa), 2), how))
    t2 = Table("Instant-centre method: omega_j = omega_i (P_ij - P_1i) / (P_ij - P_1j)",
               ("link", "frame pole", "omega (instant centres)", "omega (analytic)", "difference", "found"),
               tuple(rows2))
    return [t1, t2]


def polygon_tables(sol) -> list[Table]:
    """The velocity and acceleration polygons' rates and images beside the analytic values, with the
    range a careful hand drawing gives (:func:`velpoly.polygons.hand_drafting`)."""
    from .polygons import ConstructionError, acceleration_polygon, hand_drafting, velocity_polygon
    try:
        polys = [velocity_polygon(sol)]
    except ConstructionError as e:
        return [Table("Graphical construction", ("status",), ((f"not constructed: {e.what}",),))]
    if sol.has_accelerations:
        polys.append(acceleration_polygon(sol))
    hd = hand_drafting(sol)
    pinned = pinned_keys(sol.mechanism)
    out = []
    for poly in polys:
        vel = poly.kind == "velocity"
        h = hd[poly.kind]
        rname, pname = ("omega", "V") if vel else ("alpha", "A")
        rates, points = polygon_values(sol, poly)
        zr, zp = _floors(sol, rname, pname)   # as in the tables above
        rows = []
        for v in rates:
            lo, hi = h["omega" if vel else "alpha"][v.key]
            rows.append((f"{rname}_{v.key}", fmt(v.graphical, floor=zr), fmt(v.analytic, floor=zr),
                         f"{fmt(lo, 4, zr)} .. {fmt(hi, 4, zr)}"))
        for v in points:
            key = v.key
            if key in pinned and pinned[key] is None:
                continue   # a point of links pinned together: one row, with the first key's
            lo, hi = h["speed" if vel else "magnitude"][key]
            name = f"{pname}_{pinned[key][0]} (on {on_links(pinned[key][1])})" if key in pinned else \
                f"{pname}_{key_text(key)}"
            rows.append((f"{name} ({poly.labels[key]})", polar(v.graphical, zp), polar(v.analytic, zp),
                         f"{fmt(lo, 4, zp)} .. {fmt(hi, 4, zp)}"))
        rows.append(("max error (relative to the largest)", f"{poly.max_error:.2g}", "", ""))
        title = (f"{poly.kind.capitalize()} polygon ({len(poly.steps)} steps): graphical and analytic, "
                 f"hand-drafted 95% range at {fmt(h['scale'], 4)} mm per unit")
        out.append(Table(title, ("quantity", "graphical", "analytic", "hand-drafted"), tuple(rows)))
    return out


def solution_tables(sol) -> list[Table]:
    """Every table of the solution, in reading order."""
    out = [_links(sol), _points(sol), *_joints(sol)]
    compass = _compass(sol)
    if compass is not None:
        out.append(compass)
    out += poles_tables(sol) + polygon_tables(sol)
    ref = _reference(sol)
    if ref is not None:
        out.append(ref)
    return out


def _head(sol) -> tuple[str, str]:
    """The report's title and its driver's line."""
    m = sol.mechanism
    if m.driver.is_slider:
        return m.title, (f"driver: slider {m.driver.slider}, speed {fmt(m.driver.speed, floor=0)} "
                         f"{m.units or 'units'}/s, accel {fmt(m.driver.accel, floor=0)} {m.units or 'units'}/s^2")
    return m.title, (f"driver: link {m.driver.link} at {angle(sol.driver_angle)} deg, omega "
                     f"{fmt(m.driver.omega, floor=0)} rad/s, alpha {fmt(m.driver.alpha, floor=0)} rad/s^2")   # as given


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
    def line(text):   # a LaTeX report's lines are text typeset as written, each a paragraph; Markdown's as written
        return tex_text(text) + r"\par" if style == "latex" else md_text(text) if style == "markdown" else text
    out = "\n".join(map(line, _head(sol))) + "\n\n" + "\n".join(render_table(t, style) for t in solution_tables(sol))
    for w in sol.warnings:
        out += "\n" + line(f"warning: {w}") + "\n"
    return out


# -- a whole cycle (velpoly sweep): the CSV and the summary table --------------------------------------
def cycle_columns(sw, cen=None) -> list[tuple[str, np.ndarray]]:
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


def cycle_csv(sw, cen=None) -> str:
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
def moving_keys(sw) -> list[str]:
    """Point keys that move during the cycle (fixed points have zero speed throughout)."""
    out = []
    for key, v in sw.velocity.items():
        if np.nanmax(np.hypot(v[:, 0], v[:, 1]), initial=0.0) > 0 or np.ptp(sw.position[key], axis=0).max() > 0:
            out.append(key)
    return out


def _extremes(name: str, unit: str, values: np.ndarray, at: np.ndarray, floor: float):
    good = np.isfinite(values)
    if not good.any():
        return (name, unit, "-", "-", "-", "-")
    v = np.where(good, values, np.nan)
    i, j = int(np.nanargmin(v)), int(np.nanargmax(v))
    return (name, unit, fmt(v[i], floor=floor), f"{at[i]:.6g}", fmt(v[j], floor=floor), f"{at[j]:.6g}")


def _cycle_floor(arrays) -> float:
    """:func:`zero_floor` of a kind of quantity over the cycle: a billionth of its largest magnitude, at most 1e-9."""
    return zero_floor([float(np.nanmax(np.abs(a))) for a in arrays if np.isfinite(a).any()])


def summary_table(sw, points=None) -> Table:
    """Min and max of each link's omega and alpha, each point's speed and acceleration (``points``:
    point keys, default every moving point) and each slider's slip velocity over the cycle, with
    the driver positions where they occur."""
    m = sw.mechanism
    u = m.units or "units"
    at = sw.angles
    rows = []
    keys = list(points) if points else moving_keys(sw)
    speeds = {key: np.hypot(*sw.velocity[key].T) for key in keys}
    accels = {key: np.hypot(*sw.acceleration[key].T) for key in keys}
    zw, za = (_cycle_floor(d[k.name] for k in m.moving_links) for d in (sw.omega, sw.alpha))   # noise prints 0
    zv, zA = _cycle_floor(speeds.values()), _cycle_floor(accels.values())
    for k in m.moving_links:
        rows.append(_extremes(f"omega_{k.name}", "rad/s", sw.omega[k.name], at, zw))
    for k in m.moving_links:
        rows.append(_extremes(f"alpha_{k.name}", "rad/s^2", sw.alpha[k.name], at, za))
    for key in keys:
        rows.append(_extremes(f"|V_{key_text(key)}|", f"{u}/s", speeds[key], at, zv))
    for key in keys:
        rows.append(_extremes(f"|A_{key_text(key)}|", f"{u}/s^2", accels[key], at, zA))
    for s, r in zip(m.sliders, sw.sliders):
        slip = relative(place(s.point, s.block), place(s.point, s.guide))
        rows.append(_extremes(f"slip V_{slip}", f"{u}/s", r["slip_velocity"], at, zv))
    _, unit = driver_label(m)
    return Table(f"Over the cycle ({len(at)} poses)",
                 ("quantity", "unit", "min", f"at ({unit})", "max", f"at ({unit})"), tuple(rows))


def summary_text(sw, points=None) -> str:
    """What ``velpoly sweep`` prints without an output file: the title, the driver's span, the summary table."""
    m = sw.mechanism
    name, unit = driver_label(m)
    if len(sw.angles) > 1:
        span = f"{name} from {sw.angles[0]:.6g} to {sw.angles[-1]:.6g} {unit}"
    else:
        span = f"{name} {sw.angles[0]:.6g} {unit}"
    head = f"{m.title}\n{span}\n\n"
    return head + render_table(summary_table(sw, points), "text")
