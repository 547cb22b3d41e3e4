"""Branch continuity: sweeps and --angle stay on the assembly the file draws.

Each mechanism is drawn on either assembly branch (``near`` on either side of
the line of centres). A sweep of 3600 poses must be continuous (no point
jumps more than a few times the distance its speed carries it in one step),
keep the branch (the sign of the triangle at every two-circle construction
never changes) and close after a full turn; a non-Grashof four-bar stops at
its toggle, within a step or two of the analytic angle, and ``solve --angle``
beyond it exits 3 naming the reachable range.
"""
from __future__ import annotations

import math
import re
import time

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from velpoly.pose import circle_circle

STEP = 0.1           # degrees: 3600 poses a turn
N = 3601


# -- mechanisms --------------------------------------------------------------------------------
def near_text(p, r1, q, r2, branch: int) -> str:
    """``near = [x, y]``: the sketch point of one assembly (0: left of P->Q, 1: right)."""
    left, right, gap = circle_circle(np.array(p, float), r1, np.array(q, float), r2)
    assert gap == 0
    x, y = (left, right)[branch]
    return f"near = [{x:.6f}, {y:.6f}]"


def fourbar(a, b, c, d, theta, branch, omega=10.0) -> str:
    """Crank AB = a at theta, coupler BC = b, rocker DC = c, frame AD = d along +x."""
    bxy = (a * math.cos(math.radians(theta)), a * math.sin(math.radians(theta)))
    return f"""
title = "four-bar {a} {b} {c} {d}"
units = "mm"
[points]
A = [0, 0]
D = [{d}, 0]
B = {{ from = "A", length = {a}, angle = {theta} }}
C = {{ circles = [["B", {b}], ["D", {c}]], {near_text(bxy, b, (d, 0), c, branch)} }}
[links]
1 = {{ points = ["A", "D"], frame = true }}
2 = {{ points = ["A", "B"] }}
3 = {{ points = ["B", "C"] }}
4 = {{ points = ["D", "C"] }}
[driver]
link = "2"
omega = {omega}
"""


def watt_sixbar(branch_c: int, branch_f: int, theta=50.0, a=40.0, b=120.0, c=80.0, d=100.0, e=30.0,
                g=100.0, r5=80.0, r6=60.0) -> dict:
    """A Watt six-bar: the crank-rocker A-B-C-D, its rocker extended past D to E, and a second
    loop E-F-G (coupler 5, rocker 6 about G). Either loop drawn on either branch."""
    d_ = np.array([d, 0.0])
    bxy = a * np.array([math.cos(math.radians(theta)), math.sin(math.radians(theta))])
    left, right, _ = circle_circle(bxy, b, d_, c)
    cxy = (left, right)[branch_c]
    exy = d_ - e * (cxy - d_) / np.linalg.norm(cxy - d_)
    gxy = d_ + np.array([0.0, -g])
    fl, fr, gap = circle_circle(exy, r5, gxy, r6)
    assert gap == 0
    fxy = (fl, fr)[branch_f]
    return {
        "title": "Watt six-bar", "units": "mm",
        "points": {
            "A": [0.0, 0.0], "D": [d, 0.0], "G": [float(gxy[0]), float(gxy[1])],
            "B": {"from": "A", "length": a, "angle": theta},
            "C": {"circles": [["B", b], ["D", c]], "near": [float(cxy[0]), float(cxy[1])]},
            "E": {"from": "D", "length": e, "along": ["C", "D"]},
            "F": {"circles": [["E", r5], ["G", r6]], "near": [float(fxy[0]), float(fxy[1])]},
        },
        "links": {
            "1": {"points": ["A", "D", "G"], "frame": True},
            "2": {"points": ["A", "B"]},
            "3": {"points": ["B", "C"]},
            "4": {"points": ["D", "C", "E"]},
            "5": {"points": ["E", "F"]},
            "6": {"points": ["G", "F"]},
        },
        "driver": {"link": "2", "omega": "60 rpm cw"},
    }


