"""A sheet's results table keeps its blocks side by side where the page has their width (issue 17, the
layout leftovers, item 1).

A table whose rows do not fit one block (or that would take less of the page's height in more) stands in
blocks side by side, each block as wide as its own columns: a block of velocities beside one of accelerations
(the accelerations have no "instant centres" column), not only where the page has twice the whole table's
width. Before, a table narrowed to the page's corner fell back to one tall block there (the cam with a roller
follower's textbook sheet, blank fraction 0.555 -> 0.616).

Checked on the full and poles sheets of generated mechanisms (tests/zoo.py; some given a book's many answers,
tests/test_table_page.py) in both styles, at the data level: the table drawn (its measured layout) is in as
many blocks as fit its room's width, by its cells' measured widths, wherever more blocks would take fewer lines;
its ink (texts and rules) lies under no panel and on no caption (the Kennedy circle's caption, wider than its
panel on a slide, once had the table's title on it).
"""
from __future__ import annotations

import numpy as np
import pytest
from shapely.geometry import box

import velpoly
from test_table_page import book_reference
from velpoly.render import sheet, table
from velpoly.render.style import get_style, rc_context

import sheets
import zoo

BGAP, GAP = 3.0, 1.6   # the gap between blocks and between columns, in type sizes (velpoly.render.table)


def _width(lay, chunks) -> float:
    """The width (points) of blocks of the rows ``chunks`` side by side at the table's type size, each with the
    columns its rows fill (the quantity always), from the cells' measured widths."""
    t, size = lay.table, lay.size
    total = BGAP * size * (len(chunks) - 1)
    for chunk in chunks:
        cols = [i for i in range(len(t.header)) if i == 0 or any(r[i] for r in chunk)] if len(chunks) > 1 \
            else list(range(len(t.header)))
        wb = lay.widths_of.columns(size, chunk, cols)
        total += sum(wb) + GAP * size * (len(wb) - 1)
    return total


def _drawn(sol, name, style, cons, monkeypatch):
    """The sheet ``name`` of ``sol`` in ``style``: (figure, the measured layout of the table it draws); its space
    diagram without its marks (``sheets.unlabelled_mechanism``: the table and the panels' places are read)."""
    drawn = []
    real = sheet._draw_table

    def spy(sol, fig, sheet_name, st, layout):
        art = real(sol, fig, sheet_name, st, layout)
        drawn.append((art.ax, layout))
        return art
    monkeypatch.setattr(sheet, "_draw_table", spy)
    st = get_style(style)
    with rc_context(st), sheets.unlabelled_mechanism():   # the table and the panels' places read, not the marks
        fig = sheet.render_sheet(sol, name, st, cons=cons)
        fig.draw_without_rendering()
    monkeypatch.undo()
    (lay,) = [lay for ax, lay in drawn if ax in fig.axes]   # (the layout's trial drawings are taken away)
    return fig, lay


def _cases():
    """(kind, file, style, sheet): generated four-bars, inverted slider-cranks and a six-bar (tests/zoo.py; on
    textbook pages one table in one block where two or three were tried, one narrowed in the page's corner in
    two blocks), a six-bar and a slider-crank given a book's many answers, on slides and on a poles sheet, and a
    poles slide in two narrowed blocks. Cut when the suite had to fit 2 minutes: zoo 22 (textbook, two narrowed
    blocks as zoo 12) and zoo 7's poles slide (two narrowed blocks as zoo 1's, no more blocks to try)."""
    specimens = zoo.zoo(5, 27)
    out = [(specimens[i].kind, specimens[i].mech, style, "full")
           for i, style in ((0, "textbook"), (12, "textbook"), (5, "slides"), (26, "slides"))]
    rng = np.random.default_rng(1717)
    book = [zoo.specimen(rng, "six-bar", "watt II"), zoo.specimen(rng, "slider-crank", "offset crank")]
    return out + [(book[0].kind, book_reference(book[0], notes=2), "slides", "full"),
                  (book[1].kind, book_reference(book[1], notes=2), "textbook", "poles"),
                  (specimens[1].kind, specimens[1].mech, "slides", "poles")]


