"""Names as books write them: a point on a link, a quantity, a direction, a polygon's units.

One module says how every figure, table, caption and step equation names things, so that they all
agree (docs/figures.md, "Names"). The JSON keys (``P@cam``) and the ``[reference]`` keys stay as
FORMAT.md writes them; this is how they are *shown*.

A point on a link carries the link as a subscript: P on link 2 is P₂ (a link named by a number), P on
link ``cam`` is P with the subscript "cam". As plain text (``velpoly solve``'s tables, the step
equations, :class:`velpoly.polygons.Polygon` labels) that is ``P₂`` (Unicode subscript digits) and
``P(cam)`` (a link named otherwise, in brackets, never run together: ``Pcam`` would read as a point
named so, ``PS`` as the segment PS). In mathtext (figures) it is ``P_{2}`` and ``P_{\\mathrm{cam}}``.
A point's own digits are its subscript too (O2 -> O₂ in figures), and a link's joins them: O2 on link
3 is O_{2,3}. Images are the lower-case names (p₂, p(cam); primed in an acceleration polygon).

Quantities are written ``V_P₂``, ``A^n_BA``, ``V_P₂/P₃`` (P of link 2 relative to P of link 3) as text
and typeset by :func:`quantity_math` / :func:`index_math`.

Directions are printed in one range everywhere, [0, 360), rounded first and then folded, so that
359.999 prints 0.00 and no -0.00 or 360.00 appears (:func:`direction`).

A file without units (``units = ""``) has lengths in "units": polygon scales read "1 cm = 8 units/s"
(velocities) and "units/s²" (accelerations), never "s⁻¹", which would read as an angular velocity
(:func:`unit`).

Nothing here imports matplotlib.

>>> place("P", "2"), place("P", "cam"), place("B"), place("P", "cam", lower=True, primes=1)
('P₂', 'P(cam)', 'B', "p(cam)'")
>>> key_text("P@2"), key_text("A@crank", lower=True)
('P₂', 'a(crank)')
>>> name_tex("p(cam)'"), name_tex("b4"), name_tex("O_v"), name_tex("o2₃"), name_tex("c'")
("$p_{\\\\mathrm{cam}}'$", '$b_{4}$', '$O_{v}$', '$o_{2,3}$', 'c′')
>>> quantity_math("V", "P₂/P(cam)")
'$V_{P_{2}/P_{\\\\mathrm{cam}}}$'
>>> direction(359.999), direction(-0.001), direction(-90), direction(360)
('0.00', '0.00', '270.00', '0.00')
>>> unit("", 1), unit("mm", 2), unit("", 0)
('units/s', 'mm/s²', 'units')
"""
from __future__ import annotations

import functools
import math
import re

__all__ = ["split_key", "link_sub", "link_of", "place", "key_text", "point_text", "lower_name", "upper_name", "relative", "quantity_text",
           "math_literal", "literal", "link_math", "name_math", "name_tex", "index_math", "quantity_math", "direction",
           "polar", "unit", "NAME"]

_SUB_DIGITS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
_FROM_SUB = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")
_DIGITS = re.compile(r"[0-9]+")


# -- plain text ----------------------------------------------------------------------------------------
def split_key(key: str) -> tuple[str, str | None]:
    """A point key (FORMAT.md section 5) as (point, link): ``P@cam`` -> ("P", "cam"), ``B`` -> ("B", None)."""
    p, at, lk = str(key).partition("@")
    return (p, lk) if at else (p, None)


def link_sub(link: str) -> str:
    """A link's name as a subscript in plain text: ``2`` -> ₂, ``cam`` -> (cam)."""
    link = str(link)
    return link.translate(_SUB_DIGITS) if _DIGITS.fullmatch(link) else f"({link})"


def place(point: str, link: str | None = None, *, lower: bool = False, primes: int = 0) -> str:
    """The point ``point`` of link ``link`` (None: the point itself) as plain text: P₂, P(cam), B;
    ``lower``: an image's name (p₂); ``primes``: an acceleration image's (p₂')."""
    p = str(point).lower() if lower else str(point)
    return p + ("" if link is None else link_sub(link)) + "'" * primes


def key_text(key: str, *, lower: bool = False, primes: int = 0) -> str:
    """A point key as plain text: ``P@2`` -> P₂, ``P@cam`` -> P(cam), ``B`` -> B."""
    return place(*split_key(key), lower=lower, primes=primes)


