"""The figures, tested at the data level: what is drawn is the computed geometry.

Arrows end at the images, each image has one label, labels never overlap,
scale bars match the scale, the Kennedy circle has n points and n(n-1)/2
chords, output is reproducible and atomic, and the kernel never imports
matplotlib. Polygons are the hand-made ones of render_contract.py (the
six-bar, built like a textbook), so the drawing is checked independently of
velpoly.polygons; the gallery test renders every example with the real
constructions.
"""
from __future__ import annotations

import itertools
import subprocess
import sys
from pathlib import Path

import numpy as np
import shapely
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from shapely.geometry import Polygon as SPolygon
from shapely.geometry import box

import velpoly
from render_contract import SIXBAR, assert_page_texts_clear, load_sixbar, sixbar_acceleration, sixbar_velocity
from velpoly.errors import InputError
from velpoly.render import canvas, sheet
from velpoly.render.canvas import per_cm, tex, view_scale
from velpoly.render.displacement import draw_mechanism
from velpoly.render.labels import LabelPlacer, placer
from velpoly.render.polygon import draw_polygon
from velpoly.render.style import rc_context
import sheets
from paths import EXAMPLES

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def sixbar():
    return load_sixbar()


def _axes(size=(6, 5)):
    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    return fig.add_axes((0.02, 0.02, 0.96, 0.96))


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _display_box(ax, artist, shrink=0.3):
    """The artist's outline in display units, shrunk by ``shrink`` points (the placer pads by 1).

    A rotated text's outline is its rotated box, not the window extent around it.
    """
    from shapely import affinity
    r = ax.figure.canvas.get_renderer()
    rot = artist.get_rotation() if hasattr(artist, "get_rotation") else 0
    if rot:
        artist.set_rotation(0)
    bb = artist.get_window_extent(r)
    if rot:
        artist.set_rotation(rot)
    s = shrink * ax.figure.dpi / 72
    b = box(bb.x0 + s, bb.y0 + s, bb.x1 - s, bb.y1 - s)
    return affinity.rotate(b, rot, origin="centroid") if rot else b


def _patch_polygon(ax, patch):
    xy = patch.get_path().to_polygons(patch.get_transform())
    return SPolygon(xy[0]).buffer(0)


def _no_overlaps(ax, texts, obstacles=()):
    boxes = [_display_box(ax, t) for t in texts]
    for (i, a), (j, b) in itertools.combinations(enumerate(boxes), 2):
        assert not a.intersects(b), f"labels {texts[i].get_text()!r} and {texts[j].get_text()!r} overlap"
    for o in obstacles:
        shape = _patch_polygon(ax, o)
        for t, b in zip(texts, boxes):
            assert not b.intersects(shape), f"label {t.get_text()!r} covers {o.get_gid()}"


# -- polygons ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("build", [sixbar_velocity, sixbar_acceleration])
def test_arrows_end_at_the_images(sixbar, build):
    m, sol = sixbar
    poly = build(sol)
    ax = _axes()
    art = draw_polygon(poly, ax, mechanism=m)
    absolute = {tuple(np.round(h, 12)) for kind, t, h, _ in art.arrows if kind == "absolute"}
    for key, img in poly.images.items():
        if np.hypot(*img) > 0:
            assert tuple(np.round(img, 12)) in absolute, key
    for kind, tail, head, patch in art.arrows:
        tip = patch.get_xy()[0] - patch._velpoly_shift   # (a vector beside another on its line: moved)
        np.testing.assert_allclose(tip, head, rtol=0, atol=1e-12)   # the head's tip is exactly the image
    for kind, tail, head, _ in art.arrows:
        if kind == "absolute":
            np.testing.assert_array_equal(tail, [0, 0])
    drawn = {tuple(np.round(np.r_[t, h], 9)): kind for kind, t, h, _ in art.arrows}
    for step in poly.steps:
        for v in step.vectors:   # drawn in its own style, or as the absolute vector it coincides with
            assert drawn[tuple(np.round(np.r_[v.tail, v.head], 9))] in (v.kind, "absolute"), v.label
    shafts = art["shafts"]
    for (kind, tail, head, _), sh in zip(art.arrows, shafts):
        x, y = sh.get_data()
        np.testing.assert_allclose((x[0], y[0]), tail + sh._velpoly_shift, atol=1e-12)


def test_construction_lines_pass_through_their_intersection(sixbar):
    m, sol = sixbar
    poly = sixbar_velocity(sol)
    art = draw_polygon(poly, _axes(), mechanism=m)
    lines = art["construction"]
    assert len(lines) == sum(len(s.lines) for s in poly.steps)
    for step in poly.steps:
        hit = poly.images[step.found[0]] if step.found else None
        for li, ln in enumerate(step.lines):
            drawn = next(x for x in lines if x.get_gid() == f"construction-{step.index}-{li}-{ln.base_label}")
            (x0, x1), (y0, y1) = drawn.get_data()
            a, b = np.array([x0, y0]), np.array([x1, y1])
            d = (b - a) / np.hypot(*(b - a))
            assert abs(_cross(d, ln.direction)) < 1e-12          # along the line's direction
            assert abs(_cross(d, hit - a)) < 1e-9 * np.hypot(*hit)  # through the intersection
            t = np.dot(hit - a, d)
            assert 0 < t < np.hypot(*(b - a))                     # extended past it on both sides


@pytest.mark.parametrize("build", [sixbar_velocity, sixbar_acceleration])
def test_every_image_has_exactly_one_label(sixbar, build):
    m, sol = sixbar
    poly = build(sol)
    art = draw_polygon(poly, _axes(), mechanism=m)
    assert set(art.labels) == set(poly.images)
    texts = art["labels"]
    assert len(texts) == len(set(map(id, texts)))
    for key, lab in poly.labels.items():
        holders = [t for t in texts if {tex(lab), tex(lab, math=True)} & set(t.get_text().split(", "))]
        assert holders == [art.labels[key]], key
    origin = [t for t in texts if tex(poly.origin_label) in t.get_text()]
    assert len(origin) == 1
    # the frame's points image at the origin and share its label
    assert art.labels["A"] is art.labels["D"] is origin[0]


@pytest.mark.parametrize("build", [sixbar_velocity, sixbar_acceleration])
def test_polygon_labels_do_not_overlap(sixbar, build):
    m, sol = sixbar
    ax = _axes()
    art = draw_polygon(build(sol), ax, mechanism=m)
    _no_overlaps(ax, art["labels"] + art.get("reasons", []), obstacles=art["arrows"])


def test_steps_draw_a_growing_construction(sixbar):
    m, sol = sixbar
    poly = sixbar_velocity(sol)
    counts = []
    for k in range(1, len(poly.steps) + 1):
        art = draw_polygon(poly, _axes(), mechanism=m, upto=k)
        found = {key for s in poly.steps[:k] for key in s.found} | {"A", "D"}
        assert set(art.labels) == found
        counts.append(len(art["arrows"]))
    assert counts == sorted(counts) and counts[0] < counts[-1]


