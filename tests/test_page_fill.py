"""Sheets that use the page, text off the lines, leaders that do not cross (issue 17 items 2, 4, 8b, 8c).

- The page is cut into 1-cm cells; a cell is blank when no pixel in it has ink (the sheet rendered
  at its own 72 dpi). The mean blank fraction over the gallery files' own sheets, each file in the one
  style test_render_gallery draws it in, stays under its bound in each style.
- Over the same sheets: the scale bars of two panels stand at least 1 cm apart (they must not read as
  one bar), a table's first rule runs under its title's last line, and no label or driver's value lies
  on a construction line or a Kennedy line.
- On generated mechanisms (tests/zoo.py): every pole's label is nearer its own ring than any other
  ring, no two leaders cross, and no label lies on a Kennedy line.
- ``--steps``: the results table only in the last frame; the first Kennedy frame draws the chords of
  the poles sought (dashed, unnumbered), the later frames only the chords known.
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from shapely.geometry import LineString, box

import velpoly
import sheets
from paths import example
from velpoly.render import sheet
from velpoly.render.labels import placer
from velpoly.render.layout import MARGIN, arrange, cover, drawn_areas, share_row, smaller_scale
from velpoly.render.scalebar import BAR_GAP
from velpoly.render.style import get_style, rc_context

STYLES = ("textbook", "slides")
# the mean blank fraction of the gallery's own sheets, by style: before issue 17 0.60 (textbook) and 0.46
# (slides); 0.533 and 0.382 before the table's corner (all files); 0.528 and 0.359 before a panel could take a
# column at the page's full height, 0.522 and 0.359 (all files) before the table's blocks were counted by their own
# columns, a column or the corner could no longer shrink one polygon to grow the other, and a slide with a table
# page gave its table less room (issue 17's layout leftovers); now 0.515 and 0.380 (all files), 0.505 and 0.378
# over the halves tested below (every other file in each style, at 30 dpi); at 72 dpi (issue 19 item 7: the page's
# own, cheaper) 0.507 and 0.372 over the same halves, the bounds a few thousandths above. The target, under 0.40 in both, is reached in the slides
# style only. The textbook floor, measured (issue 17 item 2): the drawings' ink boxes cover 0.52 of the page and
# 0.55 of their 1-cm cells are blank (0.13 of the page inside the drawings' convex hulls, 0.15 in their boxes'
# corners outside the hulls), the title band and captions leave 0.048 blank, the table's lines 0.028; filling
# every other blank cell (panel margins and scale rounding 0.10, the table's room beside its blocks 0.024, gaps
# 0.031) with drawings at their own density would still leave 0.45 blank: no layout of thin lines reaches 0.40
BLANK_MOST = {"textbook": 0.51, "slides": 0.375}


def blank_fraction(fig) -> float:
    """The share of the page's 1-cm cells without a pixel of ink (``sheets.inked``: any channel below 235 of
    255), the page rasterised at its own dpi (72): a draw at the dpi its texts were laid out at reuses their
    layout (a draw at 30 dpi, as until issue 19 item 7, laid every text out again and cost half as much more)
    and leaves every artist where it was (a shared page stays as tests/sheets.py drew it)."""
    fig.canvas.draw()
    return blank_share(sheets.inked(fig), fig.dpi)


def blank_share(ink, dpi: float) -> float:
    """The share of 1-cm cells of a page's ``ink`` (its pixels, at ``dpi``) without a pixel of ink."""
    cell = dpi / 2.54
    ny, nx = int(ink.shape[0] / cell), int(ink.shape[1] / cell)
    blank = [not ink[int(i * cell):int((i + 1) * cell), int(j * cell):int((j + 1) * cell)].any()
             for i in range(ny) for j in range(nx)]
    return sum(blank) / len(blank)


def _window(fig, artist):
    bb = artist.get_window_extent(fig.canvas.get_renderer())
    return box(bb.x0, bb.y0, bb.x1, bb.y1)


