"""The ``[points]`` table: each point's position, in file order, from coordinates or a construction.

A point is ``[x, y]``; ``{from = "P", length, angle}`` (P plus the vector; ``to`` subtracts it);
``{from, length, along = ["Q", "R"], turn}`` (the direction Q -> R, turned); two circles' intersection
``{circles = [["P", r1], ["Q", r2]], near or side}``; or a circle and a line's ``{circle, line, near}``
(FORMAT.md section 1). A construction refers only to points above it.
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..model import Construction
from ..pose import circle_circle, circle_line
from .context import (TABLE_HINTS, Ctx, check_keys, coincide, direction, key_repr, length, named_entries,
                      read_name, read_number, show, table)
from .toml_positions import locate

__all__ = ["read_points", "SIZE_RANGE", "TANGENT"]

TANGENT = 1e-7   # intersections closer than this (relative to the construction's size) touch
# Floating point holds about 1e+-308: the kinematics squares speeds and multiplies rates by lengths,
# so the sizes a file may ask for are bounded well inside that range (the speeds: driver.py).
SIZE_RANGE = (1e-100, 1e100)    # the mechanism's size (its points' bounding-box diagonal), length units

_CONSTRUCTIONS = ("[x, y], {from, length, angle}, {to, length, angle}, {from, length, along, turn}, "
                  "{circles, near or side} or {circle, line, near}")
_CONSTRUCTION_KEYS = ("from", "to", "length", "angle", "along", "turn", "circles", "near", "side",
                      "circle", "line")


def read_points(ctx: Ctx, data: dict) -> None:
    """Every point of ``[points]`` into ``ctx.pts`` (in file order), and the mechanism's size."""
    raw_points = table(ctx, data, "points")
    if not raw_points:
        raise ctx.err("points", "no points", hint=TABLE_HINTS["points"])
    named_points = named_entries(ctx, "points", raw_points, "point")
    ctx.point_names = tuple(n for n, _ in named_points)
    pts = ctx.pts
    for pname, spec in named_points:
        with np.errstate(all="ignore"):   # an overflow is reported below, as no finite position
            pts[pname] = _construct(ctx, pname, spec, pts)
        if not np.all(np.isfinite(pts[pname])):
            raise ctx.err(f"points.{pname}", "the construction gives no finite position",
                          hint="check its lengths and angles")
    ctx.size = size = mechanism_size(pts)
    if not SIZE_RANGE[0] <= size <= SIZE_RANGE[1]:
        raise ctx.err("points", f"the mechanism's size {length(ctx, size)} is out of range "
                      f"({SIZE_RANGE[0]:g} to {SIZE_RANGE[1]:g})",
                      hint="the arithmetic would overflow or underflow: give the lengths in other units")


def mechanism_size(pts: dict) -> float:
    """As Mechanism.size: the points' bounding-box diagonal (1 for a single point)."""
    p = np.array(list(pts.values()))
    d = float(np.hypot(*(p.max(axis=0) - p.min(axis=0)))) if len(p) else 1.0
    return d or 1.0


def _xy(ctx, where, v) -> np.ndarray:
    if not isinstance(v, list) or len(v) != 2:
        raise ctx.err(where, f"expected [x, y], got {show(v)}" + (f" of {len(v)} items" if isinstance(v, list) else ""),
                      hint="a position is a list of two numbers, e.g. [0.3, 0.45]")
    return np.array([read_number(ctx, where, v[0]), read_number(ctx, where, v[1])])


def _ref(ctx, where, name, pts, current=None) -> np.ndarray:
    """The position of a point named in a construction: one defined above it."""
    name = read_name(ctx, where, name, "a point's name")
    if name in pts:
        return pts[name]
    if name == current:
        raise ctx.err(where, f"point {name!r} refers to itself",
                      hint="construct it from points defined above it")
    if name in ctx.point_names:
        line = locate(ctx.text, f"points.{name}")
        at = f" (line {line})" if line else ""
        raise ctx.err(where, f"refers to point {name!r}, which is defined later{at}",
                      hint=f"points are evaluated in file order: define {name!r} above "
                           f"{current!r}" if current else "points are evaluated in file order")
    raise ctx.err(where, f"refers to unknown point {name!r}",
                  hint="points defined above it: " + (", ".join(pts) or "none") if len(pts) <= 20
                  else "define it in [points], above the point that uses it")


