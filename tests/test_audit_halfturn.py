"""Outside check, ``--angle`` half a turn from the reference pose (FORMAT.md section 5, Driver: "carried there the
shorter way round from the reference pose; a toggle on the way is exit 3"). At exactly 180 deg either way round is
the shorter; where one of them crosses a toggle and the other does not, the angle is reached the other way.

Found by the audit: a non-Grashof four-bar drawn at 91.8 deg (range -98.7 to 98.7 deg) refused ``--angle -88.19``
(exactly 180 deg away, reached clockwise through 0 deg without a toggle) with exit 3, "a toggle lies on the way",
because half a turn was always taken counter-clockwise (5 of 6 generated rockers; the message's own range held
the angle). A rocker drawn at 90 deg asked at -90 deg is the round-number case.
"""
from __future__ import annotations

import numpy as np
import pytest

import velpoly

from test_audit_angles import wide_rocker


@pytest.mark.parametrize("seed", range(3))
def test_half_a_turn_is_reached_the_way_without_a_toggle(seed):
    mech, theta_max, theta = wide_rocker(seed)
    m = velpoly.load(mech)
    ref = velpoly.solve(m).driver_angle
    inward = -np.sign(ref)   # towards the middle of the range: the way without a toggle
    way = velpoly.sweep(m, ref + inward * np.linspace(0.0, 180.0, 61))
    assert len(way.angles) == 61, way.stopped
    for target in (ref + 180.0, ref - 180.0):   # the same angle, written either way
        sol = velpoly.solve(m, angle=target)
        assert abs((sol.driver_angle - ref - inward * 180.0 + 180.0) % 360.0 - 180.0) < 1e-9
        for key, p in sol.position.items():   # on the drawn branch: where the sweep that way arrives
            assert np.hypot(*(p - way.position[key][-1])) < 1e-7 * m.size, key
