"""The rigid-body relations of plane motion, written once.

A link turning at omega (rad/s) with angular acceleration alpha (rad/s^2), whose
point O moves with V_O and A_O, moves its point P at the arm r = R_PO (from O
to P) with::

    V_P = V_O + omega x r                             (point_velocity; omega x r: rate_cross)
    A_P = A_O + alpha x r - omega^2 r                 (point_acceleration)
          A^n = -omega^2 r  (normal, towards O)       (normal_acceleration)
          A^t = alpha x r   (tangential)              (rate_cross)

and a point moving relative to a link turning at omega with V_rel has the
Coriolis acceleration ``2 omega x V_rel`` (coriolis). In the plane, omega is
the scalar of omega k and ``omega x r = omega perp(r)`` with ``perp(x, y) =
(-y, x)`` (k x r, r turned +90 degrees).

Every function takes its vectors in one of three forms and answers in the same
form (one name, the paths the kernel needs):

* **float path** (one pose): a tuple ``(x, y)`` of floats -> a tuple (the components may
  also be arrays of one shape: many points at once, x and y apart);
* **array path** (vectorised over poses): a real ``np.ndarray`` of shape
  ``(..., 2)`` (a (2,) array is one pose), with a scalar's leading shape
  ``(...)`` (omega, alpha: a float or an array over the poses);
* **complex path**: ``x + iy`` as a Python ``complex`` or a complex array, where
  ``perp(z) = i z`` (the dyad walk and the polygons' replays).

The formulas are the same operations in every path, so the float and array
paths agree to the last bit (tests/test_rigid.py).

>>> point_velocity((1.0, 2.0), 3.0, (1.0, 0.0))               # V_O + omega x r
(1.0, 5.0)
>>> point_acceleration((0.0, 0.0), 0.0, 2.0, np.array([1.0, 0.0]))   # -omega^2 r
array([-4.,  0.])
>>> coriolis(2.0, 1j)                                          # 2 omega x V_rel, x + iy
(-4+0j)
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["perp", "dot", "unit", "direction", "xy", "rate_cross", "point_velocity", "point_acceleration",
           "relative_acceleration", "normal_acceleration", "coriolis", "arg", "is_zero"]


def _real_array(v) -> bool:
    """The array path: a real ndarray (..., 2)."""
    return isinstance(v, np.ndarray) and v.dtype.kind != "c"


def is_zero(x) -> bool:
    """Whether x is a scalar zero (not an array): a motion that vanishes at every pose (the frame's).

    >>> is_zero(0.0), is_zero(0j), is_zero(np.zeros(2))
    (True, True, False)
    """
    return not isinstance(x, np.ndarray) and x == 0


def arg(z: np.ndarray) -> np.ndarray:
    """arg z in (-pi, pi] (arctan2 of contiguous copies of the parts: twice as fast as of the
    strided views)."""
    return np.arctan2(z.imag.copy(), z.real.copy())


def _rate(w):
    """A scalar rate (omega, alpha) over the array path's leading shape: w[..., None]."""
    return w[..., None] if isinstance(w, np.ndarray) and w.ndim else w


def perp(v):
    """k x v: v turned +90 degrees, ``perp(x, y) = (-y, x)`` (``i v`` for x + iy).

    >>> perp((1.0, 2.0)), perp(np.array([[1.0, 2.0]])), perp(1 + 2j)
    ((-2.0, 1.0), array([[-2.,  1.]]), (-2+1j))
    """
    if type(v) is tuple or type(v) is list:
        return (-v[1], v[0])
    if _real_array(v):
        if v.ndim == 1:
            return np.array((-v[1], v[0]), float)
        return np.stack([-v[..., 1], v[..., 0]], axis=-1)
    return 1j * v


def dot(a, b):
    """a . b = a_x b_x + a_y b_y (``Re(conj(a) b)`` for x + iy); an array over the poses
    for (..., 2) arrays.

    >>> dot((1.0, 2.0), (3.0, 4.0)), dot(1 + 2j, 3 + 4j), dot(np.array([[1.0, 2.0]]), np.array([[3.0, 4.0]]))
    (11.0, 11.0, array([11.]))
    """
    if type(a) is tuple or type(a) is list or (_real_array(a) and a.ndim == 1):
        return a[0] * b[0] + a[1] * b[1]
    if _real_array(a):
        return np.einsum("...i,...i->...", a, b)
    return (a.conjugate() * b).real


def unit(v):
    """v / |v|: the unit vector along v (each row for (..., 2) arrays).

    >>> unit((3.0, 4.0)), unit(np.array([[0.0, 2.0]]))
    ((0.6, 0.8), array([[0., 1.]]))
    """
    if type(v) is tuple or type(v) is list:
        n = math.hypot(v[0], v[1])
        return (v[0] / n, v[1] / n)
    if _real_array(v):
        if v.ndim == 1:
            return v / math.hypot(*v)
        return v / np.linalg.norm(v, axis=-1, keepdims=True)
    return v / abs(v)


def direction(deg):
    """u = (cos theta, sin theta), the unit vector at ``deg`` degrees ccw from x: a (2,) array
    for a float angle, (..., 2) for an array of angles.

    >>> direction(90.0).round(12) + 0.0, direction(np.array([0.0, 180.0])).round(12) + 0.0
    (array([0., 1.]), array([[ 1.,  0.],
           [-1.,  0.]]))
    """
    if isinstance(deg, np.ndarray) and deg.ndim:
        t = np.radians(deg)
        return np.stack([np.cos(t), np.sin(t)], axis=-1)
    t = math.radians(deg)
    return np.array([math.cos(t), math.sin(t)])


def xy(z, n: int | None = None) -> np.ndarray:
    """x + iy as the contract's 2-vectors: (2,) for a complex number, (N, 2) for a complex array
    of N poses (a view of a contiguous one). With ``n``, a value equal at every pose (a Python
    number; 0 for the frame) is spread over n poses.

    >>> xy(1 + 2j), xy(np.array([1 + 2j, 3j])), xy(0, 2)
    (array([1., 2.]), array([[1., 2.],
           [0., 3.]]), array([[0., 0.],
           [0., 0.]]))
    """
    if isinstance(z, np.ndarray) and z.ndim:
        if z.dtype == complex and z.ndim == 1 and z.flags.c_contiguous:
            return z.view(np.float64).reshape(len(z), 2)
        out = np.empty(z.shape + (2,))
        out[..., 0], out[..., 1] = np.real(z), np.imag(z)
        return out
    if n is None:
        return np.array((z.real, z.imag))
    if z == 0:
        return np.zeros((n, 2))
    out = np.empty((n, 2))
    out[:, 0], out[:, 1] = z.real, z.imag
    return out


def rate_cross(w, r):
    """``w x r = w perp(r)`` for a rate w about k: the velocity of P relative to O,
    ``V_PO = omega x r`` (w = omega), or the tangential acceleration ``A^t_PO = alpha x r``
    (w = alpha), r = R_PO.

    >>> rate_cross(2.0, (1.0, 0.0)), rate_cross(2.0, 1 + 0j), rate_cross(np.array([2.0]), np.array([[1.0, 0.0]]))
    ((-0.0, 2.0), 2j, array([[-0.,  2.]]))
    """
    if type(r) is tuple:
        return (w * -r[1], w * r[0])
    if _real_array(r):
        return _rate(w) * perp(r)
    return (1j * w) * r


def point_velocity(v_o, omega, r):
    """``V_P = V_O + omega x r``: the velocity of the body point P at the arm r = R_PO from O.

    ``v_o``: V_O; ``omega``: the link's angular velocity (rad/s, ccw positive); ``r``: R_PO.

    >>> point_velocity(np.zeros((2, 2)), np.array([1.0, 2.0]), np.array([[1.0, 0.0], [0.0, 1.0]]))
    array([[ 0.,  1.],
           [-2.,  0.]])
    """
    if type(r) is tuple:
        return (v_o[0] + omega * -r[1], v_o[1] + omega * r[0])
    return v_o + rate_cross(omega, r)


def point_acceleration(a_o, alpha, omega, r):
    """``A_P = A_O + alpha x r - omega^2 r``: the acceleration of the body point P at the arm
    r = R_PO from O (tangential ``alpha x r``, normal ``-omega^2 r`` towards O).

    ``a_o``: A_O; ``alpha``, ``omega``: the link's angular acceleration and velocity; ``r``: R_PO.
    (On x + iy: ``A_O + (i alpha - omega^2) r``.)

    >>> point_acceleration((0.0, 0.0), 1.0, 2.0, (1.0, 0.0))
    (-4.0, 1.0)
    """
    if type(r) is tuple:
        w2 = omega * omega
        return (a_o[0] + alpha * -r[1] - w2 * r[0], a_o[1] + alpha * r[0] - w2 * r[1])
    if _real_array(r):
        w = _rate(omega)
        return a_o + _rate(alpha) * perp(r) - (w * w) * r
    return a_o + relative_acceleration(alpha, omega, r)


def relative_acceleration(alpha, omega, r):
    """``A_PO = alpha x r - omega^2 r``: the acceleration of P relative to O, r = R_PO
    (on x + iy: ``(i alpha - omega^2) r``).

    >>> relative_acceleration(1.0, 2.0, (1.0, 0.0)), relative_acceleration(1.0, 2.0, 1 + 0j)
    ((-4.0, 1.0), (-4+1j))
    """
    if type(r) is tuple:
        w2 = omega * omega
        return (alpha * -r[1] - w2 * r[0], alpha * r[0] - w2 * r[1])
    if _real_array(r):
        w = _rate(omega)
        return _rate(alpha) * perp(r) - (w * w) * r
    return (1j * alpha - omega * omega) * r


def normal_acceleration(omega, r):
    """``A^n = -omega^2 r``: the normal (centripetal) part of A_PO, from P towards O, r = R_PO.

    >>> normal_acceleration(3.0, (1.0, -2.0)), normal_acceleration(3.0, 1j)
    ((-9.0, 18.0), (-0-9j))
    """
    if type(r) is tuple:
        w2 = omega * omega
        return (-w2 * r[0], -w2 * r[1])
    if _real_array(r):
        omega = _rate(omega)
    return -(omega * omega) * r


def coriolis(omega, v_rel):
    """``A^c = 2 omega x V_rel``: the Coriolis acceleration of a point moving with V_rel
    relative to a link that turns at omega (the guide's, slot's or contact link's omega).

    >>> coriolis(1.5, (2.0, 0.0)), coriolis(np.array([1.0]), np.array([[0.0, 1.0]])), coriolis(2.0, 1j)
    ((-0.0, 6.0), array([[-2.,  0.]]), (-4+0j))
    """
    if type(v_rel) is tuple:
        w2 = 2.0 * omega
        return (w2 * -v_rel[1], w2 * v_rel[0])
    if _real_array(v_rel):
        return (2.0 * _rate(omega)) * perp(v_rel)
    return (2.0 * omega * 1j) * v_rel
