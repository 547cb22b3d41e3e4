"""Every arrow of the velocity and acceleration polygons is what its label and legend say (issue 13).

Generated mechanisms (tests/mechanisms.py ``ARROW_GENERATORS``: blocks on moving guides found from
either side, pins in straight and circular slots driven by the pin or by the slot, sliding cams with
curved, flat and translating followers, a rod sliding on a fixed drum or floor), each at four poses, and every gallery file go through
``checks_arrows.assert_arrows_true``; the Coriolis arrows are also compared with the JSON's
``coriolis`` of their slider or slot, and the drawn arrows with the construction's.
"""
from __future__ import annotations

import dataclasses
import glob
import os

import numpy as np
import pytest

import velpoly
from velpoly.names import place
from velpoly.polygons import acceleration_polygon, velocity_polygon

import checks_arrows
import mechanisms as M
from checks_arrows import assert_arrows_true
from paths import GALLERY_FILES, example

SEEDS = range(6)
ANGLES = (20.0, 110.0, 200.0, 290.0)
GALLERY = [str(p) for p in GALLERY_FILES]


def _solve(d):
    return velpoly.solve(velpoly.load(d))


@pytest.mark.parametrize("name", sorted(M.ARROW_GENERATORS))
def test_generated_arrows_are_true(name):
    """Every arrow of both polygons of 24 poses of each kind of joint; Coriolis and slip drawn in each."""
    gen = M.ARROW_GENERATORS[name]
    seen = {}
    for seed in SEEDS:
        for a in ANGLES:
            counts = assert_arrows_true(_solve(gen(seed, a)))
            for k, n in counts.items():
                seen[k] = seen.get(k, 0) + n
    if "fixed" not in name:   # on the frame's surface there is no Coriolis term
        assert seen.get("coriolis", 0) >= len(SEEDS) * len(ANGLES), seen
    assert seen.get("slip", 0) >= len(SEEDS) * len(ANGLES), seen


@pytest.mark.parametrize("path", GALLERY, ids=os.path.basename)
def test_gallery_arrows_are_true(path):
    assert_arrows_true(_solve(path))


def _joint_arrows(sol):
    """The acceleration polygon's Coriolis and slip arrows, and the JSON's coriolis of each joint."""
    poly = acceleration_polygon(sol)
    vecs = [v for st in poly.steps for v in st.vectors]
    d = sol.to_dict()
    json_cor = [np.array(r["coriolis"]) for r in d.get("sliders", []) + d.get("slots", [])]
    return poly, vecs, json_cor


@pytest.mark.parametrize("name,start", [("block on a driven crank", "block"),
                                        ("block on a driving guide", "guide"),
                                        ("pin in a straight slot, pin driven", "block"),
                                        ("pin in a straight slot, slot driven", "guide"),
                                        ("pin in a circular slot, pin driven", "block"),
                                        ("pin in a circular slot, slot driven", "guide")])
def test_coriolis_in_its_true_sense_from_either_side(name, start):
    """The arrow labelled Coriolis equals the JSON's 2 omega_guide x V_rel (FORMAT.md section 5), not its
    negative, whichever image the construction starts from: from the block's (pin's) image the Coriolis
    arrow ends at it and the slip arrow starts at the guide's point; from the guide's point the Coriolis
    arrow starts at it. Checked without the arrows' ``of``."""
    for seed in SEEDS:
        for a in ANGLES:
            sol = _solve(M.ARROW_GENERATORS[name](seed, a))
            poly, vecs, json_cor = _joint_arrows(sol)
            (cor,) = [v for v in vecs if v.kind == "coriolis"]
            (slip,) = [v for v in vecs if v.kind == "slip"]
            (want,) = json_cor
            big = max(float(np.hypot(*v)) for v in poly.images.values())
            assert np.hypot(*(cor.head - cor.tail - want)) <= 1e-9 * big, (seed, a, cor.label)
            assert not cor.label.startswith("-") and cor.label.startswith("2 omega_")
            s = sol.mechanism.slots[0] if sol.mechanism.slots else sol.mechanism.sliders[0]
            pin = s.pin if sol.mechanism.slots else s.point
            block = s.link if sol.mechanism.slots else s.block
            guide = s.slot if sol.mechanism.slots else s.guide
            assert cor.label.startswith(f"2 omega_{guide} x V_{place(pin, block)}/{place(pin, guide)}"), cor.label
            pin_img = poly.images[pin] if pin in poly.images else poly.images[f"{pin}@{block}"]
            gk = f"{pin}@{guide}"
            guide_img = poly.images[gk] if gk in poly.images else poly.auxiliary[gk].image
            if start == "block":
                assert np.hypot(*(cor.head - pin_img)) <= 1e-9 * big     # ends at the known image
                assert np.hypot(*(slip.tail - guide_img)) <= 1e-9 * big   # the slip from the point found
                assert np.hypot(*(slip.head - cor.tail)) <= 1e-9 * big or \
                    any(np.hypot(*(v.tail - slip.head)) <= 1e-9 * big for v in vecs if v.kind == "normal")
            else:
                assert np.hypot(*(cor.tail - guide_img)) <= 1e-9 * big   # starts at the known image
                assert np.hypot(*(slip.head - pin_img)) <= 1e-9 * big


