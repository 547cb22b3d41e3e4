"""Outside checks of a file's numbers and of the ranges velpoly names (FORMAT.md section 3: exit 2 "with one line
``error: FILE: WHERE: WHAT`` and a hint, never a traceback"; section 5, Driver: a toggle on the way is exit 3 "with the
reachable range"). Found by the audit, on generated mechanisms:

- a number written finite but beyond any float, ``omega = 1e400`` (tomllib reads it as inf), said "must be finite,
  got inf" (``expected a finite number, got inf`` for a point or a length): now "1e400 is too large: beyond any
  floating-point number", as ``"1e400 rpm"`` already was (loader.context.toml_float keeps the text it writes);
- such a number written as a TOML integer (10**400, or in a dict given to ``velpoly.load``) escaped as a raw
  OverflowError: ``velpoly solve`` exited 1, "internal error", for any entry (a point, a length, omega, a scale);
- the API (FORMAT.md section 4: a wrong argument raises a VelpolyError that is also a TypeError or ValueError, naming
  it): ``velpoly.sweep(m, [10**400, 0])`` said "the angles must be finite numbers" (``solve(m, angle=10**400)``
  says "too large"), and ``velpoly.load(d, name=5)`` raised a raw TypeError from deep in the loader;
- ``velpoly animate``, ``html`` and ``sweep --gif`` of a mechanism at rest (omega = 0) drew its polygons as dots beside
  a scale bar of a made-up size (``2×10⁻¹² mm/s``), and at omega = 1e-160 the acceleration polygon (1e-320 mm/s²) as a
  dot at 0.02 mm/s², where ``velpoly draw`` refuses both (exit 2 naming driver.omega): now refused alike, before
  anything is written (their frames, drawn without shapely, keep every size whose numbers keep a float's precision,
  solution.FRAMES_RANGE: 1e-181 and 1e179 mm/s² still draw);
- a book's printed ``omega_3 = 6.702 rad/s cw`` in ``[reference]`` was refused with "write numbers without quotes",
  which drops its sense: the reference's omega and alpha (and ``values``' ``omega_3``, ``alpha_3``) are now read as
  the driver's are, with their units and senses in words (FORMAT.md section 1, Driver);
- a refused ``--angle`` of a pin in a bounded slot named where the pin leaves wrapped to (-180, 180] beside the range
  unwrapped: "leaves the slot of wheel at its end S1 at 138.85 deg; the pin is in the slot from -221.16 to 57.91
  deg" (138.85 is -221.15 a turn on): now as the range, -221.15;
- ``velpoly sweep``'s note printed the reachable range's inner ends to six digits (``-176.202 to -84.5619``) where
  the refusal of ``--angle`` prints the range rounded outward (``-176.22 to -84.55``): one range, now printed one
  way (driver.reachable_words), for a toggle and for a pin that leaves its slot.
"""
from __future__ import annotations

import copy
import fractions
import re

import numpy as np
import pytest

import velpoly
from velpoly.kinematics import prepare
from velpoly.reference import compare
from velpoly.sweeps import stop_note

from mechanisms import in_process
from test_fuzz import to_toml
from test_slot_ends import drive, generated
from zoo import zoo


def numbers(d, path=()):
    """The path of every number in a mechanism's dict."""
    if isinstance(d, dict):
        for k, v in d.items():
            yield from numbers(v, path + (k,))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield from numbers(v, path + (i,))
    elif isinstance(d, (int, float)) and not isinstance(d, bool) and path != ("format",):
        yield path


def put(d, path, v):
    for k in path[:-1]:
        d = d[k]
    d[path[-1]] = v


