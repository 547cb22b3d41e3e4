"""The analytic kernel against printed textbook answers and finite differences.

Tolerances: printed answers to the book's own precision (5 significant digits for
Problem 1.4.4; 4 for Example 3.6); velocities against a central difference of
poses to 1e-6 relative; accelerations (and every link's alpha) against a central
difference of velocities (omegas) to 1e-6 relative.
"""
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as st

import velpoly
from velpoly.loader import parse_alpha, parse_omega
from mechanisms import (EXAMPLE_3_6, SIXBAR_1_4_4, fourbar, inverted_slider_crank, set_path_angle,
                        slider_crank)
from mechanisms import drop_tiny


def polar(v):
    return math.hypot(*v), math.degrees(math.atan2(v[1], v[0])) % 360


def sig(x, digits):
    """x rounded to ``digits`` significant digits."""
    return float(f"{x:.{digits - 1}e}")


# -- Problem 1.4.4 of seeds/003 -----------------------------------------------------------
def test_problem_1_4_4_positions_velocities_accelerations():
    s = velpoly.solve(velpoly.load(SIXBAR_1_4_4))
    printed_positions = {"B": (0.129904, 0.075), "C": (-0.0689445, 0.422073), "E": (-0.298288, 0.404712),
                         "F": (-0.37, 0.186177)}
    for p, xy in printed_positions.items():
        assert s.position[p] == pytest.approx(xy, abs=1e-6)
    printed = {
        "omega": {"1": 6.28319, "2": -1.1307, "3": -2.82169, "4": 0.58475},
        "alpha": {"2": -22.33, "3": -2.20443, "4": -21.453},
        "V": {"B": (-0.471239, 0.81621), "C": (-0.0788027, 1.04105), "E": (-0.127788, 1.68819),
              "F": (0.0, 1.64625)},
        "A": {"B": (-5.1284, -2.96088), "C": (2.87595, 1.03567), "E": (4.66371, 1.67947), "F": (0.0, 3.29262)},
    }
    for k, v in printed["omega"].items():
        assert sig(s.omega[k], 5) == pytest.approx(v, rel=1e-4)
    for k, v in printed["alpha"].items():
        assert sig(s.alpha[k], 5) == pytest.approx(v, rel=1e-4)
    for p, v in printed["V"].items():
        assert s.velocity[p] == pytest.approx(v, abs=2e-5)
    for p, v in printed["A"].items():
        assert s.acceleration[p] == pytest.approx(v, abs=2e-4)
    assert s.to_dict()["sliders"][0]["slip_velocity"] == pytest.approx(1.64625, rel=1e-5)
    assert s.to_dict()["sliders"][0]["slip_acceleration"] == pytest.approx(3.29262, rel=1e-5)


def test_problem_1_4_4_link_angles_match_the_printout():
    # the book prints phi2 = -60.1903, phi3 = 4.32878, phi4 = 71.8329 (arctan of the slopes: mod 180)
    s = velpoly.solve(velpoly.load(SIXBAR_1_4_4))
    for link, printed in (("2", -60.1903), ("3", 4.32878), ("4", 71.8329)):
        assert (s.angle[link] - printed) % 180 == pytest.approx(0, abs=1e-3) or \
            (s.angle[link] - printed) % 180 == pytest.approx(180, abs=1e-3)


# -- Example 3.6 of seeds/000 ---------------------------------------------------------------
def test_example_3_6_link_by_link():
    s = velpoly.solve(velpoly.load(EXAMPLE_3_6))
    assert s.omega["3"] == pytest.approx(6.702, abs=6e-4)
    assert s.omega["4"] == pytest.approx(8.602, abs=6e-4)
    for p, (mag, ang) in {"B": (602.137, 149.213), "E": (435.222, 172.859), "F": (347.406, 165.644)}.items():
        m, a = polar(s.velocity[p])
        assert m == pytest.approx(mag, rel=2e-4), p
        assert a == pytest.approx(ang, abs=0.01), p
    assert polar(s.velocity["A"]) == pytest.approx((400, 210))


# -- units and senses ----------------------------------------------------------------------
@pytest.mark.parametrize("text, value", [
    ("60 rpm", 2 * math.pi), ("60 RPM ccw", 2 * math.pi), ("10 rad/s cw", -10.0), ("-10 rad/s cw", 10.0),
    ("90 deg/s", math.pi / 2), ("2 Hz", 4 * math.pi), ("1 rev/s cw", -2 * math.pi), ("30 r/min", math.pi),
    (3.5, 3.5), (-2, -2.0)])
