"""Outside check, a slider driver's words (FORMAT.md section 1, Driver: "a slider driver: slider = F with speed and
accel along its path"; section 5: "A slider driver's JSON driver ... has no angle"): what velpoly says about a
slider driver speaks of the slider's place, in length units, never of a driver angle.

Found by the audit: a slider-crank driven by its slider at a dead centre (exit 3) hinted "choose another driver
angle", which a slider driver has none of (``--angle`` is refused for it); a sweep of a slider driver that stopped
at a toggle said "stopped at a toggle after 18" with no unit (a crank's says "deg").
"""
from __future__ import annotations

import numpy as np
import pytest

import velpoly


def slider_crank(rng, theta: float, units: str) -> dict:
    """A slider-crank (crank r, rod l, in line) driven by its block B along the frame's path, crank at theta."""
    r, l = float(rng.uniform(1, 3)), float(rng.uniform(5, 9))
    turn = float(rng.uniform(-180, 180))   # the whole drawing turned: the path is at this angle
    return {"units": units,
            "points": {"O": [0.0, 0.0], "A": {"from": "O", "length": r, "angle": turn + theta},
                       "B": {"circle": ["A", l], "line": {"through": [0.0, 0.0], "angle": turn},
                             "near": [float(2 * l * np.cos(np.radians(turn))), float(2 * l * np.sin(np.radians(turn)))]}},
            "links": {"1": {"points": ["O"], "frame": True}, "2": {"points": ["O", "A"]}, "3": {"points": ["A", "B"]},
                      "4": {"points": ["B"]}},
            "sliders": [{"block": "4", "guide": "1", "point": "B", "angle": turn}],
            "driver": {"slider": "B", "speed": float(rng.uniform(1, 5)), "accel": 0.0}}


@pytest.mark.parametrize("seed", range(3))
def test_a_slider_driver_at_a_dead_centre_is_told_to_move_the_slider(seed):
    rng = np.random.default_rng(seed)
    with pytest.raises(velpoly.SingularPoseError) as e:
        velpoly.solve(velpoly.load(slider_crank(rng, 0.0, "mm")))
    assert "driver angle" not in e.value.hint and "slider" in e.value.hint, e.value.hint


@pytest.mark.parametrize("units", ["mm", ""])
def test_a_slider_driver_s_sweep_stops_in_length_units(units):
    rng = np.random.default_rng(5)
    m = velpoly.load(slider_crank(rng, 40.0, units))   # the crank reaches the dead centre 0 deg as B moves out
    w = velpoly.sweep(m, np.linspace(0.0, 10.0, 41))
    assert 0 < len(w.angles) < 41
    assert w.stopped.startswith(f"stopped at a toggle after {w.angles[-1]:g}{' ' + units if units else ''}: "), \
        w.stopped
