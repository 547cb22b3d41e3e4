"""The single-instant shortcuts agree with the general evaluation they replace."""
from pathlib import Path

import numpy as np
import pytest

import velpoly
from velpoly.kinematics import accelerations, prepare, velocities
from paths import GALLERY_FILES

ROOT = Path(__file__).resolve().parent.parent
FILES = GALLERY_FILES


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_values_and_second_terms_match_evaluate(path):
    """residual and second_terms (no Jacobian) give evaluate's Phi and h exactly."""
    system = prepare(velpoly.load(path)).system
    rng = np.random.default_rng(7)
    q = rng.normal(size=(3, system.nq)) * 0.1
    qd = rng.normal(size=(3, system.nq))
    phi, jac, h = system.evaluate(q, qd)
    assert np.array_equal(system.residual(q), phi)
    assert np.array_equal(system.second_terms(q, qd), h)
    # one pose (jets of plain floats) agrees with the same pose in a batch (jets of arrays)
    for k in range(len(q)):
        phi1, jac1, h1 = system.evaluate(q[k:k + 1], qd[k:k + 1])
        tol = 1e-14 * max(1.0, system.size, np.abs(h[k]).max(), np.abs(jac[k]).max())
        assert np.abs(phi1[0] - phi[k]).max() <= tol
        assert np.abs(jac1[0] - jac[k]).max() <= tol
        assert np.abs(h1[0] - h[k]).max() <= tol
        assert np.abs(system.second_terms(q[k:k + 1], qd[k:k + 1])[0] - h[k]).max() <= tol
        assert np.abs(system.residual(q[k:k + 1])[0] - phi[k]).max() <= tol
    # the Jacobian against central differences of the values
    eps = 1e-6
    for k in range(system.nq):
        dq = np.zeros(system.nq)
        dq[k] = eps
        fd = (system.residual(q + dq) - system.residual(q - dq)) / (2 * eps)
        assert np.abs(fd - jac[:, :, k]).max() <= 1e-6 * max(1.0, system.size)


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_accelerations_with_the_velocities_jacobian(path):
    """accelerations(..., jac=J) (h-terms only) equals a fresh evaluation."""
    m = velpoly.load(path)
    kin = prepare(m)
    q = np.zeros((1, kin.system.nq))
    _, jac, _ = kin.system.evaluate(q)
    qd, _ = velocities(kin, q, jac=jac)
    assert np.array_equal(qd, velocities(kin, q)[0])
    assert np.array_equal(accelerations(kin, q, qd, jac=jac), accelerations(kin, q, qd), equal_nan=True)


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
@pytest.mark.parametrize("with_qdd", [True, False])
def test_evaluate_motion_one_pose_matches_the_batch(path, with_qdd):
    """evaluate_motion at one pose (plain floats) equals the same pose in a batch (arrays)."""
    from velpoly.motion import evaluate_motion
    m = velpoly.load(path)
    rng = np.random.default_rng(3)
    index = prepare(m).system.index
    nq = 3 * len(index)
    q, qd, qdd = (rng.normal(size=(2, nq)) * 0.3 for _ in range(3))
    qdd = qdd if with_qdd else None
    one = evaluate_motion(m, index, q[:1], qd[:1], None if qdd is None else qdd[:1])
    two = evaluate_motion(m, index, q, qd, qdd)

    def same(a, b):
        a, b = np.asarray(a, float), np.asarray(b, float)[:1]
        assert a.shape == b.shape
        assert np.array_equal(np.isnan(a), np.isnan(b))
        ok = ~np.isnan(a)
        assert np.all(np.abs(a[ok] - b[ok]) <= 1e-13 * max(1.0, np.abs(b[ok]).max(initial=0.0)))
    for name in ("angle", "omega", "alpha", "position", "velocity", "acceleration"):
        x, y = getattr(one, name), getattr(two, name)
        assert list(x) == list(y)
        for k in x:
            same(x[k], y[k])
    for name in ("sliders", "slots", "contacts"):
        x, y = getattr(one, name), getattr(two, name)
        assert len(x) == len(y)
        for r, s in zip(x, y):
            assert list(r) == list(s)
            for k in r:
                same(r[k], s[k])


def test_wrap_deg_float_equals_wrap_deg():
    from velpoly.motion import wrap_deg, wrap_deg_float
    values = [0.0, -0.0, 180.0, -180.0, 540.0, -540.0, 359.99999999999994, 1e-300, -1e-300,
              179.99999999999997, -179.99999999999997, 1e17, -7e15 + 0.5, 720.0, 30.000000000000004]
    values += list(np.random.default_rng(5).uniform(-2000, 2000, 200))
    for a in values:
        w = wrap_deg_float(float(a))
        assert type(w) is float
        assert w == float(wrap_deg(a)) and -180.0 < w <= 180.0


def _generated():
    import mechanisms as M
    for name, gen in sorted(M.ARROW_GENERATORS.items()):
        for seed in (1, 2):
            yield name, velpoly.load(gen(seed, 35.0 + 50 * seed))


