"""A textbook problem written as the book gives it (issue 18, items 1-4), on generated mechanisms.

1. a slider's path or a slot along a line of points (``along = ["O4", "B"]``) is the path at that
   line's angle, to 1e-12;
2. a bare magnitude in ``velocity``/``acceleration``, and the acceleration components ``A^n_BA``,
   ``A^t_BA``, ``A^c_B3/B4``, ``A^s_B3/B4`` in ``values``, compared like the rest (the components add
   up to the whole, the Coriolis one is the JSON's, the graphical ones are the analytic ones);
3. senses in words, in any case, read like cw/ccw;
4. notes keyed by the value they explain; a note that names no printed value, or two, is exit 2.
"""
from __future__ import annotations

import math
import random

import numpy as np
import pytest

import velpoly
from mechanisms import inverted_slider_crank, set_path_angle, slider_crank
from velpoly.cli import main
from velpoly.errors import InputError
from velpoly.loader import parse_alpha, parse_omega
from velpoly.reference import compare, evaluate, parse_key

SEEDS = range(12)


def lever(seed: int, along: bool = True) -> dict:
    """A random slotted lever (inverted slider-crank): crank O2A, block 3 at A sliding on lever 4 along
    O4 -> C (``along``; else the generator's path at 0 deg, to be set by set_path_angle)."""
    rng = random.Random(seed)
    r = rng.uniform(1, 4)
    d = rng.uniform(r + 1.5, r + 8)                 # O4 outside the crank circle: the lever swings
    mech = inverted_slider_crank(r, d, rng.uniform(-180, 180), rng.uniform(-20, 20), rng.uniform(-30, 30))
    if along:
        mech["sliders"] = [{"block": "3", "guide": "4", "point": "A", "along": ["O4", "C"]}]
    return mech


def _same(a, b, tol=1e-12):
    """Two solutions agree: every position, velocity and acceleration, relative to its largest."""
    for table in ("position", "velocity", "acceleration"):
        ta, tb = getattr(a, table), getattr(b, table)
        assert ta.keys() == tb.keys()
        scale = max(max(float(np.hypot(*v)) for v in ta.values()), 1e-300)
        for k in ta:
            assert float(np.hypot(*(np.asarray(ta[k]) - tb[k]))) <= tol * scale, (table, k)
    for lk in a.omega:
        assert a.omega[lk] == pytest.approx(b.omega[lk], rel=tol, abs=tol * max(map(abs, a.omega.values())))
        assert a.alpha[lk] == pytest.approx(b.alpha[lk], rel=tol, abs=tol * max(map(abs, a.alpha.values())))


# -- 1. along --------------------------------------------------------------------------------------
@pytest.mark.parametrize("seed", SEEDS)
def test_a_slider_along_a_line_is_the_slider_at_its_angle(seed):
    by_angle = set_path_angle(lever(seed, along=False))
    by_line = lever(seed)
    a, b = velpoly.load(by_angle), velpoly.load(by_line)
    assert b.sliders[0].angle == pytest.approx(a.sliders[0].angle, abs=1e-12)
    _same(velpoly.solve(a), velpoly.solve(b))
    turned = 30.0 + velpoly.solve(a).driver_angle
    _same(velpoly.solve(a, angle=turned), velpoly.solve(b, angle=turned))


@pytest.mark.parametrize("seed", SEEDS[:6])
def test_a_slot_along_a_line_is_the_slot_at_its_angle(seed):
    def slotted(path):
        mech = lever(seed)
        mech["links"] = {"1": {"points": ["O2", "O4"], "frame": True}, "2": {"points": ["O2", "A"]},
                         "4": {"points": ["O4", "C"]}}
        mech["sliders"] = []
        mech["slots"] = [{"pin": "A", "link": "2", "slot": "4", **path}]
        return mech
    c = velpoly.load(slotted({"along": ["O4", "C"]}))
    d = c.position("C") - c.position("O4")
    a = velpoly.load(slotted({"angle": math.degrees(math.atan2(d[1], d[0]))}))
    _same(velpoly.solve(a), velpoly.solve(c))


