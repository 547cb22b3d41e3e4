"""Analytic kinematics: mobility, velocities and accelerations by linear solves.

With the joint equations Phi(q) = 0 of :mod:`velpoly.constraints` and the
driver's coordinate d(q) = delta, the velocities solve one linear system::

    [J_Phi]        [w ]                        [J_Phi]         [w' - h_Phi]
    [J_d  ] q'  =  [d'],    the accelerations  [J_d  ] q''  =  [d'' - h_d ]

(w: prescribed slip rates, h: the velocity-product terms). Each link's
twist follows: omega_k = theta_k', and a point P of link k moves with
``V_P = V_O + omega x R_PO``, ``A_P = A_O + alpha x R_PO - omega^2 R_PO``.
Everything is batched over poses (leading axis N).

Mobility is 3(n-1) minus the rank of the joint equations (FORMAT.md
section 5): the generic rank, at a random configuration, separates
structurally redundant joints (counted once) from a pose that merely
loses rank (a change point: a singular pose).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .constraints import System, as_poses, build_system
from .errors import InputError, SingularPoseError
from .model import Mechanism
from .pose import select_rows

__all__ = ["Kinematics", "prepare", "velocities", "accelerations", "condition", "involved_links", "SINGULAR",
           "WARN", "singular_hint", "velocity_error_bound"]

SINGULAR = 1e10   # condition number above which a pose is singular (exit 3)
WARN = 1e6        # above which results carry a warning


@dataclass(frozen=True)
class Kinematics:
    """A mechanism's equations, ready to solve: the system and its independent rows.

    ``rows`` indexes the independent joint equations followed by the
    driver's row (the last equation of :meth:`System.evaluate`).
    """

    mechanism: Mechanism
    system: System
    rows: tuple[int, ...]
    mobility: int


def _scaled_rank(system: System, jac: np.ndarray, rows=None, driver=False) -> tuple[int, np.ndarray]:
    a = system.scale_matrix(jac, rows, driver=driver)
    if a.size == 0:
        return 0, np.zeros(0)
    sv = np.linalg.svd(a, compute_uv=False)
    return int((sv > SINGULAR ** -1 * sv.max()).sum()) if sv.max() > 0 else 0, sv


_PREPARED: dict = {}


def prepare(m: Mechanism) -> Kinematics:
    """Build the equations, check the mobility is 1 and the reference pose regular.

    The result is cached per mechanism object (mechanisms are immutable).
    """
    hit = _PREPARED.get(id(m))
    if hit is not None and hit.mechanism is m:
        return hit
    kin = _prepare(m)
    if len(_PREPARED) > 64:
        _PREPARED.clear()
    _PREPARED[id(m)] = kin
    return kin


def _prepare(m: Mechanism) -> Kinematics:
    """Mobility from the rank of the joint equations at the reference pose (FORMAT.md section 5).

    The rank at a random, unassembled configuration is the structural rank:
    where the reference pose's rank is lower, either a joint is redundant on
    the assembled mechanism (a wheel rolling on a drum whose centre distance
    an arm already fixes) -- then the mechanism really moves, which a small
    step of the driver shows -- or the pose is a change point: a singular pose.
    """
    system = build_system(m)
    nq = system.nq
    if nq == 0:
        raise InputError("the mechanism has no moving link (mobility 0)", where="links", file=m.source,
                         hint="add the links that move, each listing its points")
    m_eq = len(system.equations)
    _, j0, _ = system.evaluate(np.zeros((1, nq)), driver=False)
    rows = select_rows(system, system.scale_matrix(j0[0], driver=False), tol=1e-10)
    mobility = nq - len(rows)
    rng = np.random.default_rng(20261122)
    qg = rng.uniform(-1, 1, (1, nq))
    qg[:, 0::3] *= 0.3 * system.size
    qg[:, 1::3] *= 0.3 * system.size
    _, jg, _ = system.evaluate(qg)
    rows_g = select_rows(system, system.scale_matrix(jg[0][:m_eq], driver=False), tol=1e-8)
    structural = nq - len(rows_g)

    def changes() -> tuple[str, ...]:   # the links a singular-pose error names (an SVD: only for the error)
        return _involved(system, j0[0], list(range(m_eq)), False) if m_eq else ()

    if mobility != 1:
        if structural == 1 and mobility > 1:
            raise SingularPoseError(
                "singular pose: the joints lose independence at the reference pose (a change point)",
                where="links", file=m.source, links=changes(),
                hint="draw the mechanism in a pose away from the change point")
        raise InputError(
            f"mobility is {mobility} (3 x {len(m.moving_links)} moving-link coordinates minus "
            f"{len(rows)} independent joint constraints), must be 1 for one driver",
            where="links", file=m.source,
            hint=("add the joints that are missing (a point shared by two links is a pin)"
                  if mobility > 1 else "remove a joint or a link: the mechanism is locked"))
    if structural == 1 and _scaled_rank(system, jg[0][list(rows_g) + [m_eq]], list(rows_g) + [m_eq],
                                        driver=True)[0] < nq:
        raise InputError("the driver's motion is fixed by the joints: it cannot drive the mechanism",
                         where="driver", file=m.source, hint="drive a link the joints leave free")
    kin = Kinematics(m, system, tuple(rows) + (m_eq,), mobility)
    if len(rows_g) > len(rows) and not _moves(kin):
        raise SingularPoseError(
            "singular pose: the joints lose independence at the reference pose (a change point)",
            where="links", file=m.source, links=changes(),
            hint="draw the mechanism in a pose away from the change point")
    return kin


def _moves(kin: Kinematics) -> bool:
    """Whether a small driver step keeps every joint equation satisfied at the same rank.

    Distinguishes a joint redundant on the assembled mechanism (it moves) from
    an infinitesimal mechanism at a change point (it does not).
    """
    from .pose import reassemble
    system = kin.system
    if not system.holonomic:
        return True   # velocity-only rows: nothing to move along; the reference rank stands
    h = 1e-3 if not kin.mechanism.driver.is_slider else 1e-3 * system.size
    for step in (h, -h):
        try:
            r = reassemble(system, list(kin.rows), [step], coarse=2 * h)
        except Exception:
            return False
        if len(r.deltas) != 1:
            return False
        phi = system.residual(r.q)[:, :len(system.equations)]
        if np.abs(phi).max() > 1e-9 * max(system.size, 1.0):
            return False
    return True


def involved_links(kin: Kinematics, q) -> tuple[str, ...]:
    """The links that come into line at the pose q (those moving in the near-null direction
    of the velocity equations): what a singular-pose error names."""
    _, jac, _ = kin.system.evaluate(as_poses(q)[:1])
    return _involved(kin.system, jac[0][list(kin.rows)], list(kin.rows), True)


def _involved(system: System, jac, rows, driver) -> tuple[str, ...]:
    """The links that move in the matrix's near-null direction (those coming into line)."""
    a = system.scale_matrix(jac, rows, driver=driver)
    _, _, vt = np.linalg.svd(a)
    v = vt[-1]
    names = list(system.index)
    w = np.array([np.abs(v[3 * i:3 * i + 3]).max() for i in range(len(names))])
    if w.max() == 0:
        return tuple(names)
    return tuple(n for n, x in zip(names, w) if x > 0.05 * w.max())


