"""Mechanism files (TOML, FORMAT.md section 1) to :class:`~velpoly.model.Mechanism`.

Every check of the input lives here. Each failure raises
:class:`~velpoly.errors.InputError` naming the file, the entry
(``points.C``, ``driver.omega``) and what is wrong, with a hint.
"""
from __future__ import annotations

import math
import os
import re
import tomllib
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from .errors import InputError, VelpolyError
from .model import (Contact, Driver, Link, Mechanism, Pin, Reference, Slider, Slot,
                    frozen_map)
from .pose import circle_circle, circle_line

__all__ = ["load", "parse_omega", "parse_alpha"]

TOP_KEYS = ("format", "title", "units", "points", "links", "sliders", "contacts", "slots",
            "driver", "reference", "drawing")


class _Ctx:
    """The file being read: its name and text (to find line numbers)."""

    def __init__(self, file: str, text: str | None):
        self.file = file
        self.text = text
        self.units = ""
        self.point_names: tuple[str, ...] = ()   # every name in [points], in file order

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
        if k[:1] in "\"'":
            k = k[1:-1]
        out.append(k)
    return out


def _where_parts(where: str) -> list:
    """``sliders[0].guide`` -> ['sliders', 0, 'guide']."""
    out: list = []
    for piece in where.split("."):
        m = re.fullmatch(r"(.*?)((?:\[\d+\])*)", piece)
        if m.group(1):
            out.append(m.group(1))
        out.extend(int(i) for i in re.findall(r"\[(\d+)\]", m.group(2)))
    return out


def _scan_brackets(line: str, depth: int, in_ml: str | None) -> tuple[int, str | None]:
    """Bracket depth and open multi-line string after ``line`` (strings and comments skipped)."""
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
                if k == len(path) and k > best_len:
                    best, best_len = no, k
            if h:
                continue
        depth, in_ml = _scan_brackets(line, depth, in_ml)
    return best


# -- scalar parsing --------------------------------------------------------------------
def _num(ctx: _Ctx, where: str, v: Any, positive: bool = False, allow_zero: bool = True) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ctx.err(where, f"expected a number, got {_show(v)}")
    x = float(v)
    if not math.isfinite(x):
        raise ctx.err(where, f"expected a finite number, got {x}")
    if positive and (x < 0 or (x == 0 and not allow_zero)):
        raise ctx.err(where, f"must be positive, got {_show(v)}", hint="lengths are positive; "
                      "give the direction with an angle")
    return x


def _show(v: Any) -> str:
    if isinstance(v, str):
        return repr(v)
    if isinstance(v, dict):
        return "a table"
    if isinstance(v, list):
        return "a list"
    return repr(v)


def _name(ctx: _Ctx, where: str, v: Any) -> str:
    if isinstance(v, bool) or not isinstance(v, (str, int)):
        raise ctx.err(where, f"expected a name, got {_show(v)}")
    return str(v)


_OMEGA_UNITS = {
    "rad/s": 1.0, "rpm": 2 * math.pi / 60, "r/min": 2 * math.pi / 60, "rev/min": 2 * math.pi / 60,
    "deg/s": math.pi / 180, "rev/s": 2 * math.pi, "rps": 2 * math.pi, "hz": 2 * math.pi,
}
_ALPHA_UNITS = {"rad/s^2": 1.0, "rad/s2": 1.0, "rad/s²": 1.0, "rad/s/s": 1.0,
                "deg/s^2": math.pi / 180, "deg/s2": math.pi / 180}


def _parse_rate(text: str, units: Mapping[str, float]) -> float:
    m = re.fullmatch(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S+)\s*(cw|ccw)?\s*",
                     text, flags=re.IGNORECASE)
    if not m:
        raise ValueError(text)
    value, unit, sense = m.groups()
    unit = unit.lower()
    if unit not in units:
        raise ValueError(text)
    x = float(value) * units[unit]
    if sense and sense.lower() == "cw":
        x = -x
    return x


def parse_omega(v: Any) -> float:
    """An angular velocity in rad/s (ccw positive) from a number or ``"NUMBER UNIT [cw|ccw]"``.

    >>> round(parse_omega("60 rpm"), 6)
    6.283185
    >>> parse_omega("-10 rad/s cw")
    10.0
    """
    if isinstance(v, bool):
        raise ValueError(v)
    if isinstance(v, (int, float)):
        return float(v)
    if isinstance(v, str):
        return _parse_rate(v, _OMEGA_UNITS)
    raise ValueError(v)


