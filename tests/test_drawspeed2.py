"""The drawing's shortcuts of session fastdraw give what matplotlib gives (velpoly/render/textcache.py).

* A sheet's SVG, its text written as paths by :func:`velpoly.render.textcache.svg_renderer_class` (a plain
  text's measure, glyph places and outlines and each font's heights kept for the process), is the file
  matplotlib's own SVG writer makes of the same figure, byte for byte: on generated texts (plain and math,
  three families, sizes, turned, aligned, two lines, coloured and faint, kerned pairs), written fresh and
  again (found in the caches), in both styles' settings, and on a generated mechanism's sheet.

Cheap: a small figure of texts and one sheet of a zoo specimen.
"""
from __future__ import annotations

import io

import numpy as np
import pytest
from matplotlib.figure import Figure

from velpoly.render import sheet, textcache
from velpoly.render.style import get_style, rc_context

import zoo

_WORDS = ("AV", "Wa", "To", "ω", "V_B", "25.3 mm/s", "∠ 120.00°", "−4.5", "(1 cm = 0.06 m)", "P₁₃", "Kennedy",
          "ﬁ", "x²", "g y", "ABC")
_MATH = ("$V_{B}$", r"$\omega_{3}$", r"$a^{t}_{B_{3}/B_{4}}$", r"$\alpha \times r$", "$P_{13}$")


def _texts(seed: int, n: int) -> list[dict]:
    """``n`` generated texts: a few words or a math label each, in varied fonts, sizes, angles and colours."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        words = [str(rng.choice(_WORDS)) for _ in range(int(rng.integers(1, 4)))]
        if rng.random() < 0.3:
            words.insert(int(rng.integers(0, len(words) + 1)), str(rng.choice(_MATH)))
        s = " ".join(words)
        if rng.random() < 0.15:
            s = s + "\n" + str(rng.choice(_WORDS))
        out.append(dict(x=float(rng.random()), y=float(rng.random()), s=s,
                        fontsize=float(rng.choice([6.5, 8, 9.35, 11, 14.2])),
                        family=str(rng.choice(["serif", "sans-serif", "DejaVu Sans Mono"])),
                        style=str(rng.choice(["normal", "italic"])),
                        rotation=float(rng.choice([0, 0, 0, 30, 90, -12.5])),
                        ha=str(rng.choice(["left", "center", "right"])),
                        va=str(rng.choice(["baseline", "top", "center", "bottom"])),
                        color=str(rng.choice(["black", "#1f77b4", "0.4"])),
                        alpha=float(rng.choice([1.0, 1.0, 0.6]))))
    return out


def _svg(fig, **kw) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="svg", metadata={"Date": None}, **kw)
    return buf.getvalue()


def _page(spec) -> Figure:
    fig = Figure(figsize=(5, 4), dpi=72)
    textcache.new_canvas(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_axis_off()
    for t in spec:
        ax.text(t["x"], t["y"], t["s"], fontsize=t["fontsize"], family=t["family"], style=t["style"],
                rotation=t["rotation"], ha=t["ha"], va=t["va"], color=t["color"], alpha=t["alpha"])
    return fig


@pytest.mark.parametrize("style,seeds", [("textbook", (1,)), ("slides", (3,))])
def test_svg_text_kept_is_matplotlibs(style, seeds):
    """Generated texts written by the kept SVG renderer, fresh and found again, are matplotlib's own file."""
    assert hasattr(textcache.canvas_class(), "print_svg"), "matplotlib's SVG writer is not the one textcache knows"
    textcache.clear()
    with rc_context(get_style(style)):
        for seed in seeds:
            fig = _page(_texts(seed, 30))
            theirs = _svg(fig, backend="svg")   # matplotlib's FigureCanvasSVG and RendererSVG
            assert _svg(fig) == theirs          # computed (mostly) and kept
            assert _svg(fig) == theirs          # found
            assert _svg(_page(_texts(seed, 30))) == theirs   # found by another figure
    found = textcache.stats()
    for name in ("svg metrics", "svg glyphs", "outline", "height"):
        assert found[name][0] > 0 and found[name][1] > 0, (name, found[name])


