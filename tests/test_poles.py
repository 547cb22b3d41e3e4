"""Instant centres: inspection, Aronhold-Kennedy, the instant-centre method (velpoly.poles).

Every pole is checked against the velocity solution (``relative_pole``: where the two links'
velocity fields agree) and every triple against the Aronhold-Kennedy theorem. Comparisons are
made homogeneously in coordinates scaled by the mechanism's size, x' = (x - c) / L: the sine
between the two unit triples. For a pole within a few sizes of the mechanism that is its
distance in mechanism sizes, so 1e-9 is "1e-9 relative to the mechanism's size"; for a far pole
it is the relative accuracy with which a drawn intersection can fix it (poles at infinity
included).
"""
import collections
import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings, strategies as st

import velpoly
from velpoly.errors import VelpolyError
from velpoly.kinematics import velocities
from velpoly.poles import (_twist_errors, FAR, instant_centre_velocities, kennedy_circle, link_twists, locate_poles,
                           pole_label)
from velpoly.reference import evaluate, parse_key, relative_pole
from velpoly.report import poles_tables, render_table, solution_report, solution_tables
from mechanisms import EXAMPLE_3_6, fourbar, inverted_slider_crank, set_path_angle, slider_crank
from paths import GALLERY_FILES, SIXBAR
from chains import ladder, stage_chain

TOL = 1e-9
# 15 examples a property (50, then 25, until the suite had to fit 2 minutes on 2 cores; each property is one
# class of mechanism, 15 random shapes of it a run): every kind these properties draw from is also checked pole by
# pole at the data level on the zoo's 300 seeded specimens (test_zoo's check_solution runs check_poles at every
# solved pose), so hypothesis here explores the shapes a seeded batch may miss, not the kinds
SETTINGS = dict(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.filter_too_much,
                                                                       HealthCheck.too_slow])


# -- checks shared by every mechanism ----------------------------------------------------------------
def solve_or_reject(d, separation=0.02):
    """Load and solve a generated mechanism; reject draws that do not assemble or are near-singular,
    and draws whose points nearly coincide (closer than ``separation`` of the mechanism's size): a link
    whose pins are 1e-7 apart cannot fix a line through its poles, drawn or computed, to 1e-9."""
    try:
        m = velpoly.load(d)
        xy = np.array(list(m.points.values()), float)
        gaps = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
        assume(gaps[np.triu_indices(len(xy), 1)].min() >= separation * m.size)
        sol = velpoly.solve(m)
    except VelpolyError:
        assume(False)
    assume(not sol.warnings)
    return sol


def local(ps, h):
    """A world homogeneous point in the pole set's normalised coordinates, unit length (a tuple: the checks below
    run on every pole of the zoo's every solved pose, and numpy's small-array calls were most of their cost)."""
    c, L = ps.centre, ps.scale
    x, y, w = float(h[0]), float(h[1]), float(h[2])
    v = (x - float(c[0]) * w, y - float(c[1]) * w, float(L) * w)
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return (v[0] / n, v[1] / n, v[2] / n)


def hom(ps, position, direction):
    if position is not None:
        return local(ps, (position[0], position[1], 1.0))
    t = math.radians(direction)
    return (math.cos(t), math.sin(t), 0.0)


def sine(u, v):
    """|u x v|."""
    return math.sqrt((u[1] * v[2] - u[2] * v[1]) ** 2 + (u[2] * v[0] - u[0] * v[2]) ** 2
                     + (u[0] * v[1] - u[1] * v[0]) ** 2)


def det3(a, b, c):
    """The determinant of the rows a, b, c: a . (b x c)."""
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def check_poles(sol, ps=None):
    """Every property a pole set must have; returns it."""
    ps = locate_poles(sol) if ps is None else ps
    m = sol.mechanism
    names = list(m.link_names)
    n = len(names)
    # all n(n-1)/2, keyed in file order
    assert list(ps.poles) == [f"{names[a]}-{names[b]}" for a in range(n) for b in range(a + 1, n)]
    twists = link_twists(sol)
    at = {name: i for i, name in enumerate(names)}
    # every defined pole's homogeneous point in the normalised coordinates, made once for the checks below
    H = {key: local(ps, p.homogeneous) for key, p in ps.poles.items() if not p.undefined}
    # what each relative twist can be in error by (the solve's componentwise bound, velpoly.poles._alike_pairs)
    w, g, e = _twist_errors(sol, ps.centre, ps.scale)
    for key, p in ps.poles.items():
        i, j = p.links
        rel = np.linalg.norm(twists[at[i]] - twists[at[j]])
        alike = rel <= np.linalg.norm(np.abs(w[at[i]] - w[at[j]]) @ g)
        if p.undefined:
            assert p.how in ("undefined",) and alike, key
            continue
        assert (p.position is None) != (p.direction is None)
        if p.direction is not None:
            assert 0.0 <= p.direction < 180.0
        if alike:
            # links moving alike: any point is their pole; a pin (rolling contact) is still theirs, a block's
            # pole is undefined (FORMAT.md section 5)
            assert p.how in ("pin", "rolling"), key
            continue
        pos, direction = relative_pole(sol, i, j)
        assert pos is not None or direction is not None, key
        # the velocity solution itself fixes the pole only to its bound / |T_i - T_j|, and a pole copied from
        # links moving alike (their relative twist within their bound) carries that relative twist too
        tol = TOL + 2 * float(e.max()) / rel
        reported = hom(ps, p.position, p.direction)
        assert sine(reported, hom(ps, pos, direction)) <= tol, (key, p, pos, direction)
        # (a pole just beyond FAR sizes is reported at infinity: its direction is then within 1/FAR)
        assert sine(reported, H[key]) <= 1e-12 + 2 / FAR
    assert ps.max_error <= TOL
    # Aronhold-Kennedy: P_ij, P_jk, P_ik collinear, points at infinity included
    for a in range(n):
        for b in range(a + 1, n):
            for c in range(b + 1, n):
                tri = [H.get(k) for k in (f"{names[a]}-{names[b]}", f"{names[b]}-{names[c]}",
                                          f"{names[a]}-{names[c]}")]
                if all(t is not None for t in tri):
                    assert abs(det3(*tri)) <= TOL, (names[a], names[b], names[c])
    check_order(ps, H)
    return ps


