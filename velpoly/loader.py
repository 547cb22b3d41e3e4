"""Mechanism files (TOML, FORMAT.md section 1) to :class:`~velpoly.model.Mechanism`.

Every check of the input lives here. Each failure raises
:class:`~velpoly.errors.InputError` naming the file, the entry
(``points.C``, ``driver.omega``) and what is wrong, with a hint.
"""
from __future__ import annotations

import json
import copy
import math
import os
import re
import tomllib
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from .errors import ArgumentTypeError, InputError, VelpolyError, control_character
from .model import (Construction, Contact, Driver, Link, Mechanism, Pin, Reference, Slider, Slot,
                    frozen_map)
from .pose import circle_circle, circle_line

__all__ = ["load", "loads", "locate", "parse_omega", "parse_alpha"]

TOP_KEYS = ("format", "title", "units", "points", "links", "sliders", "contacts", "slots",
            "driver", "reference", "drawing")


class _Ctx:
    """The file being read: its name and text (to find line numbers)."""

    def __init__(self, file: str, text: str | None):
        self.file = file
        self.text = text
        self.units = ""
        self.point_names: tuple[str, ...] = ()   # every name in [points], in file order
        self.compass: list[Construction] = []     # the compass constructions met, in file order

    def err(self, where: str, what: str, hint: str = "") -> InputError:
        line = locate(self.text, where)
        if line:
            where = f"{where} (line {line})"
        return InputError(what, where=where, file=self.file, hint=hint)


# -- where an entry is in the TOML text --------------------------------------------------
_BARE = r"[A-Za-z0-9_-]+"
_QUOTED = r'"(?:[^"\\]|\\.)*"|' + r"'[^']*'"
_KEYPART = rf"(?:{_BARE}|{_QUOTED})"
_DOTTED = rf"{_KEYPART}(?:\s*\.\s*{_KEYPART})*"
_HEADER_RE = re.compile(rf"^\s*(\[\[|\[)\s*({_DOTTED})\s*(\]\]|\])\s*(?:#.*)?$")
_ASSIGN_RE = re.compile(rf"^\s*({_DOTTED})\s*=")
_PART_RE = re.compile(_KEYPART)
_TRIPLE = ('"' * 3, "'" * 3)


def _key_parts(dotted: str) -> list[str]:
    out = []
    for m in _PART_RE.finditer(dotted):
        k = m.group(0)
        if k[:1] == '"' and "\\" in k:   # a basic string's escapes, as TOML reads them ("E\tF")
            try:
                k = tomllib.loads("k = " + k)["k"]
            except tomllib.TOMLDecodeError:
                k = k[1:-1]
        elif k[:1] in "\"'":
            k = k[1:-1]
        out.append(k)
    return out


def _where_parts(where: str) -> list:
    """``sliders[0].guide`` -> ['sliders', 0, 'guide']."""
    out: list = []
    for piece in where.split("."):
        m = re.fullmatch(r"(.*?)((?:\[\d+\])*)", piece, flags=re.DOTALL)
        if m.group(1) in ('""', "''"):   # an empty name, written as TOML writes it
            out.append("")
        elif m.group(1):
            out.append(m.group(1))
        out.extend(int(i) for i in re.findall(r"\[(\d+)\]", m.group(2)))
    return out


def _scan_brackets(line: str, depth: int, in_ml: str | None, peak: list | None = None) -> tuple[int, str | None]:
    """Bracket depth and open multi-line string after ``line`` (strings and comments skipped); the
    deepest depth inside the line is kept in ``peak[0]`` if given."""
    i, n = 0, len(line)
    while i < n:
        if in_ml:
            j = line.find(in_ml, i)
            if j < 0:
                return depth, in_ml
            i, in_ml = j + 3, None
            continue
        c = line[i]
        if c == "#":
            break
        if line[i:i + 3] in _TRIPLE:
            in_ml = line[i:i + 3]
            i += 3
            continue
        if c in "\"'":
            j = i + 1
            while j < n and line[j] != c:
                j += 2 if (c == '"' and line[j] == "\\") else 1
            i = j + 1
            continue
        if c in "[{":
            depth += 1
            if peak is not None and depth > peak[0]:
                peak[0] = depth
        elif c in "]}":
            depth = max(depth - 1, 0)
        i += 1
    return depth, in_ml


def locate(text: str | None, where: str) -> int | None:
    """The line (1-based) of the TOML text that defines the entry ``where``.

    ``where`` is written ``table.key`` (``points.C``, ``sliders[1].guide``,
    ``reference.values.V_B``); the line is the one whose key path is the
    longest prefix of it: the key's own line, or else its table's header.
    None when the entry is not in the text (a default, or a dict input).

    >>> locate("[points]\\nA = [0, 0]\\nB = [1, 0]\\n", "points.B")
    3
    >>> locate("[[sliders]]\\nblock = 1\\n[[sliders]]\\nblock = 2\\n", "sliders[1].block")
    4
    """
    if not text or not where or "(line " in where:
        return None
    target = [str(t) for t in _where_parts(where)]
    best, best_len = None, 0
    table: list = []
    counts: dict[tuple, int] = {}
    depth, in_ml = 0, None
    for no, line in enumerate(text.splitlines(), start=1):
        if depth == 0 and not in_ml:
            path = None
            h = _HEADER_RE.match(line)
            if h:
                table = _key_parts(h.group(2))
                if h.group(1) == "[[":
                    key = tuple(table)
                    counts[key] = counts.get(key, -1) + 1
                    table = table + [str(counts[key])]
                else:  # a sub-table of the latest array-of-tables entry: [[a]] then [a.b]
                    for key, i in counts.items():
                        if tuple(table[:len(key)]) == key and len(table) > len(key):
                            table = list(key) + [str(i)] + table[len(key):]
                            break
                path = table
            else:
                a = _ASSIGN_RE.match(line)
                if a:
                    path = table + _key_parts(a.group(1))
            if path is not None:
                k = 0
                while k < min(len(path), len(target)) and path[k] == target[k]:
                    k += 1
                if (k == len(path) or (h and k == len(target))) and k > best_len:
                    best, best_len = no, k
            if h:
                continue
        depth, in_ml = _scan_brackets(line, depth, in_ml)
    return best