def _point_or_xy(ctx, where, v, pts, current=None) -> np.ndarray:
    if isinstance(v, list):
        return _xy(ctx, where, v)
    return _ref(ctx, where, v, pts, current)


def _construct(ctx: Ctx, name: str, spec: Any, pts: dict) -> np.ndarray:
    where = f"points.{name}"
    if isinstance(spec, list):
        return _xy(ctx, where, spec)
    if not isinstance(spec, dict):
        raise ctx.err(where, f"expected [x, y] or a construction table, got {show(spec)}",
                      hint="use " + _CONSTRUCTIONS)
    if "circles" in spec:
        return _two_circles(ctx, where, name, spec, pts)
    if "circle" in spec:
        return _circle_and_line(ctx, where, name, spec, pts)
    if "from" in spec or "to" in spec:
        return _polar_construction(ctx, where, name, spec, pts)
    unknown = [k for k in spec if k not in _CONSTRUCTION_KEYS]
    if unknown:
        raise ctx.err(f"{where}.{unknown[0]}", f"unknown key {key_repr(unknown[0])}",
                      hint="a point is " + _CONSTRUCTIONS)
    raise ctx.err(where, "incomplete construction: " + (", ".join(map(str, spec)) or "an empty table"),
                  hint="a point is " + _CONSTRUCTIONS)


def _circles_of(ctx, where, name, spec, pts):
    """The two circles ``[["P", r1], ["Q", r2]]`` of a two-circle construction: centres and radii."""
    cs = spec["circles"]
    if not (isinstance(cs, list) and len(cs) == 2 and all(isinstance(c, list) and len(c) == 2 for c in cs)):
        raise ctx.err(where + ".circles", f"expected [[\"P\", r1], [\"Q\", r2]], got {show(cs)}",
                      hint="two circles, each a centre point's name and a radius")
    p = _ref(ctx, where + ".circles", cs[0][0], pts, name)
    q = _ref(ctx, where + ".circles", cs[1][0], pts, name)
    r1 = read_number(ctx, where + ".circles", cs[0][1], positive=True, allow_zero=False)
    r2 = read_number(ctx, where + ".circles", cs[1][1], positive=True, allow_zero=False)
    return cs, p, q, r1, r2


def _two_circles(ctx, where, name, spec, pts):
    check_keys(ctx, where, spec, ("circles", "near", "side"))
    cs, p, q, r1, r2 = _circles_of(ctx, where, name, spec, pts)
    if ("near" in spec) == ("side" in spec):
        raise ctx.err(where, "a two-circle construction needs exactly one of 'near' and 'side'"
                      + (" (both are given)" if "near" in spec else ""),
                      hint='keep near = [x, y] (a sketch point) or side = "left" / "right", not both'
                      if "near" in spec else 'add near = [x, y] (a sketch point) or side = "left" / "right"')
    dist = float(np.hypot(*(q - p)))
    if dist == 0:
        raise ctx.err(where + ".circles", f"the circles' centres {str(cs[0][0])!r} and {str(cs[1][0])!r} coincide",
                      hint="two circles about one centre meet nowhere or everywhere: use other centres")
    left, right, gap = circle_circle(p, r1, q, r2)
    if gap > 1e-9 * max(r1, r2):
        inside = abs(r1 - r2) > dist
        raise ctx.err(where, f"circles do not meet (gap {length(ctx, gap)})",
                      hint=(f"one circle lies inside the other ({length(ctx, dist)} between centres, radii "
                            f"{r1:g} and {r2:g}): check the lengths") if inside else
                      (f"the centres are {length(ctx, dist)} apart but the radii add up to {r1 + r2:g}: "
                       "check the lengths (the links cannot reach)"))
    if np.hypot(*(left - right)) <= 2 * TANGENT * max(r1, r2, dist):
        left = right = 0.5 * (left + right)   # tangent to within rounding: on the line of centres
    given = f"circles {cs[0][0]} {r1:g}, {cs[1][0]} {r2:g}"
    if "side" in spec:
        side = spec["side"]
        if side not in ("left", "right"):
            raise ctx.err(where + ".side", f"expected \"left\" or \"right\", got {show(side)}",
                          hint="the side of the directed line from the first centre to the second")
        chosen = left if side == "left" else right
    else:
        chosen = _pick(ctx, where, (left, right), spec["near"], pts, name)
        side = "left" if chosen is left else "right"
    other = right if chosen is left else left
    touch = other is chosen or (left == right).all()
    ctx.compass.append(Construction(
        name, "circles", given, _pair(chosen), None if touch else _pair(other), _rule(spec), side,
        "" if touch else f'side = "{"right" if side == "left" else "left"}"'))
    return chosen