# -- the displacement diagram -------------------------------------------------------------------------
def test_mechanism_pins_and_labels_sit_on_the_pose(sixbar):
    m, _ = sixbar
    sol = velpoly.solve(m, angle=75.0)          # a re-assembled pose, as `--angle` draws it
    ax = _axes()
    art = draw_mechanism(sol, ax)
    for pin in {p.point for p in m.pins}:
        circle = next(p for p in art["pins"] if p.get_gid() == f"pin-{pin}")
        c = np.mean(circle.get_path().vertices[:-1], axis=0)
        np.testing.assert_allclose(c, sol.position[pin], atol=1e-9)
    assert set(art.labels) == set(sol.position)
    texts = art["labels"] + art["link_numbers"]
    assert sorted(t.get_gid() for t in art["link_numbers"]) == sorted(f"link-number-{k.name}"
                                                                       for k in m.moving_links)
    _no_overlaps(ax, texts, obstacles=art["pins"])


def test_driver_arrow_turns_with_omega(sixbar):
    m, sol = sixbar
    art = draw_mechanism(sol, _axes())
    arc = next(a for a in art["driver"] if a.get_gid() == "driver-arc")
    x, y = arc.get_data()
    a = np.unwrap(np.arctan2(y - 0.0, x - 0.0))     # around the pivot A at the origin
    assert np.all(np.diff(a) > 0)                   # counter-clockwise, as omega_1 > 0
    label = next(a for a in art["driver"] if a.get_gid() == "driver-label")
    assert "6.283 rad/s ccw" in label.get_text()


def test_scale_bar_matches_the_scale(sixbar):
    """The space diagram's scale bar at the panel's scale (the diagram drawn without its marks:
    ``mechanisms.shapes_only``, the bar and the view read)."""
    from mechanisms import shapes_only
    m, sol = sixbar
    for scale in (None, 0.04, 0.125):
        ax = _axes()
        s = canvas.fit_view(ax, (-0.4, 0.0, 0.3, 0.45), scale=scale)
        if scale is not None:
            assert s == scale
        art = draw_mechanism(sol, ax, options=shapes_only(m))
        assert view_scale(ax) == s
        assert per_cm(ax) == pytest.approx(s, rel=1e-12)
        x0, x1 = ax.get_xlim()
        fig_w = ax.figure.get_size_inches()[0] * ax.get_position().width * 2.54
        assert (x1 - x0) / fig_w == pytest.approx(s, rel=1e-12)   # 1 cm of paper = s units
        bar = art["scale_bar"][0]
        length = bar._velpoly_length
        assert bar.get_width() == pytest.approx(length, rel=1e-12)
        assert 1.0 - 1e-9 <= length / s <= 2.5 + 1e-9                    # 1 to 2.5 cm on paper
        lead = length / 10 ** np.floor(np.log10(length))
        assert round(lead, 9) in (1, 2, 5)
        assert any(t.get_text() == f"{length:g} m" for t in art["scale_bar"][1:] if hasattr(t, "get_text"))


def test_velocity_scale_bar_has_velocity_units(sixbar):
    m, sol = sixbar
    art = draw_polygon(sixbar_velocity(sol), _axes(), mechanism=m)
    texts = [t.get_text() for t in art["scale_bar"] if hasattr(t, "get_text")]
    assert any(t.endswith(" m/s") for t in texts)
    art = draw_polygon(sixbar_acceleration(sol), _axes(), mechanism=m)
    assert any(t.get_text().endswith(" m/s²") for t in art["scale_bar"] if hasattr(t, "get_text"))


def test_nice_scales():
    assert canvas.nice_scale(0.065) == 0.08
    assert canvas.nice_scale(0.08) == 0.08
    assert canvas.nice_scale(1.1) == 1.5
    assert canvas.nice_length(0.27) == 0.2
    assert canvas.nice_length(7.0) == 5.0


# -- labels ---------------------------------------------------------------------------------------------
def test_placer_keeps_crowded_labels_apart():
    ax = _axes((4, 4))
    canvas.fit_view(ax, (0, 0, 1, 1))
    pl = LabelPlacer(ax)
    from shapely.geometry import Point
    pl.add_obstacle(Point(0.5, 0.5).buffer(0.02))
    texts = [pl.place((0.5, 0.5), f"label {i}", fontsize=9) for i in range(12)]
    texts += [pl.place((0.5 + 0.01 * i, 0.5), "x", fontsize=9) for i in range(4)]
    _no_overlaps(ax, texts)
    # no label over the leader of a label placed before it (in a crowd this dense a later leader may
    # have to pass a label; the gallery test checks that real figures have none)
    from shapely.geometry import LineString
    boxes = [_display_box(ax, t) for t in texts]
    leaders = 0
    for i, t in enumerate(texts):
        ld = getattr(pl.of(t), "leader", None)
        if ld is not None:
            leaders += 1
            line = LineString(ax.transData.transform(ld.get_xydata()))
            assert not any(line.intersects(b) for b in boxes[i + 1:]), t.get_text()
    assert leaders >= 4
    centre = ax.transData.transform((0.5, 0.5))
    for t in texts:   # and none covers the obstacle
        assert not _display_box(ax, t).contains(box(*centre, *(centre + 1)))


def test_placer_is_deterministic():
    def run():
        ax = _axes((4, 4))
        canvas.fit_view(ax, (0, 0, 1, 1))
        pl = LabelPlacer(ax)
        return [pl.place((0.5, 0.5), s, fontsize=9).get_position() for s in ("A", "B", "C", "D")]
    assert run() == run()


def test_tex_labels():
    assert tex("b4") == "$b_{4}$"
    assert tex("c'") == "c′"
    assert tex("f5'") == "$f_{5}'$"
    assert tex("B") == "B"
    assert tex("O_v") == "$O_{v}$"
    assert tex("P@5") == "P@5"


def test_slotted_lever_is_drawn_under_its_crank_and_clear_of_its_pins():
    """Crank-shaper: the slotted lever 4 lies under the crank 2, its slot stops short of its pin B (B's
    label is not inside the bar), and the driver's arc crosses no other link."""
    from shapely.geometry import LineString, Point
    sol = velpoly.solve(velpoly.load(EXAMPLES / "crank_shaper.toml"))
    ax = _axes((5, 6))
    with rc_context(sheet.get_style("textbook")):
        art = draw_mechanism(sol, ax)
    links = {p.get_gid()[len("link-"):]: p for p in art["links"] if (p.get_gid() or "").startswith("link-")}
    assert links["2"].get_zorder() > links["4"].get_zorder()
    to_data = ax.transData.inverted()

    def outline(patch):
        return SPolygon(to_data.transform(patch.get_path().to_polygons(patch.get_transform())[0])).buffer(0)

    slots = [outline(p) for p in art["links"] if not p.get_gid()]
    assert slots
    pin_b = Point(*sol.position["B"]).buffer(per_cm(ax) * 0.05)
    assert not any(s.intersects(pin_b) for s in slots)
    r = ax.figure.canvas.get_renderer()
    bb = art.labels["B"].get_window_extent(r)
    (x0, y0), (x1, y1) = to_data.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
    assert not outline(links["4"]).intersects(box(x0, y0, x1, y1))
    arc = next(a for a in art["driver"] if a.get_gid() == "driver-arc")
    arc = LineString(np.column_stack(arc.get_data()))
    assert not any(outline(p).intersects(arc) for k, p in links.items() if k != "2")