# -- scalar parsing --------------------------------------------------------------------
def _show(v: Any) -> str:
    """A value as the user wrote it, on one short line: "40", true, a table, a list."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        s = json.dumps(v, ensure_ascii=False)
        return s if len(s) <= 42 else s[:38] + '..."'
    if isinstance(v, dict):
        return "a table"
    if isinstance(v, list):
        return "a list"
    if isinstance(v, float) and not math.isfinite(v):
        return str(v)
    if isinstance(v, (int, float)):
        return f"{v:g}" if isinstance(v, float) else str(v)
    return f"a {type(v).__name__}"


def _num(ctx: _Ctx, where: str, v: Any, positive: bool = False, allow_zero: bool = True) -> float:
    if isinstance(v, bool):
        raise ctx.err(where, f"expected a number, got {_show(v)}", hint="true and false are not numbers")
    if isinstance(v, str):
        raise ctx.err(where, f"expected a number, got the string {_show(v)}",
                      hint="write numbers without quotes")
    if not isinstance(v, (int, float)):
        raise ctx.err(where, f"expected a number, got {_show(v)}", hint="write a single number here")
    x = float(v)
    if not math.isfinite(x):
        raise ctx.err(where, f"expected a finite number, got {_show(x)}", hint="nan and inf are not allowed")
    if positive and (x < 0 or (x == 0 and not allow_zero)):
        raise ctx.err(where, f"must be positive, got {_show(v)}",
                      hint="lengths and radii are positive; give the direction with an angle")
    return x


def _name(ctx: _Ctx, where: str, v: Any, what: str = "a name") -> str:
    if isinstance(v, bool) or not isinstance(v, (str, int)):
        raise ctx.err(where, f"expected {what}, got {_show(v)}", hint='names are strings: "B", "3"')
    return str(v)


_OMEGA_UNITS = {
    "rad/s": 1.0, "rpm": 2 * math.pi / 60, "r/min": 2 * math.pi / 60, "rev/min": 2 * math.pi / 60,
    "deg/s": math.pi / 180, "rev/s": 2 * math.pi, "rps": 2 * math.pi, "hz": 2 * math.pi,
}
_ALPHA_UNITS = {"rad/s^2": 1.0, "rad/s2": 1.0, "rad/s²": 1.0, "rad/s/s": 1.0,
                "deg/s^2": math.pi / 180, "deg/s2": math.pi / 180}
# a sense in words, as books write it (any case): the clockwise ones reverse the sign
SENSES = {"cw": -1.0, "clockwise": -1.0, "ccw": 1.0, "counterclockwise": 1.0, "counter-clockwise": 1.0,
          "anticlockwise": 1.0, "anti-clockwise": 1.0}
_RATE_RE = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S+?)(?:\s+("
                      + "|".join(sorted(map(re.escape, SENSES), key=len, reverse=True)) + r"))?\s*",
                      flags=re.IGNORECASE)


def _parse_rate(text: str, units: Mapping[str, float]) -> float:
    m = _RATE_RE.fullmatch(text)
    if not m:
        raise ValueError(text)
    value, unit, sense = m.groups()
    unit = unit.lower()
    if unit not in units:
        raise ValueError(text)
    x = float(value) * units[unit]
    if not math.isfinite(x):
        raise ValueError(text)
    if sense:
        x *= SENSES[sense.lower()]
    return x + 0.0   # no negative zero


def parse_omega(v: Any) -> float:
    """An angular velocity in rad/s (ccw positive) from a number or ``"NUMBER UNIT [cw|ccw]"``.

    UNIT is rad/s, rpm (r/min, rev/min), deg/s or rev/s (rps, Hz), case-insensitive;
    the sense is ``cw`` or ``clockwise`` (which reverse the sign), ``ccw``, ``counterclockwise``,
    ``counter-clockwise``, ``anticlockwise`` or ``anti-clockwise``, in any case (FORMAT.md
    sections 1 and 5). Raises ValueError otherwise.

    >>> round(parse_omega("60 rpm"), 6)
    6.283185
    >>> parse_omega("-10 rad/s cw")
    10.0
    >>> parse_omega("10 rad/s Clockwise")
    -10.0
    """
    if isinstance(v, bool):
        raise ValueError(v)
    if isinstance(v, (int, float)):
        return float(v)
    if isinstance(v, str):
        return _parse_rate(v, _OMEGA_UNITS)
    raise ValueError(v)


def parse_alpha(v: Any) -> float:
    """An angular acceleration in rad/s^2 from a number or ``"NUMBER rad/s^2 [cw|ccw]"``.

    >>> parse_alpha("5 rad/s^2 cw")
    -5.0
    """
    if isinstance(v, bool):
        raise ValueError(v)
    if isinstance(v, (int, float)):
        return float(v)
    if isinstance(v, str):
        return _parse_rate(v, _ALPHA_UNITS)
    raise ValueError(v)


# -- points -------------------------------------------------------------------------------
TANGENT = 1e-7   # intersections closer than this (relative to the construction's size) touch


def _xy(ctx, where, v) -> np.ndarray:
    if not isinstance(v, list) or len(v) != 2:
        raise ctx.err(where, f"expected [x, y], got {_show(v)}" + (f" of {len(v)} items" if isinstance(v, list) else ""),
                      hint="a position is a list of two numbers, e.g. [0.3, 0.45]")
    return np.array([_num(ctx, where, v[0]), _num(ctx, where, v[1])])


def _ref(ctx, where, name, pts, current=None) -> np.ndarray:
    """The position of a point named in a construction: one defined above it."""
    name = _name(ctx, where, name, "a point's name")
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


def _keys(ctx, where, d: dict, allowed: tuple[str, ...]):
    for k in d:
        if k not in allowed:
            raise ctx.err(f"{where}.{k}" if where else str(k), f"unknown key {_key(k)}",
                          hint="valid keys: " + ", ".join(allowed))


def _key(k) -> str:
    return repr(k) if isinstance(k, str) else repr(str(k))


_CONSTRUCTIONS = ("[x, y], {from, length, angle}, {to, length, angle}, {from, length, along, turn}, "
                  "{circles, near or side} or {circle, line, near}")
_CONSTRUCTION_KEYS = ("from", "to", "length", "angle", "along", "turn", "circles", "near", "side",
                      "circle", "line")


def _construct(ctx: _Ctx, name: str, spec: Any, pts: dict) -> np.ndarray:
    where = f"points.{name}"
    if isinstance(spec, list):
        return _xy(ctx, where, spec)
    if not isinstance(spec, dict):
        raise ctx.err(where, f"expected [x, y] or a construction table, got {_show(spec)}",
                      hint="use " + _CONSTRUCTIONS)
    if "circles" in spec:
        return _two_circles(ctx, where, name, spec, pts)
    if "circle" in spec:
        return _circle_and_line(ctx, where, name, spec, pts)
    if "from" in spec or "to" in spec:
        return _polar_construction(ctx, where, name, spec, pts)
    unknown = [k for k in spec if k not in _CONSTRUCTION_KEYS]
    if unknown:
        raise ctx.err(f"{where}.{unknown[0]}", f"unknown key {_key(unknown[0])}",
                      hint="a point is " + _CONSTRUCTIONS)
    raise ctx.err(where, "incomplete construction: " + (", ".join(map(str, spec)) or "an empty table"),
                  hint="a point is " + _CONSTRUCTIONS)


def _two_circles(ctx, where, name, spec, pts):
    _keys(ctx, where, spec, ("circles", "near", "side"))
    cs = spec["circles"]
    if not (isinstance(cs, list) and len(cs) == 2 and all(isinstance(c, list) and len(c) == 2 for c in cs)):
        raise ctx.err(where + ".circles", f"expected [[\"P\", r1], [\"Q\", r2]], got {_show(cs)}",
                      hint="two circles, each a centre point's name and a radius")
    p = _ref(ctx, where + ".circles", cs[0][0], pts, name)
    q = _ref(ctx, where + ".circles", cs[1][0], pts, name)
    r1 = _num(ctx, where + ".circles", cs[0][1], positive=True, allow_zero=False)
    r2 = _num(ctx, where + ".circles", cs[1][1], positive=True, allow_zero=False)
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
        raise ctx.err(where, f"circles do not meet (gap {_length(ctx, gap)})",
                      hint=(f"one circle lies inside the other ({_length(ctx, dist)} between centres, radii "
                            f"{r1:g} and {r2:g}): check the lengths") if inside else
                      (f"the centres are {_length(ctx, dist)} apart but the radii add up to {r1 + r2:g}: "
                       "check the lengths (the links cannot reach)"))
    if np.hypot(*(left - right)) <= 2 * TANGENT * max(r1, r2, dist):
        left = right = 0.5 * (left + right)   # tangent to within rounding: on the line of centres
    given = f"circles {cs[0][0]} {r1:g}, {cs[1][0]} {r2:g}"
    if "side" in spec:
        side = spec["side"]
        if side not in ("left", "right"):
            raise ctx.err(where + ".side", f"expected \"left\" or \"right\", got {_show(side)}",
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
    _keys(ctx, where, spec, ("circle", "line", "near"))
    c = spec["circle"]
    if not (isinstance(c, list) and len(c) == 2):
        raise ctx.err(where + ".circle", f"expected [\"P\", r], got {_show(c)}",
                      hint="the circle's centre point and its radius")
    centre = _ref(ctx, where + ".circle", c[0], pts, name)
    r = _num(ctx, where + ".circle", c[1], positive=True, allow_zero=False)
    if "line" not in spec:
        raise ctx.err(where, "a circle-line construction needs 'line'",
                      hint='add line = { through = [x, y], angle = deg } or line = ["Q", "R"]')
    through, ang = _line(ctx, where + ".line", spec["line"], pts, name)
    if "near" not in spec:
        raise ctx.err(where, "a circle-line construction needs 'near'",
                      hint="add near = [x, y], a sketch point near the intersection you mean")
    a, b, gap = circle_line(centre, r, through, ang)
    if gap > 1e-9 * r:
        raise ctx.err(where, f"the line misses the circle (gap {_length(ctx, gap)})",
                      hint=f"the line passes {_length(ctx, gap + r)} from the centre, beyond the radius {r:g}: "
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
    _keys(ctx, where, spec, (key, "length", "along", "turn") if "along" in spec else (key, "length", "angle"))
    base = _ref(ctx, f"{where}.{key}", spec[key], pts, name)
    if "length" not in spec:
        raise ctx.err(where, "missing 'length'", hint=f"add length = L (the distance from {spec[key]!s})")
    L = _num(ctx, where + ".length", spec["length"], positive=True)
    if "along" in spec:
        al = spec["along"]
        if not (isinstance(al, list) and len(al) == 2):
            raise ctx.err(where + ".along", f"expected [\"Q\", \"R\"], got {_show(al)}",
                          hint="the direction from Q to R, two points' names")
        q = _ref(ctx, where + ".along", al[0], pts, name)
        r = _ref(ctx, where + ".along", al[1], pts, name)
        if _coincide(q, r):
            raise ctx.err(where + ".along", f"{str(al[0])!r} and {str(al[1])!r} coincide: no direction",
                          hint="name two points that are apart")
        d = r - q
        ang = math.degrees(math.atan2(d[1], d[0])) + _num(ctx, where + ".turn", spec.get("turn", 0.0))
    else:
        if "angle" not in spec:
            raise ctx.err(where, "missing 'angle' (or 'along')",
                          hint="add angle = deg (counter-clockwise from +x) or along = [\"Q\", \"R\"]")
        ang = _num(ctx, where + ".angle", spec["angle"])
    v = L * np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
    return base + v if key == "from" else base - v


_PATH_KEYS = ("angle", "along", "centre")


def _path_angle(ctx, where, entry, pts, what: str) -> float | None:
    """The direction (deg) of a slider's path or a slot: ``angle = deg``, or ``along = ["P", "Q"]``
    (from P to Q at the reference pose); None for a circular one (``centre``). Exactly one is given."""
    given = [k for k in _PATH_KEYS if k in entry]
    if len(given) != 1:
        raise ctx.err(where, f"give the {what} as exactly one of 'angle', 'along' and 'centre'" +
                      (f" ({' and '.join(given)} are given)" if given else ""),
                      hint=f"angle = deg or along = [\"P\", \"Q\"] (a straight {what}: the line P -> Q), "
                           f"or centre = \"K\" (a circular one)")
    if "angle" in entry:
        return _num(ctx, where + ".angle", entry["angle"])
    if "centre" in entry:
        return None
    al, w = entry["along"], where + ".along"
    if not (isinstance(al, list) and len(al) == 2):
        raise ctx.err(w, f"expected [\"P\", \"Q\"], got {_show(al)}",
                      hint=f"the {what} runs in the direction from P to Q (two points' names), e.g. [\"O4\", \"B\"]")
    ends = []
    for name in al:
        name = _name(ctx, w, name, "a point's name")
        if name not in pts:
            raise ctx.err(w, f"unknown point {name!r}",
                          hint="define it in [points]" + (": " + ", ".join(pts) if len(pts) <= 20 else ""))
        ends.append(pts[name])
    if _coincide(*ends):
        raise ctx.err(w, f"{str(al[0])!r} and {str(al[1])!r} coincide: no direction",
                      hint="name two points that are apart")
    d = ends[1] - ends[0]
    return math.degrees(math.atan2(d[1], d[0]))


def _coincide(p, q) -> bool:
    """Two points at one place, to within rounding of their coordinates."""
    return float(np.hypot(*(q - p))) <= 1e-12 * max(float(np.abs(p).max()), float(np.abs(q).max()))


def _length(ctx, x: float) -> str:
    return f"{x:.6g} {ctx.units}".rstrip()


def _line(ctx, where, spec, pts, name):
    if isinstance(spec, list):
        if len(spec) != 2:
            raise ctx.err(where, f"expected [\"Q\", \"R\"] or {{through, angle}}, got a list of {len(spec)}",
                          hint="the line through two points, or through a point at an angle")
        q = _ref(ctx, where, spec[0], pts, name)
        r = _ref(ctx, where, spec[1], pts, name)
        if _coincide(q, r):
            raise ctx.err(where, "the line's two points coincide", hint="name two points that are apart")
        d = r - q
        return q, math.degrees(math.atan2(d[1], d[0]))
    if isinstance(spec, dict):
        _keys(ctx, where, spec, ("through", "angle"))
        if "through" not in spec or "angle" not in spec:
            raise ctx.err(where, "a line needs 'through' and 'angle'",
                          hint="line = { through = \"Q\" or [x, y], angle = deg }")
        return (_point_or_xy(ctx, where + ".through", spec["through"], pts, name),
                _num(ctx, where + ".angle", spec["angle"]))
    raise ctx.err(where, f"expected a line, got {_show(spec)}",
                  hint="line = { through = \"Q\" or [x, y], angle = deg } or line = [\"Q\", \"R\"]")


def _pick(ctx, where, cands, near, pts, name) -> np.ndarray:
    if isinstance(near, dict):
        _keys(ctx, where + ".near", near, ("from", "angle"))
        if "from" not in near or "angle" not in near:
            raise ctx.err(where + ".near", "expected {from = \"P\", angle = deg}",
                          hint="the intersection whose direction from P is closest to the angle")
        base = _ref(ctx, where + ".near", near["from"], pts, name)
        ang = math.radians(_num(ctx, where + ".near.angle", near["angle"]))
        e = np.array([math.cos(ang), math.sin(ang)])

        def score(c):
            d = c - base
            n = np.hypot(*d)
            return -np.dot(d, e) / n if n > 0 else 2.0
        return min(cands, key=score)
    if not isinstance(near, (list, str, int)) or isinstance(near, bool):
        raise ctx.err(where + ".near", f"expected [x, y], a point's name or {{from, angle}}, got {_show(near)}",
                      hint="near = [x, y] is a sketch point near the intersection you mean")
    target = _point_or_xy(ctx, where + ".near", near, pts, name)
    return min(cands, key=lambda c: float(np.hypot(*(c - target))))


# -- the whole file -----------------------------------------------------------------------------
def load(source, *, name: str | None = None) -> Mechanism:
    """Read a mechanism from a file path, a dict, or TOML text with a newline in it (FORMAT.md section 4).

    A string on one line is a file's path (TOML text on one line, such as
    ``"[points]"``, is refused with a pointer to :func:`loads`); a string with
    a newline is TOML text. A dict's values may be tuples, numpy scalars or
    1-D arrays where the file has lists and numbers. Input files are only
    read, never written. Raises :class:`~velpoly.errors.InputError` (a
    :class:`VelpolyError`) naming the file, the entry and what is wrong.
    """
    text = None
    if isinstance(source, Mapping):
        file = name or "<dict>"
        data = _plain(source, file)
    elif isinstance(source, os.PathLike) or (isinstance(source, str) and source.strip() and "\n" not in source):
        path = Path(source)
        file = name or str(source)
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            if isinstance(source, str) and _looks_like_toml(source):
                raise InputError("no such file: this is TOML text, not a file's name", file=file,
                                 hint="read TOML text with velpoly.loads(text) (velpoly.load reads text "
                                      "only with a newline in it)") from None
            raise InputError("no such file", file=file, hint="check the path") from None
        except IsADirectoryError:
            raise InputError("is a directory, not a mechanism file", file=file,
                             hint="give the path of a .toml file") from None
        except UnicodeDecodeError:
            raise InputError("not a text (UTF-8) file", file=file,
                             hint="a mechanism file is TOML text in UTF-8") from None
        except (OSError, ValueError) as e:   # ValueError: a NUL character in the path
            raise InputError(f"cannot read: {getattr(e, 'strerror', None) or e}", file=file,
                             hint="check the path and its permissions") from None
        if text.startswith("\ufeff"):   # a byte-order mark, as some editors write
            text = text[1:]
        data = _parse_toml(text, file)
        if name is None:
            name = path.name
    elif isinstance(source, str):
        return loads(source, name=name)
    else:
        raise ArgumentTypeError(f"cannot load {_a(type(source).__name__)}: give a path, a dict or TOML text",
                                where="source", file=name or "",
                                hint="velpoly.load(\"fourbar.toml\"), or velpoly.loads(text) for TOML text")
    return _load_data(data, file, text, name)


def loads(text: str, *, name: str | None = None) -> Mechanism:
    """Read a mechanism from TOML text (one line or many): ``velpoly.loads('format = 1\\n[points]...')``.

    ``name`` is what errors call it (default ``<text>``). Raises
    :class:`~velpoly.errors.InputError` naming the entry and what is wrong.
    """
    if isinstance(text, (bytes, bytearray)):
        try:
            text = bytes(text).decode("utf-8")
        except UnicodeDecodeError:
            raise InputError("not UTF-8 text", where="text", file=name or "<text>",
                             hint="TOML text is UTF-8") from None
    if not isinstance(text, str):
        raise ArgumentTypeError(f"expected TOML text (a string), got {_a(type(text).__name__)}", where="text",
                                file=name or "", hint="velpoly.load(path) reads a file, velpoly.load(d) a dict")
    file = name or "<text>"
    if text.startswith("\ufeff"):
        text = text[1:]
    return _load_data(_parse_toml(text, file), file, text, name)


def _a(noun: str) -> str:
    return ("an " if noun[:1].lower() in "aeiou" else "a ") + noun


def _looks_like_toml(s: str) -> bool:
    """A one-line string that is TOML rather than a path: a [table] header or a key = value."""
    t = s.strip()
    return t.startswith("[") or "=" in t or t.startswith("#")


def _load_data(data: dict, file: str, text: str | None, name: str | None) -> Mechanism:
    ctx = _Ctx(file, text)
    try:
        return _build(ctx, data, default_title=name or file)
    except VelpolyError as e:
        raise e.with_file(file)
    except RecursionError:   # pragma: no cover (nesting is limited by _plain first)
        raise InputError(f"nested too deeply (more than {MAX_DEPTH} levels)", file=file,
                         hint="a mechanism file's entries nest a few levels at most") from None
    except (TypeError, ValueError, KeyError, IndexError, AttributeError) as e:  # pragma: no cover
        # every input is checked above; this is a last line of defence, never a traceback
        raise InputError(f"malformed entry ({type(e).__name__}: {e})", file=file,
                         hint="please report this file: velpoly should have named the entry") from None


MAX_DEPTH = 32   # levels of tables and lists: a mechanism file nests 4 or 5 at most


def _plain(data, file: str) -> dict:
    """``data`` (a dict, or what TOML gave) as plain TOML values: tuples and 1-D arrays become lists,
    numpy scalars Python numbers, and no entry nested deeper than MAX_DEPTH (an InputError naming it,
    never a RecursionError). The caller's dict is not changed."""
    def where_of(path):
        out = ""
        for k in path:
            out += f"[{k}]" if isinstance(k, int) else (f".{k}" if out else str(k))
        return out

    def conv(v, path):
        if isinstance(v, Mapping) or isinstance(v, (list, tuple)) or (isinstance(v, np.ndarray) and v.ndim):
            if len(path) >= MAX_DEPTH:
                shown = where_of(path[:6]) + ("..." if len(path) > 6 else "")
                raise InputError(f"nested more than {MAX_DEPTH} levels deep", where=shown, file=file,
                                 hint="a mechanism file's entries nest a few levels at most: "
                                      "check the brackets and table headers")
            if isinstance(v, Mapping):
                return {key(k): conv(x, path + [key(k)]) for k, x in v.items()}
            return [conv(x, path + [i]) for i, x in enumerate(v)]
        if isinstance(v, (np.generic, np.ndarray)):   # a numpy scalar or 0-d array
            return v.item() if isinstance(v, np.generic) or v.ndim == 0 else v
        return v

    def key(k):
        return k.item() if isinstance(k, np.generic) else k
    return conv(data, [])


