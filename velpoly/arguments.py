"""The Python API's argument checks (FORMAT.md section 4): a wrong argument is a VelpolyError.

Each check raises :class:`~velpoly.errors.ArgumentTypeError` (also a ``TypeError``)
or :class:`~velpoly.errors.ArgumentValueError` (also a ``ValueError``) whose
``where`` names the argument, never a raw numpy error or a warning.
"""
from __future__ import annotations

import decimal
import math
import numbers
import os
import warnings

import numpy as np

from .errors import ArgumentTypeError, ArgumentValueError
from .model import Mechanism

__all__ = ["check_mechanism", "check_angle", "check_angles", "rational_g", "MAX_ANGLE"]

MAX_ANGLE = 1e6   # degrees: beyond, an angle's rounding error nears 1e-10 deg and a sweep's walk grows huge


def _kind(v) -> str:
    """What ``v`` is, in words: "None", "the string '30'", "a list", "a complex number"."""
    if v is None:
        return "None"
    if isinstance(v, str):
        s = repr(v)
        return f"the string {s if len(s) <= 40 else s[:36] + '...'}"
    if isinstance(v, (bool, np.bool_)):
        return f"the boolean {bool(v)}"
    if isinstance(v, (complex, np.complexfloating)):
        return "a complex number"
    if isinstance(v, np.ndarray):
        return f"an array of shape {v.shape} ({v.dtype})"
    name = type(v).__name__
    return f"{'an' if name[:1].lower() in 'aeiou' else 'a'} {name}"


def check_mechanism(m, name: str = "m") -> Mechanism:
    """``m`` must be a :class:`~velpoly.model.Mechanism` (what :func:`velpoly.load` returns)."""
    if isinstance(m, Mechanism):
        return m
    hint = 'load it first: m = velpoly.load("fourbar.toml")'
    if isinstance(m, (str, os.PathLike, dict)):
        hint = f"load it first: velpoly.load({'the dict' if isinstance(m, dict) else repr(str(m))}) gives the Mechanism"
    raise ArgumentTypeError(f"expected a velpoly.Mechanism, got {_kind(m)}", where=name, hint=hint)


def _real(v) -> bool:
    """Whether ``v`` is one real number: a ``numbers.Real`` (int, float, Fraction, numpy's) or a Decimal, not a
    bool."""
    return isinstance(v, (numbers.Real, decimal.Decimal)) and not isinstance(v, (bool, np.bool_))


def _beyond(v) -> str | None:
    """``v`` to six digits where it is a finite real number beyond any float (``10**400``, ``Decimal("1e400")``,
    ``np.longdouble("1e400")``: ``float`` overflows or gives inf), else None."""
    try:
        if math.isfinite(float(v)):
            return None
    except OverflowError:
        return rational_g(v)
    except (ValueError, TypeError):
        return None
    finite = v.is_finite() if isinstance(v, decimal.Decimal) else isinstance(v, np.floating) and bool(np.isfinite(v))
    return rational_g(v) if finite else None


def check_angle(angle, name: str = "angle") -> float | None:
    """``angle`` must be None or a finite real number (degrees): a float, an int, a Fraction, a Decimal, a numpy
    scalar or a 0-d real array; never a bool, a string, a sequence or a complex number."""
    if angle is None:
        return None
    if isinstance(angle, np.ndarray) and angle.ndim == 0 and angle.dtype.kind in "iuf":
        angle = angle[()]
    if not _real(angle):
        raise ArgumentTypeError(f"expected a number of degrees, got {_kind(angle)}", where=name,
                                hint=f"{name}=40.0 (degrees, counter-clockwise from +x)")
    shown = _beyond(angle)   # beyond any float: too large, to 6 digits
    try:
        x = math.inf if shown else float(angle)
    except (ValueError, TypeError):
        x = math.nan
    if not math.isfinite(x) and shown is None:
        raise ArgumentValueError(f"the driver angle must be finite, got {angle}", where=name,
                                 hint=f"{name} is a finite number of degrees")
    if abs(x) > MAX_ANGLE:
        raise ArgumentValueError(f"the driver angle {shown or format(x, '.12g')} deg is too large (at most "
                                 f"{MAX_ANGLE:g} deg either way)",
                                 where=name, hint="give the angle within a turn or a few (it is absolute)")
    return x