def parse_alpha(v: Any) -> float:
    """An angular acceleration in rad/s^2 from a number or ``"NUMBER rad/s^2 [cw|ccw]"``."""
    if isinstance(v, bool):
        raise ValueError(v)
    if isinstance(v, (int, float)):
        return float(v)
    if isinstance(v, str):
        return _parse_rate(v, _ALPHA_UNITS)
    raise ValueError(v)


# -- points -------------------------------------------------------------------------------
def _xy(ctx, where, v) -> np.ndarray:
    if not isinstance(v, list) or len(v) != 2:
        raise ctx.err(where, f"expected [x, y], got {_show(v)}")
    return np.array([_num(ctx, where, v[0]), _num(ctx, where, v[1])])


def _ref(ctx, where, name, pts) -> np.ndarray:
    name = _name(ctx, where, name)
    if name not in pts:
        raise ctx.err(where, f"refers to point {name!r}, which is not defined before it",
                      hint="points are evaluated in file order: define it earlier")
    return pts[name]


def _point_or_xy(ctx, where, v, pts) -> np.ndarray:
    if isinstance(v, list):
        return _xy(ctx, where, v)
    return _ref(ctx, where, v, pts)


def _keys(ctx, where, d: dict, allowed: tuple[str, ...]):
    for k in d:
        if k not in allowed:
            raise ctx.err(f"{where}.{k}" if where else k, f"unknown key {k!r}",
                          hint="valid keys: " + ", ".join(allowed))


def _construct(ctx: _Ctx, name: str, spec: Any, pts: dict) -> np.ndarray:
    where = f"points.{name}"
    if isinstance(spec, list):
        return _xy(ctx, where, spec)
    if not isinstance(spec, dict):
        raise ctx.err(where, f"expected [x, y] or a construction table, got {_show(spec)}")
    if "circles" in spec:
        _keys(ctx, where, spec, ("circles", "near", "side"))
        cs = spec["circles"]
        if not (isinstance(cs, list) and len(cs) == 2 and all(isinstance(c, list) and len(c) == 2 for c in cs)):
            raise ctx.err(where + ".circles", "expected [[\"P\", r1], [\"Q\", r2]]")
        p = _ref(ctx, where + ".circles", cs[0][0], pts)
        q = _ref(ctx, where + ".circles", cs[1][0], pts)
        r1 = _num(ctx, where + ".circles", cs[0][1], positive=True, allow_zero=False)
        r2 = _num(ctx, where + ".circles", cs[1][1], positive=True, allow_zero=False)
        if ("near" in spec) == ("side" in spec):
            raise ctx.err(where, "a two-circle construction needs exactly one of 'near' and 'side'",
                          hint='add near = [x, y] (a sketch point) or side = "left"')
        left, right, gap = circle_circle(p, r1, q, r2)
        if np.allclose(p, q):
            raise ctx.err(where, f"the circles' centres {cs[0][0]!r} and {cs[1][0]!r} coincide")
        if gap > 1e-9 * max(r1, r2):
            raise ctx.err(where, f"circles do not meet (gap {gap:.6g} {ctx_units(ctx)})".replace(" )", ")"),
                          hint="check the lengths: the circles must overlap")
        if "side" in spec:
            side = spec["side"]
            if side not in ("left", "right"):
                raise ctx.err(where + ".side", f"expected \"left\" or \"right\", got {_show(side)}")
            return left if side == "left" else right
        return _pick(ctx, where, (left, right), spec["near"], pts)
    if "circle" in spec:
        _keys(ctx, where, spec, ("circle", "line", "near"))
        c = spec["circle"]
        if not (isinstance(c, list) and len(c) == 2):
            raise ctx.err(where + ".circle", "expected [\"P\", r]")
        centre = _ref(ctx, where + ".circle", c[0], pts)
        r = _num(ctx, where + ".circle", c[1], positive=True, allow_zero=False)
        if "line" not in spec:
            raise ctx.err(where, "a circle-line construction needs 'line'")
        through, ang = _line(ctx, where + ".line", spec["line"], pts)
        if "near" not in spec:
            raise ctx.err(where, "a circle-line construction needs 'near'", hint="add near = [x, y]")
        a, b, gap = circle_line(centre, r, through, ang)
        if gap > 1e-9 * r:
            raise ctx.err(where, f"the line misses the circle (gap {gap:.6g} {ctx_units(ctx)})".replace(" )", ")"),
                          hint="check the radius and the line")
        return _pick(ctx, where, (a, b), spec["near"], pts)
    if "from" in spec or "to" in spec:
        key = "from" if "from" in spec else "to"
        if "from" in spec and "to" in spec:
            raise ctx.err(where, "give one of 'from' and 'to', not both")
        if "along" in spec:
            _keys(ctx, where, spec, (key, "length", "along", "turn"))
        else:
            _keys(ctx, where, spec, (key, "length", "angle"))
        base = _ref(ctx, f"{where}.{key}", spec[key], pts)
        if "length" not in spec:
            raise ctx.err(where, "missing 'length'")
        L = _num(ctx, where + ".length", spec["length"], positive=True)
        if "along" in spec:
            al = spec["along"]
            if not (isinstance(al, list) and len(al) == 2):
                raise ctx.err(where + ".along", "expected [\"Q\", \"R\"]")
            q = _ref(ctx, where + ".along", al[0], pts)
            r = _ref(ctx, where + ".along", al[1], pts)
            d = r - q
            if np.hypot(*d) == 0:
                raise ctx.err(where + ".along", f"{al[0]!r} and {al[1]!r} coincide: no direction")
            ang = math.degrees(math.atan2(d[1], d[0])) + _num(ctx, where + ".turn", spec.get("turn", 0.0))
        else:
            if "angle" not in spec:
                raise ctx.err(where, "missing 'angle' (or 'along')")
            ang = _num(ctx, where + ".angle", spec["angle"])
        v = L * np.array([math.cos(math.radians(ang)), math.sin(math.radians(ang))])
        return base + v if key == "from" else base - v
    raise ctx.err(where, "unknown construction", hint="use [x, y], {from, length, angle}, {to, ...}, "
                  "{from, length, along, turn}, {circles, near|side} or {circle, line, near}")


