"""The file being read, what its readers have read so far, and the checks every reader uses.

Each check raises :class:`~velpoly.errors.InputError` through :meth:`Ctx.err`, which names the file,
the entry (``points.C``, ``driver.omega``) with its line, what is wrong and a hint.
"""
from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

from ..arguments import rational_g
from ..errors import InputError, control_character
from ..model import Construction, Link
from .toml_positions import locate


TOO_LARGE_HINT = ("a float holds numbers up to about 1.8e308: check the number, and give the lengths in units "
                  "that keep the numbers within range")


class Ctx:
    """The file being read: its name and text (to find line numbers), and the parts read so far.

    The readers run in table order (points, links, sliders, slots, contacts, ...) and fill it in:
    ``pts`` (name -> position, in file order), ``links``, ``listed`` (point -> the links that list it),
    ``owned`` (point -> the links that carry it without listing it: a path's centre, a slot's end, a
    contact point) and ``coincident`` ((point, link) pairs carried as a coincident point, no pin).
    """

    def __init__(self, file: str, text: str | None):
        self.file = file
        self.text = text
        self.units = ""
        self.point_names: tuple[str, ...] = ()   # every name in [points], in file order
        self.compass: list[Construction] = []     # the compass constructions met, in file order
        self.pts: dict[str, np.ndarray] = {}
        self.size = 1.0
        self.links: list[Link] = []
        self.listed: dict[str, list[str]] = {}
        self.owned: dict[str, list[str]] = {}
        self.coincident: set[tuple[str, str]] = set()

    def err(self, where: str, what: str, hint: str = "") -> InputError:
        line = locate(self.text, where)
        if line:
            where = f"{where} (line {line})"
        return InputError(what, where=where, file=self.file, hint=hint)

    @property
    def link_names(self) -> list[str]:
        return [k.name for k in self.links]

    def link(self, name: str) -> Link:
        return next(k for k in self.links if k.name == name)

    def point_ref(self, where: str, v: Any) -> str:
        """The name of a point of [points]."""
        n = read_name(self, where, v, "a point's name")
        if n not in self.pts:
            raise self.err(where, f"unknown point {n!r}", hint="define it in [points]" + (
                ": " + ", ".join(self.pts) if len(self.pts) <= 20 else ""))
        return n

    def link_ref(self, where: str, v: Any) -> str:
        """The name of a link of [links]."""
        n = read_name(self, where, v, "a link's name")
        lnames = self.link_names
        if n not in lnames:
            raise self.err(where, f"unknown link {n!r}", hint="links: " + ", ".join(lnames))
        return n

    def require(self, where: str, entry: dict, keys: tuple[str, ...], example: str) -> None:
        for req in keys:
            if req not in entry:
                raise self.err(where, f"missing '{req}'", hint=example)

    def carry(self, point: str, link: str) -> bool:
        """Let ``link`` carry ``point`` (a path's centre, a slot's end, a centre of curvature): true if the
        point is listed in no link (it becomes the link's) or in this one; false if other links list it."""
        if point not in self.listed:
            self.owned.setdefault(point, []).append(link)
            return True
        return link in self.listed[point]


class Beyond(float):
    """A TOML float written finite whose value lies beyond any float (``1e400``): the infinity tomllib reads,
    keeping the ``text`` the file writes (:func:`toml_float`), so that a message says it is too large."""

    text: str


class Beneath(float):
    """A TOML float written nonzero whose value lies below any float (``1e-400``): the zero tomllib reads,
    keeping the ``text`` the file writes (:func:`toml_float`), so that a message says it is too small."""

    text: str


def toml_float(text: str) -> float:
    """A TOML float's value (tomllib's ``parse_float``): ``float(text)``, but a :class:`Beyond` where the text
    is a finite number too large for a float (``1e400``; ``inf`` is infinity as written), a :class:`Beneath`
    where it is a nonzero number too small for one (``1e-400``: it reads as 0)."""
    x = float(text)
    if math.isinf(x) and "inf" not in text:
        x = Beyond(x)
        x.text = text
    elif x == 0 and written_nonzero(text):
        x = Beneath(x)
        x.text = text
    return x


def written_nonzero(number: str) -> bool:
    """Whether a number's text (``1e-400``, ``0.0``, ``-0e5``) writes a value other than zero: a nonzero digit
    before its exponent."""
    return any(c in "123456789" for c in number.lower().split("e")[0])


def too_small(v: Any) -> str | None:
    """``v`` as written where it is a TOML float written nonzero but below any float (:class:`Beneath`), else
    None."""
    return v.text if isinstance(v, Beneath) else None


def too_large(v: Any) -> str | None:
    """``v`` as written where it is a number written finite but beyond any float: a TOML float
    (:class:`Beyond`) or an integer (``10**400``, TOML's or a dict's: ``float`` refuses it); else None."""
    if isinstance(v, Beyond):
        return v.text
    if isinstance(v, int) and not isinstance(v, bool):
        try:
            float(v)
        except OverflowError:
            return rational_g(v)
    return None


