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

__all__ = ["Jet", "Grad", "cos_sin_value"]


def cos_sin_value(v):
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


class Grad:
    """One pose's gradient (nq,) held sparsely: ``d`` maps columns to values, and every other
    column has the value ``z`` (0.0 for most; -0.0, or NaN, where a dense gradient's untouched
    columns would have become that).

    Each operation is the dense array's elementwise one column by column, in the same order, on the
    same float64 values (Python's float arithmetic is IEEE double, as numpy's): the columns it holds
    are computed as the dense array's are, and every column it does not hold has, in the dense
    array, the same inputs in every operation so far, hence the same value, ``z`` computed once.
    A one-pose equation touches the three columns of each of its two or three links: a few float
    operations instead of numpy's cost per call on short arrays (``dense`` gives the array, bit for
    bit the one the arrays would have made, signs of zeros and NaNs included).
    """

    __slots__ = ("d", "z", "n")
    __array_ufunc__ = None     # numpy's scalars and arrays leave their operations with it to it

    def __init__(self, d: dict, z: float, n: int):
        self.d = d     # {column: value}
        self.z = z     # every other column's value
        self.n = n     # nq

    def dense(self) -> np.ndarray:
        """The gradient as an array (nq,)."""
        return self.into(np.zeros(self.n))

    def into(self, row: np.ndarray) -> np.ndarray:
        """Write the gradient into ``row`` (nq,), which holds zeros (0.0, not -0.0)."""
        z = self.z
        if not (z == 0.0 and math.copysign(1.0, z) > 0.0):   # -0.0 or NaN in the other columns
            row.fill(z)
        for k, v in self.d.items():
            row[k] = v
        return row

    def __add__(self, o):
        if type(o) is not Grad:
            return self.dense() + o
        oz, od, sz = o.z, o.d, self.z
        d = {k: v + od.get(k, oz) for k, v in self.d.items()}
        for k, v in od.items():
            if k not in d:
                d[k] = sz + v
        return Grad(d, sz + oz, self.n)

    def __sub__(self, o):
        if type(o) is not Grad:
            return self.dense() - o
        oz, od, sz = o.z, o.d, self.z
        d = {k: v - od.get(k, oz) for k, v in self.d.items()}
        for k, v in od.items():
            if k not in d:
                d[k] = sz - v
        return Grad(d, sz - oz, self.n)

    def __neg__(self):
        return Grad({k: -v for k, v in self.d.items()}, -self.z, self.n)

    def __mul__(self, c):
        if isinstance(c, np.ndarray) and c.ndim:
            return self.dense() * c
        return Grad({k: v * c for k, v in self.d.items()}, self.z * c, self.n)

    def __rmul__(self, c):
        if isinstance(c, np.ndarray) and c.ndim:
            return c * self.dense()
        return Grad({k: c * v for k, v in self.d.items()}, c * self.z, self.n)

    @staticmethod
    def lin2(a: "Grad", fa, b: "Grad", fb, plus: bool) -> "Grad":
        """``a * fa + b * fb`` (``plus``) or ``a * fa - b * fb``, column by column in one pass (the
        products of a jets' product rule, of atan2's numerator)."""
        ad, bd = a.d, b.d
        az, bz = a.z * fa, b.z * fb
        d = {}
        for k, v in ad.items():
            w = v * fa
            u = bd[k] * fb if k in bd else bz
            d[k] = w + u if plus else w - u
        for k, v in bd.items():
            if k not in ad:
                d[k] = az + v * fb if plus else az - v * fb
        return Grad(d, az + bz if plus else az - bz, a.n)

    def __radd__(self, o):
        return o + self.dense()

    def __rsub__(self, o):
        return o - self.dense()

    def __truediv__(self, c):
        if isinstance(c, np.ndarray) and c.ndim:
            return self.dense() / c
        if type(c) is float:   # numpy's inf or NaN for a division by zero, as the array's, not an exception
            c = np.float64(c)
        return Grad({k: v / c for k, v in self.d.items()}, self.z / c, self.n)


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
            if type(self.g) is Grad and type(o.g) is Grad:
                g = Grad.lin2(self.g, o.v, o.g, self.v, True)
            else:
                g = None if self.g is None else self.g * _col(o.v) + o.g * _col(self.v)
            return Jet(self.v * o.v, g,
                       self.vd * o.v + self.v * o.vd,
                       self.h * o.v + 2.0 * self.vd * o.vd + self.v * o.h)
        o = np.asarray(o, float)
        return Jet(self.v * o, None if self.g is None else self.g * (o[..., None] if o.ndim else o),
                   self.vd * o, self.h * o)

    __rmul__ = __mul__

    @staticmethod
    def rotated(a: "Jet | None", b: "Jet", fb: float, c: "Jet", fc: float, plus: bool) -> "Jet":
        """``a + b * fb + c * fc`` (``plus``) or ``a + b * fb - c * fc`` for one pose's jets with
        :class:`Grad` gradients (or none) and float factors: a point or direction of a link,
        ``x + cos * sx - sin * sy`` and the like, without ``a`` when it is None. The same operations
        in the same order as the jets' arithmetic, in one pass and without the jets between."""
        v, vd, h = b.v * fb, b.vd * fb, b.h * fb
        if a is not None:
            v, vd, h = a.v + v, a.vd + vd, a.h + h
        cv, cvd, ch = c.v * fc, c.vd * fc, c.h * fc
        if plus:
            v, vd, h = v + cv, vd + cvd, h + ch
        else:
            v, vd, h = v - cv, vd - cvd, h - ch
        if b.g is None:
            return Jet(v, None, vd, h)
        bd, cd = b.g.d, c.g.d
        bz, cz = b.g.z * fb, c.g.z * fc     # the factors' products in the columns they do not hold
        if len(bd) == 1 and len(cd) == 1 and (a is None or len(a.g.d) == 1):
            d = _rotated_one_column(a, bd, fb, cd, fc, bz, cz, plus)
            if d is not None:
                z = bz if a is None else a.g.z + bz
                return Jet(v, Grad(d, z + cz if plus else z - cz, b.g.n), vd, h)
        keys = bd.keys() | cd.keys()
        if a is not None:
            ad, az = a.g.d, a.g.z
            keys |= ad.keys()
        d = {}
        for k in keys:
            t = bd[k] * fb if k in bd else bz
            if a is not None:
                t = (ad[k] if k in ad else az) + t
            u = cd[k] * fc if k in cd else cz
            d[k] = t + u if plus else t - u
        z = bz if a is None else az + bz
        return Jet(v, Grad(d, z + cz if plus else z - cz, b.g.n), vd, h)

    def _unary(self, f, f1, f2):
        """f(self), given f, f' and f'' evaluated at ``self.v``."""
        return Jet(f, None if self.g is None else self.g * _col(f1), self.vd * f1,
                   self.h * f1 + f2 * (self.vd * self.vd))

    def cos_sin(self) -> tuple["Jet", "Jet"]:
        """(cos f, sin f), with cos' = -sin f', cos'' = -cos, sin' = cos f', sin'' = -sin (one cos
        and one sin of the value for both)."""
        c, s = cos_sin_value(self.v)
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
        if type(x.g) is Grad and type(y.g) is Grad:
            g = Grad.lin2(y.g, xv, x.g, yv, False) / r2
        else:
            g = None if x.g is None else (_col(xv) * y.g - _col(yv) * x.g) / _col(r2)
        cross_d = xv * y.vd - yv * x.vd
        vd = cross_d / r2
        h = (xv * y.h - yv * x.h) / r2 - 2.0 * cross_d * (xv * x.vd + yv * y.vd) / r2 ** 2
        return Jet(ang, g, vd, h)


def _rotated_one_column(a, bd: dict, fb, cd: dict, fc, bz, cz, plus: bool) -> dict | None:
    """:meth:`Jet.rotated`'s gradient columns where ``b`` and ``c`` hold the same one column (a link's
    cos and sin: its angle's) and ``a`` none or another one (the link's x or y): the loop's
    operations on each of the two columns written out, without building the set of columns; None
    for any other layout (the loop serves)."""
    (k, vb), = bd.items()
    if k not in cd:
        return None
    u = cd[k] * fc
    if a is None:
        t = vb * fb
        return {k: t + u if plus else t - u}
    ad = a.g.d
    (ka, va), = ad.items()
    if ka == k:
        return None
    t = a.g.z + vb * fb
    ta = va + bz
    return {k: t + u if plus else t - u, ka: ta + cz if plus else ta - cz}
