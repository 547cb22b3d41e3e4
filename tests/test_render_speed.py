"""The faster paths of drawing (issue 20) give what the slower ones gave.

A PNG written by velpoly.render.pngfile decodes to the pixels of matplotlib's own PNG of the same
figure (opaque sheets as RGB, a transparent figure keeps its alpha), with matplotlib's metadata.
"""
from __future__ import annotations

import io

import numpy as np
import pytest

import velpoly
from velpoly.render.style import get_style, rc_context
from paths import example


def _pixels(data: bytes):
    from PIL import Image
    im = Image.open(io.BytesIO(data))
    return im, np.asarray(im.convert("RGBA"))


@pytest.mark.parametrize("name, sheet, style", [("problem_1_4_4_sixbar", "full", "textbook"),
                                                ("ex3_7_instant_centres", "poles", "slides")])
def test_a_sheet_s_png_has_matplotlib_s_pixels(name, sheet, style):
    from velpoly.render.pngfile import save_png
    from velpoly.render.sheet import render_sheet
    from velpoly.render.style import get_style, rc_context
    sol = velpoly.solve(velpoly.load(example(name)))
    st = get_style(style)
    with rc_context(st):
        fig = render_sheet(sol, sheet, st)
        theirs, ours = io.BytesIO(), io.BytesIO()
        fig.savefig(theirs, format="png", dpi=st.dpi, metadata={})
        save_png(fig, ours, st.dpi)
    (a, pa), (b, pb) = _pixels(theirs.getvalue()), _pixels(ours.getvalue())
    assert a.mode == "RGBA" and b.mode == "RGB" and pa[..., 3].min() == 255
    assert a.size == b.size and np.array_equal(pa, pb)
    assert b.info["Software"] == a.info["Software"] and b.info["dpi"] == a.info["dpi"]
    assert len(ours.getvalue()) < len(theirs.getvalue())


def test_a_transparent_figure_keeps_its_alpha():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from velpoly.render.pngfile import save_png
    fig = Figure(figsize=(2.0, 1.5), dpi=72)
    FigureCanvasAgg(fig)
    fig.patch.set_alpha(0.0)
    fig.add_axes((0.1, 0.1, 0.8, 0.8)).plot([0, 1], [0, 1], "r-")
    theirs, ours = io.BytesIO(), io.BytesIO()
    fig.savefig(theirs, format="png", dpi=100, metadata={})
    save_png(fig, ours, 100, metadata={"Title": "t"})
    (a, pa), (b, pb) = _pixels(theirs.getvalue()), _pixels(ours.getvalue())
    assert b.mode == "RGBA" and pa[..., 3].min() == 0 and np.array_equal(pa, pb)
    assert b.info["Title"] == "t" and b.size == (200, 150)


# -- the results table measured, not drawn, while a sheet's layout tries its rooms -------------------------