def point_text(point: str, link: str | None = None) -> str:
    """A point as a step's caption writes it in words: as :func:`place`, and a name's own trailing
    digits as a subscript too (``O2`` -> O₂; ``B`` of link 4 -> B₄, of link ``cam`` -> B(cam); a name of
    digits alone stays as it is). ``point_text("P@cam")`` reads a point key the same way.

    >>> point_text("O2"), point_text("B", "4"), point_text("P@cam"), point_text("o2", "3"), point_text("12")
    ('O₂', 'B₄', 'P(cam)', 'o₂₃', '12')
    """
    if link is None:
        point, link = split_key(point)
    head = point.rstrip("0123456789")
    return place(head + point[len(head):].translate(_SUB_DIGITS) if head else point, link)


def link_of(sub: str) -> str:
    """The link's name from its plain-text subscript (:func:`link_sub`): ₂ -> 2, (cam) -> cam."""
    return sub[1:-1] if sub.startswith("(") else sub.translate(_FROM_SUB)


NAME = re.compile(r"([A-Za-z]+)([0-9]*)([₀-₉]+|\([^()]*\))?('*)")   # one name as plain text: P, O2, P₂, p(cam)'


@functools.lru_cache(maxsize=4096)   # a mechanism's few names, asked for every arrow of every polygon
def lower_name(name: str) -> str:
    """An image's name from a point's text name: the point lower-cased, the link's subscript as it is
    (``S(Cam)`` -> s(Cam))."""
    mo = NAME.fullmatch(name)
    if not mo:
        return name.lower()
    return (mo.group(1) + mo.group(2)).lower() + (mo.group(3) or "") + mo.group(4)


def upper_name(name: str) -> str:
    """A point's text name from its image's (:func:`lower_name` undone): ``s(Cam)`` -> S(Cam), ``b₄`` -> B₄."""
    mo = NAME.fullmatch(name)
    if not mo:
        return name.upper()
    return (mo.group(1) + mo.group(2)).upper() + (mo.group(3) or "") + mo.group(4)


def relative(a: str, b: str) -> str:
    """The index of a relative quantity of two places' text names: ``P₂/P₃`` (a relative to b)."""
    return f"{a}/{b}"


def driver_index(m) -> str:
    """A slider driver's index as plain text: its point (``A``) where its guide is the frame, else its block's point
    relative to the guide's (``A₃/A₄``): the driver's speed and acceleration are given along the guide's path, the
    slip that the polygons and step captions name V_A₃/A₄."""
    s = next(s for s in m.sliders if s.point == m.driver.slider)
    return s.point if m.link(s.guide).frame else relative(place(s.point, s.block), place(s.point, s.guide))


def quantity_text(symbol: str, index: str) -> str:
    """A quantity as plain text: ``V`` and ``P₂`` -> V_P₂, ``omega`` and ``3`` -> omega_3."""
    return f"{symbol}_{index}"


# -- mathtext ------------------------------------------------------------------------------------------
def literal(s) -> str:
    r"""A user's text (a name, a title, units) for a matplotlib Text, drawn as written: ``$`` escaped so
    it starts no mathtext, a backslash set as mathtext's backslash (so none escapes a ``$`` after it).

    >>> print(literal("$B$"), literal("a\\b"))
    \$B\$ a$\backslash$b
    """
    return r"$\backslash$".join(part.replace("$", r"\$") for part in str(s).split("\\"))


_MATH_ESCAPES = {"\\": r"{\backslash}", "{": r"\{", "}": r"\}", "$": r"\$"}


def math_literal(s) -> str:
    r"""A user's text for inside mathtext (a subscript ``$\omega_{...}$``), drawn as written: ASCII
    letters and digits as they are, braces, ``$`` and backslash escaped, other ASCII signs and spaces
    as ``\text{...}`` (mathtext would read ``_ ^ % # ~`` or drop spaces); other characters as they are.

    >>> print(math_literal("3"), math_literal("a_b"), math_literal("{x}"))
    3 a\text{_}b \{x\}
    """
    out = []
    for ch in str(s):
        if ch in _MATH_ESCAPES:
            out.append(_MATH_ESCAPES[ch])
        elif ch.isascii() and not ch.isalnum():
            out.append(r"\text{" + ch + "}")
        else:
            out.append(ch)
    return "".join(out)