def _deep_entry(text: str) -> tuple[str, int | None]:
    """The entry (``table.key``) and line where the text's brackets nest deeper than MAX_DEPTH."""
    table, key, depth, in_ml = "", "", 0, None
    for no, line in enumerate(text.splitlines(), start=1):
        if depth == 0 and not in_ml:
            h = _HEADER_RE.match(line)
            if h:
                table, key = ".".join(_key_parts(h.group(2))), ""
                if len(_key_parts(h.group(2))) > MAX_DEPTH:
                    return table[:60], no
                continue
            a = _ASSIGN_RE.match(line)
            if a:
                key = ".".join(_key_parts(a.group(1)))
        peak = [depth]
        depth, in_ml = _scan_brackets(line, depth, in_ml, peak)
        if peak[0] > MAX_DEPTH:
            return ".".join(p for p in (table, key) if p)[:60], no
    return "", None


def _parse_toml(text: str, file: str) -> dict:
    if not text.strip():
        raise InputError("the file is empty", file=file,
                         hint="a mechanism file has [points], [links] and [driver] tables (see the README)")
    try:
        return _plain(tomllib.loads(text), file)
    except RecursionError:   # tomllib reads nested brackets recursively
        entry, line = _deep_entry(text)
        raise InputError(f"nested more than {MAX_DEPTH} levels deep", file=file,
                         where=f"{entry} (line {line})" if entry and line else (f"line {line}" if line else entry),
                         hint="a mechanism file's entries nest a few levels at most: "
                              "check the brackets") from None
    except tomllib.TOMLDecodeError as e:
        msg = str(e)
        m = re.search(r"\s*\(at line (\d+), column (\d+)\)\s*$", msg)
        where = ""
        if m:
            where = f"line {m.group(1)}"
            msg = msg[:m.start()] + f" at column {m.group(2)}"
        else:
            msg = re.sub(r"\s*\(at end of document\)\s*$", " at the end of the file", msg)
            opened = _unclosed(text)
            if opened:
                where = f"line {opened}"
                msg += " (opened here)"
        raise InputError(f"bad TOML: {msg[:1].lower() + msg[1:]}", where=where, file=file,
                         hint="check the syntax there (quotes around names, = between key and value, "
                              "one key per line)") from None


