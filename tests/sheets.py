"""Gallery pages drawn once per test process and shared by every test that looks at them.

A sheet costs about a second to draw, and several test files inspect the same pages of the built-in
examples (every page checks of test_render_gallery, the page fill of test_page_fill, the poles-sheet
tests of test_render). ``page(stem, sheet, style)`` draws a page as ``velpoly draw`` does (the sheet's
own constructions, inside the style's rc_context, then drawn through without writing a file) the first time it is asked for in a process and
returns the same Figure afterwards. The figures are shared: a test only reads them (one that changes a
figure draws its own with ``sheet.render_sheet``). Measure them inside ``rc_context(get_style(style))``
(``styled(style)``), as they were drawn.

With xdist, a page is drawn once per worker that asks for it; the tests of one style are kept on one
worker by their ``on(style)`` mark (``xdist_group``, honoured by ``--dist loadgroup`` in pyproject's
addopts): the two styles' pages are drawn side by side on the two workers, each page exactly once.
"""
from __future__ import annotations

import functools

import pytest

import velpoly
from paths import example

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


@functools.cache
def rendered(stem: str, sheet_name: str, style: str):
    """One sheet of the example ``stem`` in ``style`` as ``velpoly.render.sheet.render`` returns it (its figure,
    whether it has a table page), drawn once per process. Read only."""
    from velpoly.render import sheet
    from velpoly.render.style import get_style
    with styled(style):
        done = sheet.render(solved(stem), sheet_name, get_style(style), cons=constructions(stem, sheet_name))
        done.figure.draw_without_rendering()   # drawn through as a file would be (every text laid out), a third of an SVG's cost
    return done


def page(stem: str, sheet_name: str, style: str):
    """The Figure of one sheet of the example ``stem`` in ``style``, drawn once per process. Read only."""
    return rendered(stem, sheet_name, style).figure
