"""Outside check, the readable tables of ``velpoly solve`` against the JSON (FORMAT.md section 2: angles in
degrees in (-180, 180]): an angle is printed as the JSON gives it, rounded, never ``-0.0000`` nor ``-180.0000``,
and a vector that prints as zero has no direction.

Found by the audit: a parallelogram four-bar re-assembled at another crank angle has its coupler along the
frame to rounding (-2.8e-14 deg in the JSON), and the links table printed its angle as "-0.0000" (7 of 30
generated parallelograms); a fixed pivot whose velocity was 1.8e-15 printed "0 ∠ 90.000°".
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import velpoly
from velpoly.report import solution_report
from velpoly.tables import angle, polar

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