def _unclosed(text: str) -> int | None:
    """The line where a bracket or multi-line string opens that the text never closes."""
    depth, in_ml, opened = 0, None, None
    for no, line in enumerate(text.splitlines(), start=1):
        was_open = depth > 0 or in_ml
        depth, in_ml = _scan_brackets(line, depth, in_ml)
        if (depth > 0 or in_ml) and not was_open:
            opened = no
    return opened if (depth > 0 or in_ml) else None


def _table(ctx, data, key, required=True) -> dict:
    if key not in data:
        if required:
            raise ctx.err(key, f"missing table [{key}]", hint=_TABLE_HINTS.get(key, ""))
        return {}
    v = data[key]
    if not isinstance(v, dict):
        raise ctx.err(key, f"expected a table [{key}], got {_show(v)}", hint=_TABLE_HINTS.get(key, ""))
    return v


_TABLE_HINTS = {
    "points": "[points] names each point: A = [0, 0], B = { from = \"A\", length = 0.15, angle = 30 }",
    "links": "[links] lists each link's points: 2 = { points = [\"A\", \"B\"] }, one with frame = true",
    "driver": "[driver] link = \"2\" (a crank pinned to the frame), omega = \"60 rpm\"",
    "reference": "[reference] holds published answers: omega = { \"3\" = 6.70 }, values = { V_B = 602 }",
    "drawing": "[drawing] holds presentation options (see the README)",
}


