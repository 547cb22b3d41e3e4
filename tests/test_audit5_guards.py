"""Outside check, audit 5: three steps of the figures that no test failed without (each disabled by hand on main
9284ddd, the whole suite passed), each checked now on a generated mechanism where it decides what is drawn.

1. ``kennedy._off_drawn_lines`` (a pole's label whose free place lies on a drawn line, a slider's path, placed
   again off it): the quick-return six-bar ``zoo(2026)[37]``'s poles drawing on slides puts P45 on a drawn line
   without it.
2. ``LabelPlacer.relocate`` (a label whose leader still crosses moved to where it covers least): the inverted
   slider-crank ``zoo(2026)[19]``'s poles drawing on slides leaves the driver's value on link 4's number's leader
   without it.
3. the detail's pin in ``detail._place`` (a step frame's detail where the finished construction has it): the
   four-bar ``zoo(1703)[0]`` given a far point (as test_detail's), its velocity sheet's first step frame puts its
   detail elsewhere without it (test_detail's Example 3.4 has it in the same place either way).
"""
from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import LineString, box

import velpoly
from velpoly.render import sheet
from velpoly.render.canvas import renderer_of
from velpoly.render.style import get_style, rc_context

import sheets
import zoo
from test_detail import _far_point
from test_fig17_leaders import crossings
from test_pole_labels import _poles_drawing, texts_on_lines


def poles_drawing(index: int):
    """The slides poles drawing (its axes) of ``zoo(2026)[index]``."""
    sp = zoo.zoo(2026, index + 1)[index]
    return _poles_drawing(sp.drawn, get_style("slides"))[0], sp.kind


def pole_labels_on_drawn_lines(ax) -> list:
    """(label, line) of every pole label whose box on the canvas (shrunk by a pixel) meets a line drawn on ``ax``,
    leaders excepted."""
    r = renderer_of(ax.figure)
    lines = []
    for ln in ax.lines:
        xy = ax.transData.transform(np.asarray(ln.get_xydata(), float))
        xy = xy[np.isfinite(xy).all(axis=1)]
        if ln.get_visible() and not (ln.get_gid() or "").endswith("-leader") and len(xy) >= 2:
            lines.append((ln.get_gid() or ln.get_label(), LineString(xy)))
    out = []
    for t in ax.texts:
        if (t.get_gid() or "").startswith("label-pole-") and t.get_text() and t.get_visible():
            bb = t.get_window_extent(r)
            b = box(bb.x0, bb.y0, bb.x1, bb.y1).buffer(-1.0)
            out += [(t.get_gid(), g) for g, ln in lines if ln.intersects(b)]
    return out


def test_a_pole_label_keeps_off_a_drawn_line_where_a_place_off_it_is_free():
    ax, kind = poles_drawing(37)
    assert kind == "six-bar quick-return crank"
    assert pole_labels_on_drawn_lines(ax) == []


def test_a_label_whose_leader_crosses_is_moved_where_it_covers_least():
    ax, kind = poles_drawing(19)
    assert kind == "inverted slider-crank offset both slider"
    assert texts_on_lines(ax) == [] and crossings(ax) == []


def test_a_step_frame_has_the_finished_constructions_detail_on_a_generated_mechanism():
    sp = zoo.zoo(seed=1703, count=1)[0]
    sol = velpoly.solve(velpoly.load(_far_point(sp.mech, np.random.default_rng(17))))
    cons = sheet.constructions(sol, "velocity")
    st = get_style("textbook")
    fr = sheet.frames("velocity", cons, True)

    def detail(fig):
        ax = next(a for a in fig.axes if a.get_label() == "velocity")
        frame = [p.get_bbox().bounds for p in ax.patches if p.get_gid() == "detail-frame"]
        return np.round(frame, 9).tolist(), ax.get_xlim(), ax.get_ylim()
    with rc_context(st), sheets.unlabelled_mechanism():
        last = sheet.render_sheet(sol, "velocity", st, cons=cons, frame=fr[-1])
        first = sheet.render_sheet(sol, "velocity", st, cons=cons, frame=fr[0], pins=last._velpoly_pins)
    assert detail(last)[0], "the finished construction has a detail"
    assert detail(first) == detail(last)
