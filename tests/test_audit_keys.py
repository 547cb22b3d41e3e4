"""Outside check, point keys (FORMAT.md section 5, Circular paths): "A centre K listed in no link
belongs to the guide (slot) link and is keyed ``K@guide``." Found by the audit: such a centre was keyed
``K`` (every zoo and gallery file lists its centre, so nothing had tried it). Checked on the zoo's
curved sliders and circular slots with the centre taken out of every link: the key is ``K@guide``, and
the point is the guide's (it moves with the guide, by the JSON's own rigid-body velocities).
"""
from __future__ import annotations

import copy
import functools

import numpy as np
import pytest

import velpoly

import zoo

KINDS = [("slider-crank", "curved crank"), ("slider-crank", "curved slider"), ("inverted slider-crank", "curved crank"),
         ("slot", "circular"), ("slot", "circular six-bar")]


@functools.cache
def specimen(kind, variant, seed):
    return zoo.specimen(np.random.default_rng(seed), kind, variant)


def unlisted(mech: dict) -> tuple[dict, str, str]:
    """The mechanism with its circular path's centre listed in no link; the centre and the guide."""
    d = copy.deepcopy(mech)
    joint = next(j for j in (*d.get("sliders", []), *d.get("slots", [])) if "centre" in j)
    k = joint["centre"]
    for link in d["links"].values():
        if k in link["points"]:
            link["points"].remove(k)
    return d, k, joint.get("guide", joint.get("slot"))


@pytest.mark.parametrize("kind, variant", KINDS)
@pytest.mark.parametrize("seed", range(2))
def test_an_unlisted_path_centre_is_keyed_k_at_guide(kind, variant, seed):
    d, k, guide = unlisted(specimen(kind, variant, seed).mech)
    s = velpoly.solve(velpoly.load(d)).to_dict()
    keys = [key for key in s["points"] if key.split("@")[0] == k]
    assert keys == [f"{k}@{guide}"]
    # the guide's point: V_K = V_O + omega x (K - O) for another point O of the guide
    o = next(p for p in d["links"][guide]["points"] if f"{p}@{guide}" not in s["points"])
    r = np.subtract(s["points"][keys[0]]["position"], s["points"][o]["position"])
    w = s["links"][guide]["omega"]
    v = np.add(s["points"][o]["velocity"], w * np.array([-r[1], r[0]]))
    assert np.allclose(s["points"][keys[0]]["velocity"], v, atol=1e-9 * (1 + np.abs(v).max()))
    listed = velpoly.solve(velpoly.load(specimen(kind, variant, seed).mech)).to_dict()
    assert k in listed["points"] and f"{k}@{guide}" not in listed["points"]   # listed in its link: plain K
