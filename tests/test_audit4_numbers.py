"""Outside check, every number a figure prints, at any scale (FORMAT.md: a mechanism at any scale; the sheets' rule,
``render/table.number``: 1×10⁻⁹⁰, 1000000, never a computer exponent). Found by the audit, on generated mechanisms:

- the space diagram printed the driver's value as typed, ``ω₂ = 1e-90 rad/s`` (and ``V_B = 1e+90 mm/s`` for a
  slider driver) where its own results table prints 1×10⁻⁹⁰: now the tables' number, its power of ten typeset as
  math (``render/table.number_math``: the value's text holds ``$\\omega_{2}$``, whose fonts lack superscript digits);
- ``velpoly sweep -o`` printed each axis's power of ten as matplotlib does, ``1e90`` (and ``1e6`` for the crank-slider
  example's accelerations): now ``×10⁹⁰``, ``×10⁶`` (``render/sweep.TablesPower``); a slider driver's displacement in
  a legend or a caption (``1.5e-90 m``) as the tables print it;
- ``velpoly html`` printed ``1.0477e+89`` in its results table, tooltips and scale bars: now ``1.0477×10⁸⁹``, the
  sheets' rule in the page's script (the script runs here in Node on a stand-in document, as test_audit2_html's).
"""
from __future__ import annotations

import copy
import json
import re
import subprocess

import matplotlib
import numpy as np
import pytest

import velpoly
from velpoly.render.displacement import draw_mechanism
from velpoly.render.sweep import cycle_figure

from mechanisms import shapes_only
from test_audit2_html import HARNESS, NODE
from zoo import zoo

matplotlib.use("Agg")

EXPONENT = re.compile(r"\de[+-]?\d|\de\d")   # a computer exponent: 1e-90, 1.0477e+89, 1e90
SUPER = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")


def read(text: str) -> float:
    """A number as the sheets print it (1.0477×10⁸⁹, −3.2, or typeset as math: 1{\\times}10^{-90}) back as a float."""
    text = text.replace("−", "-").replace("{\\times}", "×").replace("$", "")
    math_power = re.fullmatch(r"(.*)×10\^\{(-?\d+)\}", text)
    if math_power:
        return float(math_power[1]) * 10.0 ** int(math_power[2])
    mant, times, power = text.partition("×10")
    return float(mant) * (10.0 ** int(power.translate(SUPER)) if times else 1.0)


def specimens():
    """Generated mechanisms with a crank driver and with a slider driver (the zoo's first of each)."""
    crank = slider = None
    for sp in zoo(20261128, 40):
        if "link" in sp.mech["driver"] and crank is None and not sp.mech.get("contacts"):
            crank = sp
        if "slider" in sp.mech["driver"] and slider is None:
            slider = sp
    return crank, slider


def at_rate(sp, rate: float, accel: float) -> velpoly.Mechanism:
    mech = copy.deepcopy(sp.mech)
    keys = ("omega", "alpha") if "link" in mech["driver"] else ("speed", "accel")
    mech["driver"].update(dict(zip(keys, (rate, accel))))
    return velpoly.load(mech)


def test_the_space_diagram_prints_the_drivers_values_as_the_tables_do():
    import matplotlib.pyplot as plt
    crank, slider = specimens()
    assert crank is not None and slider is not None
    seen = 0
    for sp, rate, accel in ((crank, 1e-90, 3e-180), (crank, 12345.0, 0.0), (slider, 1e90, 0.0)):   # 12345: 1.234e+04
        m = at_rate(sp, rate, accel)
        fig, ax = plt.subplots()
        try:
            art = draw_mechanism(velpoly.solve(m), ax, options=shapes_only(m))
            texts = [t.get_text() for t in art["driver"] if hasattr(t, "get_text")]
        finally:
            plt.close(fig)
        want = [rate] + ([accel] if accel else [])
        assert len(texts) == len(want), (sp.kind, rate, texts)
        for text, value in zip(texts, want):
            assert not EXPONENT.search(text), (sp.kind, text)
            number = re.search(r"= (\S+) ", " ".join(text.split())).group(1)
            assert read(number) == pytest.approx(value, rel=5e-4), (sp.kind, text, value)
            seen += 1
    assert seen == 4


def test_a_cycles_axes_print_their_power_of_ten_as_the_tables_do():
    _, slider = specimens()
    tiny = copy.deepcopy(slider.mech)   # a slider driver's stroke at a scale of 1e-90 length units
    tiny["points"] = {k: _scaled(v, 1e-90) for k, v in tiny["points"].items()}
    tiny["driver"]["speed"] *= 1e-90
    angles = np.linspace(-0.05e-90, 0.05e-90, 9) * velpoly.load(slider.mech).size
    fig = cycle_figure(velpoly.sweep(velpoly.load(tiny), angles))
    fig.draw_without_rendering()
    shown = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert not [t for t in shown if EXPONENT.search(t)], shown
    powers = {name: [getattr(a, name).get_offset_text().get_text() for a in fig.axes] for name in ("xaxis", "yaxis")}
    assert all(p.startswith("×10⁻") for p in powers["xaxis"]), powers   # the stroke, in units of 1e-90
    assert any(p.startswith("×10⁻") for p in powers["yaxis"]), powers   # speeds and accelerations


def _scaled(v, k):
    """A [points] entry with every length and coordinate times k (angles and names as they are)."""
    if isinstance(v, list):
        return [_scaled(x, k) for x in v]
    if isinstance(v, dict):
        return {key: (x if key in ("angle", "turn", "side") or isinstance(x, str) else _scaled(x, k))
                for key, x in v.items()}
    return v * k if isinstance(v, (int, float)) and not isinstance(v, bool) else v


@pytest.mark.skipif(NODE is None, reason="no Node.js to run the page's script")
def test_the_page_prints_numbers_as_the_tables_do(tmp_path):
    harness = tmp_path / "harness.js"
    harness.write_text(HARNESS.replace("console.log(JSON.stringify(byId.results.innerHTML));",
                                       "console.log(JSON.stringify([byId.results.innerHTML, byId.velocity.innerHTML]));"))
    crank, _ = specimens()
    for rate in (1e90, 1e-90):
        m = at_rate(crank, rate, 0.0)
        page = tmp_path / "p.html"
        velpoly.html(m, step=60.0).save(page)
        table, polygon = json.loads(subprocess.run([NODE, str(harness), str(page)], capture_output=True, text=True,
                                                   check=True, timeout=60).stdout)
        shown = re.sub(r'data-[a-z]+="[^"]*"', "", table + polygon)   # the data attributes are for programs
        assert not EXPONENT.search(shown), EXPONENT.search(shown)
        omega = dict(re.findall(r"<i>ω</i><sub>(\w+)</sub> \(rad/s\)</td><td>([^<]*)</td>", table))
        sol = velpoly.solve(m)
        assert omega and all(read(v) == pytest.approx(sol.omega[k], rel=1e-4) for k, v in omega.items()), omega
        assert re.search(r"scale: [0-9.]+×10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+ ", polygon), polygon[-400:]