@pytest.mark.parametrize("follower", ["curved", "flat", "translating"])
def test_sliding_contact_by_its_equivalent_linkage(follower):
    """A sliding contact with centres of curvature: no arrow lumps the contact's terms. The construction
    goes through the centre of curvature of one profile, moving relative to the other link on a circle
    about its centre (a straight line along a flat): Coriolis 2 omega x V (where that link turns),
    V^2 / rho towards the other centre, and the slip along the tangent, each its own arrow."""
    for seed in SEEDS:
        for a in ANGLES:
            sol = _solve(M.sliding_cam(seed, a, follower))
            c = sol.mechanism.contacts[0]
            poly = acceleration_polygon(sol)
            vecs = [v for st in poly.steps for v in st.vectors]
            for v in vecs:
                if v.of[0] in ("slip", "coriolis", "path-normal"):
                    at = v.of[2 if v.of[0] == "coriolis" else 1].split("@")[0]
                    assert at in [x for x in c.centres if x], (v.label, "the joint is the equivalent linkage's")
                assert not (v.kind == "normal" and v.of[0] not in ("normal", "path-normal")), v.label
            kinds = {v.kind for v in vecs}
            assert "slip" in kinds
            if follower != "translating":
                assert "coriolis" in kinds
            if follower != "flat":
                assert any(v.of[0] == "path-normal" for v in vecs)


def _mutated(poly, change):
    steps = []
    done = False
    for st in poly.steps:
        vs = []
        for v in st.vectors:
            if not done and change(v) is not None:
                v, done = change(v), True
            vs.append(v)
        steps.append(dataclasses.replace(st, vectors=tuple(vs)))
    assert done
    return dataclasses.replace(poly, steps=tuple(steps))


@pytest.mark.parametrize("change", [
    lambda v: dataclasses.replace(v, tail=v.head, head=v.tail) if v.kind == "coriolis" else None,   # -2w x V
    lambda v: dataclasses.replace(v, label="A^n_XY") if v.kind == "normal" else None,               # mislabelled
    lambda v: dataclasses.replace(v, kind="normal") if v.kind == "coriolis" else None,             # wrong legend
    lambda v: dataclasses.replace(v, head=v.head + 1e-3 * (v.head - v.tail)) if v.kind == "slip" else None,
], ids=["reversed-coriolis", "mislabelled-normal", "coriolis-as-normal", "slip-off"])
def test_the_check_fails_on_a_wrong_arrow(monkeypatch, change):
    """The check is not vacuous: each kind of mistake of issue 13 makes it fail."""
    sol = _solve(M.block_on_driven_crank(3, 110.0))
    assert_arrows_true(sol)
    bad = _mutated(acceleration_polygon(sol), change)
    monkeypatch.setattr(checks_arrows, "acceleration_polygon", lambda s: bad)
    with pytest.raises(AssertionError):
        assert_arrows_true(sol)


@pytest.mark.parametrize("case", ["ex3_3_inverted_slider", "fig3_15b_sliding", "slot", "cam"])
def test_drawn_arrows_are_the_constructions(case):
    """The arrows render/polygon.py draws: each is a vector of the construction, tail and head at its
    ends in the axes' data units (mm on paper through the view's scale), the head's tip at the head and
    pointing from the tail, in its kind's style (its gid names the kind and the label)."""
    import matplotlib.pyplot as plt
    from velpoly.render.polygon import draw_polygon
    if case == "slot":
        sol = _solve(M.pin_in_slot(2, 110.0, "pin"))
    elif case == "cam":
        sol = _solve(M.sliding_cam(1, 200.0, "curved"))
    else:
        sol = _solve(str(example(case)))
    for poly in (velocity_polygon(sol), acceleration_polygon(sol)):
        fig, ax = plt.subplots(figsize=(6, 6))
        try:
            art = draw_polygon(poly, ax, mechanism=sol.mechanism)
            vecs = [v for st in poly.steps for v in st.vectors]
            big = max(float(np.hypot(*v)) for v in poly.images.values())
            tol = 1e-9 * big
            assert art.arrows
            drawn_kinds = set()
            for kind, tail, head, patch in art.arrows:
                match = [v for v in vecs if v.kind == kind and np.hypot(*(v.tail - tail)) <= tol
                         and np.hypot(*(v.head - head)) <= tol]
                assert match, (kind, tail, head)
                assert patch.get_gid() in {f"{kind}-{v.label}" for v in match} | \
                    {f"absolute-{k}" for k in poly.images}, patch.get_gid()
                xy = patch.get_xy() - patch._velpoly_shift      # (a vector beside another on its line: moved)
                assert np.hypot(*(xy[0] - head)) <= tol           # the tip at the head
                base = 0.5 * (xy[1] + xy[3])
                d = np.asarray(head) - np.asarray(tail)
                assert float(np.dot(xy[0] - base, d)) > 0       # pointing from the tail to the head
                # on paper: the shaft's length through the view's scale is the vector's, scaled
                px = ax.transData.transform([tail, head])
                assert np.hypot(*(px[1] - px[0])) > 0
                drawn_kinds.add(kind)
            # every non-null component not drawn as the absolute vector it coincides with is drawn
            for v in vecs:
                if np.hypot(*(v.head - v.tail)) > 1e-6 * big and v.kind != "absolute":
                    assert any((k == v.kind or k == "absolute") and np.hypot(*(t - v.tail)) <= tol
                               and np.hypot(*(h - v.head)) <= tol for k, t, h, _ in art.arrows), v.label
            if poly.kind == "acceleration" and case in ("ex3_3_inverted_slider", "slot", "cam"):
                assert "coriolis" in drawn_kinds
        finally:
            plt.close(fig)