def _circle_and_line(ctx, where, name, spec, pts):
    check_keys(ctx, where, spec, ("circle", "line", "near"))
    c = spec["circle"]
    if not (isinstance(c, list) and len(c) == 2):
        raise ctx.err(where + ".circle", f"expected [\"P\", r], got {show(c)}",
                      hint="the circle's centre point and its radius")
    centre = _ref(ctx, where + ".circle", c[0], pts, name)
    r = read_number(ctx, where + ".circle", c[1], positive=True, allow_zero=False)
    if "line" not in spec:
        raise ctx.err(where, "a circle-line construction needs 'line'",
                      hint='add line = { through = [x, y], angle = deg } or line = ["Q", "R"]')
    through, ang = _line(ctx, where + ".line", spec["line"], pts, name)
    if "near" not in spec:
        raise ctx.err(where, "a circle-line construction needs 'near'",
                      hint="add near = [x, y], a sketch point near the intersection you mean")
    a, b, gap = circle_line(centre, r, through, ang)
    if gap > 1e-9 * r:
        raise ctx.err(where, f"the line misses the circle (gap {length(ctx, gap)})",
                      hint=f"the line passes {length(ctx, gap + r)} from the centre, beyond the radius {r:g}: "
                           "check the radius and the line")
    if np.hypot(*(a - b)) <= 2 * TANGENT * max(r, float(np.hypot(*(centre - through)))):
        a = b = 0.5 * (a + b)   # tangent to within rounding
    chosen = _pick(ctx, where, (a, b), spec["near"], pts, name)
    other = b if chosen is a else a
    touch = (a == b).all()
    d = other - centre
    line = spec["line"]
    shown = (f"{line[0]}-{line[1]}" if isinstance(line, list) else
             f"through {line['through'] if isinstance(line['through'], str) else '(%g, %g)' % _pair(through)} "
             f"at {line['angle']:g} deg")
    ctx.compass.append(Construction(
        name, "circle and line", f"circle {c[0]} {r:g}, line {shown}", _pair(chosen), None if touch else _pair(other),
        _rule(spec), None,
        "" if touch else f'near = {{ from = "{c[0]}", angle = {math.degrees(math.atan2(d[1], d[0])):.2f} }}'))
    return chosen


def _pair(v) -> tuple[float, float]:
    return (float(v[0]), float(v[1]))


def _rule(spec) -> str:
    """How a compass construction picks its intersection, as the file writes it."""
    if "side" in spec:
        return f'side = "{spec["side"]}"'
    near = spec["near"]
    if isinstance(near, dict):
        return f'near = {{ from = "{near["from"]}", angle = {near["angle"]:g} }}'
    if isinstance(near, list):
        return f"near = [{near[0]:g}, {near[1]:g}]"
    return f'near = "{near}"'