def check_order(ps, H=None):
    """The order of discovery is complete: every found pole has its place and its two lines
    through poles known before it, and lies on both lines. ``H``: the defined poles' points in the
    normalised coordinates (``local``), by key, where the caller has them."""
    if H is None:
        H = {key: local(ps, p.homogeneous) for key, p in ps.poles.items() if not p.undefined}
    found = [p for p in ps.poles.values() if p.order > 0]
    assert sorted(p.order for p in found) == list(range(1, len(found) + 1))
    assert list(ps.order) == [p.key for p in sorted(found, key=lambda p: p.order)]
    for p in ps.poles.values():
        if p.order == 0:
            assert p.how in ("pin", "slider", "circular path", "rolling", "undefined")
            continue
        assert p.how in ("kennedy", "normals", "alike", "velocity")
        me = H[p.key]
        if p.how in ("kennedy", "normals"):
            for line in p.lines:
                if "-" in line[0]:           # a Kennedy line through two poles known earlier
                    for k in line:
                        q = ps.poles[k]
                        assert q.order < p.order and not q.undefined, (p.key, k)
            assert len(p.lines) == 2 and len(p.via) == 2 and len(p.construction) == 2
            for line, via in zip(p.lines, p.via):
                if "-" in line[0]:
                    assert set(p.links) < set(via) and len(set(via)) == 3
                    k = next(x for x in via if x not in p.links)
                    assert set(line) == {ps.pole(p.links[0], k).key, ps.pole(p.links[1], k).key}
                    a, b = (H[x] for x in line)
                    assert abs(det3(me, a, b)) <= TOL
            for pl in p.construction:   # the drawn line passes through the pole
                if pl.point is None:
                    assert p.at_infinity
                    continue
                assert abs(math.hypot(*pl.direction) - 1) < 1e-12
                a = local(ps, (*pl.point, 1.0))
                assert abs(det3(me, a, (pl.direction[0], pl.direction[1], 0.0))) <= TOL
            assert 0.0 <= p.sine <= 1.0
            if "-" in p.lines[0][0] and "-" in p.lines[1][0]:
                assert p.how == "kennedy"
        elif p.how == "alike":          # P_xy = P_iy, x moving like i (P_ix undefined, or known by inspection)
            (same, source), = p.lines
            assert ps.poles[same].undefined or ps.poles[same].by_inspection
            assert ps.poles[source].order < p.order
            assert sine(me, H[source]) <= 1e-15


def check_ic(sol, ps=None):
    """The instant-centre method reproduces the analytic omegas and velocities to 1e-9."""
    ic = instant_centre_velocities(sol, ps)
    w_ref = max(abs(w) for w in sol.omega.values()) or 1.0
    v_ref = max(np.hypot(*v) for v in sol.velocity.values()) or 1.0
    for lk, w in sol.omega.items():
        assert ic["omega"][lk] == pytest.approx(w, abs=TOL * w_ref), lk
    for key, v in sol.velocity.items():
        assert np.hypot(*(ic["velocity"][key] - v)) <= TOL * v_ref, key
    assert ic["max_error"]["omega"] <= TOL and ic["max_error"]["velocity"] <= TOL
    assert {lk for lk, _, _ in ic["path"]} == set(sol.mechanism.link_names) - {sol.mechanism.frame.name}
    return ic


def check_all(sol):
    ps = check_poles(sol)
    check_ic(sol, ps)
    return ps


def hows(ps):
    return collections.Counter(p.how for p in ps.poles.values())


# -- Examples 3.7 and 3.8 of seeds/000 ------------------------------------------------------------------
# The mechanism of Fig. 3.25 (Example 3.6's data): O2 at the origin, A = O2 + 40/120; the book's
# "R_O2O4 = 20/180" puts O4 20 to the right of O2 (O2 - O4 = 20/180), as the displacement analysis of
# Example 3.8 confirms (R_AO4 = 20/180 + 40/120 = 52.915/139.107). B closes |AB| = 80, |O4B| = 70 at
# theta_BA = 18.5832 deg, theta_BO4 = 59.2134 deg: the 18.584 and 59.214 of Examples 3.6-3.7 are these
# rounded; Example 3.6's data line prints 18.704, a misprint. E is 40 along AB from A and F 15 from E at
# 18.584 - 90 = 288.584 deg.
EX_3_7 = velpoly.load(EXAMPLE_3_6)


def polar(v):
    return math.hypot(*v), math.degrees(math.atan2(v[1], v[0])) % 360.0


def test_example_3_7_poles_by_kennedy_match_the_book():
    s = velpoly.solve(EX_3_7)
    ps = check_all(s)
    A, B, O2 = s.position["A"], s.position["B"], s.position["O2"]
    p13, p24 = ps.pole("1", "3"), ps.pole("2", "4")
    assert p13.how == p24.how == "kennedy"
    # P_24 on the line of centres (P_12 P_14) and on AB (P_23 P_34); P_13 on O2A and O4B (Fig. 3.25a)
    assert set(p24.lines) == {("1-2", "1-4"), ("2-3", "3-4")}
    assert set(p13.lines) == {("1-2", "2-3"), ("1-4", "3-4")}
    # printed: R_P24O2 = 123.029/180, R_AP24 = 108.697/18.584 (book precision: angles to 0.001 deg)
    r, ang = polar(p24.position - O2)
    assert r == pytest.approx(123.029, rel=1e-4) and ang == pytest.approx(180.0, abs=1e-9)
    r, ang = polar(A - p24.position)
    assert r == pytest.approx(108.697, rel=1e-4) and ang == pytest.approx(18.584, abs=1e-3)
    # printed: R_BA = R_P13A + R_BP13 = 59.686/300 + 89.845/59.214
    r, ang = polar(p13.position - A)
    assert r == pytest.approx(59.686, rel=1e-4) and ang == pytest.approx(300.0, abs=1e-9)
    r, ang = polar(B - p13.position)
    assert r == pytest.approx(89.845, rel=1e-4) and ang == pytest.approx(59.214, abs=1e-3)


def test_example_3_7_instant_centre_velocities_match_the_book():
    s = velpoly.solve(EX_3_7)
    ps = locate_poles(s)
    ic = check_ic(s, ps)
    p13 = ps.pole("1", "3").position
    # printed: omega_3 = 6.701 ccw, omega_4 = 8.602 ccw; V_E = 435.218, V_B = 602.084 (Example 3.6's
    # link-by-link answers, 6.702, 602.137 and 435.222, agree to the book's rounding)
    assert ic["omega"]["3"] == pytest.approx(6.701, abs=1.5e-3)
    assert ic["omega"]["4"] == pytest.approx(8.602, abs=1e-3)
    assert np.hypot(*ic["velocity"]["B"]) == pytest.approx(602.084, rel=1e-4)
    assert np.hypot(*ic["velocity"]["E"]) == pytest.approx(435.218, rel=1e-4)
    assert polar(s.position["E"] - p13) == pytest.approx((64.941, 82.86), rel=1e-4)
    # V_B / V_A = R_BP13 / R_AP13 (link 3 turns about P_13)
    vb = np.hypot(*ic["velocity"]["A"]) * np.hypot(*(s.position["B"] - p13)) / np.hypot(*(s.position["A"] - p13))
    assert vb == pytest.approx(np.hypot(*ic["velocity"]["B"]), rel=1e-12)
    # Misprint: R_FP13 = R_EP13 + 15/288.284 should read 15/288.584 (R_FE of the data). With 288.284 the
    # book gets 51.796/75.718 and V_F = 347.123; the right angle gives 51.837/75.645 and V_F = 347.401,
    # which is Example 3.6's link-by-link 347.406 to its rounding.
    e = s.position["E"] - p13
    wrong = e + 15 * np.array([math.cos(math.radians(288.284)), math.sin(math.radians(288.284))])
    assert polar(wrong) == pytest.approx((51.796, 75.718), rel=2e-4)
    assert polar(s.position["F"] - p13) == pytest.approx((51.837, 75.645), rel=1e-4)
    assert np.hypot(*ic["velocity"]["F"]) == pytest.approx(347.406, rel=1e-4)
    # Error in the book: "V_A / V_B = R_AP24 / R_BP24" (400 / V_B = 108.697 / 188.697, V_B = 694.396) treats
    # P_24 as a point of link 3 at rest; link 3 turns about P_13. P_24 is where links 2 and 4 share a velocity.
    assert np.hypot(*ic["velocity"]["B"]) != pytest.approx(694.396, rel=0.1)
    v24_2 = s.body_velocity("2", ps.pole("2", "4").position)
    v24_4 = s.body_velocity("4", ps.pole("2", "4").position)
    assert np.hypot(*(v24_2 - v24_4)) <= 1e-9 * np.hypot(*v24_2)


