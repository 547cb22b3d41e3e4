"""A link of three or more joints reads as one rigid plate on the space diagram (issue 17, item 7;
render/displacement.py).

Joints are its pins, the points of the blocks it guides, the pins in its slots and its contact points (where it
has a profile), in any mix.
At the data level, on seeded zoo mechanisms of the classes whose ternary links carry a slot, a moving guide or a
profile (and a four-bar coupler with a coupler point, drawn as a bell-crank's bars): every such link is drawn as one patch, a single
polygon (no separate bars or pieces) holding all its joints, filled as plates are (not white in the textbook
style); and where the convex hull of its body covers no other link's point, the body is that hull (no notch where
a slotted bar meets the plate). Where the hull would cover another link's pivot (a slotted lever over the crank's
pivot) the body is the hull notched clear of it (a fork about the crank's pivot and its ground, a bite about
another link's pin; render/displacement.py ``bitten_plate``): one polygon, still at least half its hull (bars are
far less), keeping every foreign pivot's and pin's ring clear, and lying over no other link's body drawn beneath
it (the links crossing it are seen whole). Where no notch does that, it is the bell-crank's bars, joined.
"""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.colors import to_rgb
from shapely.geometry import Point
from shapely.ops import unary_union

import zoo
from mechanisms import shapes_only
from test_space_marks import _draw   # the space diagram alone in a 4 x 3 in panel
from velpoly.render.canvas import per_cm
from velpoly.render.style import get_style

# each had a link of three or more joints unfilled (white), in two pieces or notched on main 39e3408
CASES = [("inverted slider-crank", "swinging-block slider", 0, "textbook"),
         ("inverted slider-crank", "second-pin slider", 0, "textbook"),
         ("six-bar", "floating guide crank", 0, "slides"),
         ("six-bar", "floating guide slider", 0, "textbook"),
         ("slot", "circular", 0, "textbook"),
         ("contact", "cam oscillating follower", 0, "textbook"),
         ("four-bar", "crank-rocker", 0, "textbook")]

# a plate over another link's pivot or pin, drawn as a bell-crank's bars on main 19e5f21 (each fails there): now
# notched clear of it; a frame pivot's notch holds its ground
NOTCHED = [("six-bar", "watt II", 0, "textbook"),                 # a rocker's triangle over the coupler's pin
           ("six-bar", "stephenson III", 21, "textbook"),         # a coupler over a pivot
           ("six-bar", "slider on coupler point", 14, "textbook"),   # a coupler over the rocker's pivot
           ("four-bar", "crank-rocker", 23, "slides")]            # a coupler with its point over a pivot


def joints(m, link) -> set:
    """The names of a link's joints: its points, the points of the blocks it guides, its slots' pins, its contacts
    where it has a profile (one given by its normal alone draws none)."""
    out = set(m.link(link).points) | {s.point for s in m.sliders if s.guide == link}
    return out | {s.pin for s in m.slots if s.slot == link} | {c.point for c in m.contacts
                                                                if link in c.links and c.centres is not None}


def foreign_points(sol, link, own) -> list:
    """Where the points that neither ``link`` carries nor ``own`` names are now."""
    m = sol.mechanism
    return [sol.place(m.carriers[p][0], p) for p in m.point_order if m.carriers.get(p)
            and link not in m.carriers[p] and p not in own]


def _joint_places(sol, link) -> dict:
    """Each joint of ``link`` -> where it is now (a contact's point where the two profiles touch)."""
    m = sol.mechanism
    out = {}
    for j in joints(m, link):
        carrier = link if link in m.carriers.get(j, ()) else m.carriers[j][0] if m.carriers.get(j) else None
        out[j] = np.asarray(sol.place(carrier, j), float) if carrier is not None else None
    for c, r in zip(m.contacts, sol.motion.contacts):
        if link in c.links:
            out[c.point] = np.asarray(r["place"][0], float)
    return out