def test_labels_of_close_images_stand_apart_on_their_own_sides(sixbar):
    """Six-bar, slides: e and f are a few millimetres apart at the polygon's top; each label stands on
    its own image's side (e's on the side away from f and f's away from e), not side by side as one."""
    m, sol = sixbar
    st = sheet.get_style("slides")
    ax = _axes((4.3, 3.6))
    with rc_context(st):
        art = draw_polygon(sixbar_velocity(sol), ax, mechanism=m, style=st)
    pc = per_cm(ax)
    images = {k: np.asarray(v, float) for k, v in sixbar_velocity(sol).images.items()}
    close = [(a, b) for a, b in itertools.combinations(sorted(art.labels), 2)
             if art.labels[a] is not art.labels[b] and a in images and b in images
             and 1e-9 < np.hypot(*(images[a] - images[b])) < 1.0 * pc]
    assert ("E", "F") in close
    for a, b in close:
        d = images[a] - images[b]
        la, lb = (np.array(art.labels[k].get_position()) for k in (a, b))
        assert np.dot(la - images[a], d) > 0 and np.dot(lb - images[b], -d) > 0, (a, b)
    _no_overlaps(ax, art["labels"])


@pytest.mark.parametrize("stem,name,style", [pytest.param(*p, marks=sheets.on(p[2])) for p in (
    ("ex3_6_fourbar", "poles", "textbook"), ("ex3_6_fourbar", "poles", "slides"), ("crank_shaper", "full", "textbook"))])
def test_driver_value_sits_by_its_arc_over_no_link(stem, name, style):
    """The omega arrow goes where its value can stand next to it, over no link's outline (ex3_6's poles
    sheet in slides had it across link 4 and the label of P_14)."""
    fig = sheets.page(stem, name, style)      # drawn once per worker, shared (tests/sheets.py)
    ax = next(a for a in fig.axes if any(t.get_gid() == "driver-label" for t in a.texts))
    to_data = ax.transData.inverted()
    label = next(t for t in ax.texts if t.get_gid() == "driver-label")
    bb = label.get_window_extent(fig.canvas.get_renderer())
    (x0, y0), (x1, y1) = to_data.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
    lab = box(x0, y0, x1, y1)
    leader = getattr(placer(ax).of(label), "leader", None)
    from shapely.geometry import LineString
    lead = LineString(np.column_stack(leader.get_data())) if leader is not None else None
    for p in ax.patches:
        if (p.get_gid() or "").startswith("link-"):
            outline = SPolygon(to_data.transform(p.get_path().to_polygons(p.get_transform())[0])).buffer(0)
            assert not outline.boundary.intersects(lab), p.get_gid()
            if lead is not None:
                assert not outline.boundary.intersects(lead), "leader across " + p.get_gid()
    others = [t for t in ax.texts if t is not label and (t.get_gid() or "").startswith(("label-", "link-number"))]
    _no_overlaps(ax, [label] + others)
    arc = next(a for a in ax.lines if a.get_gid() == "driver-arc")
    assert lab.distance(SPolygon(np.column_stack(arc.get_data())).convex_hull) < 1.5 * per_cm(ax)   # by its arc


# -- poles and the Kennedy circle -------------------------------------------------------------------------
def test_kennedy_circle_has_n_points_and_all_chords(sixbar):
    pytest.importorskip("velpoly.poles")
    from velpoly.poles import locate_poles
    from velpoly.render.kennedy import draw_kennedy_circle
    m, sol = sixbar
    ps = locate_poles(sol)
    ax = _axes((4, 4))
    art = draw_kennedy_circle(sol, ax, poleset=ps)
    n = len(m.links)
    assert len(art["points"]) == n
    assert len(art["chords"]) == n * (n - 1) // 2
    assert {c.get_gid() for c in art["chords"]} == {f"chord-{k}" for k in ps.poles}
    for c in art["points"]:   # on the circle
        assert np.hypot(*c.center) == pytest.approx(1.0)
    found = [p for p in ps.poles.values() if p.order > 0]
    assert len(art["numbers"]) == len(found)
    assert sorted(t.get_text() for t in art["numbers"]) == sorted(str(p.order) for p in found)
    for p in ps.poles.values():
        chord = next(c for c in art["chords"] if c.get_gid() == f"chord-{p.key}")
        assert (chord.get_linestyle() == "-") == (p.order == 0)
    _no_overlaps(ax, art["labels"] + art["numbers"])
    # step by step: the chords found so far
    art = draw_kennedy_circle(sol, _axes((4, 4)), poleset=ps, upto=2)
    assert len(art["chords"]) == sum(1 for p in ps.poles.values() if p.order <= 2)


@pytest.mark.parametrize("path", [EXAMPLES / "ex3_6_fourbar.toml", SIXBAR,
                                  EXAMPLES / "watt_sixbar.toml"], ids=lambda p: p.stem)
def test_kennedy_numbers_sit_on_their_own_chord_clear_of_crossings(path):
    """Each order number lies on its chord, meets no other chord (so no crossing: on a four-bar the
    diagonals cross at the centre) and no other number or link label."""
    pytest.importorskip("velpoly.poles")
    from shapely.geometry import LineString, Point
    from velpoly.poles import locate_poles
    from velpoly.render.kennedy import draw_kennedy_circle
    sol = velpoly.solve(velpoly.load(path))
    ps = locate_poles(sol)
    ax = _axes((4, 4))
    art = draw_kennedy_circle(sol, ax, poleset=ps)
    chords = {c.get_gid()[len("chord-"):]: np.column_stack(c.get_data()) for c in art["chords"]}
    assert art["numbers"]
    ax.figure.canvas.draw()                                            # places the numbers' circles
    to_data = ax.transData.inverted()
    boxes = []
    for t in art["numbers"]:
        key = t.get_gid()[len("chord-number-"):]
        a, b = chords[key]
        c = np.array(t.get_position())
        assert LineString([a, b]).distance(Point(*c)) < 1e-9            # on its own chord
        f = np.dot(c - a, b - a) / np.dot(b - a, b - a)
        assert 0.1 < f < 0.9                                           # inside the circle, off the ends
        bb = t.get_bbox_patch().get_window_extent(ax.figure.canvas.get_renderer())
        (x0, y0), (x1, y1) = to_data.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
        boxes.append((t.get_text(), box(x0, y0, x1, y1)))
        for k, (p, q) in chords.items():
            if k != key:
                assert not LineString([p, q]).intersects(boxes[-1][1]), f"number {t.get_text()} on chord {k}"
    for (s1, b1), (s2, b2) in itertools.combinations(boxes, 2):
        assert not b1.intersects(b2), f"numbers {s1} and {s2} overlap"
    _no_overlaps(ax, art["labels"] + art["numbers"])


def test_poles_are_drawn_where_they_are(sixbar):
    pytest.importorskip("velpoly.poles")
    from velpoly.poles import locate_poles
    from velpoly.render.kennedy import draw_poles
    m, sol = sixbar
    ps = locate_poles(sol)
    ax = _axes((7, 5))
    art = draw_poles(sol, ax, poleset=ps)
    assert set(art.labels) == {k for k, p in ps.poles.items() if not (p.position is None and p.direction is None)}
    for mark in art.get("poles", []):
        if mark.get_gid():
            key = mark.get_gid()[len("pole-"):]
            c = np.mean(mark.get_path().vertices[:-1], axis=0)
            np.testing.assert_allclose(c, ps.poles[key].position, atol=1e-9)
    for head in art.get("far", []):
        if hasattr(head, "get_xy") and head.get_gid():
            p = ps.poles[head.get_gid()[len("pole-"):]]
            tip, base = head.get_xy()[0], (head.get_xy()[1] + head.get_xy()[3]) / 2
            d = (tip - base) / np.hypot(*(tip - base))
            if p.position is None:     # a pole at infinity: the arrow points its way
                assert abs(_cross(d, [np.cos(np.radians(p.direction)), np.sin(np.radians(p.direction))])) < 1e-9
    _no_overlaps(ax, art["labels"] + art["link_numbers"] + [a for a in art["far"] if hasattr(a, "get_text")])