def ctx_units(ctx) -> str:
    return getattr(ctx, "units", "")


def _line(ctx, where, spec, pts):
    if isinstance(spec, list):
        if len(spec) != 2:
            raise ctx.err(where, "expected [\"Q\", \"R\"] or {through, angle}")
        q = _ref(ctx, where, spec[0], pts)
        r = _ref(ctx, where, spec[1], pts)
        d = r - q
        if np.hypot(*d) == 0:
            raise ctx.err(where, "the line's two points coincide")
        return q, math.degrees(math.atan2(d[1], d[0]))
    if isinstance(spec, dict):
        _keys(ctx, where, spec, ("through", "angle"))
        if "through" not in spec or "angle" not in spec:
            raise ctx.err(where, "a line needs 'through' and 'angle'")
        return _point_or_xy(ctx, where + ".through", spec["through"], pts), _num(ctx, where + ".angle", spec["angle"])
    raise ctx.err(where, f"expected a line, got {_show(spec)}")


def _pick(ctx, where, cands, near, pts) -> np.ndarray:
    if isinstance(near, dict):
        _keys(ctx, where + ".near", near, ("from", "angle"))
        if "from" not in near or "angle" not in near:
            raise ctx.err(where + ".near", "expected {from = \"P\", angle = deg}")
        base = _ref(ctx, where + ".near", near["from"], pts)
        ang = math.radians(_num(ctx, where + ".near.angle", near["angle"]))
        e = np.array([math.cos(ang), math.sin(ang)])

        def score(c):
            d = c - base
            n = np.hypot(*d)
            return -np.dot(d, e) / n if n > 0 else 2.0
        return min(cands, key=score)
    target = _point_or_xy(ctx, where + ".near", near, pts)
    return min(cands, key=lambda c: float(np.hypot(*(c - target))))


