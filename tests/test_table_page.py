"""The table shows what the teacher typed (issue 17 item 6): every row with a book's value and every † footnote
is drawn, on the sheet or, where the drawings and the table cannot share one page with all of them, on a page
of its own (``velpoly.render.sheet.table_page``: the PDF's last page, else ``OUT-table.svg`` / ``.png``).

Checked on generated mechanisms (tests/zoo.py) given a ``[reference]`` as a book prints one, with many rows and
several notes (omega and alpha of every moving link, V and A of four points, the frame-coupler pole), in both
styles, for the full and the poles sheets; and on the built-in examples whose slides cut the book's rows before
(Example 3.4's full sheet, Example 3.8's poles sheet).
"""
from __future__ import annotations

import copy
import functools

import numpy as np
import pytest

import sheets
import velpoly
from velpoly.render import sheet
from velpoly.render.style import get_style, rc_context
from velpoly.render.table import results_table

import zoo


def book_reference(sp, notes: int = 6) -> dict:
    """A generated mechanism's file with a ``[reference]`` as a book prints one: omega of every moving link,
    alpha of every driven one, the velocity and acceleration of the last four moving points (polar, the last
    digits rounded as a book rounds them), the pole of the frame and the first coupler, and a note on each of the
    first ``notes`` of them."""
    sol = sp.drawn
    mech = copy.deepcopy(sp.mech)
    driver = mech["driver"]["link"]
    frame = next(n for n, link in mech["links"].items() if link.get("frame"))
    links = [n for n in mech["links"] if n != frame]
    moving = [p for p in mech["points"] if float(np.hypot(*sol.velocity[p])) > 0][-4:]

    def polar(v):
        return [float(f"{np.hypot(*v):.4g}"), round(float(np.degrees(np.arctan2(v[1], v[0]))) % 360.0, 2)]
    from velpoly.reference import relative_pole
    coupler = next(n for n in links if n != driver)
    pole, _ = relative_pole(sol, frame, coupler)
    values = {f"P_{frame}{coupler}": [float(f"{x:.4g}") for x in pole]} if pole is not None else {}
    mech["reference"] = {
        "source": "a generated problem",
        "omega": {n: float(f"{sol.omega[n]:.4g}") for n in links},
        "alpha": {n: float(f"{sol.alpha[n]:.4g}") for n in links if n != driver},
        "velocity": {p: polar(sol.velocity[p]) for p in moving},
        "acceleration": {p: polar(sol.acceleration[p]) for p in moving},
        "values": values}
    keys = [f"omega_{n}" for n in links if n != driver] + list(values) + [f"V_{p}" for p in moving]
    mech["reference"]["note"] = {k: f"rounded intermediate: the book rounds {k} first (a long note, as books "
                                    f"explain their slips, to make it wrap on a narrow table)" for k in keys[:notes]}
    return mech


def _table_of(fig):
    return next((ax for ax in fig.axes if ax.get_label() == "table"), None)


def _book_rows_drawn(sol, name, cons, fig, page):
    """(rows with a book's value, of them drawn; footnotes, of them drawn) by the sheet ``fig`` or its table
    page ``page`` (None: none)."""
    t = results_table(sol, name, velocity=cons.velocity if name == "full" else None,
                      acceleration=cons.acceleration if name == "full" else None, poleset=cons.poles)
    refs = sum(1 for r in t.rows if r[t.header.index("reference")])
    table = _table_of(page if page is not None else fig)
    more = [int(x.get_text().split()[1]) for x in table.texts if "more rows" in x.get_text()]
    shown = len(t.rows) - (more[0] if more else 0)
    drawn_notes = {x.get_gid() for x in table.texts if (x.get_gid() or "").startswith("footnote-")}
    return refs, shown, len(t.notes), len(drawn_notes)


@functools.cache
def _specimens():
    rng = np.random.default_rng(1706)
    return [zoo.specimen(rng, "six-bar", "watt II"), zoo.specimen(rng, "slider-crank", "offset crank")]


@pytest.fixture(scope="module")
def specimens():
    return _specimens()