@pytest.mark.parametrize("stem,key,whole", [("problem_1_4_4_sixbar", "0-4", False),
                                            ("ex3_4_slotted_lever", "4-5", False), ("watt_sixbar", "1-3", True)])
@sheets.on("textbook")
def test_far_pole_arrow_stands_on_its_kennedy_line_at_the_border(stem, key, whole):
    """A finite pole too far to show is an arrow at the panel's border, on a Kennedy line that located it
    where that line leaves the view, pointing along it towards the pole: a reader follows it to the pole
    (it used to stand beside the mechanism, on no line: P_04 of Problem 1.4.4 by the slider). The poles page
    with its space diagram unlabelled (``sheets.bare_page``: the arrows, Kennedy lines and labels' words read),
    the Watt six-bar's whole (``whole``: test_mechanism_labels_keep_off_the_kennedy_lines reads its labels)."""
    pytest.importorskip("velpoly.poles")
    from shapely.geometry import LineString, Point
    from velpoly.render.canvas import view_box
    sol = sheets.solved(stem)
    pole = sheets.constructions(stem, "poles").poles.poles[key]
    assert pole.position is not None
    fig = (sheets.page if whole else sheets.bare_page)(stem, "poles", "textbook")   # once per worker, shared
    ax = next(a for a in fig.axes if any((ln.get_gid() or "").startswith("kennedy-line-") for ln in a.lines))
    view = view_box(ax)
    assert not view.contains(Point(*pole.position))
    heads = [h for h in ax.patches if h.get_gid() == f"pole-{key}"]
    assert len(heads) == 1
    xy = heads[0].get_xy()
    tip, base = xy[0], (xy[1] + xy[3]) / 2
    d = (tip - base) / np.hypot(*(tip - base))
    to_pole = (pole.position - tip) / np.hypot(*(pole.position - tip))
    assert abs(_cross(d, to_pole)) < 1e-9 and np.dot(d, to_pole) > 0      # pointing at the pole
    inset = 0.2 * per_cm(ax)
    # the tip stands ``inset`` back along the line from where the line leaves the view
    assert view.exterior.distance(Point(*(tip + d * inset))) < 1e-9 * sol.mechanism.size
    lines = [LineString(np.column_stack(ln.get_data())) for ln in ax.lines
             if (ln.get_gid() or "").startswith(f"kennedy-line-{key}-")]
    assert lines and min(ln.distance(Point(*tip)) for ln in lines) < 1e-9 * sol.mechanism.size
    label = next(t for t in ax.texts if t.get_gid() == f"label-pole-{key}")
    assert f"{pole.position[0]:.4g}".replace("-", "−") in label.get_text()


@sheets.on("textbook")
def test_mechanism_labels_keep_off_the_kennedy_lines():
    """The Kennedy lines are known before the mechanism's labels are placed: no point label and not the
    driver's value lies across one (Watt six-bar: omega_2 and O_2 used to sit on the lines through P_12). Its
    poles page (tests/sheets.py, shared with the far-pole test): read only."""
    pytest.importorskip("velpoly.poles")
    from shapely.geometry import LineString
    fig = sheets.page("watt_sixbar", "poles", "textbook")
    ax = next(a for a in fig.axes if any((ln.get_gid() or "").startswith("kennedy-line-") for ln in a.lines))
    lines = [LineString(np.column_stack(k.get_data())) for k in ax.lines
             if (k.get_gid() or "").startswith("kennedy-line-")]
    assert lines
    r = fig.canvas.get_renderer()
    to_data = ax.transData.inverted()
    texts = [t for t in ax.texts if (t.get_gid() or "").startswith("label-point-") or t.get_gid() == "driver-label"]
    assert sum(t.get_gid() == "driver-label" for t in texts) == 1 and len(texts) >= 6
    with sheets.styled("textbook"):
        for t in texts:
            bb = t.get_window_extent(r)
            (x0, y0), (x1, y1) = to_data.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
            b = box(x0, y0, x1, y1)
            assert not any(ln.intersects(b) for ln in lines), t.get_text()


# -- the results table -----------------------------------------------------------------------------------
def test_results_table_rows(sixbar):
    from velpoly.render.table import results_table
    m, sol = sixbar
    t = results_table(sol, "velocity", velocity=sixbar_velocity(sol))
    rows = {r[0]: dict(zip(t.header, r)) for r in t.rows}
    w2 = rows[r"$\omega_{2}$ (rad/s)"]
    assert (w2["graphical"], w2["analytic"]) == ("−1.1307", "−1.1307")
    lo, hi = (float(x.replace("−", "-")) for x in w2["hand-drawn, 95 %"].split(" … "))
    assert lo < sol.omega["2"] < hi                       # a hand drawing straddles the exact value
    assert rows["$V_{B}$"]["graphical"] == "0.94248 ∠ 120.00°"
    assert "reference" in t.header and "deviation" in t.header
    assert rows[r"$\omega_{3}$ (rad/s)"]["deviation"] == "< 0.001 %"


def test_reference_values_only_at_the_files_pose(sixbar):
    from velpoly.render.table import results_table
    m, sol = sixbar
    assert "reference" in results_table(sol, "velocity", velocity=sixbar_velocity(sol)).header
    other = velpoly.solve(m, angle=120.0)
    t = results_table(other, "velocity", velocity=sixbar_velocity(other))
    assert "reference" not in t.header and "no reference values at this driver angle (120°)" in t.title


def test_results_table_is_drawn_within_its_axes(sixbar):
    from velpoly.render.table import draw_results_table
    m, sol = sixbar
    fig = Figure(figsize=(11.69, 8.27))
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.05, 0.02, 0.9, 0.2))
    art = draw_results_table(sol, ax, sheet="full", velocity=sixbar_velocity(sol),
                             acceleration=sixbar_acceleration(sol))
    frame = ax.get_window_extent(fig.canvas.get_renderer())
    for t in art["cells"]:
        bb = t.get_window_extent(fig.canvas.get_renderer())
        assert frame.x0 - 1 <= bb.x0 and bb.x1 <= frame.x1 + 1 and frame.y0 - 1 <= bb.y0, t.get_text()
    assert art.shown + sum(1 for c in art["cells"] if c.get_text().startswith("…")) >= 1


