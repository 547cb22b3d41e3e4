"""The mechanism zoo (tests/zoo.py): at least 300 generated mechanisms of every kind the contract
accepts, each solved at its drawn pose and at other driver angles, and checked:

* it loads (valid, mobility 1) and solves at its drawn pose, which the generator made regular;
  at another driver angle it solves, or the analytic solve says why not (a toggle on the way:
  AssemblyError; a singular pose: SingularPoseError from the analytic Jacobian), never the
  graphical construction failing on a regular pose;
* the graphical construction equals the analytic solve to 1e-9 (relative to the largest value),
  both polygons; the JSON of ``velpoly solve --json`` builds;
* every Kennedy triple is collinear and every found pole lies on both of its construction lines
  (``check_poles`` of test_poles); the instant-centre method gives the same omegas and velocities
  (``check_ic``);
* the analytic values equal finite differences of the pose (a sample, and every slider driver);
* a few of them draw their full or poles sheet.

``check_solution(sol)`` is the hook every solved pose goes through: add further checks there.
"""
from __future__ import annotations

import collections
import functools
import json
import math

import numpy as np
import pytest

import velpoly
from velpoly.errors import AssemblyError, SingularPoseError
from velpoly.kinematics import WARN
from velpoly.polygons import acceleration_polygon, hand_drafting, velocity_polygon
from velpoly.solution import driver_reference_angle

import zoo
from mechanisms import ranges_by_dyads_only
from test_poles import check_ic, check_poles

try:   # the arrow-sense checks (tests/checks_arrows.py), where that module is in the tree
    from checks_arrows import assert_arrows_true
except ImportError:
    assert_arrows_true = None

SEED = 20261125
COUNT = 300                      # cycling through the (kind, variant) pairs: 5 or 6 of each
TOL = 1e-9
# the specimens' kinds by their first word (test_zoo_is_big_and_covers_every_kind checks this is all of them)
ZOO_KINDS = ("contact", "eight-bar", "four-bar", "inverted", "pin", "six-bar", "slider-crank")
# generated when a test first needs them, not at collection (where every xdist worker would); the module's
# tests run on one worker (its xdist group), which generates them once
pytestmark = pytest.mark.xdist_group("zoo")


@functools.cache
def specimens() -> list:
    return zoo.zoo(SEED, COUNT)


@functools.cache
def by_kind() -> dict:
    out = collections.defaultdict(list)
    for sp in specimens():
        out[sp.kind.split(" ")[0]].append(sp)
    return dict(out)


@pytest.fixture(autouse=True)
def _ranges_by_dyads_only(monkeypatch):
    """The reachable range an AssemblyError names: by a dyad walk where there is one, else (0, 0)
    (tests/mechanisms.py's ranges_by_dyads_only)."""
    ranges_by_dyads_only(monkeypatch)


def check_solution(sol):
    """Every check one solved pose must pass (the hook: add checks here).

    Graphical == analytic to 1e-9; at a pose the contract warns about (condition above 1e6, near
    a toggle, where the construction's lines are nearly parallel and the analytic solve itself
    keeps fewer digits) to 1e-14 x condition instead."""
    tol = max(TOL, 1e-14 * sol.condition)
    v = velocity_polygon(sol)
    assert v.max_error <= tol, f"velocity polygon off by {v.max_error:.3g}"
    if sol.has_accelerations:
        a = acceleration_polygon(sol)
        assert a.max_error <= tol, f"acceleration polygon off by {a.max_error:.3g}"
    ps = check_poles(sol)
    if sol.condition <= WARN:
        check_ic(sol, ps)   # the instant-centre method's omegas and velocities, to 1e-9
    d = sol.to_dict()
    assert d["graphical"]["max_error"]["velocity"] <= tol
    if assert_arrows_true is not None:
        assert_arrows_true(sol)


