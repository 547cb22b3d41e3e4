"""What the space diagram shows of the driver and the links (issue 17, item 7; render/displacement.py).

At the data level, on seeded zoo mechanisms of every kind and on the gallery's files: the driver's
alpha is its own curved arrow turning in alpha's sense (none when alpha = 0), omega's in omega's; a
slider driver's acceleration is an arrow along its path in the sense of its acceleration (none when
zero), next to its speed's arrow (clear of it, within BESIDE of it) and by its block; the driver crank lies over every link and block it touches; a link of three or more points drawn
as a plate is one light-filled Polygon patch with its corners at its points; on slides a link number's
circle is no larger in radius than a link's width.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import to_rgb
from matplotlib.figure import Figure
from matplotlib.patches import Polygon as MPolygon
from shapely.geometry import LineString, MultiPoint, Point

import sheets
import zoo
from velpoly.render.canvas import per_cm
from velpoly.render.displacement import NUMBER_RADIUS, draw_mechanism, plate_outline
from velpoly.render.options import drawing_options
from velpoly.render.style import get_style, rc_context


def _draw(sol, style="textbook"):
    """The space diagram of ``sol`` with what these checks read: the driver's marks, the bodies, and on slides the
    link numbers (their circles' size is checked there); no point labels (none is checked: the label placer was
    most of the cost), and on textbook no link numbers either (nothing of them is checked there; without them the
    driver's marks are placed once, not again for a number that reads as another link's). The driver's arcs and
    arrows are made whatever their place, the bodies and zorders before any mark (``mechanisms.shapes_only``)."""
    st = get_style(style)
    fig = Figure(figsize=(8, 6), dpi=72)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
    opts = replace(drawing_options(sol.mechanism), label_points=(),
                   link_numbers=drawing_options(sol.mechanism).link_numbers if style == "slides" else "none")
    with rc_context(st):
        art = draw_mechanism(sol, ax, style=st, options=opts)
    return ax, art


def _gid(art, role, gid):
    return [a for a in art.get(role, []) if a.get_gid() == gid]


BESIDE = 2.5     # cm: a slider driver's acceleration arrow at most this far from its speed's (next to it)
BY_BLOCK = 3.5   # cm: and from the block's point (beside the block, along its path)


def _shaft(art, gid):
    """A straight driver arrow's whole length (tail to tip, shapely), from its shaft's tail and its head's tip."""
    (shaft,) = _gid(art, "driver", gid + "-shaft")
    (head,) = _gid(art, "driver", gid)
    return LineString([tuple(np.column_stack(shaft.get_data())[0]), tuple(head.get_xy()[0])])


def _sweep(xy, p) -> np.ndarray:
    """The steps of the angle (rad) of the points ``xy`` about ``p``."""
    return np.diff(np.unwrap(np.arctan2(xy[:, 1] - p[1], xy[:, 0] - p[0])))


def check_driver(sol, art):
    m = sol.mechanism
    drv = m.driver
    if drv.is_slider:
        s = next(s for s in m.sliders if s.point == drv.slider)
        t = math.radians(float(sol.motion.sliders[m.sliders.index(s)]["direction"][0]))
        path = np.array([math.cos(t), math.sin(t)])
        for gid, value in (("driver-arrow", drv.speed), ("driver-accel-arrow", drv.accel)):
            heads = _gid(art, "driver", gid)
            if gid == "driver-accel-arrow" and not value:
                assert not heads
                continue
            (head,) = heads
            tip, base = head.get_xy()[0], 0.5 * (head.get_xy()[1] + head.get_xy()[3])
            d = (tip - base) / np.hypot(*(tip - base))
            assert abs(abs(float(d @ path)) - 1) < 1e-9                          # along the path
            assert np.sign(float(d @ path)) == np.sign(value)                    # in its sense
        if drv.accel:   # the acceleration's arrow beside the speed's (next to it, clear of it) and by the block
            speed, accel = (_shaft(art, gid) for gid in ("driver-arrow", "driver-accel-arrow"))
            block = np.asarray(sol.place(s.block, s.point), float)
            cm = 1.0 / per_cm(art.ax)
            assert 0 < speed.distance(accel) * cm <= BESIDE, speed.distance(accel) * cm
            assert accel.distance(Point(*block)) * cm <= BY_BLOCK, accel.distance(Point(*block)) * cm
        return
    pivot = next(pin.point for pin in m.pins if set(pin.links) == {drv.link, m.frame.name})
    p = np.asarray(sol.position.get(pivot, sol.place(drv.link, pivot)), float)
    for name, value in (("driver", drv.omega), ("driver-alpha", drv.alpha)):
        arcs = _gid(art, "driver", name + "-arc")
        if name == "driver-alpha" and not value:
            assert not arcs and not _gid(art, "driver", "driver-alpha-arrow")
            continue
        (arc,) = arcs
        xy = np.column_stack(arc.get_data())
        (head,) = _gid(art, "driver", name + "-arrow")
        tip = head.get_xy()[0]
        steps = _sweep(np.vstack([xy, tip]), p)
        assert np.all(np.sign(steps) == np.sign(value)), name                   # the arc turns in its sense
        if name == "driver-alpha":
            assert len(_gid(art, "driver", "driver-alpha-second")) == 1          # two heads: an acceleration
            label = _gid(art, "driver", "driver-label-alpha")[0].get_text()
            assert label.endswith("ccw" if value > 0 else " cw") and r"\alpha" in label


