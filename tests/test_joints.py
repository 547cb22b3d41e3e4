"""Contacts, slots and curved paths: velocities and accelerations against finite differences,
and against the closed forms of simple cases (tolerances 1e-9 relative for closed forms)."""
import dataclasses
import functools
import math

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from mechanisms import CAM_FLAT, CAM_ROLLER, SLOTTED_LEVER, WHEEL_ROLLING
from test_kinematics import fd_check


def test_wheel_rolls_without_slip():
    m = velpoly.load(WHEEL_ROLLING)
    s = velpoly.solve(m)
    c = s.to_dict()["contacts"][0]
    assert c["slip_velocity"] == pytest.approx(0, abs=1e-12)
    # the contact point of the wheel is at rest; the centre moves at -omega r along the ground
    assert s.velocity["P@4"] == pytest.approx([0, 0], abs=1e-9)
    assert s.velocity["C"] == pytest.approx([-20 * s.omega["4"], 0], rel=1e-12, abs=1e-9)
    # the contact point of the wheel accelerates towards the centre: omega^2 r
    assert s.acceleration["P@4"] == pytest.approx([0, 20 * s.omega["4"] ** 2], rel=1e-9, abs=1e-9)
    fd_check(m, s.driver_angle)
    w = velpoly.sweep(m, s.driver_angle + np.arange(0, 361, 2.0))
    assert len(w.angles) == 181 and not w.stopped
    assert np.abs(w.contacts[0]["slip_velocity"]).max() < 1e-9


def test_eccentric_cam_flat_follower_closed_form():
    m = velpoly.load(CAM_FLAT)
    s = velpoly.solve(m)
    e, w, al, th = 10, 10, 4, math.radians(30)
    # follower height y = e sin(theta) + const: v = e w cos, a = -e w^2 sin + e alpha cos
    assert s.velocity["F"] == pytest.approx([0, e * w * math.cos(th)], abs=1e-9)
    assert s.acceleration["F"] == pytest.approx([0, -e * w * w * math.sin(th) + e * al * math.cos(th)], abs=1e-9)
    fd_check(m, 30)
    w_ = velpoly.sweep(m, 30 + np.arange(0, 361, 1.0))
    assert len(w_.angles) == 361


def test_roller_follower_rolls_and_sweeps():
    m = velpoly.load(CAM_ROLLER)
    s = velpoly.solve(m)
    assert s.to_dict()["contacts"][0]["slip_velocity"] == pytest.approx(0, abs=1e-9)
    assert s.velocity["P@2"] == pytest.approx(s.velocity["P@4"], abs=1e-9)
    fd_check(m, 30)
    assert len(velpoly.sweep(m, 30 + np.arange(0, 361, 3.0)).angles) == 121


def test_sliding_contact_with_prescribed_slip_has_that_slip():
    t = CAM_ROLLER.replace('kind = "rolling"', 'kind = "sliding"\nslip = 6.0')
    s = velpoly.solve(velpoly.load(t))
    assert s.to_dict()["contacts"][0]["slip_velocity"] == pytest.approx(6.0, abs=1e-12)
    assert s.has_accelerations


def test_contact_by_normal_has_velocities_only():
    t = CAM_FLAT.replace('centres = ["K", "flat"]', 'normal = 90')
    s = velpoly.solve(velpoly.load(t))
    d = s.to_dict()
    e, w, th = 10, 10, math.radians(30)
    assert s.velocity["F"] == pytest.approx([0, e * w * math.cos(th)], abs=1e-9)
    assert d["points"]["F"]["acceleration"] is None
    assert d["links"]["3"]["alpha"] is None
    assert d["contacts"][0]["slip_acceleration"] is None