def chain(loops: int = 9, side: str = "right") -> dict:
    """A chain of four-bar loops: the crank drives rocker 3 through coupler 2, each rocker
    drives the next through a coupler; 2 + 2 x loops links (20 for nine loops)."""
    pts = {"P0": [0.0, 0.0], "E0": {"from": "P0", "length": 30.0, "angle": 70.0}}
    links = {"0": {"points": ["P0"], "frame": True}, "1": {"points": ["P0", "E0"]}}
    k = 2
    for i in range(1, loops + 1):
        r5, r6 = 80.0 + 3 * i, 60.0 - 2 * i
        pts[f"P{i}"] = [100.0 * i, 0.0]
        pts[f"F{i}"] = {"circles": [[f"E{i - 1}", r5], [f"P{i}", r6]], "side": side}
        pts[f"E{i}"] = {"from": f"P{i}", "length": 30.0, "along": [f"F{i}", f"P{i}"]}
        links["0"]["points"].append(f"P{i}")
        links[str(k)] = {"points": [f"E{i - 1}", f"F{i}"]}
        links[str(k + 1)] = {"points": [f"P{i}", f"F{i}", f"E{i}"]}
        k += 2
    return {"title": f"chain of {loops} four-bar loops", "units": "mm", "points": pts, "links": links,
            "driver": {"link": "1", "omega": 5}}


# -- checks -----------------------------------------------------------------------------------------
def orientation(w, p, q, r) -> np.ndarray:
    """Sign of the triangle p, q, r at every pose: which side of p->q the point r is on."""
    u = w.position[q] - w.position[p]
    v = w.position[r] - w.position[p]
    return np.sign(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])


def assert_continuous(w, step_deg, factor=4.0):
    """No point moves farther between poses than ``factor`` times its speed times the step's time."""
    m = w.mechanism
    dt = math.radians(step_deg) / abs(m.driver.omega)
    for key, p in w.position.items():
        jump = np.hypot(*np.diff(p, axis=0).T)
        speed = np.hypot(*w.velocity[key].T)
        bound = factor * np.maximum(speed[:-1], speed[1:]) * dt + 1e-9 * m.size
        worst = int(np.argmax(jump - bound))
        assert jump[worst] <= bound[worst], (key, w.angles[worst], jump[worst], bound[worst])


def assert_closes(w):
    for key, p in w.position.items():
        assert np.abs(p[-1] - p[0]).max() <= 1e-8 * w.mechanism.size, key


def sweep_turn(m, direction=1.0):
    ref = velpoly.solve(m).driver_angle
    return velpoly.sweep(m, ref + direction * STEP * np.arange(N))


def toggle_range(a, b, c, d):
    """The crank angles (deg) at which a four-bar can be assembled, about +x (A at 0, D at +d)."""
    lo_cos = (a * a + d * d - (b + c) ** 2) / (2 * a * d)
    hi_cos = (a * a + d * d - (b - c) ** 2) / (2 * a * d)
    top = math.degrees(math.acos(max(lo_cos, -1.0)))
    bottom = math.degrees(math.acos(min(hi_cos, 1.0)))
    return bottom, top     # reachable for bottom <= |theta| <= top


# -- four-bars --------------------------------------------------------------------------------------
@pytest.mark.parametrize("dims", [(40, 120, 80, 100), (100, 60, 110, 30)], ids=["crank-rocker", "drag-link"])
@pytest.mark.parametrize("branch", [0, 1])
def test_grashof_fourbar_turns_on_its_branch(dims, branch):
    m = velpoly.load(fourbar(*dims, theta=60.0, branch=branch))
    w = sweep_turn(m)
    assert len(w.angles) == N and not w.stopped
    assert_continuous(w, STEP)
    assert_closes(w)
    side = orientation(w, "B", "D", "C")
    assert np.all(side == side[0]) and side[0] == (1 if branch == 0 else -1)


