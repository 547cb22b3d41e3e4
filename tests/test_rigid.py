"""velpoly.rigid: the float, array and complex paths agree to the last bit, and the relations are the
derivatives of a rigid body's motion (finite differences on random bodies)."""
import math

import numpy as np
from hypothesis import given, settings, strategies as st

from velpoly import rigid

num = st.floats(-50, 50, allow_nan=False)
rates = st.floats(-20, 20, allow_nan=False)


def _as_complex(v):
    return complex(v[0], v[1])


@settings(max_examples=60, deadline=None)
@given(num, num, num, num, num, num, rates, rates)
def test_float_array_and_complex_paths_agree(ox, oy, ax, ay, rx, ry, w, al):
    v_o, a_o, r = (ox, oy), (ax, ay), (rx, ry)
    fv = rigid.point_velocity(v_o, w, r)
    fa = rigid.point_acceleration(a_o, al, w, r)
    fc = rigid.coriolis(w, r)
    fn, ft = rigid.normal_acceleration(w, r), rigid.rate_cross(al, r)
    # array path: one pose (2,) and many poses (N, 2) with omega (N,)
    va, aa = np.array(v_o), np.array(a_o)
    ra = np.array(r)
    assert tuple(rigid.point_velocity(va, w, ra)) == fv
    assert tuple(rigid.point_acceleration(aa, al, w, ra)) == fa
    assert tuple(rigid.coriolis(w, ra)) == fc
    assert tuple(rigid.normal_acceleration(w, ra)) == fn
    many = rigid.point_acceleration(np.stack([aa, aa]), np.array([al, 0.0]), np.array([w, w]), np.stack([ra, ra]))
    assert tuple(many[0]) == fa
    assert tuple(rigid.point_velocity(np.stack([va] * 3), np.full(3, w), np.stack([ra] * 3))[2]) == fv
    assert tuple(rigid.coriolis(np.array([w, 1.0]), np.stack([ra, ra]))[0]) == fc
    # the complex path (x + iy) gives the same numbers up to rounding
    zv = rigid.point_velocity(_as_complex(v_o), w, _as_complex(r))
    za = rigid.point_acceleration(_as_complex(a_o), al, w, _as_complex(r))
    zc, zt = rigid.coriolis(w, _as_complex(r)), rigid.rate_cross(al, _as_complex(r))
    scale = 1e-12 * (1 + abs(w) + abs(al)) ** 2 * (1 + math.hypot(*r) + math.hypot(*v_o) + math.hypot(*a_o))
    for z, f in ((zv, fv), (za, fa), (zc, fc), (zt, ft)):
        assert abs(z - complex(*f)) <= scale
    # the parts add up: A_P = A_O + A^t + A^n
    assert math.isclose(fa[0], ax + ft[0] + fn[0], rel_tol=1e-12, abs_tol=scale)
    assert math.isclose(fa[1], ay + ft[1] + fn[1], rel_tol=1e-12, abs_tol=scale)