def test_along_in_a_file_and_its_errors(tmp_path, capsys):
    velpoly_text = """
format = 1
[points]
O2 = [0, 0]
O4 = [0, -3]
A = { from = "O2", length = 1, angle = 30 }
B = { from = "O4", length = 6, along = ["O4", "A"] }
[links]
1 = { points = ["O2", "O4"], frame = true }
2 = { points = ["O2", "A"] }
3 = { points = ["A"] }
4 = { points = ["O4", "B"] }
[[sliders]]
block = "3"
guide = "4"
point = "A"
along = ["O4", "B"]
[driver]
link = "2"
omega = "10 rad/s clockwise"
"""
    m = velpoly.load(velpoly_text)
    a = m.position("A") - m.position("O4")
    assert m.sliders[0].angle == pytest.approx(math.degrees(math.atan2(a[1], a[0])), abs=1e-12)
    assert m.driver.omega == -10.0
    for bad, where, gist in (('along = ["O4", "O4"]', "sliders[0].along (line 17)", "'O4' and 'O4' coincide"),
                             ('along = ["O4", "Z"]', "sliders[0].along (line 17)", "unknown point 'Z'"),
                             ('along = "O4"', "sliders[0].along (line 17)", 'expected \\["P", "Q"\\]'),
                             ('along = ["O4", "B"]\nangle = 3', "sliders[0] (line 13)",
                              "exactly one of 'angle', 'along' and 'centre' \\(angle and along are given\\)")):
        f = tmp_path / "bad.toml"
        f.write_text(velpoly_text.replace('along = ["O4", "B"]', bad))
        assert main(["solve", str(f)]) == 2
        err = capsys.readouterr().err
        assert err.startswith(f"error: {f}: {where}: ") and __import__("re").search(gist, err), err
        assert "\nhint: " in err and "Traceback" not in err


# -- 3. senses in words ----------------------------------------------------------------------------
WORDS = {"cw": -1, "clockwise": -1, "ccw": 1, "counterclockwise": 1, "counter-clockwise": 1, "anticlockwise": 1,
         "anti-clockwise": 1}


@pytest.mark.parametrize("seed", SEEDS)
def test_senses_in_words_in_any_case_read_like_cw_and_ccw(seed):
    rng = random.Random(seed)
    x = rng.uniform(-100, 100)
    for word, sign in WORDS.items():
        cased = "".join(c.upper() if rng.random() < 0.5 else c for c in word)
        for unit, factor in (("rad/s", 1.0), ("rpm", math.pi / 30), ("deg/s", math.pi / 180)):
            assert parse_omega(f"{x!r} {unit} {cased}") == parse_omega(f"{x!r} {unit} {'cw' if sign < 0 else 'ccw'}")
            assert parse_omega(f"{x!r} {unit}  {cased} ") == pytest.approx(sign * x * factor, rel=1e-15)
        assert parse_alpha(f"{x!r} rad/s^2 {cased}") == sign * x
        m = velpoly.load({**slider_crank(), "driver": {"link": "2", "omega": f"{x!r} rad/s {cased}",
                                                        "alpha": f"2 rad/s^2 {cased}"}})
        assert (m.driver.omega, m.driver.alpha) == (sign * x + 0.0, sign * 2.0)
    for bad in ("10 rad/s clock", "10 rad/s anti clockwise", "10 clockwise", "10 rad/s cw clockwise"):
        with pytest.raises(ValueError):
            parse_omega(bad)


# -- 2. bare magnitudes and acceleration components ------------------------------------------------
def _with_reference(mech: dict, **ref) -> dict:
    return {**mech, "reference": {"source": "generated", **ref}}


@pytest.mark.parametrize("seed", SEEDS)
def test_components_add_up_and_match_the_joint_results(seed):
    m = velpoly.load(lever(seed))
    s = velpoly.solve(m)
    val = {k: evaluate(s, parse_key(m, k)) for k in ("A^c_A3/A4", "A^s_A3/A4", "A_A3/A4", "A^n_CO4", "A^t_CO4",
                                                      "A_CO4", "A^n_AO2", "A^t_AO2", "A_A2O2")}
    scale = max(float(np.hypot(*a)) for a in s.acceleration.values())
    slider = s.to_dict()["sliders"][0]
    assert np.allclose(val["A^c_A3/A4"], slider["coriolis"], rtol=0, atol=1e-12 * scale)
    # the acceleration of sliding: along the path, the slider's slip acceleration
    u = s.position["C"] - s.position["O4"]
    u = u / np.hypot(*u)
    assert np.allclose(val["A^s_A3/A4"], slider["slip_acceleration"] * u, rtol=0, atol=1e-12 * scale)
    for whole, parts in (("A_A3/A4", ("A^c_A3/A4", "A^s_A3/A4")), ("A_CO4", ("A^n_CO4", "A^t_CO4")),
                         ("A_A2O2", ("A^n_AO2", "A^t_AO2"))):
        assert np.allclose(val[parts[0]] + val[parts[1]], val[whole], rtol=0, atol=1e-12 * scale), whole
    # normal towards the centre, tangential at right angles to the radius
    r = s.position["C"] - s.position["O4"]
    assert np.dot(val["A^n_CO4"], r) <= 0 and abs(np.dot(val["A^t_CO4"], r)) <= 1e-12 * scale * np.hypot(*r)
    assert np.hypot(*val["A^n_CO4"]) == pytest.approx(s.omega["4"] ** 2 * np.hypot(*r), rel=1e-12, abs=1e-300)


