"""Crowded poles sheets get the room their poles need (issue 17, items 4 and 2).

An eight-bar has 28 poles and some ten points to label; drawn in the poles sheet's old layout (its table
shown whole, the drawing shrunk for it, the view holding every pole within 2.5 mechanism sizes) its links
took a few centimetres of a slide, and the pole labels' leaders crossed in dozens of pairs
(benchmarks/leaders_zoo.py: 133 crossing pairs on zoo(2026, 60)'s six eight-bar poles sheets). The specimens
here are the eight-bars of a seeded stream, one of each variant (drawn by the seed, not picked by hand),
checked at the data level: the poles panel's scale as planned (the links' box on paper for each label); and on
a crowded six-bar's slide, drawn, the leaders (Line2D data) that cross.
"""
from __future__ import annotations

import functools
import itertools

import numpy as np
import pytest
from matplotlib.figure import Figure
from shapely.geometry import LineString, Point

import zoo
from velpoly.render import sheet
from velpoly.render.canvas import per_cm, view_box
from velpoly.render.displacement import mechanism_bounds
from velpoly.render.labels import placer
from velpoly.render.style import get_style, rc_context
from velpoly.render.textcache import new_canvas

SEED = 17
EIGHTS = [v for k, v in zoo.variants() if k == "eight-bar"]


@functools.cache
def eight(variant: str):
    """The seeded eight-bar of ``variant`` (a generator of its own per variant: each draw independent)."""
    return zoo.specimen(np.random.default_rng(SEED), "eight-bar", variant).drawn


def planned(sol, style: str):
    """The poles sheet's plan (:func:`velpoly.render.sheet._plan`, what ``render`` lays out): its poles scale."""
    st = get_style(style)
    with rc_context(st):
        fig = Figure(figsize=st.figsize, dpi=72)
        new_canvas(fig)
        cons = sheet.constructions(sol, "poles")
        top = sheet._top(fig, st, sheet._page(fig, st, sol.mechanism, sol), "", False)
        return sheet._plan(fig, sol, st, sheet.drawing_options(sol.mechanism), cons, "poles", top, True)


def room_per_label(sol, style: str) -> float:
    """The paper (cm²) of the links' box on the planned poles panel for each pole's and point's label, at 10-pt
    type (a larger type's as its square)."""
    x0, y0, x1, y1 = mechanism_bounds(sol)
    s = planned(sol, style).scales["poles"]
    n = len(sheet.constructions(sol, "poles").poles.poles) + len(sol.mechanism.points)
    return (x1 - x0) * (y1 - y0) / s ** 2 / n / (get_style(style).font_size / 10) ** 2


@pytest.mark.parametrize("variant", EIGHTS)
def test_an_eight_bar_slide_gives_its_labels_room(variant):
    """On its slide, each eight-bar's links' box gives each of its 38 labels at least 0.75 cm² (10-pt type): 0.81
    to 1.85 now, 0.17, 0.52 and 0.67 before (the links a few centimetres wide in a panel as wide as the slide)."""
    assert room_per_label(eight(variant), "slides") >= 0.75, variant