def fd_check(sol, rel=1e-6):
    """The analytic velocities, accelerations, omegas and alphas against finite differences of the
    pose along the driver (a crank's angle or a slider's displacement u, five poses, fourth order):
    V = dp/du u', A = d2p/du2 u'^2 + dp/du u''."""
    m = sol.mechanism
    drv = m.driver
    steps = np.array([-2.0, -1.0, 0.0, 1.0, 2.0])
    if drv.is_slider:   # a step small beside the shortest link (a crank may be 1/20 of the size)
        xy = np.array(list(m.points.values()), float)
        gaps = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
        h = 2e-4 * gaps[np.triu_indices(len(xy), 1)].min()
        w = velpoly.sweep(m, steps * h)
        rate, accel = drv.speed, drv.accel
    else:
        h = 2e-4   # rad
        w = velpoly.sweep(m, sol.driver_angle + steps * math.degrees(h))
        rate, accel = drv.omega, drv.alpha
    assert len(w.angles) == 5, w.stopped
    tracks = {}   # key -> (analytic velocity, acceleration, the five poses' positions)
    for key in sol.velocity:
        p, _, lk = key.partition("@")
        if lk and (any(s.point == p and s.guide == lk for s in m.sliders)
                   or any(s.pin == p and s.slot == lk for s in m.slots) or any(c.point == p for c in m.contacts)):
            continue   # the guide's (slot's, profile's) point now under the block: not one material point
        tracks[key] = (sol.velocity[key], sol.acceleration[key], np.asarray(w.position[key], float))
    for lk in m.link_names:
        theta = np.radians(np.unwrap(np.asarray(w.angle[lk], float), period=360.0))
        tracks["theta_" + lk] = (sol.omega[lk], sol.alpha[lk], theta)
    vmax = max(float(np.max(np.abs(v))) for v, _, _ in tracks.values())
    amax = max(float(np.max(np.abs(a))) for _, a, _ in tracks.values()) if sol.has_accelerations else 0.0
    amax = max(amax, vmax * vmax / m.size)
    for key, (v, a, x) in tracks.items():
        d1 = (-x[4] + 8 * x[3] - 8 * x[1] + x[0]) / (12 * h)
        d2 = (-x[4] + 16 * x[3] - 30 * x[2] + 16 * x[1] - x[0]) / (12 * h * h)
        assert np.max(np.abs(v - d1 * rate)) <= rel * vmax, (key, v, d1 * rate)
        if sol.has_accelerations:   # the second difference loses ~eps / h^2 of the size
            assert np.max(np.abs(a - (d2 * rate ** 2 + d1 * accel))) <= 100 * rel * amax, (key, a, d2, d1)


def _solve_all(specimens):
    """Solve every specimen at each of its driver offsets; check each solved pose.

    Returns (failures, counts). A failure is any exception other than the analytic solve's own
    AssemblyError (a toggle on the way to the angle) or SingularPoseError (the Jacobian singular),
    and those too at a specimen's drawn pose, which the generator made regular.
    """
    failures, counts = [], collections.Counter()
    for k, sp in enumerate(specimens):
        m = sp.drawn.mechanism   # the generator loaded and solved it at its drawn pose
        ref = driver_reference_angle(m)
        for off in sp.offsets:
            try:
                sol = sp.drawn if off is None else velpoly.solve(m, ref + off)
            except (AssemblyError, SingularPoseError) as e:
                counts["not reached"] += 1
                if off is None:
                    failures.append((sp.kind, "drawn pose", repr(e)))
                continue
            except Exception as e:   # noqa: BLE001
                failures.append((sp.kind, off, repr(e)[:400]))
                continue
            try:
                check_solution(sol)
                if off is None and (m.driver.is_slider or k % 6 == 0) and sol.condition < WARN and \
                        all(c.centres is not None for c in m.contacts):   # (a normal alone: no other pose)
                    fd_check(sol)
                    counts["finite differences"] += 1
                if off is None and k % 8 == 0:   # the replay of the plan with drafting errors runs too
                    h = hand_drafting(sol, samples=16)
                    assert all(np.isfinite(v).all() for v in h["velocity"]["speed"].values())
            except Exception as e:   # noqa: BLE001 -- collect them all, report together
                failures.append((sp.kind, off, f"condition {sol.condition:.3g}", repr(e)[:400]))
                continue
            counts["solved"] += 1
    return failures, counts