@pytest.mark.parametrize("branch", [0, 1])
@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_non_grashof_fourbar_stops_at_its_toggle(branch, direction):
    a, b, c, d = 80, 60, 70, 100           # triple rocker: the crank swings between two toggles
    m = velpoly.load(fourbar(a, b, c, d, theta=60.0, branch=branch))
    w = sweep_turn(m, direction)
    _, top = toggle_range(a, b, c, d)      # |theta| <= 91.79 deg
    assert w.stopped.startswith("stopped at a toggle")
    last = w.angles[-1]
    assert top - 1.5 <= direction * last <= top, last
    assert_continuous(w, STEP)
    side = orientation(w, "B", "D", "C")
    assert np.all(side == side[0]) and side[0] == (1 if branch == 0 else -1)


@pytest.mark.parametrize("branch", [0, 1])
def test_angle_beyond_the_toggle_exits_3_with_the_reachable_range(capsys, tmp_path, branch):
    f = tmp_path / "triple_rocker.toml"
    f.write_text(fourbar(80, 60, 70, 100, theta=60.0, branch=branch))
    assert main(["solve", str(f), "--angle", "150"]) == 3
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith(f"error: {f}: --angle: cannot assemble at driver angle 150 deg")
    lo, hi = (float(x) for x in re.search(r"reachable: (\S+) to (\S+) deg", err[0]).groups())
    _, top = toggle_range(80, 60, 70, 100)
    assert -top - 0.02 <= lo <= -top and top <= hi <= top + 0.02, err[0]   # outward (test_audit2_range)
    assert re.search(r"\(links [\d, ]+\)$", err[0])
    # inside the range it solves, on the drawn branch
    assert main(["solve", str(f), "--angle", "-80", "--json"]) == 0
    capsys.readouterr()


def test_the_reachable_range_is_kept_for_an_equal_mechanism_only(monkeypatch):
    """driver.reachable_range keeps its last answers: the same file loaded again gets the range
    without a continuation; a mechanism that differs in one length gets its own."""
    from velpoly import driver
    from velpoly.kinematics import prepare
    text = fourbar(80, 60, 70, 100, theta=60.0, branch=0)
    first = driver.reachable_range(prepare(velpoly.load(text)))
    computed = []
    real = driver._reachable_range
    monkeypatch.setattr(driver, "_reachable_range", lambda *a: computed.append(1) or real(*a))
    assert driver.reachable_range(prepare(velpoly.load(text))) == first and not computed
    other = driver.reachable_range(prepare(velpoly.load(fourbar(80, 60, 72, 100, theta=60.0, branch=0))))
    assert computed == [1] and other != first
    _, top = toggle_range(80, 60, 72, 100)
    lo, hi = (60.0 + x for x in other)   # displacements from the drawn 60 deg
    assert top - 1.5 <= hi <= top and -top <= lo <= -top + 1.5, (lo, hi, top)
    assert driver.reachable_range(prepare(velpoly.load(text)), step=2.0) == first and computed == [1, 1]


@pytest.mark.parametrize("branch", [0, 1])
def test_solve_at_an_angle_stays_on_the_drawn_branch(branch):
    m = velpoly.load(fourbar(40, 120, 80, 100, theta=60.0, branch=branch))
    ref = velpoly.solve(m)
    w = sweep_turn(m)
    for angle in (-170.0, -100.0, 0.0, 95.0, 179.0, 235.0):
        s = velpoly.solve(m, angle=angle)
        assert s.driver_angle == pytest.approx((angle + 180) % 360 - 180)
        b, c, d = (s.position[p] for p in "BCD")
        u, v = d - b, c - b
        assert np.sign(u[0] * v[1] - u[1] * v[0]) == (1 if branch == 0 else -1)
        i = int(round(((angle - ref.driver_angle) % 360) / STEP))
        assert s.position["C"] == pytest.approx(w.position["C"][i], abs=1e-9 * m.size)
        assert s.velocity["C"] == pytest.approx(w.velocity["C"][i], rel=1e-9, abs=1e-9)


