"""Angular rates as books write them: ``"60 rpm"``, ``"10 rad/s cw"``, ``"5 rad/s^2 clockwise"``.

A sense in words multiplies the number: clockwise by -1, counter-clockwise by +1 (ccw is positive,
FORMAT.md sections 1 and 5).
"""
from __future__ import annotations

import math
import re
from typing import Any, Mapping

from .context import written_nonzero

__all__ = ["parse_omega", "parse_alpha", "SENSES", "OMEGA_HINT", "ALPHA_HINT", "RateTooLarge",
           "RateTooSmall"]

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

# what an error about a driver's rate suggests
OMEGA_HINT = ('a number in rad/s, or "NUMBER UNIT [SENSE]" with UNIT rad/s, rpm, deg/s or rev/s and SENSE '
              'cw, ccw, clockwise or anticlockwise (e.g. "60 rpm", "10 rad/s clockwise")')
ALPHA_HINT = 'a number in rad/s^2, or "NUMBER rad/s^2 [SENSE]" (SENSE cw, ccw, clockwise or anticlockwise)'


class RateTooLarge(ValueError):
    """A rate written as a finite number whose value is beyond any float (``"1e400 rpm"``)."""


class RateTooSmall(ValueError):
    """A rate written as a nonzero number whose value is below any float (``"1e-400 rpm"``: it would read as 0)."""


def _parse_rate(v: Any, units: Mapping[str, float]) -> float:
    """A number as it is, or ``"NUMBER UNIT [SENSE]"`` with UNIT one of ``units`` (to rad/s or rad/s^2);
    ValueError if it is neither, :class:`RateTooLarge` (a ValueError) if its value is beyond any float
    (``"1e400 rpm"``), :class:`RateTooSmall` if it is written nonzero but below any float (``"1e-400 rpm"``)."""
    if isinstance(v, bool):
        raise ValueError(v)
    if isinstance(v, (int, float)):
        return float(v)
    if not isinstance(v, str):
        raise ValueError(v)
    m = _RATE_RE.fullmatch(v)
    if not m:
        raise ValueError(v)
    value, unit, sense = m.groups()
    unit = unit.lower()
    if unit not in units:
        raise ValueError(v)
    x = float(value) * units[unit]
    if not math.isfinite(x):   # the pattern's number is finite: it is beyond any float
        raise RateTooLarge(v)
    if x == 0 and written_nonzero(value):   # the pattern's number is nonzero: it is below any float
        raise RateTooSmall(v)
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
    return _parse_rate(v, _OMEGA_UNITS)


def parse_alpha(v: Any) -> float:
    """An angular acceleration in rad/s^2 from a number or ``"NUMBER rad/s^2 [cw|ccw]"``.

    >>> parse_alpha("5 rad/s^2 cw")
    -5.0
    """
    return _parse_rate(v, _ALPHA_UNITS)