def _rates(kin: Kinematics) -> np.ndarray:
    """The velocity equations' right-hand side (each row's rate, the driver's last), made once per
    Kinematics (read-only: callers copy it)."""
    w = kin.__dict__.get("_rates")
    if w is None:
        eqs = kin.system.equations + (kin.system.driver,)
        drv = kin.mechanism.driver
        w = np.array([e.rate for e in eqs])
        w[-1] = drv.speed if drv.is_slider else drv.omega
        w = w[list(kin.rows)]
        w.setflags(write=False)
        kin.__dict__["_rates"] = w   # a frozen dataclass: kept beside its fields, as a cached_property would
    return w


def _row_index(kin: Kinematics) -> np.ndarray:
    """``kin.rows`` as an index array, made once per Kinematics: ``jac.take(index, axis=1)`` selects
    the rows as ``jac[:, list(kin.rows)]`` does, without converting the list at every pose."""
    index = kin.__dict__.get("_row_index")
    if index is None:
        index = np.array(kin.rows, dtype=np.intp)
        index.setflags(write=False)
        kin.__dict__["_row_index"] = index   # beside the frozen fields, as _rates keeps its own
    return index


def _scaled_cond(system: System, a: np.ndarray, rows) -> np.ndarray:
    """2-norm condition numbers of the batch of matrices a, in unit lengths.

    For many poses the Frobenius estimate ||A|| ||A^-1|| (at most n times the
    2-norm value) screens them; poses it cannot clear are measured exactly (SVD).
    """
    s = system.scale_matrix(a, rows)
    if len(s) == 1:
        return _cond_one(s)
    if len(s) <= 8:
        return np.linalg.cond(s)
    try:
        inv = np.linalg.inv(s)
    except np.linalg.LinAlgError:
        return np.linalg.cond(s)
    est = np.linalg.norm(s, axis=(1, 2)) * np.linalg.norm(inv, axis=(1, 2))
    cond = est / np.sqrt(s.shape[1])   # a lower bound of the 2-norm condition number...
    unsure = ~(est <= WARN)             # ...exact where it matters
    if unsure.any():
        cond[unsure] = np.linalg.cond(s[unsure])
    return cond


