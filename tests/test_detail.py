"""A polygon crushed by one long vector gets an enlarged detail (issue 17, item 3; render/detail.py).

The rule, re-implemented here from its statement (docs/figures.md): on paper at the panel's scale, the
polygon's points (origin, images, auxiliary images) closer than 1.3 cm (or a sixth of the polygon's larger
side, if more) are joined; the origin's group gets
a detail when it holds at least 4 distinct points, its box's larger side is at most 3 cm and the whole
polygon's is at least 3 times larger. Checked on generated mechanisms where one link carries a point far
from the rest (its image far longer than the others), on the gallery's sheets, and the detail itself at
the data level: its images at their true positions times its stated scale, its caption that scale.
"""
from __future__ import annotations

import re

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import velpoly
from velpoly.errors import VelpolyError
import sheets
import zoo
from paths import EXAMPLES
from velpoly.polygons import acceleration_polygon, velocity_polygon
from velpoly.render import sheet
from velpoly.render.detail import crowd as crowd_of
from velpoly.render.canvas import fit_view, per_cm, view_scale
from velpoly.render.polygon import draw_polygon, polygon_bounds
from velpoly.render.scalebar import scale_text
from velpoly.render.style import get_style, rc_context

REL = 1e-9


def expected(poly, unit_per_cm) -> bool:
    """The rule, brute force: the origin's group by repeated joining of points closer than 1.3 cm."""
    pts = [np.zeros(2)] + [np.asarray(v, float) for v in poly.images.values()] + \
        [np.asarray(a.image, float) for a in poly.auxiliary.values()]
    size = max(float(np.hypot(*p)) for p in pts) or 1.0
    distinct = []
    for p in pts:
        if not any(np.hypot(*(p - q)) <= 1e-9 * size for q in distinct):
            distinct.append(p)
    xy = np.array(distinct) / unit_per_cm        # cm of paper
    d = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
    p_cm = float((xy.max(0) - xy.min(0)).max())
    join = max(1.3, p_cm / 6)
    group = d[0] < join
    for _ in range(len(xy)):
        group = group | (d[group] < join).any(axis=0)
    g = xy[group]
    g_cm = float((g.max(0) - g.min(0)).max())
    return len(g) >= 4 and g_cm <= 3.0 and p_cm >= 3.0 * g_cm


PANEL = (0.34, 0.37, 0.32, 0.485)   # a polygon's panel of a full sheet (fractions of the page): a third of its width


def _panel(style="textbook", rect=PANEL):
    st = get_style(style)
    fig = Figure(figsize=st.figsize, dpi=72)
    FigureCanvasAgg(fig)
    return fig.add_axes(rect)


def _draw(sol, poly, style="textbook"):
    ax = _panel(style)
    fit_view(ax, polygon_bounds(poly), margin=0.08)
    ax.set_axis_off()
    pc = per_cm(ax)
    with rc_context(get_style(style)):
        art = draw_polygon(poly, ax, mechanism=sol.mechanism, style=style)
    assert per_cm(ax) >= pc * (1 - REL)      # kept, or made coarser to give the detail its room
    return ax, per_cm(ax), art


