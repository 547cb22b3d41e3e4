"""velpoly.render.textcache: text measured and drawn from the process's caches is what matplotlib's own Agg
renderer measures and draws, to the bit, on generated texts (plain and mathtext, fonts, sizes, angles,
alignments, antialiasing, positions at every fraction of a pixel), found in the cache and computed."""
from __future__ import annotations

import io

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from velpoly.render import textcache  # noqa: E402
from velpoly.render.style import get_style, rc_context  # noqa: E402

CHARS = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 .,;:-+=/()[]°ωαΔ·×−"
MATH = ["$V_{B}$", r"$\omega_{3}$", r"$a^{t}_{B/A}$", r"$2\omega\times V$", r"$\alpha_{2}=12.5$", "$O_{2}O_{4}$"]


def texts(seed: int, n: int) -> list[dict]:
    """``n`` generated texts: string, place, size, font, angle, alignment, antialiasing."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        if rng.random() < 0.25:
            s = MATH[rng.integers(len(MATH))]
        else:
            s = "".join(rng.choice(list(CHARS), rng.integers(1, 14)))
            if rng.random() < 0.15:
                s += "\n" + s[::-1]
        out.append(dict(x=float(rng.uniform(0.02, 0.9)), y=float(rng.uniform(0.02, 0.95)), s=s,
                        fontsize=float(rng.choice([6.3, 7, 8, 9, 10.5, 14])),
                        family=str(rng.choice(["DejaVu Sans", "DejaVu Serif", "STIXGeneral"])),
                        rotation=float(rng.choice([0, 0, 0, 90, 33.3])),
                        ha=str(rng.choice(["left", "center", "right"])),
                        va=str(rng.choice(["baseline", "center", "top"])),
                        antialiased=bool(rng.random() < 0.9)))
    return out


def page(canvas, spec: list[dict], dpi: float):
    """A figure of ``spec``'s texts on ``canvas``: (its RGBA bytes at ``dpi``, each text's extent at 72 dpi)."""
    fig = Figure(figsize=(5, 4), dpi=72)
    canvas(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_axis_off()
    made = [ax.text(t["x"], t["y"], t["s"], fontsize=t["fontsize"], family=t["family"], rotation=t["rotation"],
                    ha=t["ha"], va=t["va"], antialiased=t["antialiased"]) for t in spec]
    renderer = fig.canvas.get_renderer()
    extents = [tuple(t.get_window_extent(renderer).extents) for t in made]
    buf = io.BytesIO()
    fig.savefig(buf, format="rgba", dpi=dpi)
    svg = io.BytesIO()
    fig.savefig(svg, format="svg", metadata={"Date": None})
    return buf.getvalue(), extents, svg.getvalue()


@pytest.mark.parametrize("style,rounds", [("textbook", ((1, 200), (2, 72))), ("slides", ((3, 133.7),))])
def test_cached_text_is_matplotlibs(style, rounds):
    cached = textcache.canvas_class()
    assert cached is not FigureCanvasAgg, "matplotlib's Agg renderer is not the one textcache knows"
    textcache.clear()
    with rc_context(get_style(style)):
        for seed, dpi in rounds:
            spec = texts(seed, 30)
            plain = page(FigureCanvasAgg, spec, dpi)
            first = page(cached, spec, dpi)    # computed (mostly) and kept
            again = page(cached, spec, dpi)    # found
            assert first[1] == plain[1] and again[1] == plain[1]   # the measures, to the bit
            assert first[0] == plain[0] and again[0] == plain[0]   # the pixels
            assert first[2] == plain[2] and again[2] == plain[2]   # the SVG
    found = textcache.stats()
    for name in ("metrics", "height", "layout", "glyph"):
        assert found[name][0] > 0 and found[name][1] > 0, (name, found[name])


def test_glyphs_at_every_fraction_of_a_pixel():
    """One text moved by 1/64 of a pixel at a time, across two whole pixels: the bitmaps kept by their
    fraction of a pixel are placed where FreeType puts them (the same pixels as matplotlib's)."""
    cached = textcache.canvas_class()
    textcache.clear()
    # at 200 dpi the figure is 1000 x 800 pixels: x moves by 1/64 of a pixel (1.4 pixels over), y by whole
    # pixels from a fixed fraction, so each fraction of x comes back whole pixels on (found in the cache)
    spec = [dict(x=(100.3 + i / 64) / 1000, y=(40.55 + 5 * i) / 800, s="Wg1ω",
                 fontsize=9, family="DejaVu Sans", rotation=0, ha="left", va="baseline", antialiased=True)
            for i in range(90)]
    assert page(cached, spec, 200)[0] == page(FigureCanvasAgg, spec, 200)[0]
    assert textcache.stats()["glyph"][0] > 0


def test_caches_are_bounded(monkeypatch):
    monkeypatch.setitem(textcache.LIMITS, "metrics", 5)
    textcache.clear()
    with rc_context(get_style("textbook")):
        page(textcache.canvas_class(), texts(4, 30), 72)
    assert textcache.stats()["metrics"][2] <= 5
    textcache.clear()


def test_kept_layout_boxes_give_matplotlibs_extents():
    """``textcache.window_extent`` (the label placer's measure) equals ``Text.get_window_extent`` to the bit on
    generated texts (plain, math, two lines, turned, every alignment, five sizes), on the same texts changed
    in place (size, angle, string, place: a kept box must not follow a text's font object), in both styles'
    settings (the same text objects: another font family and mathtext set), at another dpi, and on texts
    matplotlib measures itself (empty, hidden, wrapped)."""
    fig = Figure(figsize=(5, 4), dpi=72)
    textcache.new_canvas(fig)
    ax = fig.add_axes((0, 0, 1, 1))
    renderer = fig.canvas.get_renderer()
    spec = texts(11, 60)
    made = [ax.text(t["x"], t["y"], t["s"], fontsize=t["fontsize"], family=t["family"], rotation=t["rotation"],
                    ha=t["ha"], va=t["va"]) for t in spec]
    made[0].set_text("")
    made[1].set_visible(False)
    made[2].set_wrap(True)

    def same():
        for t in made:
            assert tuple(textcache.window_extent(t, renderer).extents) == tuple(t.get_window_extent(renderer).extents), t
    rng = np.random.default_rng(5)
    for style in ("textbook", "slides", "textbook"):
        with rc_context(get_style(style)):
            same()
            same()   # the second time from the kept boxes
            for t in made[3:]:
                t.set_fontsize(float(rng.choice([6.3, 8, 11.1])))
                t.set_rotation(float(rng.choice([0, 90, 12.5])))
                t.set_position((float(rng.uniform(0, 1)), float(rng.uniform(0, 1))))
                t.set_text(spec[int(rng.integers(len(spec)))]["s"])
            same()
    fig.set_dpi(200)
    same()
    found, computed, _ = textcache.stats()["box"]
    assert found > 0 and computed > 0