def test_pin_in_slot():
    m = velpoly.load(SLOTTED_LEVER.replace("angle = 95.7", "angle = ANGLE"
                                            .replace("ANGLE", str(_dir("A", "C", SLOTTED_LEVER)))))
    s = velpoly.solve(m)
    # the pin's relative velocity lies along the slot: V_A2 - V_A3 parallel to CA
    ca = s.position["A@3"] - s.position["C"]
    rel = s.velocity["A@2"] - s.velocity["A@3"]
    assert abs(ca[0] * rel[1] - ca[1] * rel[0]) <= 1e-9 * np.hypot(*ca) * np.hypot(*rel)
    assert s.to_dict()["slots"][0]["slip_velocity"] == pytest.approx(np.dot(rel, ca) / np.hypot(*ca), rel=1e-12)
    fd_check(m, 100)


def _dir(p, q, text):
    m = velpoly.load(text)
    d = m.position(p) - m.position(q)
    return math.degrees(math.atan2(d[1], d[0]))


def test_curved_slider_turns_about_its_centre():
    t = """
[points]
O2 = [0, 0]
K = [6, 0]
A = { from = "O2", length = 2, angle = 70 }
B = { circles = [["A", 5], ["K", 4]], side = "right" }
[links]
1 = { points = ["O2"], frame = true }
2 = { points = ["O2", "A"] }
3 = { points = ["A", "B"] }
4 = { points = ["B"] }
[[sliders]]
block = "4"
guide = "1"
point = "B"
centre = "K"
[driver]
link = 2
omega = 3
alpha = 1
"""
    m = velpoly.load(t)
    s = velpoly.solve(m)
    kb = s.position["B"] - m.position("K")
    # B moves on the circle about K: V_B perpendicular to KB; the block turns at slip/radius
    assert np.dot(s.velocity["B"], kb) == pytest.approx(0, abs=1e-9)
    slip = s.to_dict()["sliders"][0]["slip_velocity"]
    assert slip == pytest.approx(s.omega["4"] * 4, rel=1e-12)
    fd_check(m, 70)


PLANET = """
title = "planet wheel rolling inside a fixed ring, carried by an arm"
units = "mm"
[points]
O = [0, 0]
C = { from = "O", length = 60, angle = 30 }
P = { from = "O", length = 100, angle = 30 }
Q = { from = "C", length = 40, angle = 120 }
[links]
1 = { points = ["O"], frame = true }
2 = { points = ["O", "C"] }
3 = { points = ["C", "Q"] }
[[contacts]]
links = ["3", "1"]
point = "P"
kind = "rolling"
centres = ["C", "O"]
[driver]
link = 2
omega = 10
alpha = 2
"""


def test_planet_in_a_ring_counts_the_redundant_contact_once_and_turns_twice_round():
    """The arm fixes the centre distance the contact also fixes (FORMAT.md section 5: mobility by rank)."""
    m = velpoly.load(PLANET)
    s = velpoly.solve(m)
    assert s.omega["3"] == pytest.approx(10 * (1 - 100 / 40), rel=1e-12)   # -15 rad/s
    assert s.alpha["3"] == pytest.approx(2 * (1 - 100 / 40), rel=1e-9)
    fd_check(m, 30)
    w = velpoly.sweep(m, 30 + np.arange(0, 721, 2.0))
    assert len(w.angles) == 361 and not w.stopped
    assert np.abs(np.diff(w.position["Q"], axis=0)).max() < 5.0
    assert np.abs(w.omega["3"] + 15).max() < 1e-9


def test_a_locked_truss_is_not_taken_for_a_redundant_joint():
    # three bars pinned in a triangle to the frame: mobility 0 at every pose
    t = """
[points]
A = [0, 0]
B = [4, 0]
C = [2, 3]
[links]
1 = { points = ["A", "B"], frame = true }
2 = { points = ["A", "C"] }
3 = { points = ["B", "C"] }
[driver]
link = 2
omega = 1
"""
    with pytest.raises(velpoly.InputError, match="mobility is 0"):
        velpoly.solve(velpoly.load(t))


