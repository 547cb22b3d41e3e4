"""The faster paths of drawing (issue 20) give what the slower ones gave.

A PNG written by velpoly.render.pngfile decodes to the pixels of matplotlib's own PNG of the same
figure (opaque sheets as RGB, a transparent figure keeps its alpha), with matplotlib's metadata.
"""
from __future__ import annotations

import io

import numpy as np
import pytest

import velpoly
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