# -- the whole file -----------------------------------------------------------------------------
def load(source, *, name: str | None = None) -> Mechanism:
    """Read a mechanism from a file path, TOML text, or a dict.

    Raises :class:`~velpoly.errors.InputError` (a :class:`VelpolyError`) naming
    the file, the entry and what is wrong.
    """
    text = None
    if isinstance(source, dict):
        data, file = source, name or "<dict>"
    elif isinstance(source, os.PathLike) or (isinstance(source, str) and "\n" not in source
                                            and "=" not in source):
        path = Path(source)
        file = name or str(source)
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise InputError("no such file", file=str(source), hint="check the path") from None
        except IsADirectoryError:
            raise InputError("is a directory, not a mechanism file", file=str(source)) from None
        except UnicodeDecodeError:
            raise InputError("not a text (UTF-8) file", file=str(source)) from None
        except OSError as e:
            raise InputError(f"cannot read: {e.strerror}", file=str(source)) from None
        data = _parse_toml(text, file)
        if name is None:
            name = path.name
    elif isinstance(source, str):
        text, file = source, name or "<text>"
        data = _parse_toml(text, file)
    else:
        raise InputError(f"cannot load a {type(source).__name__}: give a path, TOML text or a dict")
    ctx = _Ctx(file, text)
    try:
        return _build(ctx, data, default_title=name or file)
    except VelpolyError as e:
        raise e.with_file(file)
    except (TypeError, ValueError, KeyError, IndexError, AttributeError) as e:  # pragma: no cover
        raise InputError(f"malformed entry ({type(e).__name__}: {e})", file=file) from None


def _parse_toml(text: str, file: str) -> dict:
    if not text.strip():
        raise InputError("the file is empty", file=file, hint="write a mechanism: see README")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"bad TOML: {e}", file=file, hint="check the syntax at that line") from None


def _table(ctx, data, key, required=True) -> dict:
    if key not in data:
        if required:
            raise ctx.err(key, f"missing table [{key}]")
        return {}
    v = data[key]
    if not isinstance(v, dict):
        raise ctx.err(key, f"expected a table [{key}], got {_show(v)}")
    return v


def _array_of_tables(ctx, data, key) -> list[dict]:
    v = data.get(key, [])
    if not isinstance(v, list) or not all(isinstance(x, dict) for x in v):
        raise ctx.err(key, f"expected [[{key}]] entries (an array of tables)")
    return v


