"""Outside check, ``[drawing]`` scales (docs/figures.md; FORMAT.md section 1, Drawing options: "scales"): a scale is
length units (units/s, units/s^2) per cm of paper. One that draws its panel absurdly small or large (a scale
written in the wrong unit) is an input error naming the key, with a scale that fits; one that merely draws the
mechanism larger than its panel draws in the time any sheet takes.

Found by the audit: on a 5 m four-bar, ``scale = 0.02`` (the mechanism 270 cm across) ran for minutes (killed at
200 s) and ``scale = 1e-6`` ran out of memory: the link numbers' search for a free place laid a grid of places
0.08 cm apart over the whole of the link's body, off the page as it was; ``scale = 1e300`` or
``velocity_scale = 1e300`` crashed (exit 1, OverflowError in the layout), ``scale = 1e-300`` hung with
matplotlib's warnings, ``scale = 1e20`` drew an empty panel.
"""
from __future__ import annotations

import numpy as np
import pytest

import velpoly
from velpoly.render.displacement import _grid_in
from velpoly.render.sheet import render

import mechanisms


@pytest.mark.parametrize("key, factor", [("scale", 1e-30), ("scale", 1e30), ("velocity_scale", 1e300),
                                         ("acceleration_scale", 1e-30)])
def test_an_absurd_scale_is_an_input_error_naming_it(key, factor):
    rng = np.random.default_rng(len(key))
    size = float(rng.uniform(0.01, 100))
    d = mechanisms.fourbar(a=2 * size, b=5 * size, c=4 * size, d=5 * size, theta=float(rng.uniform(20, 160)))
    d["drawing"] = {key: size * factor}
    with pytest.raises(velpoly.InputError) as e:
        render(velpoly.solve(velpoly.load(d)), "full")
    assert e.value.where == f"drawing.{key}" and "cm across" in e.value.what, e.value


def test_the_grid_of_free_places_keeps_to_the_view():
    rng = np.random.default_rng(2)
    for _ in range(300):   # the same numbers as np.arange, all those whose ring may lie in the view
        a0, step, r = rng.uniform(-10, 10), rng.uniform(0.01, 0.5), rng.uniform(0, 1)
        a1, v0 = a0 + rng.uniform(0, 20), rng.uniform(-15, 10)
        v1 = v0 + rng.uniform(0, 20)
        full, grid = np.arange(a0, a1, step), _grid_in(a0, a1, step, v0, v1, r)
        need = full[(full - r >= v0) & (full + r <= v1)]
        assert set(need) <= set(grid) <= set(full)
        assert np.all(np.diff(grid) > 0)
    assert len(_grid_in(0.0, 1e6, 0.08, 10.0, 30.0, 0.2)) < 260   # a body a million times the view: the view's