@pytest.mark.parametrize("seed", SEEDS[:6])
def test_printed_components_and_magnitudes_are_compared_like_the_rest(seed):
    from velpoly.compare import comparison
    m0 = velpoly.load(lever(seed))
    s0 = velpoly.solve(m0)

    def polar(v, f=1.0):
        return [float(np.hypot(*v)) * f, math.degrees(math.atan2(v[1], v[0]))]
    ac = evaluate(s0, parse_key(m0, "A^c_A3/A4"))
    asl = evaluate(s0, parse_key(m0, "A^s_A3/A4"))
    an = evaluate(s0, parse_key(m0, "A^n_CO4"))
    values = {"A^c_A3/A4": polar(ac, 1.01), "A^s_A3/A4": polar(asl), "A^n_CO4": float(np.hypot(*an)),
              "A^t_CO4": polar(evaluate(s0, parse_key(m0, "A^t_CO4")))}
    mech = _with_reference(lever(seed), velocity={"C": float(np.hypot(*s0.velocity["C"]))},
                           acceleration={"C": float(np.hypot(*s0.acceleration["C"])) * 0.98}, values=values,
                           note={"A^c_A3/A4": "printed 1 % high", "A_C": "printed 2 % low"})
    m = velpoly.load(mech)
    s = velpoly.solve(m)
    rows = {r.key: r for r in compare(s)}
    assert rows["V_C"].deviation == pytest.approx(0, abs=1e-12) and rows["V_C"].angle_error is None
    assert rows["A_C"].deviation == pytest.approx(1 / 0.98 - 1, rel=1e-9) and rows["A_C"].note == "printed 2 % low"
    assert rows["A^c_A3/A4"].deviation == pytest.approx(abs(1 - 1 / 1.01), rel=1e-9)
    assert rows["A^c_A3/A4"].note == "printed 1 % high" and rows["A^s_A3/A4"].note == ""
    for key in ("A^s_A3/A4", "A^n_CO4", "A^t_CO4"):   # the acceleration of sliding alone, not the whole A_A3/A4
        assert rows[key].deviation == pytest.approx(0, abs=1e-9), key
        assert rows[key].angle_error is None or rows[key].angle_error < 1e-9, key
    # the comparison table: every component's graphical value is the analytic one
    c = comparison(s)
    for key, printed, graphical, analytic in c.values:
        if key.startswith("A^"):
            g = graphical if isinstance(graphical, tuple) else (graphical, 0.0)
            a = analytic if isinstance(analytic, tuple) else (analytic, 0.0)
            assert g[0] == pytest.approx(a[0], rel=1e-9, abs=1e-12), key
            assert abs((g[1] - a[1] + 180) % 360 - 180) < 1e-7, key
    assert [k for _, k, _ in c.notes] == ["A_C", "A^c_A3/A4"]


@pytest.mark.parametrize("key,gist", [
    ("A^n_CO2", "'C' and 'O2' are not on one link"), ("A^t_A2C", "not on one link"),
    ("A^c_A/A4", "the point B of two links"), ("A^s_A3/A3", "the point B of two links"),
    ("A^x_A3/A4", "unknown quantity 'A\\^x_A3/A4'$"),
])
def test_a_component_that_names_nothing_is_an_input_error(key, gist):
    with pytest.raises(InputError) as e:
        velpoly.load(_with_reference(lever(0), values={key: 1.0}))
    assert e.value.where.startswith(f"reference.values.{key}") and __import__("re").search(gist, e.value.what)
    assert "A^c_B3/B4" in e.value.hint


