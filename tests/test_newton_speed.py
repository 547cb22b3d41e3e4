"""The reachable range's second continuation of a direction follows the first's knots
(``velpoly.pose.Knots``) instead of stepping them again: the answers must be those of the
algorithm before it, bit for bit.

``_reference_range`` is the former ``velpoly.driver._reachable_range``: each reassembly from
scratch (``reassemble`` given a fresh ``Knots`` steps every knot itself, as the code before it did;
given none, it keeps them by mechanism equality from one call to the next). Every reassembly the new code makes is compared with the reference's, in order: the same driver
positions and poses (exact equality of floats), the same stop and the same slot end; and the
ranges are equal. The mechanisms are generated (seeded zoo specimens reached by continuation: a slot
and a six-bar, each past a toggle both ways; an inverted slider-crank solved at angle after angle, both
ways and past its toggle). (A contact's range as the former code gave it is test_cycle's: the rolling-contact
example's, on the range its gallery sweep computes.)
"""
from __future__ import annotations

import numpy as np
import pytest

import velpoly
from velpoly import driver, pose
from velpoly.kinematics import prepare

from zoo import specimen


def _reference_range(kin, limit=360.0, step=1.0, resolution=0.01):
    """velpoly.driver._reachable_range as it was before the knots were kept (eb22ca2): each
    continuation with knots of its own (a fresh ``Knots``: none kept from another call)."""
    out = []
    for sign in (1.0, -1.0):
        coarse = np.arange(step, limit + step / 2, step)
        r = pose.reassemble(kin.system, list(kin.rows), np.radians(coarse) * sign, knots=pose.Knots())
        if r.leaves is not None:
            out.append(round(float(np.degrees(r.leaves[2])), 6))
            continue
        last = float(np.degrees(abs(r.deltas[-1]))) if len(r.deltas) else 0.0
        if last < limit:
            fine = np.arange(last + resolution, min(last + step, limit) + resolution / 2, resolution)
            path = np.concatenate([coarse[coarse <= last + 1e-9], fine])
            r = pose.reassemble(kin.system, list(kin.rows), np.radians(path) * sign, knots=pose.Knots())
            last = float(np.degrees(abs(r.deltas[-1]))) if len(r.deltas) else 0.0
        out.append(sign * round(last / resolution) * resolution)
    return out[1], out[0]


def _recorded(monkeypatch, run, kin):
    """(range, every Reassembly the run made, in order, how many knot steps and how many
    evaluations of the equations it took)."""
    made, steps, evals = [], [], []
    real_reassemble, real_step = pose.reassemble, pose._step
    system = kin.system.positions
    real_evaluate = type(system).evaluate

    def evaluate(self, *a, **k):
        evals.append(self is system)
        return real_evaluate(self, *a, **k)

    def reassemble(*a, **k):
        made.append(real_reassemble(*a, **k))
        return made[-1]

    def step(*a):
        steps.append(1)
        return real_step(*a)
    monkeypatch.setattr(driver, "reassemble", reassemble)
    monkeypatch.setattr(pose, "reassemble", reassemble)
    monkeypatch.setattr(pose, "_step", step)
    monkeypatch.setattr(type(system), "evaluate", evaluate)
    try:
        found = run(kin, 360.0, 1.0, 0.01)
    finally:
        monkeypatch.undo()
    return found, made, len(steps), sum(evals)


def _same_reassembly(a, b):
    assert np.array_equal(a.deltas, b.deltas) and np.array_equal(a.q, b.q)
    assert (a.stopped, a.continued) == (b.stopped, b.continued)
    assert (a.leaves is None) == (b.leaves is None)
    if a.leaves is not None:
        assert a.leaves[:2] == b.leaves[:2] and a.leaves[2] == b.leaves[2]