def _array_of_tables(ctx, data, key) -> list[dict]:
    v = data.get(key, [])
    if not isinstance(v, list):
        raise ctx.err(key, f"expected [[{key}]] entries (an array of tables), got {_show(v)}",
                      hint=f"write each entry under its own [[{key}]] header")
    for i, x in enumerate(v):
        if not isinstance(x, dict):
            raise ctx.err(f"{key}[{i}]", f"expected a table, got {_show(x)}",
                          hint=f"write each entry under its own [[{key}]] header")
    return v


def _names(ctx, table: str, raw: dict, kind: str) -> list[tuple[str, Any]]:
    """The table's entries as (name, spec), names checked."""
    out, seen = [], set()
    for k, spec in raw.items():
        if isinstance(k, bool) or not isinstance(k, (str, int)):
            raise ctx.err(table, f"a {kind}'s name must be a string, got {_show(k)}", hint='e.g. "B" or "3"')
        n = str(k)
        where = f"{table}.{n}"
        if not n.strip():
            raise ctx.err(f"{table}.{json.dumps(n)}", f"a {kind}'s name is empty", hint=f"give the {kind} a name")
        if n in seen:
            raise ctx.err(where, f"{kind} {n!r} is defined twice", hint="each name once")
        for c, why in (("@", "point keys are \"P@link\""),) + ((("-", "pole keys are \"i-j\""),)
                                                             if kind == "link" else ()):
            if c in n:
                raise ctx.err(where, f"a {kind}'s name must not contain {c!r} ({why})",
                              hint=f"rename {kind} {n!r}" + (" (textbooks number links: 1, 2, 3)"
                                                             if kind == "link" else ""))
        if any(control_character(ch) for ch in n):
            raise ctx.err(where, f"a {kind}'s name must not contain control characters",
                          hint=f"rename {kind} {json.dumps(n)} (a line break, a tab or another control "
                               "character cannot be drawn or printed as a name)")
        seen.add(n)
        out.append((n, spec))
    return out


