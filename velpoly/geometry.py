"""The exact 2-D kernel: vectors, homogeneous points and lines, intersections.

Points and lines are homogeneous triples, so points at infinity (the pole
of a slider, the direction of a path) need no special case:

* a point (x, y) is ``(x, y, 1)``; a point at infinity in direction d is ``(dx, dy, 0)``;
* the line through two points is their cross product ``p x q``;
* the intersection of two lines is ``l x m``; it is at infinity when the
  lines are parallel (its third coordinate vanishes).

Intersections report a conditioning measure: the sine of the angle between
the two lines, which is what limits a drafted construction's accuracy.

>>> euclid(meet(line_through((0, 0), (1, 0)), line_through((2, 1), direction=(0, 1)))) + 0.0
array([2., 0.])
>>> is_finite(meet(line_through((0, 0), (1, 0)), line_through((0, 1), (1, 1))))   # parallel
False
"""
from __future__ import annotations

import math

import numpy as np

__all__ = [
    "point", "ideal", "line_through", "meet", "join", "is_finite", "euclid", "line_direction",
    "rotate", "perp", "unit", "angle_deg", "from_polar", "intersect_lines", "collinear",
    "line_angle_sine", "distance_point_line", "intersect_lines_batch", "rotate_batch", "intersect_lines_z",
]


def point(p) -> np.ndarray:
    """The homogeneous point (x, y, 1) of a finite point."""
    return np.array([float(p[0]), float(p[1]), 1.0])


def ideal(direction) -> np.ndarray:
    """The point at infinity in ``direction`` (its sign does not matter)."""
    d = np.asarray(direction, float)
    n = math.hypot(d[0], d[1])
    return np.array([d[0] / n, d[1] / n, 0.0])


def join(p, q) -> np.ndarray:
    """The line through two homogeneous points (either may be at infinity)."""
    return _normalise_line(np.cross(p, q))


def line_through(p, q=None, *, direction=None) -> np.ndarray:
    """The line through finite point p and q (a finite point), or along ``direction``."""
    if direction is not None:
        return join(point(p), ideal(direction))
    return join(point(p), point(q))


def meet(l, m) -> np.ndarray:
    """The intersection of two lines, a homogeneous point (finite points scaled to w = 1)."""
    x = np.cross(l, m)
    if abs(x[2]) > 1e-300 and np.all(np.isfinite(x[:2] / x[2])):
        return x / x[2]
    n = math.hypot(x[0], x[1])
    return x / n if n > 0 else x


def _normalise_line(l) -> np.ndarray:
    n = math.hypot(l[0], l[1])
    if n == 0:
        n = abs(l[2])
        return l / n if n > 0 else l  # the line at infinity, or degenerate
    return l / n


def is_finite(p, size: float = 1.0, far: float = 1e9) -> bool:
    """Whether the homogeneous point is finite and within ``far`` sizes of the origin."""
    if p[2] == 0:
        return False
    x = p[:2] / p[2]
    return bool(np.all(np.isfinite(x)) and math.hypot(*x) <= far * size)


def euclid(p) -> np.ndarray:
    """The Cartesian coordinates of a finite homogeneous point."""
    return np.asarray(p[:2], float) / p[2]


def line_direction(l) -> np.ndarray:
    """A unit direction along the line ax + by + c = 0."""
    d = np.array([-l[1], l[0]])
    return d / math.hypot(*d)


def line_angle_sine(l, m) -> float:
    """|sin| of the angle between two lines (0: parallel, 1: perpendicular)."""
    a, b = line_direction(l), line_direction(m)
    return abs(a[0] * b[1] - a[1] * b[0])


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


def distance_point_line(p, l) -> float:
    """Distance of a finite point from a (normalised) line."""
    return abs(l[0] * p[0] + l[1] * p[1] + l[2]) / math.hypot(l[0], l[1])


def collinear(p, q, r, tol: float = 1e-9) -> bool:
    """Whether three homogeneous points (possibly at infinity) lie on one line.

    The determinant of the unit-normalised triples is compared with ``tol``.
    """
    m = np.array([np.asarray(v, float) / np.linalg.norm(v) for v in (p, q, r)])
    return abs(np.linalg.det(m)) <= tol


def rotate(v, deg: float) -> np.ndarray:
    """v turned counter-clockwise by ``deg`` degrees."""
    t = math.radians(deg)
    c, s = math.cos(t), math.sin(t)
    v = np.asarray(v, float)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def perp(v) -> np.ndarray:
    """v turned +90 degrees: k x v."""
    return np.array([-v[1], v[0]], dtype=float)


def unit(v) -> np.ndarray:
    v = np.asarray(v, float)
    return v / math.hypot(*v)


def angle_deg(v) -> float:
    """Direction of v in degrees, (-180, 180]."""
    return math.degrees(math.atan2(v[1], v[0]))


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


def rotate_batch(v, rad) -> np.ndarray:
    """Vectors v (..., 2) turned counter-clockwise by angles ``rad`` (radians, broadcast over ...)."""
    v = np.asarray(v, float)
    c, s = np.cos(rad), np.sin(rad)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)