# specimens of the zoo (kind, variant, seed) reached by continuation and stopped both ways within
# a turn at a true toggle (the velocity system's condition 1e5-1e6 a fiftieth of a degree before each
# end). The four here before turned a whole turn: their "toggles" were positions equal to a knot but
# for rounding, refused by _smooth (test_knot_rounding). Each takes one path through Knots (counted: new
# knot steps, kept ones taken, toggle retries, 1-3 of them kept; none leaves a slot): the inverted
# slider-crank (offset both crank, seed 0), a fourth here until the suite had to fit 2 minutes (1.1 CPU s),
# is test_knots_kept_from_call_to_call_give_the_fresh_poses's, kept knots against fresh past its toggle both ways.
# A contact (wheel slipping on ground, seed 3; 1.1 CPU s) was cut by issue 19 item 7: every break by hand of
# Knots and _reachable_range that failed it failed the two kept (a retried step kept without its target, the
# fine walk not from the last knot reached, the second walk on fresh knots), and the contact's kept-knots range
# against the former code's is test_cycle's (Fig. 3.15a's EXACT, which the fine walk's break fails too)
SPECIMENS = [("slot", "straight offset", 0), ("six-bar", "stephenson III by its binary", 2)]


@pytest.mark.parametrize("kind, variant, seed", SPECIMENS)
def test_kept_knots_give_the_former_ranges_and_poses_bit_for_bit(monkeypatch, kind, variant, seed):
    kin = prepare(velpoly.load(specimen(np.random.default_rng(seed), kind, variant).mech))
    assert pose.plan_for(kin.system.positions) is None      # continuation, not the dyads' closed form
    old, old_made, old_steps, old_evals = _recorded(monkeypatch, _reference_range, kin)
    new, new_made, new_steps, new_evals = _recorded(monkeypatch, driver._reachable_range, kin)
    assert new == old and -360.0 < old[0] <= 0.0 <= old[1] < 360.0, (old, new)
    assert len(new_made) == len(old_made)
    for a, b in zip(new_made, old_made):
        _same_reassembly(a, b)
    assert new_steps < old_steps      # the second walk's knots were not stepped again
    assert new_evals < old_evals


def test_knots_are_forgotten_for_another_continuation():
    """A Knots kept for one system, rows or step is not used for another."""
    kin = prepare(velpoly.load(specimen(np.random.default_rng(1), "contact", "wheel on ground").mech))
    system, rows = kin.system.positions, list(kin.rows)
    knots = pose.Knots()
    coarse = np.radians(np.arange(1.0, 31.0))
    first = pose.reassemble(kin.system, rows, coarse, knots=knots)
    assert len(knots.d) > 1 and knots.key[0] is system
    other = pose.reassemble(kin.system, rows, coarse, coarse=np.radians(5.0), knots=knots)
    assert knots.key[2] == np.radians(5.0)
    _same_reassembly(other, pose.reassemble(kin.system, rows, coarse, coarse=np.radians(5.0)))
    _same_reassembly(first, pose.reassemble(kin.system, rows, coarse))


def test_knots_kept_from_call_to_call_give_the_fresh_poses(monkeypatch):
    """``reassemble`` without ``knots`` (``solve`` at an angle) keeps them by mechanism equality, one
    way from the drawn pose and the other: a mechanism loaded again and solved at angle after angle,
    both ways and past its toggle, gets the poses and stops of fresh continuations, bit for bit, in
    fewer knot steps."""
    sp = specimen(np.random.default_rng(0), "inverted slider-crank", "offset both crank")   # -100.56 to 88.66
    angles = [40.0, -30.0, 150.0, 100.0, 60.0, -90.0, -150.0]
    steps, real_step = [], pose._step
    monkeypatch.setattr(pose, "_step", lambda *a: steps.append(1) or real_step(*a))
    made, kins = [], [prepare(velpoly.load(sp.mech)) for _ in range(2)]   # equal mechanisms, not the same
    for fresh in (False, True):
        del steps[:]
        for i, t in enumerate(angles):
            kin = kins[i % 2]
            made.append(pose.reassemble(kin.system, list(kin.rows), [np.radians(t)],
                                        knots=pose.Knots() if fresh else None))
        made.append(len(steps))
    kept, fresh = made[:len(angles) + 1], made[len(angles) + 1:]
    for a, b in zip(kept[:-1], fresh[:-1]):
        _same_reassembly(a, b)
    reached = [len(r.deltas) for r in fresh[:-1]]
    assert reached == [1, 1, 0, 0, 1, 1, 0]      # 150, 100 and -150 deg are past a toggle
    assert kept[-1] < 0.6 * fresh[-1]          # each way walked once (51 knot steps, 100 fresh)
