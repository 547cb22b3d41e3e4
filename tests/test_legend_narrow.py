"""A tall legend beside its polygon in a wide, low panel (issue 17, the layout leftovers, item 4).

A polygon's legend that finds no free place in its panel gets a strip kept for it, along the panel's top or its
right (``polygon.legend_room``), the polygon then drawn a round scale or more smaller. A legend of five kinds
(absolute, normal, tangential, Coriolis, slip) in slide type is 3.2 cm tall in one column and 10-12 cm wide in
two: in a slide's wide, low panel either strip cost Example 3.3's acceleration polygon half its length
(1 cm = 3000 units/s², where the panel without a legend draws it at 1500). The legend's narrow variant (one
column, each entry in two lines, ``polygon.NARROW``) stands in a strip at the polygon's side.

Checked on the acceleration polygons of generated mechanisms with four or five kinds (tests/zoo.py: inverted
slider-cranks, slots, contacts), in low panels of a slide's and a page's shape, in both styles: drawn with the
narrow variant, no polygon is drawn smaller than both without it and as planned, the legend names the kinds drawn (its lines
joined: the style's names), lies in its panel and meets none of its labels. (Generated polygons leave a corner
free for the legend; Example 3.3's fills its panel: there the narrow variant draws it larger.)
"""
from __future__ import annotations

import pytest
from shapely.geometry import box

from velpoly.render import polygon, sheet
from velpoly.render.canvas import nice_scale
from velpoly.render.layout import MARGIN
from velpoly.render.options import drawing_options
from velpoly.render.style import KIND_LABELS, get_style, rc_context

import zoo

# (style, panel's width and height in cm): a slide's acceleration panel beside two others over its table, a
# textbook page's
PANELS = [("slides", (11.7, 6.0)), ("textbook", (8.0, 5.0)), ("slides", (10.5, 5.5))]
EX33 = ("slides", (11.7, 7.43))   # Example 3.3's acceleration panel on its slide


@pytest.fixture(scope="module")
def tall():
    """Generated mechanisms whose acceleration polygons draw four kinds or more (their legends are tall)."""
    out = []
    for sp in zoo.each(23, 40):   # made as they are looked at: 15 of the 40 (zoo.zoo(23, 40) made all 40)
        if sp.kind.split()[0] not in ("inverted", "slot", "contact"):
            continue
        cons = sheet.constructions(sp.drawn, "full")
        poly = cons.acceleration
        kinds = {v.kind for s in poly.steps for v in s.vectors} if poly is not None else set()
        if len(kinds) >= 4:
            out.append((sp, poly))
        if len(out) == len(PANELS):   # one a panel shape (six until the suite had to fit 2 minutes)
            break
    assert len(out) == len(PANELS), len(out)
    # and Example 3.3's (its five kinds crowd the panel: no corner is free)
    import velpoly
    from paths import example
    sol = velpoly.solve(velpoly.load(example("ex3_3_inverted_slider")))
    ex = zoo.Specimen("Example 3.3", {}, (), drawn=sol)
    return out + [(ex, sheet.constructions(sol, "full").acceleration)]


def _panel(sp, poly, style, size, variants, monkeypatch):
    """The acceleration polygon of ``sp`` drawn in a panel ``size`` cm as a sheet draws it, with the legend's
    ``variants``: (its scale, the legend, the axes, the figure, the scale planned for the panel)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    monkeypatch.setattr(polygon, "LEGEND_VARIANTS", variants)
    st = get_style(style)
    with rc_context(st):
        fig = Figure(figsize=st.figsize, dpi=72)
        FigureCanvasAgg(fig)
        W, H = fig.get_figwidth() * 2.54, fig.get_figheight() * 2.54
        ax = fig.add_axes((0.5 / W, 0.5 / H, size[0] / W, size[1] / H), label="acceleration")
        # the scale a sheet plans for the panel (velpoly.render.layout.share_row: the round scale that fits it)
        x0, y0, x1, y1 = polygon.polygon_bounds(poly)
        mx, mt, mb = MARGIN
        planned = nice_scale(max((x1 - x0) / (size[0] - 2 * mx), (y1 - y0) / (size[1] - mt - mb)))
        sheet._draw_polygon_panel(sp.drawn, ax, st, drawing_options(sp.drawn.mechanism), poly, None, planned, 2,
                                  None)
        fig.draw_without_rendering()
    leg = ax.get_legend()
    return ax._velpoly_placer.placed["_scale"][1], leg, ax, fig, planned


def test_narrow_legend_draws_polygons_no_smaller(tall, monkeypatch):
    """Every generated polygon with a tall legend, in each panel shape, and Example 3.3's: with the narrow variant
    no smaller than both without it and as planned (Example 3.3's larger than without it); the legend names the
    kinds drawn, in its panel, off its labels."""
    every = polygon.LEGEND_VARIANTS
    wide_only = tuple(v for v in every if v[1] != polygon.NARROW)
    assert len(wide_only) == len(every) - 2
    larger = narrow_used = 0
    for i, (sp, poly) in enumerate(tall):
        style, size = PANELS[i % len(PANELS)] if i < len(tall) - 1 else EX33
        before, *_ = _panel(sp, poly, style, size, wide_only, monkeypatch)
        after, leg, ax, fig, planned = _panel(sp, poly, style, size, every, monkeypatch)
        # never coarser than both the plan and the drawing without the narrow variant (a strip at the top can
        # draw a polygon a little finer than planned: its view keeps less margin than the plan's)
        assert after <= max(before, planned) * (1 + 1e-9), \
            f"{sp.kind}/{style}: 1 cm = {after}, {before} without the narrow legend, {planned} planned"
        larger += after < before * (1 - 1e-9)
        texts = [t.get_text() for t in leg.get_texts()]
        narrow_used += any("\n" in t for t in texts)
        arrows = {(a.get_gid() or "").split("-")[0] for a in ax.patches}   # each arrowhead's gid: KIND-TAIL-HEAD
        drawn = [k for k in get_style(style).kind_styles if k in arrows]
        assert [t.replace("\n", " ") for t in texts] == [KIND_LABELS[k] for k in drawn], (sp.kind, texts)
        r = fig.canvas.get_renderer()
        lb = leg.get_window_extent(r)
        pb = ax.get_window_extent(r)
        assert pb.x0 - 1 <= lb.x0 and lb.x1 <= pb.x1 + 1 and pb.y0 - 1 <= lb.y0 and lb.y1 <= pb.y1 + 1, sp.kind
        lbox = box(lb.x0, lb.y0, lb.x1, lb.y1)
        for t in ax.texts:
            if (t.get_gid() or "").startswith("label") and t.get_text():
                tb = t.get_window_extent(r)
                assert lbox.intersection(box(tb.x0, tb.y0, tb.x1, tb.y1)).area < 1.0, (sp.kind, t.get_text())
    # Example 3.3's polygon at 1 cm = 2000 units/s² with the narrow legend at its side, 3000 without it
    assert larger >= 1 and narrow_used >= 1 and after < before, (larger, narrow_used, before, after)