def test_zoo_is_big_and_covers_every_kind():
    assert len(specimens()) >= 300
    assert tuple(sorted(by_kind())) == ZOO_KINDS
    kinds = {sp.kind for sp in specimens()}
    for kind, (_, variants) in zoo.KINDS.items():
        for v in variants:
            assert any(k.endswith(v) for k in kinds), (kind, v)
    assert any(sp.mech["driver"].get("slider") for sp in by_kind()["inverted"])
    # the same seed, the same zoo (made anew: zoo.zoo shares a seed's specimens within the process)
    again = zoo.fresh_zoo(SEED, 20)
    assert [s.mech for s in again] == [s.mech for s in specimens()[:20]]


@pytest.mark.parametrize("kind", ZOO_KINDS)
def test_zoo(kind):
    failures, counts = _solve_all(by_kind()[kind])
    assert not failures, f"{len(failures)} failures:\n" + "\n".join(map(str, failures[:20]))
    # most poses solve (so the checks ran): every drawn pose, and most of the others
    offsets = sum(len(sp.offsets) for sp in by_kind()[kind])
    assert counts["solved"] >= len(by_kind()[kind]) and counts["solved"] >= 0.8 * offsets, counts


def test_inverted_slider_driven_uses_case_2a():
    """A slider driver on a turning guide: the block's image is found by the ordinary dyad step,
    its two lines through known images (the other link's, and the guide's offset by the slip)."""
    n = 0
    for sp in by_kind()["inverted"]:
        if not sp.mech["driver"].get("slider"):
            continue
        sol = velpoly.solve(velpoly.load(sp.mech))
        for poly in (velocity_polygon(sol), acceleration_polygon(sol)):
            kinds = [st.kind for st in poly.steps]
            assert "auxiliary" not in kinds and "instant-centre" not in kinds, (sp.kind, kinds)
            assert any("offset by the driver's slip" in ln.reason
                       for st in poly.steps if st.kind == "intersection" for ln in st.lines) \
                or kinds[:2] == ["known", "driver"], (sp.kind, kinds)
        n += 1
    assert n >= 20