def check_detail(sol, poly, ax, pc, art):
    """The detail of a drawn polygon: where the rule says, at its stated scale, its images true."""
    det = art.detail
    assert (det is not None) == expected(poly, pc), (poly.kind, pc)
    if det is None:
        assert "detail" not in art
        return
    assert view_scale(ax) == pytest.approx(pc, rel=REL)              # the panel's scale as stated
    s = det.scale
    assert s <= pc / 2 * (1 + REL)                                    # enlarged at least twice
    units = sol.mechanism.units
    power = 1 if poly.kind == "velocity" else 2
    assert det.caption.get_text() == "detail, " + scale_text(s, units, power)
    number = float(re.search(r"= ([0-9.e+-]+)", det.caption.get_text()).group(1))
    assert number == pytest.approx(s, rel=1e-12)
    assert per_cm(det.ax) == pytest.approx(s, rel=REL) and view_scale(det.ax) == s
    # every image of the marked region at its true position times the detail's scale, on paper
    fig = ax.figure
    to_cm = 2.54 / fig.dpi
    o = det.ax.transData.transform([0.0, 0.0])
    inside = [k for k in poly.images if det.region.contains(_pt(poly.images[k]))]
    assert len(inside) >= 3
    for k in inside:
        p = np.asarray(poly.images[k], float)
        got = (det.ax.transData.transform(p) - o) * to_cm
        assert np.allclose(got, p / s, rtol=0, atol=REL * max(np.hypot(*p) / s, 1e-300) + 1e-9)
        assert art.labels[k] in det.art["labels"]                    # labelled in the detail
    # its arrows are the panel's vectors (the same constructions, in the detail's data units)
    panel = {(k, tuple(np.round(t, 9)), tuple(np.round(h, 9))) for k, t, h, _ in art.arrows}
    for kind, tail, head, patch in det.art.arrows:
        assert (kind, tuple(np.round(tail, 9)), tuple(np.round(head, 9))) in panel
        assert np.hypot(*(patch.get_xy()[0] - patch._velpoly_shift - head)) <= REL * max(np.hypot(*head), 1.0)
    # the region holds the crowd; the frame lies in the panel, clear of the region
    for k in det.crowd.keys:
        q = poly.images[k] if k in poly.images else poly.auxiliary[k].image
        assert det.region.contains(_pt(q))
    from velpoly.render.canvas import view_box
    assert view_box(ax).buffer(1e-9 * pc).contains(det.frame)
    assert not det.frame.intersects(det.region)


def _pt(p):
    from shapely.geometry import Point
    return Point(float(p[0]), float(p[1]))


def _far_point(mech: dict, rng, far=(1.0, 3.0, 8.0, 15.0, 30.0)) -> dict:
    """The specimen with a point Z on one moving link, far out along it: that link's far image is long."""
    links = [k for k, v in mech["links"].items() if not v.get("frame") and len(v["points"]) >= 2]
    lk = links[int(rng.integers(len(links)))]
    a, b = mech["links"][lk]["points"][:2]
    m = velpoly.load(mech)
    xy = np.array([m.position(p) for p in m.point_order if not m.link(m.carriers[p][0]).frame] or [[0, 0]])
    size = float(np.ptp(xy, axis=0).max()) or 1.0
    far = float(rng.choice(list(far)))
    out = {**mech, "points": dict(mech["points"]), "links": {k: dict(v) for k, v in mech["links"].items()}}
    out["points"]["Z"] = {"from": a, "length": far * size, "along": [a, b], "turn": float(rng.uniform(-40, 40))}
    out["links"][lk]["points"] = list(mech["links"][lk]["points"]) + ["Z"]
    return out


def test_detail_where_the_rule_says_on_generated_mechanisms():
    """Seeded zoo mechanisms, one link given a point far from the rest (1 to 30 sizes out): the rule's
    function picks the crowds the brute-force rule picks, on every polygon; drawn (a sample of each side),
    the detail appears exactly where the rule says, its images true at its stated scale."""
    from velpoly.render.detail import crowd
    rng = np.random.default_rng(17)
    drawn = {True: 0, False: 0}
    for sp in zoo.zoo(seed=1703, count=18):
        try:
            sol = velpoly.solve(velpoly.load(_far_point(sp.mech, rng)))
        except VelpolyError:
            continue
        for poly in [velocity_polygon(sol)] + ([acceleration_polygon(sol)] if sol.has_accelerations else []):
            ax = _panel()
            pc = fit_view(ax, polygon_bounds(poly), margin=0.08)
            want = expected(poly, pc)
            assert (crowd(poly, pc) is not None) == want
            if drawn[want] < (4 if want else 2):   # (6 and 3 until the suite had to fit 2 minutes)
                ax, pc, art = _draw(sol, poly)
                check_detail(sol, poly, ax, pc, art)
                drawn[want] += 1
    assert drawn == {True: 4, False: 2}, drawn


