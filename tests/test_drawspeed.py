"""The drawing's shortcuts give what the slow path gives (velpoly/render: session drawspeed).

* a polygon's legend variants (:class:`velpoly.render.polygon._Variants`), measured as they are read,
  are the sizes :func:`_legend_sizes` measures all at once;
* a table's drawn width (:func:`velpoly.render.table.drawn_extent`), its texts' layouts kept, is the
  width measured afresh and the width of the table as drawn, to the bit;
* an axes whose artists share its background Rectangle's transform
  (:func:`velpoly.render.textcache.share_rectangle_transforms`) clips them where fresh transforms do,
  also after it moves, and writes the same SVG.

On generated mechanisms (tests/zoo.py, tests/mechanisms.py), each drawn small (well under a CPU second
for the file).
"""
from __future__ import annotations

import io

import numpy as np

import velpoly
from velpoly.polygons import acceleration_polygon
from velpoly.render import polygon, table, textcache
from velpoly.render.style import get_style, rc_context

import mechanisms
import zoo


def _figure(size=(5.0, 4.0)):
    from matplotlib.figure import Figure
    from velpoly.render.textcache import new_canvas
    fig = Figure(figsize=size, dpi=72)
    new_canvas(fig)
    return fig


def _sols():
    """A slider-crank (its acceleration polygon has a legend of three kinds) and a zoo specimen."""
    return [velpoly.solve(velpoly.load(mechanisms.slider_crank())), zoo.zoo(seed=7, count=1)[0].drawn]


SOLS = _sols()


def test_legend_variants_read_are_all_variants_measured(monkeypatch):
    """Each legend variant read (lazily) has the size measuring every variant at once gives it."""
    checked, lazy = [], polygon._Variants

    class Checked(lazy):
        def __init__(self, ax, pl, make, st):
            super().__init__(ax, pl, make, st)
            self.all = list(lazy(ax, pl, make, st))   # (_legend_sizes: every variant, in order)

        def __getitem__(self, i):
            got = super().__getitem__(i)
            checked.append(got == self.all[i])
            return got
    monkeypatch.setattr(polygon, "_Variants", Checked)
    st = get_style("slides")
    with rc_context(st):
        for sol in SOLS:
            fig = _figure()
            polygon.draw_polygon(acceleration_polygon(sol), fig.add_axes((0, 0, 1, 1)),
                                 mechanism=sol.mechanism, style=st)
    assert checked and all(checked)


def _measured(room, x, y, s, **kw):
    """What _Room.extent was before its layouts were kept: a text made and measured by matplotlib."""
    from matplotlib.text import Text
    t = Text(x, y, s, **{"verticalalignment": "baseline", "horizontalalignment": "left", "transform": room.trans,
                         "clip_on": False, **kw})
    t.set_figure(room.figure)
    return t.get_window_extent(room.renderer)


def test_text_extents_with_layouts_kept_are_to_the_bit(monkeypatch):
    """_Room.extent with its layouts kept (measured, then found in a room elsewhere) is matplotlib's extent to the
    bit, on generated texts (math, two lines, aligned, italic, sizes), and so is a table's drawn_extent."""
    rng = np.random.default_rng(5)
    st = get_style("slides")
    with rc_context(st):
        fig = _figure((13.333, 7.5))
        texts = ["$V_{B_{3}}$ = 12.5 m/s", "x", "‡ $\\omega_{3}$: rounded\nsecond line", "$A^{t}_{C}$", "−0.0314"]
        textcache.clear()
        for k, s in enumerate(texts):
            kw = dict(fontsize=float(rng.uniform(5, 14)), **({"style": "italic", "va": "top"} if k % 2 else {}))
            for _ in range(2):   # measured, then found
                rect = tuple(rng.uniform(0.0, 0.5, 2)) + tuple(rng.uniform(0.1, 0.5, 2))
                room, (x, y) = table._Room(fig, rect), rng.uniform(-0.2, 1.2, 2)
                assert np.array_equal(room.extent(x, y, s, **kw).get_points(),
                                      _measured(room, x, y, s, **kw).get_points()), (s, kw)
        sol = SOLS[0]
        lay = table.measure_results_table(sol, (fig, (0.05, 0.05, 0.5, 0.3)), style=st, sheet="velocity")
        got = []
        for rect in ((0.05, 0.05, 0.5, 0.3), (0.3137, 0.0713, 0.5, 0.3)):
            lay.set_position(rect)
            textcache.clear()
            fresh = table.drawn_extent(lay, fig)
            kept = table.drawn_extent(lay, fig)
            with monkeypatch.context() as mp:
                mp.setattr(table._Room, "extent", _measured)
                slow = table.drawn_extent(lay, fig)
            assert fresh == kept == slow
            got.append(kept)
        assert got[0] != got[1]


def test_shared_rectangle_transform_clips_as_fresh_ones():
    """Artists of an axes with the shared transform are clipped where those of a plain axes are, after moves,
    and the figures write the same SVG."""
    from matplotlib.patches import Circle
    from velpoly.render.textcache import share_rectangle_transforms
    svgs, clips = [], []
    for share in (False, True):
        with rc_context(get_style("textbook")):   # (its svg.hashsalt: the clip paths' ids are their contents')
            fig = _figure()
        ax = fig.add_axes((0.1, 0.1, 0.5, 0.5))
        if share:
            share_rectangle_transforms(ax)
        arts = [ax.plot([0, 1], [0, 1])[0], ax.text(0.5, 0.5, "$V_{B}$"),
                ax.add_patch(Circle((0.2, 0.3), 0.1))]
        ax.set_position((0.2, 0.15, 0.6, 0.7))
        ax.set_xlim(-1, 2)
        clips.append(np.array([a.clipbox.get_points() for a in arts]))
        buf = io.StringIO()
        with rc_context(get_style("textbook")):
            fig.savefig(buf, format="svg", metadata={"Date": None})
        svgs.append(buf.getvalue())
    assert np.array_equal(clips[0], clips[1])
    assert svgs[0] == svgs[1]