def test_a_contact_without_position_equation_allows_only_the_drawn_pose():
    t = CAM_FLAT.replace('centres = ["K", "flat"]', 'normal = 90')
    m = velpoly.load(t)
    velpoly.solve(m)
    with pytest.raises(velpoly.InputError, match="contacts\\[0\\].*no position equation"):
        velpoly.solve(m, angle=60)
    with pytest.raises(velpoly.InputError) as err:
        velpoly.sweep(m, [30, 40])
    assert "centres of curvature" in err.value.hint


# -- joints inferred from the links (FORMAT.md section 5) ------------------------------------------------
def _pins(m):
    return sorted((p.point, tuple(sorted(p.links))) for p in m.pins)


def test_a_point_in_k_links_is_k_minus_1_pins():
    """C is shared by the coupler 3, the rocker 4 and the bar 5 of a Watt-like six-bar: 2 pins there."""
    t = """
[points]
A = [0, 0]
D = [10, 0]
G = [12, -9]
B = { from = "A", length = 3, angle = 50 }
C = { circles = [["B", 9], ["D", 7]], side = "right" }
E = { circles = [["C", 6], ["G", 5]], side = "right" }
[links]
1 = { points = ["A", "D", "G"], frame = true }
2 = { points = ["A", "B"] }
3 = { points = ["B", "C"] }
4 = { points = ["D", "C"] }
5 = { points = ["C", "E"] }
6 = { points = ["G", "E"] }
[driver]
link = 2
omega = 2
"""
    m = velpoly.load(t)
    at_c = [links for p, links in _pins(m) if p == "C"]
    assert len(at_c) == 2 and {x for pair in at_c for x in pair} == {"3", "4", "5"}
    assert len(m.pins) == 7                                  # A, B, D, E, G once and C twice
    s = velpoly.solve(m)                                     # mobility 1: the pins are 14 equations
    assert s.velocity["C"] == pytest.approx(s.body_velocity("5", s.position["C"]), abs=1e-12)
    fd_check(m, 50)


def test_a_slider_guide_listing_the_point_is_not_pinned_to_the_block():
    from mechanisms import inverted_slider_crank
    m = velpoly.load(inverted_slider_crank())                # A is listed by the crank 2, block 3, guide 4
    assert _pins(m) == [("A", ("2", "3")), ("O2", ("1", "2")), ("O4", ("1", "4"))]
    s = velpoly.solve(m)
    assert {"A@3", "A@4"} <= set(s.position) and "A" not in s.position   # two carriers, moving apart


def test_a_contact_point_is_never_a_pin_listed_or_not():
    listed = WHEEL_ROLLING.replace('1 = { points = ["O2"]', '1 = { points = ["O2", "P"]').replace(
        '4 = { points = ["C"] }', '4 = { points = ["C", "P"] }')
    a, b = velpoly.load(WHEEL_ROLLING), velpoly.load(listed)
    assert "P" not in {p.point for p in a.pins} | {p.point for p in b.pins}
    sa, sb = velpoly.solve(a), velpoly.solve(b)
    assert sb.omega["4"] == pytest.approx(sa.omega["4"], rel=1e-12)
    assert sb.velocity["P@4"] == pytest.approx([0, 0], abs=1e-9)   # the wheel's point at the ground is at rest


def test_slider_driver_closed_form():
    """A centred slider-crank driven by its block: omega and alpha of the crank from x(theta)."""
    from mechanisms import slider_crank
    r, l, th, v, acc = 3.0, 10.0, math.radians(50), 2.0, -1.5
    d = slider_crank(r, l, 0.0, 50.0)
    d["driver"] = {"slider": "B", "speed": v, "accel": acc}
    s = velpoly.solve(velpoly.load(d))
    sn, cs = math.sin(th), math.cos(th)
    root = math.sqrt(l * l - r * r * sn * sn)
    x1 = -r * sn - r * r * sn * cs / root                    # dx/dtheta
    x2 = -r * cs - r * r * (cs * cs - sn * sn) / root - r ** 4 * sn * sn * cs * cs / root ** 3
    w = v / x1
    assert s.omega["2"] == pytest.approx(w, rel=1e-9)
    assert s.alpha["2"] == pytest.approx((acc - x2 * w * w) / x1, rel=1e-9)
    assert s.velocity["B"] == pytest.approx([v, 0], abs=1e-12)
    assert s.acceleration["B"] == pytest.approx([acc, 0], abs=1e-9)
    out = s.to_dict()
    assert out["driver"] == {"slider": "B", "speed": v, "accel": acc}
    assert out["sliders"][0]["slip_velocity"] == pytest.approx(v) and out["sliders"][0]["slip_acceleration"] == \
        pytest.approx(acc)


