"""A crowd of poles whose labels, placed one at a time, leave leaders crossing is drawn again with its labels placed
in another order (issue 17 item 4: "leader lines of pole labels cross so that one cannot tell which ring is which";
``kennedy.draw_poles``).

The specimen is the generated eight-bar of ``zoo(2026, 57)`` (its 57th, a Watt II with a dyad to the crank: 28
poles in a few centimetres), its poles drawing on a page of its own in the textbook style. On main 6d815d8 two pairs
of leaders crossed there (P12's and P57's, P24's and the driver's alpha value's); placed in the reverse order none
do. Checked at the data level: each leader as drawn (its Line2D, in display coordinates) against every other.
"""
from __future__ import annotations

import itertools

import numpy as np
from shapely.geometry import LineString

import zoo
from test_leaders_zoo import astray
from test_pole_labels import _poles_drawing
from velpoly.render.style import get_style


def drawn_leaders(ax) -> dict:
    """Each leader drawn on ``ax`` (by its label's gid) as a shapely segment in display coordinates."""
    return {ln.get_gid()[:-len("-leader")]: LineString(ax.transData.transform(np.column_stack(ln.get_data())))
            for ln in ax.lines if (ln.get_gid() or "").endswith("-leader")}


def test_an_eight_bars_pole_leaders_cross_no_leader_and_labels_sit_by_their_rings():
    """No leader of a pole label crosses another leader, and each pole label is nearer its own ring than any other
    (or has its leader from its own ring), on the generated eight-bar's poles drawing."""
    sp = zoo.zoo(2026, 57)[56]
    assert sp.kind.startswith("eight-bar")
    ax, art = _poles_drawing(sp.drawn, get_style("textbook"))
    lines = drawn_leaders(ax)
    poles = [g for g in lines if g.startswith("label-pole-")]
    assert len(poles) >= 15, len(poles)
    crossed = [(a, b) for a, b in itertools.combinations(sorted(lines), 2)
               if (a in poles or b in poles) and lines[a].intersects(lines[b])]
    assert not crossed, crossed
    assert not astray(ax, art.rings), astray(ax, art.rings)
    assert len(art.labels) == 28 and all(t.axes is ax for t in art.labels.values())   # every pole labelled, once