def show(v: Any) -> str:
    """A value as the user wrote it, on one short line: "40", true, a table, a list; a number beyond any float
    as written (``1e400``), or to six digits (``1e+400`` for 10**400)."""
    if too_large(v) or too_small(v):
        return too_large(v) or too_small(v)
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


def read_number(ctx: Ctx, where: str, v: Any, positive: bool = False, allow_zero: bool = True) -> float:
    """A finite number (``positive``: not below zero, and not zero unless ``allow_zero``)."""
    if isinstance(v, bool):
        raise ctx.err(where, f"expected a number, got {show(v)}", hint="true and false are not numbers")
    if isinstance(v, str):
        raise ctx.err(where, f"expected a number, got the string {show(v)}",
                      hint="write numbers without quotes")
    if not isinstance(v, (int, float)):
        raise ctx.err(where, f"expected a number, got {show(v)}", hint="write a single number here")
    if too_large(v):
        raise ctx.err(where, f"{show(v)} is too large: beyond any floating-point number", hint=TOO_LARGE_HINT)
    x = float(v)
    if not math.isfinite(x):
        raise ctx.err(where, f"expected a finite number, got {show(x)}", hint="nan and inf are not allowed")
    if positive and x == 0 and not allow_zero and too_small(v):   # (it is positive as written)
        raise ctx.err(where, f"{show(v)} is too small: below any floating-point number (it would read as 0)",
                      hint="give the lengths in units that keep the numbers within range")
    if positive and (x < 0 or (x == 0 and not allow_zero)):
        raise ctx.err(where, f"must be positive, got {show(v)}",
                      hint="lengths and radii are positive; give the direction with an angle")
    return x


def read_name(ctx: Ctx, where: str, v: Any, what: str = "a name") -> str:
    """A name: a string, or an integer (links are numbered: 3 reads as "3")."""
    if isinstance(v, bool) or not isinstance(v, (str, int)):
        raise ctx.err(where, f"expected {what}, got {show(v)}", hint='names are strings: "B", "3"')
    return str(v)


def check_keys(ctx: Ctx, where: str, d: dict, allowed: tuple[str, ...]) -> None:
    """Every key of the table ``d`` is one of ``allowed``."""
    for k in d:
        if k not in allowed:
            raise ctx.err(f"{where}.{k}" if where else str(k), f"unknown key {key_repr(k)}",
                          hint="valid keys: " + ", ".join(allowed))


def key_repr(k) -> str:
    return repr(k) if isinstance(k, str) else repr(str(k))


def length(ctx: Ctx, x: float) -> str:
    """A length with the file's unit: ``0.0125 m``."""
    return f"{x:.6g} {ctx.units}".rstrip()


def coincide(p, q) -> bool:
    """Two points at one place, to within rounding of their coordinates."""
    return float(np.hypot(*(q - p))) <= 1e-12 * max(float(np.abs(p).max()), float(np.abs(q).max()))


def direction(p, q) -> float:
    """The direction (deg, counter-clockwise from +x) from ``p`` to ``q``."""
    d = q - p
    return math.degrees(math.atan2(d[1], d[0]))


def table(ctx: Ctx, data: dict, key: str, required: bool = True) -> dict:
    """The top-level table ``[key]`` ({} if it is optional and absent)."""
    if key not in data:
        if required:
            raise ctx.err(key, f"missing table [{key}]", hint=TABLE_HINTS.get(key, ""))
        return {}
    v = data[key]
    if not isinstance(v, dict):
        raise ctx.err(key, f"expected a table [{key}], got {show(v)}", hint=TABLE_HINTS.get(key, ""))
    return v


TABLE_HINTS = {
    "points": "[points] names each point: A = [0, 0], B = { from = \"A\", length = 0.15, angle = 30 }",
    "links": "[links] lists each link's points: 2 = { points = [\"A\", \"B\"] }, one with frame = true",
    "driver": "[driver] link = \"2\" (a crank pinned to the frame), omega = \"60 rpm\"",
    "reference": "[reference] holds published answers: omega = { \"3\" = 6.70 }, values = { V_B = 602 }",
    "drawing": "[drawing] holds presentation options (see the README)",
}


def array_of_tables(ctx: Ctx, data: dict, key: str) -> list[dict]:
    """The ``[[key]]`` entries, each a table ([] if there are none)."""
    v = data.get(key, [])
    if not isinstance(v, list):
        raise ctx.err(key, f"expected [[{key}]] entries (an array of tables), got {show(v)}",
                      hint=f"write each entry under its own [[{key}]] header")
    for i, x in enumerate(v):
        if not isinstance(x, dict):
            raise ctx.err(f"{key}[{i}]", f"expected a table, got {show(x)}",
                          hint=f"write each entry under its own [[{key}]] header")
    return v


def named_entries(ctx: Ctx, table: str, raw: dict, kind: str) -> list[tuple[str, Any]]:
    """The entries of ``[points]`` or ``[links]`` as (name, spec), in file order, each name checked."""
    out, seen = [], set()
    for k, spec in raw.items():
        if isinstance(k, bool) or not isinstance(k, (str, int)):
            raise ctx.err(table, f"a {kind}'s name must be a string, got {show(k)}", hint='e.g. "B" or "3"')
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
