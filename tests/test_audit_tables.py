"""Outside check, the readable tables of ``velpoly solve`` against the JSON (FORMAT.md section 2: angles in
degrees in (-180, 180]): an angle is printed as the JSON gives it, rounded, never ``-0.0000`` nor ``-180.0000``,
and a vector that prints as zero has no direction.

Also: a slow or small mechanism's values are printed, not rounded to 0 (fmt's floor for rounding noise was
1e-9 absolute: a crank at 1e-5 rad/s on a 1 m four-bar has accelerations of 1e-10 m/s^2, and every one of them
printed 0 in the points, links, sliders, polygon and reference tables and in the sweep's summary, beside the right
JSON).

Found by the audit: a parallelogram four-bar re-assembled at another crank angle has its coupler along the
frame to rounding (-2.8e-14 deg in the JSON), and the links table printed its angle as "-0.0000" (7 of 30
generated parallelograms); a fixed pivot whose velocity was 1.8e-15 printed "0 ∠ 90.000°".
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import velpoly
from velpoly.report import solution_report, summary_table
from velpoly.tables import angle, polar

import mechanisms

BAD = re.compile(r"(?<![\d.])-0\.0+(?!\d)|-180\.0+(?!\d)| 0 ∠")


def parallelogram(rng) -> dict:
    """A parallelogram four-bar (crank and rocker alike), the frame along +x or -x, of random size."""
    frame = float(rng.choice([0.0, 180.0]))
    length, crank, theta = rng.uniform(2, 5), rng.uniform(0.5, 1.5), float(rng.uniform(10, 170))
    return {"points": {"O2": [0, 0], "O4": [float(length * np.cos(np.radians(frame))), 0.0],
                       "A": {"from": "O2", "length": crank, "angle": theta},
                       "B": {"from": "O4", "length": crank, "angle": theta}},
            "links": {"1": {"points": ["O2", "O4"], "frame": True}, "2": {"points": ["O2", "A"]},
                      "3": {"points": ["A", "B"]}, "4": {"points": ["O4", "B"]}},
            "driver": {"link": "2", "omega": float(rng.uniform(1, 10))}}


def test_the_solve_tables_print_no_minus_zero_angle():
    rng = np.random.default_rng(1)
    for _ in range(12):
        sol = velpoly.solve(velpoly.load(parallelogram(rng)), angle=float(rng.uniform(5, 175)))
        text = solution_report(sol)
        assert not BAD.findall(text), BAD.findall(text)
        coupler = next(line for line in text.splitlines() if line.startswith("3 "))
        assert coupler.split()[1] in ("0.0000", "180.0000"), coupler


@pytest.mark.parametrize("deg, text", [(-2.8e-14, "0.0000"), (-0.00004, "0.0000"), (-179.99999999, "180.0000"),
                                       (180.0, "180.0000"), (-179.9999, "-179.9999"), (12.34567, "12.3457")])
def test_an_angle_prints_in_the_json_s_range(deg, text):
    assert angle(deg) == text


def test_a_vector_that_prints_as_zero_has_no_direction():
    assert polar([0.0, 1.8e-15]) == "0" and polar([0.0, 0.0]) == "0"
    assert polar([0.0, 2.0]) == "2 ∠ 90.000°"


def test_a_slow_mechanism_s_values_are_printed_not_zero():
    rng = np.random.default_rng(3)
    for _ in range(3):   # a four-bar a metre across, the crank at 1e-6 .. 1e-4 rad/s: accelerations 1e-12 .. 1e-8
        d = mechanisms.fourbar(theta=float(rng.uniform(20, 160)), omega=float(10 ** rng.uniform(-6, -4)))
        d["points"] = {k: ([x / 10 for x in v] if isinstance(v, list) else
                           {**v, **({"length": v["length"] / 10} if "length" in v else {}),
                            **({"circles": [[c, r / 10] for c, r in v["circles"]]} if "circles" in v else {})})
                       for k, v in d["points"].items()}
        sol = velpoly.solve(velpoly.load(d))
        text = solution_report(sol).splitlines()
        for lk, a in sol.alpha.items():   # the links table: alpha as the JSON has it, to its 6 digits
            row = next(line.split() for line in text if line.split()[:1] == [lk])
            assert float(row[-1]) == pytest.approx(a, rel=1e-5, abs=1e-30), (lk, row, a)
        points = text.index("Points")
        for key, acc in sol.acceleration.items():
            row = next(line for line in text[points:] if line.split()[:1] == [key])
            shown = row.split(")", 1)[1].split()[-3 if np.any(acc) else -1]
            assert float(shown) == pytest.approx(np.hypot(*acc), rel=1e-5, abs=1e-30), (key, row, acc)
        assert not any(line.split()[1:3] == ["0", "0"] for line in text if line.startswith("A_B"))   # the polygon
    w = velpoly.sweep(sol.mechanism, sol.driver_angle + np.arange(0.0, 360.0, 30.0))   # velpoly sweep's summary
    rows = {r[0]: r for r in summary_table(w).rows}
    assert float(rows["|A_B|"][4]) == pytest.approx(np.hypot(*w.acceleration["B"].T).max(), rel=1e-5)