def check_links(sol, ax, art, style):
    m = sol.mechanism
    st = get_style(style)
    pc = per_cm(ax)
    patches = {p.get_gid(): p for p in art["links"] if p.get_gid()}
    blocks = {p.get_gid()[len("block-"):]: p for p in art.get("sliders", []) if p.get_gid()}
    drv = None if m.driver.is_slider else m.driver.link
    slotted = {s.slot for s in m.slots if not m.link(s.slot).frame} | \
        {s.guide for s in m.sliders if not m.link(s.guide).frame}
    if drv is not None and drv not in slotted and f"link-{drv}" in patches:
        z = patches[f"link-{drv}"].get_zorder()
        body = art.bodies[drv]
        for lk, g in art.bodies.items():
            if lk != drv and g.intersects(body):
                assert z > patches[f"link-{lk}"].get_zorder(), (drv, lk)
        for lk, b in blocks.items():
            assert z > b.get_zorder(), (drv, "block", lk)
    shaped = slotted | {lk for c in m.contacts for lk in c.links}     # links with a slot, a guide or a profile
    for link in m.moving_links:
        plate = plate_outline(sol, link.name, st.bar_width * pc)
        if link.name in art.plates:
            assert plate is not None, link.name
        elif plate is not None:    # not drawn as a plate: only a link with a slot, a guide or a profile's shape
            assert link.name in shaped, link.name
        if link.name not in art.plates:
            continue
        (patch,) = [p for p in art["links"] if p.get_gid() == f"link-{link.name}"]
        assert isinstance(patch, MPolygon)
        corners = patch.get_xy()
        pts = np.array([sol.place(link.name, q) for q in link.points])
        hull = MultiPoint([tuple(q) for q in pts]).convex_hull
        assert len({tuple(np.round(c, 9)) for c in corners}) == len(hull.exterior.coords) - 1
        for c in corners:                                                      # each corner is a point of the link
            assert np.min(np.hypot(*(pts - c).T)) <= 1e-9 * m.size
        for q in pts:                                                          # the plate holds every point
            assert hull.buffer(1e-9 * m.size).contains(Point(*q))
        assert min(to_rgb(patch.get_facecolor()[:3])) >= 0.6 and patch.get_facecolor()[:3] != (1, 1, 1)
    if style == "slides":
        r = ax.figure.canvas.get_renderer()
        assert art.get("link_numbers"), "no link number drawn"
        for t in art.get("link_numbers", []):
            if t.get_bbox_patch() is None:
                continue
            bb = t.get_bbox_patch().get_window_extent(r)
            radius_cm = max(bb.width, bb.height) / 2 / ax.figure.dpi * 2.54
            assert radius_cm <= NUMBER_RADIUS * st.bar_width * (1 + 1e-6) <= st.bar_width, t.get_text()


def test_driver_and_links_on_generated_mechanisms():
    """Every kind of the zoo (seeded; every seventh variant, 9 of them: every fourth, 14, until the suite had to
    fit 2 minutes), in both styles alternately: the driver's arrows in their senses, the driver on top, plates as
    one polygon, slides circles no larger than the links. Only the nine drawn are made (from one seeded
    generator: until issue 19 item 7's twelfth session, the first 57 of ``zoo(77)`` were made and every seventh
    drawn; 0.9 CPU s for 48 specimens never looked at)."""
    rng = np.random.default_rng(77)
    pairs = zoo.variants()[::7]                          # every kind, a seventh of the variants
    assert {k for k, _ in pairs} == set(zoo.KINDS)
    specimens = [zoo.specimen(rng, *pair) for pair in pairs]
    kinds = {"alpha": 0, "no alpha": 0, "slider accel": 0, "plate": 0}
    for i, sp in enumerate(specimens):
        sol = sp.drawn
        style = ("textbook", "slides")[i % 2]
        ax, art = _draw(sol, style)
        check_driver(sol, art)
        check_links(sol, ax, art, style)
        drv = sol.mechanism.driver
        if drv.is_slider:
            kinds["slider accel"] += bool(drv.accel)
        else:
            kinds["alpha" if drv.alpha else "no alpha"] += 1
        kinds["plate"] += any(isinstance(p, MPolygon) for p in art["links"])
    assert all(v >= 2 for v in kinds.values()), kinds


@pytest.mark.parametrize("name, style", [("ex3_10_rolling_contact", "textbook"), ("ex3_10_rolling_contact", "slides"),
                                         ("watt_sixbar", "slides"), ("ex3_4_slotted_lever", "textbook"),
                                         ("ex3_3_inverted_slider", "slides"), ("stephenson_sixbar", "textbook")])
def test_driver_and_links_on_gallery_files(name, style):
    """Example 3.10 (alpha = 7 cw; plates 3 and 6), the Watt six-bar (alpha = 20 ccw; plate 4), Example 3.4
    (the crank over the block in the lever's slot), Example 3.3 and the Stephenson six-bar."""
    sol = sheets.solved(name)   # solved once a process (Example 3.10 for both styles; the gallery's tests too)
    ax, art = _draw(sol, style)
    check_driver(sol, art)
    check_links(sol, ax, art, style)
    if name in ("ex3_10_rolling_contact", "watt_sixbar"):
        assert _gid(art, "driver", "driver-alpha-arc")
        assert any(isinstance(p, MPolygon) for p in art["links"])
