"""Every example renders, with the real constructions, in every sheet kind and style.

Every built-in example (velpoly/examples/*.toml, the gallery's files) draws its own sheet (the one
``velpoly draw`` and the gallery draw: its ``[drawing] sheet``, else the full sheet with every panel of
that file), in one style (alternating textbook and slides through the sorted files), and in both for
the files in ``BOTH_STYLES`` (a slotted lever with its Coriolis term and a slider, whose slide has a
table page, and a rolling contact whose acceleration polygon needs its detail): the other kinds of
example meet both styles through the alternation (four-bars, six-bars, cams, sliders, rolling and
sliding contacts on each side: ``test_both_styles_are_covered``). ``OTHER_PAGES`` draws each other
sheet kind (velocity, acceleration, poles, displacement) once in each style, the poles pages being
those test_render reads anyway, so that every sheet kind is drawn in each style
(``test_every_sheet_kind_and_style_is_covered``). Each page is a test of its own, drawn once per worker
by tests/sheets.py (other tests look at the same pages: a page only one test needs is not drawn twice)
and drawn through, every text laid out: it has its sheet's panels and table, no two labels overlap,
captions state their panels' scales. (Until issue 19 item 7 every second file drew a sheet of the
rotation and four files both styles: 32 pages here, 43 drawn in a run with the other tests' own; now 29
and 34, each file still drawn and checked in one style.)
A file whose contacts are given by their normals only has no acceleration sheet (an InputError saying
that centres of curvature are needed, FORMAT.md section 5); its full sheet shows velocities only.
"""
from __future__ import annotations

import itertools
import re
from pathlib import Path

import pytest
from shapely.geometry import box

import velpoly
from render_contract import assert_page_texts_clear, leaders_crossing_labels, legend_trouble, reasons_too_close
from velpoly.errors import InputError
from velpoly.render import sheet
from velpoly.render.canvas import per_cm
from velpoly.render.options import drawing_options
import sheets
from paths import GALLERY_FILES
from test_detail import expected as expected_detail

ROOT = Path(__file__).resolve().parent.parent
FILES = GALLERY_FILES
STYLES = ("textbook", "slides")
BOTH_STYLES = {"ex3_4_slotted_lever", "ex3_10_rolling_contact"}   # test_table_page and test_detail read both
# each other sheet kind once in each style; the poles pages are test_render's (drawn for it anyway)
OTHER_PAGES = (("cam_roller_follower", "velocity", "textbook"), ("ex3_7_instant_centres", "velocity", "slides"),
               ("crank_slider", "acceleration", "textbook"), ("ex3_9_graphical", "acceleration", "slides"),
               ("ex3_6_fourbar", "poles", "textbook"), ("ex3_6_fourbar", "poles", "slides"),
               ("ex3_5_slider_crank", "displacement", "textbook"), ("problem_1_4_4_sixbar", "displacement", "slides"))


def styles_for(index: int, path: Path) -> tuple[str, ...]:
    """Both styles for the files in BOTH_STYLES, else one, alternating through FILES."""
    return STYLES if path.stem in BOTH_STYLES else (STYLES[index % 2],)


def pages_for(index: int, path: Path) -> list[tuple[str, str]]:
    """The (sheet, style) pages a file draws: its own sheet (``sheet.default_sheet``) in ``styles_for``, then
    its pages of OTHER_PAGES."""
    own = sheets.own_sheet(path.stem)
    return [(own, style) for style in styles_for(index, path)] + \
        [(name, style) for stem, name, style in OTHER_PAGES if stem == path.stem]


def _label_boxes(fig):
    """Window boxes of the labels (gid label-...), link numbers, scale bars' texts and legends of every
    axes, shrunk by 0.3 pt."""
    r = fig.canvas.get_renderer()
    s = 0.3 * fig.dpi / 72
    out = []
    for ax in fig.axes:
        texts = [t for t in ax.texts if (t.get_gid() or "").startswith(("label-", "link-number-", "kennedy-label-",
                                                                        "chord-number-", "driver-label",
                                                                        "scale-bar"))]
        if ax.get_legend() is not None:
            texts.append(ax.get_legend())
        for t in texts:
            bb = t.get_window_extent(r)
            name = t.get_text() if hasattr(t, "get_text") else "legend"
            out.append((name, box(bb.x0 + s, bb.y0 + s, bb.x1 - s, bb.y1 - s)))
    return out


def features(m) -> set[str]:
    """The kinds of example a gallery file is, as its drawing shows them (a four-bar's or a six-bar's number of
    links; the cam with three links is a sliding contact and a slider, the slotted lever's seven a slot)."""
    out = {f"{len(m.links)} links"} & {"4 links", "6 links"} | {f"{c.kind} contact" for c in m.contacts}
    out |= {"slider"} if m.sliders else set()
    out |= {"slot"} if m.slots else set()
    out |= {f"own sheet {sheet.default_sheet(m)}"}
    return out