def test_omega_strings(text, value):
    assert parse_omega(text) == pytest.approx(value)


@pytest.mark.parametrize("text, value", [("7 rad/s^2 cw", -7.0), ("7 rad/s^2", 7.0), (0, 0.0)])
def test_alpha_strings(text, value):
    assert parse_alpha(text) == pytest.approx(value)


def test_cw_driver_reverses_every_velocity():
    a = velpoly.solve(velpoly.load(fourbar(omega=10)))
    b = velpoly.solve(velpoly.load(fourbar(omega="10 rad/s cw")))
    for k in a.velocity:
        assert b.velocity[k] == pytest.approx(-a.velocity[k], abs=1e-12)
        # centripetal terms do not change sign with omega (alpha = 0)
        assert b.acceleration[k] == pytest.approx(a.acceleration[k], abs=1e-9)


# -- finite differences ---------------------------------------------------------------------
def _rich(f, hr):
    """d f / d theta at the middle of five poses theta + (-h, -h/2, 0, h/2, h): Richardson's
    extrapolation of two central differences, exact to O(h^4), so that a pose near a toggle (where
    the derivatives grow fast) is checked as tightly as any other."""
    d1 = (f[4] - f[0]) / (2 * hr)
    d2 = (f[3] - f[1]) / hr
    return (4 * d2 - d1) / 3


def fd_check(m, angle, h=1e-3):
    """Velocities vs differences of positions; accelerations vs those of velocities (1e-6 relative)."""
    w = velpoly.sweep(m, angle + h * np.array([-1, -0.5, 0, 0.5, 1]))
    assert len(w.angles) == 5
    omega = m.driver.omega
    alpha = m.driver.alpha
    hr = math.radians(h)
    scale_v = max(np.abs(v[2]).max() for v in w.velocity.values()) + 1e-300
    scale_a = max(np.abs(x[2]).max() for x in w.acceleration.values()) + 1e-300
    for key in w.position:
        if "@" in key:
            continue  # coincident points are re-evaluated at a moving place
        v = _rich(w.position[key], hr) * omega
        assert np.abs(v - w.velocity[key][2]).max() <= 1e-6 * scale_v, key
        # A = dV/dth omega + (V/omega) alpha: the difference of velocities
        a = _rich(w.velocity[key], hr) * omega + w.velocity[key][2] / omega * alpha
        assert np.abs(a - w.acceleration[key][2]).max() <= 1e-6 * scale_a, key
    scale_w = max(abs(x[2]) for x in w.omega.values())
    scale_al = max(abs(x[2]) for x in w.alpha.values()) + abs(alpha) + scale_w * abs(omega)
    for link in w.omega:
        th = np.radians(np.unwrap(np.asarray(w.angle[link], float), period=360.0))
        assert _rich(th, hr) * omega == pytest.approx(w.omega[link][2], abs=1e-6 * scale_w), link
        # alpha = d(omega)/d(theta) omega_driver + (omega / omega_driver) alpha_driver
        al = _rich(w.omega[link], hr) * omega + w.omega[link][2] / omega * alpha
        assert al == pytest.approx(w.alpha[link][2], abs=1e-6 * scale_al), link
    # sliders, slots and contacts: the slip acceleration is the rate of the slip velocity
    for kind in ("sliders", "slots", "contacts"):
        for i, joint in enumerate(getattr(w, kind, None) or ()):
            sv, sa = joint["slip_velocity"], joint.get("slip_acceleration")
            if sa is None or not np.all(np.isfinite(sa)):
                continue
            rate = _rich(sv, hr) * omega + sv[2] / omega * alpha
            assert rate == pytest.approx(sa[2], abs=1e-6 * (scale_a + abs(sa[2]))), (kind, i)


def test_fd_problem_1_4_4():
    fd_check(velpoly.load(SIXBAR_1_4_4), 30.0)


def test_fd_example_3_6():
    fd_check(velpoly.load(EXAMPLE_3_6), 120.0)


# The finite differences' own rounding error grows with the pose's condition number (positions and
# velocities carry eps * condition, divided by a step of 1e-3 degrees, twice for an acceleration): at
# 1.3e4-1.8e4 (a crank 0.125 deg from a toggle, a kite 0.03 deg from its change point, found by hypothesis)
# the differences themselves are off by 2e-6-2e-5 of the scale, and shrinking the step makes it worse. The
# random mechanisms are checked where the differences are good to 1e-6; poses near toggles and change points
# have their own tests (test_change_points.py, test_branch.py).
FD_CONDITION = 1e3


