"""Outside check, audit 5: input the contract gives no meaning is refused, one line naming the file and entry.

1. ``[reference]`` values of a shape their kind does not take (FORMAT.md section 1): a ``speed`` is a magnitude
   (not ``[magnitude, direction]``; a negative one is the reversed vector's, test_audit7_input); a pole's
   position is ``[x, y]`` (``P_24 = 5`` was compared as the pole's distance from the origin). Every kind of ``values`` key, written in every shape, over generated mechanisms: the
   shapes FORMAT.md gives it are read, every other is exit 2 naming the entry.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import velpoly
from velpoly.reference import compare, parse_key

from mechanisms import in_process
from test_fuzz import to_toml
from zoo import each

# the shapes a printed value may be written in, and which kinds (reference.Quantity.kind) take each
SHAPES = {"number": 2.5, "negative": -2.5, "pair": [2.5, 30.0], "triple": [1.0, 2.0, 3.0], "empty": []}
TAKES = {"number": {"omega", "alpha", "theta", "V", "A", "R", "VP", "AP"},
         "negative": {"omega", "alpha", "theta", "V", "A", "R", "VP", "AP"},
         "pair": {"V", "A", "R", "VP", "AP", "P"}}


def value_keys(sol) -> list[str]:
    """One ``values`` key of each kind the mechanism has: rates, angle, vectors, components, poles."""
    m = sol.mechanism
    moving = [lk for lk in m.link_names if sol.omega[lk] != 0]
    points = [p for p in sol.velocity if "@" not in p]
    a, b = moving[0], moving[-1]
    keys = [f"omega_{a}", f"alpha_{a}", f"theta_{a}", f"V_{points[0]}", f"A_{points[-1]}",
            f"R_{points[-1]}{points[0]}", f"P_{m.link_names[0]}{a}", f"V_P{m.link_names[0]}{b}"]
    keys = [k for k in keys if parse_key(m, k) is not None]
    assert {parse_key(m, k).kind for k in keys} >= {"omega", "theta", "V", "R", "P", "VP"}, keys
    return keys


def test_a_printed_value_takes_only_the_shapes_its_kind_has(tmp_path):
    checked = 0
    for sp in each(2026, 7):   # a specimen of every kind
        keys = value_keys(sp.drawn)
        kinds = {key: parse_key(sp.drawn.mechanism, key).kind for key in keys}
        for shape, v in SHAPES.items():
            taken = [key for key in keys if kinds[key] in TAKES.get(shape, ())]
            if taken:   # read and compared
                rows = compare(velpoly.solve(velpoly.load({**sp.mech, "reference": {"values": {k: v for k in taken}}})))
                assert [r.key for r in rows] == taken
            for key in set(keys) - set(taken):
                with pytest.raises(velpoly.VelpolyError) as e:
                    velpoly.load({**sp.mech, "reference": {"values": {key: v}}})
                assert e.value.where.startswith(f"reference.values.{key}"), (sp.kind, key, shape, str(e.value))
            checked += len(keys)
        point = next(p for p, v in sp.drawn.velocity.items() if "@" not in p and np.hypot(*v) > 0)
        speed = float(np.hypot(*sp.drawn.velocity[point]))
        assert compare(velpoly.solve(velpoly.load({**sp.mech, "reference": {"speed": {point: speed}}})))[0].deviation \
            < 1e-9
        with pytest.raises(velpoly.VelpolyError, match="expected a number, got a list") as e:
            velpoly.load({**sp.mech, "reference": {"speed": {point: [speed, 0.0]}}})
        assert e.value.where == f"reference.speed.{point}"
    assert checked > 250
    # as the command line says it: one line naming the file and entry, exit 2
    f = tmp_path / "m.toml"
    f.write_text(to_toml({**sp.mech, "reference": {"speed": {point: [speed, 0.0]}}}))
    r = in_process(["solve", f])
    assert r.returncode == 2 and r.stderr.startswith(f"error: {f}: reference.") and len(r.stderr.splitlines()) == 2


def test_a_poles_printed_position_is_compared_as_a_position():
    sp = next(each(2026, 1))
    m = sp.drawn.mechanism
    pole = velpoly.solve(m).to_dict()["poles"]
    key, p = next((k, v["position"]) for k, v in pole.items() if v["position"] and np.hypot(*v["position"]) > 0)
    i, j = key.split("-")
    rows = compare(velpoly.solve(velpoly.load({**sp.mech, "reference": {"values": {f"P_{i}{j}": list(p)}}})))
    assert rows[0].deviation < 1e-9 and rows[0].printed == pytest.approx(tuple(p))
    with pytest.raises(velpoly.VelpolyError, match=r"pole's position \[x, y\], got a number"):
        velpoly.load({**sp.mech, "reference": {"values": {f"P_{i}{j}": math.hypot(*p)}}})


# -- 2. driver rates at the edges of floating point ---------------------------------------------------------------
def rewritten(mech: dict, key: str, text: str) -> str:
    """``mech``'s TOML with the driver's ``key`` written as ``text`` (a number's text, as TOML reads it)."""
    lines = to_toml({**mech, "driver": {**mech["driver"], key: 1.0}}).splitlines()
    at = lines.index('["driver"]')
    k = next(i for i in range(at, len(lines)) if lines[i].startswith(f'"{key}" = '))
    lines[k] = f'"{key}" = {text}'
    return "\n".join(lines) + "\n"


def slider_driven(count: int) -> list[dict]:
    import zoo
    rng = np.random.default_rng(5)
    return [zoo.specimen(rng, kind, variant).mech
            for kind, variant in (("slider-crank", "offset slider"), ("slider-crank", "curved slider"),
                                  ("inverted slider-crank", "offset block slider"))[:count]]


def test_a_driver_rate_written_nonzero_that_reads_as_zero_is_too_small(tmp_path):
    """``omega = 1e-400`` was read as 0, a driver at rest, silently; and ``"1e-400 rpm"``, ``"1e-322 deg/s"``
    alike (the unit's factor takes a denormal to 0)."""
    mechs = [sp.mech for sp in each(2026, 4)] + slider_driven(3)
    f = tmp_path / "m.toml"
    checked = 0
    for mech in mechs:
        keys = ("speed", "accel") if "slider" in mech["driver"] else ("omega", "alpha")
        for key in keys:
            rates = ("1e-400", "-2.5E-999", '"1e-322 deg/s"' if key == "omega" else "-7e-330") \
                if key != "alpha" else ("1e-400", '"1e-400 rad/s^2 cw"')
            for text in rates:
                f.write_text(rewritten(mech, key, text))
                r = in_process(["solve", f])
                assert r.returncode == 2 and f"driver.{key}" in r.stderr and "too small" in r.stderr, (text, r.stderr)
                checked += 1
            for zero in ("0e-400", "-0.0"):   # zero written as zero: read as zero
                f.write_text(rewritten(mech, key, zero))
                value = velpoly.load(f).driver
                assert getattr(value, key) == 0 and "0e" not in str(getattr(value, key))
    assert checked == 4 * 5 + 3 * 6
    # a radius alike (it is positive as written): too small, not "must be positive, got 0"
    import re
    text = re.sub(r'("circles" = \[\["\w+", )[^\]]+\]', r"\g<1>1e-400]", to_toml(mechs[0]), count=1)
    f.write_text(text)
    r = in_process(["solve", f])
    assert r.returncode == 2 and ".circles" in r.stderr and "1e-400 is too small" in r.stderr, r.stderr


def test_the_apis_real_numbers_are_read_and_its_masked_angles_refused():
    """``angle=Decimal("30")`` was refused though a Decimal is a real number; ``np.longdouble("1e400")`` said
    "must be finite" (it is finite: too large); a masked array's masked values were swept."""
    import decimal
    import fractions
    for sp in each(2026, 2):
        m, a = sp.drawn.mechanism, sp.drawn.driver_angle
        if a is None:
            continue
        want = velpoly.solve(m, angle=a + 1.0).to_dict()
        for written in (decimal.Decimal(repr(a + 1.0)), np.longdouble(a + 1.0), fractions.Fraction(a + 1.0)):
            assert velpoly.solve(m, angle=written).to_dict() == want, written
        for beyond in (np.longdouble("1e400"), decimal.Decimal("-1e400")):
            with pytest.raises(velpoly.VelpolyError, match="too large") as e:
                velpoly.solve(m, angle=beyond)
            assert isinstance(e.value, ValueError) and e.value.where == "angle" and "1e+400" in str(e.value)
        angles = a + np.arange(0.0, 4.0)
        w = velpoly.sweep(m, [decimal.Decimal(repr(float(x))) for x in angles])
        assert np.array_equal(w.angles, velpoly.sweep(m, angles).angles)
        with pytest.raises(velpoly.VelpolyError, match="too large"):
            velpoly.sweep(m, np.array([a, np.longdouble("1e400")], dtype=np.longdouble))
        masked = np.ma.masked_array(np.r_[angles, 1e9], mask=[0, 0, 0, 0, 1])
        with pytest.raises(ValueError, match="masked") as e:
            velpoly.sweep(m, masked)
        assert e.value.where == "angles"
        w = velpoly.sweep(m, np.ma.masked_array(angles))   # nothing masked: its values
        assert np.array_equal(w.angles, angles)


# -- 3. messages that mislead ------------------------------------------------------------------------------------
def test_a_cycle_of_a_driver_at_rest_is_refused_with_the_hint_to_give_it_a_rate(tmp_path):
    """animate, html and sweep --gif of a driver at rest (omega = 0, alpha given: a start from rest) suggested
    ``draw --sheet acceleration``, which draws one instant, not the cycle asked for: what helps is a rate."""
    crank = next(each(2026, 1)).mech
    mechs = [crank] + slider_driven(1)
    f = tmp_path / "m.toml"
    for mech, accel in ((m, a) for m in mechs for a in (0.0, 3.0)):
        rate = "speed" if "slider" in mech["driver"] else "omega"
        f.write_text(to_toml({**mech, "driver": {**mech["driver"], rate: 0.0,
                                                 "accel" if rate == "speed" else "alpha": accel}}))
        commands = [["animate", f, "-o", tmp_path / "a.gif", "--sheet", "velocity"],
                    ["sweep", f, "--gif", tmp_path / "s.gif"]] + ([] if accel else [["html", f, "-o", tmp_path / "a.html"]])
        for args in commands:
            r = in_process(args)
            assert r.returncode == 2 and f"driver.{rate}" in r.stderr, (args, r.stderr)
            assert f"give the driver a rate ({rate})" in r.stderr and "--sheet" not in r.stderr, (args, r.stderr)
        if accel:   # one instant's sheets: the start from rest has its acceleration sheet
            r = in_process(["draw", f, "-o", tmp_path / "a.svg", "--sheet", "velocity"])
            assert r.returncode == 2 and "draw --sheet acceleration" in r.stderr, r.stderr
