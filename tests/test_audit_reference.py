"""Outside check, ``[reference]`` values in textbook notation (FORMAT.md section 1).

1. Every key a book prints, read back exactly: for generated mechanisms of every kind (the zoo), each
   value the notation names (omega_3, alpha_3, theta_3, V_B, A_B, R_BA, V_BA, A^n_BA, A^t_BA, V_B3/B4,
   A^c_B3/B4, A^s_B3/B4, P_13, V_P24), computed here from the JSON's definitions alone, is written as a
   printed value, and the comparison must find no deviation.
2. Found by the audit: a scalar (``omega_3``, ``alpha_3``, ``theta_3``) written as a vector ``[1, 2]``
   in ``[reference.values]`` crashed the comparison (exit 1, an internal error); it is an input error.
"""
from __future__ import annotations

import functools
import math

import numpy as np
import pytest

import velpoly
from velpoly.cli import main
from velpoly.reference import compare

import mechanisms
import zoo
from test_fuzz import to_toml

SEED = 4242


@functools.cache
def specimens():
    return zoo.zoo(SEED, 24)


def polar(v):
    return [float(np.hypot(*v)), float(math.degrees(math.atan2(v[1], v[0])))]


def perp(v):
    return np.array([-v[1], v[0]])


def printed_values(d: dict, s: dict) -> dict:
    """Every value of the notation, from the JSON ``s`` of the mechanism ``d`` by FORMAT.md's definitions."""
    links = s["links"]
    frame = next(k for k, v in d["links"].items() if v.get("frame"))

    def pos(p, lk, what="position"):
        key = f"{p}@{lk}" if f"{p}@{lk}" in s["points"] else p
        return np.array(s["points"][key][what], float)
    has_acc = all(v["acceleration"] is not None for v in s["points"].values())
    vals = {}
    for lk, L in links.items():
        vals[f"theta_{lk}"] = L["angle"]
        if lk != frame:
            vals[f"omega_{lk}"] = L["omega"]
            if has_acc:
                vals[f"alpha_{lk}"] = L["alpha"]
    for k, v in s["points"].items():
        if "@" not in k and np.hypot(*v["velocity"]) > 1e-9:
            vals[f"V_{k}"] = polar(v["velocity"])
            if has_acc and np.hypot(*v["acceleration"]) > 1e-9:
                vals[f"A_{k}"] = polar(v["acceleration"])
    for lk, spec in d["links"].items():
        a, b = (spec["points"] + [None])[:2]
        if b is None or any(k.startswith((a + "@", b + "@")) for k in s["points"]):
            continue
        r = pos(b, lk) - pos(a, lk)
        w, al = links[lk]["omega"], links[lk]["alpha"]
        vals[f"R_{b}{a}"] = polar(r)
        if abs(w) > 1e-9:
            vals[f"V_{b}{a}"] = polar(pos(b, lk, "velocity") - pos(a, lk, "velocity"))   # omega x R_BA
            if has_acc:
                vals[f"A^n_{b}{a}"] = polar(-w * w * r)
        if has_acc and abs(al) > 1e-9:
            vals[f"A^t_{b}{a}"] = polar(al * perp(r))
    for group, on, path, at in (("sliders", "block", "guide", "point"), ("slots", "link", "slot", "pin")):
        for j in s.get(group, []):
            blk, gd, p = j[on], j[path], j[at]
            g0 = next(q for q in d["links"][gd]["points"] if q != p)
            x = pos(p, blk)
            r = x - pos(g0, gd)
            v_rel = pos(p, blk, "velocity") - (pos(g0, gd, "velocity") + links[gd]["omega"] * perp(r))
            if np.hypot(*v_rel) < 1e-9:
                continue
            vals[f"V_{p}{blk}/{p}{gd}"] = polar(v_rel)
            if has_acc:
                cor = 2 * links[gd]["omega"] * perp(v_rel)               # 2 omega_guide x V_rel
                a_guide = pos(g0, gd, "acceleration") + links[gd]["alpha"] * perp(r) - links[gd]["omega"] ** 2 * r
                slide = pos(p, blk, "acceleration") - a_guide - cor
                if np.hypot(*cor) > 1e-9:
                    vals[f"A^c_{p}{blk}/{p}{gd}"] = polar(cor)
                if np.hypot(*slide) > 1e-9:
                    vals[f"A^s_{p}{blk}/{p}{gd}"] = polar(slide)
    for key, pole in s["poles"].items():
        i, j = key.split("-")
        if pole["position"] is None:
            continue
        vals[f"P_{i}{j}"] = pole["position"]
        x = np.array(pole["position"])
        o = d["links"][i]["points"][0]
        v = pos(o, i, "velocity") + links[i]["omega"] * perp(x - pos(o, i))
        if np.hypot(*v) > 1e-9:
            vals[f"V_P{i}{j}"] = polar(v)
    return vals