def bar_groups(fig) -> dict:
    """Each panel's scale bar with its labels, as a box on the page (pixels)."""
    out = {}
    for ax in fig.axes:
        parts = [p for p in ax.patches if p.get_gid() == "scale-bar"] + \
                [t for t in ax.texts if (t.get_gid() or "").startswith("scale-bar")]
        if parts:
            boxes = [_window(fig, a) for a in parts]
            out[ax.get_label()] = box(min(b.bounds[0] for b in boxes), min(b.bounds[1] for b in boxes),
                                      max(b.bounds[2] for b in boxes), max(b.bounds[3] for b in boxes))
    return out


def labels_on_lines(fig) -> list:
    """(label, line) of every label (and driver's value) whose box, shrunk by 1 px, meets a construction line
    or a Kennedy line of its panel."""
    out = []
    for ax in fig.axes:
        lines = [(ln.get_gid(), LineString(ax.transData.transform(np.column_stack(ln.get_data()))))
                 for ln in ax.lines if (ln.get_gid() or "").startswith(("construction-", "kennedy-line-"))]
        for t in ax.texts:
            if (t.get_gid() or "").startswith(("label-", "driver-label")) and t.get_text():
                b = _window(fig, t).buffer(-1.0)
                out += [(t.get_gid(), gid) for gid, ln in lines if ln.intersects(b)]
    return out


def test_share_row_fills_the_band_at_round_scales():
    """Panels share the width by their drawings' shapes; every scale is round, every drawing fits its
    panel, the widths add up to the band, and a wide drawing gets the wide panel."""
    spans = [(700.0, 300.0), (300.0, 300.0), (3000.0, 4000.0)]
    row = share_row(spans, 28.0, 11.0, 0.3)
    assert sum(row.widths) + 0.3 * 2 == pytest.approx(28.0)
    for (w, h), s, width in zip(spans, row.scales, row.widths):
        assert w / s <= width - 1.0 + 1e-9 and h / s <= 11.0 - 1.5 + 1e-9
        assert smaller_scale(s) < s and float(f"{s:.3g}") == s
    assert row.widths[0] == max(row.widths)
    # no round scale one step larger would still fit: the drawings are as large as the band allows
    grown = [(w / smaller_scale(s), h / smaller_scale(s)) for (w, h), s in zip(spans, row.scales)]
    assert any(h > 11.0 - 1.5 for _, h in grown) or sum(w for w, _ in grown) + 3.6 > 28.0


def _panels(bands, spans):
    """Each panel's box (cm) and the area its drawing covers, from an arrangement's bands."""
    out = {}
    for b in bands:
        x = b.left
        for name, w, a in zip(b.names, b.row.widths, drawn_areas([spans[n] for n in b.names], b.row)):
            out[name] = (box(x, b.bottom, x + w, b.bottom + b.height), a)
            x += w + 0.35
    return out


@pytest.mark.parametrize("seed", range(6))
def test_arrange_fills_the_corner_beside_a_narrow_table(seed):
    """Random drawings and tables: with the table's corner kept (``notch``), every panel lies on the page, off
    the table and off the other panels with their captions; every drawing fits its panel; the arrangement
    draws them at least as large as the rows over the table do (it may stand beside the table)."""
    rng = np.random.default_rng(seed)
    names = ["mechanism", "velocity", "acceleration"]
    spans = {n: (float(rng.uniform(1, 10)), float(rng.uniform(1, 10))) for n in names}
    width, top, bottom, cap = 28.0, 18.0, 0.3, 0.6
    nw, nh = float(rng.uniform(8, 20)), float(rng.uniform(3, 10))
    over = arrange(spans, names, width, top, bottom + nh, 0.35, cap, {}, {})
    bands = arrange(spans, names, width, top, bottom, 0.35, cap, {}, {}, notch=(nw, nh))
    got = _panels(bands, spans)
    assert set(got) == set(names)
    table = box(bands.table_left, bottom, bands.table_left + nw, bottom + nh - 1e-6)
    mx, mt, mb = MARGIN
    for b in bands:
        for (w, h), s, pw in zip([spans[n] for n in b.names], b.row.scales, b.row.widths):
            assert w / s <= pw - 2 * mx + 1e-6 and h / s <= b.height - mt - mb + 1e-6
    for name, (panel, _) in got.items():
        x0, y0, x1, y1 = panel.bounds
        assert x0 >= -1e-9 and x1 <= width + 1e-6 and y0 >= bottom - 1e-6 and y1 <= top + 1e-6, name
        assert panel.intersection(table).area < 1e-6, f"{name} on the table"
    for (a, (pa, _)), (b, (pb, _)) in itertools.combinations(got.items(), 2):
        grown = [box(*p.bounds[:3], p.bounds[3] + cap) for p in (pa, pb)]
        assert grown[0].intersection(grown[1]).area < 1e-6, f"{a} and {b} overlap"
    assert cover([a for _, a in got.values()]) >= cover([a for _, a in _panels(over, spans).values()]) - 1e-9


