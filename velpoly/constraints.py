"""The joint constraints of a mechanism as equations in the links' coordinates.

Every moving link k has three generalised coordinates ``q = (x_k, y_k,
theta_k)``: the position of the point of the link that lies at the world
origin in the reference pose, and its rotation from the reference pose. A
point with reference position s on link k is therefore at::

    r_k(s) = (x_k, y_k) + R(theta_k) s,      so q = 0 is the reference pose.

Each joint contributes scalar equations Phi(q) = 0 (FORMAT.md section 5):

* pin at P between i and j:            r_i(P) - r_j(P) = 0                         (2)
* straight slider, block b, guide g:   theta_b - theta_g = 0,
                                       (r_b(P) - r_g(P)) . n_g = 0                 (2)
* circular slider about K:             r_b(K) - r_g(K) = 0                         (2)
* pin P of l in a straight slot of s:  (r_l(P) - r_s(P)) . n_s = 0                 (1)
* pin in a circular slot about K:      |r_l(P) - r_s(K)| - R = 0                   (1)
* contact with centres Ca, Cb:         |r_b(Cb) - r_a(Ca)| - D = 0   (a flat: the
                                       distance of the centre from the flat)       (1)
  and, rolling or with a prescribed slip, the integrated slip
                                       sigma = la (theta_a - phi) - lb (theta_b - phi)   (1)
  whose rate is the slip (V_P(a) - V_P(b)) . t (zero when rolling; a
  prescribed slip s is constant in time, so sigma = s t: in positions,
  with the driver at a constant rate, sigma - s d(q) / omega_d = 0, see
  :attr:`System.positions`);
* contact given by ``normal`` only:    velocity rows (V_P(a) - V_P(b)) . u = 0
                                       (and . t = slip), at the reference pose only.

Velocities solve J q' = w and accelerations J q'' = w' - h (see
:mod:`velpoly.jet`), with the driver's row added: theta_d = delta (crank)
or the slider's displacement along its path s = delta.
"""
from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .errors import InputError
from .jet import Grad, Jet, cos_sin_value
from .model import Mechanism
from .rigid import direction as _unit, dot as _dot

__all__ = ["Equation", "System", "build_system", "Frame", "contact_frame", "contact_slip_equation",
           "slider_coordinate"]


@dataclass(frozen=True)
class Equation:
    """One scalar constraint: its label, the links it couples, its function.

    ``dim`` is 1 for an equation in lengths and 0 for one in angles (for
    scaling). ``holonomic`` is False for velocity-only rows (contacts given
    by a normal, prescribed slips); ``rate`` is the prescribed value of the
    equation's rate (a slip speed; zero for ordinary joints). ``timed``
    marks an equation whose value grows at its constant ``rate`` along the
    motion, fn(q(t)) = rate t (a prescribed slip's integrated slip): it
    holds in positions once time is a function of the driver's position.
    Its ``fn(f, sigma)`` takes the value sigma it is expected to have there
    (default 0), by which an angle in it is unwrapped over many turns.
    """

    label: str
    links: tuple[str, ...]
    fn: Callable
    dim: int = 1
    holonomic: bool = True
    rate: float = 0.0
    timed: bool = False


def as_poses(q) -> np.ndarray:
    """q as poses (N, nq): ``np.atleast_2d(q)``, the very array where q is one (2-D) already, without
    the call's cost (a one-pose solve passes its arrays through a dozen functions that take poses)."""
    return q if type(q) is np.ndarray and q.ndim == 2 else np.atleast_2d(q)