def _build(ctx: _Ctx, data: dict, default_title: str) -> Mechanism:
    for k in data:
        if k not in TOP_KEYS:
            raise ctx.err(str(k), f"unknown key {_key(k)}", hint="valid keys: " + ", ".join(TOP_KEYS))
    fmt = data.get("format", 1)
    if isinstance(fmt, bool) or fmt != 1:
        raise ctx.err("format", f"unsupported format {_show(fmt)}", hint="this velpoly reads format = 1")
    title = data.get("title", default_title)
    if not isinstance(title, str):
        raise ctx.err("title", f"expected a string, got {_show(title)}", hint='title = "Four-bar, Example 3.6"')
    units = data.get("units", "m")
    if not isinstance(units, str):
        raise ctx.err("units", f"expected a string such as \"mm\", got {_show(units)}",
                      hint='units = "mm" (a label for lengths; "" for none)')
    ctx.units = units

    # points, in file order
    raw_points = _table(ctx, data, "points")
    if not raw_points:
        raise ctx.err("points", "no points", hint=_TABLE_HINTS["points"])
    named_points = _names(ctx, "points", raw_points, "point")
    ctx.point_names = tuple(n for n, _ in named_points)
    pts: dict[str, np.ndarray] = {}
    for pname, spec in named_points:
        with np.errstate(all="ignore"):   # an overflow is reported below, as no finite position
            pts[pname] = _construct(ctx, pname, spec, pts)
        if not np.all(np.isfinite(pts[pname])):
            raise ctx.err(f"points.{pname}", "the construction gives no finite position",
                          hint="check its lengths and angles")
    size = _size(pts)
    _check_size(ctx, pts)

    # links
    raw_links = _table(ctx, data, "links")
    links: list[Link] = []
    for lname, spec in _names(ctx, "links", raw_links, "link"):
        where = f"links.{lname}"
        if lname in pts:
            raise ctx.err(where, f"{lname!r} names both a point and a link",
                          hint="give links numbers and points letters, as textbooks do")
        if not isinstance(spec, dict):
            raise ctx.err(where, f"expected {{ points = [...] }}, got {_show(spec)}",
                          hint=f'{lname} = {{ points = ["A", "B"] }}')
        _keys(ctx, where, spec, ("points", "frame"))
        lp = spec.get("points")
        if not isinstance(lp, list) or not lp:
            raise ctx.err(where + ".points", "expected a non-empty list of point names" +
                          ("" if lp is None else f", got {_show(lp)}"),
                          hint=f'{lname} = {{ points = ["A", "B"] }}: the points fixed to the link')
        names = []
        for p in lp:
            p = _name(ctx, where + ".points", p, "a point's name")
            if p not in pts:
                raise ctx.err(where + ".points", f"unknown point {p!r}",
                              hint="define it in [points]" + (": " + ", ".join(pts) if len(pts) <= 20 else ""))
            if p in names:
                raise ctx.err(where + ".points", f"point {p!r} is listed twice", hint="list each point once")
            names.append(p)
        frame = spec.get("frame", False)
        if not isinstance(frame, bool):
            raise ctx.err(where + ".frame", f"expected true or false, got {_show(frame)}",
                          hint="frame = true marks the fixed link")
        if len(names) >= 2 and np.hypot(*(pts[names[0]] - pts[names[1]])) <= 1e-12 * size:
            raise ctx.err(where + ".points", f"its first two points {names[0]!r} and {names[1]!r} coincide, "
                          "so the link's angle is undefined",
                          hint="a link's angle is the direction from its first point to its second: "
                               "list two points that are apart first")
        links.append(Link(lname, tuple(names), frame))
    frames = [k for k in links if k.frame]
    if not frames:
        raise ctx.err("links", "no link is the frame", hint="mark exactly one link with frame = true")
    if len(frames) > 1:
        raise ctx.err(f"links.{frames[1].name}", "two or more links are the frame: " +
                      ", ".join(k.name for k in frames), hint="mark exactly one link with frame = true")
    lnames = [k.name for k in links]
    listed: dict[str, list[str]] = {}
    for k in links:
        for p in k.points:
            listed.setdefault(p, []).append(k.name)

    def link_ref(where, v):
        n = _name(ctx, where, v, "a link's name")
        if n not in lnames:
            raise ctx.err(where, f"unknown link {n!r}", hint="links: " + ", ".join(lnames))
        return n

    def point_ref(where, v):
        n = _name(ctx, where, v, "a point's name")
        if n not in pts:
            raise ctx.err(where, f"unknown point {n!r}",
                          hint="define it in [points]" + (": " + ", ".join(pts) if len(pts) <= 20 else ""))
        return n

    def require(where, entry, keys, example):
        for req in keys:
            if req not in entry:
                raise ctx.err(where, f"missing '{req}'", hint=example)

    owned: dict[str, list[str]] = {}   # points carried without being listed
    coincident: set[tuple[str, str]] = set()  # (point, link): carried as a coincident point, no pin

    def path_centre(where, cen, p, guide, what):
        """A circular path's centre: a point of the guide (or listed in no link: the guide's)."""
        if np.hypot(*(pts[p] - pts[cen])) == 0:
            raise ctx.err(where, f"the {what}'s centre is the point {p!r} itself",
                          hint="the centre of a circular path is the centre of its arc")
        if cen not in listed:
            owned.setdefault(cen, []).append(guide)
        elif guide not in listed[cen]:
            raise ctx.err(where, f"the centre {cen!r} is not a point of link {guide!r}",
                          hint=f"a circular path turns with its link: list {cen!r} in links.{guide}, "
                               "or in no link")

    # sliders
    sliders = []
    for i, s in enumerate(_array_of_tables(ctx, data, "sliders")):
        where = f"sliders[{i}]"
        _keys(ctx, where, s, ("block", "guide", "point", "angle", "along", "centre"))
        require(where, s, ("block", "guide", "point"),
                'a slider has block = "5", guide = "0", point = "F" and angle = deg (or along = ["P", "Q"], '
                'or centre = "K")')
        b, g = link_ref(where + ".block", s["block"]), link_ref(where + ".guide", s["guide"])
        p = point_ref(where + ".point", s["point"])
        if b == g:
            raise ctx.err(where + ".guide", f"block and guide are the same link {b!r}",
                          hint="the block slides on another link, its guide")
        if p not in ctx_link(links, b).points:
            raise ctx.err(where + ".point", f"point {p!r} is not a point of the block {b!r}",
                          hint=f"list {p!r} in links.{b}")
        ang = _path_angle(ctx, where, s, pts, "path")
        cen = point_ref(where + ".centre", s["centre"]) if "centre" in s else None
        if cen is not None:
            path_centre(where + ".centre", cen, p, g, "path")
        if p in ctx_link(links, g).points:
            coincident.add((p, g))
        sliders.append(Slider(b, g, p, ang, cen))

    # slots
    slots = []
    for i, s in enumerate(_array_of_tables(ctx, data, "slots")):
        where = f"slots[{i}]"
        _keys(ctx, where, s, ("pin", "link", "slot", "angle", "along", "centre", "ends"))
        require(where, s, ("pin", "link", "slot"),
                'a slot has pin = "P", link = "3" (carries the pin), slot = "4" and angle = deg (or '
                'along = ["P", "Q"], or centre = "K")')
        p = point_ref(where + ".pin", s["pin"])
        lk, sk = link_ref(where + ".link", s["link"]), link_ref(where + ".slot", s["slot"])
        if lk == sk:
            raise ctx.err(where + ".slot", f"the pin's link and the slot's link are the same link {lk!r}",
                          hint="the pin of one link slides in a slot of another")
        if p not in ctx_link(links, lk).points:
            raise ctx.err(where + ".pin", f"point {p!r} is not a point of link {lk!r}", hint=f"list it in links.{lk}")
        ang = _path_angle(ctx, where, s, pts, "slot")
        cen = point_ref(where + ".centre", s["centre"]) if "centre" in s else None
        if cen is not None:
            path_centre(where + ".centre", cen, p, sk, "slot")
        if p in ctx_link(links, sk).points:
            coincident.add((p, sk))
        ends = _slot_ends(ctx, where + ".ends", s["ends"], p, sk, ang, pts, listed, owned, point_ref) \
            if "ends" in s else None
        slots.append(Slot(p, lk, sk, ang, cen, ends))

    # contacts
    contacts = []
    for i, c in enumerate(_array_of_tables(ctx, data, "contacts")):
        where = f"contacts[{i}]"
        _keys(ctx, where, c, ("links", "point", "kind", "slip", "centres", "normal"))
        if "links" not in c or not isinstance(c["links"], list) or len(c["links"]) != 2:
            raise ctx.err(where + ".links", "expected links = [\"a\", \"b\"]" +
                          (f", got {_show(c['links'])}" if "links" in c else ""),
                          hint="the two links that touch")
        a, b = link_ref(where + ".links", c["links"][0]), link_ref(where + ".links", c["links"][1])
        if a == b:
            raise ctx.err(where + ".links", f"a contact needs two different links, got {a!r} twice",
                          hint="the two links that touch")
        require(where, c, ("point",), 'point = "P": the contact point, defined in [points]')
        p = point_ref(where + ".point", c["point"])
        kind = c.get("kind")
        if kind not in ("rolling", "sliding"):
            raise ctx.err(where + ".kind", "expected \"rolling\" or \"sliding\"" +
                          (f", got {_show(kind)}" if "kind" in c else " (kind is missing)"),
                          hint="rolling: no slip; sliding: slip along the common tangent")
        slip = None
        if "slip" in c:
            if kind != "sliding":
                raise ctx.err(where + ".slip", "a prescribed slip needs kind = \"sliding\"",
                              hint="a rolling contact has no slip: remove slip, or make it sliding")
            slip = _num(ctx, where + ".slip", c["slip"])
        if ("centres" in c) == ("normal" in c):
            raise ctx.err(where, "give exactly one of 'centres' and 'normal'" +
                          (" (both are given)" if "normal" in c else ""),
                          hint="centres = [\"Ca\", \"Cb\"] (\"flat\" for a straight profile), or normal = deg")
        centres = None
        normal = None
        if "centres" in c:
            centres = _contact_centres(ctx, where, c["centres"], (a, b), p, pts, listed, owned, point_ref, size)
        else:
            normal = _num(ctx, where + ".normal", c["normal"])
        for lk in (a, b):
            if lk not in listed.get(p, []):
                owned.setdefault(p, []).append(lk)
            coincident.add((p, lk))
        contacts.append(Contact((a, b), p, kind, slip, centres, normal))

    # every point is carried by something
    for pname in pts:
        if pname not in listed and pname not in owned:
            raise ctx.err(f"points.{pname}", f"point {pname!r} is listed in no link",
                          hint="list it in the link that carries it")

    # pins: k links listing a point (not as a coincident point) -> k-1 pins
    pins = []
    for pname, ls in listed.items():
        carriers = [lk for lk in ls if (pname, lk) not in coincident]
        block = next((s.block for s in sliders if s.point == pname), None)
        if block in carriers:
            carriers.remove(block)
            carriers.insert(0, block)
        for other in carriers[1:]:
            pins.append(Pin(pname, (carriers[0], other)))

    carriers = {}
    for pname in pts:
        cl = list(listed.get(pname, []))
        for lk in owned.get(pname, []):
            if lk not in cl:
                cl.append(lk)
        carriers[pname] = tuple(cl)

    driver = _driver(ctx, _table(ctx, data, "driver"), lnames, frames[0].name, pins, sliders, links)
    reference = _reference(ctx, _table(ctx, data, "reference", required=False), lnames)
    drawing = copy.deepcopy(_table(ctx, data, "drawing", required=False))   # not shared with a caller's dict
    m = Mechanism(
        title=title, units=units,
        points=frozen_map({k: (float(v[0]), float(v[1])) for k, v in pts.items()}),
        links=tuple(links), pins=tuple(pins), sliders=tuple(sliders), contacts=tuple(contacts),
        slots=tuple(slots), driver=driver, reference=reference, drawing=frozen_map(drawing),
        carriers=frozen_map(carriers), source=ctx.file, point_order=tuple(pts),
        constructions=tuple(ctx.compass),
    )
    _check_range(ctx, m)
    _check_reference(ctx, m)
    _check_drawing(ctx, m)
    return m