# rendering is slow: a few specimens only, where the drawing has the most to draw (blocks on turning
# guides, slots, contacts, a six-bar driven by its slider, an eight-bar), both sheets, as SVG
def test_slider_driver_on_a_turning_guide_lines_are_the_books():
    """At the data level: the block's point X (pinned to crank 2 about O2) is found where the line
    through o2 perpendicular to O2X meets the line through o4 + V_X3/X4 (the driver's slip, speed
    along the path) perpendicular to O4X; in the acceleration polygon the offset line starts at
    o4' + A^n_X4O4 + A_X3/X4 + 2 omega_4 x V_X3/X4, every term from the analytic solve."""
    n = 0
    for sp in by_kind()["inverted"]:
        drv = sp.mech["driver"]
        if not drv.get("slider") or "swinging" in sp.kind or "curved" in sp.kind:
            continue
        sol = sp.drawn
        m = sol.mechanism
        o4 = sol.position["O4"]
        d = np.array([math.cos(math.radians(sol.motion.sliders[0]["direction"][0])),
                      math.sin(math.radians(sol.motion.sliders[0]["direction"][0]))])
        w4 = sol.omega["4"]
        vrel = m.driver.speed * d
        scale = max(np.abs(v).max() for v in sol.velocity.values())
        ascale = max(np.abs(v).max() for v in sol.acceleration.values())
        for poly in (velocity_polygon(sol), acceleration_polygon(sol)):
            st = next(st for st in poly.steps if st.kind == "intersection")
            x_pos = sol.position["A@2" if "A@2" in sol.position else "A"]
            r = x_pos - o4
            off = [ln for ln in st.lines if "offset by the driver's slip" in ln.reason]
            crank = [ln for ln in st.lines if ln.reason == "perpendicular to O2A"]
            assert len(off) == 1 and len(crank) == 1, [ln.reason for ln in st.lines]
            if poly.kind == "velocity":
                base, tol = vrel, 1e-9 * scale
                x_img = sol.velocity["A@2" if "A@2" in sol.velocity else "A"]
            else:
                base = -w4 ** 2 * r + m.driver.accel * d + 2 * w4 * np.array([-vrel[1], vrel[0]])
                tol = 1e-9 * ascale
                x_img = sol.acceleration["A@2" if "A@2" in sol.acceleration else "A"]
            assert np.abs(off[0].base - base).max() <= tol
            assert abs(float(np.dot(off[0].direction, r))) <= 1e-9 * np.linalg.norm(r)
            a_pos = x_pos - sol.position["O2"]
            assert abs(float(np.dot(crank[0].direction, a_pos))) <= 1e-9 * np.linalg.norm(a_pos)
            for ln in st.lines:   # the image found lies on both lines
                e = x_img - ln.base
                assert abs(e[0] * ln.direction[1] - e[1] * ln.direction[0]) <= tol
        n += 1
    assert n >= 15


def test_slider_driver_files_solve_from_the_command_line(tmp_path, capsys):
    """The hydraulic boom (cylinder 4 about O4 drives the block 3 pinned to the boom 2 at A): exit 0,
    as TOML through the CLI, the path through the pivot and offset from it; --angle stays exit 2."""
    from velpoly.cli import main
    for offset in (0.0, 25.0):
        path = tmp_path / "boom.toml"
        o4, a = (2.0, 0.0), (1.5 * math.cos(math.radians(60)), 1.5 * math.sin(math.radians(60)))
        angle = math.degrees(math.atan2(a[1] - o4[1], a[0] - o4[0])) + offset
        path.write_text(f"""title = "hydraulic boom"
[points]
O2 = [0, 0]
O4 = [2, 0]
A = {{ from = "O2", length = 1.5, angle = 60 }}
C = {{ from = "O4", length = 4, along = ["O4", "A"] }}
[links]
1 = {{ points = ["O2", "O4"], frame = true }}
2 = {{ points = ["O2", "A"] }}
3 = {{ points = ["A"] }}
4 = {{ points = ["O4", "C", "A"] }}
[[sliders]]
block = "3"
guide = "4"
point = "A"
angle = {angle!r}
[driver]
slider = "A"
speed = 0.5
accel = 0.1
""")
        assert main(["solve", str(path), "--json"]) == 0
        out = json.loads(capsys.readouterr().out)
        assert out["graphical"]["max_error"]["velocity"] <= TOL
        assert out["graphical"]["max_error"]["acceleration"] <= TOL
        assert abs(out["sliders"][0]["slip_velocity"] - 0.5) <= 1e-12
        assert main(["solve", str(path), "--angle", "30"]) == 2
        assert "a slider driver has no angle" in capsys.readouterr().err


# (four until the suite had to fit 2 minutes, a sheet is a second: a cam with a roller follower and a quick-return
# six-bar draw every panel of their full sheets as the gallery's cam_roller_follower and crank_shaper in
# test_render_gallery; a slider driver's full sheet stays here, the inverted slider-crank's)
RENDER = {"inverted slider-crank offset both slider": "full", "pin in a slot circular six-bar": "poles"}


