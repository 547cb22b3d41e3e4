"""Names as books write them (issue 17 item 5, docs/figures.md "Names"): at the data level, over generated
mechanisms whose links are named by numbers and by words.

* a point on a link is drawn with the link as its subscript (p₂, p with the subscript "cam") in the
  polygons' labels, the results table's cells, the step captions and the solve report, never run
  together ("pcam", "V_Pcam") and never with its JSON key's "@";
* no drawn text has a literal "_" outside mathtext (O_v, P_13 are typeset);
* a file without units reads "units/s" and "units/s²", never "s⁻¹";
* every printed direction is in [0, 360): "360.00" never appears.
"""
from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import velpoly
from velpoly.names import direction, key_text, name_math, place, split_key

import mechanisms as M
import zoo

# kinds whose points are keyed P@link (blocks on moving guides, pins in slots, contacts), and plain ones
VARIANTS = [("inverted slider-crank", "offset both crank"), ("slot", "straight six-bar"),
            ("contact", "cam roller follower"), ("six-bar", "floating guide lists the point slider")]


@pytest.fixture(scope="module")
def specimens():
    rng = np.random.default_rng(1717)
    out = []
    for kind, variant in VARIANTS:
        mech = zoo.specimen(rng, kind, variant).mech
        out.append((f"{kind} {variant}, numbers", mech))
        words = M.rename_links(mech)
        words["units"] = ""        # unit-less: the polygons' scales read units/s
        out.append((f"{kind} {variant}, words", words))
    return out


_ANGLE = re.compile(r"∠ ([−\-]?[0-9]+(?:\.[0-9]+)?)°")


def _outside_math(s: str) -> str:
    """The parts of a matplotlib text outside mathtext ($...$, an escaped \\$ is no delimiter)."""
    parts = re.split(r"(?<!\\)\$", s)
    return "".join(parts[0::2])


def _check_text(s: str, sol, where: str) -> None:
    m = sol.mechanism
    assert "@" not in s, (where, s)
    assert "_" not in _outside_math(s), (where, s)
    assert "s⁻¹" not in s and "s⁻²" not in s, (where, s)
    for lk in m.link_names:
        if lk.isdigit():
            continue
        for key in sol.position:
            p, on = split_key(key)
            if on == lk:   # never run together: "pcam", "Pcam"
                assert f"{p}{lk}" not in s and f"{p.lower()}{lk}" not in s, (where, s)
    for a in _ANGLE.findall(s):
        x = float(a.replace("−", "-"))
        assert 0.0 <= x < 360.0, (where, s)


def _texts(fig) -> list[str]:
    from matplotlib.text import Text
    return [t.get_text() for t in fig.findobj(Text) if t.get_text()]


