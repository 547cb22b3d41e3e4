"""Finite slots (issue 13 item 6, FORMAT.md ``[[slots]] ends``).

Generated crank-and-slotted-link drives: a crank O1A = a turns a link about a pivot C (distance e,
any direction) through a pin A in a straight slot of that link along C -> A; the slot's ends are
cut at distances r_lo and r_hi from C. Geneva drives (n slots: e = a / sin(pi / n), the slot opening
at the rim sqrt(e^2 - a^2), the pin leaving at +-(90 - 180 / n) deg from the line of centres) and
slotted levers whose lever oscillates (e > a) or turns round (e < a, a Whitworth link), with one end,
both or neither within the pin's reach. The pin's distance from C is |A(theta) - C| in closed form,
so where it reaches an end (the first driver angle, in the sweep's sense, where it reaches r_lo or
r_hi) is found here by bisection on the closed form to 1e-12 rad; the sweep must stop there and say
so, the angle it reports within 1e-6 deg, and ``solve`` must solve inside and exit 3 outside.
"""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from velpoly.pose import slot_travel


def drive(a, e, psi, theta, r_lo, r_hi, omega=3.0, swap=False, ends=True, names=("frame", "crank", "wheel")):
    """The mechanism dict: O1 at the origin, C at e along psi deg, the pin A at theta deg."""
    f, k, w = names
    c = e * np.array([math.cos(math.radians(psi)), math.sin(math.radians(psi))])
    pa = a * np.array([math.cos(math.radians(theta)), math.sin(math.radians(theta))])
    u = (pa - c) / np.linalg.norm(pa - c)
    s_lo, s_hi = c + r_lo * u, c + r_hi * u
    ends_pts = ("S2", "S1") if swap else ("S1", "S2")
    mech = {
        "title": "pin in a bounded slot", "units": "mm",
        "points": {"O1": [0.0, 0.0], "C": c.tolist(), "A": {"from": "O1", "length": a, "angle": theta},
                   ends_pts[0]: s_lo.tolist(), ends_pts[1]: s_hi.tolist()},
        "links": {f: {"points": ["O1", "C"], "frame": True}, k: {"points": ["O1", "A"]},
                  w: {"points": ["C", "S1", "S2"]}},
        "slots": [{"pin": "A", "link": k, "slot": w, "angle": math.degrees(math.atan2(u[1], u[0]))}],
        "driver": {"link": k, "omega": omega},
    }
    if ends:
        mech["slots"][0]["ends"] = ["S1", "S2"]
    return mech


def rho(a, e, psi, theta_deg):
    """The pin's distance from the slotted link's pivot C at the crank angle theta."""
    t, p = np.radians(theta_deg), math.radians(psi)
    return np.hypot(a * np.cos(t) - e * math.cos(p), a * np.sin(t) - e * math.sin(p))


def exit_angle(a, e, psi, theta0, sense, r_lo, r_hi, span=360.0):
    """The first crank angle from theta0 in the sense ``sense`` where the pin reaches r_lo or r_hi
    (closed form sampled at 0.01 deg, then bisection to 1e-12 rad), or None within ``span``."""
    ts = theta0 + sense * np.arange(0.0, span + 0.005, 0.01)
    r = rho(a, e, psi, ts)
    out = (r <= r_lo) | (r >= r_hi)
    if not out.any():
        return None
    k = int(np.argmax(out))
    lo, hi = ts[k - 1], ts[k]
    bound = r_lo if r[k] <= r_lo else r_hi
    f = lambda t: rho(a, e, psi, t) - bound     # noqa: E731
    flo = f(lo)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if abs(hi - lo) < 1e-12 * 180 / math.pi:
            break
        if (f(mid) > 0) == (flo > 0):
            lo, flo = mid, f(mid)
        else:
            hi = mid
    return 0.5 * (lo + hi)