def test_a_number_beyond_any_float_is_too_large_wherever_it_is_written(tmp_path):
    checked = 0
    specimens = zoo(2026, 60)
    for sp in (specimens[i] for i in (0, 10, 40, 45, 50)):   # points, curved paths, slots, contacts, the drivers
        mech = copy.deepcopy(sp.mech)
        mech["drawing"] = {"scale": 0.5}
        mech["reference"] = {"values": {"V_" + next(iter(mech["points"])): [1.5, 30.0]}}
        for path in numbers(mech):
            for written, shown in (("1e400", "1e400"), ("-1.5e999", "-1.5e999"), (str(10 ** 400), "1e+400")):
                d = copy.deepcopy(mech)
                put(d, path, 7.25)
                text = to_toml(d).replace("7.25", written, 1)
                with pytest.raises(velpoly.VelpolyError) as e:
                    velpoly.loads(text)
                assert f"{shown} is too large: beyond any floating-point number" in str(e.value), (path, str(e.value))
                assert "inf" not in str(e.value).splitlines()[0], str(e.value)
                checked += 1
            if checked % 7 == 0:   # a dict's integer, as TOML's
                d = copy.deepcopy(mech)
                put(d, path, -(10 ** 400))
                with pytest.raises(velpoly.VelpolyError, match=r"-1e\+400 is too large"):
                    velpoly.load(d)
    assert checked > 200
    f = tmp_path / "big.toml"   # the command: one line naming the file and the entry, exit 2
    d = copy.deepcopy(zoo(2026, 1)[0].mech)
    d["driver"]["omega"] = 7.25
    f.write_text(to_toml(d).replace("7.25", str(10 ** 400)))
    r = in_process(["solve", f])
    assert r.returncode == 2 and r.stderr.startswith(f"error: {f}: driver.omega (line "), r.stderr
    assert "1e+400 is too large" in r.stderr.splitlines()[0], r.stderr


def refused_range(m, beyond: float) -> str:
    """The range the refusal of ``--angle`` names (``reachable: LO to HI`` or ``the pin is in the slot from``)."""
    with pytest.raises(velpoly.PoseError) as e:
        velpoly.solve(m, angle=beyond)
    return re.search(r"(?:reachable: |in the slot from )(\S+ to \S+) deg", str(e.value))[1]


def test_a_sweeps_note_prints_the_range_as_the_refusal_does():
    rockers = [sp for sp in zoo(20261128, 5) if "rocker" in sp.kind and "crank" not in sp.kind][:2]
    slotted = [g for g in generated(3) if g[0] == "oscillating"][:1]
    cases = [velpoly.load(sp.mech) for sp in rockers]
    cases += [velpoly.load(drive(a, e, psi, theta, lo, hi, omega=3.0 * sense, swap=swap))
              for _, a, e, psi, theta, lo, hi, sense, swap in slotted]
    assert len(cases) == 3
    for m in cases:
        kin = prepare(m)
        ref = velpoly.solve(m).driver_angle
        sw = velpoly.sweep(m, ref + np.sign(m.driver.omega) * np.arange(0.0, 360.0, 5.0))
        note = stop_note(sw, kin)
        printed = re.search(r"(?:reachable on this branch: |in its slot from )(\S+ to \S+) deg", note)[1]
        ends = [float(x) for x in printed.split(" to ")]
        far = ref + 179.0 * (1.0 if ends[1] - ref < 179.0 else -1.0)   # beyond the range, the shorter way round
        bounds = [float(x) for x in refused_range(m, far).split(" to ")]
        # to 0.01 deg as the refusal prints it: inward (every angle printed is reached) within its outward bounds
        assert all(re.fullmatch(r"-?\d+(\.\d\d?)?", x) for x in printed.split(" to ")), note
        assert bounds[0] <= ends[0] <= bounds[0] + 0.0301 and bounds[1] - 0.0301 <= ends[1] <= bounds[1], (note, bounds)
        for end in ends:
            if abs(end - ref) < 180.0:   # --angle turns the shorter way round
                velpoly.solve(m, angle=end)


def test_the_apis_wrong_arguments_are_named():
    for sp in zoo(2026, 60)[::20]:
        m = velpoly.load(sp.mech)
        for angles, shown in (([10 ** 400, 0.0], "1e+400"), ([0, -(10 ** 401)], "-1e+401"),
                              ([fractions.Fraction(10 ** 400, 3), 1], "3.33333e+399")):
            with pytest.raises(velpoly.ArgumentValueError, match=rf"a value of {re.escape(shown)} \S+ is too large"):
                velpoly.sweep(m, angles)
        for name in (5, b"m.toml", ["m"]):
            for call in (lambda: velpoly.load(sp.mech, name=name), lambda: velpoly.loads(to_toml(sp.mech), name=name)):
                with pytest.raises(velpoly.ArgumentTypeError) as e:
                    call()
                assert isinstance(e.value, TypeError) and e.value.where == "name", str(e.value)