def test_results_table_blocks_show_only_their_columns():
    """A table set in blocks side by side: each block heads only the columns that have values in its rows
    (Example 3.4's poles sheet: the second block, poles' positions only, used to repeat empty "instant
    centres", "reference" and "deviation" headers), and every value of the rows drawn is drawn."""
    pytest.importorskip("velpoly.poles")
    from velpoly.render.table import draw_results_table, results_table
    sol = velpoly.solve(velpoly.load(EXAMPLES / "ex3_4_slotted_lever.toml"))
    with rc_context(sheet.get_style("textbook")):   # a room too short for one block (the sheet gives it more)
        fig = Figure(figsize=(11.69, 8.27))
        FigureCanvasAgg(fig)
        ax = fig.add_axes((0.05, 0.02, 0.9, 0.25))
        draw_results_table(sol, ax, sheet="poles", poleset=sheet.constructions(sol, "poles").poles)
    cells = [t for t in ax.texts if t.get_gid() != "results-table"]
    starts = sorted(t.get_position()[0] for t in cells if t.get_text() == "quantity")
    assert len(starts) >= 2                                   # the table is split
    head_y = next(t.get_position()[1] for t in cells if t.get_text() == "quantity")
    header = [t for t in cells if abs(t.get_position()[1] - head_y) < 1e-12]
    body = [t for t in cells if t.get_position()[1] < head_y - 1e-12]
    for t in header:
        x = t.get_position()[0]
        below = [c for c in body if abs(c.get_position()[0] - x) < 1e-12 and c.get_text().strip()]
        assert below, f"an empty column headed {t.get_text()!r} at x = {x:.3f}"
    # the blocks stand apart, and no value is lost
    block = np.searchsorted(starts, [t.get_position()[0] + 1e-12 for t in cells]) - 1
    r = fig.canvas.get_renderer()
    to_ax = ax.transAxes.inverted()
    for b in range(len(starts) - 1):
        right = max(to_ax.transform(t.get_window_extent(r))[1][0] for t, k in zip(cells, block) if k == b)
        assert right < starts[b + 1]
    drawn = {t.get_text() for t in body}
    table = results_table(sol, "poles", poleset=sheet.constructions(sol, "poles").poles)
    for row in table.rows:
        assert all(v in drawn for v in row[1:] if v), row


# -- sheets and files ------------------------------------------------------------------------------------
def _cons(sol):
    from velpoly.render.sheet import Constructions
    poles = None
    try:
        from velpoly.poles import locate_poles
        poles = locate_poles(sol)
    except ImportError:
        pass
    return Constructions(sixbar_velocity(sol), sixbar_acceleration(sol), poles)


def test_same_input_same_bytes(sixbar, tmp_path):
    m, sol = sixbar
    for suffix, name in ((".svg", "full"), (".pdf", "velocity")):   # each drawn twice, from its own solve
        a = sheet.draw_to_file(sol, tmp_path / f"a{suffix}", name, cons=_cons(sol))[0]
        b = sheet.draw_to_file(velpoly.solve(velpoly.load(SIXBAR)), tmp_path / f"b{suffix}", name,
                               cons=_cons(sol))[0]
        assert a.read_bytes() == b.read_bytes()
    assert b"<dc:date>" not in a.with_suffix(".svg").read_bytes()


def test_a_failed_drawing_leaves_no_file(sixbar, tmp_path, monkeypatch):
    m, sol = sixbar

    def boom(*args, **kw):
        raise RuntimeError("drawing failed")
    monkeypatch.setattr(sheet, "draw_results_table", boom)
    for name, steps in (("out.svg", False), ("out.pdf", False), ("out.pdf", True), ("out.svg", True)):
        with pytest.raises(RuntimeError):
            sheet.draw_to_file(sol, tmp_path / name, "velocity", steps=steps, cons=_cons(sol))
        assert list(tmp_path.iterdir()) == []


def test_steps_write_numbered_files_and_pdf_pages(sixbar, tmp_path):
    """--steps: an SVG a frame, numbered, each with its caption; a PDF a page a frame. Drawn for Example 3.5 (three
    steps a polygon: a frame is a sheet drawn; the six-bar's five each until the suite had to fit 2 minutes),
    the frames' captions of the six-bar's hand-made polygons."""
    m, sol = sixbar
    cons = _cons(sol)
    frames = sheet.frames("full", cons, True)
    assert len(frames) == len(cons.velocity.steps) + len(cons.acceleration.steps)
    assert frames[1].caption.startswith("Step 2: ") and r"$V_{CB}$" in frames[1].caption
    small = sheets.solved("ex3_5_slider_crank")
    cons = sheet.constructions(small, "full")
    with sheets.unlabelled_mechanism():   # the files, their captions and pages read, not the space diagram's marks
        files = sheet.draw_to_file(small, tmp_path / "v.svg", "velocity", steps=True, cons=cons)
        pdf = sheet.draw_to_file(small, tmp_path / "a.pdf", "acceleration", steps=True, cons=cons)[0]
    n = len(cons.velocity.steps)
    assert n >= 3 and [p.name for p in files] == [f"v-{i:02d}.svg" for i in range(1, n + 1)]
    assert all(p.exists() for p in files)
    assert all('id="step-caption"' in p.read_text() for p in files)
    assert pdf.read_bytes().count(b"/Type /Page\n") + pdf.read_bytes().count(b"/Type /Page ") >= \
        len(cons.acceleration.steps)


@pytest.mark.parametrize("stem,largest,style,whole", [pytest.param(*p, marks=sheets.on(p[2])) for p in (
    ("ex3_6_fourbar", 10.0, "textbook", True), ("crank_shaper", 80.0, "textbook", False),
    ("ex3_7_instant_centres", 10.0, "slides", True))])
def test_poles_sheet_layouts_draw_the_mechanism_large(stem, largest, style, whole):
    """The poles sheet picks the layout drawing the mechanism largest; the panels never overlap and stay on
    the page, and the table keeps its full type size (ex3_6's far P_24 used to shrink the mechanism to
    1 cm = 15 mm). Example 3.7's poles sheet in slides, the gallery's own page (1 cm = 10 mm; 8 in textbook,
    drawn for this test alone until issue 19 item 7). The gallery's pages whole (``whole``, test_render_gallery
    reads them), the crank shaper's, read here alone, with its space diagram unlabelled (``sheets.bare_page``:
    the layout read)."""
    pytest.importorskip("velpoly.poles")
    from shapely.geometry import box as sbox
    st = sheet.get_style(style)
    fig = (sheets.page if whole else sheets.bare_page)(stem, "poles", style)   # once per worker, shared
    axes = {ax.get_label(): ax for ax in fig.axes}
    assert view_scale(axes["poles"]) <= largest
    rects = {k: sbox(*ax.get_position().bounds[:2], *(np.add(ax.get_position().bounds[:2],
                                                             ax.get_position().bounds[2:])))
             for k, ax in axes.items() if k != "table"}
    assert all(0 <= r.bounds[0] and r.bounds[2] <= 1 and 0 <= r.bounds[1] and r.bounds[3] <= 0.95
               for r in rects.values())
    for a, b in itertools.combinations(rects.values(), 2):
        assert a.intersection(b).area < 1e-12, stem
    sizes = {t.get_fontsize() for t in axes["table"].texts if t.get_gid() != "results-table"}
    assert sizes and max(sizes) >= st.small_size * 0.99      # not shrunk to fit