def assemblable(d):
    try:
        return velpoly.load(d)
    except velpoly.VelpolyError:
        return None


@settings(max_examples=25, deadline=None)
@given(a=st.floats(1, 5), b=st.floats(4, 12), c=st.floats(3, 12), d=st.floats(4, 12),
       theta=st.floats(-180, 180), omega=st.floats(-20, 20).filter(lambda x: abs(x) > 0.1),
       alpha=st.floats(-50, 50).map(drop_tiny), branch=st.sampled_from(["left", "right"]))
def test_fd_random_fourbars(a, b, c, d, theta, omega, alpha, branch):
    m = assemblable(fourbar(a, b, c, d, theta, omega, alpha, branch, coupler=(3.0, 30.0)))
    assume(m is not None)
    try:
        s = velpoly.solve(m)
    except velpoly.PoseError:
        assume(False)
    assume(s.condition < FD_CONDITION)
    fd_check(m, s.driver_angle)


@settings(max_examples=20, deadline=None)
@given(r=st.floats(1, 4), l=st.floats(6, 15), e=st.floats(-2, 2), theta=st.floats(-180, 180),
       omega=st.floats(-20, 20).filter(lambda x: abs(x) > 0.1), alpha=st.floats(-30, 30).map(drop_tiny),
       path=st.floats(-60, 60))
def test_fd_random_slider_cranks(r, l, e, theta, omega, alpha, path):
    m = assemblable(slider_crank(r, l, e, theta, omega, alpha, path))
    assume(m is not None)
    s = velpoly.solve(m)
    assume(s.condition < FD_CONDITION)
    fd_check(m, s.driver_angle)
    # the block moves along its path: V_B parallel to the path direction
    t = math.radians(path)
    vb = s.velocity["B"]
    assert abs(vb[0] * math.sin(t) - vb[1] * math.cos(t)) <= 1e-9 * (1 + np.hypot(*vb))


@settings(max_examples=20, deadline=None)
@given(r=st.floats(1, 4), d=st.floats(5, 10), theta=st.floats(-180, 180),
       omega=st.floats(-20, 20).filter(lambda x: abs(x) > 0.1), alpha=st.floats(-30, 30).map(drop_tiny))
def test_fd_random_inverted_slider_cranks(r, d, theta, omega, alpha):
    m = velpoly.load(set_path_angle(inverted_slider_crank(r, d, theta, omega, alpha)))
    s = velpoly.solve(m)
    fd_check(m, s.driver_angle)
    # block and guide turn together; the Coriolis term is 2 omega_4 x V_rel
    assert s.omega["3"] == pytest.approx(s.omega["4"], abs=1e-9 * abs(omega))
    sl = s.to_dict()["sliders"][0]
    d_ = s.motion.sliders[0]["direction"][0]
    vrel = sl["slip_velocity"] * np.array([math.cos(math.radians(d_)), math.sin(math.radians(d_))])
    cor = 2 * s.omega["4"] * np.array([-vrel[1], vrel[0]])
    assert sl["coriolis"] == pytest.approx(cor, abs=1e-9 * (1 + np.hypot(*cor)))
    # A_A(3) = A_A(4) + A_rel + Coriolis, with A_rel along the path
    a3, a4 = s.acceleration["A@3"], s.acceleration["A@4"]
    arel = a3 - a4 - cor
    e = np.array([math.cos(math.radians(d_)), math.sin(math.radians(d_))])
    assert abs(arel[0] * e[1] - arel[1] * e[0]) <= 1e-9 * (1 + np.hypot(*a3))
    assert np.dot(arel, e) == pytest.approx(sl["slip_acceleration"], abs=1e-9 * (1 + np.hypot(*a3)))



@pytest.mark.parametrize("omega, alpha", [(40.0, 0.0), (-7.3, 2.9), (0.1, -1e3)])
def test_the_driver_reads_its_input_exactly(omega, alpha):
    """The crank's omega and alpha are the file's, to the last bit (the linear solve is not allowed to
    turn 40 rad/s into 39.99999999999999); its points move with exactly that omega."""
    for d in (inverted_slider_crank(3.0, 7.0, 45.0, omega, alpha), SIXBAR_1_4_4):
        m = velpoly.load(d)
        s = velpoly.solve(m)
        drv = m.driver
        out = s.to_dict()["links"][drv.link]
        assert out["omega"] == drv.omega and out["alpha"] == drv.alpha
        assert s.omega[drv.link] == drv.omega