def test_free_sliding_contact_reports_its_slip():
    """A flat-faced follower on an eccentric cam slides: the slip is v_cam(P) - v_follower(P) along t."""
    s = velpoly.solve(velpoly.load(CAM_FLAT))
    c = s.to_dict()["contacts"][0]
    a, b = c["links"]
    u = s.motion.contacts[0]["normal"][0]
    u = np.array([math.cos(math.radians(u)), math.sin(math.radians(u))]) if np.ndim(u) == 0 else np.asarray(u)
    t = np.array([-u[1], u[0]])
    rel = s.velocity[f"P@{a}"] - s.velocity[f"P@{b}"]
    assert abs(np.dot(rel, u)) < 1e-9                         # no separation along the normal
    assert c["slip_velocity"] == pytest.approx(np.dot(rel, t), rel=1e-12)
    assert abs(c["slip_velocity"]) > 1.0                      # it does slide
    # the slip acceleration is the rate of the slip velocity (a central difference over the sweep)
    m, h = s.mechanism, 1e-3
    w = velpoly.sweep(m, s.driver_angle + h * np.array([-1.0, 0.0, 1.0]))
    sv = w.contacts[0]["slip_velocity"]
    rate = (sv[2] - sv[0]) / (2 * math.radians(h)) * m.driver.omega + sv[1] / m.driver.omega * m.driver.alpha
    assert c["slip_acceleration"] == pytest.approx(rate, rel=1e-6)
    # a prescribed slip (constant in time) with the driver accelerating (CAM_ROLLER's alpha = -2): the
    # pose at another angle depends on the driver's history, so only the drawn pose is analysed
    slipping = velpoly.load(CAM_ROLLER.replace('kind = "rolling"', 'kind = "sliding"\nslip = 6.0'))
    with pytest.raises(velpoly.InputError, match=r"contacts\[0\]: only the drawn pose .*constant in time and "
                       r"the driver accelerates \(alpha = -2\).*history") as err:
        velpoly.sweep(slipping, [30.0, 31.0])
    assert "alpha = 0" in err.value.hint


# -- a prescribed slip over a cycle (formerly issue 2 of gallery/SOLVER_ISSUES.md) ----------------------------
# The integrated slip sigma(q) grows at the slip s, constant in time; with the driver at a constant rate
# omega_d the time is d(q) / omega_d, so sigma(q) - s d(q) / omega_d = 0 holds in positions.
def slipping_cam(slip: float, omega: float = 10.0) -> str:
    """CAM_ROLLER (a roller of radius 5 on a circular cam of radius 25) sliding with ``slip``, alpha = 0."""
    return CAM_ROLLER.replace('kind = "rolling"', f'kind = "sliding"\nslip = {slip}') \
                     .replace("alpha = -2\n", "").replace("omega = 10", f"omega = {omega}")


SLIDING_WHEEL = """
title = "wheel sliding on the ground, its centre driven along it"
units = "mm"
[points]
O = [0, 0]
C = [0, 20]
P = { from = "C", length = 20, angle = -90 }
[links]
1 = { points = ["O"], frame = true }
3 = { points = ["C"] }
4 = { points = ["C"] }
[[sliders]]
block = "3"
guide = "1"
point = "C"
angle = 0
[[contacts]]
links = ["4", "1"]
point = "P"
kind = "sliding"
slip = 3
centres = ["C", "flat"]
[driver]
slider = "C"
speed = 5
"""