def test_bad_arguments_are_input_errors(sixbar, tmp_path):
    m, sol = sixbar
    with pytest.raises(InputError, match="valid sheets"):
        sheet.draw_to_file(sol, tmp_path / "x.svg", "everything")
    with pytest.raises(InputError, match="valid styles"):
        sheet.draw_to_file(sol, tmp_path / "x.svg", "full", style="fancy", cons=_cons(sol))
    with pytest.raises(InputError, match="unknown figure type '.jpg'") as e:
        sheet.draw_to_file(sol, tmp_path / "x.jpg", "full")
    assert ".svg, .png or .pdf" in e.value.hint
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("drawing, where, what", [
    ({"scael": 0.1}, "drawing.scael", "valid keys: scale, velocity_scale"),
    ({"scale": -1}, "drawing.scale", "positive"),
    ({"velocity_scale": "big"}, "drawing.velocity_scale", "positive"),
    ({"label_points": ["A", "Q"]}, "drawing.label_points", "unknown point 'Q'"),
    ({"link_colours": {"9": "red"}}, "drawing.link_colours.9", "unknown link"),
    ({"link_colours": {"2": "reddish"}}, "drawing.link_colours.2", "not a colour"),
    ({"link_numbers": "boxed"}, "drawing.link_numbers", "circled, plain, none"),
    ({"table": "yes"}, "drawing.table", "true or false"),
])
def test_drawing_options_are_checked(drawing, where, what):
    import tomllib
    from velpoly.render.options import drawing_options
    data = tomllib.loads(SIXBAR.read_text())
    data["drawing"] = drawing
    with pytest.raises(InputError) as e:   # checked on load, by the rules draw applies
        velpoly.load(data)
    assert e.value.where == where and what in e.value.what + e.value.hint
    good = velpoly.load({**data, "drawing": {}})
    with pytest.raises(InputError) as e:   # and by drawing_options itself, on a Mechanism made otherwise
        drawing_options(__import__("dataclasses").replace(good, drawing=drawing))
    assert e.value.where == where and what in e.value.what + e.value.hint


def test_drawing_options_take_effect(sixbar):
    import tomllib
    data = tomllib.loads(SIXBAR.read_text())
    data["drawing"] = {"scale": 0.05, "label_points": ["B", "C"], "link_numbers": "none",
                       "link_colours": {"2": "#ff0000"}}
    m = velpoly.load(data)
    sol = velpoly.solve(m)
    art = draw_mechanism(sol, _axes(), style="slides")
    assert view_scale(art.ax) == 0.05
    assert set(art.labels) == {"B", "C"}
    assert "link_numbers" not in art
    body = next(p for p in art["links"] if p.get_gid() == "link-2")
    assert body.get_facecolor()[0] == 1.0 and body.get_facecolor()[1] < 0.8


def test_mechanism_svg_for_jupyter(sixbar):
    m, _ = sixbar
    svg = m._repr_svg_()
    assert svg.lstrip().startswith("<?xml") and "<svg" in svg
    assert svg == m._repr_svg_()


