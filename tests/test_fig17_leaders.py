"""Leaders of pole labels that do not cross (issue 17, item 4: "leaders never crossing").

A crowd of poles has labels with no free place near their rings: each goes, one at a time, to the place that
covers least, and its leader may cross a leader drawn before it. Two labels whose leaders cross are then
exchanged where that leaves fewer crossings (``LabelPlacer.untangle``). Checked at the data level: the
leaders' segments (Line2D data) against each other and against every label's box, on a made-up scene and on
dense generated six-bars (slides) that had crossing leaders before; no label goes onto a Kennedy line or a
leader for it."""
from __future__ import annotations

import itertools

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from shapely.geometry import LineString

from test_pole_labels import DENSE, dense_drawing, dense_sixbars, texts_on_lines
from velpoly.render.canvas import box
from velpoly.render.labels import placer

# of sixbars(5, 36) on slides: leaders crossed in these before (eb22ca2: 18 of the 36), in none of them now. Six-bar
# 10 (slider on frame) is the crowd whose crossing no place for one label or for the two together clears while a third
# stands (P25's leader across P26's with kennedy._clear_with_third disabled by hand): the three placed again now,
# as test_crowd's Stephenson III slide was until issue 19 item 7 (its sheet cost 10-11 CPU s, this drawing 3-6).
# Six-bar 8 (floating guide slider) is the crowd every untangling step leaves crossed (P23's leader across P56's, on
# 6d815d8 too) that is drawn again with its labels in the reverse order (kennedy._least_tangled; test_poles_order's).
# 14, 33 and 35 were cut by issue 19 item 7 (about 2 CPU s): on 7d0e9a2, of thirteen breaks by hand of the label
# placer's steps (each of kennedy._apart's steps, the whole of it, _clear_with_third, labels.REACH_RINGS emptied,
# LabelPlacer.relocate and untangle, _least_tangled, _off_drawn_lines, the Kennedy lines no hard obstacles), those
# that fail them (the Kennedy lines no obstacles: 14 and 33; _apart taken away: 35) fail 3, 8 or 10 too, and with
# the whole of _apart taken away or _clear_of_all or the Kennedy lines' obstacles 10 and 8 fail
UNCROSSED = (3, 8, 10)


def crossings(ax) -> list:
    """(text, text) of every pole label's leader that crosses another label's leader or another label's box."""
    pl = placer(ax)
    lines = {id(p.text): LineString(np.column_stack(p.leader.get_data())) for p in pl.labels if p.leader is not None}
    out = []
    for p in pl.labels:
        line = lines.get(id(p.text))
        if line is None or not (p.text.get_gid() or "").startswith("label-pole-"):
            continue
        for q in pl.labels:
            if q is not p and (q.box.intersects(line) or
                               (id(q.text) in lines and lines[id(q.text)].intersects(line))):
                out.append((p.text.get_gid(), q.text.get_gid()))
    return out


def test_untangle_exchanges_two_crossed_places():
    """Two labels put down with crossed leaders (anchor a to a box beyond b's, b to one beyond a's): exchanged,
    their leaders cross no more, each box keeps its size, each text sits in its box, and the placement a
    frame of ``--steps`` repeats (``placed``) follows."""
    fig = Figure(figsize=(4, 4), dpi=72)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 10)
    pl = placer(ax)
    made = []
    for gid, anchor, centre in (("a", (2.0, 5.0), (8.0, 8.0)), ("b", (2.0, 8.0), (8.0, 5.0))):
        t = ax.text(0, 0, gid.upper(), ha="center", va="center")
        t.set_gid(gid)
        w, h = pl.text_size(t)
        b = box(centre[0] - w / 2, centre[1] - h / 2, centre[0] + w / 2, centre[1] + h / 2)
        pl._put(t, np.array(anchor), (0, np.array(centre), b, 30.0), gid, True, True, None)
        made.append(t)
    assert len(crossings_of(pl)) == 1
    assert pl.untangle(made) == 1
    assert crossings_of(pl) == []
    got = {p.text.get_gid(): p for p in pl.labels}
    assert np.allclose(got["a"].text.get_position(), (8.0, 5.0)) and np.allclose(got["b"].text.get_position(), (8.0, 8.0))
    for p in got.values():
        x0, y0, x1, y1 = p.box.bounds
        assert np.allclose(((x0 + x1) / 2, (y0 + y1) / 2), p.text.get_position())
        assert np.allclose(np.column_stack(p.leader.get_data())[0], p.anchor, atol=0.2)
        assert pl.placed[p.text.get_gid()][1] == tuple(p.text.get_position())
    assert len([ln for ln in ax.lines if (ln.get_gid() or "").endswith("-leader")]) == 2   # the old ones gone


def crossings_of(pl) -> list:
    return [c for c in pl._crossings() if c[2] == "leader"]


@DENSE
def test_crowded_six_bars_leaders_apart():
    """Dense generated six-bars whose pole labels' leaders crossed (a leader across another leader or across a
    label): now none crosses, no pole label or driver's value lies on a Kennedy line or a leader, and every pole
    still has its label."""
    specs = dense_sixbars(5)   # six-bar 3's drawing is test_pole_labels' too: drawn once (their xdist group)
    for i in UNCROSSED:
        ax, art = dense_drawing(5, i, "slides")
        assert not crossings(ax), (i, specs[i].kind, crossings(ax))
        assert not texts_on_lines(ax), (i, texts_on_lines(ax))
        gids = {t.get_gid() for t in ax.texts}
        assert {f"label-pole-{k}" for k in art.labels} <= gids
        assert all(t.axes is ax for t in art.labels.values())   # the labels returned are those drawn
        for a, b in itertools.combinations([p.leader for p in placer(ax).labels if p.leader is not None], 2):
            assert a.axes is ax and b.axes is ax