def test_example_3_8_omega_50_cw():
    d = velpoly.load(EXAMPLE_3_6.replace('omega = "10 rad/s ccw"', 'omega = "50 rad/s cw"'))
    s = velpoly.solve(d)
    ps = check_all(s)
    ic = instant_centre_velocities(s, ps)
    ref = instant_centre_velocities(velpoly.solve(EX_3_7))
    # the poles do not depend on omega_2; every omega scales by -5
    assert ps.pole("1", "3").position == pytest.approx(locate_poles(velpoly.solve(EX_3_7)).pole("1", "3").position)
    for lk in ("2", "3", "4"):
        assert ic["omega"][lk] == pytest.approx(-5 * ref["omega"][lk], rel=1e-12)
    # exact: omega_3 = 33.509 cw, omega_4 = 43.009 cw, V_P24 = 50 x 123.033 = 6151.7/90, |V_B| = 3010.6
    assert ic["omega"]["3"] == pytest.approx(-33.509, abs=1e-3)
    assert ic["omega"]["4"] == pytest.approx(-43.009, abs=1e-3)
    vp24 = evaluate(s, parse_key(s.mechanism, "V_P24"))
    assert polar(vp24) == pytest.approx((50 * 123.0334, 90.0), rel=1e-6)
    # The book's Example 3.8 uses theta_BA = 18.7044 and theta_BP13 = 59.0287 (Example 3.6's misprinted
    # 18.704 carried into a new displacement analysis): its triangle ABP13 then gives R_P13A = 59.2096 as
    # printed (and R_BP13 = 89.721, printed 89.4932: not even its own triangle's), so omega_3 = 2000 /
    # 59.2096 = 33.778 and omega_4 = 33.778 x 89.4932 / 70 = 43.184, 0.8 % and 0.4 % off the exact values.
    t = np.radians([300.0, 59.0287])
    m = np.array([[math.cos(t[0]), math.cos(t[1])], [math.sin(t[0]), math.sin(t[1])]])
    x, y = np.linalg.solve(m, 80 * np.array([math.cos(math.radians(18.7044)), math.sin(math.radians(18.7044))]))
    assert x == pytest.approx(59.2096, rel=1e-4) and y == pytest.approx(89.721, rel=1e-4)
    assert 2000 / x == pytest.approx(33.778, rel=1e-4)
    assert 2000 / x * 89.4932 / 70 == pytest.approx(43.184, rel=1e-4)
    assert abs(ic["omega"]["3"]) != pytest.approx(33.778, rel=5e-3)
    assert abs(ic["omega"]["4"]) != pytest.approx(43.184, rel=3e-3)
    # Its second route, omega_4 = V_P24 / R_P24O4, is right in principle (P_24 is a point of link 4) but
    # divides by 147 and uses R_P24O2 = 127.2394 (printed V_P24 = 6361.97): exact R_P24O4 = 143.033.
    p24 = ps.pole("2", "4").position
    assert np.hypot(*(p24 - s.position["O4"])) == pytest.approx(143.033, rel=1e-5)
    assert np.hypot(*vp24) / np.hypot(*(p24 - s.position["O4"])) == pytest.approx(-ic["omega"]["4"], rel=1e-12)


def test_reference_poles_are_these_poles():
    s = velpoly.solve(EX_3_7)
    ps = locate_poles(s)
    ic = instant_centre_velocities(s, ps)
    for key in ("P_13", "P_24", "P13", "P_14"):
        q = parse_key(s.mechanism, key)
        assert evaluate(s, q) == pytest.approx(ps.pole(*q.links).position, abs=1e-9 * s.mechanism.size)
    q = parse_key(s.mechanism, "V_P24")
    v = evaluate(s, q)
    p24 = ps.pole("2", "4").position
    omega2 = ic["omega"]["2"]
    # V_P24 = omega_2 x (P_24 - P_12) = omega_4 x (P_24 - P_14)
    for lk, pivot in (("2", "1-2"), ("4", "1-4")):
        r = p24 - ps.poles[pivot].position
        assert v == pytest.approx(ic["omega"][lk] * np.array([-r[1], r[0]]), abs=1e-9 * abs(omega2) * s.mechanism.size)


# -- inspection, infinity, undefined ---------------------------------------------------------------------
def test_slider_crank_pole_at_infinity_and_kennedy():
    s = velpoly.solve(velpoly.load(slider_crank(r=3, l=10, e=1, theta=50, path=20)))
    ps = check_all(s)
    p14 = ps.pole("1", "4")
    assert p14.how == "slider" and p14.position is None and p14.direction == pytest.approx(110.0)
    # P_13: the crank line O2A meets the normal to the path through B (through P_14 at infinity)
    p13 = ps.pole("1", "3")
    assert set(p13.lines) == {("1-2", "2-3"), ("1-4", "3-4")}
    B = s.position["B"]
    assert np.dot(p13.position - B, [math.cos(math.radians(20)), math.sin(math.radians(20))]) == pytest.approx(0, abs=1e-9)


def test_slider_crank_at_dead_centre_has_an_undefined_block_pole():
    # the block stops: it moves like the frame, so P_24 = P_12 and P_13 = P_34 = B, and P_14 is undefined
    # (FORMAT.md section 5: two links moving alike): a block's inspection pole is normal to the direction it
    # slides in, which it has not here (tests/test_dead_centres.py: every kind of block, generated)
    s = velpoly.solve(velpoly.load(slider_crank(r=3, l=10, e=0, theta=0, path=0)))
    ps = check_all(s)
    assert ps.pole("1", "4").how == "undefined" and ps.pole("1", "4").undefined
    assert ps.pole("2", "4").position == pytest.approx(s.position["O2"], abs=1e-12)
    assert ps.pole("1", "3").position == pytest.approx(s.position["B"], abs=1e-12)
    assert hows(ps)["alike"] >= 1
    assert s.to_dict()["poles"]["1-4"] == {"position": None, "direction": None, "how": "undefined", "order": 0}


def test_parallelogram_poles_at_infinity_and_a_translating_coupler():
    s = velpoly.solve(velpoly.load(fourbar(a=4, b=10, c=4, d=10, theta=70, branch="left")))
    ps = check_all(s)
    p13, p24 = ps.pole("1", "3"), ps.pole("2", "4")
    assert p13.at_infinity and p13.direction == pytest.approx(70.0, abs=1e-6)   # the coupler translates
    assert p24.at_infinity and p24.direction == pytest.approx(0.0, abs=1e-6) or p24.direction == pytest.approx(180, abs=1e-6)
    ic = instant_centre_velocities(s, ps)
    assert ic["omega"]["3"] == pytest.approx(0.0, abs=1e-12)
    d = s.to_dict()["poles"]["1-3"]
    assert d["position"] is None and d["direction"] == pytest.approx(70.0, abs=1e-6)