def test_driver_angle_in_the_file_stays_on_the_branch():
    text = fourbar(40, 120, 80, 100, theta=60.0, branch=1).replace('omega = 10.0', 'omega = 10.0\nangle = -120')
    s = velpoly.solve(velpoly.load(text))
    b, c, d = (s.position[p] for p in "BCD")
    u, v = d - b, c - b
    assert s.driver_angle == pytest.approx(-120) and u[0] * v[1] - u[1] * v[0] < 0


def test_driver_angle_in_the_file_beyond_the_toggle_exits_3_at_its_line(capsys, tmp_path):
    f = tmp_path / "triple_rocker.toml"
    f.write_text(fourbar(80, 60, 70, 100, theta=60.0, branch=0).replace("omega = 10.0", "omega = 10.0\nangle = 150"))
    assert main(["solve", str(f)]) == 3
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith(f"error: {f}: driver.angle (line 17): cannot assemble at driver "
                                               "angle 150 deg: a toggle lies on the way"), err
    assert re.search(r"reachable: -\d+(\.\d+)? to \d+(\.\d+)? deg \(links [\d, ]+\)$", err[0]), err[0]


# -- six-bars ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("branch_c, branch_f", [(0, 0), (0, 1), (1, 0), (1, 1)])
def test_watt_sixbar_turns_on_both_loops_branches(branch_c, branch_f):
    m = velpoly.load(watt_sixbar(branch_c, branch_f))
    w = sweep_turn(m)
    assert len(w.angles) == N and not w.stopped
    assert_continuous(w, STEP)
    assert_closes(w)
    for (p, q, r), br in ((("B", "D", "C"), branch_c), (("E", "G", "F"), branch_f)):
        side = orientation(w, p, q, r)
        assert np.all(side == (1 if br == 0 else -1)), (p, q, r)


def stephenson_sixbar(side_b: str, side_d: str, mirror: bool) -> dict:
    """A Stephenson III six-bar: the crank-rocker O2-A-B-O4 whose coupler carries C, and the dyad
    C-D-O6 driven from that coupler point. ``mirror`` reflects it in the frame line (the other
    branch of the first loop, with a second loop that still closes)."""
    k = -1.0 if mirror else 1.0
    return {
        "title": "Stephenson III six-bar", "units": "mm",
        "points": {"O2": [0.0, 0.0], "O4": [120.0, 0.0], "O6": [40.0, k * 160.0],
                   "A": {"from": "O2", "length": 40.0, "angle": k * 45.0},
                   "B": {"circles": [["A", 120.0], ["O4", 80.0]], "side": side_b},
                   "C": {"from": "A", "length": 70.0, "along": ["A", "B"], "turn": k * 50.0},
                   "D": {"circles": [["C", 90.0], ["O6", 60.0]], "side": side_d}},
        "links": {"1": {"points": ["O2", "O4", "O6"], "frame": True}, "2": {"points": ["O2", "A"]},
                  "3": {"points": ["A", "B", "C"]}, "4": {"points": ["O4", "B"]}, "5": {"points": ["C", "D"]},
                  "6": {"points": ["O6", "D"]}},
        "driver": {"link": "2", "omega": -10.0},
    }


@pytest.mark.parametrize("side_b, side_d, mirror", [("left", "left", False), ("left", "right", False),
                                                    ("right", "right", True), ("right", "left", True)])
def test_stephenson_sixbar_turns_on_both_loops_branches(side_b, side_d, mirror):
    m = velpoly.load(stephenson_sixbar(side_b, side_d, mirror))
    w = sweep_turn(m)
    assert len(w.angles) == N and not w.stopped
    assert_continuous(w, STEP)
    assert_closes(w)
    for (p, q, r), side in ((("A", "O4", "B"), side_b), (("C", "O6", "D"), side_d)):
        assert np.all(orientation(w, p, q, r) == (1 if side == "left" else -1)), (p, q, r)