def rational_g(v) -> str:
    """A rational number (a Decimal, a numpy long double) too large for a float, as ``%g`` would write it
    ("1e+400", "-3.33333e+399")."""
    try:
        if isinstance(v, (decimal.Decimal, np.floating)):
            d = decimal.Decimal(str(v)).normalize()
        else:
            d = (decimal.Decimal(v.numerator) / decimal.Decimal(v.denominator)).normalize()
    except (AttributeError, TypeError, ArithmeticError):
        return "beyond any float"
    return format(d, ".6g").replace("E", "e")


def check_angles(angles, name: str = "angles", limit: float = MAX_ANGLE, unit: str = "deg") -> np.ndarray:
    """``angles`` must be a 1-D sequence (a list, a tuple, a range, a 1-D array) of finite real numbers,
    none larger than ``limit`` in size; returned as a float array."""
    hint = f"{name} is a 1-D sequence of degrees, e.g. 30 + np.arange(0, 360, 5.0)"
    if isinstance(angles, (str, bytes, dict, set, frozenset)) or not hasattr(angles, "__len__") \
            or not hasattr(angles, "__getitem__"):
        raise ArgumentTypeError(f"expected a 1-D sequence of angles, got {_kind(angles)}", where=name,
                                hint=hint + (" (make the generator a list)" if hasattr(angles, "__next__") else ""))
    if np.ma.is_masked(angles):   # np.asarray would keep the masked values: there is no saying which to use
        raise ArgumentValueError(f"a masked array ({np.ma.count_masked(angles)} of its {np.size(angles)} values masked)", where=name,
                                 hint=f"pass the values to use: {name}.compressed() (the unmasked ones)")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            a = np.asarray(angles)
    except (ValueError, TypeError, Warning, OverflowError):
        raise ArgumentValueError(f"not a 1-D sequence of numbers (rows of different lengths?)", where=name,
                                 hint=hint) from None
    if not isinstance(angles, np.ndarray) and a.dtype.kind in "iuf" and \
            any(isinstance(x, (bool, np.bool_)) for x in angles):   # numpy reads [30, True] as numbers
        raise ArgumentTypeError("expected real numbers, got booleans", where=name, hint=hint)
    if a.dtype.kind == "O":   # Python objects: numbers too large for a float, Fractions, Decimals, or a mixture
        a = _objects(a, name, hint, unit, limit)
    if a.dtype.kind not in "iuf":
        what = {"b": "booleans", "c": "complex numbers", "U": "strings", "S": "bytes"}.get(a.dtype.kind, str(a.dtype))
        raise ArgumentTypeError(f"expected real numbers, got {what}", where=name, hint=hint)
    if a.ndim != 1:
        raise ArgumentValueError(f"expected a 1-D sequence, got shape {a.shape}", where=name,
                                 hint=hint + " (flatten it with .ravel() if that is what you mean)")
    with np.errstate(over="ignore", invalid="ignore"):
        a, wide = a.astype(float), a
    beyond = np.isinf(a) & np.isfinite(wide)   # a long double beyond any float
    if beyond.any():
        raise _too_large(rational_g(wide[beyond][np.argmax(np.abs(wide[beyond]))]), unit, limit, name, hint)
    if not np.all(np.isfinite(a)):
        raise ArgumentValueError("the angles must be finite numbers", where=name, hint=hint)
    if len(a) and np.abs(a).max() > limit:
        raise _too_large(f"{np.abs(a).max():g}", unit, limit, name, hint)
    return a


def _objects(a: np.ndarray, name: str, hint: str, unit: str, limit: float) -> np.ndarray:
    """An object array (``check_angles``) of real numbers as floats; an error naming the argument if one is not a
    real number, or is beyond any float."""
    flat = a.ravel()
    if a.ndim != 1 or not all(_real(x) for x in flat):
        bad = [x for x in flat if not _real(x)]
        raise ArgumentTypeError(f"expected numbers, got {_kind(bad[0]) if bad else 'nested sequences'}",
                                where=name, hint=hint)
    beyond = [x for x in flat if _beyond(x)]
    if beyond:   # an int, a fraction or a Decimal beyond any float (10**400): too large, as check_angle says
        raise _too_large(rational_g(max(beyond, key=abs)), unit, limit, name, hint)
    try:
        return np.array([float(x) for x in flat])
    except ValueError:   # a signalling NaN
        raise ArgumentValueError("the angles must be finite numbers", where=name, hint=hint) from None


def _too_large(shown: str, unit: str, limit: float, name: str, hint: str) -> ArgumentValueError:
    return ArgumentValueError(f"a value of {shown} {unit} is too large (at most {limit:g} {unit} either way)",
                              where=name, hint=hint)