def test_poles_of_the_sixbar_example_and_the_json_section():
    s = velpoly.solve(velpoly.load(SIXBAR))
    ps = check_all(s)
    assert len(ps) == 15 and hows(ps)["pin"] == 6 and hows(ps)["slider"] == 1
    d = s.to_dict()["poles"]
    assert list(d) == list(ps.poles)
    for key, p in ps.poles.items():
        if p.position is not None:
            assert d[key]["position"] == pytest.approx(list(p.position))
            assert "direction" not in d[key]
        else:
            assert d[key]["position"] is None and d[key]["direction"] == p.direction
        assert d[key]["how"] == p.how and d[key]["order"] == p.order


def test_kennedy_circle_has_n_points_and_every_chord():
    s = velpoly.solve(velpoly.load(SIXBAR))
    ps = locate_poles(s)
    kc = kennedy_circle(ps)
    n = len(ps.links)
    assert list(kc.points) == list(ps.links)
    assert len(kc.chords) == n * (n - 1) // 2 == len({c.key for c in kc.chords})
    for p in kc.points.values():
        assert np.hypot(*p) == pytest.approx(1.0)
    assert kc.points[ps.links[0]] == pytest.approx([0.0, 1.0])
    assert sum(c.solid for c in kc.chords) == sum(p.by_inspection for p in ps.poles.values()) == 7
    gaps = {round(float(np.hypot(*(kc.points[a] - kc.points[b]))), 9) for a, b in zip(ps.links, ps.links[1:])}
    assert len(gaps) == 1   # equally spaced


def test_readable_tables_list_every_pole_and_both_omegas():
    s = velpoly.solve(EX_3_7)
    t1, t2 = poles_tables(s)
    assert [t.title for t in solution_tables(s)].count(t1.title) == 1   # velpoly solve shows them
    assert [r[0] for r in t1.rows] == ["P_12", "P_13", "P_14", "P_23", "P_24", "P_34"]
    row13 = next(r for r in t1.rows if r[0] == "P_13")
    assert row13[2] == "kennedy" and "P_12" in row13[4] and "P_34" in row13[4]
    assert [r[0] for r in t2.rows] == ["2", "3", "4"]
    assert all(float(r[2]) == pytest.approx(float(r[3]), rel=1e-6) for r in t2.rows)
    text = solution_report(s)
    assert "Instant centres" in text and "Instant-centre method" in text
    assert render_table(t1, "markdown").count("\n| P_") == 6
    assert pole_label("10-12") == "P_{10-12}" and pole_label("1-3") == "P_13"


# -- random mechanisms -----------------------------------------------------------------------------------
# Random mechanisms are drawn to a thousandth: coordinates and lengths on a 1e-3 grid, angles to 0.01
# degree. Exactly degenerate draws stay in (collinear pins, dead centres, links that stop), nearly
# degenerate ones at the 1e-12 level do not: there the relative motion of two links is below what the
# velocity solution resolves, and whether they "move alike" is a matter of rounding.
def grid(lo, hi, step=1e-3):
    return st.integers(round(lo / step), round(hi / step)).map(lambda k: k * step)


angles = grid(0, 360, 0.01)
coords = grid(-1.0, 1.0)
omegas = grid(0.5, 20).flatmap(lambda w: st.sampled_from([w, -w]))


@settings(**SETTINGS)
@given(a=grid(0.5, 3), b=grid(2, 9), c=grid(2, 9), d=grid(2, 9), theta=angles,
       branch=st.sampled_from(["left", "right"]), omega=omegas)
def test_random_fourbars(a, b, c, d, theta, branch, omega):
    s = solve_or_reject(fourbar(a, b, c, d, theta, omega, branch=branch, coupler=(3.0, 40.0)))
    ps = check_all(s)
    c = hows(ps)
    if c["alike"] and not c["undefined"]:
        # omega_3 = omega_4 exactly when A is on the line of centres: then P_13 = P_14 = O4, and P_34 is
        # still the pin B (a pin's pole never depends on how the links move)
        assert math.sin(math.radians(theta)) == pytest.approx(0, abs=1e-12)
        assert c == {"pin": 4, "alike": 2}
        assert np.array_equal(ps.pole("3", "4").position, s.position["B"])
    elif not c["undefined"]:   # (a folded rhombus, B on O2, has two pairs moving alike)
        assert c == {"pin": 4, "kennedy": 2}


@settings(**SETTINGS)
@given(r=grid(0.5, 4), l=grid(5, 12), e=grid(-2, 2), theta=angles, path=angles, omega=omegas)
def test_random_slider_cranks(r, l, e, theta, path, omega):
    s = solve_or_reject(slider_crank(r, l, e, theta, omega, path=path))
    ps = check_all(s)
    p14 = ps.pole("1", "4")   # by inspection, except at a dead centre where the block stops (undefined)
    if p14.undefined:
        assert s.motion.sliders[0]["slip_velocity"][0] == pytest.approx(0, abs=1e-12 * abs(omega) * r)
    else:
        assert p14.how == "slider" and p14.direction == pytest.approx((path + 90) % 180, abs=1e-9)


@settings(**SETTINGS)
@given(r=grid(0.5, 4), d=grid(1, 8), theta=angles, omega=omegas)
def test_random_inverted_slider_cranks(r, d, theta, omega):
    try:
        mech = set_path_angle(inverted_slider_crank(r, d, theta, omega))
    except VelpolyError:
        assume(False)
    s = solve_or_reject(mech)
    ps = check_all(s)
    p34 = ps.pole("3", "4")
    if p34.undefined:   # the block does not slide at this instant (A on the line of centres)
        assert s.to_dict()["sliders"][0]["slip_velocity"] == pytest.approx(0, abs=1e-12 * abs(omega) * r)
    else:
        assert p34.how == "slider" and p34.position is None


@settings(**SETTINGS)
@given(r=grid(0.5, 4), d=grid(2, 8), theta=angles, speed=grid(0.1, 5).flatmap(lambda v: st.sampled_from([v, -v])))
def test_slider_driven_slider_crank(r, d, theta, speed):
    mech = slider_crank(r, 10, 1, theta, path=15.0)
    mech["driver"] = {"slider": "B", "speed": speed}
    s = solve_or_reject(mech)
    check_all(s)