@pytest.mark.parametrize("style", [pytest.param(st, marks=sheets.on(st)) for st in STYLES])
def test_gallery_sheets_use_the_page(style):
    """Every gallery file's own sheet (one style each, alternating, as test_render_gallery draws them; a test a
    style, so that the two run side by side): the blank fraction's mean, taken over the pages drawn in that
    style (10 textbook, 9 slides: not over all 19 in each), under its bound; scale bars apart; the table's
    rule under its title; no label on a line."""
    fractions = {style: []}
    for stem, name in sheets.own_pages(style):
        fig = sheets.page(stem, name, style)     # drawn once per worker, shared (tests/sheets.py)
        with sheets.styled(style):
            fractions[style].append(blank_share(sheets.ink(stem, name, style), fig.dpi))   # the ink of its drawing
            cm = fig.dpi / 2.54
            for (a, ga), (b, gb) in itertools.combinations(bar_groups(fig).items(), 2):
                assert ga.distance(gb) >= BAR_GAP * cm * 0.99, f"{stem}/{style}: the bars of {a} and {b} touch"
            table = next(ax for ax in fig.axes if ax.get_label() == "table")
            title = next(t for t in table.texts if t.get_gid() == "results-table")
            rule = max((ln for ln in table.lines), key=lambda ln: ln.get_ydata()[0])
            top = table.transAxes.transform((0, rule.get_ydata()[0]))[1]
            assert top < _window(fig, title).bounds[1], f"{stem}/{style}: the rule strikes the title"
            assert not labels_on_lines(fig), f"{stem}/{style}: {labels_on_lines(fig)}"
    for style, got in fractions.items():
        assert np.mean(got) < BLANK_MOST[style], f"{style}: {np.round(got, 3)}"


@pytest.fixture(scope="module")
def specimens():
    from zoo import zoo
    return zoo(11, 8)