def _cond_one(s: np.ndarray) -> np.ndarray:
    """``np.linalg.cond(s)`` of one matrix (1, n, n): its largest singular value over its smallest,
    divided as floats (inf where the smallest is 0 and s holds no NaN, as numpy makes it)."""
    sv = np.linalg.svd(s, compute_uv=False)[0]
    big, small = float(sv[0]), float(sv[-1])
    if small != 0.0:
        r = big / small
    else:   # numpy's x / 0: inf (nan for 0 / 0 or nan / 0, then inf where s holds no NaN)
        r = math.copysign(math.inf, big) if big != 0.0 and big == big else math.nan
    if r != r and not np.isnan(s).any():
        r = math.inf
    return np.array([r])


def condition(kin: Kinematics, q) -> np.ndarray:
    """Condition numbers of the velocity systems at poses q (unit lengths).

    Below WARN they may be estimates; at and above it they are exact.
    """
    _, jac, _ = kin.system.evaluate(q)
    return _scaled_cond(kin.system, jac[:, list(kin.rows)], list(kin.rows))


def velocities(kin: Kinematics, q, check: bool = True, where: str = "pose", jac=None):
    """q' at poses q (N, nq); returns (qd, cond). ``where`` names the pose in a singular-pose error.

    ``cond`` is exact where it exceeds WARN (1e6), an estimate below. ``jac``: the
    Jacobian of :meth:`System.evaluate` at q, if already evaluated.
    """
    q = as_poses(q)
    if jac is None:
        _, jac, _ = kin.system.evaluate(q)
    rows = list(kin.rows)
    a = jac.take(_row_index(kin), axis=1)
    cond = _scaled_cond(kin.system, a, rows)
    bad = ~(cond <= SINGULAR)
    any_bad = bool(bad.any())
    if check and any_bad:
        i = int(np.argmax(bad))
        raise SingularPoseError(
            f"singular pose: the velocity equations are singular (condition number "
            f"{'inf' if not np.isfinite(cond[i]) else f'{cond[i]:.3g}'})",
            where=where, file=kin.mechanism.source,
            links=_involved(kin.system, a[i], rows, True),
            hint=singular_hint(kin.mechanism))
    rhs = np.empty(a.shape[:2])
    rhs[:] = _rates(kin)
    if any_bad:
        a = a.copy()
        a[bad] = np.eye(a.shape[1])
        rhs[bad] = np.nan
    qd = np.linalg.solve(a, rhs[..., None])[..., 0]
    _exact_crank(kin, qd, kin.mechanism.driver.omega)
    return qd, cond