def test_a_cycles_figures_of_polygons_at_rest_or_too_small_are_refused_as_draw_refuses(tmp_path):
    specimens = zoo(2026, 60)
    crank, slider = specimens[0], next(sp for sp in specimens if "slider" in sp.mech["driver"])
    for sp, rate in ((crank, 0.0), (crank, 1e-160), (slider, 0.0)):
        d = copy.deepcopy(sp.mech)
        key = "omega" if "omega" in d["driver"] else "speed"
        d["driver"].update({key: rate, "alpha" if key == "omega" else "accel": 0.0})
        f = tmp_path / "m.toml"
        f.write_text(to_toml(d))
        commands = [["animate", f, "-o", tmp_path / "a.gif", "--step", "60", "--size", "320x180", "--sheet", "full"],
                    ["html", f, "-o", tmp_path / "a.html", "--step", "60"]]
        if rate == 0.0:   # at 1e-160 the velocity polygon (1e-161 mm/s) draws: only the accelerations (1e-321) do not
            commands.append(["sweep", f, "--step", "60", "--gif", tmp_path / "s.gif", "--csv", tmp_path / "s.csv"])
        for args in commands:
            r = in_process(args)
            assert r.returncode == 2 and r.stderr.startswith(f"error: {f}: driver.{key} (line "), (args, r.stderr)
            assert sorted(p.name for p in tmp_path.iterdir()) == ["m.toml"], args   # nothing written
    for rate in (1e90, 1e-90):   # a polygon of any size above the floor is drawn (1e179, 1e-181 mm/s^2 here)
        d = copy.deepcopy(crank.mech)
        d["driver"].update({"omega": rate, "alpha": 0.0})
        f.write_text(to_toml(d))
        assert in_process(["html", f, "-o", tmp_path / "a.html", "--step", "60"]).returncode == 0


def test_a_books_rates_are_read_with_their_units_and_senses_in_words():
    compared = 0
    for sp in zoo(2026, 60)[:30:3]:
        d = copy.deepcopy(sp.mech)
        if "link" not in d["driver"]:
            continue
        sol = velpoly.solve(velpoly.load(d))
        moving = [k for k, w in sol.omega.items() if abs(w) > 1e-9]
        senses = ("cw", "Clockwise", "CCW", "anticlockwise")
        d["reference"] = {
            "omega": {k: f"{abs(sol.omega[k]):.9g} rad/s {senses[i % 2] if sol.omega[k] < 0 else senses[2 + i % 2]}"
                      for i, k in enumerate(moving)},
            "values": {f"omega_{k}": f"{-sol.omega[k] * 30 / np.pi:.9g} rpm cw" for k in moving},   # cw: minus
        }
        if sol.alpha and any(abs(a) > 1e-9 for a in sol.alpha.values()):
            k = max(sol.alpha, key=lambda n: abs(sol.alpha[n]))
            d["reference"]["alpha"] = {k: f"{abs(sol.alpha[k]):.9g} rad/s^2 {'cw' if sol.alpha[k] < 0 else 'ccw'}"}
        rows = compare(velpoly.solve(velpoly.load(d)))
        assert len(rows) >= 2 * len(moving), rows
        for r in rows:
            assert r.deviation is not None and r.deviation < 1e-7, (sp.kind, r)
            compared += 1
    assert compared > 20
    bad = copy.deepcopy(zoo(2026, 1)[0].mech)
    bad["reference"] = {"omega": {"3": "6.7 rad/sec cw"}}
    with pytest.raises(velpoly.InputError, match=r"reference\.omega\.3.*cannot read \"6\.7 rad/sec cw\" as an angular velocity"):
        velpoly.load(bad)


def test_where_a_pin_leaves_its_slot_lies_in_the_range_the_refusal_names():
    checked = 0
    levers = [g for g in generated(3) if g[0] != "geneva"][:3]   # ranges that reach beyond half a turn
    for _, a, e, psi, theta, lo, hi, sense, swap in levers:
        m = velpoly.load(drive(a, e, psi, theta, lo, hi, omega=3.0 * sense, swap=swap))
        ref = velpoly.solve(m).driver_angle
        for far in (ref + 179.0, ref - 179.0):
            try:
                velpoly.solve(m, angle=far)
                continue
            except velpoly.PoseError as e:
                text = str(e)
            words = re.search(r"at its end S[12] at (\S+) deg; the pin is in the slot from (\S+) to (\S+) deg",
                              text).groups()
            leaves, first, last = (float(x) for x in words)
            assert first - 0.01 <= leaves <= last + 0.01, text
            # the end on the refused side, printed as the range is (audit 5: it was 59.4272 beside 59.43)
            assert words[0] == words[1 if far < ref else 2], text
            checked += 1
    assert checked >= 4