@pytest.mark.parametrize("source", ["gallery", "generated"])
def test_the_json_s_max_error_without_the_polygons_is_theirs_to_the_bit(source):
    """to_dict replays the plan without recording the steps: the same max_error as the polygons give,
    whether it runs before they are built or after."""
    from velpoly.polygons import acceleration_polygon, max_error, velocity_polygon
    cases = [(p.stem, velpoly.load(p)) for p in FILES] if source == "gallery" else list(_generated())
    assert len(cases) >= 19
    for name, m in cases:
        for angle in (None, 77.0) if source == "gallery" else (None,):
            try:
                first, second = velpoly.solve(m, angle=angle), velpoly.solve(m, angle=angle)
            except velpoly.VelpolyError:
                continue    # a pose the mechanism cannot reach
            d = first.to_dict()["graphical"]["max_error"]              # lean replay, polygons not built
            levels = ("velocity", "acceleration") if first.has_accelerations else ("velocity",)
            polys = {"velocity": velocity_polygon, "acceleration": acceleration_polygon}
            for level in levels:
                built = polys[level](second).max_error
                assert d[level] == built and max_error(second, level) == built, (name, angle, level)
                assert built < 1e-9, (name, level)
            assert first.to_dict() == second.to_dict(), name                # built first, then the JSON


def _systems():
    """Every example's equations, the zoo's (one of each kind and variant) and the generated joints'."""
    import mechanisms as M
    from zoo import variants, zoo
    mechs = [velpoly.load(p) for p in FILES] + [velpoly.load(sp.mech) for sp in zoo(11, len(variants()))]
    mechs += [velpoly.load(gen(seed, 40.0 + 30 * seed)) for _, gen in sorted(M.ARROW_GENERATORS.items()) for seed in (1, 2)]
    out = []
    for m in mechs:
        try:
            out.append(prepare(m).system)
        except velpoly.VelpolyError:
            continue
    assert len(out) >= 40
    return out


def test_one_pose_equations_are_the_batch_s_to_the_bit():
    """evaluate, residual and second_terms at one pose (the pins on plain floats, _pins_one; the jets'
    values floats, cos and sin from math) give the bytes the batch gives for the same pose."""
    rng = np.random.default_rng(11)
    checked = 0
    for system in _systems():
        for scale in (1e-3, 0.3, 4.0):
            q = rng.normal(size=(2, system.nq)) * scale
            qd = rng.normal(size=(2, system.nq))
            both = system.evaluate(q, qd), (system.residual(q),), (system.second_terms(q, qd),)
            for k in range(2):
                one = system.evaluate(q[k:k + 1], qd[k:k + 1]), (system.residual(q[k:k + 1]),), \
                    (system.second_terms(q[k:k + 1], qd[k:k + 1]),)
                for got, want in zip((x for t in one for x in t), (x for t in both for x in t)):
                    assert got[0].tobytes() == want[k].tobytes(), system.mechanism.title
                checked += 1
    assert checked >= 240


def test_math_cos_and_sin_are_numpy_s():
    """The one-pose jets and pins take cos and sin from math, the batch from numpy: the same values here
    (the JSON would change its last bits on a platform where they differ: this test says so first)."""
    import math
    rng = np.random.default_rng(2)
    x = np.concatenate([rng.uniform(-s, s, 20000) for s in (1e-6, 0.1, 1.0, 3.2, 7.0, 100.0, 1e5)]
                       + [np.array([0.0, -0.0, math.pi, -math.pi, math.pi / 2, 1e-300, 5e-324])])
    assert np.cos(x).tolist() == [math.cos(v) for v in x.tolist()]
    assert np.sin(x).tolist() == [math.sin(v) for v in x.tolist()]


def test_the_condition_number_of_one_matrix_is_numpy_s():
    """_cond_one (one pose: the ratio of singular values divided as floats) gives np.linalg.cond's
    value, also where the matrix is singular (inf), zero (0 / 0: inf) or holds NaN (NaN)."""
    from velpoly.kinematics import _cond_one
    rng = np.random.default_rng(4)
    cases = [rng.normal(size=(1, n, n)) for n in (1, 2, 5, 15) for _ in range(20)]
    singular = rng.normal(size=(1, 6, 6))
    singular[0, 3] = singular[0, 1]
    cases += [singular, np.zeros((1, 4, 4)), np.eye(3)[None] * 1e-300, np.diag([1e300, 1e-300])[None]]
    with_nan = rng.normal(size=(1, 3, 3))
    with_nan[0, 1, 1] = np.nan
    cases.append(with_nan)
    for a in cases:
        try:
            want = np.linalg.cond(a)
        except np.linalg.LinAlgError:
            with pytest.raises(np.linalg.LinAlgError):
                _cond_one(a)
            continue
        got = _cond_one(a)
        assert got.shape == want.shape == (1,) and got.tobytes() == want.tobytes(), a


def test_atan2_of_one_pose_s_floats_is_numpy_s():
    """Jet.atan2 at one pose (float values, as the jets' cos and sin from math leave them) gives the
    values numpy's scalars gave, and inf or NaN rather than an exception at r = 0 or on overflow."""
    from velpoly.jet import Jet
    g = np.array([1.0, 0.0, 2.0])
    cases = [(0.3, -1.2, 0.7, 0.1), (0.0, 0.0, 1.0, 0.0), (1e200, 1e200, 1.0, 1.0), (-2.0, 0.0, 0.5, -0.5)]
    with np.errstate(all="ignore"):
        for xv, yv, xd, yd in cases:
            floats = Jet.atan2(Jet(yv, g, yd, 0.1), Jet(xv, -g, xd, 0.2), 1.0)
            scalars = Jet.atan2(Jet(np.float64(yv), g, yd, 0.1), Jet(np.float64(xv), -g, xd, 0.2), 1.0)
            for a, b in zip((floats.v, floats.g, floats.vd, floats.h), (scalars.v, scalars.g, scalars.vd, scalars.h)):
                assert np.asarray(a).tobytes() == np.asarray(b).tobytes(), (xv, yv)