# -- 4. notes keyed by their value -----------------------------------------------------------------
def test_notes_are_keyed_by_the_value_they_explain():
    base = lever(1)
    ref = dict(omega={"4": 1.0}, alpha={"4": 2.0}, velocity={"C": [1.0, 0.0]}, values={"A^c_A3/A4": 1.0})
    m = velpoly.load(_with_reference(base, **ref, note={"omega_4": "w", "alpha_4": "a", "V_C": "v",
                                                          "A^c_A3/A4": "c"}))
    notes = {r.key: r.note for r in compare(velpoly.solve(m))}
    assert notes == {"omega_4": "w", "alpha_4": "a", "V_C": "v", "A^c_A3/A4": "c"}
    # an older file's bare key that names one printed value still reads; one that names two is an error
    m = velpoly.load(_with_reference(base, omega={"4": 1.0}, note={"4": "w"}))
    assert [r.note for r in compare(velpoly.solve(m))] == ["w"]
    for note, gist in (({"4": "?"}, "a note for '4', which names omega_4 and alpha_4"),
                       ({"theta_4": "?"}, "a note for 'theta_4', which is no reference value"),
                       ({"omega_3": "?"}, "which is no reference value")):
        with pytest.raises(InputError) as e:
            velpoly.load(_with_reference(base, **ref, note=note))
        assert e.value.where == f"reference.note.{next(iter(note))}" and gist in e.value.what, e.value.what
        assert "omega_4" in e.value.hint


def test_every_gallery_note_is_keyed_by_its_value():
    from paths import GALLERY_FILES
    from velpoly.reference import value_keys
    for path in GALLERY_FILES:
        ref = velpoly.load(path).reference
        assert set(ref.note) <= set(value_keys(ref)), path.name


# -- 5. the branch each compass construction takes, and the other one ---------------------------------
def _switched(spec: dict, switch: str) -> dict:
    import tomllib
    return {**{k: v for k, v in spec.items() if k not in ("near", "side")}, **tomllib.loads(switch)}


@pytest.mark.parametrize("seed", SEEDS)
def test_each_compass_construction_lists_the_other_intersection_and_how_to_take_it(seed):
    from mechanisms import fourbar
    rng = random.Random(seed)
    while True:   # a four-bar that assembles at this crank angle
        a, b, c, d = (rng.uniform(1, 10) for _ in range(4))
        mech = fourbar(a, b, c, d, theta=rng.uniform(-180, 180), branch=rng.choice(["left", "right"]))
        if seed % 2:   # a sketch point near the intersection instead of a side
            mech["points"]["B"] = {"circles": mech["points"]["B"]["circles"], "near": [rng.uniform(-9, 9), 0]}
        try:
            m = velpoly.load(mech)
        except InputError:
            continue
        break
    (con,) = m.constructions
    assert con.point == "B" and con.kind == "circles" and con.chosen == pytest.approx(m.position("B"), abs=0)
    A, O4 = m.position("A"), m.position("O4")
    for p in (con.chosen, con.other):   # both on both circles
        assert np.hypot(*(np.asarray(p) - A)) == pytest.approx(b, rel=1e-12)
        assert np.hypot(*(np.asarray(p) - O4)) == pytest.approx(c, rel=1e-12)
    cross = (O4 - A)[0] * (np.asarray(con.chosen) - A)[1] - (O4 - A)[1] * (np.asarray(con.chosen) - A)[0]
    assert con.side == ("left" if cross > 0 else "right")
    other = velpoly.load({**mech, "points": {**mech["points"], "B": _switched(mech["points"]["B"], con.switch)}})
    assert np.allclose(other.position("B"), con.other, rtol=0, atol=1e-12 * m.size)
    assert other.constructions[0].other == pytest.approx(con.chosen, abs=1e-12 * m.size)
    # a circle and a line: the slider-crank's block
    s = slider_crank(r=rng.uniform(1, 3), l=rng.uniform(4, 9), e=rng.uniform(-1, 1), theta=rng.uniform(-180, 180),
                     path=rng.uniform(-90, 90))
    m = velpoly.load(s)
    (con,) = m.constructions
    assert con.kind == "circle and line" and con.side is None
    sw = velpoly.load({**s, "points": {**s["points"], "B": _switched(s["points"]["B"], con.switch)}})
    assert np.allclose(sw.position("B"), con.other, rtol=0, atol=1e-9 * m.size)


def test_solve_prints_the_compass_constructions(capsys):
    from paths import example
    assert main(["solve", str(example("problem_1_4_4_sixbar"))]) == 0
    out = capsys.readouterr().out
    part = out.split("Compass constructions", 1)[1].split("\n\n", 1)[0].splitlines()
    assert part[1].split() == ["point", "construction", "taken", "other", "picked", "by", "for", "the", "other", "write"]
    c, f = part[3], part[4]
    assert c.startswith("C      circles B 0.4, D 0.37") and "(-0.0689445, 0.422073) left" in c
    assert "(0.522022, 0.154016) right" in c and c.rstrip().endswith('side = "right"')
    assert f.startswith("F") and "(-0.37, 0.623247)" in f and 'near = { from = "E", angle = 108.17 }' in f