def test_slider_drivers_on_a_moving_guide_and_on_a_circular_path():
    # the block's motion relative to its guide is the input: a translation along a rocker's slot
    # (both twists from lambda_b P_1b - lambda_g P_1g = the relative twist), and a turn about K
    mech = set_path_angle(inverted_slider_crank(3, 7, 60, 5))
    mech["driver"] = {"slider": "A", "speed": 2.0}
    s = velpoly.solve(velpoly.load(mech))
    ic = check_ic(s, check_poles(s))
    assert ic["path"][:2] == (("3", None, "3-4"), ("4", "3", "3-4"))
    d = {"points": {"O2": [0, 0], "O4": [8, 0], "A": [1.5, 2.6], "B": [6, 4]},
         "links": {"1": {"points": ["O2"], "frame": True}, "2": {"points": ["O2", "A"]},
                   "3": {"points": ["A", "B"]}, "4": {"points": ["B"]}},
         "sliders": [{"block": "4", "guide": "1", "point": "B", "centre": "O4"}],
         "driver": {"slider": "B", "speed": 3.0}}
    s = velpoly.solve(velpoly.load(d))
    ic = check_ic(s, check_poles(s))
    assert ic["omega"]["4"] == pytest.approx(3.0 / math.hypot(2, 4), rel=1e-12)   # ccw about O4


def random_chain(topology, frame, points, names, order, omega):
    """A pinned chain: ``topology`` maps each link to its points, all placed at ``points``."""
    fp = set(topology[frame])
    driver = next(lk for lk in order if lk != frame and set(topology[lk]) & fp)
    links = {names[lk]: {"points": list(topology[lk])} for lk in order}
    links[names[frame]]["frame"] = True
    return {"points": {p: list(xy) for p, xy in points.items()}, "links": links,
            "driver": {"link": names[driver], "omega": omega}}


STEPHENSON = {"T1": "abc", "T2": "def", "B1": "ad", "B2": "be", "B3": "cg", "B4": "gf"}
WATT = {"T1": "abc", "T2": "cde", "B1": "af", "B2": "fd", "B3": "bg", "B4": "ge"}
# an eight-bar in which Kennedy's lines stall (found by search): four ternary links 0, 4, 5, 7
EIGHT = {"0": ["p03", "p04", "p06"], "1": ["p14", "p15"], "2": ["p24", "p27"], "3": ["p03", "p37"],
         "4": ["p04", "p14", "p24"], "5": ["p15", "p56", "p57"], "6": ["p06", "p56"], "7": ["p27", "p37", "p57"]}


def chain_strategy(topology):
    pts = sorted({p for ps in topology.values() for p in ps})
    return st.fixed_dictionaries({
        "points": st.fixed_dictionaries({p: st.tuples(coords, coords) for p in pts}),
        "frame": st.sampled_from(sorted(topology)),
        "order": st.permutations(sorted(topology)),
        "names": st.permutations([str(i) for i in range(1, len(topology) + 1)] if len(topology) < 7 else
                                 ["frame", "crank", "c", "d", "E", "F", "g7", "h8"][:len(topology)]),
        "omega": omegas,
    })


def chain_dict(topology, draw):
    names = dict(zip(sorted(topology), draw["names"]))
    return random_chain(topology, draw["frame"], draw["points"], names, draw["order"], draw["omega"])


@settings(**SETTINGS)
@given(draw=chain_strategy(WATT))
def test_random_watt_sixbars_every_inversion(draw):
    check_all(solve_or_reject(chain_dict(WATT, draw)))


@settings(**SETTINGS)
@given(draw=chain_strategy(STEPHENSON))
def test_random_stephenson_sixbars_every_inversion(draw):
    check_all(solve_or_reject(chain_dict(STEPHENSON, draw)))


@pytest.mark.parametrize("name, topology", [("Watt", WATT), ("Stephenson", STEPHENSON)])
def test_kennedy_alone_finds_every_pole_of_generic_sixbars(name, topology):
    # every inversion of both six-bar chains, at generic poses: 7 pins, 8 poles by Kennedy, none from
    # the velocities (hypothesis' near-collinear draws above may need the velocities, legitimately)
    rng = np.random.default_rng(7)
    pts = sorted({p for ps in topology.values() for p in ps})
    for frame in sorted(topology):
        draw = {"points": {p: tuple(rng.uniform(-1, 1, 2)) for p in pts}, "frame": frame,
                "order": sorted(topology), "names": [str(i) for i in range(1, 7)], "omega": 2.0}
        ps = check_all(velpoly.solve(velpoly.load(chain_dict(topology, draw))))
        assert hows(ps) == {"pin": 7, "kennedy": 8}, (name, frame)


# a draw on the 1e-3 grid where the pinned links named "4" and "7" both turn at exactly 4/3 omega_1 (finite differences agree): a pinned pair
# moving alike, whose P_ik = P_jk copies (how 'alike') unblock Kennedy: no pole from the velocities is needed
EIGHT_ALIKE = {"points": {"p03": (0.006, 0.009), "p04": (0.006, 0.0), "p06": (0.009, 0.0), "p14": (0.012, 0.009),
                          "p15": (0.0, 0.009), "p24": (0.012, 0.0), "p27": (0.0, 0.012), "p37": (0.006, 0.012),
                          "p56": (0.0, 0.006), "p57": (0.012, 0.006)},
               "frame": "3", "order": ["5", "1", "0", "4", "6", "3", "2", "7"],
               "names": ["1", "3", "2", "5", "6", "4", "7", "8"], "omega": 2.0}


@settings(**{**SETTINGS, "max_examples": 10, "derandomize": True})
@given(draw=chain_strategy(EIGHT))
@example(draw=EIGHT_ALIKE)
def test_eight_bar_where_kennedy_stalls_is_finished_from_the_velocities(draw):
    # Deterministic (derandomized). Points on a 1e-3 grid can make a pinned pair of links turn exactly alike
    # (EIGHT_ALIKE): then velpoly is right to copy their poles (P_ik = P_jk, how 'alike', each checked against
    # the velocity solution by check_all), and those copies may finish what Kennedy alone could not
    s = solve_or_reject(chain_dict(EIGHT, draw))
    ps = check_all(s)
    c = hows(ps)
    if c["undefined"]:
        return
    assert c["pin"] == 10 and c["kennedy"] + c["velocity"] + c["alike"] == 18
    if c["alike"]:   # every copy names a pinned pair moving alike: its relative twist is zero to the solve's bound
        at = {nm: i for i, nm in enumerate(ps.links)}
        w, g, _ = _twist_errors(s, ps.centre, ps.scale)
        t = link_twists(s)
        for p in ps.poles.values():
            if p.how == "alike":
                i, x, _ = p.via[0]
                assert ps.pole(i, x).how == "pin"
                assert np.linalg.norm(t[at[i]] - t[at[x]]) <= np.linalg.norm(np.abs(w[at[i]] - w[at[x]]) @ g)
    else:
        assert c["velocity"] >= 1


def test_eight_bar_generic_pose_needs_one_pole_from_the_velocities():
    rng = np.random.default_rng(3)
    pts = sorted({p for ps in EIGHT.values() for p in ps})
    draw = {"points": {p: tuple(rng.uniform(-1, 1, 2)) for p in pts}, "frame": "0", "order": sorted(EIGHT),
            "names": [str(i) for i in range(1, 9)], "omega": 1.0}
    ps = check_all(velpoly.solve(velpoly.load(chain_dict(EIGHT, draw))))
    assert hows(ps) == {"pin": 10, "kennedy": 17, "velocity": 1}
    # Kennedy cannot start: no unknown chord closes two triangles of known ones (a line through P_12
    # needs P_1k and P_2k for some k, and link 2 is pinned to links not pinned to the frame...). The
    # pole on the most known lines comes from the velocities, and Kennedy finishes from there.
    first = next(p for p in ps.poles.values() if p.how == "velocity")
    assert first.order == 1
    assert all(p.how == "kennedy" for p in ps.poles.values() if p.order > 1)