def velocity_error_bound(kin: Kinematics, q, qd) -> tuple[np.ndarray, np.ndarray]:
    """What the velocity solution at one pose can be in error by, coordinate by coordinate.

    The componentwise forward error bound of the solve A q' = b (Skeel's; LAPACK's xGERFS
    computes its norm as FERR)::

        |q' - q'_exact| <= |A^-1| g,    g = |A q' - b| + (k + 1) eps (|A| |q'| + |b|)

    (k: the most nonzeros in a row of A; eps: the unit round-off). The second term is a relative
    perturbation of every entry of A and b by (k + 1) eps: the round-off of the solve and of the
    Jacobian's entries, which hold the positions (their rounding, eps times the coordinates, is
    of the same order). A linear combination L q' (a link's twist) is then in error by at most
    |L A^-1| g: returns ``(A^-1, g)`` for one pose q (1-D), ``g`` infinite where A cannot be
    inverted or the solution is not finite. Unlike condition x |q'|, the bound is per
    coordinate: far down a chain of stages a slow link's twist is as precise, relatively, as
    the crank's.
    """
    q, qd = np.asarray(q, float).reshape(1, -1), np.asarray(qd, float)
    _, jac, _ = kin.system.evaluate(q)
    a = jac.take(_row_index(kin), axis=1)[0]
    b = _rates(kin)
    try:
        inv = np.linalg.inv(a)
    except np.linalg.LinAlgError:
        inv = np.zeros_like(a)
    k = int(np.count_nonzero(a, axis=1).max()) if a.size else 0
    g = np.abs(a @ qd - b) + (k + 1) * np.finfo(float).eps * (np.abs(a) @ np.abs(qd) + np.abs(b))
    if not (np.isfinite(inv).all() and np.isfinite(g).all() and inv.any()):
        g = np.full_like(g, np.inf)
    return inv, g


def singular_hint(m) -> str:
    """What to do about a singular pose: another driver angle, or for a slider driver (which has none) another
    place of the slider on its path."""
    where = "draw the slider elsewhere on its path" if m.driver.is_slider else "choose another driver angle"
    return f"links in line (a toggle or dead centre) or two pins at one place: {where}"


def _exact_crank(kin: Kinematics, rates: np.ndarray, value: float) -> None:
    """Write the crank's prescribed rate (theta_d' = omega, theta_d'' = alpha) into its column.

    The driver's row makes that column equal the input up to the solve's round-off;
    the input itself is exact (a driver given as 40 rad/s reads 40, not 39.99999999999999).
    """
    if kin.system.crank >= 0:
        j = 3 * kin.system.crank + 2
        if len(rates) == 1:   # one pose: the same test on its float
            if math.isfinite(rates[0, j]):
                rates[0, j] = value
            return
        col = rates[:, j]
        col[np.isfinite(col)] = value


def accelerations(kin: Kinematics, q, qd, jac=None):
    """q'' at poses q with velocities qd (N, nq).

    With ``jac`` (the Jacobian at q, as the velocities used it) only the h-terms are
    evaluated: J q'' = w' - h needs no second Jacobian.
    """
    q, qd = as_poses(q), as_poses(qd)
    if jac is None:
        _, jac, h = kin.system.evaluate(q, qd)
    else:
        h = kin.system.second_terms(q, qd)
    index = _row_index(kin)
    a = jac.take(index, axis=1)
    rhs = -h.take(index, axis=1)
    drv = kin.mechanism.driver
    rhs[:, -1] += drv.accel if drv.is_slider else drv.alpha
    if len(a) == 1:   # one pose: the same test without the reductions per axis
        good = np.array([bool(np.isfinite(rhs).all() and np.isfinite(a).all())])
    else:
        good = np.isfinite(rhs).all(axis=1) & np.isfinite(a).all(axis=(1, 2))
    if good.all():
        out = np.linalg.solve(a, rhs[..., None])[..., 0]
    else:
        out = np.full(q.shape, np.nan)
        if good.any():
            out[good] = np.linalg.solve(a[good], rhs[good][..., None])[..., 0]
    if not drv.is_slider:
        _exact_crank(kin, out, drv.alpha)
    return out
