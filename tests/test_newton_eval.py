"""One pose's equations with sparse gradients (``velpoly.jet.Grad``, fused points) give the bits of
the dense arrays they replace: residuals, Jacobians and h-terms, and so every Newton correction and
continuation step made with them.

The reference is the same evaluation with ``Frame(..., dense=True)`` (the jets' gradients numpy
arrays (nq,), as before the sparse ones). Floats are compared by their bytes: signs of zeros included
(NaNs where the other has NaN). The mechanisms are generated (seeded): zoo specimens of every kind with contacts
(rolling, slipping, prescribed slip, cams, gears), slots (straight, circular), sliders (inverted,
curved, on a coupler) and the arrow generators' cams, slots and blocks; at the drawn pose (exact
zeros: sin 0), at random poses, and at poses with an infinite or NaN coordinate.
"""
from __future__ import annotations

import functools

import numpy as np
import pytest

import velpoly
from velpoly import constraints, pose
from velpoly.errors import InputError
from velpoly.kinematics import prepare

from mechanisms import ARROW_GENERATORS
from zoo import specimen

ZOO = [("contact", v) for v in ("wheel on ground", "wheel slipping on ground", "gears", "internal gears",
                                "cam flat follower", "cam roller follower", "cam curved follower",
                                "cam oscillating follower")] \
    + [("slot", v) for v in ("straight through", "straight offset", "circular", "circular six-bar")] \
    + [("slider-crank", "curved slider"), ("inverted slider-crank", "through both crank"),
       ("inverted slider-crank", "curved crank"), ("six-bar", "slider on coupler point"),
       ("six-bar", "floating guide slider"), ("eight-bar", "watt II + dyad")]


def _dense(monkeypatch):
    """The former evaluation (the reference): System.evaluate's one-pose frames dense, and every
    Newton batched."""
    monkeypatch.setattr(constraints, "Frame", functools.partial(constraints.Frame, dense=True))
    monkeypatch.setattr(pose, "_newton", pose._newton_batch)       # as it was for one pose too