@settings(**SETTINGS)
@given(o2=st.tuples(coords, coords), a=st.tuples(coords, coords), s_=grid(-1, 1), radius=grid(0.1, 0.8),
       phi=grid(-60, 60), omega=omegas)
def test_random_wheel_rolling_on_the_frame(o2, a, s_, radius, phi, omega):
    t = np.radians(phi)
    e, n = np.array([np.cos(t), np.sin(t)]), np.array([-np.sin(t), np.cos(t)])
    c = np.array([0.0, -1.5]) + s_ * e + radius * n
    d = {"points": {"O2": list(o2), "A": list(a), "C": c.tolist(), "P": (c - radius * n).tolist()},
         "links": {"1": {"points": ["O2"], "frame": True}, "2": {"points": ["O2", "A"]},
                   "3": {"points": ["A", "C"]}, "4": {"points": ["C"]}},
         "contacts": [{"links": ["4", "1"], "point": "P", "kind": "rolling", "centres": ["C", "flat"]}],
         "driver": {"link": "2", "omega": omega}}
    s = solve_or_reject(d)
    ps = check_all(s)
    assert ps.pole("1", "4").how == "rolling"
    assert ps.pole("1", "4").position == pytest.approx(s.position["P@4"], abs=1e-12)


@settings(**SETTINGS)
@given(o2=st.tuples(coords, coords), o4=st.tuples(coords, coords), u=grid(-0.5, 0.5), off=grid(0.1, 0.5),
       radius=grid(0.1, 0.6), phi=angles, omega=omegas)
def test_random_wheel_rolling_on_a_lever(o2, o4, u, off, radius, phi, omega):
    # wheel 3 (centre C, pinned to crank 2) rolls on the flat of lever 4 (pivot O4)
    t = np.radians(phi)
    e, n = np.array([np.cos(t), np.sin(t)]), np.array([-np.sin(t), np.cos(t)])
    p = np.array(o4) + u * e + off * n
    c = p + radius * n
    d = {"points": {"O2": list(o2), "O4": list(o4), "C": c.tolist(), "P": p.tolist(), "Q": (p + e).tolist()},
         "links": {"1": {"points": ["O2", "O4"], "frame": True}, "2": {"points": ["O2", "C"]},
                   "3": {"points": ["C"]}, "4": {"points": ["O4", "Q"]}},
         "contacts": [{"links": ["3", "4"], "point": "P", "kind": "rolling", "centres": ["C", "flat"]}],
         "driver": {"link": "2", "omega": omega}}
    s = solve_or_reject(d)
    ps = check_all(s)
    assert ps.pole("3", "4").how == "rolling"


@settings(**SETTINGS)
@given(arm=grid(0.3, 1.0), frac=grid(0.2, 0.8), theta=angles, omega=omegas)
def test_planet_gear_on_a_fixed_sun(arm, frac, theta, omega):
    # every pole by inspection (two pins, the pitch point); omega_planet through P_12 and P_02
    t = math.radians(theta)
    c = [arm * math.cos(t), arm * math.sin(t)]
    d = {"points": {"O": [0, 0], "C": c, "P": [frac * c[0], frac * c[1]], "G": [1.0, -1.0]},
         "links": {"0": {"points": ["O", "G"], "frame": True}, "arm": {"points": ["O", "C"]},
                   "planet": {"points": ["C"]}},
         "contacts": [{"links": ["planet", "0"], "point": "P", "kind": "rolling", "centres": ["C", "O"]}],
         "driver": {"link": "arm", "omega": omega}}
    s = solve_or_reject(d)
    ps = check_all(s)
    assert hows(ps) == {"pin": 2, "rolling": 1}
    ic = instant_centre_velocities(s, ps)
    # omega_planet = omega_arm (C - O) / (C - P), along their common line
    assert ic["omega"]["planet"] == pytest.approx(omega / (1 - frac), rel=1e-9)
    assert ic["path"][-1] == ("planet", "arm", "arm-planet")


@settings(**SETTINGS)
@given(ecc=grid(0.1, 0.8), radius=grid(0.5, 1.5), theta=angles, psi=grid(30, 150),
       omega=omegas)
def test_random_cam_with_flat_faced_translating_follower(ecc, radius, theta, psi, omega):
    # sliding contact: P_23 on the common normal through the contact and on the line P_12 P_13
    k = ecc * np.array([math.cos(math.radians(theta)), math.sin(math.radians(theta))])
    dvec = np.array([math.cos(math.radians(psi)), math.sin(math.radians(psi))])
    p = k + radius * dvec
    d = {"points": {"O": [0, 0], "K": k.tolist(), "P": p.tolist(), "F": (p + 0.3 * np.array([-dvec[1], dvec[0]])).tolist()},
         "links": {"1": {"points": ["O"], "frame": True}, "2": {"points": ["O", "K"]}, "3": {"points": ["F"]}},
         "sliders": [{"block": "3", "guide": "1", "point": "F", "angle": psi}],
         "contacts": [{"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": ["K", "flat"]}],
         "driver": {"link": "2", "omega": omega}}
    s = solve_or_reject(d)
    ps = check_all(s)
    p23 = ps.pole("2", "3")
    assert "2-3" in ps.constraint_lines and len(ps.constraint_lines["2-3"]) == 1
    assert ps.pole("1", "3").how == "slider"
    if p23.how == "alike":    # the follower dwells (theta = psi): the cam turns about O under it
        assert np.hypot(*s.velocity["F"]) <= 1e-9 * abs(omega) and p23.position == pytest.approx([0, 0], abs=1e-12)
    else:
        assert p23.how == "kennedy" and ("normal", "P") in p23.lines and ("1-2", "1-3") in p23.lines


@settings(**SETTINGS)
@given(k=st.tuples(coords, coords), q=st.tuples(coords, coords), radius=grid(0.2, 0.8), phi=angles,
       omega=omegas)
def test_random_cam_with_oscillating_flat_faced_follower(k, q, radius, phi, omega):
    n = np.array([math.cos(math.radians(phi)), math.sin(math.radians(phi))])
    p = np.array(k) + radius * n
    d = {"points": {"O": [0.05, -0.02], "K": list(k), "Q": [q[0] + 3, q[1]], "P": p.tolist(),
                    "F": (p + 0.5 * np.array([-n[1], n[0]])).tolist()},
         "links": {"1": {"points": ["O", "Q"], "frame": True}, "2": {"points": ["O", "K"]},
                   "3": {"points": ["Q", "F"]}},
         "contacts": [{"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": ["K", "flat"]}],
         "driver": {"link": "2", "omega": omega}}
    s = solve_or_reject(d)
    check_all(s)


@settings(**SETTINGS)
@given(o3=st.tuples(coords, coords), a=st.tuples(coords, coords), slot=angles, circular=st.booleans(),
       k=st.tuples(coords, coords), omega=omegas)
