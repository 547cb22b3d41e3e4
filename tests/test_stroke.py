"""A slider driver's continuation takes the crank's steps: its acceptance test is in the same units.

The continuation (velpoly.pose) predicts a pose q + h q' and corrects it by Newton; the correction is
accepted when it is at most half the predicted step, 0.5 max(|h| / u, |h q'|) in unit lengths and radians
(``pose._drift_bound``; u = 1 for a crank's radians, the size L for a slider's lengths). Main divided a
slider's predicted step h q' by L once more, so the bound was L times too tight: a drawing of size 80
retried nearly every pose of a stroke one by one, halving its step (7-15 CPU s for a page). Checked here on
generated slider-driven mechanisms of every kind that has them (tests/zoo.py), each drawn at three sizes
(powers of two apart, so the drawings are the same in every bit but the exponent):

* the continuation's tangent q' agrees with finite differences of solved poses (1e-6 relative);
* the batched correction accepts the poses near the drawn one alike at every size: the continuation makes
  the same steps and retries at every size, at most one retry (on main, every pose retried at size ~64);
* the poses are main's (its bound, kept here as ``_main_bound``) and the same at every size, to 1e-9 of
  the size.
"""
from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest

import velpoly
from velpoly import pose
from velpoly.kinematics import prepare

from zoo import specimen

# every kind with a slider driver (the six-bar's "slider on ..." variants drive it by a crank mostly)
VARIANTS = [("slider-crank", "curved slider"), ("inverted slider-crank", "curved slider"),
            ("inverted slider-crank", "through both slider"), ("inverted slider-crank", "offset block slider"),
            ("inverted slider-crank", "second-pin slider"), ("inverted slider-crank", "swinging-block slider"),
            ("inverted slider-crank", "rocker slider"), ("six-bar", "floating guide slider"),
            ("six-bar", "quick-return slider")]
SIZES = (1.0 / 64, 1.0, 64.0)    # the drawings' sizes, about (each scaled by a power of two)


def scaled(m, k: float):
    """The mechanism drawn k times larger (lengths, and the driver's speed and acceleration)."""
    pts = {name: (k * float(x), k * float(y)) for name, (x, y) in m.points.items()}
    drv = dataclasses.replace(m.driver, speed=k * m.driver.speed, accel=k * m.driver.accel)
    return dataclasses.replace(m, points=pts, driver=drv)


@functools.cache
def _mechanisms():
    """Each variant's specimen (seeded) at each of SIZES: [(name, [mechanism at each size])]."""
    rng = np.random.default_rng(1127)
    out = []
    for kind, variant in VARIANTS:
        m = velpoly.load(specimen(rng, kind, variant).mech)
        assert m.driver.is_slider
        out.append((f"{kind}: {variant}", [scaled(m, 2.0 ** round(math.log2(s / m.size))) for s in SIZES]))
    return out


def _main_bound(system, h, qd):
    """Main's drift bound (5ffbd6b): a slider's step h q' divided by the size twice."""
    rate = np.maximum(1.0, np.abs(pose._scaled(system, qd)).max(axis=1))
    if system.mechanism.driver.is_slider:
        h = h / system.size
    return 0.5 * np.abs(h) * rate + 1e-9


def _positions(system, rows):
    """Driver positions either way from the drawn pose, none farther than a coarse step, where the
    links turn by at most 0.1 radian at the drawn pose's rates (about a crank's coarse step, 6 degrees):
    inside the stroke, all predicted from the drawn pose (no knot step between)."""
    q0 = np.zeros((1, system.nq))
    rate = float(np.abs(pose._velocity(system, rows, q0)[0, 2::3]).max())
    h = min(pose.coarse_step(system), 0.1 / max(rate, 1e-300))
    return h * np.array([0.25, 0.5, 0.75, 1.0, -0.25, -0.5, -0.75, -1.0])