def _same(a, b) -> bool:
    """Equal bytes, but for the sign of a NaN (x86 gives an operation on two NaNs the first one's,
    and numpy's vector loops may take them in the other order: a NaN pose is a failed one either way)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype == float:
        nan = np.isnan(a)
        if not np.array_equal(nan, np.isnan(b)):
            return False
        a, b = np.where(nan, 0.0, a), np.where(nan, 0.0, b)
    return a.tobytes() == b.tobytes()


def _systems():
    rng = np.random.default_rng(19)
    for kind, variant in ZOO:
        yield f"{kind}: {variant}", prepare(velpoly.load(specimen(rng, kind, variant).mech))
    for name, gen in ARROW_GENERATORS.items():
        yield name, prepare(velpoly.load(gen(3, 50.0)))


# the tests reading _all() on one worker: its generated systems are made once (0.26 CPU s a worker)
ON_ALL = pytest.mark.xdist_group("newton-eval-systems")


@functools.cache
def _all():
    return list(_systems())


def _poses(system, rng):
    nq = system.nq
    out = [np.zeros(nq)]
    for scale in (0.05, 0.5, 3.0):
        q = rng.normal(size=nq) * scale
        q[0::3] *= system.size
        q[1::3] *= system.size
        out.append(q)
    for bad, col in ((np.inf, 0), (-np.inf, 1), (np.nan, 2)):    # an angle is never infinite (math.cos)
        q = out[1].copy()
        q[3 * rng.integers(nq // 3) + col] = bad
        out.append(q)
    return out


def _evaluations(system, rows, qs, qd, monkeypatch, dense):
    """Every one-pose evaluation (evaluate with and without rates, the values alone, the h-terms)
    and a Newton correction from each finite pose, with the dense or the sparse gradients."""
    if dense:
        _dense(monkeypatch)
    out = []
    try:
        with np.errstate(all="ignore"):
            for i, q in enumerate(qs):
                q1 = q[None, :]
                out += list(system.evaluate(q1)) + list(system.evaluate(q1, qd, driver=False))
                out += [system.residual(q1), system.second_terms(q1, qd)]
                if np.isfinite(q).all():
                    for target in (q[2] * 0.5, q[2] + 0.3, 3.0)[:3 if i == 1 else 1]:   # near, farther, far
                        out += list(pose._newton(system, rows, q1, np.array([target])))
    finally:
        monkeypatch.undo()
    return out


@ON_ALL
def test_sparse_gradients_give_the_dense_bits_on_generated_mechanisms(monkeypatch):
    rng = np.random.default_rng(2026)
    kinds = set()
    for name, kin in _all():
        system = kin.system
        try:
            system = system.positions
        except InputError:          # a contact by its normal: velocities only (still evaluated)
            pass
        kinds |= {e.label.split()[0] for e in system.equations}
        qs = _poses(system, rng)
        qd = rng.normal(size=(1, system.nq))
        new = _evaluations(system, list(kin.rows), qs, qd, monkeypatch, dense=False)
        old = _evaluations(system, list(kin.rows), qs, qd, monkeypatch, dense=True)
        assert len(new) == len(old)
        for k, (a, b) in enumerate(zip(new, old)):
            assert _same(a, b), (name, k, a, b)
    # every kind of equation was among them
    assert {"pin", "slider", "slot", "rolling", "sliding"} <= kinds, kinds


@pytest.mark.parametrize("kind, variant, seed", [("contact", "wheel on ground", 1), ("slot", "circular", 2),
                                                 ("six-bar", "slider on coupler point", 3)])
def test_continuation_steps_are_the_dense_ones(monkeypatch, kind, variant, seed):
    """A reassembly by continuation past toggles (every knot step, halving and failing Newton)
    gives the same poses with sparse and dense gradients."""
    kin = prepare(velpoly.load(specimen(np.random.default_rng(seed), kind, variant).mech))
    deltas = np.radians(np.arange(2.0, 362.0, 6.0))
    made = pose._continue(kin.system.positions, list(kin.rows), np.concatenate([deltas, -deltas]), None)[0]
    _dense(monkeypatch)
    ref = pose._continue(kin.system.positions, list(kin.rows), np.concatenate([deltas, -deltas]), None)[0]
    monkeypatch.undo()
    assert _same(made.deltas, ref.deltas) and _same(made.q, ref.q) and made.stopped == ref.stopped


def test_grad_holds_the_dense_columns():
    """Grad's arithmetic column by column, with the untouched columns' value carried (a -0.0 from a
    negative factor, NaN from an infinite one)."""
    from velpoly.jet import Grad
    a, b = Grad({1: 2.0}, 0.0, 4), Grad({2: -3.0}, 0.0, 4)
    da, db = a.dense(), b.dense()
    with np.errstate(all="ignore"):
        pairs = [(a + b, da + db), (a - b, da - db), (-a, -da), (a * -2.0, da * -2.0), (-2.0 * b, -2.0 * db),
                 (a * np.inf, da * np.inf), (b / np.float64(0.0), db / np.float64(0.0)),
                 ((a * -1.0) + (b * -1.0), (da * -1.0) + (db * -1.0))]
    for x, y in pairs:
        assert _same(x.dense(), y)


@ON_ALL
def test_scaled_divides_the_lengths_alone():
    """pose._scaled (one division by the column scales L, L, 1) gives the lengths' columns divided
    by L and the angles' as they are, to the byte (-0.0, infinities)."""
    system = _all()[0][1].system
    dq = np.random.default_rng(3).normal(size=(5, system.nq)) * 10.0
    dq[0, :3] = [-0.0, np.inf, -np.inf]
    dq[1, 2::3] = -0.0
    old = dq.copy()
    old[:, 0::3] /= system.size
    old[:, 1::3] /= system.size
    assert _same(pose._scaled(system, dq), old) and not np.shares_memory(pose._scaled(system, dq), dq)