def _check_drawing(ctx, m: Mechanism) -> None:
    """The [drawing] table checked on load, by the rules ``draw`` applies (velpoly.render.options, which
    imports matplotlib only to check a colour): a file ``solve`` accepts, ``draw`` accepts too."""
    if not m.drawing:
        return
    from .render.options import drawing_options
    try:
        drawing_options(m)
    except InputError as e:
        raise ctx.err(e.where, e.what, e.hint) from None


# Floating point holds about 1e+-308: the kinematics squares speeds and multiplies rates by lengths,
# so the sizes, speeds and accelerations a file may ask for are bounded well inside that range.
SIZE_RANGE = (1e-100, 1e100)    # the mechanism's size (its points' bounding-box diagonal), length units
MAX_SPEED = 1e100               # the driver's speeds: |omega| x size, |speed|
MAX_ACCEL = 1e200               # and accelerations: (omega^2 + |alpha|) x size, |accel|


def _check_size(ctx, pts: dict) -> None:
    """The mechanism's size (as Mechanism.size: its points' bounding-box diagonal) inside SIZE_RANGE."""
    size = _size(pts)
    if not SIZE_RANGE[0] <= size <= SIZE_RANGE[1]:
        raise ctx.err("points", f"the mechanism's size {_length(ctx, size)} is out of range "
                      f"({SIZE_RANGE[0]:g} to {SIZE_RANGE[1]:g})",
                      hint="the arithmetic would overflow or underflow: give the lengths in other units")


def _check_range(ctx, m: Mechanism) -> None:
    """The driver's motion inside the range the arithmetic holds (the size is checked with the
    points): else speeds or accelerations would overflow or vanish (an input error, never a wrong number)."""
    size = m.size
    d = m.driver
    if d.is_slider:
        speed, accel = abs(d.speed), abs(d.accel)
        checks = (("driver.speed", speed, MAX_SPEED, f"{d.speed:g}"), ("driver.accel", accel, MAX_ACCEL, f"{d.accel:g}"))
    else:
        speed, accel = abs(d.omega) * size, (d.omega * d.omega + abs(d.alpha)) * size
        checks = (("driver.omega", speed, MAX_SPEED, f"{d.omega:g} rad/s"),
                  ("driver.alpha" if abs(d.alpha) > d.omega * d.omega else "driver.omega", accel, MAX_ACCEL,
                   f"{d.alpha:g} rad/s^2" if abs(d.alpha) > d.omega * d.omega else f"{d.omega:g} rad/s"))
    unit = m.units or "length units"
    for where, value, limit, shown in checks:
        if not value <= limit:
            what, per = ("speeds", "/s") if limit == MAX_SPEED else ("accelerations", "/s^2")
            reach = f"{value:.3g}" if math.isfinite(value) else "beyond 1e+308"
            raise ctx.err(where, f"{shown} is too large: {what} of {reach} {unit}{per} (at most {limit:g})",
                          hint="check the driver's value and its unit (omega in rad/s or rpm), and give the "
                               "lengths in units that keep the numbers within range")


def _slot_ends(ctx, where, v, pin, slot, angle, pts, listed, owned, point_ref):
    """A straight slot's ``ends = ["S1", "S2"]``: two points of the slot link (or listed in no link:
    the slot link's), apart along the slot, with the pin between them at the reference pose."""
    if not isinstance(v, list) or len(v) != 2:
        raise ctx.err(where, "give the slot's ends as two points", hint='ends = ["S1", "S2"]: two points of '
                      f"link {slot!r} at the ends of the slot")
    if angle is None:
        raise ctx.err(where, "only a straight slot has ends", hint="give the slot's path by angle = deg, "
                      "or leave out 'ends' (a circular slot is unbounded)")
    names = tuple(point_ref(f"{where}[{i}]", x) for i, x in enumerate(v))
    for i, n in enumerate(names):
        if n not in listed:
            owned.setdefault(n, []).append(slot)
        elif slot not in listed[n]:
            raise ctx.err(f"{where}[{i}]", f"the end {n!r} is not a point of the slot's link {slot!r}",
                          hint=f"a slot's ends are cut in its link: list {n!r} in links.{slot}, or in no link")
    e = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    s1, s2, p = (np.asarray(pts[n], float) for n in (*names, pin))
    length = float(np.dot(s2 - s1, e))
    size = max(float(np.ptp(np.array(list(pts.values()), float), axis=0).max()), 1e-300)
    if abs(length) <= 1e-9 * size:
        raise ctx.err(where, f"the ends {names[0]!r} and {names[1]!r} are not apart along the slot",
                      hint="the ends bound the slot along its path: two points at either end of it")
    t = float(np.dot(p - s1, e)) / length
    if not -1e-9 <= t <= 1 + 1e-9:
        raise ctx.err(where, f"the pin {pin!r} is not between the ends {names[0]!r} and {names[1]!r} of the slot "
                      f"in the drawn pose (it is {abs(min(t, 1 - t)) * abs(length):.6g} beyond "
                      f"{names[0] if t < 0 else names[1]!r})",
                      hint="draw the pin inside its slot, or give the slot's true ends")
    return names


def _contact_centres(ctx, where, cs, owners, p, pts, listed, owned, point_ref, size):
    """A contact's centres of curvature, checked: each a point of its link (or "flat")."""
    w = where + ".centres"
    if not isinstance(cs, list) or len(cs) != 2:
        raise ctx.err(w, f"expected [\"Ca\", \"Cb\"], got {_show(cs)}",
                      hint="the centres of curvature of the profiles of links a and b, \"flat\" for a straight one")
    cc = []
    for cn, owner in zip(cs, owners):
        if cn == "flat":
            cc.append(None)
            continue
        cn = point_ref(w, cn)
        if cn == p or np.hypot(*(pts[cn] - pts[p])) == 0:
            raise ctx.err(w, f"centre {cn!r} is at the contact point: the profile has no radius",
                          hint="the centre of curvature is the centre of the profile's arc at the contact")
        cc.append(cn)
        if cn not in listed:
            owned.setdefault(cn, []).append(owner)
        elif owner not in listed[cn]:
            raise ctx.err(w, f"centre {cn!r} is not a point of link {owner!r}",
                          hint=f"the centres are in the order of links: list {cn!r} in links.{owner}")
    if cc[0] is None and cc[1] is None:
        raise ctx.err(w, "both profiles are flat", hint="a flat on a flat is a slider: use [[sliders]]")
    if cc[0] is not None and cc[1] is not None:
        A, B, P = pts[cc[0]], pts[cc[1]], pts[p]
        d = B - A
        if np.hypot(*d) == 0:
            raise ctx.err(w, "the two centres of curvature coincide",
                          hint="concentric profiles touch everywhere or nowhere")
        off = abs(d[0] * (P - A)[1] - d[1] * (P - A)[0]) / np.hypot(*d)
        if off > 1e-6 * size:
            raise ctx.err(where + ".point", f"the contact point is off the line of centres by {_length(ctx, off)}",
                          hint="profiles touch on their common normal, the line through both centres "
                               "of curvature: put the point there")
    return tuple(cc)


