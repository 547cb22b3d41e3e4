"""The construction plan kept per mechanism (velpoly.polygons ``_planned``, ``_Tape``; issue 20).

A plan made at one pose is re-used at another pose of the same mechanism when every decision the
planner made from the pose (a point apart from another, the best pair of lines and whether it is
regular, the auxiliary point's pair and place) comes out alike there; else the planner plans afresh.
The outputs must be the very bytes of planning afresh at every pose: here the JSON of
``velpoly solve --json`` and both polygons whole (steps, lines, vectors, captions, sines, images, every
float by its repr), poses solved one after another in one process (the plans kept) against each pose
planned afresh (nothing kept), on the examples, on generated mechanisms (tests/zoo.py,
tests/mechanisms.py: six-bars, sliders, slots, contacts, Coriolis), and where a kept plan's decision
fails (a sweep across the poses where an auxiliary point's pair changes; a kept tape made to disagree).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import velpoly
from velpoly import polygons
from velpoly.polygons import acceleration_polygon, velocity_polygon
from velpoly.solution import driver_reference_angle

import mechanisms
import zoo
from test_polygons import STEPHENSON3, _stephenson3

EXAMPLES = sorted((Path(velpoly.__file__).parent / "examples").glob("*.toml"))
TRIAD = {"points": {"O2": [0, 0], "G1": [1.0, 0.0], "G2": [0.6, -0.3], "A": [0.15, 0.2], "X": [0.9, 0.6],
                    "Y": [0.4, 0.5], "Z": [0.3, 0.9]},
         "links": {"0": {"points": ["O2", "G1", "G2"], "frame": True}, "2": {"points": ["O2", "A"]},
                   "3": {"points": ["A", "Z"]}, "4": {"points": ["G1", "X"]}, "5": {"points": ["G2", "Y"]},
                   "6": {"points": ["X", "Y", "Z"]}},
         "driver": {"link": "2", "omega": 3, "alpha": 1}}   # link 6 on three binaries: an auxiliary point


def _plain(x):
    """A polygon (dataclasses, arrays, dicts) as plain data, every float by its repr."""
    if isinstance(x, np.ndarray):
        return _plain(x.tolist())
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if isinstance(x, float):
        return repr(x)
    if hasattr(x, "__dataclass_fields__"):
        return {k: _plain(getattr(x, k)) for k in x.__dataclass_fields__}
    return x


def _outputs(m, angle, polygons_too=True) -> str:
    """What a pose gives: the JSON text, both polygons whole, or the error each raises."""
    try:
        s = velpoly.solve(m, angle)
    except velpoly.VelpolyError as e:
        return f"solve: {type(e).__name__}: {e}"
    out = [json.dumps(s.to_dict(), indent=2, allow_nan=False)]
    for fn in (velocity_polygon, acceleration_polygon) if polygons_too else ():
        try:
            out.append(json.dumps(_plain(fn(s))))
        except velpoly.VelpolyError as e:
            out.append(f"{fn.__name__}: {type(e).__name__}: {e}")
    return "\n".join(out)


@pytest.fixture(autouse=True)
def _no_reachable_range(monkeypatch):
    """A pose beyond a toggle: the AssemblyError's range by continuation takes seconds (test_zoo does
    the same); here it is (0, 0) on both paths alike."""
    from velpoly import solution
    monkeypatch.setattr(solution, "reachable_range", lambda kin: (0.0, 0.0))
    monkeypatch.setattr(solution, "reachable_words", lambda kin, ref, refused=None: "0 to 0")   # its words too


@pytest.fixture
def planned(monkeypatch):
    """Counts the planner's runs per mechanism (``planned[m]``); the plans kept start empty."""
    monkeypatch.setattr(polygons, "_PLANS", {})
    runs = {}
    real = polygons._Planner.run

    def counting(self):
        runs[id(self.g.m)] = runs.get(id(self.g.m), 0) + 1
        return real(self)

    monkeypatch.setattr(polygons._Planner, "run", counting)
    return type("Runs", (), {"__getitem__": lambda _, m: runs.get(id(m), 0)})()


def _fresh(m, angle, polygons_too=True) -> str:
    """The pose planned afresh: no plan kept for the mechanism."""
    polygons._PLANS.clear()
    return _outputs(m, angle, polygons_too)


def _sweep_alike(m, angles, polygons_too=True) -> int:
    """Solve the poses one after another (plans kept), each against the same pose planned afresh;
    returns how many poses solved."""
    kept = [_outputs(m, a, polygons_too) for a in angles]
    fresh = [_fresh(m, a, polygons_too) for a in angles]
    for a, k, f in zip(angles, kept, fresh):
        assert k == f, f"{m.title or m.source}: driver angle {a}: a kept plan gives other outputs than planning afresh"
    return sum(not k.startswith("solve:") for k in kept)


