"""A crank over the plate it drives, and a short crank's number that reads as the crank's, in a crowded space diagram
(issue 17, items 7 and 4; render/displacement.py).

The crank-shaper class (six-bar quick-return crank: crank 2 pinned at A to block 3 in the slotted lever 4): where no
free place beside the crank reads as its own (the lever's plate under it, the rod near its middle, the driver's
values about its pivot), its circled number stands on the crank's own bar (the circle over the bar, the bar seen on
both sides of it, the crank drawn over the lever), as books draw it. At the data level, in a 4 x 3 in panel: every
number nearer its own link than any other and its leader across none, the driver's arrows across no other link, no
number or value on a line (a number on its own bar is on its own link: test_space_marks.on_own_bar), and the
crank's number on its crank, drawn over the crank, the crank over the lever.

A link of three or more joints whose plate would be notched about the pivot of a crank that lies over it (a slotted
lever, an inverted slider-crank's guide about its crank) is that notched plate, beneath the crank, where the marks
then read (displacement._Drawing.reads): one polygon, drawn beneath the crank, with every number nearer its own link,
the driver's arrows across no other link (alpha's arc its own arrow in its sense, clear of the plate: beside omega's
in the notch where beyond it the arc crossed the plate) and every point label off the links not its point's.
"""
from __future__ import annotations

import numpy as np
from shapely.geometry import LineString

import zoo
from test_space_diagram import check_driver
from test_space_marks import _data_box, _draw, driver_faults, line_faults, number_faults, on_own_bar, point_faults

# (seed, style): on main 6d815d8 each had the crank's number 2 nearer the lever or the rod than its crank (with a
# leader across the lever; 3 slides also on a line and the block's 3 astray)
CASES = [(19, "textbook"), (3, "slides"), (13, "slides")]


def test_crank_number_on_its_crank():
    for seed, style in CASES:
        sol = zoo.specimen(np.random.default_rng(seed), "six-bar", "quick-return crank").drawn
        ax, art = _draw(sol, style)
        assert number_faults(sol, ax, art) == [], (seed, style)
        assert driver_faults(sol, ax, art, style) == [], (seed, style)
        assert line_faults(ax, art) == [], (seed, style)
        t = next(t for t in art["link_numbers"] if t.get_gid() == "link-number-2")
        r = ax.figure.canvas.get_renderer()
        t.update_bbox_position_size(r)
        b = _data_box(ax, t.get_bbox_patch().get_window_extent(r))
        assert on_own_bar(ax, art, t.get_gid(), b), (seed, style)
        z = {p.get_gid(): p.get_zorder() for p in art["links"] if p.get_gid()}
        assert z["link-2"] > z["link-4"] and t.get_zorder() > z["link-2"]   # the crank over the lever, 2 on it


# (kind, variant, seed): on main 6d815d8 each lever or guide 4 was drawn as bars (displacement._Drawing.cranks_over);
# on main 7c7c973 the last two too: alpha's arc, beyond omega's, crossed the plate about the crank's pivot (now
# beside omega's at the same radius in the notch: displacement._Drawing._side_plans)
PLATED = [("inverted slider-crank", "curved crank", 1), ("six-bar", "quick-return crank", 3),
          ("inverted slider-crank", "curved crank", 0), ("inverted slider-crank", "offset both crank", 5)]


def test_plate_beneath_its_crank():
    for kind, variant, seed in PLATED:
        sol = zoo.specimen(np.random.default_rng(seed), kind, variant).drawn
        ax, art = _draw(sol, "textbook")
        assert "4" in art.notched, (variant, seed)
        plate = art.bodies["4"]
        assert plate.geom_type == "Polygon" and not plate.interiors
        crank = art.bodies["2"]
        z = {p.get_gid(): p.get_zorder() for p in art["links"] if p.get_gid()}
        assert z["link-2"] > z["link-4"] and plate.intersects(crank)   # the crank seen over the plate
        assert number_faults(sol, ax, art) == [], (variant, seed)
        assert driver_faults(sol, ax, art, "textbook") == [], (variant, seed)
        assert point_faults(sol, ax, art) == [], (variant, seed)
        check_driver(sol, art)   # omega's arc and alpha's, each its own arrow in its sense (alpha's two heads)
        if sol.mechanism.driver.alpha:   # alpha's arc clear of the plate (and of every link but the crank)
            (arc,) = [a for a in art["driver"] if a.get_gid() == "driver-alpha-arc"]
            assert not LineString(np.column_stack(arc.get_data())).intersects(plate), (variant, seed)
