"""The animation's table at any scale (FORMAT.md: any scale; docs/figures.md: numbers without computer exponents).

A driver at 1e90 or 1e-90 rad/s printed every angular velocity and speed of a frame as 91 digits across the
figure, or as 0.000000: a kind (unit) whose largest value lies beyond ``animate.FIXED_BAND`` prints each value as a
sheet's table does (``1.0583×10⁸⁷``); within it, as before (fixed point, three significant digits of the
largest). Generated four-bars (seeded), the text of every row of the first and a middle frame read back from
the artist and compared with the value the frame shows."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import velpoly
from mechanisms import fourbar
from velpoly.render.animate import FIXED_BAND, Animator, plan_frames

SMALL = (320, 180)
SUPER = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")


def read(text: str) -> float:
    """A table's number as printed (minus sign, ×10 with a superscript power) back as a float."""
    text = text.replace("−", "-")
    mant, times, power = text.partition("×10")
    return float(mant) * (10.0 ** int(power.translate(SUPER)) if times else 1.0)


@pytest.mark.parametrize("omega", [1e90, 1e-90, 1e-7, 12.0, 3e8])
def test_every_value_of_a_frame_is_printed_as_a_number_of_its_size(omega):
    rng = np.random.default_rng(int(abs(math.log10(omega))) + 7)
    a, d = rng.uniform(2.0, 3.0), rng.uniform(8.0, 9.0)
    m = velpoly.load(fourbar(a=a, b=rng.uniform(8.5, 9.5), c=rng.uniform(7.5, 8.5), d=d, omega=omega))
    anim = Animator(plan_frames(m, 60.0), "velocity", "slides", SMALL)
    columns = 0
    unit_of = {name: unit for name, _, unit in anim.table_rows}
    kind = {}                            # the largest value of each unit in the table
    for name, (_, vals, _) in anim.table.items():
        kind[unit_of[name]] = max(kind.get(unit_of[name], 0.0), float(np.abs(vals[np.isfinite(vals)]).max()))
    for k in (0, len(anim.plan.angles) // 2):
        anim.update(k)
        for name, (t, vals, dec) in anim.table.items():
            text, v, big = t.get_text(), float(vals[k]), kind[unit_of[name]]
            assert "e" not in text.lower() and len(text) <= 14, (name, text)
            if dec is not None:          # fixed point: the value to its printed decimals
                assert unit_of[name] == "°" or big == 0 or FIXED_BAND[0] <= big < FIXED_BAND[1], (name, big)
                assert read(text) == pytest.approx(v, abs=0.51 * 10.0 ** -dec), (name, text, v)
            else:                        # beyond the band: five significant digits, or 0 under a billionth
                assert not FIXED_BAND[0] <= big < FIXED_BAND[1], (name, big)
                want = 0.0 if abs(v) < 1e-9 * big else v
                assert read(text) == pytest.approx(want, rel=1e-4, abs=1e-9 * big), (name, text, v)
                columns += 1
    from matplotlib.text import Text   # every text of the frame, the scale bars' numbers too: no computer exponent
    shown = [t.get_text() for t in anim.fig.findobj(Text)]
    assert not [t for t in shown if re.search(r"\de[+-]?\d", t)], shown
    beyond = not FIXED_BAND[0] <= abs(omega) * 1.0 < FIXED_BAND[1]
    assert (columns > 0) == beyond, (omega, columns)


def test_a_scale_is_printed_as_the_tables_print_numbers():
    """Round scales from 1e-120 to 1e120 (1, 2, 2.5 and 5 of each power): the same number, never an exponent."""
    from velpoly.render.scalebar import scale_number
    for power in range(-120, 121):
        for lead in (1.0, 2.0, 2.5, 5.0):
            x = lead * 10.0 ** power
            text = scale_number(x)
            assert "e" not in text and read(text) == pytest.approx(x, rel=1e-12), (x, text)