def plate_faults(sol, ax, art, style) -> list:
    """The links of three or more joints that do not read as one plate: (link, why)."""
    m, st = sol.mechanism, get_style(style)
    near = st.bar_width * per_cm(ax)      # a point this near a plate's hull is covered by it (a notch keeps clear)
    patches = {p.get_gid(): p for p in art.get("links", []) if p.get_gid()}
    blocks = {s.guide: set(m.link(s.block).points) for s in m.sliders}
    out = []
    for link in m.moving_links:
        lk = link.name
        if len(joints(m, lk)) < 3:
            continue
        patch, body = patches.get(f"link-{lk}"), art.bodies.get(lk)
        if patch is None or body is None or body.geom_type != "Polygon":
            out.append((lk, "not one piece"))
            continue
        if to_rgb(patch.get_facecolor()[:3]) == to_rgb(st.paper):
            out.append((lk, "unfilled"))
        tol = 0.01 * m.size        # a profile's circle is drawn as a polygon: its contact point on the chord
        if any(body.distance(Point(*q)) > tol for q in _joint_places(sol, lk).values() if q is not None):
            out.append((lk, "misses a joint"))
        own = joints(m, lk) | blocks.get(lk, set())
        hull = body.convex_hull
        covers = any(hull.distance(Point(*q)) < near for q in foreign_points(sol, lk, own))
        if not covers and body.area < 0.99 * hull.area:
            out.append((lk, "notched"))
    return out


def notch_faults(sol, ax, art, style) -> list:
    """The links of three or more joints whose body's hull covers another link's point, where the body does not read
    as one plate clear of it: (link, why)."""
    m, st = sol.mechanism, get_style(style)
    pc = per_cm(ax)
    patches = {p.get_gid(): p for p in art.get("links", []) if p.get_gid()}
    blocks = {s.guide: set(m.link(s.block).points) for s in m.sliders}
    out = []
    for link in m.moving_links:
        lk, body = link.name, art.bodies.get(link.name)
        if len(joints(m, lk)) < 3 or body is None:
            continue
        own = joints(m, lk) | blocks.get(lk, set())
        foreign = foreign_points(sol, lk, own)
        hull = body.convex_hull
        if not any(hull.distance(Point(*q)) < st.bar_width * pc for q in foreign):
            continue
        if body.area < 0.5 * hull.area:
            out.append((lk, "bars, not a plate"))
        if any(body.distance(Point(*q)) < st.pin_radius * pc for q in foreign):
            out.append((lk, "covers a pin's ring"))
        z = patches[f"link-{lk}"].get_zorder()
        mine = [np.asarray(sol.place(lk, q), float) for q in link.points]
        for k, g in art.bodies.items():   # the links drawn beneath it: not covered (but about a pin they share)
            if k == lk or patches[f"link-{k}"].get_zorder() > z:
                continue
            shared = [Point(*q).buffer(st.bar_width * pc) for q in mine if g.distance(Point(*q)) < 1e-9 * m.size]
            if body.intersection(g).difference(unary_union(shared)).area > (0.05 * pc) ** 2:
                out.append((lk, f"over link {k}"))
    return out


@pytest.mark.parametrize("kind, variant, seed, style", CASES)
def test_links_of_three_joints_are_plates(kind, variant, seed, style):
    sol = zoo.specimen(np.random.default_rng(seed), kind, variant).drawn
    assert any(len(joints(sol.mechanism, k.name)) >= 3 for k in sol.mechanism.moving_links)
    ax, art = _draw(sol, style, shapes_only(sol.mechanism))   # its shapes: no labels, no link numbers
    assert plate_faults(sol, ax, art, style) == []


@pytest.mark.parametrize("kind, variant, seed, style", NOTCHED)
def test_plates_notched_clear_of_other_links(kind, variant, seed, style):
    sol = zoo.specimen(np.random.default_rng(seed), kind, variant).drawn
    ax, art = _draw(sol, style, shapes_only(sol.mechanism))   # its shapes: no labels, no link numbers
    assert plate_faults(sol, ax, art, style) == []
    assert notch_faults(sol, ax, art, style) == []