def test_random_pin_in_a_slot(o3, a, slot, circular, k, omega):
    d = {"points": {"O2": [0, 0], "O3": [o3[0] + 2.5, o3[1]], "A": [a[0] * 0.5, a[1] * 0.5], "S": [3, 2],
                    "K": [k[0] + 2, k[1] + 1]},
         "links": {"1": {"points": ["O2", "O3"], "frame": True}, "2": {"points": ["O2", "A"]},
                   "3": {"points": ["O3", "S", "K"]}},
         "slots": [{"pin": "A", "link": "2", "slot": "3", **({"centre": "K"} if circular else {"angle": slot})}],
         "driver": {"link": "2", "omega": omega}}
    s = solve_or_reject(d)
    ps = check_all(s)
    p23 = ps.pole("2", "3")
    assert ps.pole("1", "3").how == "pin"
    if p23.how == "alike":   # the pin runs along the slot and the lever stands still
        assert abs(s.omega["3"]) <= 1e-9 * abs(omega) and p23.position == pytest.approx([0, 0], abs=1e-12)
    else:
        assert p23.how == "kennedy" and ("slot normal", "A") in p23.lines


@settings(**SETTINGS)
@given(a=grid(0.5, 3), b=grid(2, 9), c=grid(2, 9), d=grid(2, 9), theta=angles,
       branch=st.sampled_from(["left", "right"]), omega=omegas)
def test_block_on_a_circular_path_is_a_fourbar(a, b, c, d, theta, branch, omega):
    # the rocker O4B replaced by a block in a curved slot about O4: P_14 at O4 by inspection
    mech = fourbar(a, b, c, d, theta, omega, branch=branch)
    mech["links"]["1"]["points"] = ["O2"]
    mech["links"]["4"]["points"] = ["B"]
    mech["sliders"] = [{"block": "4", "guide": "1", "point": "B", "centre": "O4"}]
    s = solve_or_reject(mech)
    ps = check_all(s)
    assert ps.pole("1", "4").how == "circular path"
    assert ps.pole("1", "4").position == pytest.approx(s.position["O4@1"], abs=1e-12)   # listed in no link: K@guide


@pytest.mark.parametrize("seed", range(4))
def test_twenty_link_chains(seed):
    d = ladder(21, seed)
    try:
        s = velpoly.solve(velpoly.load(d))
    except VelpolyError:
        pytest.skip("this draw does not assemble or is singular")
    ps = check_all(s)
    assert len(ps) == len(s.mechanism.links) * (len(s.mechanism.links) - 1) // 2


def test_gallery_mechanisms():
    """Every gallery file's poles (a file that stops loading or solving fails here, never skipped: issue 19
    item 7; paths.py fails when there are no gallery files at all)."""
    for f in GALLERY_FILES:
        check_all(velpoly.solve(velpoly.load(f)))


# -- the Kennedy lines as drawn (issue 13 item 4) -----------------------------------------------------
def seeded_mechanisms(seed):
    """Generated mechanisms, one of each kind a pole needs lines for: a four-bar, a slider-crank, an
    inverted slider-crank, a Watt and a Stephenson six-bar, a pin in a straight and in a circular slot,
    a cam with a sliding flat-faced follower (the common normal)."""
    rng = np.random.default_rng(seed)
    u = lambda lo, hi: float(rng.uniform(lo, hi))  # noqa: E731
    xy = lambda: [u(-1, 1), u(-1, 1)]  # noqa: E731
    yield "four-bar", fourbar(u(0.5, 3), u(6, 9), u(6, 9), u(6, 9), u(0, 360), u(-20, 20),
                              branch=str(rng.choice(["left", "right"])))
    yield "slider-crank", slider_crank(u(0.5, 4), u(6, 12), u(-2, 2), u(0, 360), u(1, 9), path=u(0, 180))
    yield "inverted slider-crank", set_path_angle(inverted_slider_crank(u(0.5, 4), u(5, 8), u(0, 360), u(1, 9)))
    for topology in (WATT, STEPHENSON):
        pts = {p: xy() for p in sorted({p for ps in topology.values() for p in ps})}
        order = sorted(topology)
        names = {lk: str(i + 1) for i, lk in enumerate(order)}
        yield "six-bar", random_chain(topology, order[0], pts, names, order, u(1, 9))
    for circular in (False, True):
        yield "pin in a slot", {
            "points": {"O2": [0, 0], "O3": [2.5 + u(-1, 1), u(-1, 1)], "A": [u(-0.5, 0.5), u(-0.5, 0.5)],
                       "S": [3, 2], "K": [2 + u(-1, 1), 1 + u(-1, 1)]},
            "links": {"1": {"points": ["O2", "O3"], "frame": True}, "2": {"points": ["O2", "A"]},
                      "3": {"points": ["O3", "S", "K"]}},
            "slots": [{"pin": "A", "link": "2", "slot": "3", **({"centre": "K"} if circular else {"angle": u(0, 180)})}],
            "driver": {"link": "2", "omega": u(1, 9)}}
    theta, psi, ecc, radius = u(0, 360), u(30, 150), u(0.1, 0.8), u(0.5, 1.5)
    k = ecc * np.array([math.cos(math.radians(theta)), math.sin(math.radians(theta))])
    dv = np.array([math.cos(math.radians(psi)), math.sin(math.radians(psi))])
    p = k + radius * dv
    yield "sliding contact", {
        "points": {"O": [0, 0], "K": k.tolist(), "P": p.tolist(), "F": (p + 0.3 * np.array([-dv[1], dv[0]])).tolist()},
        "links": {"1": {"points": ["O"], "frame": True}, "2": {"points": ["O", "K"]}, "3": {"points": ["F"]}},
        "sliders": [{"block": "3", "guide": "1", "point": "F", "angle": psi}],
        "contacts": [{"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": ["K", "flat"]}],
        "driver": {"link": "2", "omega": u(1, 9)}}


