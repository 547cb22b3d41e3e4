"""Outside check, the space diagram's frame pivots (docs/figures.md: frame pivots stand on hatched ground): every
frame point a link turns about is drawn with its ground symbol, a pedestal and hatching at the pivot, and no link's
body is drawn over it.

Found by the audit: a cam's or a gear's driving disc is drawn over the links it drives (zorder 3.3), and with it
over its own pivot's ground (2.9): the pivot O of every generated cam and gear (and the gallery's two cams) showed
a bare pin on the disc, no ground (the gallery's two cams too: golden cam_*.svg).
"""
from __future__ import annotations

import matplotlib
import numpy as np
from matplotlib.collections import LineCollection
from shapely.geometry import Point, Polygon

from velpoly.render.displacement import draw_mechanism

import zoo
from mechanisms import shapes_only

matplotlib.use("Agg")


def shape(patch) -> Polygon:
    rings = patch.get_path().to_polygons()
    return Polygon(rings[0], rings[1:]).buffer(0)


def grounds_shown(sol) -> list:
    """Each frame pivot, with whether a ground pedestal stands at it that no body drawn above it covers (the
    space diagram's shapes: no labels or link numbers, ``mechanisms.shapes_only``)."""
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    try:
        art = draw_mechanism(sol, ax, options=shapes_only(sol.mechanism))
        m, frame = sol.mechanism, sol.mechanism.frame.name
        out = []
        for point in sorted({pin.point for pin in m.pins if frame in pin.links}):
            at = Point(*np.asarray(sol.place(frame, point), float))
            pedestals = [a for a in art["ground"] if not isinstance(a, LineCollection)
                         and shape(a).distance(at) < 1e-9 * m.size]
            hatches = [a for a in art["ground"] if isinstance(a, LineCollection)]
            seen = any(not any(b.get_zorder() > p.get_zorder() and shape(b).contains(shape(p).centroid)
                               for b in art["links"] if b.get_fill())
                       and any(h.get_zorder() >= p.get_zorder() for h in hatches) for p in pedestals)
            out.append((point, seen))
        return out
    finally:
        plt.close(fig)


def test_every_frame_pivot_of_a_cam_gear_or_contact_stands_on_ground():
    rng = np.random.default_rng(20271127)
    checked = 0
    for variant in zoo.CONTACTS:   # every contact the zoo makes: wheels, gears, cams, at a random draw each
        sp = zoo.specimen(rng, "contact", variant)
        for point, seen in grounds_shown(sp.drawn):
            assert seen, (variant, point)
            checked += 1
    assert checked >= 12