def ctx_link(links, name) -> Link:
    return next(k for k in links if k.name == name)


def _size(pts) -> float:
    p = np.array(list(pts.values()))
    d = float(np.hypot(*(p.max(axis=0) - p.min(axis=0)))) if len(p) else 1.0
    return d or 1.0


_OMEGA_HINT = ('a number in rad/s, or "NUMBER UNIT [SENSE]" with UNIT rad/s, rpm, deg/s or rev/s and SENSE '
               'cw, ccw, clockwise or anticlockwise (e.g. "60 rpm", "10 rad/s clockwise")')


_ALPHA_HINT = 'a number in rad/s^2, or "NUMBER rad/s^2 [SENSE]" (SENSE cw, ccw, clockwise or anticlockwise)'


def _driver(ctx, d, lnames, frame, pins, sliders, links) -> Driver:
    _keys(ctx, "driver", d, ("link", "omega", "alpha", "angle", "slider", "speed", "accel"))
    if ("link" in d) == ("slider" in d):
        raise ctx.err("driver", "give exactly one of 'link' (a crank) and 'slider' (a slider's point)" +
                      (" (both are given)" if "link" in d else ""),
                      hint='link = "2" with omega, or slider = "F" with speed')
    if "slider" in d:
        p = _name(ctx, "driver.slider", d["slider"], "a point's name")
        sl = [s for s in sliders if s.point == p]
        if not sl:
            raise ctx.err("driver.slider", f"no slider has the point {p!r}",
                          hint="name the point of a [[sliders]] entry" +
                          (": " + ", ".join(s.point for s in sliders) if sliders else " (there are none)"))
        for k in ("omega", "alpha", "angle"):
            if k in d:
                raise ctx.err(f"driver.{k}", f"'{k}' belongs to a crank driver",
                              hint="a slider driver has speed and accel (along its path)")
        if "speed" not in d:
            raise ctx.err("driver", "a slider driver needs 'speed'", hint="speed = v, in length units per second")
        return Driver(slider=p, speed=_num(ctx, "driver.speed", d["speed"]),
                      accel=_num(ctx, "driver.accel", d.get("accel", 0.0)))
    link = _name(ctx, "driver.link", d["link"], "a link's name")
    if link not in lnames:
        raise ctx.err("driver.link", f"unknown link {link!r}", hint="links: " + ", ".join(lnames))
    if link == frame:
        raise ctx.err("driver.link", f"the driver cannot be the frame {frame!r}",
                      hint="drive a crank pinned to the frame")
    if not any(set(p.links) == {link, frame} for p in pins):
        raise ctx.err("driver.link", f"link {link!r} is not pinned to the frame {frame!r}",
                      hint="a crank driver turns about a pin on the frame (a point listed in both); "
                           "for a slider give slider = \"P\"")
    for k in ("speed", "accel"):
        if k in d:
            raise ctx.err(f"driver.{k}", f"'{k}' belongs to a slider driver", hint="a crank has omega and alpha")
    if "omega" not in d:
        raise ctx.err("driver", "missing 'omega'", hint='e.g. omega = "60 rpm" or omega = 10 (rad/s)')
    try:
        omega = parse_omega(d["omega"])
    except ValueError:
        raise ctx.err("driver.omega", f"cannot read {_show(d['omega'])} as an angular velocity",
                      hint=_OMEGA_HINT) from None
    if not math.isfinite(omega):
        raise ctx.err("driver.omega", f"must be finite, got {_show(omega)}", hint=_OMEGA_HINT)
    try:
        alpha = parse_alpha(d.get("alpha", 0.0))
    except ValueError:
        raise ctx.err("driver.alpha", f"cannot read {_show(d['alpha'])} as an angular acceleration",
                      hint=_ALPHA_HINT) from None
    if not math.isfinite(alpha):
        raise ctx.err("driver.alpha", f"must be finite, got {_show(alpha)}",
                      hint=_ALPHA_HINT)
    angle = _num(ctx, "driver.angle", d["angle"]) if "angle" in d else None
    return Driver(link=link, omega=omega, alpha=alpha, angle=angle)


def _reference(ctx, r, lnames) -> Reference:
    if not r:
        return Reference()
    _keys(ctx, "reference", r, ("source", "omega", "alpha", "speed", "velocity", "acceleration", "values", "note"))
    src = r.get("source", "")
    if not isinstance(src, str):
        raise ctx.err("reference.source", f"expected a string, got {_show(src)}", hint='source = "Example 3.6"')
    out = {}
    for key in ("omega", "alpha", "speed", "velocity", "acceleration", "values", "note"):
        t = r.get(key, {})
        if not isinstance(t, dict):
            raise ctx.err(f"reference.{key}", f"expected a table, got {_show(t)}",
                          hint=f'{key} = {{ "3" = 6.702 }}' if key in ("omega", "alpha") else
                          f"{key} = {{ KEY = VALUE, ... }}")
        for k, v in t.items():
            w = f"reference.{key}.{k}"
            if key in ("omega", "alpha"):
                if str(k) not in lnames:
                    raise ctx.err(w, f"unknown link {_key(k)}", hint="links: " + ", ".join(lnames))
                _num(ctx, w, v)
            elif key == "speed":
                _num(ctx, w, v)
            elif key in ("velocity", "acceleration", "values"):   # [magnitude, direction] or a bare magnitude
                if isinstance(v, list):
                    if len(v) != 2:
                        raise ctx.err(w, f"expected a magnitude or [magnitude, direction], got a list of {len(v)}",
                                      hint="a vector is [magnitude, direction in degrees], e.g. [435.2, 21.7]")
                    _num(ctx, w, v[0]), _num(ctx, w, v[1])
                else:
                    _num(ctx, w, v)
            elif not isinstance(v, str):
                raise ctx.err(w, f"expected a string saying what is wrong with the printed value, got {_show(v)}",
                              hint='note = { V_B = "misprint: ..." }')
        # vectors become tuples: the model shares no list with the caller's dict (it is immutable)
        out[key] = frozen_map({str(k): tuple(v) if isinstance(v, list) else v for k, v in t.items()})
    return Reference(source=src, **out)


def _check_reference(ctx, m: Mechanism) -> None:
    """Every reference key names something of this mechanism (FORMAT.md section 1)."""
    from .motion import point_keys
    from .reference import parse_key, validate_reference
    try:
        validate_reference(m, ctx)
    except InputError as e:
        raise ctx.err(e.where, e.what, e.hint) from None
    moving = {}
    for key, p, lk in point_keys(m):
        if key != p:
            moving.setdefault(p, []).append(lk)
    ref = m.reference
    for table, prefix in (("speed", "V_"), ("velocity", "V_"), ("acceleration", "A_"), ("values", "")):
        for k in getattr(ref, table):
            q = parse_key(m, prefix + k)
            w = f"reference.{table}.{k}"
            if q is None:
                raise ctx.err(w, f"unknown point {k!r}", hint="a point's name, or point and link (B3 or B@3): "
                              + ", ".join(m.point_order[:20]))
            for p, lk in (q.refs if q.kind in ("V", "A") else ()):
                if lk is None and p in moving:
                    raise ctx.err(w, f"point {p!r} moves differently on links {', '.join(moving[p])}: say which",
                                  hint=f"e.g. {prefix or (q.kind + '_')}{p}{moving[p][0]} or {p}@{moving[p][0]}")