@pytest.mark.parametrize("branch_c, branch_f", [(0, 1), (1, 0)])
def test_watt_sixbar_at_an_angle_stays_on_both_drawn_branches(branch_c, branch_f):
    m = velpoly.load(watt_sixbar(branch_c, branch_f))
    ref = velpoly.solve(m).driver_angle
    w = sweep_turn(m)
    for angle in (-150.0, -60.0, 10.0, 140.0, 230.0):
        s = velpoly.solve(m, angle=angle)
        i = int(round(((angle - ref) % 360) / STEP))
        for key in s.position:
            assert s.position[key] == pytest.approx(w.position[key][i], abs=1e-9 * m.size), (angle, key)
        for (p, q, r), br in ((("B", "D", "C"), branch_c), (("E", "G", "F"), branch_f)):
            u, v = s.position[q] - s.position[p], s.position[r] - s.position[p]
            assert np.sign(u[0] * v[1] - u[1] * v[0]) == (1 if br == 0 else -1), (angle, p, q, r)


@pytest.mark.parametrize("near_f", ["[-0.37, 0.19]", "[-0.37, 0.62]"])
def test_textbook_sixbar_with_a_slider_on_either_branch(near_f):
    from mechanisms import SIXBAR_1_4_4
    m = velpoly.load(SIXBAR_1_4_4.replace("near = [-0.37, 0.19]", f"near = {near_f}"))
    w = sweep_turn(m)
    assert len(w.angles) == N and not w.stopped
    assert_continuous(w, STEP)
    assert_closes(w)
    above = w.position["F"][:, 1] > w.position["E"][:, 1]   # F stays on its side of E along the slider's path
    assert np.all(above == above[0])


# -- scale ---------------------------------------------------------------------------------------------------
def test_twenty_link_chain_solves_and_turns_quickly():
    d = chain(9)
    t0 = time.perf_counter()
    m = velpoly.load(d)
    s = velpoly.solve(m)
    assert time.perf_counter() - t0 < 5.0
    assert len(m.links) == 20 and len(s.omega) == 20
    t0 = time.perf_counter()
    w = velpoly.sweep(m, s.driver_angle + np.arange(0, 360.5, 1.0))
    assert time.perf_counter() - t0 < 5.0
    assert len(w.angles) == 361 and not w.stopped
    assert_continuous(w, 1.0)
    assert_closes(w)
    for i in range(1, 10):
        side = orientation(w, f"E{i - 1}", f"P{i}", f"F{i}")
        assert np.all(side == -1), i   # side = "right" of E -> P, every loop, the whole turn


def test_the_continuity_check_sees_a_branch_jump():
    # the checks above can fail: a sweep with one pose on the other assembly is caught
    import dataclasses
    m = velpoly.load(fourbar(40, 120, 80, 100, theta=60.0, branch=0))
    w = velpoly.sweep(m, 60.0 + STEP * np.arange(200))
    other = velpoly.load(fourbar(40, 120, 80, 100, theta=60.0 + 100 * STEP, branch=1))
    pos = dict(w.position)
    pos["C"] = pos["C"].copy()
    pos["C"][100] = other.position("C")
    bad = dataclasses.replace(w, position=pos)
    with pytest.raises(AssertionError):
        assert_continuous(bad, STEP)
    assert set(orientation(bad, "B", "D", "C")) == {1.0, -1.0}


# -- a singular drawn pose (formerly kernel issue 1 of docs/requests/robustness.md) ---------------------------------------------------------
@pytest.mark.parametrize("how", ["solve", "sweep"])
def test_reassembly_from_a_singular_reference_pose_is_a_pose_error(how):
    from mechanisms import inverted_slider_crank
    # the block's pin A 1.7e-10 from the rocker's pivot O4: the rocker's direction is undefined
    m = velpoly.load(inverted_slider_crank(1.0, 1.0, 1e-8, 1.0, 0.0))
    with pytest.raises(velpoly.SingularPoseError):
        velpoly.solve(m)                       # at the reference pose it is already reported
    try:
        if how == "solve":
            velpoly.solve(m, angle=30.0)
        else:
            w = velpoly.sweep(m, [1e-8, 10.0])
            assert w.stopped
    except velpoly.PoseError:
        pass


