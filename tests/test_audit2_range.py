"""Outside check, a refused ``--angle`` (FORMAT.md section 5, Driver; section 1, Pins in slots): the
exit-3 message names the range of driver angles the driver reaches. Found by the audit: the range was
the last poses the continuation reached before each toggle (on a 0.01 deg grid from the reference
pose) printed to six significant digits, so angles just beyond it were accepted: a slotted lever
refused with "-53.66 to 219.99" solved 220; a generated non-Grashof rocker with its toggle at 98.7033
deg printed "to 98.6981" and solved 98.7; a parallelogram printed "0.01 to 179.99" and solved 179.999.
Now each end is rounded outward to 0.01 deg (a slot's end, known to 1e-6 deg, to its own value) and,
where the refused angle lies that near the end, narrowed and printed to the digits that leave the
refused angle outside: every accepted angle lies in the printed range, the refused one beyond it.

The true ends are closed forms: a four-bar's crank limit (coupler and rocker in line) and the crank
angle where the pin of a slotted lever reaches an end of its slot (test_slot_ends.exit_angle).
"""
from __future__ import annotations

import re

import pytest

import velpoly

import mechanisms
from test_audit_angles import wide_rocker
from test_slot_ends import drive, exit_angle, generated


def printed(err: str) -> tuple[float, float]:
    got = re.search(r"(?:reachable:|in the slot from) (-?[\d.]+) to (-?[\d.]+) deg", err)
    return float(got.group(1)), float(got.group(2))


def refused(m, angle) -> str:
    with pytest.raises(velpoly.PoseError) as e:
        velpoly.solve(m, angle=angle)
    return str(e.value)


def ends():
    """(label, mechanism, true end as an absolute angle, sense) for generated rockers and slotted
    levers whose end lies less than 179 deg from the drawn pose (``--angle`` goes the shorter way)."""
    for seed in range(4):
        mech, theta_max, theta = wide_rocker(seed)
        sense = 1.0 if theta > 0 else -1.0
        yield f"rocker {seed}", velpoly.load(mech), sense * theta_max, sense
    for kind, a, e, psi, theta, r_lo, r_hi, sense, swap in generated(5)[:6]:
        want = exit_angle(a, e, psi, theta, sense, r_lo, r_hi, span=178.0)
        if want is not None:
            m = velpoly.load(drive(a, e, psi, theta, r_lo, r_hi, omega=3.0 * sense, swap=swap))
            yield f"{kind} a={a} e={e} psi={psi} theta={theta}", m, want, sense


def test_the_printed_range_holds_every_accepted_angle_and_not_the_refused_one():
    checked = 0
    for label, m, end, sense in ends():
        ref = velpoly.solve(m).driver_angle
        wrapped = lambda a: (a - ref + 180.0) % 360.0 - 180.0 + ref      # noqa: E731 as the message prints it
        for beyond in (0.5, 0.004, 2e-5):
            target = float(end + sense * beyond)
            err = refused(m, target)
            lo, hi = printed(err)
            edge = wrapped(end)
            assert lo - 1e-6 <= edge <= hi + 1e-6, (label, beyond, err)      # every accepted angle
            assert not lo <= wrapped(target) <= hi, (label, beyond, err)      # and not the refused one
            assert f"driver angle {target!r} deg" in err or f"driver angle {target:g} deg" in err, err
        far = printed(refused(m, float(end + sense * 0.5)))[sense > 0]   # the printed end, refused itself
        if wrapped(far) != wrapped(end):
            lo, hi = printed(refused(m, far))
            assert not lo <= wrapped(far) <= hi and lo - 1e-6 <= wrapped(end) <= hi + 1e-6, (label, far, lo, hi)
        checked += 1
    assert checked >= 6


def test_the_command_line_names_the_range_holding_the_angles_it_accepts(tmp_path):
    mech, theta_max, theta = wide_rocker(0)
    sense = 1.0 if theta > 0 else -1.0
    f = tmp_path / "rocker.toml"
    from test_fuzz import to_toml
    f.write_text(to_toml(mech))
    r = mechanisms.in_process(["solve", f, "--angle", repr(sense * (theta_max + 0.003))])
    assert r.returncode == 3, r.stderr
    lo, hi = printed(r.stderr)
    assert lo <= -theta_max and theta_max <= hi, r.stderr
    inside = sense * (theta_max - 1e-4)
    assert mechanisms.in_process(["solve", f, "--angle", repr(inside)]).returncode == 0
