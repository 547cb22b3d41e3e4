"""Outside check, ``--angle`` beyond a toggle (FORMAT.md section 5, Driver): the driver is carried to
the angle the shorter way round from the reference pose, and a toggle on the way is exit 3 "with the
reachable range". Found by the audit: where the drawn branch's range reaches more than 180 degrees
from the reference pose, the message gave the whole range and the hint said "choose an angle in the
reachable range", yet an angle in that range beyond 180 degrees from the reference pose was refused
(the shorter way round from it crosses the toggle): a non-Grashof four-bar drawn at -90 deg, range
-93.8 to 93.8 deg, refused 92 deg and told the user to choose in -93.8 to 93.8. The hint now gives the
angles ``--angle`` reaches when they are fewer than the range, and each of them solves.
"""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

import velpoly
from velpoly.cli import main

import mechanisms
from test_fuzz import to_toml


def wide_rocker(seed: int) -> tuple[dict, float, float]:
    """A non-Grashof four-bar whose crank rocks through more than 180 deg (limits +-theta_max about the
    frame line, where coupler and rocker come into line), drawn a few degrees inside one limit; returns
    the dict, theta_max and the drawn crank angle (degrees from the frame line O2 -> O4)."""
    rng = np.random.default_rng(seed)
    while True:
        a, b, c, d = float(rng.uniform(5, 7)), float(rng.uniform(4, 6)), float(rng.uniform(6, 8)), 10.0
        s, l = min(a, b, c, d), max(a, b, c, d)
        cos_max = (a * a + d * d - (b + c) ** 2) / (2 * a * d)
        if s + l > sum((a, b, c, d)) - s - l and -0.5 < cos_max < -0.02 and abs(b - c) < d - a:
            break
    theta_max = math.degrees(math.acos(cos_max))
    side = float(rng.choice([-1.0, 1.0]))
    theta = side * (theta_max - float(rng.uniform(2, 8)))
    mech = mechanisms.fourbar(a=a, b=b, c=c, d=d, theta=theta, omega=float(rng.uniform(-10, 10)),
                              branch="left" if side > 0 else "right")
    return mech, theta_max, theta


def choosable(err: str) -> tuple[float, float]:
    """The range of driver angles an exit-3 message tells the user to choose from: the hint's
    ``from A to B`` if it gives one, else the message's ``reachable: A to B``."""
    hint = re.search(r"hint: .*from (-?[\d.e+]+) to (-?[\d.e+]+) deg", err)
    got = hint or re.search(r"reachable: (-?[\d.e+]+) to (-?[\d.e+]+) deg", err)
    return float(got.group(1)), float(got.group(2))


@pytest.mark.parametrize("seed", range(4))
def test_the_angles_an_exit_3_offers_are_angles_that_solve(tmp_path, capsys, seed):
    mech, theta_max, theta = wide_rocker(seed)
    m = velpoly.load(mech)
    ref = velpoly.solve(m).driver_angle
    assert abs(abs(ref) - abs(theta)) < 1e-9          # the frame lies along +x
    far = math.copysign(theta_max - 1.0, -theta)       # on the range, more than 180 deg from the drawn pose
    assert abs(far - theta) > 180
    f = tmp_path / "m.toml"
    f.write_text(to_toml(mech))
    assert main(["solve", str(f), "--angle", repr(far)]) == 3
    err = capsys.readouterr().err
    lo, hi = choosable(err)
    assert not lo - 1e-6 <= far <= hi + 1e-6 and not lo - 1e-6 <= far - math.copysign(360, far) <= hi + 1e-6, err
    for angle in (lo + 1e-3, (lo + hi) / 2, hi - 1e-3):   # what the user is told to choose from solves
        sol = velpoly.solve(m, angle=angle)
        assert abs((sol.driver_angle - angle + 180) % 360 - 180) < 1e-9


def test_a_range_within_180_deg_keeps_its_hint(tmp_path, capsys):
    """A rocker whose whole range is within 180 deg of the drawn pose: the hint is as before."""
    mech = mechanisms.fourbar(a=6, b=5, c=7, d=10, theta=10.0)
    f = tmp_path / "m.toml"
    f.write_text(to_toml(mech))
    assert main(["solve", str(f), "--angle", "150"]) == 3
    err = capsys.readouterr().err.splitlines()
    assert "reachable: " in err[0] and err[1] == "hint: choose an angle in the reachable range"