# -- a drag link through a rolling contact (formerly issue 3 of gallery/SOLVER_ISSUES.md) ----------------------
from paths import EXAMPLES as GALLERY  # noqa: E402


def rolling_drag_link(radius: float = 4.0) -> str:
    """Fig. 3.15 (a) with a circular cam of ``radius`` about Q on the normal CP: the four-bar A-C-Q-B
    (AB = 1.999, CQ = 1 + radius), a drag link in which every link turns round; the wheel turns fast."""
    text = (GALLERY / "fig3_15a_rolling.toml").read_text()
    a = 'A = { to = "C", length = 5.646, angle = 85.694 }'
    assert a in text and 'centres = ["C", "flat"]' in text
    return text.replace(a, f'{a}\nQ = {{ from = "P", length = {radius}, angle = 315 }}') \
               .replace('centres = ["C", "flat"]', 'centres = ["C", "Q"]')


def test_rolling_drag_link_solves_at_every_integer_angle():
    # the batched correction of a pose 5 deg past its knot missed (167 deg exited 3, "reachable: -197 to
    # 118"): such a pose is retried step by step from the nearest converged pose before it is a toggle.
    # Every integer angle sweeps; solve (a walk from the drawn pose each time, its knots kept from the one
    # before by pose._kept_knots, a batched correction and the velocities anew) is checked at every
    # 17th degree from a seeded offset and at the angles that failed, which keeps the suite fast
    m = velpoly.load(rolling_drag_link())
    w = velpoly.sweep(m, np.arange(0.0, 360.0, 1.0))
    assert len(w.angles) == 360 and not w.stopped
    start = int(np.random.default_rng(20261125).integers(17))
    for angle in sorted(set(range(-179 + start, 181, 17)) | {118, 119, 166, 167, 168, 180}):
        s = velpoly.solve(m, angle=float(angle))
        assert s.driver_angle == pytest.approx(angle)
        j = angle % 360                                   # the same pose on the sweep
        for key in ("A", "C", "P@3"):
            assert s.position[key] == pytest.approx(w.position[key][j], abs=1e-9 * m.size), (angle, key)
            assert s.velocity[key] == pytest.approx(w.velocity[key][j], rel=1e-8, abs=1e-8), (angle, key)


def test_rolling_drag_link_solves_at_167_from_the_command_line(capsys, tmp_path):
    f = tmp_path / "drag_link.toml"
    f.write_text(rolling_drag_link())
    assert main(["solve", str(f), "--angle", "167"]) == 0
    capsys.readouterr()


# every step in both directions and on both radii, every radius in both directions: each pair of the three
# (all 16 combinations until the suite had to fit 2 minutes; a sweep by continuation is 0.35 s); step 1 forwards
# on radius 4 is also test_rolling_drag_link_solves_at_every_integer_angle's sweep
@pytest.mark.parametrize("radius, step, direction", [
    (4.0, 0.25, 1.0), (5.0, 0.25, -1.0), (4.0, 1.0, -1.0), (5.0, 1.0, 1.0),
    (4.0, 2.0, 1.0), (5.0, 2.0, -1.0), (4.0, 3.0, -1.0), (5.0, 3.0, 1.0)])
def test_rolling_drag_link_sweeps_a_whole_turn_at_any_step(radius, step, direction):
    # the stops used to depend on the step (after 118.5 deg with 0.25, 166 with 2): no toggle at all
    m = velpoly.load(rolling_drag_link(radius))
    w = velpoly.sweep(m, direction * np.arange(0.0, 360.0 + step / 2, step))
    assert len(w.angles) == len(np.arange(0.0, 360.0 + step / 2, step)) and not w.stopped, w.stopped
    assert_continuous(w, step)
    assert_closes(w)
    assert np.abs(w.contacts[0]["slip_velocity"]).max() < 1e-9            # it rolls
    ca = w.position["C"] - w.position["Q"]
    assert np.hypot(*ca.T) == pytest.approx(1.0 + radius, rel=1e-12)      # the profiles touch
