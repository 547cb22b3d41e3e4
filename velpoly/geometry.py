"""The exact 2-D kernel: homogeneous points and lines, intersections (the rigid-body
relations and the vector helpers perp, dot, unit are in :mod:`velpoly.rigid`).

Points and lines are homogeneous triples, so points at infinity (the pole
of a slider, the direction of a path) need no special case:

* a point (x, y) is ``(x, y, 1)``; a point at infinity in direction d is ``(dx, dy, 0)``;
* the line through two points is their cross product ``p x q``;
* the intersection of two lines is ``l x m``; it is at infinity when the
  lines are parallel (its third coordinate vanishes).

Intersections report a conditioning measure: the sine of the angle between
the two lines, which is what limits a drafted construction's accuracy.

>>> join((0.0, 0.0, 1.0), ideal((0.0, 2.0))) + 0.0      # the line x = 0 through a finite point and a direction
array([-1.,  0.,  0.])
>>> x, s, t, sine = intersect_lines((0, 0), (1, 0), (2, 1), (0, 1)); x, float(sine)
(array([2., 0.]), 1.0)
>>> intersect_lines((0, 0), (1, 0), (0, 1), (1, 0))[0] is None                    # parallel
True
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["ideal", "join", "from_polar", "intersect_lines", "intersect_lines_batch", "intersect_lines_z"]


def ideal(direction) -> np.ndarray:
    """The point at infinity in ``direction`` (its sign does not matter)."""
    d = np.asarray(direction, float)
    n = math.hypot(d[0], d[1])
    return np.array([d[0] / n, d[1] / n, 0.0])


def join(p, q) -> np.ndarray:
    """The line through two homogeneous points (either may be at infinity)."""
    return _normalise_line(np.cross(p, q))


def _normalise_line(l) -> np.ndarray:
    n = math.hypot(l[0], l[1])
    if n == 0:
        n = abs(l[2])
        return l / n if n > 0 else l  # the line at infinity, or degenerate
    return l / n


def intersect_lines(p, d, q, e):
    """Intersection of the line through p along d with the line through q along e.

    Solves p + s d = q + t e. Returns ``(x, s, t, sine)``: the point, the two
    parameters and |sin| of the angle between the lines (its conditioning).
    Parallel lines give ``x = None`` (so do lines so nearly parallel that s or t
    overflows).
    """
    p, d, q, e = (np.asarray(v, float) for v in (p, d, q, e))
    den = d[0] * e[1] - d[1] * e[0]
    scale = math.hypot(*d) * math.hypot(*e)
    sine = abs(den) / scale if scale > 0 else 0.0
    if den == 0:
        return None, math.nan, math.nan, 0.0
    w = q - p
    s = (w[0] * e[1] - w[1] * e[0]) / den
    t = (w[0] * d[1] - w[1] * d[0]) / den
    if not (math.isfinite(s) and math.isfinite(t)):
        return None, math.nan, math.nan, sine
    return p + s * d, s, t, sine


def intersect_lines_z(p, d, q, e):
    """:func:`intersect_lines` with the 2-vectors as complex numbers x + iy (Python scalars).

    Solves p + s d = q + t e by the same formulas (cross products a x b = Im(conj(a) b)).
    Returns ``(x, s, t, sine)``, x complex; parallel lines give ``x = None``.
    """
    den = (d.conjugate() * e).imag
    scale = abs(d) * abs(e)
    sine = abs(den) / scale if scale > 0 else 0.0
    if den == 0:
        return None, math.nan, math.nan, 0.0
    w = q - p
    s = (w.conjugate() * e).imag / den
    t = (w.conjugate() * d).imag / den
    if not (math.isfinite(s) and math.isfinite(t)):
        return None, math.nan, math.nan, sine
    return p + s * d, s, t, sine


def from_polar(mag: float, deg: float) -> np.ndarray:
    """The vector of magnitude ``mag`` at ``deg`` degrees (textbook ``mag ∠ deg``)."""
    t = math.radians(deg)
    return np.array([mag * math.cos(t), mag * math.sin(t)])


def intersect_lines_batch(p, d, q, e):
    """:func:`intersect_lines` for many line pairs at once (arrays of shape (..., 2)).

    Solves p + s d = q + t e for every leading index. Returns ``(x, s, t, sine)``
    with shapes (..., 2), (...), (...), (...); parallel pairs give NaN in x, s, t
    and a sine of 0 (pairs whose s or t overflows give NaN too, with their sine).

    >>> x, s, t, sine = intersect_lines_batch([[0, 0], [0, 0]], [[1, 0], [1, 0]],
    ...                                       [[2, 1], [0, 1]], [[0, 1], [1, 0]])
    >>> x[0] + 0.0, bool(np.isnan(x[1]).all()), float(sine[0]), float(sine[1])
    (array([2., 0.]), True, 1.0, 0.0)
    """
    p, d, q, e = np.broadcast_arrays(*(np.asarray(v, float) for v in (p, d, q, e)))
    den = d[..., 0] * e[..., 1] - d[..., 1] * e[..., 0]
    scale = np.hypot(d[..., 0], d[..., 1]) * np.hypot(e[..., 0], e[..., 1])
    w = q - p
    with np.errstate(divide="ignore", invalid="ignore"):
        sine = np.where(scale > 0, np.abs(den) / np.where(scale > 0, scale, 1.0), 0.0)
        s = np.where(den != 0, (w[..., 0] * e[..., 1] - w[..., 1] * e[..., 0]) / den, np.nan)
        t = np.where(den != 0, (w[..., 0] * d[..., 1] - w[..., 1] * d[..., 0]) / den, np.nan)
        meets = np.isfinite(s) & np.isfinite(t)
        s, t = np.where(meets, s, np.nan), np.where(meets, t, np.nan)
    return p + s[..., None] * d, s, t, sine