def _angles(m, count, step):
    """The file's pose and ``count`` others about it, ``step`` degrees apart (near: a pose beyond a
    toggle costs the reassembly a second to say so)."""
    if m.driver.is_slider:
        return [None]
    ref = driver_reference_angle(m)
    return [None] + [ref + step * (k - count // 2) for k in range(count + 1) if k != count // 2]


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_examples_alike_with_kept_plans(path, planned):
    m = velpoly.load(path)
    angles = _angles(m, 6, 12.0)
    solved = _sweep_alike(m, angles)
    assert solved >= 1


def test_the_six_bar_plans_once_for_every_pose(planned):
    """The JSON's mechanism: one plan for a whole turn of the crank (the cache is used)."""
    m = velpoly.load(EXAMPLES[[p.stem for p in EXAMPLES].index("problem_1_4_4_sixbar")])
    ref = driver_reference_angle(m)
    texts = [_outputs(m, ref + 10.0 * k, polygons_too=False) for k in range(36)]
    assert planned[m] == 1 and len(polygons._PLANS[id(m)][1]) == 1
    assert all(t.startswith("{") for t in texts)


_RNG = np.random.default_rng(20261126)
ZOO = [zoo.specimen(_RNG, kind) for kind in zoo.KINDS for _ in range(2)]   # four- and six-bars, sliders, slots,
                                                                          # contacts, eight-bars


@pytest.mark.parametrize("sp", ZOO, ids=[f"{i}-{s.kind}" for i, s in enumerate(ZOO)])
def test_zoo_alike_with_kept_plans(sp, planned):
    m = velpoly.load(sp.mech)
    angles = [None] if sp.offsets == (None,) else _angles(m, 4, 15.0)
    _sweep_alike(m, angles)


GENERATED = ([mechanisms.block_on_driven_crank(s) for s in range(2)]
             + [mechanisms.block_on_driving_guide(s) for s in range(2)]
             + [mechanisms.pin_in_slot(1, driver=d, circular=c) for d in ("pin", "slot") for c in (False, True)]
             + [mechanisms.sliding_cam(1, follower=f) for f in ("curved", "flat")]
             + [mechanisms.sliding_on_frame(1, surface=f) for f in ("curved", "flat")])


@pytest.mark.parametrize("mech", GENERATED, ids=range(len(GENERATED)))
def test_coriolis_slots_and_contacts_alike_with_kept_plans(mech, planned):
    m = velpoly.load(mech)
    _sweep_alike(m, _angles(m, 4, 15.0))


@pytest.mark.parametrize("mech", [_stephenson3(STEPHENSON3, "1", 3.0, 1.0), TRIAD], ids=["stephenson III", "triad"])
def test_a_decision_that_changes_plans_afresh(mech, planned):
    """Across these poses the auxiliary point's pair of normals changes (or whether S is the link's
    instant centre): the kept plan's decisions fail there and the planner plans afresh; every pose
    is still the fresh plan's, and the plans made are kept (at most KEPT_PLANS)."""
    m = velpoly.load(mech)
    ref = driver_reference_angle(m)
    angles = [ref + k for k in range(-30, 12)]   # (beyond: the Stephenson III's toggle)
    kept = [_outputs(m, a, polygons_too=False) for a in angles]
    runs = planned[m]
    assert 1 < runs < len(angles)   # some poses re-used a plan, some needed another
    assert 1 < len(polygons._PLANS[id(m)][1]) <= polygons.KEPT_PLANS
    assert sum(not k.startswith("solve:") for k in kept) == len(angles)
    for a, k in zip(angles[::3], kept[::3]):
        assert k == _fresh(m, a, polygons_too=False), f"driver angle {a}"
    assert _sweep_alike(m, angles[::6]) > 5


def _spoil(m, which):
    """Make the decision ``which`` of the plan kept for m disagree with every pose."""
    tape = polygons._PLANS[id(m)][1][0].tape
    k = [i for i, (fn, _, _) in enumerate(tape.entries) if fn.__name__ == which][-1]
    fn, args, out = tape.entries[k]
    tape.entries[k] = (fn, args, ("not", "an", "outcome"))


@pytest.mark.parametrize("which", ["_best_pair", "_farthest", "_apart"])
def test_a_kept_plan_whose_decision_fails_is_not_used(which, planned):
    """A kept tape made to disagree (as a pose where that decision differs would): the pose is planned
    afresh, gives the fresh plan's outputs, and the new plan is kept in front."""
    m = velpoly.load(EXAMPLES[[p.stem for p in EXAMPLES].index("problem_1_4_4_sixbar")])
    ref = driver_reference_angle(m)
    _outputs(m, ref)
    _spoil(m, which)
    got = _outputs(m, ref + 20.0)
    assert planned[m] == 2 and len(polygons._PLANS[id(m)][1]) == 2
    assert got == _fresh(m, ref + 20.0)


def test_a_failed_tape_after_an_auxiliary_point_leaves_a_clean_geometry(planned):
    """The tape places the auxiliary point S in the pose's geometry before its later decisions: one of
    those failing, the pose is planned on a geometry without S (else S' would be named)."""
    m = velpoly.load(TRIAD)
    ref = driver_reference_angle(m)
    _outputs(m, ref)
    tape = polygons._PLANS[id(m)][1][0].tape
    names = [fn.__name__ for fn, _, _ in tape.entries]
    assert "_place_auxiliary" in names and names.index("_place_auxiliary") < len(names) - 1
    fn, args, out = tape.entries[-1]
    tape.entries[-1] = (fn, args, ("not", "an", "outcome"))
    got = _outputs(m, ref + 2.0)
    assert planned[m] == 2
    assert got == _fresh(m, ref + 2.0)
    assert "S6'" not in got


def test_trial_solutions_are_planned_afresh(planned):
    """Which trial is best compares whole constructions: such a plan is not kept."""
    m = velpoly.load(_stephenson3(STEPHENSON3, "4", 3.0, 1.0))
    ref = driver_reference_angle(m)
    angles = [ref, ref + 1.0, ref - 1.0]
    assert _sweep_alike(m, angles) == 3
    assert not polygons._PLANS[id(m)][1]
