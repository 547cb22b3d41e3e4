"""A polygon's steps write their equation and caption when first read (``Step._written``, issue 20):
the texts read late, after everything else the polygons, the poles and the hand-drafting estimate do
to the pose's geometry, are the texts written as each step was drawn (``_assemble(..., eager=True)``,
what the code did before), on every variant of the seeded zoo, on generated joints with Coriolis
terms, slots and contacts, an auxiliary point (a triad) and every example."""
from __future__ import annotations

import copy
import dataclasses
import functools
import pickle
from pathlib import Path

import numpy as np
import pytest

import velpoly
from velpoly import polygons
from velpoly.polygons import Step, acceleration_polygon, hand_drafting, velocity_polygon
from velpoly.poles import locate_poles

import mechanisms
import zoo
from test_plan_cache import TRIAD, _plain

EXAMPLES = sorted((Path(velpoly.__file__).parent / "examples").glob("*.toml"))
VARIANTS = zoo.variants()


@functools.cache
def zoo_specimens() -> list:
    """A specimen of every (kind, variant) of the zoo, in ``VARIANTS``' order: made when a test first needs them,
    not at collection, which every xdist worker repeats (half a second)."""
    rng = np.random.default_rng(20261127)
    return [zoo.specimen(rng, kind, variant).mech for kind, variant in VARIANTS]


GENERATED = ([mechanisms.block_on_driving_guide(2), mechanisms.pin_in_slot(2, driver="slot", circular=True),
              mechanisms.sliding_cam(2, follower="flat"), mechanisms.sliding_on_frame(2, surface="curved"), TRIAD])
# a number: the zoo's specimen of that variant (made by one worker: their xdist group)
CASES = [pytest.param(i, marks=pytest.mark.xdist_group("lazy-steps-zoo"), id=f"{kind}-{variant}")
         for i, (kind, variant) in enumerate(VARIANTS)] + GENERATED + EXAMPLES


def _eager(sol) -> list:
    """Both polygons' steps with their texts written as each step is drawn, on a construction of their own."""
    c = polygons._Construction(sol)
    vel, run = polygons._assemble(c, sol, "velocity", None, eager=True)
    out = [vel.steps]
    if sol.has_accelerations:
        out.append(polygons._assemble(c, sol, "acceleration", run, eager=True)[0].steps)
    return out


def _texts(steps) -> list:
    return [(s.equation, s.caption) for s in steps]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.stem if isinstance(c, Path) else None)
def test_texts_read_late_are_those_written_at_once(case):
    if isinstance(case, int):
        case = zoo_specimens()[case]
    try:
        sol = velpoly.solve(velpoly.load(case))
        lazy = [velocity_polygon(sol).steps] + ([acceleration_polygon(sol).steps] if sol.has_accelerations else [])
    except velpoly.VelpolyError:   # a pose with no construction: nothing to write
        pytest.skip("no construction at this pose")
    assert all("equation" not in s.__dict__ and "caption" not in s.__dict__ for steps in lazy for s in steps)
    locate_poles(sol)
    hand_drafting(sol, samples=8)    # more replays of the plan on the same geometry, then the texts
    eager = _eager(sol)
    for got, want in zip(lazy[::-1], eager[::-1]):   # the acceleration's first: read in another order
        assert _texts(got) == _texts(want)
        assert _plain(got) == _plain(want)   # every other field too, every float by its repr
        assert all(s.equation and s.caption for s in got)


def test_a_lazy_step_copies_pickles_and_replaces_with_its_texts():
    sol = velpoly.solve(velpoly.load(EXAMPLES[[p.stem for p in EXAMPLES].index("problem_1_4_4_sixbar")]))
    step = velocity_polygon(sol).steps[2]
    fresh = velocity_polygon(velpoly.solve(sol.mechanism)).steps[2]   # not read yet
    for other in (copy.copy(fresh), copy.deepcopy(fresh), pickle.loads(pickle.dumps(fresh))):
        assert "_texts" not in other.__dict__ and _texts([other]) == _texts([step])
    moved = dataclasses.replace(step, caption="other")
    assert moved.caption == "other" and moved.equation == step.equation
    plain = Step(1, "driver", "V_B = omega_1 x R_BA", (), ("B",), (), {}, 1.0)   # the public constructor
    assert plain.caption == "" and plain.equation == "V_B = omega_1 x R_BA"
    with pytest.raises(AttributeError):
        step.nothing
    with pytest.raises(dataclasses.FrozenInstanceError):
        step.caption = "x"
