"""The pose continuation's shortcuts give the bits of the computations they replace.

* one pose's pins (``constraints._pins_one``, pin by pin) and equations (rows gathered, chords kept per
  frame) give the bytes of the same pose evaluated in a batch of poses (arrays, nothing kept);
* ``Jet.rotated``'s two-column case (a link's point or direction) gives the general loop's columns;
* a continuation step's tangents, each solved once (``pose._tangent``), and its kept retries
  (``Knots.retry``) give the poses and stops of tangents and retries made afresh.

The mechanisms are generated (seeded: tests/zoo.py): contacts (rolling, cams with a flat or curved
follower), a slot, sliders (a slider driver, a curved one, a floating guide). Floats are compared by their bytes.
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

import velpoly
from velpoly import constraints, jet, pose
from velpoly.jet import Grad, Jet
from velpoly.kinematics import prepare

from zoo import specimen

KINDS = [("contact", "wheel on ground", 5), ("contact", "cam flat follower", 5), ("contact", "cam curved follower", 5),
         ("slot", "circular", 1), ("slider-crank", "curved slider", 5), ("six-bar", "floating guide slider", 5)]
CAM, SLOT = 1, 3    # a cam turning 135 degrees either way; a slot with a toggle at 10-15 degrees (KINDS' seed 1)


@functools.cache
def _systems():
    return [prepare(velpoly.load(specimen(np.random.default_rng(seed), kind, variant).mech)).system
            for kind, variant, seed in KINDS]


def _slider_driven():
    """A slider-crank driven by its block (the driver's coordinate and the path share a chord)."""
    from mechanisms import slider_crank
    mech = slider_crank()
    mech["driver"] = {"slider": "B", "speed": 2.0, "accel": 0.5}
    return prepare(velpoly.load(mech)).system


def test_one_pose_is_the_batch_s_row_to_the_bit():
    """evaluate at one pose (pins on floats, rows gathered, chords kept) == that pose in a batch (arrays)."""
    rng = np.random.default_rng(3)
    for system in [*_systems(), _slider_driven()]:
        for s in (system, system.positions):
            q = rng.normal(size=(2, s.nq)) * 0.3
            q[:, 0::3] *= s.size
            q[:, 1::3] *= s.size
            qd = rng.normal(size=(2, s.nq))
            both = s.evaluate(q, qd)
            for k in range(2):
                one = s.evaluate(q[k:k + 1], qd[k:k + 1])
                for got, want in zip(one, both):
                    assert got[0].tobytes() == want[k].tobytes(), s.mechanism.title


def test_chords_kept_in_a_frame_are_the_ones_made_afresh(monkeypatch):
    """A frame's kept chord (:meth:`Frame.chord`) is what each equation made for itself before."""
    rng = np.random.default_rng(4)
    systems = [*_systems(), _slider_driven()]
    poses = [rng.normal(size=(1, s.nq)) * 0.2 for s in systems]
    kept = [s.evaluate(q, q) for s, q in zip(systems, poses)]
    monkeypatch.setattr(constraints.Frame, "chord",
                        lambda f, a, sa, b, sb: constraints._sub(f.point(a, sa), f.point(b, sb)))
    for s, q, want in zip(systems, poses, kept):
        for got, w in zip(s.evaluate(q, q), want):
            assert got.tobytes() == w.tobytes(), s.mechanism.title


def _grad(rng, cols, n=9):
    return Grad({int(k): float(rng.normal()) for k in cols}, float(rng.choice([0.0, -0.0])), n)


def test_rotated_two_columns_are_the_loop_s(monkeypatch):
    """Jet.rotated with the one-column layouts (and others, which the loop takes) == the general loop."""
    rng = np.random.default_rng(6)
    cases = []
    for _ in range(100):
        t, i = rng.choice(9, 2, replace=False)
        layouts = [([t], [t], [i]), ([t], [t], None), ([t], [i], [t]), ([t], [t], [t]), ([t, i], [t], [i])]
        for bk, ck, ak in layouts:
            a = None if ak is None else Jet(float(rng.normal()), _grad(rng, ak), float(rng.normal()), 0.0)
            b = Jet(float(rng.normal()), _grad(rng, bk), float(rng.normal()), float(rng.normal()))
            c = Jet(float(rng.normal()), _grad(rng, ck), float(rng.normal()), float(rng.normal()))
            cases.append((a, b, float(rng.normal()), c, float(rng.normal()), bool(rng.integers(2))))
    fast = [Jet.rotated(*x) for x in cases]
    monkeypatch.setattr(jet, "_rotated_one_column", lambda *a: None)
    for x, f in zip(cases, fast):
        s = Jet.rotated(*x)
        assert (f.v, f.vd, f.h) == (s.v, s.vd, s.h)
        assert f.g.dense().tobytes() == s.g.dense().tobytes() and f.g.d.keys() == s.g.d.keys()


WAY = np.radians(np.arange(5.0, 140.0, 5.0))    # driver positions, one way (times +-1)


def _reassembly(system, rows, way: float, knots=None):
    """A continuation one way to 135 degrees (fresh knots unless given), as bytes and why it stopped."""
    r = pose.reassemble(system, rows, way * WAY, knots=knots or pose.Knots())
    return r.deltas.tobytes(), r.q.tobytes(), r.stopped


# a cam (a whole way, no toggle) and a pin in a circular slot (a toggle after 10 degrees: the knot step
# across it halved, and the positions the batched correction misses before it retried)
@pytest.mark.parametrize("which, way", [(CAM, -1.0), (SLOT, 1.0)])
def test_kept_tangents_and_retries_give_the_same_continuation(monkeypatch, which, way):
    """pose._tangent (a Jacobian's tangent kept for the next step, and for a halved one) gives the
    continuation that solving every tangent again gives, in fewer solves; Knots.retry keeps the
    sequential retry of a pose the batched correction missed: the same continuation asked again (the
    same knots) makes no step at all and gets the first one's bytes (whose retries were stepped)."""
    kin = prepare(_systems()[which].mechanism)
    system, rows = kin.system, list(kin.rows)
    assert pose.plan_for(system.positions) is None      # continuation, not the dyads' closed form
    solves, steps = [], []
    real, real_step = pose._velocity, pose._step

    def velocity(*a):
        solves.append(1)
        return real(*a)
    monkeypatch.setattr(pose, "_velocity", velocity)
    knots = pose.Knots()
    kept = _reassembly(system, rows, way, knots)
    n_kept = len(solves)
    assert kept[2] == ("toggle" if which == SLOT else "") and bool(knots.retried) == (which == SLOT)
    monkeypatch.setattr(pose, "_step", lambda *a: steps.append(1) or real_step(*a))
    assert _reassembly(system, rows, way, knots) == kept and not steps
    monkeypatch.setattr(pose, "_tangent", lambda s, r, q, j: velocity(s, r, q, j))
    del solves[:]
    assert _reassembly(system, rows, way) == kept
    assert n_kept < len(solves)