def _build(ctx: _Ctx, data: dict, default_title: str) -> Mechanism:
    for k in data:
        if k not in TOP_KEYS:
            raise ctx.err(k, f"unknown key {k!r}", hint="valid keys: " + ", ".join(TOP_KEYS))
    fmt = data.get("format", 1)
    if fmt != 1 or isinstance(fmt, bool):
        raise ctx.err("format", f"unsupported format {fmt!r}", hint="this velpoly reads format = 1")
    title = data.get("title", default_title)
    if not isinstance(title, str):
        raise ctx.err("title", f"expected a string, got {_show(title)}")
    units = data.get("units", "m")
    if not isinstance(units, str):
        raise ctx.err("units", f"expected a string such as \"mm\", got {_show(units)}")
    ctx.units = units

    # points
    raw_points = _table(ctx, data, "points")
    if not raw_points:
        raise ctx.err("points", "no points", hint="define the mechanism's points in [points]")
    pts: dict[str, np.ndarray] = {}
    for pname, spec in raw_points.items():
        if "@" in pname:
            raise ctx.err(f"points.{pname}", "a point's name must not contain '@'")
        pts[pname] = _construct(ctx, pname, spec, pts)
        if not np.all(np.isfinite(pts[pname])):
            raise ctx.err(f"points.{pname}", "the construction gives no finite position")

    # links
    raw_links = _table(ctx, data, "links")
    links: list[Link] = []
    for lname, spec in raw_links.items():
        where = f"links.{lname}"
        if "-" in lname:
            raise ctx.err(where, "a link's name must not contain '-' (pole keys are \"i-j\")")
        if lname in pts:
            raise ctx.err(where, f"{lname!r} names both a point and a link",
                          hint="give links numbers and points letters, as textbooks do")
        if not isinstance(spec, dict):
            raise ctx.err(where, f"expected {{ points = [...] }}, got {_show(spec)}")
        _keys(ctx, where, spec, ("points", "frame"))
        lp = spec.get("points")
        if not isinstance(lp, list) or not lp:
            raise ctx.err(where + ".points", "expected a non-empty list of point names")
        names = []
        for p in lp:
            p = _name(ctx, where + ".points", p)
            if p not in pts:
                raise ctx.err(where + ".points", f"unknown point {p!r}", hint="define it in [points]")
            if p in names:
                raise ctx.err(where + ".points", f"point {p!r} is listed twice")
            names.append(p)
        frame = spec.get("frame", False)
        if not isinstance(frame, bool):
            raise ctx.err(where + ".frame", f"expected true or false, got {_show(frame)}")
        links.append(Link(lname, tuple(names), frame))
    frames = [k for k in links if k.frame]
    if len(frames) != 1:
        raise ctx.err("links", "no link is the frame" if not frames else
                      "two or more links are the frame: " + ", ".join(k.name for k in frames),
                      hint="mark exactly one link with frame = true")
    lnames = {k.name for k in links}
    listed: dict[str, list[str]] = {}
    for k in links:
        for p in k.points:
            listed.setdefault(p, []).append(k.name)

    def link_ref(where, v):
        n = _name(ctx, where, v)
        if n not in lnames:
            raise ctx.err(where, f"unknown link {n!r}", hint="links: " + ", ".join(sorted(lnames)))
        return n

    def point_ref(where, v):
        n = _name(ctx, where, v)
        if n not in pts:
            raise ctx.err(where, f"unknown point {n!r}", hint="define it in [points]")
        return n

    owned: dict[str, list[str]] = {}   # points carried without being listed
    coincident: set[tuple[str, str]] = set()  # (point, link): carried as a coincident point, no pin

    # sliders
    sliders = []
    for i, s in enumerate(_array_of_tables(ctx, data, "sliders")):
        where = f"sliders[{i}]"
        _keys(ctx, where, s, ("block", "guide", "point", "angle", "centre"))
        for req in ("block", "guide", "point"):
            if req not in s:
                raise ctx.err(where, f"missing '{req}'")
        b, g = link_ref(where + ".block", s["block"]), link_ref(where + ".guide", s["guide"])
        p = point_ref(where + ".point", s["point"])
        if b == g:
            raise ctx.err(where, "block and guide are the same link")
        if p not in ctx_link(links, b).points:
            raise ctx.err(where + ".point", f"point {p!r} is not a point of the block {b!r}",
                          hint=f"list {p!r} in links.{b}")
        if ("angle" in s) == ("centre" in s):
            raise ctx.err(where, "give the path as exactly one of 'angle' and 'centre'")
        ang = _num(ctx, where + ".angle", s["angle"]) if "angle" in s else None
        cen = point_ref(where + ".centre", s["centre"]) if "centre" in s else None
        if cen is not None:
            if np.hypot(*(pts[p] - pts[cen])) == 0:
                raise ctx.err(where + ".centre", "the path's centre is the slider's point")
            if cen not in listed:
                owned.setdefault(cen, []).append(g)
        if p in ctx_link(links, g).points:
            coincident.add((p, g))
        sliders.append(Slider(b, g, p, ang, cen))

    # slots
    slots = []
    for i, s in enumerate(_array_of_tables(ctx, data, "slots")):
        where = f"slots[{i}]"
        _keys(ctx, where, s, ("pin", "link", "slot", "angle", "centre"))
        for req in ("pin", "link", "slot"):
            if req not in s:
                raise ctx.err(where, f"missing '{req}'")
        p = point_ref(where + ".pin", s["pin"])
        l, sk = link_ref(where + ".link", s["link"]), link_ref(where + ".slot", s["slot"])
        if l == sk:
            raise ctx.err(where, "the pin's link and the slot's link are the same")
        if p not in ctx_link(links, l).points:
            raise ctx.err(where + ".pin", f"point {p!r} is not a point of link {l!r}", hint=f"list it in links.{l}")
        if ("angle" in s) == ("centre" in s):
            raise ctx.err(where, "give the slot's path as exactly one of 'angle' and 'centre'")
        ang = _num(ctx, where + ".angle", s["angle"]) if "angle" in s else None
        cen = point_ref(where + ".centre", s["centre"]) if "centre" in s else None
        if cen is not None:
            if np.hypot(*(pts[p] - pts[cen])) == 0:
                raise ctx.err(where + ".centre", "the slot's centre is the pin")
            if cen not in listed:
                owned.setdefault(cen, []).append(sk)
        if p in ctx_link(links, sk).points:
            coincident.add((p, sk))
        slots.append(Slot(p, l, sk, ang, cen))

    # contacts
    contacts = []
    size = _size(pts)
    for i, c in enumerate(_array_of_tables(ctx, data, "contacts")):
        where = f"contacts[{i}]"
        _keys(ctx, where, c, ("links", "point", "kind", "slip", "centres", "normal"))
        if "links" not in c or not isinstance(c["links"], list) or len(c["links"]) != 2:
            raise ctx.err(where + ".links", "expected links = [\"a\", \"b\"]")
        a, b = link_ref(where + ".links", c["links"][0]), link_ref(where + ".links", c["links"][1])
        if a == b:
            raise ctx.err(where + ".links", "a contact needs two different links")
        if "point" not in c:
            raise ctx.err(where, "missing 'point'")
        p = point_ref(where + ".point", c["point"])
        kind = c.get("kind")
        if kind not in ("rolling", "sliding"):
            raise ctx.err(where + ".kind", f"expected \"rolling\" or \"sliding\", got {_show(kind)}")
        slip = None
        if "slip" in c:
            if kind != "sliding":
                raise ctx.err(where + ".slip", "a prescribed slip needs kind = \"sliding\"")
            slip = _num(ctx, where + ".slip", c["slip"])
        if ("centres" in c) == ("normal" in c):
            raise ctx.err(where, "give exactly one of 'centres' and 'normal'",
                          hint="centres = [\"Ca\", \"Cb\"] (\"flat\" for a straight profile), or normal = deg")
        centres = None
        normal = None
        if "centres" in c:
            cs = c["centres"]
            if not isinstance(cs, list) or len(cs) != 2:
                raise ctx.err(where + ".centres", "expected [\"Ca\", \"Cb\"]")
            cc = []
            for j, (cn, owner) in enumerate(zip(cs, (a, b))):
                if cn == "flat":
                    cc.append(None)
                    continue
                cn = point_ref(where + ".centres", cn)
                if cn == p:
                    raise ctx.err(where + ".centres", f"centre {cn!r} is the contact point itself")
                cc.append(cn)
                if cn not in listed:
                    owned.setdefault(cn, []).append(owner)
                elif owner not in listed[cn]:
                    raise ctx.err(where + ".centres", f"centre {cn!r} is not a point of link {owner!r}",
                                  hint=f"the centres are in the order of links: list {cn!r} in links.{owner}")
            if cc[0] is None and cc[1] is None:
                raise ctx.err(where + ".centres", "both profiles are flat", hint="use a slider for a flat on a flat")
            if cc[0] is not None and cc[1] is not None:
                A, B, P = pts[cc[0]], pts[cc[1]], pts[p]
                d = B - A
                if np.hypot(*d) == 0:
                    raise ctx.err(where + ".centres", "the two centres of curvature coincide")
                off = abs(d[0] * (P - A)[1] - d[1] * (P - A)[0]) / np.hypot(*d)
                if off > 1e-6 * size:
                    raise ctx.err(where + ".point", f"the contact point is off the line of centres by "
                                  f"{off:.6g} {units}".rstrip(), hint="the contact point lies on the common normal, "
                                  "the line through both centres of curvature")
            centres = tuple(cc)
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
    reference = _reference(ctx, _table(ctx, data, "reference", required=False), lnames, pts)
    drawing = _table(ctx, data, "drawing", required=False)
    m = Mechanism(
        title=title, units=units,
        points=frozen_map({k: (float(v[0]), float(v[1])) for k, v in pts.items()}),
        links=tuple(links), pins=tuple(pins), sliders=tuple(sliders), contacts=tuple(contacts),
        slots=tuple(slots), driver=driver, reference=reference, drawing=frozen_map(drawing),
        carriers=frozen_map(carriers), source=ctx.file, point_order=tuple(pts),
    )
    # a link needs two points to have a shape, unless it is a slider block or a wheel
    from .reference import validate_reference
    validate_reference(m, ctx)
    return m


