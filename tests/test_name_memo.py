"""The names kept per mechanism (velpoly.polygons ``_Shape``'s ``_named``: each place's textbook name and a
centripetal term's labels; velpoly.names ``lower_name``'s cache; issue 20).

The polygons' every label, ``of`` and caption must be those of names made afresh at every pose: poses of one
mechanism drawn one after another (the names kept) against each pose with nothing kept; a mechanism whose
auxiliary point is named at the pose (the pose's names come first, nothing of them kept); and two
mechanisms alike but for their names, drawn in turn (each keeps its own).
"""
from __future__ import annotations

import copy
import json

import numpy as np
import pytest

import velpoly
from velpoly import names, polygons
from velpoly.solution import driver_reference_angle

import zoo
from test_plan_cache import EXAMPLES, TRIAD, ZOO, _angles, _outputs


def _afresh(m, angle) -> str:
    """The pose with nothing kept: no shape (names), no plan, no names' cache."""
    polygons._SHAPES.clear()
    polygons._PLANS.clear()
    names.lower_name.cache_clear()
    return _outputs(m, angle)


@pytest.fixture(autouse=True)
def _empty(monkeypatch):
    monkeypatch.setattr(polygons, "_SHAPES", {})
    monkeypatch.setattr(polygons, "_PLANS", {})
    from velpoly import solution
    monkeypatch.setattr(solution, "reachable_range", lambda kin: (0.0, 0.0))   # as test_plan_cache
    monkeypatch.setattr(solution, "reachable_words", lambda kin, ref, refused=None: "0 to 0")   # its words too


def _alike(m, angles):
    kept = [_outputs(m, a) for a in angles]
    for a, k in zip(angles, kept):
        assert k == _afresh(m, a), f"{m.title or m.source}: driver angle {a}: kept names differ from fresh ones"
    return kept


@pytest.mark.parametrize("sp", ZOO[::2], ids=[f"{i}-{s.kind}" for i, s in enumerate(ZOO[::2])])
def test_zoo_names_kept_are_names_made_afresh(sp):
    m = velpoly.load(sp.mech)
    _alike(m, [None] if sp.offsets == (None,) else _angles(m, 3, 20.0))


def test_an_auxiliary_point_named_at_the_pose():
    """The triad's link 6 on three binaries: an auxiliary point S6 is named at the pose (``geo.names``),
    whose names are never kept; its poses in turn, and interleaved with another mechanism's."""
    m = velpoly.load(TRIAD)
    ref = driver_reference_angle(m)
    kept = _alike(m, [ref + k for k in range(-30, 12, 6)])
    assert all(json.dumps("S₆@6") in k for k in kept)   # the auxiliary point S₆ at every pose
    other = velpoly.load(EXAMPLES[[p.stem for p in EXAMPLES].index("problem_1_4_4_sixbar")])
    for a in (ref - 12, ref):
        assert _outputs(other, None) == _afresh(other, None)
        assert _outputs(m, a) == _afresh(m, a)


def test_two_mechanisms_alike_but_for_their_names():
    """A generated six-bar and the same with its points renamed: drawn in turn, each keeps its own names."""
    spec = zoo.specimen(np.random.default_rng(5), "six-bar").mech
    table = {p: f"{p}x" for p in spec["points"]}

    def renamed(x):   # every point name, as a key or a value, with an x after it
        if isinstance(x, str):
            return table.get(x, x)
        if isinstance(x, list):
            return [renamed(v) for v in x]
        if isinstance(x, dict):
            return {table.get(k, k): renamed(v) for k, v in x.items()}
        return x
    m1, m2 = velpoly.load(copy.deepcopy(spec)), velpoly.load(renamed(spec))
    out = [_outputs(m, None) for m in (m1, m2, m1, m2)]
    assert out[0] == out[2] and out[1] == out[3] and out[0] != out[1]
    assert out[0] == _afresh(m1, None) and out[1] == _afresh(m2, None)