@pytest.mark.parametrize("seed, variant", [(3, "stephenson I")])
def test_a_crowded_six_bar_slide_has_leaders_apart(seed, variant):
    """A seeded six-bar's poles slide, drawn: no two leaders of which one is a pole label's cross, and every pole
    label in view stands nearer its own ring than any other or has its leader from its own ring. The Stephenson
    I had two crossing pairs before the crowded layout (its links 6 x 7 cm over a table of 6 of its 13 rows, now
    10 x 11 cm beside a table of 11). The Stephenson III six-bar of seed 9 (P35's leader across P46's on 39e3408
    and 5ffbd6b, the three labels placed again now: kennedy._clear_of_all) was cut by issue 19 item 7, the suite's
    costliest test (10-11 CPU s): with kennedy._clear_with_third disabled by hand it fails, and so does
    test_fig17_leaders' six-bar 10 of seed 5 (its drawing 3-6 CPU s, P25's leader then across P26's)."""
    from test_leaders_zoo import astray
    sol = zoo.specimen(np.random.default_rng(seed), "six-bar", variant).drawn
    st = get_style("slides")
    with rc_context(st):
        fig = sheet.render(sol, "poles", st).figure
        ax = next(a for a in fig.axes if a.get_label() == "poles")
        lines = {p.text.get_gid(): LineString(np.column_stack(p.leader.get_data())) for p in placer(ax).labels
                 if p.leader is not None}
        crossed = [(a, b) for a, b in itertools.combinations(sorted(lines), 2)
                   if "label-pole-" in a + b and lines[a].intersects(lines[b])]
        assert not crossed
        rings = {key: Point(*p.position).buffer(0.085 * per_cm(ax)) for key, p in
                 sheet.constructions(sol, "poles").poles.poles.items() if p.position is not None
                 and view_box(ax).contains(Point(*p.position))}
        assert not astray(ax, rings)


def _layouts(sol, style: str, which=(0, -1)):
    """The poles sheet of ``sol`` laid out without ``--steps`` and as its frames ``which`` (indices into
    :func:`velpoly.render.sheet.frames`), each rendered with its panels left empty (the plan is what is compared):
    for each, the plan's poles scale, view (``reach``) and every panel's box, and the figure."""
    st = get_style(style)
    out = []
    real = sheet._draw_panels

    def plan_only(sol, axes, st, opts, cons, name, frame, plan, pins):
        fig = next(iter(axes.values())).figure
        fig.plan = plan
        return {}
    sheet._draw_panels = plan_only
    try:
        with rc_context(st):
            cons = sheet.constructions(sol, "poles")
            fr = sheet.frames("poles", cons, True)
            for frame in [None] + [fr[k] for k in which]:
                fig = sheet.render(sol, "poles", st, cons=cons, frame=frame).figure
                boxes = {a.get_label(): tuple(np.round(a.get_position().bounds, 9)) for a in fig.axes
                         if a.get_label() in ("poles", "kennedy")}
                out.append(((fig.plan.scales["poles"], fig.plan.reach, boxes), fig))
    finally:
        sheet._draw_panels = real
    return out


@pytest.mark.parametrize("variant", EIGHTS[:1])
def test_a_crowded_sheets_step_frames_keep_its_layout(variant):
    """A crowded poles slide's ``--steps`` frames (the first, without the table, and the last, with it) draw the
    mechanism at the plain sheet's scale and view, the poles panel and the Kennedy circle where the plain sheet has
    them (before, each frame was laid out anew under its caption: the crank shaper's slide at 1 cm = 60 mm against
    the sheet's 50 mm); the step's caption stands clear of both panels, in the page, and of the last frame's
    table."""
    from render_contract import assert_page_texts_clear
    from velpoly.render.canvas import renderer_of
    (plain, _), *frames = _layouts(eight(variant), "slides")
    for got, fig in frames:
        assert got == plain, variant
        assert_page_texts_clear(fig)   # (title, captions: on the page, clear of each other and of the panels)
        r = renderer_of(fig)
        cap = next(t for t in fig.texts if t.get_gid() == "step-caption")
        pad = (0.3 * cap.get_fontsize() + 1.0) * fig.dpi / 72   # its box's pad and outline (laid out when drawn)
        bb = cap.get_window_extent(r).expanded(1, 1).padded(pad)
        page = fig.bbox
        assert page.x0 <= bb.x0 and bb.x1 <= page.x1 and page.y0 <= bb.y0 and bb.y1 <= page.y1
        for ax in fig.axes:
            if ax.get_label() in ("poles", "kennedy"):
                assert not bb.overlaps(ax.bbox), (variant, ax.get_label())
            if ax.get_label() == "table":
                assert all(not bb.overlaps(t.get_window_extent(r)) for t in ax.texts if t.get_text()), variant
