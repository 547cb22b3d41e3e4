"""A driver position equal to a continuation knot but for rounding is reached, not taken for a toggle.

The continuation steps its knots 6 degrees at a time (``pose.coarse_step``): knot k sits at k times
``radians(6)``, and a sweep in whole degrees asks ``radians(6 k)``, the same position but for the last
bit (96.00000000000001 deg against the knot's 95.99999999999999). Its step from the knot has no length,
so its chord is Newton's stopping noise (about 1e-12 unit lengths), which ``pose._smooth`` measured
against a tenth of itself plus 1e-12: the step was refused, retried, refused again and called a toggle.
Mechanisms that turn a whole turn by continuation (contacts, slots, sliders on rotating guides,
six-bars without a dyad plan) then stopped at 84, 96, 120 or 144 degrees with "links ... come into
line", their reachable range and sweeps cut there, while ``solve`` at a single angle went on through.

Checked on generated mechanisms (the zoo, seeded) of every continuation kind: four that turn a
whole turn (each stopped at a knot before the fix) and two stopped at true toggles.
"""
from __future__ import annotations

import numpy as np
import pytest

import velpoly
from velpoly import pose
from velpoly.errors import VelpolyError
from velpoly.kinematics import prepare

from mechanisms import ranges_by_dyads_only
from zoo import specimen

# (kind, variant, seed, whole turn?): the first four stopped at a knot before the fix (wheel -96/120,
# slot -84/120, inverted slider-crank +-96, six-bar -84/144 degrees)
SPECIMENS = [("contact", "wheel on ground", 1, True), ("slot", "straight through", 0, True),
             ("inverted slider-crank", "through both crank", 0, True),
             ("six-bar", "stephenson III by its binary", 1, True),
             ("inverted slider-crank", "offset both crank", 0, False),     # -100.56 to 88.66
             ("six-bar", "stephenson III by its binary", 2, False)]        # -53.08 to 22.92


def _reach(kin, degrees) -> float:
    """How far (degrees) a continuation through ``degrees`` gets."""
    r = pose.reassemble(kin.system, list(kin.rows), np.radians(degrees), knots=pose.Knots())
    return float(np.degrees(r.deltas[-1])) if len(r.deltas) else 0.0


def test_whole_degrees_and_half_degrees_stop_alike():
    """A sweep in whole degrees (meeting every knot but for rounding) and one in half-odd degrees
    (meeting none) get equally far each way, within their one-degree spacing; the whole-turn
    mechanisms get through 150 degrees each way, and their reachable range is the whole turn."""
    for kind, variant, seed, whole in SPECIMENS:
        m = velpoly.load(specimen(np.random.default_rng(seed), kind, variant).mech)
        kin = prepare(m)
        assert pose.plan_for(kin.system.positions) is None, (kind, variant)   # by continuation
        for sign in (1.0, -1.0):
            on_knots = _reach(kin, sign * np.arange(1.0, 151.0))
            between = _reach(kin, sign * np.arange(0.5, 150.0))
            assert abs(on_knots - between) <= 1.0, (kind, variant, seed, sign, on_knots, between)
            if whole:
                assert on_knots == sign * 150.0, (kind, variant, seed, on_knots)
        if whole:
            assert velpoly.driver.reachable_range(kin) == (-360.0, 360.0), (kind, variant, seed)


def test_solve_past_a_true_toggle_is_refused_and_a_whole_turn_is_not(monkeypatch):
    """``solve`` at an angle agrees with the range: past a true toggle exit 3 (VelpolyError), on a
    whole-turn mechanism every angle. The refusal is checked, not the range its message names (stubbed:
    ``mechanisms.ranges_by_dyads_only``, 1 CPU s of continuation): that specimen (-100.56 to 88.66 degrees) is
    solved at angle after angle past its toggle both ways, kept knots against fresh ones, in test_newton_speed
    (the range against the former code's is checked there on a contact, a slot and a six-bar)."""
    ranges_by_dyads_only(monkeypatch)
    limited = velpoly.load(specimen(np.random.default_rng(0), "inverted slider-crank", "offset both crank").mech)
    ref = velpoly.solve(limited).to_dict()["driver"]["angle"]
    for d in (89.66, 95.0, -101.56, -110.0):
        with pytest.raises(VelpolyError):
            velpoly.solve(limited, angle=ref + d)
    whole = velpoly.load(specimen(np.random.default_rng(0), "inverted slider-crank", "through both crank").mech)
    ref = velpoly.solve(whole).to_dict()["driver"]["angle"]
    w = velpoly.sweep(whole, ref + np.arange(0.0, 361.0, 12.0))
    assert len(w.angles) == 31