@functools.cache
def _book(which: int):
    """The specimen ``which`` given book_reference's answers, solved (once a process)."""
    return velpoly.solve(velpoly.load(book_reference(_specimens()[which])))


@functools.cache
def _drawn(which: int, style: str, name: str):
    """(solution, constructions, ``sheet.render``'s result) of a book specimen's sheet, drawn once a process for
    both tests that read it (their xdist group keeps them on one worker); its space diagram without its marks
    (``sheets.unlabelled_mechanism``: both read the table and the panels' places). Read only."""
    sol = _book(which)
    cons = sheet.constructions(sol, name)
    st = get_style(style)
    with rc_context(st), sheets.unlabelled_mechanism():
        return sol, cons, sheet.render(sol, name, st, cons=cons)


SHARED = pytest.mark.xdist_group("table-page-books")   # the slides sheets both tests below draw, drawn once
CASES = [(0, "slides", "full"), (0, "textbook", "poles"), (1, "textbook", "full"), (1, "slides", "poles")]


@SHARED
@pytest.mark.parametrize("which,style,name", CASES)
def test_every_book_row_and_footnote_is_drawn(which, style, name):
    """Generated mechanisms with a book's many answers and notes: every row with a reference value and every
    footnote is drawn, on the sheet or on its table page (the sheet's table, cut, then says so in its last
    line); the table page's texts stay on its page."""
    sp = _specimens()[which]
    sol, cons, done = _drawn(which, style, name)
    st = get_style(style)
    fig = done.figure
    with rc_context(st):
        page = sheet.table_page(sol, name, st, cons=cons) if done.table_page else None
    assert not hasattr(fig, "_velpoly_table_page")   # carried by the frozen result, not hung on the figure
    with pytest.raises(AttributeError):
        done.table_page = not done.table_page
    refs, shown, notes, drawn = _book_rows_drawn(sol, name, cons, fig, page)
    assert refs >= 4 and notes >= 3, f"{sp.kind}/{style}/{name}: {refs} book rows, {notes} notes"
    assert shown >= refs, f"{sp.kind}/{style}/{name}: {shown} rows drawn of {refs} with a book's value"
    assert drawn == notes, f"{sp.kind}/{style}/{name}: {drawn} footnotes drawn of {notes}"
    if page is not None:   # the sheet's own table sends the reader there
        assert any("on the table page" in t.get_text() for t in _table_of(fig).texts)
        assert {ax.get_label() for ax in page.axes} == {"table"}
        texts = [t.get_text() for t in page.texts]
        assert any(sol.mechanism.title.split(":")[0] in t for t in texts), "the table page has no title"
        # the table's texts stay on its page
        r = page.canvas.get_renderer()
        W, H = page.get_figwidth() * page.dpi, page.get_figheight() * page.dpi
        for t in _table_of(page).texts:
            bb = t.get_window_extent(r)
            assert bb.x0 >= -1 and bb.y0 >= -1 and bb.x1 <= W + 1 and bb.y1 <= H + 1, t.get_text()


@pytest.mark.parametrize("style", [pytest.param(st, marks=sheets.on(st)) for st in ("textbook", "slides")])
def test_the_book_cut_on_one_slide_gets_a_table_page(style):
    """The gallery's sheets that cut the book's rows (Example 3.4 on slides: 7 of 14 shown; Example 3.8's poles
    on slides: 2 of 6; Example 3.10, 13 of 17 in both styles): a table page with all of them and their notes;
    the others keep every row on the sheet (the gallery's own pages, drawn once a worker: tests/sheets.py; Example
    3.8's poles slide, read here alone, with its space diagram unlabelled: ``sheets.bare_rendered``, its table read)."""
    st = get_style(style)
    for stem, name, gallery in (("ex3_4_slotted_lever", "full", sheets.STYLES),
                                ("ex3_10_rolling_contact", "full", sheets.STYLES),
                                ("ex3_8_instant_centres_cw", "poles", ("textbook",))):   # the gallery's styles
        sol, cons = sheets.solved(stem), sheets.constructions(stem, name)
        done = (sheets.rendered if style in gallery else sheets.bare_rendered)(stem, name, style)
        fig = done.figure
        with sheets.styled(style):
            page = sheet.table_page(sol, name, st, cons=cons) if done.table_page else None
        assert (page is not None) == (style == "slides" or stem == "ex3_10_rolling_contact"), f"{stem}/{style}"
        refs, shown, notes, drawn = _book_rows_drawn(sol, name, cons, fig, page)
        assert shown >= refs >= 6 and drawn == notes >= 5, (stem, style, refs, shown, notes, drawn)


