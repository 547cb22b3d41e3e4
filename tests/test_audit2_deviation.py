"""Outside check, ``[reference]`` deviations of values printed as 0 (FORMAT.md section 1: "every drawn results
table show[s] each one beside the graphical and analytic values, with the deviation"). Found by the audit: a
pole printed at the origin (``P_24 = [0, 0]``, as a book prints a pole on a pivot there) divided its distance
by 1e-300: a slider-crank whose P_24 lies at (0, 2.55) showed a deviation of 2.55e+302 %; a scalar printed 0
(``omega_3 = 0``) showed its computed value itself as the deviation (omega_3 = 6.7: 670 %). A value printed as
0 has no size to be relative to: its deviation is now relative to the largest value of its kind in the
mechanism (compare.kind_scales: the mechanism's size for a position), as the graphical values' are.
On the zoo's generated mechanisms of every kind.
"""
from __future__ import annotations

import copy
import math

import velpoly
from velpoly.compare import kind_scales
from velpoly.reference import compare

from zoo import zoo


def test_a_value_printed_as_zero_deviates_relative_to_its_kind():
    checked = 0
    for sp in zoo(20261125, 14):
        m = velpoly.load(sp.mech)
        sol = velpoly.solve(m)
        moving = [lk.name for lk in m.moving_links if abs(sol.omega[lk.name]) > 0]
        poles = {k: p["position"] for k, p in sol.to_dict()["poles"].items() if p["position"] is not None}
        if not moving or not poles:
            continue
        key, pos = next(iter(sorted(poles.items(), key=lambda kv: -math.hypot(*kv[1]))))
        i, j = key.split("-")
        mech = copy.deepcopy(sp.mech)
        mech["reference"] = {"omega": {moving[0]: 0}, "values": {f"P_{i}{j}" if len(i + j) == 2 else f"P_{i},{j}": [0, 0]}}
        rows = {r.key: r for r in compare(velpoly.solve(velpoly.load(mech)))}
        scales = kind_scales(sol)
        w = rows[f"omega_{moving[0]}"]
        assert math.isclose(w.deviation, abs(sol.omega[moving[0]]) / scales["omega"], rel_tol=1e-12), (sp.kind, w)
        assert w.deviation <= 1 + 1e-12
        p = next(r for k, r in rows.items() if k.startswith("P_"))
        assert math.isclose(p.deviation, math.hypot(*pos) / m.size, rel_tol=1e-9), (sp.kind, p, m.size)
        checked += 1
    assert checked >= 10