def assert_rates_are_those_of_the_poses(w, rate, h):
    """q' = dq/dd * rate (central differences over the triples of driver positions h apart) to 1e-6."""
    for i in range(1, len(w.angles) - 1, 3):
        fd = (w.q[i + 1] - w.q[i - 1]) / (2 * h) * rate
        assert np.abs(fd - w.qd[i]).max() <= 1e-6 * np.abs(w.qd[i]).max(), w.angles[i]


TRIPLES_H = 1e-3     # deg: the triples of driver angles h apart at which rates are differenced


def three_turns(omega: float) -> np.ndarray:
    """Three turns of the driver from 30 deg in the sense of ``omega`` every 10 deg (s t / D = 3.6 rad at slip 60;
    five turns until the suite had to fit 2 minutes), with triples ``TRIPLES_H`` apart about three angles on the
    way (one sweep serves the rates' differences too; it walked the turns once more to reach them)."""
    grid = np.arange(0, 1081, 10.0)
    base = np.array([17.0, 400.0, 1000.0])
    near = (base[:, None] + TRIPLES_H * np.array([-1, 0, 1])).ravel()
    return np.sign(omega) * np.unique(np.concatenate([grid, near])) + 30.0


def triples(w) -> list[int]:
    """The indices in a sweep over ``three_turns`` of its triples, each in ascending angle (its middle angle's
    neighbours TRIPLES_H apart)."""
    d = np.abs(np.diff(w.angles))
    return [int(j) for i in np.flatnonzero(d < 2 * TRIPLES_H)[::2] for j in i + np.argsort(w.angles[i:i + 3])]


@functools.cache
def rolling_sweep(omega: float):
    """CAM_ROLLER rolling (alpha = 0) over ``three_turns(omega)``: shared by the cases at one rate."""
    rolling = velpoly.load(CAM_ROLLER.replace("alpha = -2\n", "").replace("omega = 10", f"omega = {omega}"))
    return velpoly.sweep(rolling, three_turns(omega))


# each sign of the slip and of the driver's rate, a small and a large slip (60 and 10 too until the suite had to
# fit 2 minutes: three turns by continuation are a second)
@pytest.mark.xdist_group("joints-rolling-sweeps")   # one worker: rolling_sweep computed once a rate
@pytest.mark.parametrize("slip, omega", [(6.0, 10.0), (-60.0, 10.0), (60.0, -10.0)])
def test_prescribed_slip_sweeps_with_the_driver_at_a_constant_rate(slip, omega):
    m = velpoly.load(slipping_cam(slip, omega))
    turns = three_turns(omega)
    w, wr = velpoly.sweep(m, turns), rolling_sweep(omega)
    assert len(w.angles) == len(turns) and not w.stopped
    assert np.abs(w.contacts[0]["slip_velocity"] - slip).max() <= 1e-9 * abs(slip)
    # the cam and the follower move as when rolling; the roller turns s / r faster, and by s t / r more
    for key in ("K", "R"):
        assert w.position[key] == pytest.approx(wr.position[key], abs=1e-9 * m.size)
        assert w.velocity[key] == pytest.approx(wr.velocity[key], abs=1e-9 * abs(omega) * m.size)
    assert w.omega["4"] - wr.omega["4"] == pytest.approx(np.full(len(turns), slip / 5), rel=1e-9)
    t = np.radians(turns - 30.0) / omega
    k = 3 * list(m.moving_links).index(m.link("4")) + 2
    assert w.q[:, k] - wr.q[:, k] == pytest.approx(slip * t / 5, abs=1e-9)
    # velocities against differences of the poses, anywhere on the way (the sweep's triples); accelerations too
    at = triples(w)
    assert len(at) == 9 and w.angles[at[1]] == 30.0 + 17.0 * np.sign(omega)
    fine = dataclasses.replace(w, angles=w.angles[at], q=w.q[at], qd=w.qd[at])
    assert_rates_are_those_of_the_poses(fine, omega, math.radians(TRIPLES_H))
    fd_check(m, 200.0)
    # at the reference angle the sweep is the drawn pose's solution, elsewhere that of solve(angle)
    ref, there = velpoly.solve(m), velpoly.solve(m, angle=200.0)
    i = int(np.flatnonzero(turns == 200.0 if omega > 0 else turns == 200.0 - 360.0)[0])
    for s, j in ((ref, 0), (there, i)):
        assert s.omega["4"] == pytest.approx(w.omega["4"][j], rel=1e-12)
        assert s.to_dict()["contacts"][0]["slip_velocity"] == pytest.approx(slip, rel=1e-12)
        for key in s.position:
            assert s.position[key] == pytest.approx(w.position[key][j], abs=1e-9 * m.size), key
            assert s.velocity[key] == pytest.approx(w.velocity[key][j], rel=1e-9, abs=1e-9), key
            assert s.acceleration[key] == pytest.approx(w.acceleration[key][j], rel=1e-9, abs=1e-9), key