def test_pole_labels_by_their_rings_and_leaders_apart(specimens):
    """Generated mechanisms, both styles: each pole label in view is nearer its own ring than any other
    ring (coincident poles aside), no two leaders cross, no label lies on a Kennedy line. Four of the eight
    specimens (a crank-rocker and a through-crank slider-crank in textbook, a change-point four-bar and an
    offset-crank slider-crank in slides); none of the eight failed with the velpoly before this test
    (64fd5b1's parent), and the other four were cut when the suite had to fit 2 minutes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from velpoly.poles import locate_poles
    from velpoly.render.kennedy import draw_poles
    for i in (0, 3, 5, 6):
        sp = specimens[i]
        st = get_style(STYLES[i % 2])
        with rc_context(st):
            fig = Figure(figsize=(8, 6), dpi=72)
            FigureCanvasAgg(fig)
            ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
            art = draw_poles(sp.drawn, ax, style=st, poleset=locate_poles(sp.drawn))
            inv = ax.transData.inverted()
            for key, ring in art.rings.items():
                bb = art.labels[key].get_window_extent(fig.canvas.get_renderer())
                (x0, y0), (x1, y1) = inv.transform([[bb.x0, bb.y0], [bb.x1, bb.y1]])
                lab = box(x0, y0, x1, y1)
                own = lab.distance(ring)
                for other, g in art.rings.items():
                    if other != key and not g.equals(ring):
                        assert own < lab.distance(g) + 1e-9, f"{sp.kind}: P{key}'s label nearer P{other}"
            leaders = [LineString(np.column_stack(p.leader.get_data())) for p in placer(ax).labels
                       if p.leader is not None]
            for a, b in itertools.combinations(leaders, 2):
                assert not a.intersects(b), f"{sp.kind}: two leaders cross"
            assert not labels_on_lines(fig), f"{sp.kind}: {labels_on_lines(fig)}"


def test_driver_values_off_the_kennedy_lines():
    """Generated mechanisms whose driver has an alpha or is a slider, on the poles sheet (its Kennedy lines drawn
    before the mechanism): omega's, alpha's, a slider's speed's and acceleration's values lie on no line, no arc
    or arrow of the driver lost."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from zoo import zoo
    from velpoly.poles import locate_poles
    from velpoly.render.kennedy import draw_poles
    chosen = [sp for sp in zoo(8, 16) if sp.drawn.mechanism.driver.alpha or sp.drawn.mechanism.driver.is_slider]
    assert len(chosen) >= 8
    # of chosen[1:9], styles alternating: a four-bar with alpha (textbook), the slider-driven slider-crank whose
    # driver's value lay on a Kennedy line before 2bce3dd (slides; the only one of the eight, measured with its
    # parent's velpoly), an inverted slider-crank with alpha (textbook) and one driven by its slider (slides); the
    # other four (two four-bars, two slider-driven slider-cranks) cut when the suite had to fit 2 minutes
    for i in (0, 5, 6, 7):
        sp = chosen[1 + i]
        drv = sp.drawn.mechanism.driver
        st = get_style(STYLES[i % 2])
        with rc_context(st):
            fig = Figure(figsize=(8, 6), dpi=72)
            FigureCanvasAgg(fig)
            ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
            draw_poles(sp.drawn, ax, style=st, poleset=locate_poles(sp.drawn))
            gids = {a.get_gid() for a in ax.get_children()}
            want = {"driver-label"} | ({"driver-label-accel"} if drv.is_slider and drv.accel else set()) | \
                ({"driver-alpha-arc", "driver-label-alpha"} if not drv.is_slider and drv.alpha else set())
            assert want <= gids, f"{sp.kind}: {want - gids}"
            on = [hit for hit in labels_on_lines(fig) if hit[0].startswith("driver-label")]
            assert not on, f"{sp.kind}/{STYLES[i % 2]}: {on}"


def test_steps_keep_the_answers_to_the_last_frame():
    """The results table only in the last frame; the first Kennedy frame shows the chords sought dashed
    and unnumbered, the later ones only the chords found so far."""
    sol = velpoly.solve(velpoly.load(example("ex3_7_instant_centres")))
    st = get_style("slides")
    cons = sheet.constructions(sol, "poles")
    frames = sheet.frames("poles", cons, True)
    assert [f.table for f in frames] == [False] * (len(frames) - 1) + [True]
    with rc_context(st), sheets.unlabelled_mechanism():   # the table and the Kennedy circle read
        last = sheet.render_sheet(sol, "poles", st, cons=cons, frame=frames[-1])
        figs = [sheet.render_sheet(sol, "poles", st, cons=cons, frame=f, pins=last._velpoly_pins)
                for f in frames[:-1]] + [last]
    found = sorted((p for p in cons.poles.poles.values() if p.order > 0), key=lambda p: p.order)
    assert found
    for k, fig in enumerate(figs):
        texts = {t.get_gid() for ax in fig.axes for t in ax.texts}
        assert ("results-table" in texts) == (k == len(figs) - 1)
        kennedy = next(ax for ax in fig.axes if ax.get_label() == "kennedy")
        chords = {ln.get_gid() for ln in kennedy.lines}
        sought = {f"chord-sought-{p.key}" for p in found if p.order > k}
        shown = {f"chord-{p.key}" for p in found if p.order <= k}
        assert shown <= chords and not {f"chord-{p.key}" for p in found if p.order > k} & chords
        assert (sought <= chords) if k == 0 else not any(g.startswith("chord-sought-") for g in chords)
        numbers = {t.get_text() for t in kennedy.texts if (t.get_gid() or "").startswith("chord-number-")}
        assert numbers == {str(p.order) for p in found if p.order <= k}
    # velocity steps: no table before the last frame either
    sol6 = velpoly.solve(velpoly.load(example("ex3_6_fourbar")))
    cons6 = sheet.constructions(sol6, "velocity")
    fr = sheet.frames("velocity", cons6, True)
    with rc_context(st), sheets.unlabelled_mechanism():
        first = sheet.render_sheet(sol6, "velocity", st, cons=cons6, frame=fr[0])
    assert not any(t.get_gid() == "results-table" for ax in first.axes for t in ax.texts)