def check_drawn_lines(sol):
    """Every pole found (not by inspection) shows the two lines that located it: each drawn line passes
    through the pole (1e-9 of the mechanism's size) and runs past it, covers its two poles (or, a
    constraint line, the points that define it: the contact point, the pin, a circular slot's centre)
    wherever they are in view, and lies over every body (a wheel's rim or a plate's outline never cuts
    it). Returns the number of lines checked."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from shapely.geometry import Point
    from velpoly.render.canvas import per_cm, view_box
    from velpoly.render.kennedy import draw_poles
    from mechanisms import shapes_only
    fig = Figure(figsize=(8, 6))
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    ps = locate_poles(sol)
    art = draw_poles(sol, ax, poleset=ps, options=shapes_only(sol.mechanism))   # no point labels, no link numbers
    view, pc, size = view_box(ax), per_cm(ax), sol.mechanism.size
    drawn = {ln.get_gid(): ln for ln in art.get("kennedy_lines", [])}
    bodies = [a for role in ("links", "sliders", "ground", "guides") for a in art.get(role, [])]
    top = max((b.get_zorder() for b in bodies), default=0.0)
    checked = 0
    for p in ps.poles.values():
        if p.how not in ("kennedy", "normals"):
            continue
        assert len(p.construction) == 2, p.key
        for ln in p.construction:
            defining = [ps.poles[k].position for k in ln.through] + list(ln.marks)
            wanted = [q for q in defining + [p.position] if q is not None and view.contains(Point(*q))]
            line = drawn.get(f"kennedy-line-{p.key}-{ln.label}")
            if line is None:
                assert not wanted, (p.key, ln.label)   # nothing of it in view
                continue
            assert line.get_zorder() > top, (p.key, ln.label)
            xy = line.get_xydata()
            a, b = xy[0], xy[-1]
            length = float(np.hypot(*(b - a)))
            e = (b - a) / length
            if p.position is None:
                d = np.array([math.cos(math.radians(p.direction)), math.sin(math.radians(p.direction))])
                assert abs(e[0] * d[1] - e[1] * d[0]) <= 1e-9, (p.key, ln.label)
            else:
                r = p.position - a
                assert abs(e[0] * r[1] - e[1] * r[0]) <= 1e-9 * max(size, float(np.hypot(*r))), (p.key, ln.label)
            for q in wanted:   # covered, the pole with room to spare (or the line runs out of the view)
                t = float(np.dot(q - a, e))
                assert -1e-9 * size <= t <= length + 1e-9 * size, (p.key, ln.label, q)
            if p.position is not None and view.contains(Point(*p.position)):
                t = float(np.dot(p.position - a, e))
                for end, room in ((a, t), (b, length - t)):
                    assert room >= 0.5 * pc or view.exterior.distance(Point(*end)) <= 1e-9 * size, (p.key, ln.label)
            checked += 1
    return checked


@pytest.mark.parametrize("seed", [0])   # one seed (two until the suite had to fit 2 minutes): every kind once
def test_kennedy_lines_are_drawn_through_every_found_pole_and_over_the_bodies(seed):
    kinds, lines = set(), 0
    for kind, d in seeded_mechanisms(seed):
        try:
            s = velpoly.solve(velpoly.load(d))
        except VelpolyError:
            continue
        lines += check_drawn_lines(s)
        kinds.add(kind)
    assert len(kinds) >= 6 and lines >= 20, (kinds, lines)


@pytest.mark.parametrize("stem", ["ex3_4_slotted_lever", "fig3_15b_sliding", "wheel_rolling", "cam_roller_follower",
                                  "ex3_7_instant_centres"])
def test_gallery_kennedy_lines_as_drawn(stem):
    from paths import example
    s = velpoly.solve(velpoly.load(example(stem)))
    check_drawn_lines(s)
    if stem == "ex3_4_slotted_lever":   # the slot's normal at its pin A is drawn, through A
        p23 = locate_poles(s).pole("2", "3")
        ln = next(x for x in p23.construction if x.label.startswith("normal to the slot"))
        assert ln.marks and np.array_equal(ln.marks[0], s.position["A"] if "A" in s.position else s.position["A@2"])


# -- a pole by inspection never depends on the other links or on omega (issue 13 item 7) -------------
@pytest.mark.parametrize("stages,omega", [(9, 1e-6), (9, 1e6), (29, 1e6)])
def test_every_pin_is_its_pole_exactly_in_long_chains_at_any_speed(stages, omega):
    # far down a chain of four-bar stages the last rockers turn at 1e-13 of the crank's speed (at 60 links):
    # their pins were once reported "undefined"; they are known to a relative 1e-10 (the solve's
    # componentwise bound), so they move, and no pole of the chain is undefined or copied as alike
    d = stage_chain(stages)
    d["driver"]["omega"] = omega
    s = velpoly.solve(velpoly.load(d))
    ps = locate_poles(s, cached=False)
    assert len(ps) == len(s.mechanism.links) * (len(s.mechanism.links) - 1) // 2
    for pin in s.mechanism.pins:
        p = ps.pole(*pin.links)
        assert p.how == "pin" and p.order == 0 and np.array_equal(p.position, s.place(pin.links[0], pin.point))
    out = s.to_dict()["poles"]
    for pin in s.mechanism.pins:
        assert out[ps.pole(*pin.links).key]["position"] == s.place(pin.links[0], pin.point).tolist()
    assert not any(p.how in ("alike", "undefined") for p in ps.poles.values())
    if stages == 29:   # genuinely moving: every twist far above its bound, and positions perturbed by 4 units in
        # the last place move the slowest twists (1e-13 of the crank's) by a relative 1e-6 at most
        w, g, e = _twist_errors(s, ps.centre, ps.scale)
        t = link_twists(s, ps.centre, ps.scale)
        n = np.linalg.norm(t, axis=1)[1:]
        assert n.min() < 1e-11 * n.max() and np.all(n > 1e3 * e[1:])
        q = s.q * (1 + 4 * np.finfo(float).eps * np.random.default_rng(0).choice([-1, 1], s.q.shape))
        qd, _ = velocities(s.kinematics, q[None])
        moved = dataclasses.replace(s, q=q, qd=qd[0])
        assert np.all(np.linalg.norm(link_twists(moved, ps.centre, ps.scale) - t, axis=1)[1:] <= 1e-6 * n)


# -- the construction on arrays (big mechanisms) against the one on floats ------------------------------
def both_forms(sol):
    """The pole sets of both forms of the construction (velpoly.poles._SMALL forced either way)."""
    import velpoly.poles as P
    small = P._SMALL
    try:
        P._SMALL = 10 ** 9
        floats = P._locate(sol)
        P._SMALL = 0
        arrays = P._locate(sol)
    finally:
        P._SMALL = small
    return floats, arrays


def test_construction_on_arrays_is_the_construction_on_floats():
    """The same poles, found in the same order by the same lines, on generated mechanisms of every kind
    (where a pole has more than 12 lines the arrays pick its pair in two sweeps: then the same pole to
    1e-9, with the same order); the arrays' poles agree with the velocity solution to 1e-9."""
    mechs = [d for seed in range(2) for _, d in seeded_mechanisms(seed)]
    mechs += [ladder(21, seed) for seed in range(2)] + [stage_chain(4), ladder(31, 0)]
    same_lines = identical = 0
    for d in mechs:
        try:
            s = velpoly.solve(velpoly.load(d))
        except VelpolyError:
            continue
        floats, arrays = both_forms(s)
        check_poles(s, arrays)
        check_order(arrays)
        assert floats.order == arrays.order
        assert abs(floats.max_error - arrays.max_error) <= 1e-12
        for key, p in floats.poles.items():
            q = arrays.poles[key]
            assert (p.how, p.order) == (q.how, q.order), key
            assert (p.position is None) == (q.position is None) and p.direction == q.direction, key
            if p.position is not None:
                assert np.hypot(*(p.position - q.position)) <= 1e-9 * s.mechanism.size, key
            same_lines += (p.via, p.lines) == (q.via, q.lines)
        if all((p.via, p.lines) == (arrays.poles[k].via, arrays.poles[k].lines) for k, p in floats.poles.items()):
            identical += 1   # every pole by the same two lines: the very same numbers
            for key, p in floats.poles.items():
                q = arrays.poles[key]
                assert p.position is None or np.array_equal(p.position, q.position), key
                assert p.sine == pytest.approx(q.sine, abs=1e-15)
    assert same_lines > 0.97 * sum(len(m["links"]) * (len(m["links"]) - 1) // 2 for m in mechs)
    assert identical >= 16
