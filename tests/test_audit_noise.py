"""Outside check, ``velpoly solve``'s tables against the JSON: rounding noise prints 0, in every table, by the one
relation the drawn tables read (velpoly.compare.kind_floor: a billionth of the largest value of its kind in the
mechanism, alpha at least omega^2, an acceleration at least speed^2 / size).

Found by the audit: the solve tables floored each column by its own largest value, so a column that is all
rounding noise printed it: a parallelogram four-bar at a constant crank speed, re-assembled at another angle, has
alpha_4 = 2.2e-14 rad/s^2 in the JSON, and the links table printed "2.19908e-14" (the sheet's table, 0).
"""
from __future__ import annotations

import numpy as np

import velpoly
from velpoly.report import solution_report

from test_audit_tables import parallelogram


def test_a_column_of_rounding_noise_prints_zero():
    rng = np.random.default_rng(11)
    noisy = 0
    for _ in range(16):   # parallelograms at a constant crank speed: every alpha is 0, up to rounding
        sol = velpoly.solve(velpoly.load(parallelogram(rng)), angle=float(rng.uniform(5, 175)))
        noisy += any(a != 0 for a in sol.alpha.values())
        lines = solution_report(sol).splitlines()
        links = lines[lines.index("Links") + 3:lines.index("Points") - 1]
        assert [row.split()[-1] for row in links] == ["0"] * 4, links
        assert all(abs(a) < 1e-9 * float(sol.omega["2"]) ** 2 for a in sol.alpha.values())   # noise indeed
    assert noisy >= 2   # the JSON has noise to print