@pytest.mark.parametrize("style, name, kind", [("textbook", "ex3_4_slotted_lever", "velocity"),
                                               ("textbook", "ex3_10_rolling_contact", "acceleration"),
                                               ("textbook", "cam_roller_follower", "acceleration"),
                                               ("slides", "ex3_4_slotted_lever", "velocity")])
def test_crushed_gallery_polygons_get_their_detail(style, name, kind):
    """Example 3.4's velocity polygon (a₂ five times the rest), Example 3.10's and the roller follower's
    acceleration polygons (d₅′) are drawn with a detail, textbook; Example 3.4's in slides too (what is checked,
    the detail where the rule says, at its stated scale, its images true, is the style's only through the
    panel's size: the other two in slides were cut by issue 19 item 7; Example 3.10's slide draws its detail in
    its full sheet, test_example_3_10_full_sheet_detail_has_its_room)."""
    sol = sheets.solved(name)
    poly = velocity_polygon(sol) if kind == "velocity" else acceleration_polygon(sol)
    ax, pc, art = _draw(sol, poly, style)
    assert art.detail is not None
    check_detail(sol, poly, ax, pc, art)


def test_step_frames_keep_the_finished_detail():
    """--steps: every frame has the finished construction's detail, in the same place at the same scale."""
    sol = velpoly.solve(velpoly.load(EXAMPLES / "ex3_4_slotted_lever.toml"))
    cons = sheet.constructions(sol, "velocity")
    st = get_style("textbook")
    fr = sheet.frames("velocity", cons, True)

    def detail(fig):
        ax = next(a for a in fig.axes if a.get_label() == "velocity")
        frame = next(p for p in ax.patches if p.get_gid() == "detail-frame")
        cap = next(t for t in ax.texts if t.get_gid() == "detail-caption")
        return tuple(np.round(frame.get_bbox().bounds, 9)), cap.get_text(), ax.get_xlim(), ax.get_ylim()
    with rc_context(st), sheets.unlabelled_mechanism():   # the velocity polygon's detail read
        last = sheet.render_sheet(sol, "velocity", st, cons=cons, frame=fr[-1])
        first = sheet.render_sheet(sol, "velocity", st, cons=cons, frame=fr[0], pins=last._velpoly_pins)
    assert detail(first) == detail(last)


# (left, bottom, width, height) of a panel on the page: a narrow tall column, a full sheet's third, a wide
# short band, a small square
PANELS = [(0.05, 0.1, 0.22, 0.7), PANEL, (0.1, 0.1, 0.6, 0.35), (0.3, 0.2, 0.3, 0.3)]


def test_detail_frames_cover_nothing_of_their_panel_on_generated_mechanisms():
    """Seeded zoo mechanisms, one link given a point 8 to 30 sizes out (its image far longer than the rest),
    six crushed polygons (ten until the suite had to fit 2 minutes) drawn in panels of four shapes in turn: the detail's frame covers no link image,
    vector, construction line, label, reason, legend or scale bar of its panel, nor the region it enlarges,
    and stays in its panel (a panel with no room for it at its scale has the scale made coarser, as the
    caption and the scale bar state, the detail still at least twice as fine)."""
    from frame_checks import frame_clashes
    rng = np.random.default_rng(1721)
    drawn, kinds, scales = 0, set(), []
    for sp in zoo.each(seed=1721, count=16):   # made as they are looked at: 6 of the 16
        if drawn == 6:
            break
        try:
            sol = velpoly.solve(velpoly.load(_far_point(sp.mech, rng, far=(8.0, 15.0, 30.0))))
        except VelpolyError:
            continue
        for poly in [velocity_polygon(sol)] + ([acceleration_polygon(sol)] if sol.has_accelerations else []):
            rect = PANELS[drawn % len(PANELS)]
            ax = _panel(rect=rect)
            pc0 = fit_view(ax, polygon_bounds(poly), margin=0.08)
            if crowd_of(poly, pc0) is None or drawn == 6:
                continue
            ax.set_axis_off()
            with rc_context(get_style("textbook")):
                art = draw_polygon(poly, ax, mechanism=sol.mechanism, style="textbook")
            assert art.detail is not None
            pc = per_cm(ax)
            assert view_scale(ax) == pytest.approx(pc, rel=REL) and pc >= pc0 * (1 - REL)
            assert art.detail.scale <= pc / 2 * (1 + REL)
            clashes = frame_clashes(ax)
            assert not clashes, (sp.kind, poly.kind, rect, clashes)
            drawn += 1
            kinds.add(poly.kind)
            scales.append(pc / pc0)
    assert drawn == 6 and kinds == {"velocity", "acceleration"}, (drawn, kinds)


