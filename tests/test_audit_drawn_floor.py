"""Outside check, the drawn results table against ``velpoly solve``'s: a slow mechanism's values are printed, not
rounded to 0. Kinematics scale with the driver: the driver's speed times k makes every velocity and omega k times,
every acceleration and alpha k^2 times (with the driver's alpha k^2 times and a prescribed slip k times), so a
sheet's table for the slow mechanism must show the same digits, times k or k^2.

Found by the audit: the drawn table (velpoly/render/table.py) kept its own 1e-9 absolute zero floor while
``velpoly solve``'s tables read a billionth of the largest value of its kind (velpoly.compare.kind_floor): a
generated mechanism driven at 1e-5 of its speed drew every acceleration and alpha of its sheet as 0 (and
"0 ∠ 172.24°"), beside the right JSON.
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import velpoly
from velpoly.render.constructions import constructions
from velpoly.render.table import given_table, results_table

import mechanisms
from zoo import each

K = 1e-5
_SUP = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")
NUMBER = re.compile(r"(−?[\d.]+(?:×10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?)(?: ∠ ([\d.]+)°)?")


def slowed(mech: dict, k: float) -> dict:
    """The mechanism with its driver k times as fast (its accelerations k^2 times)."""
    d, drv = dict(mech), dict(mech["driver"])
    m = velpoly.load(mech).driver
    if "slider" in drv:
        drv.update(speed=m.speed * k, accel=m.accel * k * k)
    else:
        drv.update(omega=m.omega * k, alpha=m.alpha * k * k)
    d["driver"] = drv
    d["contacts"] = [{**c, **({"slip": c["slip"] * k} if "slip" in c else {})} for c in mech.get("contacts", ())]
    if not d["contacts"]:
        del d["contacts"]
    return d


def numbers(cell: str) -> list:
    """A cell's magnitudes (floats) and directions (as printed)."""
    out = []
    for mag, direction in NUMBER.findall(cell):
        mant, _, e = mag.replace("−", "-").partition("×10")
        out.append(float(mant) * 10.0 ** int(e.translate(_SUP) or 0))
        if direction:
            out.append(direction)
    return out


def table_of(mech: dict):
    sol = velpoly.solve(velpoly.load(mech))
    c = constructions(sol, "full")
    return results_table(sol, "full", velocity=c.velocity, acceleration=c.acceleration, poleset=c.poles), sol


def test_a_slow_mechanism_s_drawn_table_shows_its_values_scaled():
    checked = 0
    for sp in each(20271127, 12):
        (fast, _), (slow, sol) = table_of(sp.mech), table_of(slowed(sp.mech, K))
        assert [r[0] for r in slow.rows] == [r[0] for r in fast.rows], sp.kind
        for f_row, s_row in zip(fast.rows, slow.rows):
            k = K * K if s_row[0].startswith(("$A", r"$\alpha")) else K
            for f_cell, s_cell in zip(f_row[1:], s_row[1:]):
                want, got = numbers(f_cell), numbers(s_cell)
                assert len(got) == len(want), (sp.kind, s_row, f_row)
                for w, g in zip(want, got):
                    if isinstance(w, str):
                        assert g == w, (sp.kind, s_row, f_row)
                    else:
                        assert g == pytest.approx(w * k, rel=2e-4, abs=1e-30), (sp.kind, s_row, f_row)
                        checked += w != 0
        assert sol.to_dict()["driver"]   # the slow mechanism solves
    assert checked > 200


def test_the_given_data_of_a_tiny_slow_mechanism_are_printed():
    rng = np.random.default_rng(5)
    for _ in range(4):   # a four-bar 1e-11 units across, its crank at 1e-12 rad/s: the displacement sheet's data
        size, omega = 10 ** rng.uniform(-13, -11), float(rng.choice([-1, 1]) * 10 ** rng.uniform(-13, -10))
        d = mechanisms.fourbar(a=2 * size, b=5 * size, c=4 * size, d=5 * size, theta=float(rng.uniform(20, 160)),
                               omega=omega, alpha=omega ** 2)
        rows = dict(given_table(velpoly.solve(velpoly.load(d))).rows)
        assert numbers(rows["AB (link 3)"])[0] == pytest.approx(5 * size, rel=1e-4), rows
        assert numbers(rows["O4 (frame)"])[0] == pytest.approx(5 * size, rel=1e-4), rows
        assert numbers(rows[r"$\omega_{2}$ (rad/s)"])[0] == pytest.approx(abs(omega), rel=1e-4), rows
        assert numbers(rows[r"$\alpha_{2}$ (rad/s²)"])[0] == pytest.approx(omega ** 2, rel=1e-4), rows
