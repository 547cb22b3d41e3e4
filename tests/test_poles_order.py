"""A crowd of poles whose labels, placed one at a time, leave leaders crossing is drawn again with its labels placed
in another order (issue 17 item 4: "leader lines of pole labels cross so that one cannot tell which ring is which";
``kennedy.draw_poles``, ``kennedy._least_tangled``).

The specimen is the dense generated six-bar 8 of seed 5 (a floating guide driven by its slider: 15 poles), its poles
drawing on a page of its own in the slides style (``test_pole_labels.dense_drawing(5, 8, "slides")``: drawn once a
worker in the dense six-bars' xdist group, test_fig17_leaders and test_leaders_zoo check it too). Placed in the
listed order, P23's leader crosses P56's and every untangling step leaves it so; placed in the reverse order none
crosses. On main 6d815d8 (before the orders) and on 7d0e9a2 with the other orders taken away by hand
(``kennedy._crossed`` answering 0) those two leaders cross. Until issue 19 item 7 the specimen was the eight-bar of
``zoo(2026, 57)`` (its 57th, a Watt II with a dyad to the crank: 28 poles in a few centimetres; two pairs of
leaders crossed on 6d815d8), drawn twice in the textbook style for this test alone, 6.6 CPU s, the suite's
dearest test; the six-bar is drawn twice too, in about half that, and shared. Checked at the data level: each
leader as drawn (its Line2D, in display coordinates) against every other.
"""
from __future__ import annotations

import itertools

import numpy as np
from shapely.geometry import LineString

from test_leaders_zoo import astray
from test_pole_labels import DENSE, dense_drawing, dense_sixbars


def drawn_leaders(ax) -> dict:
    """Each leader drawn on ``ax`` (by its label's gid) as a shapely segment in display coordinates."""
    return {ln.get_gid()[:-len("-leader")]: LineString(ax.transData.transform(np.column_stack(ln.get_data())))
            for ln in ax.lines if (ln.get_gid() or "").endswith("-leader")}


@DENSE
def test_a_crowds_pole_leaders_cross_no_leader_and_labels_sit_by_their_rings():
    """No leader of a pole label crosses another leader, and each pole label is nearer its own ring than any other
    (or has its leader from its own ring), on the generated six-bar's poles drawing."""
    assert dense_sixbars(5)[8].kind == "six-bar floating guide slider"
    ax, art = dense_drawing(5, 8, "slides")   # read only
    lines = drawn_leaders(ax)
    poles = [g for g in lines if g.startswith("label-pole-")]
    assert len(poles) >= 10, len(poles)   # (13 when measured)
    crossed = [(a, b) for a, b in itertools.combinations(sorted(lines), 2)
               if (a in poles or b in poles) and lines[a].intersects(lines[b])]
    assert not crossed, crossed
    assert not astray(ax, art.rings), astray(ax, art.rings)
    assert len(art.labels) == 15 and all(t.axes is ax for t in art.labels.values())   # every pole labelled, once
