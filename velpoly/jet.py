"""Second-order forward differentiation along a motion, vectorised over poses.

A :class:`Jet` is a scalar quantity f(q) of the generalised coordinates q
(each moving link's ``x, y, theta``), carried together with what kinematics
needs of it along a motion q(t):

* ``v`` -- the value f(q);
* ``g`` -- the gradient df/dq (a row of the constraint Jacobian);
* ``vd`` -- the rate  f' = g . q';
* ``h`` -- the velocity-product term of the second derivative,
  f'' = g . q'' + h, i.e. h = q'^T (d2f/dq2) q'.

The rules are the chain and product rules, e.g. for a product
``(ab)'' = a'' b + 2 a' b' + a b''``. Every field has a leading axis over
poses, so one evaluation serves a whole crank cycle; for a single pose the
values and rates may be plain floats and the gradient a vector (nq,) (the
same rules, cheaper than arrays of one element). With ``q' = 0`` the
rate terms vanish and only values and gradients are computed.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["Jet"]


def _cos_sin(v):
    """cos v and sin v: numpy's for arrays; for one pose's float, math's (the same values as numpy's
    on the platforms checked, tests/test_instant_speedups.py), which keep the jets' values plain
    floats: numpy's scalars cost ten times a float in every later operation."""
    if type(v) is float and math.isfinite(v):
        return math.cos(v), math.sin(v)
    return np.cos(v), np.sin(v)


def _scalar(v):
    """A float as a numpy scalar (numpy's inf and NaN where a float's division by zero or power would
    raise); arrays and numpy scalars as they are."""
    return np.float64(v) if type(v) is float else v


def _col(v):
    """v as the factor of a gradient: a column (N, 1) over poses, or one pose's float itself."""
    return v[:, None] if isinstance(v, np.ndarray) else v


class Jet:
    """A quantity with its gradient and first and second rates (see module doc)."""

    __slots__ = ("v", "g", "vd", "h")

    def __init__(self, v, g, vd, h):
        self.v = v    # (N,)
        self.g = g    # (N, nq)
        self.vd = vd  # (N,)
        self.h = h    # (N,)

    # -- construction ----------------------------------------------------------
    @staticmethod
    def const(c, n: int, nq: int | None) -> "Jet":
        """A constant (zero gradient and rates); ``nq = None``: values only."""
        z = np.zeros(n)
        return Jet(np.full(n, float(c)) if np.ndim(c) == 0 else np.asarray(c, float),
                   None if nq is None else np.zeros((n, nq)), z, z)

    @staticmethod
    def coordinate(q: np.ndarray, qd: np.ndarray, i: int, values_only: bool = False) -> "Jet":
        """The generalised coordinate ``q[:, i]`` itself (with no gradient if ``values_only``)."""
        n, nq = q.shape
        g = None
        if not values_only:
            g = np.zeros((n, nq))
            g[:, i] = 1.0
        return Jet(q[:, i].copy(), g, qd[:, i].copy(), np.zeros(n))

    # -- arithmetic --------------------------------------------------------------
    def __add__(self, o):
        if isinstance(o, Jet):
            return Jet(self.v + o.v, None if self.g is None else self.g + o.g, self.vd + o.vd, self.h + o.h)
        return Jet(self.v + o, self.g, self.vd, self.h)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, None if self.g is None else -self.g, -self.vd, -self.h)

    def __sub__(self, o):   # a - b is a + (-b) to the bit; one Jet made instead of two
        if isinstance(o, Jet):
            return Jet(self.v - o.v, None if self.g is None else self.g - o.g, self.vd - o.vd, self.h - o.h)
        return Jet(self.v - o, self.g, self.vd, self.h)

    def __rsub__(self, o):
        return Jet(o - self.v, None if self.g is None else -self.g, -self.vd, -self.h)

    def __mul__(self, o):
        if type(o) is float:   # a constant (a point's reference coordinate): the same products as below
            return Jet(self.v * o, None if self.g is None else self.g * o, self.vd * o, self.h * o)
        if isinstance(o, Jet):
            return Jet(self.v * o.v,
                       None if self.g is None else self.g * _col(o.v) + o.g * _col(self.v),
                       self.vd * o.v + self.v * o.vd,
                       self.h * o.v + 2.0 * self.vd * o.vd + self.v * o.h)
        o = np.asarray(o, float)
        return Jet(self.v * o, None if self.g is None else self.g * (o[..., None] if o.ndim else o),
                   self.vd * o, self.h * o)

    __rmul__ = __mul__

    def _unary(self, f, f1, f2):
        """f(self), given f, f' and f'' evaluated at ``self.v``."""
        return Jet(f, None if self.g is None else self.g * _col(f1), self.vd * f1,
                   self.h * f1 + f2 * (self.vd * self.vd))

    def cos_sin(self) -> tuple["Jet", "Jet"]:
        """(cos f, sin f), with cos' = -sin f', cos'' = -cos, sin' = cos f', sin'' = -sin (one cos
        and one sin of the value for both)."""
        c, s = _cos_sin(self.v)
        return self._unary(c, -s, -c), self._unary(s, c, -s)

    def cos(self):
        return self.cos_sin()[0]

    def sin(self):
        return self.cos_sin()[1]

    def sqrt(self):
        r = np.sqrt(self.v)
        return self._unary(r, 0.5 / r, -0.25 / (r * self.v))

    @staticmethod
    def atan2(y: "Jet", x: "Jet", ref: float = 0.0) -> "Jet":
        """The angle of the vector (x, y), unwrapped to within pi of ``ref``.

        theta' = (x y' - y x') / r^2. One pose's float values are taken as numpy scalars here: r^2 = 0
        or an overflow then gives inf or NaN as arrays do, not an exception.
        """
        xv, yv = _scalar(x.v), _scalar(y.v)
        r2 = xv ** 2 + yv ** 2
        ang = np.arctan2(yv, xv)
        ang = ref + np.mod(ang - ref + np.pi, 2 * np.pi) - np.pi
        g = None if x.g is None else (_col(xv) * y.g - _col(yv) * x.g) / _col(r2)
        cross_d = xv * y.vd - yv * x.vd
        vd = cross_d / r2
        h = (xv * y.h - yv * x.h) / r2 - 2.0 * cross_d * (xv * x.vd + yv * y.vd) / r2 ** 2
        return Jet(ang, g, vd, h)