@pytest.mark.xdist_group("audit-reference-zoo")   # one worker makes specimens() (zoo.zoo(4242, 24)) for all eight
@pytest.mark.parametrize("index", range(0, 24, 3))
def test_every_printed_value_is_read_as_the_book_means_it(index):
    sp = specimens()[index:index + 3]
    for x in sp:
        d = dict(x.mech)
        vals = printed_values(d, x.drawn.to_dict())
        d["reference"] = {"source": "read back", "values": vals}
        rows = compare(velpoly.solve(velpoly.load(d)))
        assert len(rows) == len(vals)
        for row in rows:
            assert row.computed is not None and (row.deviation or 0) < 1e-7 and (row.angle_error or 0) < 1e-6, (
                x.kind, row)


@pytest.mark.parametrize("key", ["omega_2", "alpha_3", "theta_4"])
def test_a_scalar_written_as_a_vector_is_exit_2(tmp_path, capsys, key):
    d = mechanisms.fourbar(alpha=3.0)
    d["reference"] = {"values": {key: [6.702, 30.0]}}
    f = tmp_path / "m.toml"
    f.write_text(to_toml(d))
    assert main(["solve", str(f)]) == 2
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"error: {f}: reference.values.{key}") and "expected a number, got a list" in err[0]
    assert err[1].startswith("hint: ") and len(err) == 2


@pytest.mark.parametrize("seed", range(3))
def test_a_printed_pole_that_is_at_infinity_is_shown_not_compared(tmp_path, capsys, seed):
    """Found by the audit: a printed pole (``P_34 = [x, y]``, ``V_P34 = [m, d]``) that is at infinity here
    (a block on a straight guide) crashed ``velpoly solve`` (exit 1: the printed pair read as a number),
    and the drawn results table showed its deviation as 0. Now: "at infinity", no deviation."""
    from velpoly.render.table import _dev
    rng = np.random.default_rng(seed)
    d = mechanisms.inverted_slider_crank(r=float(rng.uniform(2, 4)), d=float(rng.uniform(6, 9)),
                                         theta=float(rng.uniform(20, 160)), omega=float(rng.uniform(-9, 9)))
    d["reference"] = {"values": {"P_34": [1.0, 2.0], "V_P34": [3.0, 40.0], "A_P34": 5.0, "P_13": [1.0, 1.0]}}
    f = tmp_path / "m.toml"
    f.write_text(to_toml(d))
    assert main(["solve", str(f)]) == 0
    table = capsys.readouterr().out.split("Reference values")[1].splitlines()
    for key, printed in (("P_34", "(1, 2)"), ("V_P34", "3 ∠ 40.000°"), ("A_P34", "5")):
        row = next(line.split("  ") for line in table if line.startswith(key + " "))
        cells = [c.strip() for c in row if c.strip()]
        assert cells[1:] == [printed, "at infinity", "-"], cells
    rows = {r.key: r for r in compare(velpoly.solve(velpoly.load(d)))}
    assert rows["P_13"].computed is not None and rows["P_13"].deviation > 0
    for key in ("P_34", "V_P34", "A_P34"):
        assert rows[key].computed is None and rows[key].deviation is None and _dev(rows[key]) == "-"