def _table_specimens():
    """Generated mechanisms (tests/zoo.py): a slot, and a six-bar with a book value explained in a footnote."""
    import copy
    import zoo
    rng = np.random.default_rng(2020)
    six, slot = (zoo.specimen(rng, kind, zoo.KINDS[kind][1][0]) for kind in ("six-bar", "slot"))
    m = six.drawn.mechanism
    lk = [k.name for k in m.moving_links if k.name != m.driver.link][-1]
    mech = copy.deepcopy(six.mech)
    mech["reference"] = {"source": "Problem 9.99 of a book with a long name that wraps the table's title",
                         "omega": {lk: round(six.drawn.omega[lk] * 1.33, 6)},
                         "note": {f"omega_{lk}": "misprint: the book's value carries a slip of the pen, " * 3}}
    return [slot.drawn, velpoly.solve(velpoly.load(mech))]


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_a_table_measured_for_its_room_is_the_table_drawn_there(style):
    """measure_results_table (no axes, no artists: what a sheet's layout does for every room it tries) gives
    what the table measured in an axes at that room gives, to the bit (its size, the share of the room it
    uses, the rows shown, every rule and text), and the table drawn from the measurement puts its ink within
    the height it said it uses, down to its last line; on generated mechanisms, in a roomy, a short and a
    narrow room (type shrunk, rows cut, blocks side by side, footnotes)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from velpoly.render.sheet import constructions
    from velpoly.render.table import draw_results_table, measure_results_table
    st = get_style(style)
    rects = [(0.01, 0.02, 0.97, 0.45), (0.01, 0.5, 0.97, 0.13), (0.6, 0.1, 0.25, 0.5)]   # roomy, short, narrow
    seen = set()
    with rc_context(st):
        for sol in _table_specimens():
            cons = constructions(sol, "full")
            kw = dict(sheet="full", style=st, velocity=cons.velocity, acceleration=cons.acceleration,
                      poleset=cons.poles)
            for rect in rects:
                fig = Figure(figsize=st.figsize, dpi=72)
                FigureCanvasAgg(fig)
                lay = measure_results_table(sol, (fig, rect), **kw)
                assert not fig.axes   # nothing made, nothing drawn
                there = measure_results_table(sol, fig.add_axes(rect), **kw)   # measured in an axes there
                assert [(x.used, x.whole, x.size, x.shown, x.blocks, x.notes, x.title, x.rules, x.cells, x.footnotes)
                        for x in (lay, there)] == [(there.used, there.whole, there.size, there.shown, there.blocks,
                                                    there.notes, there.title, there.rules, there.cells,
                                                    there.footnotes)] * 2
                art = draw_results_table(sol, fig.add_axes(rect), layout=lay, style=st)
                assert (art.used, art.shown, art.size, art.notes) == (lay.used, lay.shown, lay.size, lay.notes)
                r = fig.canvas.get_renderer()
                box = art.ax.get_window_extent(r)
                ink = [a.get_window_extent(r) for a in art.all()]
                low = min(b.y0 for b in ink)
                bottom = box.y1 - lay.used * box.height   # where the table said it ends
                assert low <= bottom + 1.0 * lay.size * fig.dpi / 72, (rect, low, bottom)
                assert lay.used == 1.0 or low >= bottom - 1e-6, (rect, low, bottom)   # (1: more than its room)
                assert max(b.y1 for b in ink) <= box.y1 + 1e-6 and min(b.x0 for b in ink) >= box.x0 - 1e-6
                seen.add((lay.shown < len(lay.table.rows), bool(lay.notes),
                          len(lay.blocks) > 1 if style == "textbook" else lay.size < st.small_size))
    # rows cut, footnotes; blocks side by side (textbook), type shrunk (the slides' large type)
    assert all(any(s[i] for s in seen) for i in range(3)), seen


def test_figures_share_their_mathtext_parses_and_only_the_same_ones():
    """Every renderer has its own mathtext parser; velpoly.render.style.share_mathtext lets them share what
    they parsed: a second parser gets the first one's parse of the same text, dpi, font and settings (the
    very object), and a fresh one where any of them differs (another dpi, font size, output type, or a
    mathtext setting changed in between)."""
    import matplotlib
    from matplotlib.font_manager import FontProperties
    from matplotlib.mathtext import MathTextParser
    from velpoly.render.style import share_mathtext
    assert share_mathtext() and share_mathtext()   # installed once, idempotent
    prop = FontProperties(family="DejaVu Sans", size=9.0)
    text = r"$V_{B_{3}/B_{4}} = \omega_{2}^{2}\,R$ (test 20)"
    a, b = MathTextParser("agg"), MathTextParser("agg")
    first = a.parse(text, 72, prop)
    assert b.parse(text, 72, prop.copy()) is first
    others = [b.parse(text, 200, prop), b.parse(text, 72, FontProperties(family="DejaVu Sans", size=9.5)),
              MathTextParser("path").parse(text, 72, prop)]
    assert all(o is not first for o in others) and others[0].width > 2.5 * first.width
    with matplotlib.rc_context({"mathtext.default": "bf"}):
        bold = b.parse(text, 72, prop)
    assert bold is not first and bold.width != first.width
    assert b.parse(text, 72, prop) is first   # the setting back: the first parse again