def _continued(m, monkeypatch, bound=None, pick=slice(None)):
    """(poses, positions, steps, retries, system, rows) of the continuation to _positions (``pick`` of
    them), with fresh knots."""
    kin = prepare(m)
    system, rows = kin.system.positions, list(kin.rows)
    count = {"steps": 0, "retries": 0}
    step, retry = pose._step, pose.Knots.retry

    def counted_step(*a):
        count["steps"] += 1
        return step(*a)

    def counted_retry(self, *a):
        count["retries"] += 1
        return retry(self, *a)
    with monkeypatch.context() as mp:
        mp.setattr(pose, "_step", counted_step)
        mp.setattr(pose.Knots, "retry", counted_retry)
        if bound is not None:
            mp.setattr(pose, "_drift_bound", bound)
        deltas = _positions(system, rows)[pick]
        r = pose.reassemble(kin.system, rows, deltas, knots=pose.Knots())
    assert not r.stopped and len(r.deltas) == len(deltas)
    return r.q, deltas, count["steps"], count["retries"], system, rows


def test_the_tangent_is_the_branch_s():
    """q' = J^-1 e_d at the continued poses against central differences of poses solved at d +- e."""
    for name, ms in _mechanisms():
        m = ms[1]
        kin = prepare(m)
        system, rows = kin.system.positions, list(kin.rows)
        d = np.r_[0.0, _positions(system, rows)[[1, 5]]]
        q = pose.reassemble(kin.system, rows, d, knots=pose.Knots()).q
        qd = pose._velocity(system, rows, q)
        e = 2e-6 * system.size
        ends = [pose._newton(system, rows, q + s * e * qd, d + s * e) for s in (1.0, -1.0)]
        assert ends[0][1].all() and ends[1][1].all(), name
        fd = (ends[0][0] - ends[1][0]) / (2 * e)
        err = np.abs(pose._scaled(system, fd - qd)).max(axis=1)
        assert np.all(err <= 1e-6 * np.abs(pose._scaled(system, qd)).max(axis=1)), (name, err)


def test_every_size_steps_alike_retrying_at_most_one_pose(monkeypatch):
    """The batched correction accepts the poses alike at every size: at most one is retried sequentially
    (the quick-return six-bar's last, turning fast near its stroke's end), with the same steps at every
    size (main retried all eight at size ~64: 24-328 steps), and the poses are the same at every size,
    to 1e-9 of the size."""
    for name, ms in _mechanisms():
        runs = [_continued(m, monkeypatch) for m in ms]
        assert len({r[2:4] for r in runs}) == 1 and runs[0][3] <= 1, (name, [r[2:4] for r in runs])
        ref, k_ref = runs[1][0], ms[1].size
        for (q, _, _, _, system, _), m in zip(runs, ms):
            k = np.ones(system.nq)
            k[0::3] = k[1::3] = m.size / k_ref         # x and y scale with the drawing, angles do not
            err = np.abs(pose._scaled(system, q - ref * k)).max()
            assert err <= 1e-9, (name, m.size, err)


def test_the_poses_are_main_s(monkeypatch):
    """Main's bound reaches the same poses (retrying them at size ~64, halving each step), to 1e-9 of
    the size: one position each (a retried step costs main ~20 Newton corrections)."""
    for name, ms in _mechanisms():
        q, *_ = _continued(ms[2], monkeypatch, pick=[5])
        q_main, _, _, retries, system, _ = _continued(ms[2], monkeypatch, bound=_main_bound, pick=[5])
        assert retries == 1, name
        assert np.abs(pose._scaled(system, q - q_main)).max() <= 1e-9, name


def test_a_failing_step_halves_to_the_same_fraction_of_the_size(monkeypatch):
    """A step that fails at every length (here: the determinant's sign demanded the other way) is halved
    down to 1e-6 of the driver's unit, a slider's size: the same halvings at every size (the old floor
    of 1e-6 length units halved a size-64 drawing's step 10 times, a size-1/64 one's not at all)."""
    for name, ms in _mechanisms():
        calls = []
        for m in ms:
            kin = prepare(m)
            system, rows = kin.system.positions, list(kin.rows)
            q0 = np.zeros((1, system.nq))
            jac = system.evaluate(q0)[1][:, rows]
            count, step = [0], pose._step

            def counted(*a, count=count, step=step):
                count[0] += 1
                return step(*a)
            with monkeypatch.context() as mp:
                mp.setattr(pose, "_step", counted)
                assert pose._step(system, rows, q0, jac, 0.0, 1e-5 * system.size, -pose._orientation(jac)[0]) is None
            calls.append(count[0])
        assert calls == [calls[1]] * len(ms), (name, calls)
