"""Gallery pages drawn once per test process and shared by every test that looks at them.

A sheet costs about a second to draw, and several test files inspect the same pages of the built-in
examples (every page checks of test_render_gallery, the page fill of test_page_fill, the poles-sheet
tests of test_render). ``page(stem, sheet, style)`` draws a page as ``velpoly draw`` does (the sheet's
own constructions, inside the style's rc_context, then drawn through without writing a file) the first time it is asked for in a process and
returns the same Figure afterwards. The figures are shared: a test only reads them (one that changes a
figure draws its own with ``sheet.render_sheet``). Measure them inside ``rc_context(get_style(style))``
(``styled(style)``), as they were drawn.

``bare_page`` (``bare_rendered``) is a page with its space diagram unlabelled, for the tests that read no mark of it, and
``unlabelled_mechanism()`` draws any sheet so (for a test that reads a sheet's table, captions or panels' places:
the label placer is most of a space diagram's cost).

With xdist, a page is drawn once per worker that asks for it; the tests of one style are kept on one
worker by their ``on(style)`` mark (``xdist_group``, honoured by ``--dist loadgroup`` in pyproject's
addopts): the two styles' pages are drawn side by side on the two workers, each page exactly once.
"""
from __future__ import annotations

import contextlib
import functools
from dataclasses import replace

import pytest

import velpoly
from paths import GALLERY_FILES, example

STYLES = ("textbook", "slides")


def on(style: str):
    """The xdist group of the tests that look at ``style``'s pages (one worker draws them all)."""
    return pytest.mark.xdist_group(f"sheets-{style}")


@functools.cache
def loaded(stem: str):
    """The example ``stem``'s mechanism (loaded once; cheap enough for collection, unlike ``solved``)."""
    return velpoly.load(example(stem))


def own_sheet(stem: str) -> str:
    """The sheet ``velpoly draw`` and the gallery draw for the example ``stem`` (``full`` for a file that does not
    load: asked for at collection, where an error would take every test of the module with it; the file's page
    test then fails on loading it)."""
    from velpoly.errors import VelpolyError
    from velpoly.render import sheet
    try:
        return sheet.default_sheet(loaded(stem))
    except VelpolyError:
        return "full"


@functools.cache
def solved(stem: str):
    """``velpoly.solve`` of the example ``stem`` at its file's pose (loaded and solved once)."""
    return velpoly.solve(loaded(stem))


@functools.cache
def constructions(stem: str, sheet_name: str):
    """The constructions ``velpoly draw`` builds for that sheet of the example ``stem``."""
    from velpoly.render import sheet
    return sheet.constructions(solved(stem), sheet_name)


def styled(style: str):
    """The rc_context the pages of ``style`` are drawn and measured in."""
    from velpoly.render.style import get_style, rc_context
    return rc_context(get_style(style))


def rendered(stem: str, sheet_name: str, style: str):
    """One sheet of the example ``stem`` in ``style`` as ``velpoly.render.sheet.render`` returns it (its figure,
    whether it has a table page), drawn once per process. Read only."""
    return _rendered(stem, sheet_name, style, False)


@functools.cache
def _rendered(stem: str, sheet_name: str, style: str, bare: bool):
    """The sheet drawn as ``velpoly draw`` draws it (``bare``: its space diagram unlabelled), then drawn through
    (every text laid out, as a file would be: a third of an SVG's cost); a page of ``own_pages`` drawn through
    by Agg at its own 72 dpi instead, its ink kept (``ink``)."""
    from velpoly.render import sheet
    from velpoly.render.style import get_style
    with styled(style), (unlabelled_mechanism() if bare else contextlib.nullcontext()):
        done = sheet.render(solved(stem), sheet_name, get_style(style), cons=constructions(stem, sheet_name))
        if not bare and (stem, sheet_name) in own_pages(style):
            done.figure.canvas.draw()
            _INK[stem, sheet_name, style] = inked(done.figure)
        else:
            done.figure.draw_without_rendering()
    return done


_INK: dict = {}   # (stem, sheet, style) -> the ink of a page of own_pages, as its first drawing left it