def test_both_styles_are_covered():
    """Every kind of example (four- and six-link, each contact kind, sliders, a slot, a file whose own
    sheet is the poles sheet) has its own sheet drawn in each style, and each style draws about half the files."""
    assert {p.stem for p in FILES} >= BOTH_STYLES                    # the named files exist
    drawn = {st: set() for st in STYLES}
    for i, p in enumerate(FILES):
        for st in styles_for(i, p):
            drawn[st] |= features(sheets.loaded(p.stem))
    every = set().union(*drawn.values())
    assert drawn["textbook"] == drawn["slides"] == every, drawn
    assert {"4 links", "6 links", "rolling contact", "sliding contact", "slider", "slot", "own sheet poles"} <= every
    chosen = [styles_for(i, p) for i, p in enumerate(FILES)]
    assert all(sum(st in c for c in chosen) >= len(FILES) // 2 for st in STYLES)


def test_every_sheet_kind_and_style_is_covered():
    """Each sheet kind is drawn in each style (an acceleration sheet only by a file that has one); every
    file draws its own sheet, in one style at least."""
    drawn = {}
    for i, p in enumerate(FILES):
        pages = pages_for(i, p)
        assert (sheets.own_sheet(p.stem), styles_for(i, p)[0]) in pages
        has_acc = sheets.solved(p.stem).has_accelerations   # (solved once a process, for the page tests too)
        for page in pages:
            if page[0] != "acceleration" or has_acc:
                drawn[page] = drawn.get(page, 0) + 1
    assert drawn.keys() == {(n, st) for n in sheet.SHEETS for st in STYLES}, drawn


PAGES = [(index, path, name, style) for index, path in enumerate(FILES) for name, style in pages_for(index, path)]


@pytest.mark.parametrize("index,path,name,style", [pytest.param(*p, marks=sheets.on(p[3])) for p in PAGES],
                         ids=[f"{p.stem}-{name}-{style}" for _, p, name, style in PAGES])
def test_every_page_is_drawn_clear(index, path, name, style):
    """One page (sheet, style) of a gallery file, drawn as ``velpoly draw`` draws it (tests/sheets.py: once
    per worker, shared with the other tests that look at it) and drawn through (every text laid out)."""
    m = velpoly.load(path)      # a gallery file that stops loading fails here (never a skip)
    sol = sheets.solved(path.stem)
    if (name, style) == pages_for(index, path)[0] and not sol.has_accelerations:
        with pytest.raises(InputError, match="centres of curvature"):
            sheet.constructions(sol, "acceleration")
    assert sol.mechanism == m
    if name == "acceleration" and not sol.has_accelerations:
        return
    fig = sheets.page(path.stem, name, style)
    cons = sheets.constructions(path.stem, name)
    with sheets.styled(style):
        labels = {ax.get_label() for ax in fig.axes}       # the sheet's panels and its table
        assert labels == set(sheet._PANELS[name]) | ({"table"} if drawing_options(m).table else set()), labels
        if style == "slides":
            w, h = fig.get_size_inches()
            assert w / h == pytest.approx(16 / 9, rel=1e-3)
        table = "data-table" if name == "displacement" else "results-table"
        assert any(t.get_gid() == table for ax in fig.axes for t in ax.texts), f"{name}/{style}: no {table}"
        assert_page_texts_clear(fig)
        assert not legend_trouble(fig), f"{name}/{style}: the legend runs {legend_trouble(fig)[:3]}"
        assert not reasons_too_close(fig), f"{name}/{style}: reasons run into labels {reasons_too_close(fig)}"
        assert not leaders_crossing_labels(fig), f"{name}/{style}: leaders cross {leaders_crossing_labels(fig)}"
        sizes = {t.get_fontsize() for t in fig.texts if (t.get_gid() or "").startswith("caption-")}
        assert len(sizes) == 1, f"{name}/{style}: captions in sizes {sizes}"
        for ax in fig.axes:   # each caption's scale is its panel's (a legend's strip changes it)
            cap = next((t.get_text() for t in fig.texts if t.get_gid() == f"caption-{ax.get_label()}"), "")
            said = re.search(r"1 cm = ([0-9.e+-]+)", cap)
            if said:
                assert per_cm(ax) == pytest.approx(float(said.group(1)), rel=1e-9), f"{name}/{style}: {cap}"
                bar = next(p for p in ax.patches if p.get_gid() == "scale-bar")
                assert 1.0 - 1e-9 <= bar.get_width() / per_cm(ax) <= 2.5 + 1e-9
        for ax in fig.axes:   # numbers with a minus sign, not a hyphen ('P_04 (-3.185, 0.1862)')
            bad = [t.get_text() for t in ax.texts if re.search(r"(?<![\w.])-[0-9]", t.get_text())]
            assert not bad, f"{name}/{style}: hyphen for minus in {bad}"
        for ax in fig.axes:   # a polygon crushed by a long vector has its detail, and only that (test_detail)
            if ax.get_label() in ("velocity", "acceleration"):
                poly = cons.velocity if ax.get_label() == "velocity" else cons.acceleration
                has = any(p.get_gid() == "detail-frame" for p in ax.patches)
                assert has == expected_detail(poly, per_cm(ax)), f"{name}/{style}: {ax.get_label()} detail"
        boxes = _label_boxes(fig)
        assert boxes, "no labels drawn"
        for (ta, a), (tb, b) in itertools.combinations(boxes, 2):
            assert not a.intersects(b), f"{name}/{style}: labels {ta!r} and {tb!r} overlap"