def ctx_link(links, name) -> Link:
    return next(k for k in links if k.name == name)


def _size(pts) -> float:
    p = np.array(list(pts.values()))
    d = float(np.hypot(*(p.max(axis=0) - p.min(axis=0)))) if len(p) else 1.0
    return d or 1.0


def _driver(ctx, d, lnames, frame, pins, sliders, links) -> Driver:
    if not d:
        raise ctx.err("driver", "missing table [driver]", hint="e.g. [driver] link = \"2\", omega = \"10 rad/s\"")
    _keys(ctx, "driver", d, ("link", "omega", "alpha", "angle", "slider", "speed", "accel"))
    if ("link" in d) == ("slider" in d):
        raise ctx.err("driver", "give exactly one of 'link' (a crank) and 'slider' (a slider's point)")
    if "slider" in d:
        p = _name(ctx, "driver.slider", d["slider"])
        sl = [s for s in sliders if s.point == p]
        if not sl:
            raise ctx.err("driver.slider", f"no slider has the point {p!r}",
                          hint="name the point of a [[sliders]] entry")
        for k in ("omega", "alpha", "angle"):
            if k in d:
                raise ctx.err(f"driver.{k}", f"'{k}' belongs to a crank driver; a slider driver has speed and accel")
        if "speed" not in d:
            raise ctx.err("driver", "a slider driver needs 'speed'")
        return Driver(slider=p, speed=_num(ctx, "driver.speed", d["speed"]),
                      accel=_num(ctx, "driver.accel", d.get("accel", 0.0)))
    link = _name(ctx, "driver.link", d["link"])
    if link not in lnames:
        raise ctx.err("driver.link", f"unknown link {link!r}", hint="links: " + ", ".join(sorted(lnames)))
    if link == frame:
        raise ctx.err("driver.link", "the driver cannot be the frame")
    if not any(set(p.links) == {link, frame} for p in pins):
        raise ctx.err("driver.link", f"link {link!r} is not pinned to the frame {frame!r}",
                      hint="a crank driver turns about a pin on the frame; for a slider give slider = \"P\"")
    if "omega" not in d:
        raise ctx.err("driver", "missing 'omega'", hint='e.g. omega = "60 rpm" or omega = 10')
    for k in ("speed", "accel"):
        if k in d:
            raise ctx.err(f"driver.{k}", f"'{k}' belongs to a slider driver; a crank has omega and alpha")
    try:
        omega = parse_omega(d["omega"])
    except ValueError:
        raise ctx.err("driver.omega", f"cannot read {_show(d['omega'])} as an angular velocity",
                      hint='a number in rad/s, or "NUMBER UNIT [cw|ccw]" with UNIT rad/s, rpm, deg/s or rev/s') from None
    if not math.isfinite(omega):
        raise ctx.err("driver.omega", "must be finite")
    try:
        alpha = parse_alpha(d.get("alpha", 0.0))
    except ValueError:
        raise ctx.err("driver.alpha", f"cannot read {_show(d['alpha'])} as an angular acceleration",
                      hint='a number in rad/s^2, or "NUMBER rad/s^2 [cw|ccw]"') from None
    if not math.isfinite(alpha):
        raise ctx.err("driver.alpha", "must be finite")
    angle = _num(ctx, "driver.angle", d["angle"]) if "angle" in d else None
    return Driver(link=link, omega=omega, alpha=alpha, angle=angle)