@pytest.mark.parametrize("kind", RENDER)
def test_zoo_sheets_draw(kind, tmp_path):
    """The full or the poles sheet of a few specimens draws (SVG, no error, a real drawing): each sheet
    on one kind the gallery lacks (every gallery file draws its full sheet and some their poles sheet:
    test_render_gallery)."""
    from velpoly.render import draw_to_file
    sp = next(s for s in specimens() if s.kind.endswith(kind))
    sol = velpoly.solve(velpoly.load(sp.mech))
    sheet = RENDER[kind]
    out = draw_to_file(sol, tmp_path / f"{sheet}.svg", sheet=sheet)
    assert out and all(p.stat().st_size > 10_000 for p in out)
    text = out[0].read_text()
    assert text.count("<path") > 20


def test_auxiliary_point_reached_through_a_slip_is_true():
    """A block on a floating guide (tests/zoo.py ``gen_floating_guide``): link 4's auxiliary point
    S4 is reached from the block's point A through the slip, ``V_S4 = V_O2 + V_A2O2 - V_A3/A4 +
    V_S4A4`` (a line that subtracts a joint's terms and adds others). On fresh seeds, every variant
    (crank or slider driven, the guide listing A or not), at the drawn pose and (crank driven) others:
    every arrow is what its label names and they run tip to tail (the subtracted slip and
    Coriolis drawn forwards as V_A4/A3, 2 omega_4 x V_A4/A3); a step is called the instant
    centre's only where S4's image is at O_v (a line offset by a known slip does not go through it);
    graphical == analytic."""
    rng = np.random.default_rng(SEED + 13)
    variants = [v for v in zoo.SIXBARS if v.startswith("floating guide")]
    reversed_seen = ic_seen = solved = 0
    # ten of each variant (twenty until the suite had to fit 2 minutes; about 1 s: the slider driven ones reach
    # S4 through the slip): 39 poses, 15 reversed slips or Coriolis terms, 5 instant-centre steps
    for k in range(10 * len(variants)):
        sp = zoo.specimen(rng, "six-bar", variants[k % len(variants)])
        m = sp.drawn.mechanism
        ref = driver_reference_angle(m)
        for off in sp.offsets:
            try:
                sol = sp.drawn if off is None else velpoly.solve(m, ref + off)
            except (AssemblyError, SingularPoseError):
                assert off is not None, sp.kind
                continue
            check_solution(sol)
            assert_arrows_true(sol)   # (also where check_solution's import fell back)
            solved += 1
            for poly in (velocity_polygon(sol), acceleration_polygon(sol)):
                for st in poly.steps:
                    if st.kind == "instant-centre":
                        ic_seen += 1
                        for key in st.auxiliary:
                            assert np.abs(poly.auxiliary[key].image).max() <= 1e-12, st.equation
                    for v in st.vectors:
                        if v.kind in ("slip", "coriolis") and tuple(v.of[1:3] if v.kind == "slip" else v.of[2:4]) == \
                                ("A@4", "A@3"):
                            reversed_seen += 1   # A4 relative to A3: a subtracted term drawn forwards
    assert solved >= 35 and reversed_seen >= 10 and ic_seen >= 3, (solved, reversed_seen, ic_seen)


def test_a_seed_s_specimens_are_made_once_and_each_call_gets_its_own_dicts():
    """zoo.zoo shares a seed's specimens within the process: a longer batch goes on from a shorter one, as
    fresh_zoo makes them; the solutions are shared, each call's dicts are its own. zoo.each hands out the same
    specimens one at a time, going on from those made (two made here, then one more) with dicts of its own."""
    first = zoo.zoo(424242, 3)
    more = zoo.zoo(424242, 5)
    assert [s.mech for s in more] == [s.mech for s in zoo.fresh_zoo(424242, 5)]
    assert all(a.drawn is b.drawn and a.mech is not b.mech and a.mech == b.mech for a, b in zip(first, more))
    one = list(zoo.each(424242, 6))
    assert [s.mech for s in one] == [s.mech for s in zoo.fresh_zoo(424242, 6)]
    assert all(a.drawn is b.drawn and a.mech is not b.mech for a, b in zip(one, more))
