"""Pins in slots and ground, as the space diagram draws them (issue 13 item 5), at the data level.

A slot is a cut in its link's body: its centre line lies along the slot's path (the straight line
through the pin in the slot's direction, or the circle about K through the pin), the pin inside
it; the cut lies within the link's drawn body, which is one piece holding the link's own points
(the slot attached to its link); the cut encloses none of the link's other points (a slotted
lever's pivot) unless the slot's ``ends`` put it there; with ``ends`` the cut runs between them.
Ground hatching crosses no moving link's body but those pinned to that ground.
"""
from __future__ import annotations

import glob
import math
import os

import matplotlib.pyplot as plt
import numpy as np
import pytest
from shapely.geometry import LineString, MultiLineString, Point

import velpoly
from velpoly.errors import InputError
from velpoly.render.displacement import draw_mechanism

import mechanisms as M
from paths import GALLERY_FILES

GALLERY = [str(p) for p in GALLERY_FILES]
# each (driver, slot shape) at two of the four poses, half a turn apart: straight slots driven by the pin and
# circular ones by the slot at 20 and 200 deg, the other two at 110 and 290 deg (each at three of six poses, 65 and
# 245 deg too, until issue 19 item 7: every driver and slot shape is still drawn in two opposite quadrants)
CONFIGS = (("pin", False), ("slot", False), ("pin", True), ("slot", True))
CASES = [(seed, a, *CONFIGS[k]) for seed, a in enumerate((20.0, 110.0, 200.0, 290.0))
         for k in ((0, 3) if seed % 2 == 0 else (1, 2))]


def _drawn(sol):
    """The space diagram's shapes (no labels or link numbers: ``mechanisms.shapes_only``) and the tolerance."""
    fig, ax = plt.subplots(figsize=(7, 7))
    try:
        art = draw_mechanism(sol, ax, options=M.shapes_only(sol.mechanism))
        tol = 1e-6 * sol.mechanism.size
        return art, tol
    finally:
        plt.close(fig)


def _check_slot(sol, art, tol, ends=None):
    m = sol.mechanism
    assert art.slot_cuts, "no slot drawn"
    for i, (link, line, cut) in art.slot_cuts.items():
        s = m.slots[i]
        r = sol.motion.slots[i]
        pin = np.asarray(sol.place(s.link, s.pin), float)
        xy = np.asarray(line.coords)
        if s.centre is None:   # along the straight path through the pin
            d = np.array([math.cos(math.radians(float(r["direction"][0]))), math.sin(math.radians(float(r["direction"][0])))])
            off = (xy - pin) @ np.array([-d[1], d[0]])
            assert np.max(np.abs(off)) <= tol, "the slot leaves its path"
        else:                  # on the circle about K through the pin
            k = np.asarray(sol.place(s.slot, s.centre), float)
            rad = np.hypot(*(pin - k))
            assert np.max(np.abs(np.hypot(*(xy - k).T) - rad)) <= tol, "the slot leaves its circle"
        chord = float(np.max(np.hypot(*np.diff(xy, axis=0).T)))
        sag = 0.0 if s.centre is None else chord ** 2 / (8 * rad)   # a polygonal arc's chords cut inside it
        assert line.distance(Point(*pin)) <= tol + sag, "the pin is not in its slot"
        assert cut.contains(Point(*pin).buffer(0.4 * cut.area / max(line.length, 1e-300)))   # inside, not at an edge
        body = art.bodies[link]
        assert body.geom_type == "Polygon", "the slot's link is drawn in pieces (a slot floating off its link)"
        assert body.buffer(tol).contains(cut), "the slot is not cut in its link's body"
        for q in m.link(link).points:
            if q == s.pin:
                continue
            p = Point(*sol.place(link, q))
            assert body.buffer(tol).contains(p), f"the body does not hold its point {q}"
            between = ends is not None and s.centre is None and _between(sol, link, ends, q)
            if not between:
                assert not cut.contains(p), f"the slot encloses {q}, a point of its own link"
        if ends is not None:
            e = [np.asarray(sol.place(link, x), float) for x in ends]
            got = sorted((tuple(np.round(xy[0], 9)), tuple(np.round(xy[-1], 9))))
            assert np.allclose(sorted(map(tuple, e)), got, atol=tol), "the slot does not run between its ends"


def _between(sol, link, ends, q):
    a, b = (np.asarray(sol.place(link, x), float) for x in ends)
    p = np.asarray(sol.place(link, q), float)
    return LineString([tuple(a), tuple(b)]).distance(Point(*p)) <= 1e-9 * sol.mechanism.size