def _polar_construction(ctx, where, name, spec, pts):
    if "from" in spec and "to" in spec:
        raise ctx.err(where, "give one of 'from' and 'to', not both",
                      hint="from = \"P\": P plus the vector; to = \"P\": P minus it")
    key = "from" if "from" in spec else "to"
    if "along" in spec and "angle" in spec:
        raise ctx.err(where, "give one of 'angle' and 'along', not both",
                      hint="angle = deg: an absolute direction; along = [\"Q\", \"R\"] (with turn = deg): "
                           "the direction from Q to R")
    check_keys(ctx, where, spec, (key, "length", "along", "turn") if "along" in spec else (key, "length", "angle"))
    base = _ref(ctx, f"{where}.{key}", spec[key], pts, name)
    if "length" not in spec:
        raise ctx.err(where, "missing 'length'", hint=f"add length = L (the distance from {spec[key]!s})")
    L = read_number(ctx, where + ".length", spec["length"], positive=True)
    if "along" in spec:
        al = spec["along"]
        if not (isinstance(al, list) and len(al) == 2):
            raise ctx.err(where + ".along", f"expected [\"Q\", \"R\"], got {show(al)}",
                          hint="the direction from Q to R, two points' names")
        q = _ref(ctx, where + ".along", al[0], pts, name)
        r = _ref(ctx, where + ".along", al[1], pts, name)
        if coincide(q, r):
            raise ctx.err(where + ".along", f"{str(al[0])!r} and {str(al[1])!r} coincide: no direction",
                          hint="name two points that are apart")
        ang = direction(q, r) + read_number(ctx, where + ".turn", spec.get("turn", 0.0))
    else:
        if "angle" not in spec:
            raise ctx.err(where, "missing 'angle' (or 'along')",
                          hint="add angle = deg (counter-clockwise from +x) or along = [\"Q\", \"R\"]")
        ang = read_number(ctx, where + ".angle", spec["angle"])
    v = L * np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
    return base + v if key == "from" else base - v


def _line(ctx, where, spec, pts, name):
    """A construction's line: ``["Q", "R"]`` or ``{through = "Q" or [x, y], angle = deg}``, as (a point, deg)."""
    if isinstance(spec, list):
        if len(spec) != 2:
            raise ctx.err(where, f"expected [\"Q\", \"R\"] or {{through, angle}}, got a list of {len(spec)}",
                          hint="the line through two points, or through a point at an angle")
        q = _ref(ctx, where, spec[0], pts, name)
        r = _ref(ctx, where, spec[1], pts, name)
        if coincide(q, r):
            raise ctx.err(where, "the line's two points coincide", hint="name two points that are apart")
        return q, direction(q, r)
    if isinstance(spec, dict):
        check_keys(ctx, where, spec, ("through", "angle"))
        if "through" not in spec or "angle" not in spec:
            raise ctx.err(where, "a line needs 'through' and 'angle'",
                          hint="line = { through = \"Q\" or [x, y], angle = deg }")
        return (_point_or_xy(ctx, where + ".through", spec["through"], pts, name),
                read_number(ctx, where + ".angle", spec["angle"]))
    raise ctx.err(where, f"expected a line, got {show(spec)}",
                  hint="line = { through = \"Q\" or [x, y], angle = deg } or line = [\"Q\", \"R\"]")


def _pick(ctx, where, cands, near, pts, name) -> np.ndarray:
    """The intersection ``near`` picks: nearest a sketch point or named point, or (``{from, angle}``)
    the one whose direction from a point is closest to the angle."""
    if isinstance(near, dict):
        check_keys(ctx, where + ".near", near, ("from", "angle"))
        if "from" not in near or "angle" not in near:
            raise ctx.err(where + ".near", "expected {from = \"P\", angle = deg}",
                          hint="the intersection whose direction from P is closest to the angle")
        base = _ref(ctx, where + ".near", near["from"], pts, name)
        ang = math.radians(read_number(ctx, where + ".near.angle", near["angle"]))
        e = np.array([math.cos(ang), math.sin(ang)])

        def score(c):
            d = c - base
            n = np.hypot(*d)
            return -np.dot(d, e) / n if n > 0 else 2.0
        return min(cands, key=score)
    if not isinstance(near, (list, str, int)) or isinstance(near, bool):
        raise ctx.err(where + ".near", f"expected [x, y], a point's name or {{from, angle}}, got {show(near)}",
                      hint="near = [x, y] is a sketch point near the intersection you mean")
    target = _point_or_xy(ctx, where + ".near", near, pts, name)
    return min(cands, key=lambda c: float(np.hypot(*(c - target))))
