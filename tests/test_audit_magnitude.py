"""Outside check, FORMAT.md section 1, Reference values: a vector is ``[magnitude, direction]`` (a negative magnitude
reverses it) or a bare magnitude. A negative bare magnitude is the vector reversed, whose magnitude it still is: a
book's ``V_B = -53.1094`` (against the direction the book assumed) beside an analytic speed of 53.1094 deviates by
nothing. (A ``speed`` alike: one rule for every printed magnitude, test_audit7_input.)

Found by the audit: such a value was compared as a signed number with the (positive) magnitude, and every one,
printed exactly, showed a deviation of 200 % in ``velpoly solve``'s table, the sheets' and the gallery's.
"""
from __future__ import annotations

import numpy as np

import velpoly
from velpoly.reference import compare

from zoo import each


def test_a_negative_bare_magnitude_is_the_reversed_vector_s_magnitude():
    checked = 0
    for sp in each(20271127, 10):
        sol = sp.drawn
        moving = [k for k, v in sol.velocity.items() if "@" not in k and np.hypot(*v) > 0]
        accel = [k for k in moving if sol.acceleration.get(k) is not None]
        ref = {"velocity": {k: -float(np.hypot(*sol.velocity[k])) for k in moving},
               "acceleration": {k: -float(np.hypot(*sol.acceleration[k])) for k in accel},
               "values": {f"V_{k}": [-float(np.hypot(*sol.velocity[k])), 0.0] for k in moving[:1]}}
        rows = compare(velpoly.solve(velpoly.load({**sp.mech, "reference": ref})))
        for r in rows:
            assert r.deviation is not None and r.deviation < 1e-9, (sp.kind, r)
            if isinstance(r.printed, float):
                assert r.printed < 0, r   # shown as the book prints it
            checked += 1
    assert checked > 40
