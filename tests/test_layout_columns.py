"""A panel in a column at the page's full height (velpoly.render.layout.arrange), on generated mechanisms.

The drawings' sizes come from real constructions of generated mechanisms (tests/zoo.py): every arrangement
keeps its panels on the page, off each other (captions included), off the table's corner, every drawing in its
panel; a column is taken only where it draws larger (``score``) than the rows alone and its drawings cover at
least as much paper as in rows (over the specimens a tenth more). A generated sheet drawn with and without columns: the
blank fraction (tests/test_page_fill.py's measure) is lower with them.
"""
from __future__ import annotations

import itertools

import numpy as np
import pytest
from shapely.geometry import box

import sheets
from test_page_fill import blank_fraction
from velpoly.render import layout, sheet
from velpoly.render.layout import MARGIN, _in_rows, arrange, drawn_areas
from velpoly.render.style import get_style, rc_context

NAMES = ["mechanism", "velocity", "acceleration"]
GAP, CAPTION = 0.35, 0.6


@pytest.fixture(scope="module")
def specimens():
    from zoo import zoo
    return zoo(5, 30)


def _spans(sp):
    cons = sheet.constructions(sp.drawn, "full")
    if cons.acceleration is None:
        return None
    out = {}
    for n in NAMES:
        x0, y0, x1, y1 = sheet._bounds(sp.drawn, cons, n)
        out[n] = (x1 - x0, y1 - y0)
    return out


def _boxes(bands, spans):
    """Each panel's box (cm), its drawing's box's area and whether the drawing fits the panel."""
    mx, mt, mb = MARGIN
    out = {}
    for b in bands:
        x = b.left
        for name, w, s in zip(b.names, b.row.widths, b.row.scales):
            dw, dh = spans[name]
            fits = dw / s <= w - 2 * mx + 1e-6 and dh / s <= b.height - mt - mb + 1e-6
            out[name] = (box(x, b.bottom, x + w, b.bottom + b.height), dw * dh / s ** 2, fits)
            x += w + GAP
    return out


def test_columns_keep_panels_apart_and_draw_larger(specimens):
    """30 generated mechanisms, each with a random table's corner (or none): panels on the page, off the
    table and each other; a column only where it draws larger; the drawings' paper no less in the mean."""
    rng = np.random.default_rng(17)
    width, top, bottom = 29.1, 19.2, 0.3
    least, extra = {n: 6.0 for n in NAMES}, {"mechanism": 2.0}
    ratios, columns = [], 0
    for sp in specimens:
        spans = _spans(sp)
        if spans is None:
            continue
        notch = (float(rng.uniform(9, 22)), float(rng.uniform(3, 9))) if rng.uniform() < 0.75 else None
        new = arrange(spans, NAMES, width, top, bottom, GAP, CAPTION, {}, least, extra, notch=notch)
        rows = _in_rows(spans, NAMES, width, top, bottom, GAP, CAPTION, {}, least, extra, notch=notch)
        got = _boxes(new, spans)
        assert set(got) == set(NAMES), sp.kind
        columns += any(b.height >= top - bottom - 1e-9 and len(b.names) == 1 for b in new) and new.score > rows.score
        for name, (panel, _, fits) in got.items():
            x0, y0, x1, y1 = panel.bounds
            assert x0 >= -1e-9 and x1 <= width + 1e-6 and y0 >= bottom - 1e-6 and y1 <= top + 1e-6, (sp.kind, name)
            assert fits, f"{sp.kind}: {name}'s drawing overflows its panel"
            if notch is not None:
                table = box(new.table_left, bottom, new.table_left + notch[0], bottom + notch[1] - 1e-6)
                assert panel.intersection(table).area < 1e-6, f"{sp.kind}: {name} on the table"
        for (a, (pa, _, _)), (b, (pb, _, _)) in itertools.combinations(got.items(), 2):
            grown = [box(*p.bounds[:3], p.bounds[3] + CAPTION) for p in (pa, pb)]
            assert grown[0].intersection(grown[1]).area < 1e-6, f"{sp.kind}: {a} and {b} overlap"
        assert new.score >= rows.score - 1e-9
        # no polygon drawn smaller than in the rows while the other is drawn larger (no trade between them)
        was = {n: s for b in rows for n, s in zip(b.names, b.row.scales)}
        now = {n: s for b in new for n, s in zip(b.names, b.row.scales)}
        smaller = [n for n in ("velocity", "acceleration") if now[n] > was[n] * (1 + 1e-9)]
        larger = [n for n in ("velocity", "acceleration") if now[n] < was[n] * (1 - 1e-9)]
        assert not (smaller and larger), f"{sp.kind}: {smaller} drawn smaller for {larger}: {now} (rows: {was})"
        area = sum(a for a in (g[1] for g in got.values()))
        ratios.append(area / sum(drawn_areas([spans[n] for n in b.names], b.row)[k]
                                 for b in rows for k in range(len(b.names))))
    assert len(ratios) >= 20 and columns >= 5, (len(ratios), columns)
    # never less paper (layout.fuller); over these specimens a tenth more (1.11 when measured)
    assert min(ratios) >= 1.0 - 1e-9 and np.mean(ratios) >= 1.05, np.round(ratios, 3)


@pytest.mark.parametrize("style", [pytest.param("textbook", marks=sheets.on("textbook"))])
def test_columns_no_blanker_on_generated_sheets(style, specimens, monkeypatch):
    """A generated change-point four-bar's full sheet (its mechanism takes a column) drawn with columns and
    without: its blank fraction is lower with them (0.557 against 0.609 when measured at 72 dpi; 0.562 against
    0.616 at 30)."""
    st = get_style(style)
    got = {}
    for penalty in (float("inf"), layout.COLUMN_PENALTY):
        monkeypatch.setattr(layout, "COLUMN_PENALTY", penalty)
        with rc_context(st):
            got[penalty] = blank_fraction(sheet.render_sheet(specimens[3].drawn, "full", st))
    old, new = got.values()
    assert new <= old - 0.02, got