def _reference(ctx, r, lnames, pts) -> Reference:
    if not r:
        return Reference()
    _keys(ctx, "reference", r, ("source", "omega", "alpha", "speed", "velocity", "acceleration", "values", "note"))
    src = r.get("source", "")
    if not isinstance(src, str):
        raise ctx.err("reference.source", "expected a string")
    out = {}
    for key in ("omega", "alpha", "speed", "velocity", "acceleration", "values", "note"):
        t = r.get(key, {})
        if not isinstance(t, dict):
            raise ctx.err(f"reference.{key}", f"expected a table, got {_show(t)}")
        for k, v in t.items():
            w = f"reference.{key}.{k}"
            if key in ("omega", "alpha"):
                if k not in lnames:
                    raise ctx.err(w, f"unknown link {k!r}")
                _num(ctx, w, v)
            elif key == "speed":
                _num(ctx, w, v)
            elif key in ("velocity", "acceleration"):
                if not (isinstance(v, list) and len(v) == 2):
                    raise ctx.err(w, "expected [magnitude, direction in degrees]")
                _num(ctx, w, v[0]), _num(ctx, w, v[1])
            elif key == "values":
                if isinstance(v, list):
                    if len(v) != 2:
                        raise ctx.err(w, "expected a magnitude or [magnitude, direction]")
                    _num(ctx, w, v[0]), _num(ctx, w, v[1])
                else:
                    _num(ctx, w, v)
            else:
                if not isinstance(v, str):
                    raise ctx.err(w, "expected a string saying what is wrong with the printed value")
        out[key] = frozen_map(t)
    return Reference(source=src, **out)
