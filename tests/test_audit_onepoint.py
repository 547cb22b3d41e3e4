"""Outside check, links of one point (FORMAT.md section 1: "a one-point link (a slider block) has the angle of its
path"; section 5: "Angles of one-point links that are not slider blocks: their rotation"): a gear or a cam that
lists only its pivot is drawn with its number, as any link.

Found by the audit: two spur gears in mesh (each gear ``{ points = ["O2"] }``, a rolling contact with
``centres = ["O2", "O3"]``) or a cam given by its contact's ``normal`` crashed every sheet but the acceleration
sheet (exit 1, "internal error: UnboundLocalError ... 'n'" in render/displacement.py's link numbers: the bar's
normal was read for a link with no bar). Checked on generated gear pairs (external and internal) and cams.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import velpoly
from velpoly.render.displacement import draw_mechanism
from velpoly.render.style import get_style, rc_context


def gears(rng) -> dict:
    """A pinion and a wheel, each listing only its pivot, in mesh (rolling) at P; internal or external."""
    r2, r3 = rng.uniform(10, 40), rng.uniform(45, 120)
    internal, turn = bool(rng.integers(2)), float(rng.uniform(-180, 180))
    c = r3 - r2 if internal else r2 + r3
    o3 = [c * math.cos(math.radians(turn)), c * math.sin(math.radians(turn))]
    p = [-r2 * math.cos(math.radians(turn)), -r2 * math.sin(math.radians(turn))] if internal else \
        [r2 * math.cos(math.radians(turn)), r2 * math.sin(math.radians(turn))]
    return {"points": {"O2": [0.0, 0.0], "O3": o3, "P": p},
            "links": {"1": {"points": ["O2", "O3"], "frame": True}, "2": {"points": ["O2"]}, "3": {"points": ["O3"]}},
            "contacts": [{"links": ["2", "3"], "point": "P", "kind": "rolling", "centres": ["O2", "O3"]}],
            "driver": {"link": "2", "omega": float(rng.uniform(-30, 30)), "alpha": float(rng.uniform(-5, 5))}}


def cam(rng) -> dict:
    """A one-point cam 2 about O2 pushing a rocker 3 (O3 F) by a sliding contact at P given by its normal."""
    p = [float(x) for x in rng.uniform(0.5, 1.5, 2)]
    o3 = [p[0] + rng.uniform(0.8, 1.5), p[1] + rng.uniform(0.8, 1.5)]
    lean = math.degrees(math.atan2(o3[1] - p[1], o3[0] - p[0]))
    return {"points": {"O2": [0.0, 0.0], "O3": o3, "P": p, "F": {"from": "O3", "length": 1.5, "angle": lean + 180}},
            "links": {"1": {"points": ["O2", "O3"], "frame": True}, "2": {"points": ["O2"]}, "3": {"points": ["O3", "F"]}},
            "contacts": [{"links": ["2", "3"], "point": "P", "kind": "sliding",
                          "normal": float(lean + rng.uniform(-60, 60) + 90)}],
            "driver": {"link": "2", "omega": float(rng.uniform(1, 9))}}


@pytest.mark.parametrize("make", [gears, cam])
@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_a_one_point_link_is_drawn_with_its_number(make, style):
    sol = velpoly.solve(velpoly.load(make(np.random.default_rng(len(style)))))   # one specimen a case: 0.3 s a drawing
    ax = Figure(figsize=(4, 3), dpi=72).add_axes((0.02, 0.02, 0.96, 0.96))
    FigureCanvasAgg(ax.figure)
    with rc_context(get_style(style)):
        art = draw_mechanism(sol, ax, style=get_style(style))
    numbers = sorted(t.get_text() for t in art.get("link_numbers", []))
    assert numbers == ["2", "3"], numbers