@settings(max_examples=40, deadline=None)
@given(num, num, rates, rates, rates, rates, st.floats(-3, 3), st.floats(-3, 3), num, num)
def test_relations_are_the_derivatives_of_a_rigid_motion(x0, y0, vx, vy, w, al, th0, t, sx, sy):
    """A body whose point O moves as O(t) = O0 + V0 t + A0 t^2 / 2 and turns as theta(t) = th0 + w t +
    al t^2 / 2 carries P(t) = O(t) + R(theta(t)) s: the rigid-body V_P and A_P equal the central
    differences of P(t) (fourth order), at a random time."""
    a0 = (0.3 * vy, -0.7 * vx)

    def motion(tt):
        o = (x0 + vx * tt + a0[0] * tt * tt / 2, y0 + vy * tt + a0[1] * tt * tt / 2)
        v = (vx + a0[0] * tt, vy + a0[1] * tt)
        th = th0 + w * tt + al * tt * tt / 2
        c, sn = math.cos(th), math.sin(th)
        return o, v, a0, (c * sx - sn * sy, sn * sx + c * sy), w + al * tt

    def place(tt):
        o, _, _, r, _ = motion(tt)
        return np.array([o[0] + r[0], o[1] + r[1]])

    o, v, a, r, om = motion(t)
    h = 1e-3 / (1 + abs(w) + abs(al))
    d1 = (-place(t + 2 * h) + 8 * place(t + h) - 8 * place(t - h) + place(t - 2 * h)) / (12 * h)
    d2 = (-place(t + 2 * h) + 16 * place(t + h) - 30 * place(t) + 16 * place(t - h) - place(t - 2 * h)) / (12 * h * h)
    size = 1 + math.hypot(sx, sy) + math.hypot(x0, y0)
    speed = 1 + math.hypot(vx, vy) + (abs(w) + abs(al)) * math.hypot(sx, sy)
    vp = np.array(rigid.point_velocity(v, om, r))
    ap = np.array(rigid.point_acceleration(a, al, om, r))
    assert np.allclose(vp, d1, rtol=0, atol=1e-7 * speed * size)
    assert np.allclose(ap, d2, rtol=0, atol=1e-4 * speed * (1 + abs(w) + abs(al)) * size)
    # Coriolis: a point sliding along the body with V_rel in body axes has A = A_body + 2 omega x V_rel + A_rel
    u = (0.6, 0.8)                                   # a body-fixed direction, the slide at unit speed

    def slide(tt):
        o, _, _, _, _ = motion(tt)
        th = th0 + w * tt + al * tt * tt / 2
        c, sn = math.cos(th), math.sin(th)
        s2 = (sx + tt * u[0], sy + tt * u[1])
        return np.array([o[0] + c * s2[0] - sn * s2[1], o[1] + sn * s2[0] + c * s2[1]])
    th = th0 + w * t + al * t * t / 2
    c, sn = math.cos(th), math.sin(th)
    s2 = (sx + t * u[0], sy + t * u[1])
    r2 = (c * s2[0] - sn * s2[1], sn * s2[0] + c * s2[1])
    v_rel = (c * u[0] - sn * u[1], sn * u[0] + c * u[1])
    a_slide = np.array(rigid.point_acceleration(a, al, om, r2)) + np.array(rigid.coriolis(om, v_rel))
    d2s = (-slide(t + 2 * h) + 16 * slide(t + h) - 30 * slide(t) + 16 * slide(t - h) - slide(t - 2 * h)) / (12 * h * h)
    assert np.allclose(a_slide, d2s, rtol=0, atol=1e-4 * (speed + 1) * (1 + abs(w) + abs(al)) * (size + 3))


def test_helpers_on_every_path():
    assert rigid.perp((1.0, 2.0)) == (-2.0, 1.0) and rigid.perp(1 + 2j) == -2 + 1j
    assert np.array_equal(rigid.perp(np.array([[1.0, 2.0], [3.0, 4.0]])), [[-2.0, 1.0], [-4.0, 3.0]])
    assert rigid.dot((1.0, 2.0), (3.0, 4.0)) == 11.0 == rigid.dot(1 + 2j, 3 + 4j)
    assert np.array_equal(rigid.dot(np.ones((3, 2)), np.full((3, 2), 2.0)), [4.0, 4.0, 4.0])
    assert rigid.unit((3.0, 4.0)) == (0.6, 0.8) and np.allclose(rigid.unit(np.array([[0.0, 5.0]])), [[0.0, 1.0]])
    assert np.allclose(rigid.direction(30.0), [math.cos(math.pi / 6), 0.5])
    assert np.array_equal(rigid.direction(np.array([0.0, 30.0]))[1], rigid.direction(30.0))
    z = np.array([1 + 2j, 3 - 1j])
    assert np.array_equal(rigid.xy(z), [[1.0, 2.0], [3.0, -1.0]]) and np.array_equal(rigid.xy(2j), [0.0, 2.0])
    assert np.array_equal(rigid.xy(0, 3), np.zeros((3, 2))) and np.array_equal(rigid.xy(1 + 1j, 2), np.ones((2, 2)))
    assert rigid.is_zero(0.0) and not rigid.is_zero(np.zeros(2)) and not rigid.is_zero(1e-300)
    assert np.allclose(rigid.arg(np.array([1j, -1.0])), [math.pi / 2, math.pi])
