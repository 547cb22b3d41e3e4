"""Outside check, ``[reference] values`` keys (FORMAT.md section 1, Reference values: "``P_13`` (a
pole's position, ``[x, y]``)"; "an unknown key in ``values`` is an input error"). Found by the audit:
- a pole of links named by words could not be written at all: ``P_lever,cylinder`` (the figures print
  P_{lever,cylinder}) was refused as an unknown quantity. FORMAT.md gives ``P_13`` only; the README
  now extends it in its style: the two names with a comma between them, as the figures print them;
- a point relative to itself (``A^n_AA``, ``V_AA``, ``R_BB``) was accepted and compared as 0;
- ``P_13`` in a file without link 1 said only "unknown quantity": the message now names the link.
Over generated mechanisms of every kind (the zoo's first twelve, links renamed to words or numbered
from 2).
"""
from __future__ import annotations

import copy

import pytest

import velpoly
from velpoly.reference import compare

import mechanisms
from zoo import zoo


def specimens():
    return [sp.mech for sp in zoo(20261125, 12)]


def with_values(mech: dict, values: dict) -> dict:
    m = copy.deepcopy(mech)
    m["reference"] = {"source": "audit", "values": values}
    return m


def test_a_pole_of_word_named_links_is_written_with_a_comma_and_compared():
    compared = 0
    for mech in specimens():
        words = mechanisms.rename_links(mech)
        poles = velpoly.solve(velpoly.load(words)).to_dict()["poles"]
        values = {}
        for key, pole in poles.items():
            i, j = key.split("-")
            if pole["position"] is not None:
                values[f"P_{j},{i}" if len(values) % 2 else f"P_{i},{j}"] = pole["position"]
        rows = compare(velpoly.solve(velpoly.load(with_values(words, values))))
        assert {r.key for r in rows} == set(values)
        for r in rows:
            assert r.deviation is not None and r.deviation < 1e-9, (mech["title"], r)
        compared += len(rows)
    assert compared >= 30


def test_a_point_relative_to_itself_is_refused_naming_the_entry():
    for mech in specimens():
        m = velpoly.load(mech)
        link = next(lk for lk in m.links if len(lk.points) >= 2 and not lk.frame)
        p = link.points[1]
        for key in (f"A^n_{p}{p}", f"A^t_{p}{p}", f"V_{p}{p}", f"R_{p}{p}"):
            if f"{p}{p}" in m.points:
                continue
            with pytest.raises(velpoly.InputError) as e:
                velpoly.load(with_values(mech, {key: 1.0}))
            assert e.value.where == f"reference.values.{key}", e.value
            assert f"{p} relative to itself" in str(e.value) and "\n" not in str(e.value), e.value


def test_a_pole_of_a_link_the_file_has_not_names_that_link():
    for mech in specimens():
        names = {k: str(n) for n, k in enumerate(mech["links"], start=2)}   # no link 1
        numbered = mechanisms.rename_links(mech, tuple(names.values()))
        last = list(names.values())[-1]
        for key in ("P_1" + last, f"V_P1{last}"):
            with pytest.raises(velpoly.InputError) as e:
                velpoly.load(with_values(numbered, {key: 1.0}))
            assert e.value.where == f"reference.values.{key}" and "no link '1'" in str(e.value), e.value
