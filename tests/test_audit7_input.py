"""Outside check, audit 7: input at the edges, refused in one line naming the file and entry (exit 2), or read.

1. A driver rate whose speeds would fall below 1e-100 or whose acceleration terms (omega^2, alpha, a slider's
   accel) below 1e-200 is too small, as a rate below any float is (``omega = 1e-200`` was read: omega^2
   underflows to 0).
2. ``--angle abc`` said "invalid _degrees value" (the parsing function's name): now what it expects.
3. One rule for every printed magnitude (FORMAT.md section 1): a negative bare magnitude is the reversed
   vector's, a ``speed``'s too (``speed = { B = -5 }`` was exit 2 while ``velocity = { B = -5 }`` was read).
4. ``velpoly html m.html`` (no -o: the default output is the input) said "-o: the output is the input file";
   ``draw -o /dev/null`` said "unknown figure type '(none)'".
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import velpoly
MIN_SPEED, MIN_ACCEL = 1e-100, 1e-200   # the floors of the driver's speeds and acceleration terms
from velpoly.reference import compare

from mechanisms import in_process
from test_audit5_input import slider_driven
from test_fuzz import to_toml
from zoo import each


def _refused(mech: dict, key: str, value: float, match: str = "too small") -> None:
    with pytest.raises(velpoly.InputError, match=match) as e:
        velpoly.load({**mech, "driver": {**mech["driver"], key: value}})
    assert e.value.where == f"driver.{key}", str(e.value)


def test_driver_rates_too_small_for_the_arithmetic_are_refused(tmp_path):
    mechs = [sp.mech for sp in each(2026, 6)] + slider_driven(3)
    checked = 0
    for mech in mechs:
        size = velpoly.load(mech).size
        if "slider" in mech["driver"]:
            for key, floor in (("speed", MIN_SPEED), ("accel", MIN_ACCEL)):
                for v in (floor / 3, -floor / 3, 1e-300):
                    _refused(mech, key, v)
                    checked += 1
                ok = velpoly.load({**mech, "driver": {**mech["driver"], key: 3 * floor}})
                assert getattr(ok.driver, key) == 3 * floor
            continue
        slow = MIN_SPEED / size / 3          # its speeds under 1e-100
        squared = math.sqrt(MIN_ACCEL / size / 3)   # omega^2 x size under 1e-200 (its speeds may be above)
        for v in (slow, -slow, squared, 1e-200, -1e-200):
            _refused(mech, "omega", v)
            checked += 1
        _refused(mech, "alpha", MIN_ACCEL / size / 3)
        checked += 1
        # just inside: read, and its velocities and accelerations come out nonzero and finite
        omega = 3 * max(MIN_SPEED / size, math.sqrt(MIN_ACCEL / size))
        sol = velpoly.solve(velpoly.load({**mech, "driver": {**mech["driver"], "omega": omega, "alpha": 0.0}}))
        speeds = [float(np.hypot(*v)) for v in sol.velocity.values()]
        accels = [float(np.hypot(*a)) for a in sol.acceleration.values() if a is not None]
        assert max(speeds) > 0 and max(accels) > 0 and all(map(math.isfinite, speeds + accels))
    assert checked == 6 * 6 + 3 * 6
    # as the command line says it
    f = tmp_path / "m.toml"
    f.write_text(to_toml({**mechs[0], "driver": {**mechs[0]["driver"], "omega": 1e-200}}))
    r = in_process(["solve", f])
    lines = r.stderr.splitlines()
    assert r.returncode == 2 and len(lines) == 2 and lines[0].startswith(f"error: {f}: driver.omega") \
        and "1e-200 rad/s is too small" in lines[0], r.stderr


@pytest.mark.parametrize("args", [["solve", "--angle", "abc"], ["draw", "--angle", "1.5.2"],
                                  ["solve", "--angle="], ["sweep", "--step", "x"], ["animate", "--step", "2deg"]])
def test_a_bad_number_of_degrees_says_what_is_expected(args, tmp_path, capsys):
    f = tmp_path / "m.toml"
    f.write_text(to_toml(next(each(2026, 1)).mech))
    from velpoly.cli import main
    with pytest.raises(SystemExit) as e:   # argparse's own error: it exits
        main([args[0], str(f), *args[1:]] + (["-o", str(tmp_path / "a.gif")] if args[0] == "animate" else []))
    r, err = e.value.code, capsys.readouterr().err
    last = err.splitlines()[-1]
    option, text = args[1].split("=") if "=" in args[1] else (args[1], args[2])
    assert r == 2 and last == f"velpoly {args[0]}: error: argument {option}: expected a number of degrees " \
                              f"(plain decimal digits, as 30 or -2.5), got {text!r}", err
    assert "_degrees" not in err and "Traceback" not in err


def test_a_negative_speed_is_read_as_a_negative_bare_magnitude_is():
    checked = 0
    for sp in each(2026, 7):
        sol = sp.drawn
        moving = [k for k, v in sol.velocity.items() if "@" not in k and np.hypot(*v) > 0][:3]
        ref = {"speed": {k: -float(np.hypot(*sol.velocity[k])) for k in moving},
               "velocity": {k: -float(np.hypot(*sol.velocity[k])) for k in moving}}
        rows = compare(velpoly.solve(velpoly.load({**sp.mech, "reference": ref})))
        assert len(rows) == 2 * len(moving)
        speeds, bare = rows[:len(moving)], rows[len(moving):]
        for s, v in zip(speeds, bare):   # one rule: the same reading, the same deviation
            assert s.key == f"|{v.key}|" and s.printed == v.printed < 0 and s.computed == v.computed > 0
            assert s.deviation == v.deviation < 1e-9
            checked += 1
    assert checked >= 14


def test_outputs_without_a_type_or_replacing_the_input_say_so(tmp_path, monkeypatch):
    mech = next(each(2026, 1)).mech
    monkeypatch.chdir(tmp_path)
    page = tmp_path / "m.html"   # a mechanism file named .html: its default page is itself
    page.write_text(to_toml(mech))
    before = page.read_text()
    r = in_process(["html", "m.html"])
    assert r.returncode == 2 and r.stderr.splitlines()[0] == \
        "error: m.html: -o: the default output 'm.html' is the input file: an output never replaces its input"
    assert page.read_text() == before and len(r.stderr.splitlines()) == 2
    f = tmp_path / "m.toml"
    f.write_text(to_toml(mech))
    for command, kind in (("draw", "figure"), ("animate", "animation"), ("html", "page"), ("sweep", "file")):
        for out, what in (("/dev/null", "a special file"), ("plain", "a name")):
            r = in_process([command, f, "-o", out])
            assert r.returncode == 2 and r.stderr.splitlines()[0] == \
                f"error: {out}: -o: no {kind} type: {out!r} is {what} with no suffix to choose one", r.stderr
            assert len(r.stderr.splitlines()) == 2 and not (tmp_path / "plain").exists()