def test_sweep_one_turn_is_continuous_and_closes():
    m = velpoly.load(fourbar(2, 8, 7, 9))   # Grashof crank-rocker
    ref = velpoly.solve(m).driver_angle
    w = velpoly.sweep(m, ref + np.arange(0, 360.01, 0.5))
    assert len(w.angles) == 721 and not w.stopped
    for key, p in w.position.items():
        assert np.abs(np.diff(p, axis=0)).max() < 0.2
        assert p[-1] == pytest.approx(p[0], abs=1e-9)


def test_solve_at_angle_equals_sweep():
    m = velpoly.load(SIXBAR_1_4_4)
    s = velpoly.solve(m, angle=100.0)
    w = velpoly.sweep(m, [100.0])
    assert s.driver_angle == pytest.approx(100.0)
    for k in s.velocity:
        assert s.velocity[k] == pytest.approx(w.velocity[k][0], abs=1e-12)


def test_mobility_is_counted_by_rank():
    # a four-bar with its coupler doubled by a second, parallel-free bar is locked (mobility 0)
    d = fourbar()
    d["points"]["G"] = [4.0, -3.0]
    d["links"]["1"]["points"].append("G")
    d["links"]["5"] = {"points": ["G", "B"]}
    with pytest.raises(velpoly.InputError, match="mobility is 0"):
        velpoly.solve(velpoly.load(d))
    # without the rocker it has two degrees of freedom
    d = fourbar()
    del d["links"]["4"]
    d["links"]["1"]["points"].remove("O4")
    d["points"].pop("O4")
    d["points"]["B"] = [9.0, 4.0]
    with pytest.raises(velpoly.InputError, match="mobility is 2"):
        velpoly.solve(velpoly.load(d))


def test_json_matches_contract():
    s = velpoly.solve(velpoly.load(SIXBAR_1_4_4)).to_dict()
    assert s["format"] == 1 and s["units"] == {"length": "m"}
    assert s["driver"] == {"link": "1", "angle": pytest.approx(30.0), "omega": pytest.approx(2 * math.pi),
                           "alpha": 0.0}
    assert set(s["links"]) == {"0", "1", "2", "3", "4", "5"}
    assert s["links"]["0"]["omega"] == 0.0
    assert set(s["points"]) == {"A", "B", "C", "D", "E", "F"}
    for v in s["links"].values():
        assert -180 < v["angle"] <= 180


def _count_newton(monkeypatch):
    """A list that grows by one at each call of the continuation's Newton corrector."""
    import velpoly.pose as pose
    calls, real = [], pose._newton
    monkeypatch.setattr(pose, "_newton", lambda *a, **k: calls.append(1) or real(*a, **k))
    return calls