# -- matplotlib stays out of the kernel ---------------------------------------------------------------
def test_kernel_and_solve_do_not_import_matplotlib():
    code = ("import sys, velpoly, velpoly.cli, io, contextlib\n"
            "assert 'matplotlib' not in sys.modules, 'import velpoly'\n"
            f"with contextlib.redirect_stdout(io.StringIO()):\n"
            f"    rc = velpoly.cli.main(['solve', {str(SIXBAR)!r}, '--json'])\n"
            "assert rc == 0\n"
            "assert 'matplotlib' not in sys.modules, 'velpoly solve'\n"
            "import velpoly.render\n"
            "assert 'matplotlib' not in sys.modules, 'import velpoly.render'\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr


def test_auxiliary_points_are_labelled_in_the_polygon_and_marked_on_the_mechanism():
    from velpoly.polygons import velocity_polygon
    from velpoly.render.displacement import mark_auxiliary
    names = ("O1", "O4", "P", "Q", "S", "U", "R")        # Stephenson III: a triad, no dyad order
    pts = ((0, 0), (1.0, 0.1), (0.2, 0.25), (-0.05, 0.3), (0.5, 0.9), (0.1, 0.8), (1.1, 0.7))
    m = velpoly.load({"points": {n: list(p) for n, p in zip(names, pts)},
                      "links": {"0": {"points": ["O1", "O4"], "frame": True}, "1": {"points": ["O1", "P", "Q"]},
                                "2": {"points": ["P", "S"]}, "3": {"points": ["Q", "U"]},
                                "4": {"points": ["O4", "R"]}, "5": {"points": ["S", "U", "R"]}},
                      "driver": {"link": "1", "omega": 10}})
    sol = velpoly.solve(m)
    poly = velocity_polygon(sol)
    assert poly.auxiliary
    art = draw_polygon(poly, _axes(), mechanism=m)
    for key, aux in poly.auxiliary.items():
        assert key in art.labels and tex(aux.label) in art.labels[key].get_text()
    ax = _axes()
    canvas.fit_view(ax, (-0.2, 0.0, 1.6, 3.1))
    draw_mechanism(sol, ax)
    marks = mark_auxiliary(sol, ax, poly)
    for key, aux in poly.auxiliary.items():
        ring = next(p for p in marks["auxiliary"] if p.get_gid() == f"auxiliary-{key}")
        np.testing.assert_allclose(np.mean(ring.get_path().vertices[:-1], axis=0), aux.position, atol=1e-9)
        assert marks.labels[key].get_text().startswith(tex(aux.label.upper()))


def test_panels_draw_on_pyplots_current_axes():
    """Each panel's drawing function, given no axes, draws on pyplot's current one. Example 3.6's four-bar (the
    six-bar of Problem 1.4.4 until issue 19 item 7: where a panel draws does not depend on the mechanism, and the
    four-bar's panels are the cheaper to draw)."""
    import matplotlib.pyplot as plt
    from velpoly.render import (draw_acceleration_polygon, draw_kennedy_circle, draw_mechanism, draw_poles,
                                draw_results_table, draw_velocity_polygon)
    sol = sheets.solved("ex3_6_fourbar")
    try:
        for fn in (draw_mechanism, draw_velocity_polygon, draw_acceleration_polygon, draw_poles,
                   draw_kennedy_circle, draw_results_table):
            fig = plt.figure()
            art = fn(sol)
            assert art.ax is plt.gca() and art.all(), fn.__name__
            plt.close(fig)
    finally:
        plt.close("all")
    from velpoly.polygons import velocity_polygon
    poly = velocity_polygon(sol)
    fig = plt.figure()
    art = draw_velocity_polygon(sol, polygon=poly)
    assert set(art.labels) == set(poly.images)
    plt.close(fig)


# -- issue 6 audit: what a textbook editor rejected ---------------------------------------------------
def test_link_image_is_the_hull_of_its_images(sixbar):
    """A plate A, B, E, F with E on AB: its image is the triangle a b f (e on its side), similar to the
    plate, not the figure a-b-e-f in file order (which shaded the triangle a e f)."""
    from velpoly.polygons import Polygon
    m, _ = sixbar
    images = {"A": np.array([1.0, 0.0]), "B": np.array([0.0, 2.0]), "E": np.array([0.5, 1.0]),
              "F": np.array([1.5, 1.5]), "D": np.zeros(2)}
    poly = Polygon("velocity", "O_v", images, {k: k.lower() for k in images}, (),
                   {"3": ("A", "B", "E", "F")}, {}, 0.0)
    ax = _axes()
    art = draw_polygon(poly, ax, mechanism=m)
    (patch,) = art["images"]
    shaded = SPolygon(patch.get_xy()[:-1] if len(patch.get_xy()) > 3 else patch.get_xy())
    hull = SPolygon([images["A"], images["F"], images["B"]])
    assert shaded.symmetric_difference(hull).area == pytest.approx(0.0, abs=1e-12)
    assert all(shaded.buffer(1e-12).contains(shapely.Point(*v)) for v in images.values() if np.any(v))


def test_legend_lists_only_the_kinds_drawn(sixbar):
    """A component that is also an absolute vector (the slip of a block on the frame, drawn once, as
    absolute) is not in the legend; the components drawn are."""
    from dataclasses import replace

    from velpoly.polygons import Step, Vector
    m, sol = sixbar
    poly = sixbar_acceleration(sol)
    extra = Step(5, "known", "A_F along the path", (), (), (Vector(np.zeros(2), poly.images["F"], "slip", "A_F"),),
                 {}, 1.0)
    poly = replace(poly, steps=poly.steps + (extra,))
    art = draw_polygon(poly, _axes((7, 6)), mechanism=m)
    (leg,) = art["legend"]
    texts = [t.get_text() for t in leg.get_texts()]
    assert "slip along the path" not in texts
    assert any(t.startswith("normal") for t in texts) and any(t.startswith("tangential") for t in texts)
    drawn = {kind for kind, *_ in art.arrows}
    assert drawn == {"absolute", "normal", "tangential"}


@pytest.fixture(scope="module")
def slide_frames(sixbar):
    """The six-bar's first and last --steps frames in slides, of the full and the poles sheets (the first drawn
    as --steps draws it, with the last frame's pins), shared by the frame tests; the poles sheet's with its
    space diagram unlabelled (``sheets.unlabelled_mechanism``: only its page's texts and panels' places are
    read). Read only."""
    m, sol = sixbar
    cons = _cons(sol)
    st = sheet.get_style("slides")
    with rc_context(st):
        full = _first_and_last(sol, "full", st, cons)
        with sheets.unlabelled_mechanism():
            return {"full": full, "poles": _first_and_last(sol, "poles", st, cons)}


def _first_and_last(sol, name, st, cons):
    """The first and the last --steps frames of the sheet ``name`` (the first with the last's pins)."""
    fr = sheet.frames(name, cons, True)
    last = sheet.render_sheet(sol, name, st, cons=cons, frame=fr[-1])
    return sheet.render_sheet(sol, name, st, cons=cons, frame=fr[0], pins=last._velpoly_pins), last


@pytest.mark.xdist_group("render-slide-frames")   # one worker draws slide_frames
def test_step_caption_has_its_own_room(slide_frames):
    """The frame's equation, boxed under the title, runs into no panel caption (it struck through
    'Instant centres' and the three captions of the full sheet); the frames' panels are alike."""
    with rc_context(sheet.get_style("slides")):
        for name in ("full", "poles"):
            figs = slide_frames[name]
            for fig in figs:
                assert_page_texts_clear(fig)
            pos = [[tuple(ax.get_position().bounds) for ax in fig.axes if ax.get_label() != "table"] for fig in figs]
            assert pos[0] == pos[1]
            # the results table only in the last frame (issue 17 item 8b: it gives the answers away)
            assert [any(ax.get_label() == "table" for ax in fig.axes) for fig in figs] == [False, True]


def test_long_step_caption_in_two_lines():
    """A step's caption too long for one line (the crank shaper's Coriolis step) is wrapped into two lines of
    about equal width, at a space outside mathtext, nearly at full size (it was shrunk to 0.7 of it); clear of
    the title and the panels' captions, the panels where a one-line frame has them."""
    sol = velpoly.solve(velpoly.load(EXAMPLES / "crank_shaper.toml"))
    st = sheet.get_style("slides")
    cons = sheet.constructions(sol, "full")
    fr = sheet.frames("full", cons, True)
    short, long = min(fr, key=lambda f: len(f.caption)), max(fr, key=lambda f: len(f.caption))
    with rc_context(st), sheets.unlabelled_mechanism():   # the page's texts and the panels' places read
        figs = [sheet.render_sheet(sol, "full", st, cons=cons, frame=f) for f in (short, long)]
    caps = [next(t for t in fig.texts if t.get_gid() == "step-caption") for fig in figs]
    assert "\n" not in caps[0].get_text() and caps[0].get_fontsize() == pytest.approx(st.font_size * 1.1)
    first, second = caps[1].get_text().split("\n")
    assert first.count("$") % 2 == 0 and first + " " + second == long.caption
    assert caps[1].get_fontsize() >= 0.85 * st.font_size * 1.1
    r = figs[1].canvas.get_renderer()
    widths = []
    for line in (first, second):
        probe = figs[1].text(0, 0, line, fontsize=caps[1].get_fontsize())
        widths.append(probe.get_window_extent(r).width)
        probe.remove()
    assert max(widths) < 1.25 * min(widths)
    for fig in figs:
        assert_page_texts_clear(fig)
    pos = [[tuple(ax.get_position().bounds) for ax in fig.axes if ax.get_label() != "table"] for fig in figs]
    assert pos[0] == pos[1]


def test_long_captions_fit_their_columns():
    """Slide type: 'Acceleration polygon (1 cm = 20000 mm/s²)' ran into its neighbour and off the page."""
    m = velpoly.load(SIXBAR)
    sol = velpoly.solve(m)
    from velpoly.render.sheet import fit_width
    st = sheet.get_style("slides")
    with rc_context(st):
        with sheets.unlabelled_mechanism():   # the page's texts and the panels' places read
            fig = sheet.render_sheet(sol, "full", st, cons=_cons(sol))
        cap = next(t for t in fig.texts if t.get_gid() == "caption-acceleration")
        cap.set_text("Acceleration polygon   (1 cm = 20000 mm/s²)")
        cap.set_fontsize(st.font_size)
        fit_width(fig, cap, next(ax for ax in fig.axes if ax.get_label() == "acceleration").get_position().width)
        assert cap.get_fontsize() < st.font_size
        assert_page_texts_clear(fig)


def test_typesetting_of_numbers_equations_and_reasons():
    """Tables print minus signs and no computer exponents (A_A was '1e+05 ∠ 300.00°'); a deviation in
    magnitude and direction reads '0.41 %, 0.21°'; equations and reasons subscript point names
    ('perpendicular to O4B', 'omega_2^2' printed with its caret)."""
    from types import SimpleNamespace

    from velpoly.render.canvas import prose_tex
    from velpoly.render.table import _dev, _fmt
    assert [_fmt(x) for x in (1e5, 136550.3, -3.1853, 2.5e-9, 12.5)] == \
        ["100000", "136550", "−3.1853", "2.5×10⁻⁹", "12.5"]
    assert _dev(SimpleNamespace(deviation=0.0041, angle_error=0.21, note="")) == "0.41 %, 0.21°"
    eq = sheet.equation_tex("driver of link 2: turned +180 deg: A_A = A_O2 + alpha_2 x R_AO2 - omega_2^2 R_AO2")
    assert "^" not in eq.replace("^{", "") and r"$\omega_{2}^{2}$" in eq and r"$A_{O_{2}}$" in eq
    assert " − " in eq and "+180°" in eq
    assert sheet.equation_tex("V_A3 = V_A2 + V_A3/A2") == r"$V_{A_{3}}$ = $V_{A_{2}}$ + $V_{A_{3}/A_{2}}$"
    assert prose_tex("perpendicular to O4B") == "perpendicular to $O_{4}$B"
    assert prose_tex("along the slot of 3 at A") == "along the slot of 3 at A"
    from matplotlib.mathtext import MathTextParser
    parser = MathTextParser("path")
    for s in (eq, prose_tex("perpendicular to O4B")):   # mathtext accepts them
        for part in s.split("$")[1::2]:
            parser.parse("$" + part + "$")


@pytest.mark.xdist_group("render-slide-frames")
def test_frames_put_everything_where_the_finished_construction_has_it(slide_frames):
    """--steps: the labels, scale bars, legend and views of every frame are those of the last frame
    (the acceleration scale bar moved from the bottom to the top between frames, labels moved about)."""
    first, last = slide_frames["full"]

    def where(fig):
        out = {}
        for ax in fig.axes:
            for t in ax.texts:
                if t.get_gid():
                    out[(ax.get_label(), t.get_gid())] = tuple(np.round(t.get_position(), 9))
            for p in ax.patches:
                if p.get_gid() == "scale-bar":
                    out[(ax.get_label(), "bar")] = tuple(np.round(p.get_xy(), 9))
            if ax.get_legend() is not None:
                out[(ax.get_label(), "legend")] = tuple(t.get_text() for t in ax.get_legend().get_texts())
            out[(ax.get_label(), "view")] = tuple(np.round(ax.get_xlim() + ax.get_ylim(), 9))
        return out
    a, b = where(first), where(last)
    common = set(a) & set(b)
    assert {("velocity", "bar"), ("acceleration", "bar"), ("velocity", "view"), ("acceleration", "view"),
            ("velocity", "label-velocity-origin+A+D")} <= common
    moved = {k: (a[k], b[k]) for k in common if a[k] != b[k]}
    assert not moved


@sheets.on("textbook")
def test_poles_at_infinity_are_labelled_arrows_beyond_the_mechanism():
    """Each pole at infinity is an arrow pointing its way, beyond the mechanism (at the border of the
    drawing), labelled 'P_ij ∞'; a finite pole out of reach is labelled with its position, minus signs
    and all (ex3_4: P_16, P_17, P_67 at infinity, P_45 far away). Its poles page with its space diagram
    unlabelled (``sheets.bare_page``, shared with the far-pole test): read only."""
    pytest.importorskip("velpoly.poles")
    from velpoly.render.displacement import mechanism_bounds
    sol = sheets.solved("ex3_4_slotted_lever")
    ps = sheets.constructions("ex3_4_slotted_lever", "poles").poles
    fig = sheets.bare_page("ex3_4_slotted_lever", "poles", "textbook")
    ax = next(a for a in fig.axes if any((ln.get_gid() or "").startswith("kennedy-line-") for ln in a.lines))
    x0, y0, x1, y1 = mechanism_bounds(sol)
    inside = box(x0, y0, x1, y1)
    heads = {h.get_gid()[len("pole-"):]: h for h in ax.patches
             if (h.get_gid() or "").startswith("pole-") and hasattr(h, "get_xy")}
    labels = {t.get_gid()[len("label-pole-"):]: t for t in ax.texts if (t.get_gid() or "").startswith("label-pole-")}
    at_infinity = [k for k, p in ps.poles.items() if p.position is None and p.direction is not None]
    assert at_infinity and set(at_infinity) <= set(heads)
    vx0, vx1 = ax.get_xlim()
    vy0, vy1 = ax.get_ylim()
    for k, h in heads.items():
        tip = h.get_xy()[0]
        assert not inside.contains(shapely.Point(*tip)) and vx0 < tip[0] < vx1 and vy0 < tip[1] < vy1
        text = labels[k].get_text()
        if ps.poles[k].position is None:
            assert text.endswith(r"$\infty$")
            d = np.radians(ps.poles[k].direction)
            xy = h.get_xy()
            w = xy[0] - (xy[1] + xy[3]) / 2
            assert abs(_cross(w / np.hypot(*w), [np.cos(d), np.sin(d)])) < 1e-9     # pointing its way
        else:
            assert "(" in text and "-" not in text.split("(")[1]


def test_current_chord_is_heavier_with_dashes_as_long(sixbar):
    """--steps on the poles sheet: the chord of the pole just found is drawn heavier, its dashes as long on
    paper as the other found chords' (matplotlib scaled them with the width: the chord ended in a gap)."""
    pytest.importorskip("velpoly.poles")
    from velpoly.poles import locate_poles
    from velpoly.render.kennedy import draw_kennedy_circle
    m, sol = sixbar
    ps = locate_poles(sol)
    found = sorted((p for p in ps.poles.values() if p.order > 0), key=lambda p: p.order)
    assert len(found) >= 2
    k = found[-1].order
    art = draw_kennedy_circle(sol, _axes((4, 4)), poleset=ps, upto=k)
    chords = {c.get_gid()[len("chord-"):]: c for c in art["chords"]}
    heavy, other = chords[found[-1].key], chords[found[0].key]
    assert heavy.get_linewidth() > other.get_linewidth()
    np.testing.assert_allclose(heavy._dash_pattern[1], other._dash_pattern[1])


def test_current_step_lines_are_heavier_with_dashes_as_long(sixbar):
    """A step frame draws its own construction lines heavier, dashed like the earlier steps' on paper."""
    m, sol = sixbar
    poly = sixbar_velocity(sol)
    art = draw_polygon(poly, _axes(), mechanism=m, upto=4)
    lines = {ln.get_gid().split("-")[1]: ln for ln in art["construction"]}
    heavy, earlier = lines["4"], lines["2"]
    assert heavy.get_linewidth() > earlier.get_linewidth()
    np.testing.assert_allclose(heavy._dash_pattern[1], earlier._dash_pattern[1])


def test_page_title_is_typeset_like_an_equation(tmp_path):
    """A title's ``omega_2`` and ``deg`` read as a book prints them, not as file text."""
    sol = velpoly.solve(velpoly.load(EXAMPLES / "ex3_5_slider_crank.toml"))
    with sheets.unlabelled_mechanism():   # the title read, not the space diagram's marks
        fig = sheet.render_sheet(sol, "velocity")
    title = next(t for t in fig.texts if t.get_gid() == "sheet-title").get_text()
    assert r"$\omega_{2}$ = 10 rad/s ccw" in title and "omega_2" not in title


def test_a_deviation_the_file_explains_is_marked():
    """A book value with a ``[reference] note`` (a misprint) carries its mark († ‡ ...) in the drawn table,
    which its title explains (the note is a footnote); the book's values without a note carry none."""
    from velpoly.polygons import velocity_polygon
    from velpoly.reference import compare
    from velpoly.render.table import NOTED, _printed, results_table
    sol = velpoly.solve(velpoly.load(EXAMPLES / "ex3_10_rolling_contact.toml"))
    refs = compare(sol)
    noted = {_printed(r) for r in refs if r.note}
    plain = {_printed(r) for r in refs if not r.note}
    t = results_table(sol, "velocity", velocity=velocity_polygon(sol))
    col = t.header.index("reference")
    seen = {True: 0, False: 0}
    for row in t.rows:
        if not row[col]:
            continue
        mark = (row[-1].split() or [""])[-1] in {n[0] for n in t.notes}   # † ‡ ...: each note its own mark
        assert row[col] in (noted if mark else plain), row
        seen[mark] += 1
    assert seen[True] and seen[False] and NOTED in t.title