class Frame:
    """The links' poses at some q as jets: the evaluation context of equations.

    A link's jets (x, y, cos theta, sin theta, theta) are built on first use. With
    ``one_pose`` (q holds a single pose) the jets' values and rates are plain floats and
    their gradients vectors (nq,): the same rules, without numpy's cost per operation on
    arrays of one element.
    """

    def __init__(self, system: "System", q: np.ndarray, qd: np.ndarray | None = None,
                 values_only: bool = False, one_pose: bool = False, dense: bool = False):
        q = as_poses(q)
        n, nq = q.shape
        self.n, self.nq = n, (None if values_only else nq)
        self.values_only = values_only
        self.scalar = one_pose and n == 1
        self.sparse = self.scalar and not dense   # one pose's gradients as Grad (the same bits as arrays)
        if self.scalar:   # the pose's coordinates and rates as floats
            self.q = q[0].tolist()
            self.qd = [0.0] * nq if qd is None else as_poses(qd)[0].tolist()
        else:
            self.q, self.qd = q, (np.zeros_like(q) if qd is None else as_poses(qd))
        self._index = system.index
        self._cache = {}
        self._points = {}
        self._chords = {}

    def _body(self, link: str):
        b = self._cache.get(link)
        if b is None:
            k = self._index.get(link)
            if k is None:
                return None
            if self.sparse and not self.values_only:
                b = self._sparse_body(3 * k)
            else:
                x, y, th = (self._coordinate(3 * k + i) for i in range(3))
                b = (x, y, *th.cos_sin(), th)
            self._cache[link] = b
        return b

    def _sparse_body(self, i: int) -> tuple:
        """One pose's (x, y, cos, sin, theta) jets of the link with coordinates i, i + 1, i + 2, made
        at once: :meth:`_coordinate`'s jets and :meth:`Jet.cos_sin`'s products (``Jet._unary``: the
        gradient times f', the rate times f', h f' + f'' rate^2 with h = 0), the same operations."""
        q, qd, n, t = self.q, self.qd, self.nq, i + 2
        v, w = q[t], qd[t]
        c, s = cos_sin_value(v)
        ms, mc, ww = -s, -c, w * w
        return (Jet(q[i], Grad({i: 1.0}, 0.0, n), qd[i], 0.0), Jet(q[i + 1], Grad({i + 1: 1.0}, 0.0, n), qd[i + 1], 0.0),
                Jet(c, Grad({t: 1.0 * ms}, 0.0 * ms, n), w * ms, 0.0 * ms + mc * ww),
                Jet(s, Grad({t: 1.0 * c}, 0.0 * c, n), w * c, 0.0 * c + ms * ww),
                Jet(v, Grad({t: 1.0}, 0.0, n), w, 0.0))

    def _coordinate(self, i: int) -> Jet:
        if self.scalar:
            g = None
            if self.sparse and not self.values_only:
                g = Grad({i: 1.0}, 0.0, self.nq)
            elif not self.values_only:
                g = np.zeros(self.nq)
                g[i] = 1.0
            return Jet(self.q[i], g, self.qd[i], 0.0)
        return Jet.coordinate(self.q, self.qd, i, self.values_only)

    def const(self, c) -> Jet:
        if self.scalar:
            g = None if self.values_only else Grad({}, 0.0, self.nq) if self.sparse else np.zeros(self.nq)
            return Jet(float(c), g, 0.0, 0.0)
        return Jet.const(c, self.n, self.nq)

    def theta(self, link: str) -> Jet:
        b = self._body(link)
        return self.const(0.0) if b is None else b[4]

    def point(self, link: str, s) -> tuple[Jet, Jet]:
        """r_link(s): the world position of the link's point s (reference coordinates).

        The frame's points are plain floats (constants: Jet arithmetic takes them as they are).
        """
        sx, sy = float(s[0]), float(s[1])
        b = self._body(link)
        if b is None:  # the frame
            return sx, sy
        x, y, c, s_, _ = b
        if self.sparse:   # one pose: the same operations fused, kept for the frame's other equations
            key = (link, sx, sy)
            p = self._points.get(key)
            if p is None:
                p = self._points[key] = (Jet.rotated(x, c, sx, s_, sy, False), Jet.rotated(y, s_, sx, c, sy, True))
            return p
        return x + c * sx - s_ * sy, y + s_ * sx + c * sy

    def chord(self, a: str, sa, b: str, sb) -> tuple:
        """r_a(sa) - r_b(sb): from b's point sb to a's point sa (reference coordinates, tuples of floats).

        Kept for the frame's other equations: a contact's normal and slip equations both take the one
        between its centres, a slider's path equation and a slider driver's coordinate the one at its
        point (the same jets, made once)."""
        key = (a, sa, b, sb)
        d = self._chords.get(key)
        if d is None:
            d = self._chords[key] = _sub(self.point(a, sa), self.point(b, sb))
        return d

    def direction(self, link: str, d) -> tuple[Jet, Jet]:
        """R(theta_link) d: a direction fixed to the link."""
        dx, dy = float(d[0]), float(d[1])
        b = self._body(link)
        if b is None:  # the frame: constants
            return dx, dy
        _, _, c, s_, _ = b
        if self.sparse:
            return Jet.rotated(None, c, dx, s_, dy, False), Jet.rotated(None, s_, dx, c, dy, True)
        return c * dx - s_ * dy, s_ * dx + c * dy