def _content(lay) -> tuple:
    return (lay.rect, lay.cells, lay.rules, lay.footnotes, lay.blocks, lay.notes, lay.title, lay.title_size, lay.shown,
            lay.size, lay.used, lay.whole, lay.overflows)


def test_generated_sheet_svg_is_matplotlibs(monkeypatch):
    """A generated mechanism's sheet (its table, labels, captions, math) written as SVG by velpoly is the file
    matplotlib's SVG writer makes of it. Its layout measured the table once a room (``_Planner._measured``): each
    room asked for again gets what measuring it afresh gives, a copy of its own (moving it moves no other)."""
    asked, measure = [], sheet._Planner._measured

    def checked(self, rect):
        got = measure(self, rect)
        fresh = sheet._measure_table(self.sol, self.fig, rect, self.sheet, self.st, self.cons, self.table_rows)
        assert _content(got) == _content(fresh)
        got.set_position((9.0, 9.0, 1.0, 1.0))
        assert measure(self, rect).rect == tuple(rect)
        asked.append(rect)
        return measure(self, rect)
    monkeypatch.setattr(sheet._Planner, "_measured", checked)
    sol = zoo.zoo(seed=11, count=2)[1].drawn   # (a four-bar whose table is narrowed in the page's corner)
    st = get_style("textbook")
    with rc_context(st):
        fig = sheet.render_sheet(sol, "full", st)
        assert _svg(fig) == _svg(fig, backend="svg")
    assert len(asked) > len(set(asked))   # rooms asked for again


def _old_sprite(dpi, t, s, per_char):
    """What ``Animator._sprite`` made before: a scratch figure on matplotlib's own Agg canvas, its whole picture
    made float, then cut to the ink."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    sc = Figure(figsize=(800 / dpi, 300 / dpi), dpi=dpi)
    sc.patch.set_alpha(0.0)
    FigureCanvasAgg(sc)
    tx = sc.text(0.5, 0.5, s, fontproperties=t.get_fontproperties(), color=t.get_color(),
                 ha="left" if per_char else t.get_ha(), va=t.get_va())
    sc.canvas.draw()
    buf = np.asarray(sc.canvas.buffer_rgba()).astype(np.float32) / 255.0
    adv = tx.get_window_extent(sc.canvas.get_renderer()).width if per_char else 0.0
    alpha = buf[..., 3]
    rows, cols = np.flatnonzero(alpha.any(axis=1)), np.flatnonzero(alpha.any(axis=0))
    if not len(rows):
        return np.zeros((1, 1, 4), np.float32), 0, 0, adv
    return buf[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1], cols[0] - 400.0, rows[0] - 150.0, adv


def test_animation_sprites_are_the_old_pictures():
    """An animation's text pictures (``Animator._sprite``: drawn on a canvas whose glyphs are kept, only the ink's
    rectangle made float) are the old ones, value for value, on generated texts and characters (and a blank)."""
    from types import SimpleNamespace
    from velpoly.render.animate import Animator
    rng = np.random.default_rng(8)
    with rc_context(get_style("slides")):
        fig = _page([])
        for spec in _texts(4, 6) + [dict(_texts(5, 1)[0], s=" ")]:
            dpi = float(rng.choice([60.0, 120.0]))
            me = SimpleNamespace(dpi=dpi, _sprites={})
            t = fig.text(0.5, 0.5, spec["s"], fontsize=spec["fontsize"], family=spec["family"], color=spec["color"],
                         ha=spec["ha"], va=spec["va"])
            for s, per_char in [(spec["s"], False)] + [(ch, True) for ch in spec["s"][:3]]:
                new, old = Animator._sprite(me, t, s, per_char), _old_sprite(dpi, t, s, per_char)
                assert new[0].dtype == old[0].dtype and np.array_equal(new[0], old[0]), s
                assert new[1:] == old[1:]