# -- 8. a point of links pinned together is one row in the tables -------------------------------------
@pytest.mark.parametrize("seed", SEEDS[:4])
def test_a_pinned_pair_is_shown_once_and_the_json_keeps_its_keys(seed):
    from velpoly.polygons import acceleration_polygon, velocity_polygon
    from velpoly.render.table import results_table
    from velpoly.report import pinned_keys, solution_report
    m = velpoly.load(lever(seed))
    s = velpoly.solve(m)
    assert {"A@2", "A@3", "A@4"} <= set(s.to_dict()["points"])              # FORMAT.md section 5
    for table in (s.velocity, s.acceleration):   # pinned: equal (to rounding)
        assert np.allclose(table["A@2"], table["A@3"], rtol=0, atol=1e-12 * np.hypot(*table["A@2"]))
    assert pinned_keys(m) == {"A@2": ("A", ("2", "3")), "A@3": None}
    rows = [line for line in solution_report(s).split("Points\n", 1)[1].split("\n\n", 1)[0].splitlines()[2:]]
    labels = [r.split("  ")[0] for r in rows]
    assert "A (on 2 and 3)" in labels and "A₄" in labels and not {"A@2", "A@3"} & set(labels)
    row = rows[labels.index("A (on 2 and 3)")]
    assert row.split("  ")[-1].strip().startswith(f"{np.hypot(*s.acceleration['A@2']):.6g}"[:5])
    report = solution_report(s)   # and the polygons' tables of the same report
    assert "V_A (on 2 and 3) (a" in report and "A_A (on 2 and 3) (a" in report
    assert "V_A@2" not in report and "V_A@3" not in report and "V_A₄ (a₄)" in report
    t = results_table(s, "full", velocity=velocity_polygon(s), acceleration=acceleration_polygon(s))
    names = [r[0] for r in t.rows]
    assert "$V_{A}$ (on 2 and 3)" in names and "$A_{A}$ (on 2 and 3)" in names
    assert not any(n.startswith(("$V_{A₃}$", "$A_{A₃}$", "$V_{A₂}$", "$A_{A₂}$")) for n in names)
    assert "$V_{A₄}$" in names


def test_a_printed_value_of_a_pinned_point_sits_on_its_row():
    from velpoly.polygons import velocity_polygon
    from velpoly.render.table import results_table
    s0 = velpoly.solve(velpoly.load(lever(3)))
    v = s0.velocity["A@2"]
    for key in ("A3", "A2"):   # the book names the point on either link of the pair
        m = velpoly.load(_with_reference(lever(3), velocity={key: [float(np.hypot(*v)), 0.0]},
                                         acceleration={"A4": 1.0}))
        s = velpoly.solve(m)
        rows = {r[0]: r for r in results_table(s, "velocity", velocity=velocity_polygon(s)).rows}
        row = rows["$V_{A}$ (on 2 and 3)"]
        assert row[-2].startswith(f"{np.hypot(*v):.5g}"[:4]) and row[-1]   # reference and deviation
        assert not any(k.startswith(f"$V_{{{key}}}") for k in rows)        # not again below


def test_three_links_pinned_at_a_point_and_a_guide():
    from velpoly.report import on_links, pinned_keys
    assert on_links(("2", "3", "5")) == "2, 3 and 5" and on_links(("2", "3")) == "2 and 3"
    m = velpoly.load(lever(0))
    assert pinned_keys(velpoly.load(slider_crank())) == {}    # one key per point: nothing to merge
    assert pinned_keys(m)["A@2"] == ("A", ("2", "3"))


# -- 9. a notebook shows a Solution as the tables of `velpoly solve` -----------------------------------
def test_a_solution_shows_its_tables_in_a_notebook():
    from velpoly.report import solution_report, solution_tables
    m = velpoly.load(_with_reference(lever(2), omega={"4": 1.0}, note={"omega_4": "a <misprint> & more"}))
    s = velpoly.solve(m)
    html = s._repr_html_()
    tables = solution_tables(s)
    assert html.count("<table>") == len(tables) and html.count("<tr>") == sum(len(t.rows) + 1 for t in tables)
    assert "a &lt;misprint&gt; &amp; more" in html and "<misprint>" not in html
    assert html.startswith("<h4>&lt;dict&gt;</h4>") and solution_report(s).splitlines()[1] in html   # title <dict>
    assert "A (on 2 and 3)" in html