@functools.cache
def own_pages(style: str) -> tuple:
    """(stem, sheet) of the gallery files' own sheets drawn in ``style``, every other file in each (the style
    test_render_gallery draws them in): the pages test_page_fill measures the ink of. These are drawn through
    by Agg rather than without rendering (the one draw lays out every text as the other does: every text's
    place, size and box, every line, patch, view, legend and placed label compared equal on the 19 pages, issue
    19 item 7), so that their ink is that draw's, not a second one's (about 0.05 CPU s a page)."""
    return tuple((p.stem, own_sheet(p.stem)) for i, p in enumerate(GALLERY_FILES) if STYLES[i % 2] == style)


def inked(fig):
    """Where the Agg canvas of ``fig``, as last drawn, has ink: a boolean array of its pixels (rows from the
    top), any channel below 235 of 255."""
    import numpy as np
    return (np.asarray(fig.canvas.buffer_rgba())[:, :, :3] < 235).any(axis=2)


def ink(stem: str, sheet_name: str, style: str):
    """``inked`` of a page of ``own_pages(style)`` as it was drawn (once per process, with the page). Read only."""
    rendered(stem, sheet_name, style)
    return _INK[stem, sheet_name, style]


def page(stem: str, sheet_name: str, style: str):
    """The Figure of one sheet of the example ``stem`` in ``style``, drawn once per process. Read only."""
    return rendered(stem, sheet_name, style).figure


def bare_rendered(stem: str, sheet_name: str, style: str):
    """``rendered`` with the space diagram unlabelled (:func:`unlabelled_mechanism`), for a test that reads the
    sheet's table, or whether it has a table page, on a page no other test reads whole (Example 3.8's poles
    slide, read by test_table_page alone). Read only."""
    return _rendered(stem, sheet_name, style, True)


def bare_page(stem: str, sheet_name: str, style: str):
    """The Figure of one sheet of the example ``stem`` in ``style`` with its space diagram unlabelled
    (:func:`unlabelled_mechanism`), drawn through once per process, for a test that reads its poles, their
    arrows and labels' words, its Kennedy lines or its layout, and no point label, link number or place of a
    label, on a page no other test reads whole (the textbook poles pages of Example 3.4, Problem 1.4.4 and the
    crank shaper, read by test_render's pole tests alone: 1.1, 0.35 and 0.55 CPU s whole, 0.5, 0.25 and 0.3
    bare; their pole arrows, Kennedy lines, labels' words, panels, table and captions compared equal). Read only."""
    return bare_rendered(stem, sheet_name, style).figure


@contextlib.contextmanager
def unlabelled_mechanism():
    """Sheets drawn inside draw their space diagram (the mechanism panel, and the mechanism under a poles
    panel's poles) without point labels and link numbers (``mechanisms.shapes_only``'s options, the sheet's own
    otherwise), for a test that reads a sheet's table, captions, step caption or panels' places and no mark of
    the mechanism. The label placer is most of a space diagram's cost (a sheet 2 to 3 times cheaper); nothing
    else depends on those marks: the sheet is planned (its panels' places and scales, its table) before any
    panel is drawn, the space diagram's and the poles drawing's views are set before their marks are placed,
    and the polygons and the Kennedy circle are drawn on axes of their own. Compared equal with and without
    the labels on the 13 generated sheets of test_table_blocks and test_table_page (issue 19, the sheet
    tests): every axes' place, the space diagrams' views, every text (with its box) and line of the table,
    polygon and Kennedy circle panels, every caption, whether the sheet has a table page."""
    from velpoly.render import sheet
    from velpoly.render.options import drawing_options
    real_mechanism, real_poles = sheet.draw_mechanism, sheet.draw_poles

    def bare(sol, options):
        return replace(options or drawing_options(sol.mechanism), label_points=(), link_numbers="none")

    def mechanism(sol, ax=None, *, options=None, **kw):
        return real_mechanism(sol, ax, options=bare(sol, options), **kw)

    def poles(sol, ax=None, *, options=None, **kw):
        return real_poles(sol, ax, options=bare(sol, options), **kw)
    sheet.draw_mechanism, sheet.draw_poles = mechanism, poles
    try:
        yield
    finally:
        sheet.draw_mechanism, sheet.draw_poles = real_mechanism, real_poles
