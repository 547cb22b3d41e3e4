"""A slider driver's value in the space diagram (and the interactive page) is named as what it is.

A slider driver's ``speed`` and ``accel`` are given along its path (FORMAT.md): on a guide that is the frame that
is the block's own velocity V_A, on a moving guide the block's velocity relative to the guide, the slip V_A₃/A₄
that the polygons and the step captions name. The space diagram wrote "V_A = 22.89 mm/s" for both: on a swinging guide a
reader met V_A = 20.01 in the results table and took the figure for wrong. Checked at the data level on generated
slider-driven mechanisms of a fixed and of moving guides: the drawn label's name and value against the solution's
relative velocity and acceleration along the path. Fails on the code before the change (the name V_A).
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import velpoly
from test_space_marks import _draw   # the space diagram alone in a 4 x 3 in panel
from velpoly.html import _driver_text
from velpoly.names import place, quantity_math, relative
from velpoly.render.table import given_table
from zoo import specimen

# (kind, variant): a slider on the frame's guide, a block through a swinging guide, a rocker's block, a guide through
# both pivots
CASES = (("slider-crank", "offset slider"), ("inverted slider-crank", "swinging-block slider"),
         ("inverted slider-crank", "rocker slider"), ("inverted slider-crank", "through both slider"))


@pytest.mark.parametrize("case", CASES, ids=lambda c: c[1])
def test_a_slider_drivers_value_is_named_as_what_it_is(case):
    m = velpoly.load(specimen(np.random.default_rng(20261127), *case).mech)
    sol = velpoly.solve(m)
    s = next(s for s in m.sliders if s.point == m.driver.slider)
    p = s.point
    fixed = m.link(s.guide).frame
    # the block's velocity relative to its guide's point under it (the frame's is at rest)
    v = np.asarray(sol.velocity[f"{p}@{s.block}"] if f"{p}@{s.block}" in sol.velocity else sol.velocity[p], float)
    if not fixed:
        v = v - np.asarray(sol.body_velocity(s.guide, sol.place(s.block, p)), float)
    # the name as velpoly.names writes a quantity (tested there): the block's point relative to the guide's
    index = p if fixed else relative(place(p, s.block), place(p, s.guide))
    ax, art = _draw(sol, "textbook")
    texts = {t.get_gid(): t.get_text() for t in art["driver"] if hasattr(t, "get_text")}
    speed = re.fullmatch(r"(\$.+\$) =\s([0-9.e+-]+) .*", texts["driver-label"])
    assert speed and speed.group(1) == quantity_math("V", index), texts["driver-label"]
    assert float(speed.group(2)) == pytest.approx(np.hypot(*v), rel=5e-4)       # printed to 4 digits
    assert float(speed.group(2)) == pytest.approx(abs(m.driver.speed), rel=5e-4)
    if m.driver.accel:
        accel = re.fullmatch(r"(\$.+\$) =\s([0-9.e+-]+) .*", texts["driver-label-accel"])
        assert accel and accel.group(1) == quantity_math("A", index), texts["driver-label-accel"]
    # the interactive page and the handout's table of given data (--sheet displacement) name it the same
    assert _driver_text(m).startswith(f"V_{index} = ")
    assert [r[0] for r in given_table(sol).rows[:2]] == [f"$V_{{{index}}}$", f"$A_{{{index}}}$"]
