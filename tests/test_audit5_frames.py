"""Outside check, audit 5: every frame of an animation draws its polygons within their panels.

Found by the audit: a slider-driven slider-crank (O2 at the origin, crank 3 at 60 deg, coupler 10, the slider on
the guide y = 1 driven at speed 2) drew the velocity polygon of its first frames off the panel: near the dead
centre the crank's omega grows without bound, and the panel's scale leaves out such a toggle's surge frames
(animate._surge_box). Such a frame is now drawn at 1/2, 1/5, 1/10 ... of the scale, within the panel, and says
so beside the scale bar ("drawn at 1/5 scale"); every other frame is drawn as before.
"""
from __future__ import annotations

import numpy as np

import velpoly
from velpoly.render.animate import Animator, plan_frames

import zoo

SMALL = (320, 180)


def slider_driven():
    rng = np.random.default_rng(5)
    for kind, variant in (("slider-crank", "offset slider"), ("slider-crank", "through slider"),
                          ("slider-crank", "curved slider")):
        yield zoo.specimen(rng, kind, variant).mech


def test_every_frames_polygons_lie_within_their_panels():
    reduced = {"velocity": 0, "acceleration": 0}
    for mech in slider_driven():
        m = velpoly.load(mech)
        plan = plan_frames(m, 20.0)
        anim = Animator(plan, "full", "slides", SMALL)
        polys = {kind: anim.polys[kind] for kind in ("velocity", "acceleration")}
        for k in range(len(plan)):
            anim.update(k)
            for kind, art in anim._poly_art.items():
                ax = art["ax"]
                x0, x1 = ax.get_xlim()
                y0, y1 = ax.get_ylim()
                drawn = [np.asarray(a.get_xydata() if hasattr(a, "get_xydata") else a.get_xy(), float)
                         for pair in art["arrows"].values() for a in pair if a.get_visible()]
                drawn += [np.asarray(p.get_xy(), float) for p in art["shades"].values() if p.get_visible()]
                xy = np.vstack(drawn)
                assert (x0 <= xy[:, 0]).all() and (xy[:, 0] <= x1).all() and (y0 <= xy[:, 1]).all() \
                    and (xy[:, 1] <= y1).all(), (m.title, k, kind)
                n = anim.reduction[kind][k]
                # drawn at 1/n of the scale, and saying so: each absolute vector's tip is the image over n
                assert art["note"].get_text() == ("" if n == 1 else f"drawn at 1/{n} scale"), (k, kind)
                for key, image in polys[kind][k].images.items():
                    if f"abs-{key}" in art["arrows"] and art["arrows"][f"abs-{key}"][0].get_visible():
                        shaft, head = art["arrows"][f"abs-{key}"]   # (drawn apart from one on its line: shifted)
                        v = np.asarray(head.get_xy())[0] - shaft.get_xydata()[0]
                        assert np.hypot(*(v * n - np.asarray(image))) <= 1e-9 * np.hypot(*image), (k, kind, key)
                reduced[kind] += n > 1
    assert reduced["velocity"] >= 2 and reduced["acceleration"] >= 10, reduced   # the surge frames
