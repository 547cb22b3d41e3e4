"""A plate over another link's frame pivot, drawn whole beneath the links, the crank over it (issue 17, item 7;
render/displacement.py ``_Drawing.underlays``).

A link of three or more joints whose plate (the hull of its joints) covers another link's frame pivot is notched
clear of it where a notch leaves one plate and the marks then read; where not (no notch leaves one polygon, the
crank over it too short for its number, the notched drawing's number astray or arcs across the plate) it was drawn
as bars on main 9945c0a: a bell-crank's arms that read as separate links. It is now its whole plate, lighter, beneath
every link: one polygon holding the hull of its joints, under every other link's body, the pivot's ground and every
pin (the crank over it seen whole, with its pins on top).

At the data level, in a 4 x 3 in panel (textbook), on generated mechanisms of the classes with such a link (zoo
specimens: an inverted slider-crank's slotted guide about its crank, a six-bar's coupler, a four-bar's coupler over
the crank's pivot): each such link's patch is one polygon covering its joints' hull (bars cover about a quarter to
three quarters of it), drawn beneath every other link's body, ground and pin (the crank over it, not covered), and
every link number reads as its link's (test_space_marks.number_faults).
"""
from __future__ import annotations

import numpy as np
from matplotlib.colors import to_rgb
from shapely.geometry import MultiPoint, Point, Polygon

import zoo
from test_space_marks import _draw, number_faults
from test_space_plates import joints
from velpoly.render.canvas import per_cm
from velpoly.render.style import get_style

# (kind, variant, seed): each such link was bars on main 9945c0a (refused: a number astray, the crank too short for
# its number, or no notch leaving one plate)
CASES = [("inverted slider-crank", "second-pin crank", 1), ("inverted slider-crank", "swinging-block crank", 1),
         ("six-bar", "slider on coupler point", 0), ("four-bar", "change-point", 5)]


def over_pivot(sol, bar_width) -> dict:
    """The moving links of three or more points whose joints' hull covers (within a bar width) a frame pivot of a
    link they do not carry: link -> that hull."""
    m, out = sol.mechanism, {}
    pivots = {pin.point for pin in m.pins if m.frame.name in pin.links}
    for link in m.moving_links:
        own = joints(m, link.name)   # its pins, its blocks' points, its slots' pins, its contact points
        pts = [tuple(sol.place(m.carriers[p][0], p)) for p in own if m.carriers.get(p)]
        if len(pts) < 3:
            continue
        hull = MultiPoint(pts).convex_hull
        if any(p not in own and link.name not in m.carriers[p] and hull.distance(Point(*sol.place(m.carriers[p][0], p))) < bar_width
               for p in pivots):
            out[link.name] = hull
    return out


def test_plate_beneath_the_links_over_it():
    for kind, variant, seed in CASES:
        sol = zoo.specimen(np.random.default_rng(seed), kind, variant).drawn
        ax, art = _draw(sol, "textbook")
        found = over_pivot(sol, get_style("textbook").bar_width * per_cm(ax))
        assert found, (variant, seed)
        patches = {p.get_gid(): p for p in art["links"] if p.get_gid()}
        for lk, hull in found.items():
            if lk in art.notched:   # notched clear of the pivot (tests/test_space_plates.py)
                continue
            rings = patches[f"link-{lk}"].get_path().to_polygons()
            assert len(rings) == 1, (variant, seed, lk)          # one polygon, not bars in pieces
            plate = Polygon(rings[0]).buffer(0)
            assert hull.difference(plate).area < 1e-6 * hull.area, (variant, seed, lk)   # the whole hull: a plate
            assert to_rgb(patches[f"link-{lk}"].get_facecolor()) != (1.0, 1.0, 1.0)      # filled
            z = patches[f"link-{lk}"].get_zorder()
            over = [p.get_zorder() for k, p in patches.items() if k != f"link-{lk}" and k.startswith("link-")]
            over += [a.get_zorder() for a in [*art.get("ground", []), *art.get("pins", [])]]
            assert over and min(over) > z, (variant, seed, lk)   # beneath every link, ground and pin: the crank seen
        assert number_faults(sol, ax, art) == [], (variant, seed)