def _check_ground(art, tol):
    n = 0
    for role in ("ground", "guides", "contacts"):
        for lc in art.get(role, []):
            if lc not in art.exempt:
                continue
            segs = [s for s in lc.get_segments() if len(s) >= 2]
            ground = MultiLineString([[tuple(p) for p in s] for s in segs])
            for lk, body in art.bodies.items():
                if lk in art.exempt[lc]:
                    continue
                assert not ground.intersects(body.buffer(-tol)), f"{role} hatching crosses link {lk}"
            n += 1
    return n


@pytest.mark.parametrize("seed,angle,driver,circular", CASES)
def test_generated_slots_cut_in_their_links(seed, angle, driver, circular):
    sol = velpoly.solve(velpoly.load(M.pin_in_slot(seed, angle, driver, circular)))
    art, tol = _drawn(sol)
    _check_slot(sol, art, tol)
    assert _check_ground(art, tol) >= 2


def _with_ends(seed, angle, lo, hi):
    """A straight slot with ends S1, S2 on its line, lo and hi from the pin (FORMAT.md ``ends``)."""
    d = M.pin_in_slot(seed, angle, "pin")
    d["slots"][0].pop("along", None)
    ang = d["slots"][0]["angle"]
    d["points"]["S1"] = {"from": "A", "length": lo, "angle": ang + 180}
    d["points"]["S2"] = {"from": "A", "length": hi, "angle": ang}
    d["links"]["3"]["points"] += ["S1", "S2"]
    try:   # the loader knows ends (issue 13 item 6)
        d["slots"][0]["ends"] = ["S1", "S2"]
        m = velpoly.load(d)
    except InputError:   # not yet: the same slot, its ends given to the drawing directly
        del d["slots"][0]["ends"]
        m = velpoly.load(d)
        object.__setattr__(m.slots[0], "ends", ("S1", "S2"))
    return velpoly.solve(m)


@pytest.mark.parametrize("seed,angle", [(0, 20.0), (1, 110.0), (2, 200.0), (3, 290.0)])
def test_slot_between_its_ends(seed, angle):
    sol = _with_ends(seed, angle, 1.0, 2.5)
    art, tol = _drawn(sol)
    _check_slot(sol, art, tol, ends=("S1", "S2"))


@pytest.mark.parametrize("path", GALLERY, ids=os.path.basename)
def test_gallery_ground_crosses_no_moving_link(path):
    """Every gallery file: the ground's hatching crosses no moving link; a slot is cut in its link. Example 3.4
    (its own test until issue 19 item 7, which drew it a second time): the lever's slot runs along C -> A and
    its cut stops before the pivot C."""
    sol = velpoly.solve(velpoly.load(path))
    art, tol = _drawn(sol)
    assert _check_ground(art, tol) >= 1
    if sol.mechanism.slots:
        _check_slot(sol, art, tol)
    if os.path.basename(path) == "ex3_4_slotted_lever.toml":
        (link, line, cut), = art.slot_cuts.values()
        assert cut.distance(Point(*sol.place("3", "C"))) > 0


@pytest.mark.parametrize("seed,angle,follower", [(0, 20.0, "curved"), (1, 200.0, "curved"), (2, 110.0, "flat"),
                                                 (3, 290.0, "flat"), (4, 65.0, "translating")])
def test_sliding_cam_ground_and_equivalent_linkage(seed, angle, follower):
    """A sliding cam: ground clear of the moving links; its equivalent linkage drawn dashed, joining the
    two centres of curvature (or a block at the centre facing a flat), and named in the caption."""
    from velpoly.render.displacement import equivalent_linkage_note
    sol = velpoly.solve(velpoly.load(M.sliding_cam(seed, angle, follower)))
    art, tol = _drawn(sol)
    _check_ground(art, tol)
    c = sol.mechanism.contacts[0]
    lines = [ln for ln in art.get("equivalent", []) if hasattr(ln, "get_xydata")]
    assert lines and all(ln.get_linestyle() == "--" for ln in lines)
    centres = [np.asarray(sol.place(lk, n), float) for lk, n in zip(c.links, c.centres) if n is not None]
    xy = np.asarray(lines[0].get_xydata())
    if len(centres) == 2:   # the coupler: from one centre to the other
        assert np.allclose(sorted(map(tuple, xy)), sorted(map(tuple, centres)), atol=tol)
    else:                   # the block's path: through the centre, along the common tangent
        t = np.array([-math.sin(math.radians(float(sol.motion.contacts[0]["normal"][0]))),
                      math.cos(math.radians(float(sol.motion.contacts[0]["normal"][0])))])
        assert LineString([tuple(p) for p in xy]).distance(Point(*centres[0])) <= tol
        e = xy[-1] - xy[0]
        assert abs(float(e[0] * t[1] - e[1] * t[0])) <= tol * np.hypot(*e)
    assert equivalent_linkage_note(sol.mechanism) == "dashed: equivalent linkage"