def _with_reference(sp) -> dict:
    """A generated mechanism's file with a ``[reference]`` as a book prints one: omega of every moving link but
    the driver, alpha of the last, the velocity and acceleration of its last two moving points (polar, from the
    analytic solve, the last digits rounded), and a footnote on the first velocity."""
    import copy
    sol = sp.drawn
    mech = copy.deepcopy(sp.mech)
    driver = mech["driver"]["link"]
    frame = {n for n, link in mech["links"].items() if link.get("frame")}
    links = [n for n in mech["links"] if n not in frame | {driver}]
    moving = [p for p in mech["points"] if float(np.hypot(*sol.velocity[p])) > 0][-2:]

    def polar(v):
        return [float(f"{np.hypot(*v):.4g}"), round(float(np.degrees(np.arctan2(v[1], v[0]))) % 360.0, 2)]
    mech["reference"] = {
        "source": "a generated problem",
        "omega": {n: float(f"{sol.omega[n]:.4g}") for n in links},
        "alpha": {n: float(f"{sol.alpha[n]:.4g}") for n in links[-1:]},
        "velocity": {p: polar(sol.velocity[p]) for p in moving},
        "acceleration": {p: polar(sol.acceleration[p]) for p in moving},
        "note": {f"V_{moving[0]}": "rounded intermediate: the book rounds the angular velocity first"}}
    return mech


def test_generated_sheets_show_every_book_row():
    """A generated six-bar (slides) and slider-crank (textbook) with a book's answers (omega of every link, alpha
    of the last, V and A of two points, a footnote), full sheet: the table shows every row with a reference
    value (they come first; a table cut to its room counts the rest in its last line) with the footnote, and
    nothing of the table lies under a panel."""
    from zoo import specimen
    from velpoly.render.table import results_table
    rng = np.random.default_rng(17)
    picked = [(specimen(rng, "six-bar", "watt II"), "slides"), (specimen(rng, "slider-crank", "offset crank"), "textbook")]
    for sp, style in picked:
        sol = velpoly.solve(velpoly.load(_with_reference(sp)))
        cons = sheet.constructions(sol, "full")
        t = results_table(sol, "full", velocity=cons.velocity, acceleration=cons.acceleration, poleset=cons.poles)
        refs = sum(1 for r in t.rows if r[t.header.index("reference")])
        assert refs >= 6, f"{sp.kind}: {refs} rows with a book's value"
        st = get_style(style)
        with rc_context(st), sheets.unlabelled_mechanism():   # the table and the panels' boxes read
            fig = sheet.render_sheet(sol, "full", st, cons=cons)
        table = next(ax for ax in fig.axes if ax.get_label() == "table")
        more = [int(x.get_text().split()[1]) for x in table.texts if "more rows" in x.get_text()]
        shown = len(t.rows) - (more[0] if more else 0)
        assert shown >= refs, f"{sp.kind}/{style}: {shown} rows shown of {refs} with a book's value"
        assert any((x.get_gid() or "").startswith("footnote-") for x in table.texts)
        tb = _window(fig, table)
        for ax in fig.axes:
            if ax is not table:
                assert _window(fig, ax).intersection(tb).area < 1.0, f"{sp.kind}/{style}: {ax.get_label()} on the table"
