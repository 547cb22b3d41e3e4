"""The vectorised additions to the geometry kernel agree with the scalar kernel."""
import math

import numpy as np
from hypothesis import given, settings, strategies as st

from velpoly import geometry as G

coord = st.floats(-100, 100, allow_nan=False)
angle = st.floats(-180, 180, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(coord, coord, angle, coord, coord, angle)
def test_intersect_lines_batch_agrees_with_intersect_lines(px, py, a, qx, qy, b):
    p, q = np.array([px, py]), np.array([qx, qy])
    d, e = G.from_polar(1.0, a), G.from_polar(2.0, b)
    x, s, t, sine = G.intersect_lines(p, d, q, e)
    xb, sb, tb, sineb = G.intersect_lines_batch(p[None], d[None], q[None], e[None])
    assert math.isclose(sineb[0], sine, rel_tol=1e-12, abs_tol=1e-15)
    if x is None:
        assert np.isnan(xb).all()
        return
    # same formula, same rounding: equal to the last bits
    assert np.allclose(xb[0], x, rtol=0, atol=1e-12 * (1 + np.abs(x).max()))
    assert math.isclose(sb[0], s, rel_tol=1e-12, abs_tol=1e-12)
    assert math.isclose(tb[0], t, rel_tol=1e-12, abs_tol=1e-12)


def test_intersect_lines_batch_broadcasts_and_flags_parallel_lines():
    p = np.zeros((3, 2))
    d = np.array([1.0, 0.0])                       # broadcast over the three pairs
    q = np.array([[2.0, 1.0], [0.0, 1.0], [5.0, 5.0]])
    e = np.array([[0.0, 1.0], [1.0, 0.0], [1.0, 1.0]])
    x, s, t, sine = G.intersect_lines_batch(p, d, q, e)
    assert np.allclose(x[0], [2.0, 0.0]) and np.allclose(x[2], [0.0, 0.0])
    assert np.isnan(x[1]).all() and np.isnan(s[1]) and np.isnan(t[1])
    assert np.allclose(sine, [1.0, 0.0, math.sqrt(0.5)])
    assert np.allclose(p + s[:, None] * d, q + t[:, None] * e, equal_nan=True)
