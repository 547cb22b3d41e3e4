"""Outside check, audit 5: input the contract gives no meaning is refused, one line naming the file and entry.

1. ``[reference]`` values of a shape their kind does not take (FORMAT.md section 1): a ``speed`` is a magnitude
   (``speed = { B = -602 }`` was compared as 602: "a negative magnitude reverses" is a vector's, and a speed has
   no direction to reverse); a pole's position is ``[x, y]`` (``P_24 = 5`` was compared as the pole's distance
   from the origin). Every kind of ``values`` key, written in every shape, over generated mechanisms: the
   shapes FORMAT.md gives it are read, every other is exit 2 naming the entry.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import velpoly
from velpoly.reference import parse_key

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


def refusal(tmp_path, mech: dict, reference: dict):
    """``velpoly solve`` of ``mech`` with ``reference`` written in its file: its exit code and stderr."""
    f = tmp_path / "m.toml"
    f.write_text(to_toml({**mech, "reference": reference}))
    r = in_process(["solve", f])
    assert r.returncode == 0 or r.returncode == 2 and len(r.stderr.strip().splitlines()) <= 2, r.stderr
    return r.returncode, r.stderr


def test_a_printed_value_takes_only_the_shapes_its_kind_has(tmp_path):
    checked = 0
    for sp in each(2026, 7):   # a specimen of every kind
        keys = value_keys(sp.drawn)
        for key in keys:
            kind = parse_key(sp.drawn.mechanism, key).kind
            for shape, v in SHAPES.items():
                rc, err = refusal(tmp_path, sp.mech, {"values": {key: v}})
                if kind in TAKES.get(shape, ()):
                    assert rc == 0, (sp.kind, key, shape, err)
                else:
                    assert rc == 2 and f"reference.values.{key}" in err, (sp.kind, key, shape, err)
                checked += 1
        point = next(p for p, v in sp.drawn.velocity.items() if "@" not in p and np.hypot(*v) > 0)
        speed = float(np.hypot(*sp.drawn.velocity[point]))
        assert refusal(tmp_path, sp.mech, {"speed": {point: speed}})[0] == 0
        rc, err = refusal(tmp_path, sp.mech, {"speed": {point: -speed}})
        assert rc == 2 and f"reference.speed.{point}" in err and "a speed is a magnitude" in err, err
    assert checked > 250


def test_a_poles_printed_position_is_compared_as_a_position():
    sp = next(each(2026, 1))
    m = sp.drawn.mechanism
    pole = velpoly.solve(m).to_dict()["poles"]
    key, p = next((k, v["position"]) for k, v in pole.items() if v["position"] and np.hypot(*v["position"]) > 0)
    i, j = key.split("-")
    from velpoly.reference import compare
    rows = compare(velpoly.solve(velpoly.load({**sp.mech, "reference": {"values": {f"P_{i}{j}": list(p)}}})))
    assert rows[0].deviation < 1e-9 and rows[0].printed == pytest.approx(tuple(p))
    with pytest.raises(velpoly.VelpolyError, match=r"pole's position \[x, y\], got a number"):
        velpoly.load({**sp.mech, "reference": {"values": {f"P_{i}{j}": math.hypot(*p)}}})