@pytest.mark.parametrize("style", [pytest.param(st, marks=sheets.on(st)) for st in sheets.STYLES])
def test_example_3_10_full_sheet_detail_has_its_room(style):
    """Example 3.10's acceleration polygon on the full sheet: where the page's layout gives it a column in
    which the rule calls for a detail, no free place held the detail at the planned scale (its frame lay
    over the polygon and ran above the panel) and the panel's scale is made coarser until one does; where
    the layout gives it room enough (the tall corner column), the rule calls for none at the scale drawn.
    Either way the caption states the scale drawn."""
    from frame_checks import frame_clashes
    sol = sheets.solved("ex3_10_rolling_contact")
    fig = sheets.page("ex3_10_rolling_contact", "full", style)   # the gallery's page, shared: read only
    ax = next(a for a in fig.axes if a.get_label() == "acceleration")
    cap = next(t for t in fig.texts if t.get_gid() == "caption-acceleration")
    assert cap.get_text().endswith("(" + scale_text(view_scale(ax), sol.mechanism.units, 2) + ")")
    assert view_scale(ax) == pytest.approx(per_cm(ax), rel=REL)
    if not any(p.get_gid() == "detail-frame" for p in ax.patches):
        assert crowd_of(acceleration_polygon(sol), view_scale(ax)) is None
        return
    assert not frame_clashes(ax)
    inset = next(t for t in ax.texts if t.get_gid() == "detail-caption")
    s = float(re.search(r"= ([0-9.e+-]+)", inset.get_text()).group(1))
    assert s <= view_scale(ax) / 2 and per_cm(ax.child_axes[0]) == pytest.approx(s, rel=REL)


def test_detail_frames_that_covered_their_panel():
    """The generated polygons (a seeded zoo, points 1 to 30 sizes out) whose detail's frame covered part of
    their panel when the frame took the place meeting the fewest marks (a link image, vectors, or beyond the
    panel's edge): now clear of everything (the frame keeps off link images; a panel with no room has its
    scale made coarser)."""
    from frame_checks import frame_clashes
    cases = {(13, "velocity"): 3, (16, "acceleration"): 3, (27, "velocity"): 2, (27, "acceleration"): 0}
    rng = np.random.default_rng(17)
    wanted = {i for i, _ in cases}
    for i, sp in enumerate(zoo.zoo(seed=1703, count=28)):
        mech = _far_point(sp.mech, rng)   # (every specimen draws from rng)
        if i not in wanted:
            continue                      # (solved only where a case is)
        try:
            sol = velpoly.solve(velpoly.load(mech))
        except VelpolyError:
            continue
        for poly in [velocity_polygon(sol)] + ([acceleration_polygon(sol)] if sol.has_accelerations else []):
            if (i, poly.kind) not in cases:
                continue
            ax = _panel(rect=PANELS[cases.pop((i, poly.kind))])
            fit_view(ax, polygon_bounds(poly), margin=0.08)
            ax.set_axis_off()
            with rc_context(get_style("textbook")):
                art = draw_polygon(poly, ax, mechanism=sol.mechanism, style="textbook")
            assert art.detail is not None
            assert not frame_clashes(ax), (i, sp.kind, poly.kind, frame_clashes(ax))
    assert not cases
