"""The ``[drawing]`` table of a mechanism file: presentation choices, checked.

Every key is optional. Lengths on paper are in centimetres: a scale of
``0.05`` means that 1 cm of the printed figure (at its nominal size) stands
for 0.05 length units, the way books print "space diagram: 1 cm = 0.05 m".

==========================  ===============================================================
key                         meaning
==========================  ===============================================================
``scale``                   space diagram: length units per cm of paper (default: chosen
                            to fit, a round 1, 2, 2.5 or 5 times a power of ten)
``velocity_scale``          velocity polygon: units/s per cm of paper
``acceleration_scale``      acceleration polygon: units/s^2 per cm of paper
``label_points``            the points to label on the mechanism (default: all); ``true``
                            labels all, ``false`` none
``link_colours``            ``{ link = colour }``: a link's colour (any matplotlib colour)
``link_numbers``            ``"circled"`` (default), ``"plain"`` or ``"none"``
``reasons``                 mark construction lines with their reason (default true)
``table``                   draw the results table on each sheet (default true)
``sheet``                   the sheet ``velpoly draw`` draws without ``--sheet``, and the
                            gallery shows: one of SHEETS (default ``"full"``)
==========================  ===============================================================
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

from ..errors import InputError
from ..loader.context import TOO_LARGE_HINT, show, too_large

__all__ = ["DrawingOptions", "drawing_options", "KEYS", "SHEETS"]

KEYS = ("scale", "velocity_scale", "acceleration_scale", "label_points", "link_colours", "link_numbers",
        "reasons", "table", "sheet")
SHEETS = ("velocity", "acceleration", "poles", "full", "displacement")   # the sheets of ``velpoly draw``
LINK_NUMBERS = ("circled", "plain", "none")


@dataclass(frozen=True)
class DrawingOptions:
    """The checked ``[drawing]`` table (see the module's docstring for each key)."""

    scale: float | None = None
    velocity_scale: float | None = None
    acceleration_scale: float | None = None
    label_points: tuple[str, ...] | None = None
    link_colours: Mapping = field(default_factory=lambda: MappingProxyType({}))
    link_numbers: str = "circled"
    reasons: bool = True
    table: bool = True
    sheet: str = "full"


def _typed(v) -> str:
    """A value as the file has it: a string quoted (TOML's literal string), ``true`` and ``false`` as TOML
    writes them (not Python's True), numbers as written, a table or a list by its kind."""
    return repr(v) if isinstance(v, str) else show(v)


def _err(m, key: str, what: str, hint: str = "") -> InputError:
    return InputError(what, where=f"drawing.{key}", file=m.source, hint=hint)


def _positive(m, key: str, v) -> float:
    if too_large(v):
        raise _err(m, key, f"{show(v)} is too large: beyond any floating-point number", hint=TOO_LARGE_HINT)
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
        raise _err(m, key, f"expected a positive number, got {_typed(v)}",
                   hint=f"{key} is in units per cm of paper, e.g. {key} = 0.05")
    return float(v)


def _boolean(m, key: str, v) -> bool:
    if not isinstance(v, bool):
        raise _err(m, key, f"expected true or false, got {_typed(v)}")
    return v


def _label_points(m, v) -> tuple[str, ...] | None:
    """``label_points``: a list of the file's points, or true (every point, as without it) or false (none)."""
    if isinstance(v, bool):
        return None if v else ()
    odd = v if not isinstance(v, list) else next((p for p in v if not isinstance(p, str)), None)
    if odd is not None:
        raise _err(m, "label_points", f"expected a list of point names, true or false, got {_typed(odd)}"
                   + (" in the list" if odd is not v else ""), hint='e.g. label_points = ["A", "B"]')
    for p in v:
        if p not in m.points:
            raise _err(m, "label_points", f"unknown point {_typed(p)}",
                       hint="points: " + ", ".join(m.point_order or m.points))
    return tuple(v)


def drawing_options(m) -> DrawingOptions:
    """Check ``m.drawing`` and return it as :class:`DrawingOptions`.

    Raises :class:`~velpoly.errors.InputError` naming the key, for an unknown
    key (listing the valid ones) or a bad value.

    >>> import velpoly
    >>> drawing_options(velpoly.load({"points": {"A": [0, 0], "B": [1, 0]},
    ...     "links": {"0": {"points": ["A"], "frame": True}, "1": {"points": ["A", "B"]}},
    ...     "driver": {"link": "1", "omega": 1}, "drawing": {"scale": 0.5}})).scale
    0.5
    """
    d = dict(m.drawing or {})
    for key in d:
        if key not in KEYS:
            raise _err(m, key, f"unknown drawing option {_typed(key)}; valid keys: " + ", ".join(KEYS))
    out = {}
    for key in ("scale", "velocity_scale", "acceleration_scale"):
        if key in d:
            out[key] = _positive(m, key, d[key])
    if "label_points" in d:
        out["label_points"] = _label_points(m, d["label_points"])
    if "link_colours" in d:
        v = d["link_colours"]
        if not isinstance(v, Mapping):
            raise _err(m, "link_colours", f"expected a table of link = colour, got {_typed(v)}")
        from matplotlib.colors import is_color_like
        colours = {}
        for lk, c in v.items():
            if str(lk) not in m.link_names:
                raise _err(m, f"link_colours.{lk}", f"unknown link {_typed(lk)}",
                           hint="links: " + ", ".join(m.link_names))
            if not isinstance(c, str) or not is_color_like(c):
                raise _err(m, f"link_colours.{lk}", f"not a colour: {_typed(c)}",
                           hint='a name or hex code, e.g. "tab:blue" or "#1f77b4"')
            colours[str(lk)] = c
        out["link_colours"] = MappingProxyType(colours)
    if "link_numbers" in d:
        v = d["link_numbers"]
        if v not in LINK_NUMBERS:
            raise _err(m, "link_numbers", f"expected one of {', '.join(LINK_NUMBERS)}, got {_typed(v)}")
        out["link_numbers"] = v
    for key in ("reasons", "table"):
        if key in d:
            out[key] = _boolean(m, key, d[key])
    if "sheet" in d:
        v = d["sheet"]
        if v not in SHEETS:
            raise _err(m, "sheet", f"unknown sheet {_typed(v)}; valid sheets: " + ", ".join(SHEETS),
                       hint='the sheet velpoly draw draws without --sheet, e.g. sheet = "poles"')
        out["sheet"] = v
    return DrawingOptions(**out)