@sheets.on("textbook")   # on test_layout_columns' worker: zoo(5, 27) are the first of its zoo(5, 30), made once there
def test_blocks_side_by_side_where_they_fit(monkeypatch):
    """Generated mechanisms, full and poles sheets, both styles: the table is in as many blocks (three at most) as
    fit its room's width wherever more would take fewer lines; its ink lies under no panel and on no caption. Some tables stand in
    blocks that the whole table's width (every column) would not have let stand side by side."""
    narrow_blocks, blocks_seen = 0, 0
    for kind, mech, style, name in _cases():
        sol = velpoly.solve(velpoly.load(mech))
        cons = sheet.constructions(sol, name)
        fig, lay = _drawn(sol, name, style, cons, monkeypatch)
        rows, b = list(lay.table.rows), len(lay.blocks)
        shown = rows[:lay.shown]
        per = -(-len(shown) // b)
        blocks_seen += b > 1
        for k in range(b + 1, 4):
            fewer = -(-len(rows) // k)
            if fewer >= per:
                continue   # no line less
            chunks = [rows[j * fewer:(j + 1) * fewer] for j in range(k)]
            assert _width(lay, [c for c in chunks if c]) > lay.width_pt, \
                f"{kind}/{style}/{name}: {k} blocks of {fewer} rows fit {lay.width_pt:.0f} pt, drawn {b} of {per}"
        whole = _width(lay, [rows])   # every column of the table, as one block
        narrow_blocks += b > 1 and b * whole + (b - 1) * BGAP * lay.size > lay.width_pt
        # its ink under no panel
        r = fig.canvas.get_renderer()
        tab = next(ax for ax in fig.axes if ax.get_label() == "table")
        ink = [a.get_window_extent(r) for a in (*tab.texts, *tab.lines)]
        for ax in fig.axes:
            if ax is tab:
                continue
            pb = ax.get_window_extent(r)
            panel = box(pb.x0, pb.y0, pb.x1, pb.y1)
            for bb in ink:
                assert panel.intersection(box(bb.x0, bb.y0, bb.x1, bb.y1)).area < 1.0, \
                    f"{kind}/{style}/{name}: the table under {ax.get_label()}"
        # and off every caption (a panel's caption may be wider than its panel: the Kennedy circle's on slides)
        for cap in fig.texts:
            cb = cap.get_window_extent(r)
            for bb in ink:
                assert box(cb.x0, cb.y0, cb.x1, cb.y1).intersection(box(bb.x0, bb.y0, bb.x1, bb.y1)).area < 1.0, \
                    f"{kind}/{style}/{name}: the table on the caption {cap.get_text()!r}"
    assert blocks_seen >= 2 and narrow_blocks >= 1, (blocks_seen, narrow_blocks)


def test_layout_counts_blocks_by_their_own_columns():
    """The table module's layout: two blocks of rows that fill different columns stand side by side in a width
    that two blocks of every column would not fit; one where not even they fit."""
    rows = [("a", "1", "", "x")] * 4 + [("b", "", "2", "y")] * 4

    def fits_width(width):
        def fits(blocks, per, shown):
            chunks = [c for c in (shown[j * per:(j + 1) * per] for j in range(blocks)) if c]
            cols = [[i for i in range(4) if i == 0 or any(r[i] for r in c)] for c in chunks]
            return sum(len(c) for c in cols) * 10 + 5 * (len(chunks) - 1) <= width
        return fits
    assert table._layout(rows, 4, fits_width(65))[:2] == (2, 4)    # 3 + 3 columns of 10 and a gap
    assert table._layout(rows, 4, fits_width(60))[:2] == (1, 4)    # not even they: one block, 4 rows shown
    assert len(table._layout(rows, 4, fits_width(60))[2]) == 3     # (the last line counts the rest)
