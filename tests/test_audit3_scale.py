"""Outside check, FORMAT.md: a mechanism at any scale. Found by the audit: a very slow or very fast driver
(``omega = 1e-90`` or ``1e90`` rad/s, accelerations near 1e-178 or 1e181) made ``velpoly draw`` exit 1
("internal error"): the row layout squared a scale (OverflowError past 1e154, 0/0 below 1e-154), and
shapely's geometry of the drawing (the polygon's origin disc, label boxes) vanishes or overflows at such
sizes. The layout now divides before it multiplies; a polygon whose largest vector is outside
``solution.DRAWN_RANGE`` is an input error (exit 2) naming the driver's rate, as a polygon at rest is."""
from __future__ import annotations

import copy

from velpoly import load, solve
from velpoly.render.layout import drawn_areas, share_row
from velpoly.solution import DRAWN_RANGE, polygon_at_rest

from mechanisms import in_process
from test_fuzz import to_toml
from zoo import zoo


def test_the_row_layout_holds_at_any_scale():
    for k in (1e-200, 1e-90, 1.0, 1e90, 1e200):
        spans = [(3.0 * k, 2.0 * k), (1.0 * k, 4.0 * k)]
        row = share_row(spans, 20.0, 8.0, 0.5)
        assert all(0 < w < 20 for w in row.widths), (k, row)
        assert all(0 < a < 200 for a in drawn_areas(spans, row)), (k, row)


def test_a_driver_too_slow_or_fast_to_draw_is_an_input_error_naming_its_rate(tmp_path):
    lo, hi = DRAWN_RANGE
    refused = drawn = 0
    for i, sp in enumerate(zoo(20271203, 6)):
        for key, value in (("omega", 1e-90), ("omega", 1e90), ("alpha", 1e-90), ("alpha", 1e90),
                           ("omega", 1e-60)):
            mech = copy.deepcopy(sp.mech)
            if "link" not in mech["driver"]:
                continue
            mech["driver"].update({"omega": 1.0, "alpha": 0.0} if key == "alpha" else {})
            mech["driver"][key] = value
            sol = solve(load(mech))
            for sheet, vectors in (("velocity", sol.velocity), ("full", {**sol.velocity, **sol.acceleration})):
                size = max(max(abs(float(x)) for x in v) for v in vectors.values() if v is not None)
                err = polygon_at_rest(sol, sheet)
                assert (err is not None) == (not lo <= size <= hi), (sp.kind, key, value, sheet, size, err)
                if err is not None:
                    assert err.where in ("driver.omega", "driver.alpha"), err.where
                    assert err.where == "driver.alpha" or key == "omega", (key, err.where)
                    refused += 1
                    if refused <= 2:   # the program's answer: exit 2, one line naming the entry
                        f = tmp_path / f"m{i}.toml"
                        f.write_text(to_toml(mech))
                        r = in_process(["draw", f, "--sheet", sheet, "-o", tmp_path / "m.svg"])
                        assert r.returncode == 2, r.stderr
                        assert r.stderr.startswith(f"error: {f}: {err.where} (line "), r.stderr
                        assert "cannot be drawn" in r.stderr
                else:
                    drawn += 1
    assert refused >= 6 and drawn >= 6, (refused, drawn)