def test_drawn_names_tables_and_captions(specimens):
    """Every specimen's labels, results table and step captions; the full sheet (and its whole table) drawn for one naming of each
    variant (numbers for the first and third, words and no units for the second and fourth: each variant's
    points on links drawn once, both namings drawn twice; all eight until the suite had to fit 2 minutes; the
    sheet's labels are the polygons' ``labels`` checked on all eight here)."""
    from velpoly.render.sheet import constructions, frames, render_sheet
    from velpoly.render.style import rc_context
    from velpoly.render.table import _parts, draw_results_table, results_table
    import matplotlib.figure
    sheets_drawn = 0
    for k, (where, mech) in enumerate(specimens):
        sol = velpoly.solve(velpoly.load(mech))
        cons = constructions(sol, "full")
        drawn_sheet = (k // 2 + k) % 2 == 0     # specimens alternate numbers, words: 0, 3, 4, 7
        with rc_context(velpoly.render.style.get_style("textbook")):
            texts = _texts(render_sheet(sol, "full", "textbook", cons=cons)) if drawn_sheet else []
            sheets_drawn += drawn_sheet
            for s in texts:
                _check_text(s, sol, where)
            # each image of a point on a link is labelled with the link as its subscript
            for poly in (cons.velocity, cons.acceleration):
                if poly is None:
                    continue
                for key, lab in poly.labels.items():
                    p, lk = split_key(key)
                    assert lab == place(p, lk, lower=True, primes=poly.kind == "acceleration"), (where, key, lab)
                    if lk is not None and drawn_sheet:
                        want = name_math(lab)
                        assert any(want in s for s in texts), (where, key, want)
            units = [s for s in texts if "1 cm =" in s]
            if mech["units"] == "" and drawn_sheet:
                assert any("units/s)" in s for s in units) and any("units/s²" in s for s in units), units
            # the results table: every row of a point on a link names it V_P₂ / V_P(cam) and draws the link
            # a subscript of the point's subscript; all rows drawn on a tall axes
            t = results_table(sol, "full", velocity=cons.velocity, acceleration=cons.acceleration, poleset=cons.poles)
            # (drawn with the sheet; for the others every cell's pieces as the table draws them, sizes relative)
            if drawn_sheet:
                tall = matplotlib.figure.Figure(figsize=(12, 30))
                art = draw_results_table(sol, tall.add_axes((0, 0, 1, 1)), table=t)
                assert art.shown == len(t.rows)
                drawn = [(x.get_text(), x.get_fontsize()) for x in art["cells"]]
            else:
                drawn = [piece[:2] for row in t.rows for c in row for piece in _parts(c)]
            for s, _ in drawn:
                _check_text(s, sol, where + " table")
            for key in sol.position:
                p, lk = split_key(key)
                if lk is None or key not in cons.velocity.images or "@" not in key:
                    continue
                rows = [r for r in t.rows if r[0] == f"$V_{{{key_text(key)}}}$"]
                if not rows:
                    continue   # a pinned group's one row "V_A (on 2 and 3)"
                pieces = _parts(rows[0][0])
                assert [x[0] for x in pieces[:3]] == ["V", p, lk] and pieces[2][1] < pieces[1][1] < 1, pieces
                sizes = {f for s, f in drawn if s == lk}
                assert sizes and max(sizes) < max(f for _, f in drawn), (where, key, sizes)
            for row in t.rows:
                for c in row:
                    _check_text(c, sol, where + " table row")
        # the --steps captions: typeset equations, the links as subscripts
        for fr in frames("full", cons, True):
            _check_text(fr.caption, sol, where + " caption")
    assert sheets_drawn == len(VARIANTS)


def test_solve_report_names_and_directions(specimens):
    from velpoly.report import solution_report
    for where, mech in specimens:
        sol = velpoly.solve(velpoly.load(mech))
        text = solution_report(sol)
        for a in _ANGLE.findall(text):
            assert 0.0 <= float(a.replace("−", "-")) < 360.0, (where, a)
        assert "360.000°" not in text
        for key in sol.position:
            p, lk = split_key(key)
            if lk is not None and key in text.split("Velocity polygon", 1)[-1]:
                pytest.fail(f"{where}: the polygon table names {key} by its JSON key")
            if lk is not None and "Velocity polygon" in text:
                assert f"V_{key_text(key)} ({key_text(key, lower=True)})" in text or \
                    f"V_{p} (on " in text, (where, key)
        if mech["units"] == "":
            assert "velocity (units/s)" in text


def test_animation_and_sweep_labels_name_points_on_links(specimens):
    """The GIF's table and the sweep plots' legends: |V_P₂|, never |V_P@2|."""
    from velpoly.render.animate import _name_tex
    from velpoly.render.sweep import _quantity
    for where, mech in specimens:
        m = velpoly.load(mech)
        sol = velpoly.solve(m)
        for key in sol.position:
            p, lk = split_key(key)
            for s in (_name_tex("V", key, bars=True), _quantity("V", key, "|")):
                assert "@" not in s and s.startswith("$|V_{") and s.endswith("}|$")
                if lk is not None:
                    assert name_math(key_text(key)) in s, (where, s)


def test_no_run_together_names_in_equations():
    """A block on a guide named by a word: V_P(blk)/P(S), typeset V with the subscript P_blk / P_S (it read
    as the segment PS)."""
    from velpoly.render.sheet import equation_tex
    s = equation_tex("V_P(blk) = V_P(S) + V_P(blk)/P(S)")
    assert r"$V_{P_{\mathrm{blk}}/P_{S}}$" in s and "_" not in _outside_math(s)
    assert equation_tex("the image is at O_v") == "the image is at $O_{v}$"


@settings(max_examples=200, deadline=None)
@given(st.floats(-1e4, 1e4, allow_nan=False), st.sampled_from([0, 1, 2, 3]))
def test_direction_is_one_range(deg, decimals):
    """Rounded first, then folded into [0, 360): 359.999 prints 0.00; never -0.00 or 360.00; the printed
    value is the direction to the printed precision."""
    s = direction(deg, decimals)
    x = float(s)
    assert 0.0 <= x < 360.0 and not s.startswith("-")
    assert s != f"{360:.{decimals}f}"
    err = abs((x - deg + 180.0) % 360.0 - 180.0)
    assert err <= 0.5 * 10 ** -decimals + 1e-9 * max(1.0, abs(deg))
    assert direction(359.999) == "0.00" and direction(-0.001) == "0.00" and direction(360) == "0.00"


def test_unit_less_scales_read_units_per_second():
    from velpoly.render.scalebar import scale_text
    assert scale_text(8, "", 1) == "1 cm = 8 units/s"
    assert scale_text(8, "", 2) == "1 cm = 8 units/s²"
    assert scale_text(0.05, "m", 0) == "1 cm = 0.05 m"


def test_user_names_stay_literal_in_subscripts():
    """A link named with mathtext's signs is drawn as written (math_literal), in a label and a quantity."""
    from velpoly.names import quantity_math
    lab = place("P", "a_b$", lower=True)
    assert name_math(lab) == r"p_{\mathrm{a\text{_}b\$}}"
    assert quantity_math("V", place("P", "x^2")) == r"$V_{P_{\mathrm{x\text{^}2}}}$"
    assert math.isclose(float(direction(-90)), 270.0)


def test_every_printer_of_a_direction_folds_it():
    """A direction a hair below 0 (a block moving along -y rounded, an acceleration along +x) printed
    "∠ 360.000°" in one table and "∠ 0.00°" in the next: every printer rounds, then folds into [0, 360)."""
    from velpoly.report import polar
    from velpoly.render.table import _vec, _printed
    from velpoly.reference import Row
    tiny = [1.0, -1e-9]
    assert polar(tiny).endswith("∠ 0.000°") and _vec(tiny).endswith("∠ 0.00°")
    assert polar([0.0, -2.0]).endswith("∠ 270.000°") and _vec([-1.0, -1e-12]).endswith("∠ 180.00°")
    row = Row("V_B", (2.0, -0.0001), (2.0, 359.9999), 0.0, 0.0)
    assert _printed(row) == "2 ∠ 0.00°"