def link_math(link: str) -> str:
    """A link's name inside a mathtext subscript: digits and one letter as they are (italic), a word
    upright (``\\mathrm{cam}``), as the user wrote it."""
    link = str(link)
    if _DIGITS.fullmatch(link) or (len(link) == 1 and link.isascii() and link.isalpha()):
        return link
    return r"\mathrm{" + math_literal(link) + "}"


def name_math(name: str) -> str | None:
    """One name of plain text (:func:`place`, :func:`lower_name`) as mathtext, without the ``$``:
    ``p(cam)'`` -> p_{\\mathrm{cam}}', ``O2`` -> O_{2}, ``o2₃`` -> o_{2,3}; None where it is no such name.
    ``O_v``, ``P_13`` (an explicit subscript) read as O_{v}, P_{13}."""
    mo = NAME.fullmatch(name) or None
    if mo is None:
        ex = re.fullmatch(r"([A-Za-z]+)_([0-9A-Za-z]+)('*)", name)
        return None if ex is None else ex.group(1) + "_{" + ex.group(2) + "}" + ex.group(3)
    base, digits, link, primes = mo.groups()
    subs = [digits] if digits else []
    if link:
        subs.append(link_math(link_of(link)))
    return base + ("_{" + ",".join(subs) + "}" if subs else "") + primes


def name_tex(label: str, math: bool = False) -> str:
    """A name (an image's label: ``b4``, ``p₂'``, ``p(cam)``, ``O_v``) as the text of an italic Text:
    mathtext where it has a subscript; a plain name stays plain text (primes as ′) unless ``math``
    (a label beside mathtext ones). Anything else is drawn as it is written (:func:`literal`)."""
    s = str(label)
    body = name_math(s)
    if body is None:
        return literal(s)
    if "_" not in body:
        return "$" + body + "$" if math else body.replace("'", "′")
    return "$" + body + "$"


_TOKEN = re.compile(NAME.pattern + r"|(.)")


def index_math(index: str) -> str:
    """A quantity's subscript of plain text names (``P₂/P(cam)``, ``B(cam)A(cam)``, ``AO2``, ``13``) as
    mathtext: each name with its own subscripts; other characters as written."""
    if _DIGITS.fullmatch(index):
        return index
    out = []
    for mo in _TOKEN.finditer(index):
        if mo.group(5) is not None:
            out.append("/" if mo.group(5) == "/" else math_literal(mo.group(5)))
        else:
            out.append(name_math(mo.group(0)))
    return "".join(out)


_GREEK = {"omega": r"\omega", "alpha": r"\alpha", "theta": r"\theta"}


def quantity_math(symbol: str, index: str, bars: bool = False, sup: str = "") -> str:
    """A quantity as mathtext: ``V``, ``P₂`` -> $V_{P_{2}}$; ``omega``, ``3`` -> $\\omega_{3}$;
    ``bars``: its magnitude $|V_{B}|$; ``sup``: a component's mark (``n``: $A^{n}_{BA}$)."""
    index = link_math(index) if symbol in _GREEK else index_math(str(index))   # a rate's index is a link
    body = _GREEK.get(symbol, symbol) + ("^{" + sup + "}" if sup else "") + "_{" + index + "}"
    return "$|" + body + "|$" if bars else "$" + body + "$"


# -- numbers and units ---------------------------------------------------------------------------------
def direction(deg: float, decimals: int = 2) -> str:
    """A direction in degrees in [0, 360), rounded first and then folded: 359.999 -> 0.00, -90 -> 270.00,
    never -0.00 or 360.00."""
    d = round(float(deg), decimals) % 360.0
    if round(d, decimals) >= 360.0:
        d = 0.0
    return f"{d + 0.0:.{decimals}f}"


def polar(magnitude: str, deg: float, decimals: int = 2) -> str:
    """A vector printed as books print it: ``12.5 ∠ 30.00°`` (the magnitude already formatted)."""
    return f"{magnitude} ∠ {direction(deg, decimals)}°"


def vector_direction(v) -> float:
    """The direction of the vector ``v`` = (x, y), in degrees."""
    return math.degrees(math.atan2(float(v[1]), float(v[0])))


_POWERS = ("", "/s", "/s²")


def unit(units: str, power: int) -> str:
    """The unit of a length (``power`` 0), a velocity (1) or an acceleration (2) of a file whose length
    unit is ``units`` (as written; ``""``: "units", so that "1 cm = 8 units/s" never reads as an angular
    velocity)."""
    return (str(units) or "units") + _POWERS[power]
