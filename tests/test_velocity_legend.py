"""A velocity polygon that draws a slip lists its kinds (issue 17, items 4 and 5: every drawn thing is what it
reads as).

A block driven along a moving guide (a slider driver on a rotating guide) or a contact with a given slip has its
known V_a/b drawn as a slip along the path (long dashes; orange on slides). Without a legend of its own, the only
legend on the sheet was the acceleration polygon's, where long dashes read as a normal component. The velocity
polygon now has a legend wherever it draws a kind other than absolute and relative; the legend lists exactly the
kinds drawn (those of the arrows drawn), and a velocity polygon of absolute and relative vectors alone keeps
none (their weight, colour and labels tell them apart). Checked on seeded generated mechanisms of the kinds that
draw a known slip, both styles."""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

import velpoly
from velpoly.polygons import velocity_polygon
from velpoly.render.polygon import draw_polygon
from velpoly.render.style import KIND_LABELS, get_style, rc_context
from zoo import INVERTED, specimen

KINDS = ("absolute", "relative", "normal", "tangential", "coriolis", "slip")


def _drawn(sol, style):
    """(the kinds of the vectors drawn, the legend's texts or None) of ``sol``'s velocity polygon."""
    st = get_style(style)
    with rc_context(st):
        fig = Figure(figsize=(6, 5), dpi=72)
        FigureCanvasAgg(fig)
        ax = fig.add_axes((0.02, 0.02, 0.96, 0.96))
        art = draw_polygon(velocity_polygon(sol), ax, mechanism=sol.mechanism, style=st)
        kinds = {kind for kind, *_ in art.arrows}
        leg = ax.get_legend()
        return kinds, None if leg is None else [t.get_text() for t in leg.get_texts()]


def _specimens():
    rng = np.random.default_rng(20261127)
    sliders = [v for v in INVERTED if v.endswith("slider")]
    out = [specimen(rng, "inverted slider-crank", v) for v in rng.choice(sliders, 3, replace=False)]
    return out + [specimen(rng, "four-bar")]


@pytest.fixture(scope="module")
def specimens():
    return _specimens()


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_velocity_polygon_lists_its_kinds_where_it_draws_a_slip(specimens, style):
    slips = 0
    for sp in specimens:
        kinds, legend = _drawn(sp.drawn, style)
        if kinds - {"absolute", "relative"}:
            slips += 1
            assert legend == [KIND_LABELS[k] for k in KINDS if k in kinds], f"{sp.kind}: {legend} for {kinds}"
        else:
            assert legend is None, f"{sp.kind}: a legend {legend} for {kinds}"
    assert slips == 3, "a generated slider driver on a moving guide drew no slip"   # the class is exercised


def test_fig_3_15b_velocity_polygon_names_its_slip():
    """The gallery's sliding contact with a prescribed slip: its velocity polygon's legend names the slip."""
    from paths import example
    sol = velpoly.solve(velpoly.load(example("fig3_15b_sliding")))
    kinds, legend = _drawn(sol, "textbook")
    assert "slip" in kinds and legend is not None and KIND_LABELS["slip"] in legend