def test_the_table_page_is_written(tmp_path):
    """Drawn to files: the PDF has the table page as its second page, an SVG has it as a second file
    OUT-table.svg with the footnotes the sheet could not hold."""
    sol = sheets.solved("ex3_8_instant_centres_cw")
    cons = sheets.constructions("ex3_8_instant_centres_cw", "poles")
    with sheets.unlabelled_mechanism():   # the files and their tables read, not the space diagram's marks
        written = sheet.draw_to_file(sol, tmp_path / "ic.svg", "poles", "slides", cons=cons)
        pdf = sheet.draw_to_file(sol, tmp_path / "ic.pdf", "poles", "slides", cons=cons)
    assert [p.name for p in written] == ["ic.svg", "ic-table.svg"]
    assert "footnote-4" in written[1].read_text() and "footnote-4" not in written[0].read_text()
    assert pdf == [tmp_path / "ic.pdf"]
    assert pdf[0].read_bytes().count(b"/Type /Page\n") + pdf[0].read_bytes().count(b"/Type /Page ") == 2


@SHARED
def test_a_sheet_with_a_table_page_draws_larger(specimens):
    """Generated mechanisms with a book's many answers, on slides (full and poles sheets; the textbook page holds
    their tables): where the whole table goes on its
    table page, the sheet is laid out again with its own table in less room (``TABLE_CUT``): every drawing at
    least as large as with the table cut in its usual room (some larger), the panels drawn where that plan puts
    them, the table's ink under no panel, its last line sending the reader to the table page."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from shapely.geometry import box
    from velpoly.render.options import drawing_options
    style = "slides"
    st = get_style(style)
    pages = larger = 0
    for which, sp in enumerate(specimens):
        for name in ("full", "poles"):
            sol, cons, done = _drawn(which, style, name)
            with rc_context(st):
                if not done.table_page:
                    continue
                pages += 1
                fig = Figure(figsize=st.figsize, dpi=72)
                FigureCanvasAgg(fig)
                title = sheet._page(fig, st, sol.mechanism, sol)
                top = sheet._top(fig, st, title, "", False)
                usual = sheet._plan(fig, sol, st, drawing_options(sol.mechanism), cons, name, top, True)
                cut = sheet._plan(fig, sol, st, drawing_options(sol.mechanism), cons, name, top, True, cut=True)
            for panel, s in usual.scales.items():
                if s is not None:
                    assert cut.scales[panel] <= s * (1 + 1e-9), f"{sp.kind}/{style}/{name}: {panel} {cut.scales[panel]} > {s}"
            larger += any(s is not None and cut.scales[p] < s * (1 - 1e-9) for p, s in usual.scales.items())
            drawn = {ax.get_label(): ax for ax in done.figure.axes}
            for panel, rect in cut.rects.items():
                assert drawn[panel].get_position().bounds == pytest.approx(rect, abs=1e-9), (sp.kind, panel)
            table = drawn["table"]
            assert any("on the table page" in t.get_text() for t in table.texts)
            r = done.figure.canvas.get_renderer()
            ink = [a.get_window_extent(r) for a in (*table.texts, *table.lines)]
            for panel in cut.rects:
                pb = drawn[panel].get_window_extent(r)
                for bb in ink:
                    assert box(pb.x0, pb.y0, pb.x1, pb.y1).intersection(box(bb.x0, bb.y0, bb.x1, bb.y1)).area < 1.0, \
                        f"{sp.kind}/{style}/{name}: the table under {panel}"
    assert pages >= 3 and larger >= 2, (pages, larger)