def test_prescribed_slip_sweeps_with_a_slider_driver_at_a_constant_speed():
    # the wheel's centre at speed v, slip s = v + r omega_4 on the ground: omega_4 = (s - v) / r and the
    # wheel's angle after a displacement x is (s - v) / r * x / v
    m = velpoly.load(SLIDING_WHEEL)
    x = np.linspace(-50.0, 50.0, 101)
    w = velpoly.sweep(m, x)
    assert len(w.angles) == 101 and not w.stopped
    assert w.omega["4"] == pytest.approx(np.full(101, (3 - 5) / 20), rel=1e-12)
    assert np.radians(w.angle["4"]) == pytest.approx((3 - 5) / 20 * x / 5, abs=1e-12)
    assert np.abs(w.contacts[0]["slip_velocity"] - 3).max() < 1e-12
    assert_rates_are_those_of_the_poses(velpoly.sweep(m, np.array([0.0, 7.0, 7.001, 7.002])[1:]), 5.0, 1e-3)
    s = velpoly.solve(m)
    assert s.velocity["P@4"] == pytest.approx(w.velocity["P@4"][50], abs=1e-12)


@pytest.mark.parametrize("change, why", [("alpha = 0.5", r"the driver accelerates \(alpha = 0\.5\)"),
                                         ("omega = 0", "the driver is at rest")])
def test_prescribed_slip_needs_a_constant_non_zero_driver_rate_away_from_the_drawn_pose(change, why, capsys, tmp_path):
    text = slipping_cam(6.0).replace("omega = 10.0", "omega = 10.0\nalpha = 0.5") if change.startswith("alpha") \
        else slipping_cam(6.0, 0.0)
    m = velpoly.load(text)
    velpoly.solve(m)                                           # the drawn pose is analysed as ever
    with pytest.raises(velpoly.InputError, match=why + ".*depends on the driver's history"):
        velpoly.solve(m, angle=60.0)
    f = tmp_path / "slipping.toml"
    f.write_text(text)
    assert main(["solve", str(f), "--angle", "60"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"error: {f}: contacts[0]") and "constant in time" in err[0], err


def test_zero_prescribed_slip_sweeps_whatever_the_driver_rate():
    # slip = 0 integrates to sigma(q) = 0: rolling, with or without alpha
    m = velpoly.load(CAM_ROLLER.replace('kind = "rolling"', 'kind = "sliding"\nslip = 0'))
    rolling = velpoly.load(CAM_ROLLER)
    w, wr = velpoly.sweep(m, 30 + np.arange(0, 361, 3.0)), velpoly.sweep(rolling, 30 + np.arange(0, 361, 3.0))
    assert len(w.angles) == 121 and w.omega["4"] == pytest.approx(wr.omega["4"], rel=1e-12, abs=1e-12)