def test_the_closed_form_check_tells_a_wrong_branch_and_a_wrong_mechanism():
    """The joint equations on the walk's poses refuse a plan that is not the mechanism's; both
    assemblies satisfy them, so the plan's sides are checked against the drawn pose."""
    from dataclasses import replace
    import velpoly.pose as pose
    from velpoly.dyads import assemble, draws_the_reference, dyad_plan
    from velpoly.kinematics import prepare
    for m in (velpoly.load(EXAMPLE_3_6), velpoly.load(slider_crank())):
        kin = prepare(m)
        system, rows = kin.system.positions, list(kin.rows)
        plan = dyad_plan(m)
        assert draws_the_reference(m, plan)
        deltas = np.radians(np.arange(0.0, 50.0, 1.0))
        q, reach = assemble(m, system.index, plan, deltas)
        assert reach == len(deltas) and pose.check_closed_form(system, rows, q, deltas)
        other = replace(plan, steps=plan.steps[:-1] + (plan.steps[-1][:-1] + (-plan.steps[-1][-1],),))
        assert not draws_the_reference(m, other)
        q2, _ = assemble(m, system.index, other, deltas)
        assert pose.check_closed_form(system, rows, q2, deltas)    # the other branch: joints hold
        wrong = q.copy()
        wrong[len(deltas) // 2, 3 * system.index[plan.steps[-1][1]]] += 1e-6 * m.size
        assert not pose.check_closed_form(system, rows, wrong, deltas)  # a joint open: refused
        assert not pose.check_closed_form(system, rows, q, deltas + 1e-3)  # at other positions


@pytest.mark.parametrize("text", [SIXBAR_1_4_4, EXAMPLE_3_6, "slider-crank"])
def test_closed_form_dyads_equal_continuation(text, monkeypatch):
    """The vectorised dyad assembly and Newton continuation find the same branch (1e-9)."""
    import velpoly.pose as pose
    from velpoly.dyads import dyad_plan
    m = velpoly.load(slider_crank() if text == "slider-crank" else text)
    assert dyad_plan(m) is not None
    ref = velpoly.solve(m).driver_angle
    angles = ref + np.arange(0, 360, 7.0)
    newton = _count_newton(monkeypatch)
    fast = velpoly.sweep(m, angles)
    assert not newton, "the sweep with a dyad plan continued"
    monkeypatch.setattr(pose, "check_closed_form", lambda *a: False)   # every walk refused
    slow = velpoly.sweep(m, angles)
    assert newton, "the sweep without the closed form did not continue"
    assert len(fast.angles) == len(slow.angles) == len(angles)
    vmax = max(np.abs(v).max() for v in slow.velocity.values())
    amax = max(np.abs(a).max() for a in slow.acceleration.values())
    for key in fast.position:
        assert fast.position[key] == pytest.approx(slow.position[key], abs=1e-9 * m.size)
        assert fast.velocity[key] == pytest.approx(slow.velocity[key], abs=1e-9 * vmax)
        assert fast.acceleration[key] == pytest.approx(slow.acceleration[key], abs=1e-9 * amax)
    for link in fast.omega:
        assert fast.alpha[link] == pytest.approx(slow.alpha[link], abs=1e-9 * amax / m.size)


def test_closed_form_stops_at_the_toggle_like_continuation(monkeypatch):
    import velpoly.pose as pose
    m = velpoly.load(fourbar(4, 5, 6, 9))   # non-Grashof: the crank cannot turn round
    ref = velpoly.solve(m).driver_angle
    angles = ref + np.arange(0, 360, 1.0)
    newton = _count_newton(monkeypatch)
    fast = velpoly.sweep(m, angles)
    assert not newton
    monkeypatch.setattr(pose, "check_closed_form", lambda *a: False)
    slow = velpoly.sweep(m, angles)
    assert newton
    assert fast.stopped and slow.stopped
    assert abs(len(fast.angles) - len(slow.angles)) <= 1


@pytest.mark.parametrize("angles", [[-100.0, -99.0], [100.0, 105.0, 200.0, 105.0], [100.0, 50.0, 0.0, -100.0, -105.0]])
def test_closed_form_follows_the_path_between_positions_like_continuation(monkeypatch, angles):
    """A toggle between two requested positions stops the closed form too: -100 is reached from the
    drawn 100 the shorter way, across the toggle at 109.47 deg (cos = -1/3), so not at all; a jump
    from 105 to 200 crosses it; going down through 0 crosses none."""
    import velpoly.pose as pose
    m = velpoly.load(fourbar(4, 5, 6, 9, theta=100.0))
    fast = velpoly.sweep(m, np.array(angles))
    monkeypatch.setattr(pose, "check_closed_form", lambda *a: False)
    slow = velpoly.sweep(m, np.array(angles))
    assert len(fast.angles) == len(slow.angles) and bool(fast.stopped) == bool(slow.stopped)
    if len(slow.angles):
        assert np.allclose(fast.position["B"], slow.position["B"], atol=1e-9)


def test_import_is_light_and_the_api_names_stay_functions():
    """`velpoly --help` imports no numpy; importing every module keeps load/solve/sweep callable."""
    import subprocess
    import sys
    out = subprocess.run([sys.executable, "-c", "import sys, velpoly.cli; print('numpy' in sys.modules)"],
                         capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
    import velpoly.centrodes, velpoly.sweeps, velpoly.solution, velpoly.loader  # noqa: F401,E401
    assert callable(velpoly.sweep) and callable(velpoly.solve) and callable(velpoly.load)


# -- the model -------------------------------------------------------------------------------------
def test_the_mechanism_is_immutable_and_shares_nothing_with_its_source():
    import copy
    import dataclasses
    import tomllib
    d = tomllib.loads(EXAMPLE_3_6 + '\n[drawing]\nlabel_points = ["A", "B"]\n')
    d["reference"] = {"source": "book", "omega": {"3": 1.0}, "velocity": {"B": [1.0, 30.0]},
                      "values": {"V_B": [1.0, 30.0]}}
    keep = copy.deepcopy(d)
    m = velpoly.load(d)
    before = (dict(m.points), m.links, m.pins, m.driver, {k: dict(getattr(m.reference, k)) for k in
                                                          ("omega", "velocity", "values")}, dict(m.drawing))
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.title = "changed"
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.driver.omega = 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.links[0].frame = False
    for mapping in (m.points, m.carriers, m.drawing, m.reference.omega, m.reference.velocity):
        with pytest.raises(TypeError):
            mapping["X"] = 1
    assert isinstance(m.links, tuple) and all(isinstance(k.points, tuple) for k in m.links)
    assert isinstance(m.reference.velocity["B"], tuple) and isinstance(m.reference.values["V_B"], tuple)
    m.position("B")[:] = 99.0                      # a copy: the model's point stays where it was
    # changing the dict it was read from changes nothing in it
    for name, link in d["links"].items():
        link["points"].append("A")
    d["points"]["A"] = [5, 5]
    d["reference"]["velocity"]["B"][0] = 7.0
    d["reference"]["values"]["V_B"][1] = 0.0
    d["drawing"]["label_points"].append("C")
    after = (dict(m.points), m.links, m.pins, m.driver, {k: dict(getattr(m.reference, k)) for k in
                                                         ("omega", "velocity", "values")}, dict(m.drawing))
    assert after == before
    assert velpoly.load(keep).points == m.points
    # and solving does not change it either
    velpoly.solve(m, angle=m.driver.angle)
    velpoly.sweep(m, [100.0, 110.0])
    assert (dict(m.points), m.links, m.driver) == before[:1] + before[1:2] + before[3:4]


def test_every_point_construction():
    """Each construction of FORMAT.md section 1 against its closed form."""
    text = """
title = "every construction: all but B on the frame"
[points]
D = [10, 0]
A = [0, 0]
B = { from = "A", length = 5, angle = 30 }
T = { to = "B", length = 2, angle = 90 }
E = { from = "B", length = 3, along = ["A", "D"], turn = 90 }
G = { from = "B", length = 3, along = ["A", "B"] }
H = { from = "B", length = 3, along = ["A", "B"], turn = -90 }
C1 = { circles = [["B", 8], ["D", 6]], near = [8, 6] }
C2 = { circles = [["B", 8], ["D", 6]], near = [8, -6] }
C3 = { circles = [["B", 8], ["D", 6]], side = "left" }
C4 = { circles = [["B", 8], ["D", 6]], side = "right" }
C5 = { circles = [["B", 8], ["D", 6]], near = "T" }
C6 = { circles = [["B", 8], ["D", 6]], near = { from = "B", angle = -60 } }
C7 = { circles = [["B", 8], ["D", 6]], near = { from = "B", angle = 10 } }
F1 = { circle = ["B", 7], line = { through = [0, -1], angle = 0 }, near = [20, 0] }
F2 = { circle = ["B", 7], line = { through = "D", angle = 90 }, near = [10, 20] }
F3 = { circle = ["B", 7], line = ["A", "D"], near = [-5, 0] }
[links]
1 = { points = ["A", "D", "T", "E", "G", "H", "C1", "C2", "C3", "C4", "C5", "C6", "C7", "F1", "F2", "F3"], frame = true }
2 = { points = ["A", "B"] }
[driver]
link = 2
omega = 1
"""
    m = velpoly.load(text)
    P = {k: m.position(k) for k in m.points}
    c30, s30 = math.cos(math.radians(30)), math.sin(math.radians(30))
    b = np.array([5 * c30, 5 * s30])
    assert P["B"] == pytest.approx(b, abs=1e-12)
    assert P["T"] == pytest.approx(b - [0, 2], abs=1e-12)                   # B lies at 2, 90 deg from T
    assert P["E"] == pytest.approx(b + [0, 3], abs=1e-12)                   # along A->D (+x) turned 90 ccw
    assert P["G"] == pytest.approx(b + 3 * np.array([c30, s30]), abs=1e-12)
    assert P["H"] == pytest.approx(b + 3 * np.array([s30, -c30]), abs=1e-12)
    # the two circles about B (8) and D (6): both intersections in closed form
    d_ = np.array([10.0, 0.0])
    u = (d_ - b) / np.linalg.norm(d_ - b)
    dist = np.linalg.norm(d_ - b)
    x = (dist ** 2 + 8 ** 2 - 6 ** 2) / (2 * dist)
    h = math.sqrt(8 ** 2 - x ** 2)
    left, right = b + x * u + h * np.array([-u[1], u[0]]), b + x * u - h * np.array([-u[1], u[0]])
    assert left[1] > 0 > right[1]
    for k, want in (("C1", left), ("C2", right), ("C3", left), ("C4", right), ("C5", right), ("C6", right), ("C7", left)):
        assert P[k] == pytest.approx(want, abs=1e-12), k
        assert np.linalg.norm(P[k] - b) == pytest.approx(8) and np.linalg.norm(P[k] - d_) == pytest.approx(6)
    # circle about B (7) and a line: y = -1, x = 10, y = 0
    assert P["F1"] == pytest.approx([b[0] + math.sqrt(49 - (b[1] + 1) ** 2), -1], abs=1e-12)
    assert P["F2"] == pytest.approx([10, b[1] + math.sqrt(49 - (10 - b[0]) ** 2)], abs=1e-12)
    assert P["F3"] == pytest.approx([b[0] - math.sqrt(49 - b[1] ** 2), 0], abs=1e-12)


def test_newton_reassembles_a_mechanism_drawn_without_constructions():
    """A four-bar whose points are bare coordinates, and a curved slider (no closed form):
    re-assembled by Newton continuation from the reference pose, on the drawn branch."""
    from velpoly.dyads import dyad_plan
    built = velpoly.load(fourbar(2, 8, 7, 9, theta=40.0, branch="right"))
    bare = fourbar(2, 8, 7, 9)
    bare["points"] = {k: list(built.points[k]) for k in built.points}
    m = velpoly.load(bare)
    w_built = velpoly.sweep(built, 40.0 + np.arange(0, 361, 15.0))
    w_bare = velpoly.sweep(m, 40.0 + np.arange(0, 361, 15.0))
    assert len(w_bare.angles) == 25 and not w_bare.stopped
    for key in w_built.position:
        assert w_bare.position[key] == pytest.approx(w_built.position[key], abs=1e-9)
        assert w_bare.velocity[key] == pytest.approx(w_built.velocity[key], abs=1e-8)
    s = velpoly.solve(m, angle=-135.0)
    assert s.position["B"] == pytest.approx(velpoly.solve(built, angle=-135.0).position["B"], abs=1e-9)
    # a block pinned to the crank at A slides in a curved slot (about K) of the rocker 3, which turns
    # about O4: a circular path on a moving guide, no dyad plan, Newton all the way round
    curved = {
        "points": {"O2": [0.0, 0.0], "O4": [10.0, 0.0], "A": {"from": "O2", "length": 3.0, "angle": 60.0},
                   "K": {"from": "O4", "length": 5.0, "angle": 90.0}},
        "links": {"1": {"points": ["O2", "O4"], "frame": True}, "2": {"points": ["O2", "A"]},
                  "3": {"points": ["O4", "K"]}, "4": {"points": ["A"]}},
        "sliders": [{"block": "4", "guide": "3", "point": "A", "centre": "K"}],
        "driver": {"link": "2", "omega": 4.0, "alpha": -1.0}}
    m = velpoly.load(curved)
    assert dyad_plan(m) is None
    w = velpoly.sweep(m, 60.0 + np.arange(0, 361, 5.0))
    assert len(w.angles) == 73 and not w.stopped
    radius = np.linalg.norm(m.position("A") - m.position("K"))
    ka = w.position["A"] - w.position["K"]
    assert np.abs(np.hypot(*ka.T) - radius).max() < 1e-9       # A stays on the slot's arc
    assert np.abs(np.hypot(*(w.position["K"] - [10, 0]).T) - 5).max() < 1e-9
    for key in w.position:                                     # the same pose after a turn
        assert np.abs(w.position[key][-1] - w.position[key][0]).max() < 1e-9, key
    fd_check(m, 100.0)
    # the Coriolis term of a curved slot on a turning guide: 2 omega_3 x V_rel (FORMAT.md section 5)
    s = velpoly.solve(m, angle=100.0)
    vrel = s.velocity["A"] - s.body_velocity("3", s.position["A"])
    cor = 2 * s.omega["3"] * np.array([-vrel[1], vrel[0]])
    assert s.to_dict()["sliders"][0]["coriolis"] == pytest.approx(cor, abs=1e-9 * np.hypot(*cor))
    assert np.hypot(*cor) > 1.0


def _printed_digits_unit(x: float) -> float:
    """One unit in the last digit of ``x`` as written (0.651 -> 0.001, 97.0 -> 1)."""
    text = repr(abs(float(x)))
    if "e" in text:
        mant, exp = text.split("e")
        return 10.0 ** (int(exp) - len(mant.replace(".", "").lstrip("0").rstrip("0") or "0") + 1)
    whole, _, frac = text.partition(".")
    frac = frac.rstrip("0")
    if frac:
        return 10.0 ** -len(frac)
    return 10.0 ** (len(whole) - len(whole.rstrip("0")))


from paths import BOOK_FILES as SEEDS  # noqa: E402


def _agrees(printed: float, computed: float) -> bool:
    """A book's figure: to one unit of its last printed digit, or 1e-4 relative (books carry rounded
    intermediate values, so 602.137 for 602.1236)."""
    return abs(computed - printed) <= max(_printed_digits_unit(printed), 1e-4 * abs(printed)) + 1e-12


@pytest.mark.parametrize("path", SEEDS, ids=[p.stem for p in SEEDS])
def test_seed_example_files_match_their_printed_answers(path):
    """Every printed value of a seed example file with the book's answers (its [reference]), magnitudes and
    directions, as ``velpoly solve`` compares them, but those a `note` marks as misprints."""
    from velpoly.reference import compare
    m = velpoly.load(path)
    assert m.reference, path
    checked = 0
    for r in compare(velpoly.solve(m)):
        if r.note or r.computed is None:
            continue
        printed, computed = r.printed, r.computed
        if isinstance(printed, tuple) and r.key.startswith("P") and r.angle_error is None:   # a pole [x, y]
            assert all(_agrees(p, c) for p, c in zip(printed, computed)), r
        elif isinstance(printed, tuple):                 # [magnitude, direction]
            assert _agrees(printed[0], computed[0]), r
            if r.angle_error is not None and printed[0] > 0:
                assert r.angle_error <= max(_printed_digits_unit(printed[1]), 0.02), r
        elif r.key.startswith("theta"):
            assert r.angle_error <= max(_printed_digits_unit(printed), 0.02), r
        else:
            assert _agrees(printed, computed), r
        checked += 1
    assert checked >= 4


def test_the_printed_digits_rule():
    assert _printed_digits_unit(0.651) == pytest.approx(1e-3)
    assert _printed_digits_unit(97.0) == 1 and _printed_digits_unit(1200.0) == 100
    assert _printed_digits_unit(6.28319) == pytest.approx(1e-5) and _printed_digits_unit(2.5e-05) == pytest.approx(1e-6)


@pytest.mark.parametrize("scale", [1e-90, 1e-30, 1e30, 1e90])
def test_constructions_and_kinematics_hold_at_any_scale(scale):
    """Compass constructions take their squares at the construction's own scale (a power of two,
    exact), even 1e200 times smaller or larger; a mechanism drawn in units 1e90 times smaller or
    larger (the range velpoly accepts: docs/errors.md) has the same shape, omegas and alphas."""
    from velpoly.pose import circle_circle, circle_line
    for k in (scale, scale ** 2 if scale > 1 else scale ** 2.2):   # up to 1e+-198
        for got, want in ((circle_circle([0, 0], 5 * k, [8 * k, 0], 5 * k), circle_circle([0, 0], 5, [8, 0], 5)),
                          (circle_line([0, 0], 5 * k, [0, 3 * k], 0.0), circle_line([0, 0], 5, [0, 3], 0.0))):
            for g, w in zip(got[:2], want[:2]):
                assert np.asarray(g) == pytest.approx(np.asarray(w) * k, rel=1e-15, abs=0)
    d = fourbar(2, 8, 7, 9, theta=40.0, coupler=(3.0, 30.0))
    base = velpoly.load(d)
    d["points"]["O4"] = [x * scale for x in d["points"]["O4"]]
    for p in ("A", "B", "E"):
        spec = d["points"][p]
        if "length" in spec:
            spec["length"] *= scale
        if "circles" in spec:
            spec["circles"] = [[c, r * scale] for c, r in spec["circles"]]
    m = velpoly.load(d)
    for p in base.points:
        assert m.position(p) == pytest.approx(base.position(p) * scale, rel=1e-12, abs=0), p
    for angle in (None, 150.0):
        a, b = velpoly.solve(base, angle=angle), velpoly.solve(m, angle=angle)
        for link in a.omega:
            assert b.omega[link] == pytest.approx(a.omega[link], rel=1e-9, abs=1e-12)
            assert b.alpha[link] == pytest.approx(a.alpha[link], rel=1e-9, abs=1e-12)
        assert b.acceleration["E"] == pytest.approx(a.acceleration["E"] * scale, rel=1e-9, abs=0)