@dataclass(frozen=True)
class PinBlock:
    """Every pin's two equations, laid out for evaluation in bulk (built once per mechanism).

    Side 0 of pin p is its first link, side 1 its second (the frame indexed as an extra link
    at rest after the moving ones). ``theta``, ``x``, ``y`` index each side's coordinates in
    q padded with the frame's zeros; ``j0`` is the Jacobian's constant part (the +-1 of the
    origins' columns); ``flat`` and ``sign`` place each moving side's theta column.
    """

    ki: np.ndarray        # (L,) link index of each pin's first link, -1 for the frame
    kj: np.ndarray        # (L,) of its second link
    s: np.ndarray         # (L, 2) the pin's reference position
    sx: np.ndarray        # (2L,) sides 0 then sides 1: the pin's reference position
    sy: np.ndarray
    theta: np.ndarray     # (2L,) column of the side's theta_k in the padded q
    x: np.ndarray
    y: np.ndarray
    j0: np.ndarray        # (2L, nq)
    moving: np.ndarray    # (2L,) bool: the side is a moving link
    flat_x: np.ndarray    # flat (row, theta column) of the x row of each moving side, in jac (m, nq)
    flat_y: np.ndarray
    sign: np.ndarray      # (moving sides,) +1 for side 0, -1 for side 1

    @functools.cached_property
    def pinwise(self) -> list:
        """Each pin's (theta, x, y columns in the padded q of side 0, the same of side 1, reference x, y,
        whether side 0 and side 1 are moving links) as floats and ints (:func:`_pins_one`)."""
        n = len(self.ki)
        t, x, y, m = self.theta.tolist(), self.x.tolist(), self.y.tolist(), self.moving.tolist()
        return [(t[p], x[p], y[p], t[p + n], x[p + n], y[p + n], float(self.s[p, 0]), float(self.s[p, 1]),
                 m[p], m[p + n]) for p in range(n)]

    @functools.cached_property
    def flat_pinwise(self) -> np.ndarray:
        """``flat_x`` then ``flat_y``, each in the order of the pins (side 0 before side 1 of a pin):
        every theta column of the pins' rows for one assignment, as :func:`_pins_one` gathers them."""
        n = len(self.ki)
        sides = np.flatnonzero(self.moving)               # as flat_x lists them: sides 0, then sides 1
        order = np.lexsort((sides // n, sides % n))        # by pin, side 0 first
        return np.concatenate([self.flat_x[order], self.flat_y[order]])

    @staticmethod
    def build(ki, kj, s, nq: int) -> "PinBlock":
        n_pins = len(ki)
        k2 = np.concatenate([ki, kj])
        pad = np.where(k2 < 0, nq // 3, k2)            # the frame: the zero link after the moving ones
        sign2 = np.repeat([1.0, -1.0], n_pins)
        row2 = np.tile(2 * np.arange(n_pins), 2)
        moving = k2 >= 0
        j0 = np.zeros((2 * n_pins, nq))
        r, k, sg = row2[moving], k2[moving], sign2[moving]
        j0[r, 3 * k] = sg
        j0[r + 1, 3 * k + 1] = sg
        s = np.asarray(s, float)
        return PinBlock(np.asarray(ki), np.asarray(kj), s, np.tile(s[:, 0], 2), np.tile(s[:, 1], 2),
                        3 * pad + 2, 3 * pad, 3 * pad + 1, j0, moving, r * nq + 3 * k + 2, (r + 1) * nq + 3 * k + 2, sg)


def _pins_bulk(block: PinBlock, q, qd, phi, jac, h) -> int:
    """All pins at once: Phi = r_i(s) - r_j(s), with r_k(s) = x_k + R(theta_k) s.

    dr/dx_k = I, dr/dtheta_k = k x R s, and h = -theta_i'^2 R_i s + theta_j'^2 R_j s.
    ``jac`` and ``h`` (with ``qd``) are filled where given. Returns the number of rows (2 per pin).
    One pose goes to :func:`_pins_one`.
    """
    n, nq = q.shape
    if n == 1:
        return _pins_one(block, q, qd, phi, jac, h)
    n_pins = len(block.ki)
    qe = np.zeros((n, nq + 3))       # a zero "link" for the frame
    qe[:, :nq] = q
    th = qe[:, block.theta]          # (N, 2L)
    c, sn = np.cos(th), np.sin(th)
    sx, sy = block.sx, block.sy
    rx = c * sx - sn * sy
    ry = sn * sx + c * sy
    px, py = qe[:, block.x] + rx, qe[:, block.y] + ry
    phi[:, 0:2 * n_pins:2] = px[:, :n_pins] - px[:, n_pins:]
    phi[:, 1:2 * n_pins:2] = py[:, :n_pins] - py[:, n_pins:]
    if jac is not None:
        jac[:, :2 * n_pins] = block.j0
        flat = jac.reshape(n, -1)    # a view: jac is freshly allocated and contiguous
        flat[:, block.flat_x] = -block.sign * ry[:, block.moving]
        flat[:, block.flat_y] = block.sign * rx[:, block.moving]
    if h is not None and qd is not None:
        qe[:, :nq] = qd
        w2 = qe[:, block.theta] ** 2
        hx, hy = w2 * rx, w2 * ry
        h[:, 0:2 * n_pins:2] = hx[:, n_pins:] - hx[:, :n_pins]
        h[:, 1:2 * n_pins:2] = hy[:, n_pins:] - hy[:, :n_pins]
    return 2 * n_pins


def _pins_one(block: PinBlock, q, qd, phi, jac, h) -> int:
    """:func:`_pins_bulk` at one pose on plain floats: the same operations in the same order, pin by
    pin (each side's R(theta) s, its place x + R s, Phi = r_i - r_j, the theta columns -R s_y and
    R s_x signed, h = theta_j'^2 R_j s - theta_i'^2 R_i s), so the same bits (math's cos and sin are
    numpy's on the platforms checked: tests/test_instant_speedups.py). At one pose the arrays' cost
    per call was most of the pins' time (``solve`` evaluates them twice); each row's values are
    gathered in the one loop over the pins, in the order :attr:`PinBlock.pinwise` lays them out."""
    n_pins = len(block.ki)
    qe = q[0].tolist() + [0.0, 0.0, 0.0]   # a zero "link" for the frame
    cos, sin = math.cos, math.sin
    vals, rs, fx, fy = [], [], [], []
    for ti, xi, yi, tj, xj, yj, sx, sy, mi, mj in block.pinwise:
        th = qe[ti]
        c, sn = cos(th), sin(th)
        ui, vi = c * sx - sn * sy, sn * sx + c * sy
        th = qe[tj]
        c, sn = cos(th), sin(th)
        uj, vj = c * sx - sn * sy, sn * sx + c * sy
        vals.append((qe[xi] + ui) - (qe[xj] + uj))
        vals.append((qe[yi] + vi) - (qe[yj] + vj))
        rs.append((ui, vi, uj, vj))
        if mi:     # the theta columns: -sign R s_y in the x row, sign R s_x in the y row
            fx.append(-vi)
            fy.append(ui)
        if mj:
            fx.append(vj)
            fy.append(-uj)
    phi[0, :2 * n_pins] = vals
    if jac is not None:
        jac[0, :2 * n_pins] = block.j0
        jac.reshape(-1)[block.flat_pinwise] = fx + fy
    if h is not None and qd is not None:
        qe[:-3] = qd[0].tolist()
        hs = []
        for (ti, _, _, tj, *_), (ui, vi, uj, vj) in zip(block.pinwise, rs):
            wi, wj = qe[ti], qe[tj]
            wi2, wj2 = wi * wi, wj * wj
            hs.append(wj2 * uj - wi2 * ui)
            hs.append(wj2 * vj - wi2 * vi)
        h[0, :2 * n_pins] = hs
    return 2 * n_pins


def _rows_one(f: Frame, rest, start: int, phi, jac, h) -> None:
    """The equations ``rest`` at one pose's sparse frame ``f``, written from row ``start`` on: each
    jet's value and h-term gathered and stored with one assignment per array (the same floats that
    element by element assignments store; numpy's cost per item was a good part of a small system's
    evaluation), its gradient written into its row of ``jac`` (:meth:`Grad.into`; a dense one as is)."""
    rows = jac[0]
    vals, hs = [], []
    for i, e in enumerate(rest, start=start):
        j = e.fn(f)
        vals.append(j.v)
        hs.append(j.h)
        if type(j.g) is Grad:
            j.g.into(rows[i])
        else:
            rows[i] = j.g
    end = start + len(rest)
    phi[0, start:end] = vals
    h[0, start:end] = hs


def _sub(a, b):
    return a[0] - b[0], a[1] - b[1]


def _xy(s) -> tuple[float, float]:
    """A point's reference coordinates as a tuple of floats (a key of :meth:`Frame.chord`'s)."""
    return float(s[0]), float(s[1])


@dataclass(frozen=True)
class System:
    """The constraint equations of a mechanism and its coordinates' layout.

    ``index`` maps each moving link to its block of three coordinates;
    ``equations`` lists every joint equation; ``driver`` is the driver's
    coordinate function (crank angle or slider displacement).
    """

    mechanism: Mechanism
    index: dict
    equations: tuple[Equation, ...]
    driver: Equation
    size: float
    pin_block: PinBlock | None = None   # the first 2 x (number of pins) equations, evaluated in bulk
    crank: int = -1         # the crank driver's link index (its row is theta_k), -1 otherwise

    @property
    def nq(self) -> int:
        return 3 * len(self.index)

    @property
    def holonomic(self) -> bool:
        return all(e.holonomic for e in self.equations)

    @functools.cached_property
    def positions(self) -> "System":
        """The equations in positions alone, for reassembly (:func:`velpoly.pose.reassemble`).

        Every joint equation is one already, except a prescribed slip's. Its
        integrated slip sigma(q) (0 at the reference pose) grows at the slip s,
        constant in time (FORMAT.md section 5): sigma(q(t)) = s t. With the
        driver at a constant rate omega_d (a crank's alpha = 0, a slider
        driver's accel = 0; omega_d its omega or speed) the time is a function
        of the driver's coordinate d(q) (theta_d, or the slider's displacement;
        0 at the reference pose), t = d(q) / omega_d, and the slip holds in
        positions::

            sigma(q) - s d(q) / omega_d = 0

        Its rate is s - s = 0 and its second rate sigma'' - s d'' / omega_d =
        sigma'' (d'' = 0): the velocities and accelerations are those of the
        prescribed slip. Raises InputError when a row has no position form: a
        contact given by its normal (velocity rows only), or a non-zero slip
        with the driver accelerating or at rest (the slip accumulated on the
        way to a driver position then depends on the driver's history).
        """
        return _position_system(self)

    def evaluate(self, q, qd=None, driver: bool = True):
        """Values, Jacobian and h-terms of every equation (and the driver's last).

        Returns ``(phi, jac, h)`` with shapes (N, m), (N, m, nq), (N, m).
        """
        q = as_poses(q)
        n, nq = q.shape
        m_all = len(self.equations) + (1 if driver else 0)
        phi = np.zeros((n, m_all))
        jac = np.zeros((n, m_all, nq))
        h = np.zeros((n, m_all))
        start = 0
        if self.pin_block is not None:
            start = _pins_bulk(self.pin_block, q, qd, phi, jac, h)
        rest = list(self.equations[start:])
        crank = driver and self.crank >= 0
        if driver and not crank:
            rest.append(self.driver)
        if rest:
            f = Frame(self, q, qd, one_pose=True)
            if f.sparse:
                _rows_one(f, rest, start, phi, jac, h)
            else:
                for i, e in enumerate(rest, start=start):
                    j = e.fn(f)
                    phi[:, i], h[:, i] = j.v, j.h
                    if type(j.g) is Grad:
                        j.g.into(jac[0, i])
                    else:
                        jac[:, i] = j.g
        if crank:
            k = self.crank
            phi[:, -1] = q[:, 3 * k + 2]
            jac[:, -1, 3 * k + 2] = 1.0
        return phi, jac, h

    def residual(self, q, driver: bool = True) -> np.ndarray:
        """The equations' values Phi(q) alone (N, m): no Jacobian is built for the pins."""
        return self._values(q, None, driver)[0]

    def second_terms(self, q, qd, driver: bool = True) -> np.ndarray:
        """The h-terms alone (N, m): Phi'' = J q'' + h, without building the Jacobian again
        (for the accelerations once the velocities are solved with the Jacobian)."""
        return self._values(q, qd, driver)[1]

    def _values(self, q, qd, driver: bool):
        """Phi(q) and, with qd, h = q'^T (d2 Phi/dq2) q' (else None); no gradients."""
        q = as_poses(q)
        n, nq = q.shape
        m_all = len(self.equations) + (1 if driver else 0)
        phi = np.zeros((n, m_all))
        h = None if qd is None else np.zeros((n, m_all))
        qd = None if qd is None else as_poses(qd)
        start = _pins_bulk(self.pin_block, q, qd, phi, None, h) if self.pin_block is not None else 0
        rest = list(self.equations[start:])
        crank = driver and self.crank >= 0
        if driver and not crank:
            rest.append(self.driver)
        if rest:
            f = Frame(self, q, qd, values_only=True, one_pose=True)
            for i, e in enumerate(rest, start=start):
                j = e.fn(f)
                phi[:, i] = j.v
                if h is not None:
                    h[:, i] = j.h
        if crank:
            phi[:, -1] = q[:, 3 * self.crank + 2]   # theta_d: no h-term
        return phi, h

    def scale_matrix(self, jac: np.ndarray, rows: list[int] | None = None,
                     driver: bool = True) -> np.ndarray:
        """The Jacobian in unit lengths (lengths divided by the mechanism's size)."""
        row, col = self._scales
        if rows is None:
            row = row[:len(row) - (0 if driver else 1)][:, None]
        else:   # the rows' scales as a column, made once for each set of rows (the velocities' every pose)
            key = tuple(rows)
            row = self._row_scales.get(key)
            if row is None:
                row = self._row_scales[key] = row_all = self._scales[0][list(rows)][:, None]
                row_all.setflags(write=False)
        return jac * row * col[None, :]

    @property
    def column_scales(self) -> np.ndarray:
        """Each coordinate's unit (read-only): the mechanism's size L for a link's x and y, 1.0 for its
        angle; dividing by it divides the lengths by L and leaves the angles exactly as they are."""
        return self._scales[1]

    @functools.cached_property
    def _row_scales(self) -> dict:
        return {}

    @functools.cached_property
    def _scales(self) -> tuple[np.ndarray, np.ndarray]:
        """Row scales of every equation and the driver's (1/L for lengths), column scales (L for x, y)."""
        L = self.size
        col = np.ones(self.nq)
        col[0::3] = L
        col[1::3] = L
        row = np.array([1.0 / L if e.dim == 1 else 1.0 for e in self.equations + (self.driver,)])
        col.setflags(write=False)
        return row, col


def _position_system(system: System) -> System:
    """:attr:`System.positions` (see there)."""
    if system.holonomic:
        return system
    m = system.mechanism
    if not all(e.holonomic or e.timed for e in system.equations):
        bad = next(i for i, c in enumerate(m.contacts) if c.centres is None)
        raise InputError("only the drawn pose can be analysed: this contact, given by its normal, has no "
                         "position equation", where=f"contacts[{bad}]", file=m.source,
                         hint="give the contact's centres of curvature to analyse other driver positions "
                              "or a whole cycle")
    drv = m.driver
    rate, accel, name = (drv.speed, drv.accel, "accel") if drv.is_slider else (drv.omega, drv.alpha, "alpha")
    timed = [e for e in system.equations if e.timed and e.rate != 0.0]
    if timed and (accel != 0.0 or rate == 0.0):
        bad = next(i for i, c in enumerate(m.contacts) if c.slip)
        why = (f"the driver accelerates ({name} = {accel:g})" if accel != 0.0 else "the driver is at rest")
        raise InputError(f"only the drawn pose can be analysed: the prescribed slip is constant in time and {why}, "
                         "so the slip accumulated on the way to another driver position, and with it the pose "
                         "there, depends on the driver's history, not on its position",
                         where=f"contacts[{bad}]", file=m.source,
                         hint=(f"give the driver a constant rate ({name} = 0)" if accel != 0.0 else
                               f"give the driver a non-zero {'speed' if drv.is_slider else 'omega'}")
                              + " to analyse other driver positions or a whole cycle")
    d = system.driver.fn

    def in_positions(e: Equation) -> Equation:
        if not e.timed:
            return e
        k = e.rate / rate if e.rate != 0.0 else 0.0     # s / omega_d: t = d(q) / omega_d
        if k == 0.0:
            return Equation(e.label, e.links, e.fn, e.dim)

        def fn(f, g=e.fn, k=k):
            t = k * d(f)                  # s t = s d(q) / omega_d: the slip so far
            return g(f, t.v) - t
        return Equation(e.label, e.links, fn, e.dim)
    return dataclasses.replace(system, equations=tuple(in_positions(e) for e in system.equations))


def _coincide(lab: str, a: str, b: str, s) -> list[Equation]:
    """Links a and b share their point with reference position s: r_a(s) - r_b(s) = 0 (x, y)."""
    return [Equation(lab, (a, b), lambda f: f.point(a, s)[0] - f.point(b, s)[0]),
            Equation(lab, (a, b), lambda f: f.point(a, s)[1] - f.point(b, s)[1])]


def _on_line(lab: str, a: str, b: str, s, n) -> Equation:
    """a's point s stays on b's straight path through s with normal n (reference pose):
    (r_a(s) - r_b(s)) . R_b n = 0 (with n along the path instead: a's travel along it)."""
    s = _xy(s)
    return Equation(lab, (a, b), lambda f: _dot(f.chord(a, s, b, s), f.direction(b, n)))


def _on_circle(lab: str, a: str, b: str, s, k) -> Equation:
    """a's point s stays on b's circle about k through s: |r_a(s) - r_b(k)| - |s - k| = 0."""
    r0 = float(np.hypot(*(s - k)))

    def fn(f):
        d = _sub(f.point(a, s), f.point(b, k))
        return _dot(d, d).sqrt() - r0
    return Equation(lab, (a, b), fn)


def _joint_equations(m: Mechanism, P: dict) -> list[Equation]:
    """The pins', sliders' and slots' equations: a pin's two links coincide at it; a block on a
    straight path keeps its guide's angle and its point on the path, on a circular path its
    path's centre coincides with the guide's; a pin in a straight slot stays on the slot's line,
    in a circular slot on its circle."""
    eqs: list[Equation] = []
    for pin in m.pins:
        i, j = pin.links
        eqs += _coincide(f"pin {pin.point} ({i}, {j})", i, j, P[pin.point])
    for sl in m.sliders:
        b, g = sl.block, sl.guide
        lab = f"slider {sl.point} (block {b} on {g})"
        if sl.centre is None:
            eqs.append(Equation(lab, (b, g), lambda f, b=b, g=g: f.theta(b) - f.theta(g), dim=0))
            eqs.append(_on_line(lab, b, g, P[sl.point], _unit(sl.angle + 90.0)))
        else:
            eqs += _coincide(lab, b, g, P[sl.centre])
    for sl in m.slots:
        lab = f"slot {sl.pin} (pin of {sl.link} in {sl.slot})"
        if sl.centre is None:
            eqs.append(_on_line(lab, sl.link, sl.slot, P[sl.pin], _unit(sl.angle + 90.0)))
        else:
            eqs.append(_on_circle(lab, sl.link, sl.slot, P[sl.pin], P[sl.centre]))
    return eqs


def build_system(m: Mechanism) -> System:
    """Translate the mechanism's joints and driver into constraint equations Phi(q) = 0
    (pins, sliders, slots, contacts in that order), the driver's coordinate and every pin's
    equations as one :class:`PinBlock`."""
    index = {k.name: i for i, k in enumerate(m.moving_links)}
    P = {name: np.array(xy, float) for name, xy in m.points.items()}
    eqs = _joint_equations(m, P)
    for c in m.contacts:
        eqs.extend(_contact_equations(m, c, P))

    drv = m.driver
    if drv.is_slider:
        sl = next(x for x in m.sliders if x.point == drv.slider)
        driver = _slider_coordinate(sl, P, f"driver slider {sl.point}")
    else:
        d = drv.link
        driver = Equation(f"driver {d}", (d,), lambda f, d=d: f.theta(d), dim=0)
    pins = m.pins
    block = None
    if pins:
        block = PinBlock.build(np.array([index.get(p.links[0], -1) for p in pins]),
                               np.array([index.get(p.links[1], -1) for p in pins]),
                               np.array([P[p.point] for p in pins], float), 3 * len(index))
    crank = -1 if drv.is_slider else index[drv.link]
    return System(m, index, tuple(eqs), driver, m.size, block, crank)


def contact_slip_equation(m: Mechanism, c) -> Equation | None:
    """The integrated slip of a contact with centres (its rate is the slip velocity)."""
    P = {name: np.array(xy, float) for name, xy in m.points.items()}
    return _contact_equations(m, c, P, with_slip=True)[1]


def slider_coordinate(m: Mechanism, sl) -> Equation:
    """The block's displacement along its path from the reference pose (an Equation)."""
    P = {name: np.array(xy, float) for name, xy in m.points.items()}
    return _slider_coordinate(sl, P, f"slider {sl.point}")


def _slider_coordinate(sl, P, label) -> Equation:
    """The block's displacement along its path from the reference pose.

    Straight path: s = (r_b(P) - r_g(P)) . d_g; circular: s = R (theta_b - theta_g).
    """
    b, g = sl.block, sl.guide
    s = P[sl.point]
    if sl.centre is None:
        return _on_line(label, b, g, s, _unit(sl.angle))
    r = float(np.hypot(*(s - P[sl.centre])))
    return Equation(label, (b, g), lambda f: r * (f.theta(b) - f.theta(g)))


def contact_frame(m: Mechanism, c, P=None):
    """The contact's common normal u (from a to b) and tangent t at the reference pose.

    Also returns the signed distances la = (P - Ca) . u and lb = (P - Cb) . u
    (None for a flat profile or a contact given by its normal).
    """
    P = P or {name: np.array(xy, float) for name, xy in m.points.items()}
    p = P[c.point]
    la = lb = None
    if c.centres is None:
        u = _unit(c.normal)
    else:
        ca, cb = c.centres
        if ca is not None and cb is not None:
            u = P[cb] - P[ca]
        elif ca is None:  # flat on a: from P towards Cb
            u = P[cb] - p
        else:             # flat on b: from Ca towards P
            u = p - P[ca]
        nu = float(np.hypot(*u))
        u = u / nu
        if ca is not None:
            la = float(np.dot(p - P[ca], u))
        if cb is not None:
            lb = float(np.dot(p - P[cb], u))
    t = np.array([-u[1], u[0]])
    return u, t, la, lb


def _contact_equations(m: Mechanism, c, P, with_slip: bool = False):
    """The contact's equations; with ``with_slip`` also its slip equation (whose rate is
    the slip velocity), whether or not it constrains the motion (None without centres)."""
    a, b = c.links
    p = P[c.point]
    u, t, la, lb = contact_frame(m, c, P)
    lab = f"{c.kind} contact {c.point} ({a}, {b})"
    tangential = c.kind == "rolling" or c.slip is not None
    rate = float(c.slip or 0.0)
    if c.centres is None:
        out = [Equation(lab, (a, b), lambda f: _dot(_sub(f.point(a, p), f.point(b, p)), (u[0], u[1])),
                        holonomic=False)]
        if tangential:
            out.append(Equation(lab, (a, b), lambda f: _dot(_sub(f.point(a, p), f.point(b, p)), (t[0], t[1])),
                                holonomic=False, rate=rate))
        return (out, None) if with_slip else out
    ca, cb = c.centres
    if ca is not None and cb is not None:
        A, B = P[ca], P[cb]
        D = float(np.hypot(*(B - A)))
        A_, B_ = _xy(A), _xy(B)
        phi0 = float(np.arctan2(u[1], u[0]))

        def normal_eq(f):
            d = f.chord(b, B_, a, A_)
            return _dot(d, d).sqrt() - D

        def slip_eq(f, sigma=0.0):
            d = f.chord(b, B_, a, A_)
            ta, tb = f.theta(a), f.theta(b)
            # the line of centres' turn, unwrapped near the value that the slip sigma implies
            # (D = la - lb), phi = (la theta_a - lb theta_b - sigma) / D, so that it stays
            # continuous over many turns (sigma = 0 rolling, s t with a prescribed slip s)
            near = phi0 + (la * ta.v - lb * tb.v - sigma) / D
            phi = Jet.atan2(d[1], d[0], near) - phi0
            return la * (ta - phi) - lb * (tb - phi)
    else:
        # one flat profile: the curved link c_ (centre C, signed distance l) and flat link fl;
        # written with the normal pointing from the curved profile's centre towards P.
        if cb is None:   # flat on b, u from Ca to P
            cur, fl, C, l_, uu = a, b, P[ca], la, u
        else:            # flat on a: use u' = -u from Cb towards P
            cur, fl, C, l_, uu = b, a, P[cb], -lb, -u
        tt = np.array([-uu[1], uu[0]])
        C_, p_ = _xy(C), _xy(p)
        # the rate of slip_eq is (V_P(cur) - V_P(fl)) . tt = (V_P(a) - V_P(b)) . t either way

        def normal_eq(f):
            return _dot(f.chord(cur, C_, fl, p_), f.direction(fl, uu)) + l_

        def slip_eq(f, sigma=0.0):
            return _dot(f.chord(cur, C_, fl, p_), f.direction(fl, tt)) \
                + l_ * (f.theta(cur) - f.theta(fl))
    out = [Equation(lab, (a, b), normal_eq)]
    slip = Equation(lab, (a, b), slip_eq, holonomic=c.slip is None, rate=rate, timed=c.slip is not None)
    if tangential:
        out.append(slip)
    return (out, slip) if with_slip else out
