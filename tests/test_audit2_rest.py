"""Outside check, a driver at rest (FORMAT.md section 1, Driver: omega a number of rad/s; section 3:
"never a traceback", exit 2 for input a command cannot take). Found by the audit:
``omega = 0`` (a mechanism at rest, or starting from rest with ``alpha`` given, as books pose it) made
``velpoly draw`` (the velocity and full sheets; the acceleration sheet too without alpha) fail with exit 1,
"internal error: ZeroDivisionError" (a polygon of one point has no scale). Such a sheet is now exit 2
naming driver.omega (driver.speed) and saying the polygon is a single point, before anything is drawn;
the acceleration sheet of a mechanism starting from rest is drawn (solution.polygon_at_rest).
On generated mechanisms of every kind (a prescribed slip moves a mechanism whose crank is at rest).
"""
from __future__ import annotations

import copy


import velpoly
from velpoly.solution import polygon_at_rest

from mechanisms import in_process
from test_fuzz import to_toml
from zoo import zoo


def resting(mech: dict, alpha: float = 0.0) -> dict:
    m = copy.deepcopy(mech)
    if "link" in m["driver"]:
        m["driver"].update(omega=0.0, alpha=alpha)
    else:
        m["driver"].update(speed=0.0, accel=alpha)
    return m


def test_a_sheet_whose_polygon_is_one_point_is_refused_naming_the_driver():
    seen = set()
    for sp in zoo(20261125, 28):
        for alpha in (0.0, 3.0):
            sol = velpoly.solve(velpoly.load(resting(sp.mech, alpha)))
            moving = any(abs(v).max() > 0 for v in sol.velocity.values())   # a prescribed slip
            rate = "driver.omega" if "link" in sp.mech["driver"] else "driver.speed"
            for sheet in ("velocity", "acceleration", "full", "poles", "displacement"):
                e = polygon_at_rest(sol, sheet)
                point = not moving and (sheet in ("velocity", "full") or (sheet == "acceleration" and not alpha))
                assert (e is not None) == point, (sp.kind, alpha, sheet)
                if e is not None:
                    assert e.where == rate and "single point" in str(e) and e.exit_code == 2, e
                    seen.add((sheet, alpha))
    assert len(seen) == 5


def test_draw_at_rest_is_exit_2_before_drawing(tmp_path):
    for k, sp in enumerate(zoo(20261125, 3)):
        f = tmp_path / f"m{k}.toml"
        f.write_text(to_toml(resting(sp.mech, alpha=2.0)))
        out = tmp_path / f"m{k}.svg"
        r = in_process(["draw", f, "--sheet", "velocity", "-o", out])
        lines = r.stderr.splitlines()
        assert r.returncode == 2 and len(lines) == 2 and "the velocity polygon is a single point" in lines[0], r.stderr
        assert lines[0].startswith(f"error: {f}: driver.") and not out.exists()