def generated(seed):
    """Geneva drives and slotted levers with random sizes, ends, reference angles and senses."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < 12:
        kind = ("geneva", "oscillating", "whitworth")[len(out) % 3]
        a = float(rng.uniform(0.5, 3.0))
        psi = float(rng.uniform(-180, 180)) if kind != "geneva" else 0.0
        if kind == "geneva":
            nslots = int(rng.integers(3, 9))
            e = a / math.sin(math.pi / nslots)
            r_hi = math.sqrt(e * e - a * a) * (1.0 if rng.random() < 0.5 else float(rng.uniform(0.95, 1.05)))
            r_lo = (e - a) * 0.7
        else:
            e = a * float(rng.uniform(1.3, 2.5) if kind == "oscillating" else rng.uniform(0.2, 0.75))
            lo_, hi_ = abs(e - a), e + a
            r_lo = lo_ + float(rng.uniform(-0.3, 0.5)) * (hi_ - lo_)
            r_hi = hi_ - float(rng.uniform(-0.3, 0.4)) * (hi_ - lo_)
            if r_hi - r_lo < 0.2 * (hi_ - lo_):
                continue
        theta = float(rng.uniform(-180, 180))
        r0 = float(rho(a, e, psi, theta))
        if not (r_lo + 0.05 * a < r0 < r_hi - 0.05 * a):
            continue
        sense = 1.0 if rng.random() < 0.5 else -1.0
        out.append((kind, a, e, psi, theta, r_lo, r_hi, sense, bool(rng.random() < 0.5)))
    return out


@pytest.mark.parametrize("seed", [3])
def test_the_sweep_stops_where_the_pin_reaches_an_end_and_solve_agrees(seed, monkeypatch):
    from velpoly import solution
    # the range the error names ("the pin is in the slot from ...") takes four continuations a
    # mechanism: test_command_line_messages checks it; here the end where the pin leaves is checked
    monkeypatch.setattr(solution, "reachable_range", lambda kin: (0.0, 0.0))
    monkeypatch.setattr(solution, "reachable_words", lambda kin, ref, refused=None: "0 to 0")   # its words too
    stops = 0
    for kind, a, e, psi, theta, r_lo, r_hi, sense, swap in generated(seed):
        m = velpoly.load(drive(a, e, psi, theta, r_lo, r_hi, omega=3.0 * sense, swap=swap))
        label = f"{kind} a={a} e={e} psi={psi} theta={theta} ends {r_lo}, {r_hi}, sense {sense}"
        step = 1.5
        angles = theta + sense * step * np.arange(240)
        w = velpoly.sweep(m, angles)
        want = exit_angle(a, e, psi, theta, sense, r_lo, r_hi, span=step * 239)
        # the pin stays between the ends at every pose the sweep gives
        t = slot_travel(m, w.kinematics.system.index, w.q)
        assert np.all((t >= -1e-9) & (t <= 1 + 1e-9)), label
        if want is None:
            assert len(w.angles) == len(angles) and not w.stopped and w.leaves is None, label
            continue
        stops += 1
        assert w.leaves is not None and w.leaves[:2] == ("A", "wheel"), label
        assert abs(w.leaves[2] - want) < 1e-6, (label, w.leaves, want)
        assert re.fullmatch(rf"pin A leaves the slot of wheel at {want:.1f} deg: \d+ of 240 positions not reached",
                            w.stopped), w.stopped
        passed = sense * (angles - want) > 0
        assert len(w.angles) == int(np.argmax(passed)), label
        if kind == "geneva" and r_hi == math.sqrt(e * e - a * a):   # the textbook drive: 90 - 180/n
            nslots = round(math.pi / math.asin(a / e))
            assert abs(abs(w.leaves[2]) - (90 - 180 / nslots)) < 1e-6, label
        # solve: inside the engaged stretch it solves on it, past the end it is exit 3
        inside = theta + 0.5 * (want - theta)
        s = velpoly.solve(m, angle=float(inside))
        assert np.allclose(s.position["A"], a * np.array([math.cos(math.radians(inside)),
                                                          math.sin(math.radians(inside))]), atol=1e-9 * a)
        if abs(want - theta) < 179.0:     # beyond it, still the shorter way round
            beyond = want + sense * min(1.0, 0.5 * (180 - abs(want - theta)))
            with pytest.raises(velpoly.PoseError, match=r"pin A leaves the slot of wheel at its end S[12] at "):
                velpoly.solve(m, angle=float(beyond))
    assert stops >= 6


def test_without_ends_nothing_changes():
    """The same slotted lever without ends: a whole turn, and the same poses where both reach."""
    a, e, psi, theta = 2.0, 0.8, -90.0, 30.0
    r_lo, r_hi = 1.5, 2.6
    bounded = velpoly.load(drive(a, e, psi, theta, r_lo, r_hi))
    free = velpoly.load(drive(a, e, psi, theta, r_lo, r_hi, ends=False))
    angles = theta + np.arange(360.0)
    wb, wf = velpoly.sweep(bounded, angles), velpoly.sweep(free, angles)
    assert len(wf.angles) == 360 and not wf.stopped and wf.leaves is None
    assert 0 < len(wb.angles) < 360 and wb.leaves is not None
    for key in wb.position:
        assert np.allclose(wb.position[key], wf.position[key][:len(wb.angles)], atol=1e-12)
    assert velpoly.solve(free, angle=200.0)


def test_the_pin_must_be_between_the_ends_in_the_drawn_pose():
    mech = drive(2.0, 0.8, -90.0, 30.0, 1.5, 2.6)
    pin_at = float(rho(2.0, 0.8, -90.0, 30.0))
    bad = drive(2.0, 0.8, -90.0, 30.0, pin_at + 0.1, 2.6)
    with pytest.raises(velpoly.InputError, match=r"slots\[0\]\.ends.*the pin 'A' is not between the ends"):
        velpoly.load(bad)
    wrong = dict(mech, slots=[dict(mech["slots"][0], ends=["S1", "O1"])])
    with pytest.raises(velpoly.InputError, match=r"slots\[0\]\.ends\[1\].*not a point of the slot's link"):
        velpoly.load(wrong)
    one = dict(mech, slots=[dict(mech["slots"][0], ends=["S1"])])
    with pytest.raises(velpoly.InputError, match=r"slots\[0\]\.ends.*two points"):
        velpoly.load(one)
    same = dict(mech, slots=[dict(mech["slots"][0], ends=["S1", "S1"])])
    with pytest.raises(velpoly.InputError, match=r"not apart along the slot"):
        velpoly.load(same)


GENEVA_4 = """
title = "Geneva drive, four slots"
units = "mm"
[points]
O2 = [0, 0]
O4 = [70.710678118654755, 0]
P = { from = "O2", length = 50, angle = 20 }
S1 = { from = "O4", length = 50, along = ["O4", "P"] }
S2 = { from = "O4", length = 15, along = ["O4", "P"] }
[links]
frame = { points = ["O2", "O4"], frame = true }
crank = { points = ["O2", "P"] }
wheel = { points = ["O4", "S1", "S2"] }
[[slots]]
pin = "P"
link = "crank"
slot = "wheel"
angle = %r
ends = ["S1", "S2"]
[driver]
link = "crank"
omega = "60 rpm"
"""


def test_command_line_messages(capsys, tmp_path):
    """A Geneva drive of four slots: ``solve --angle`` past the end is exit 3 naming the slot and
    the engaged range (+-45 deg), and ``sweep`` warns where the pin leaves the slot."""
    p = 50 * np.array([math.cos(math.radians(20)), math.sin(math.radians(20))]) - [70.710678118654755, 0]
    f = tmp_path / "geneva.toml"
    f.write_text(GENEVA_4 % math.degrees(math.atan2(p[1], p[0])))
    assert main(["solve", str(f), "--angle", "44"]) == 0
    capsys.readouterr()
    assert main(["solve", str(f), "--angle", "60"]) == 3
    err = capsys.readouterr().err.splitlines()
    assert err[0] == (f"error: {f}: --angle: cannot assemble at driver angle 60 deg: pin P leaves the slot of "
                      "wheel at its end S1 at 45 deg; the pin is in the slot from -45 to 45 deg (links crank, wheel)")
    assert main(["sweep", str(f), "--csv", str(tmp_path / "g.csv")]) == 0
    err = capsys.readouterr().err
    assert "warning: " in err and "pin P leaves the slot of wheel at 45.0 deg: 334 of 360 positions not reached" in err
    assert "the pin is in its slot from -45 to 45 deg" in err
    assert len((tmp_path / "g.csv").read_text().splitlines()) == 1 + 26


@pytest.mark.parametrize("before", [31.0, 31.3])     # 31: the end at a continuation step exactly
def test_a_pin_that_overshoots_an_end_between_two_steps_still_leaves(before):
    """The pin's farthest reach from C passes the outer end by a window of 2 deg only: narrower
    than a continuation step (6 deg) and than the sweep's steps (5 deg). ``solve`` 5 deg past the
    window and a 5-deg sweep across it both see the pin leave, where the closed form says."""
    a, e, psi = 1.0, 2.0, 0.0
    far = psi + 180.0                                   # A opposite C: |AC| = e + a
    half = math.radians(1.0)
    r_hi = float(rho(a, e, psi, far + math.degrees(half)))
    theta = far - before
    m = velpoly.load(drive(a, e, psi, theta, 0.5, r_hi, omega=2.0))
    want = exit_angle(a, e, psi, theta, 1.0, 0.5, r_hi, span=60.0)
    assert abs(want - (far - 1.0)) < 1e-9
    with pytest.raises(velpoly.PoseError, match=rf"leaves the slot of wheel at its end S2 at {want:g} deg"):
        velpoly.solve(m, angle=far + 6.0)
    w = velpoly.sweep(m, theta + 5.0 * np.arange(12))   # theta + 30 is in the window, +25 and +35 are not
    assert w.leaves is not None and abs(w.leaves[2] - want) < 1e-6 and len(w.angles) == 7
    w = velpoly.sweep(m, theta + 4.0 * np.arange(12))   # +28 and +32 both miss the window
    assert w.leaves is not None and abs(w.leaves[2] - want) < 1e-6 and len(w.angles) == 8
    free = velpoly.load(drive(a, e, psi, theta, 0.5, r_hi, omega=2.0, ends=False))
    assert len(velpoly.sweep(free, theta + 5.0 * np.arange(12)).angles) == 12
