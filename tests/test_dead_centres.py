"""Blocks at their dead centres have an undefined pole; slow links far down a chain keep theirs.

FORMAT.md section 5: two links moving alike at the instant have an undefined pole (position and direction
null). A block at rest on its guide moves alike with it. Generated mechanisms (seeded slider-cranks of any
sizes, offset and path angle; the zoo's inverted slider-cranks, quick-returns and six-bars with a block) are
driven exactly to a dead centre of a block (the driver angle where its slip velocity is zero, by Brent's
method), checked by finite differences to be a simple zero of the slip (it changes sign across the pose:
the block really is at rest there), and then: the JSON pole of block and guide is null/null, every other pole
agrees with the velocity solution and every triple of defined poles is collinear (test_poles.check_poles),
and the poles sheet draws nothing for it while its table says "undefined". (That slow links far down a
chain of stages keep their poles: test_poles.test_every_pin_is_its_pole_exactly_in_long_chains_at_any_speed.)
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

import velpoly
from velpoly.errors import VelpolyError
from velpoly.poles import locate_poles, pole_key

from mechanisms import slider_crank
from test_poles import check_poles
from zoo import specimen


def _slip(m, angle, k):
    return float(velpoly.solve(m, angle=angle).motion.sliders[k]["slip_velocity"][0])


def dead_centre(m, k, start, steps=12):
    """The first driver angle after ``start`` where slider k's slip velocity changes sign (to 1e-12 deg),
    found from a scan of ``steps`` poses over a turn; None where none is reached."""
    grid = start + np.linspace(0.0, 360.0, steps + 1)
    prev = None
    for a in grid:
        try:
            v = _slip(m, a, k)
        except VelpolyError:
            prev = None
            continue
        if prev is not None and prev[1] * v < 0:
            try:
                return brentq(lambda x: _slip(m, x, k), prev[0], a, xtol=1e-13, rtol=1e-15)
            except VelpolyError:
                return None
        prev = (a, v)
    return None


def generated():
    """(label, mechanism dict, slider index): seeded slider-cranks, then the zoo's kinds with a block."""
    rng = np.random.default_rng(20261128)
    for n in range(3):
        r = float(rng.uniform(0.2, 3.0))
        d = slider_crank(r=r, l=float(r * rng.uniform(1.6, 4.0)), e=float(r * rng.uniform(-0.8, 0.8)),
                         theta=float(rng.uniform(0, 360)), omega=float(rng.choice([-1, 1]) * rng.uniform(0.5, 30)),
                         path=float(rng.uniform(0, 180)))
        yield f"slider-crank {n}", d, 0
    for kind, variant, k in (("inverted slider-crank", "offset both crank", 0),
                             ("six-bar", "quick-return crank", 0), ("six-bar", "quick-return crank", 1),
                             ("six-bar", "slider on frame", 0)):
        sp = specimen(np.random.default_rng(len(variant) + 7 * k), kind, variant)
        yield f"{kind} {variant} block {k}", sp.mech, k


CASES = list(generated())


@pytest.mark.parametrize("label, mech, k", CASES, ids=[c[0] for c in CASES])
def test_block_at_its_dead_centre_has_an_undefined_pole(label, mech, k):
    m = velpoly.load(mech)
    start = velpoly.solve(m).driver_angle
    t = dead_centre(m, k, start)
    assert t is not None, label
    # finite differences: the slip changes sign across the pose, linearly (a simple zero: the block is at rest)
    h = 1e-3
    lo, hi = _slip(m, t - h, k), _slip(m, t + h, k)
    assert lo * hi < 0 and abs(lo + hi) <= 0.05 * (abs(lo) + abs(hi)), (label, lo, hi)
    s = velpoly.solve(m, angle=t)
    sl = m.sliders[k]
    key = pole_key(list(m.link_names), sl.block, sl.guide)
    poles = s.to_dict()["poles"]
    assert poles[key] == {"position": None, "direction": None, "how": "undefined", "order": 0}, label
    ps = check_poles(s)   # every other pole where the two links' velocities agree; Kennedy's collinearity
    undefined = [p.key for p in ps.poles.values() if p.undefined]   # (a quick-return's ram stops with its lever,
    assert key in undefined, label                                   # which stops its rod: 3 pairs move alike)
    # a few degrees away the block slides: its pole is the slider's, at infinity normal to its path
    away = velpoly.solve(m, angle=t + 3.0).to_dict()["poles"][key]
    assert away["how"] in ("slider", "circular path"), label


def test_the_poles_sheet_draws_nothing_for_an_undefined_pole_and_its_table_says_so():
    import matplotlib.pyplot as plt
    from velpoly.render.kennedy import draw_poles
    from velpoly.render.table import results_table
    # an exact dead centre by construction: crank and rod in line with the path
    s = velpoly.solve(velpoly.load(slider_crank(r=2.0, l=7.0, e=0.0, theta=30.0, path=30.0)))
    ps = locate_poles(s)
    fig, ax = plt.subplots()
    try:
        art = draw_poles(s, ax)
        gids = {a.get_gid() for a in fig.findobj()} - {None}
        labelled = set(art.labels)
    finally:
        plt.close(fig)
    assert "pole-1-4" not in gids and "label-pole-1-4" not in gids and "1-4" not in labelled, (gids, labelled)
    shown = {p.key for p in ps.poles.values() if not p.undefined and p.position is not None}
    assert shown <= labelled, labelled   # every other finite pole is marked and labelled
    table = results_table(s, "poles", poleset=ps)
    rows = [r for r in table.rows if "P" in r[0] and "14" in r[0]]
    assert rows and rows[0][1:3] == ("undefined", "undefined"), rows   # graphical and analytic columns
