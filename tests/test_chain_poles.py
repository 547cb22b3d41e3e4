"""Long chains' fast paths against the general ones (issue 20), on generated mechanisms.

- The poles: the construction on arrays (what mechanisms of more than ``velpoly.poles._SMALL`` links
  use, no lines stored) gives the poles of the general Kennedy search on floats: the same ``how`` and
  ``order`` of discovery, the same directions, positions to 1e-9 of the mechanism's size; a pin's
  pole is the pin exactly, found by no search (order 0).
- The JSON: ``poles_section`` without a pole set built (the construction without its lines) is the
  section read from the PoleSet, to the bit.
- The solve: ``select_rows`` in blocks keeps the rows a Gram-Schmidt one row at a time keeps, on
  Jacobians with dependent rows among them.

Timings are not tested here: ``benchmarks/bench_poles.py`` measures them.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import velpoly
from velpoly.constraints import build_system
from velpoly.errors import VelpolyError
from velpoly.pose import select_rows
from velpoly.poles import locate_poles, poles_section
from chains import ladder, parallel_chain, stage_chain
from test_poles import both_forms, check_order, check_poles
from zoo import zoo

# on test_zoo's worker: the specimens of its seed are made once there (tests/zoo.py)
pytestmark = pytest.mark.xdist_group("zoo")


def _solved(dicts):
    out = []
    for d in dicts:
        try:
            out.append(velpoly.solve(velpoly.load(d)))
        except VelpolyError:
            continue
    return out


# (n, seed) of each long chain's generator: the chains are made by the fixture, not at the module's import,
# which every xdist worker repeats in its collection (0.04 CPU s)
CHAINS = ((parallel_chain, ((10, 1), (16, 2), (26, 1))), (ladder, ((9, 4), (13, 5), (17, 6))), (stage_chain, ((5, 3),)))


@pytest.fixture(scope="module")
def chains():
    return _solved([make(n, seed) for make, args in CHAINS for n, seed in args])


@pytest.fixture(scope="module")
def specimens():
    every = zoo(20261125, 57)   # every kind of the zoo once; half of them, and all the contacts (gears)
    return [sp.drawn for k, sp in enumerate(every) if k % 2 == 0 or sp.kind.startswith("contact")]   # (solved as made)


def test_fast_pole_path_is_the_general_kennedy_search(chains, specimens):
    """Arrays (fast) against floats (general): every pole with the same how, order and direction,
    positions to 1e-9 relative; pins exactly their pins, order 0."""
    compared = 0
    for s in chains + specimens:
        general, fast = both_forms(s)
        check_order(fast)
        assert fast.order == general.order
        size = s.mechanism.size
        for key, p in general.poles.items():
            q = fast.poles[key]
            assert (q.how, q.order, q.direction) == (p.how, p.order, p.direction), key
            assert (q.position is None) == (p.position is None), key
            if p.position is not None:
                assert np.hypot(*(q.position - p.position)) <= 1e-9 * size, key
            compared += 1
        for pin in s.mechanism.pins:
            q = fast.pole(*pin.links)
            assert q.how == "pin" and q.order == 0
            assert np.array_equal(q.position, s.place(pin.links[0], pin.point))
    assert len(chains) == sum(len(args) for _, args in CHAINS) and len(specimens) >= 20
    assert compared > 800


def test_chain_poles_are_complete_and_consistent(chains):
    """The long chains' pole sets (arrays beyond _SMALL links) pass every check of the pole tests."""
    for s in chains:
        check_poles(s, locate_poles(s, cached=False))


def test_json_section_without_lines_is_the_pole_sets(chains, specimens):
    """solve --json's poles section computed lean equals the one read from the full PoleSet."""
    for s in chains + specimens:
        lean = json.dumps(poles_section(s))   # no pole set cached yet for this solution
        locate_poles(s)
        assert json.dumps(poles_section(s)) == lean


def _rows_one_by_one(jac, tol):
    """Modified Gram-Schmidt one row at a time (what select_rows did before it worked in blocks)."""
    keep, basis = [], []
    for i, row in enumerate(jac):
        r = row.copy()
        for b in basis:
            r -= np.dot(r, b) * b
        nr = np.linalg.norm(r)
        if nr > tol * max(1.0, np.linalg.norm(row)):
            basis.append(r / nr)
            keep.append(i)
    return keep


def test_select_rows_in_blocks_keeps_the_same_rows(chains, specimens):
    """On each mechanism's Jacobian at the reference pose (tol 1e-10) and at a random configuration
    (1e-8), as kinematics.prepare takes them; some of them have dependent rows."""
    dependent = 0
    rng = np.random.default_rng(5)
    for s in chains + specimens:
        system = build_system(s.mechanism)
        m_eq = len(system.equations)
        _, j0, _ = system.evaluate(np.zeros((1, system.nq)), driver=False)
        _, jg, _ = system.evaluate(rng.uniform(-1, 1, (1, system.nq)))
        for a, tol in ((system.scale_matrix(j0[0], driver=False), 1e-10),
                       (system.scale_matrix(jg[0][:m_eq], driver=False), 1e-8)):
            keep = select_rows(system, a, tol)
            assert keep == _rows_one_by_one(a, tol)
            dependent += len(keep) < len(a)
    assert dependent >= 2   # the gear pairs' contacts among the specimens
    # rows that depend on rows of earlier blocks of 32, inserted into a long chain's Jacobian: each is
    # dropped (and nothing else), one a little off (1e-6) is kept
    s = next(s for s in chains if len(s.mechanism.links) == 26)
    a = s.kinematics.system.scale_matrix(s.kinematics.system.evaluate(s.q[None, :], driver=False)[1][0],
                                         driver=False)
    rows = list(a)
    for at, off in ((40, 0.0), (50, 1e-6), (66, 1e-14), (70, 0.0)):
        combo = rng.normal(size=at) @ np.array(rows[:at])
        rows.insert(at, combo + off * np.linalg.norm(combo) * rng.normal(size=a.shape[1]))
    b = np.array(rows)
    keep = select_rows(None, b, 1e-10)
    assert len(b) > 70 and keep == _rows_one_by_one(b, 1e-10)
    assert sorted(set(range(len(b))) - set(keep)) == [40, 66, 70]
