"""The cheaper computations of a sheet (issue 20, seventh session) give what the ones they replace gave.

* velpoly.render.pngfile writes the PNG itself (unfiltered rows, zlib): the file decodes to the pixels it
  was given and carries the dpi and text Pillow's writer gives, on generated images (opaque and not,
  odd sizes, noise and drawings) and metadata (Latin-1 and not).
* velpoly.render.table.drawn_extent measures where a table drawn in its room ends without drawing it: the
  same bits as the table drawn in a scratch axes, on generated mechanisms' and generated tables.
* velpoly.render.style._unmemoised parses a shallow label without pyparsing's memo: the same parse as
  with it, on generated labels.
"""
from __future__ import annotations

import io

import numpy as np
import pytest


def _decoded(data: bytes):
    from PIL import Image
    im = Image.open(io.BytesIO(data))
    im.load()
    return im, np.asarray(im)


def _pillow(rgba, dpi, text):
    """The same image written by Pillow (what velpoly wrote before): its mode, dpi and text as decoded."""
    from PIL import Image, PngImagePlugin
    image = Image.fromarray(rgba, "RGBA")
    if rgba[..., 3].min() == 255:
        image = image.convert("RGB")
    info = PngImagePlugin.PngInfo()
    for k, v in text.items():
        info.add_text(k, v)
    out = io.BytesIO()
    image.save(out, format="png", pnginfo=info, dpi=(dpi, dpi), compress_level=1)
    return _decoded(out.getvalue())[0]


def _images(rng):
    """Generated RGBA images: noise, a drawing (white paper, a few lines and a glyph-like blot), each opaque
    and with some transparency, in odd sizes."""
    for h, w in [(1, 1), (3, 7), (17, 5), (64, 129)]:
        noise = rng.integers(0, 256, (h, w, 4), dtype=np.uint8)
        paper = np.full((h, w, 4), 255, np.uint8)
        paper[rng.integers(0, h, 3)] = (0, 0, 0, 255)
        paper[:, rng.integers(0, w, 2), :3] = rng.integers(0, 256, 3, dtype=np.uint8)
        for img in (noise, paper):
            opaque = img.copy()
            opaque[..., 3] = 255
            yield opaque
            yield img


def test_a_png_written_by_velpoly_decodes_to_its_pixels_with_pillow_s_metadata():
    from velpoly.render.pngfile import png_bytes
    rng = np.random.default_rng(7)
    texts = [{"Software": "Matplotlib version3.11.2, https://matplotlib.org/"},
             {"Software": "x", "Title": "ω₂ = 3 rad/s", "Author": "Ünal"}, {}]
    seen = set()
    for k, rgba in enumerate(_images(rng)):
        dpi, text = (72, 100, 200, 199.5)[k % 4], texts[k % 3]
        im, pixels = _decoded(png_bytes(rgba, dpi, text))
        opaque = bool(rgba[..., 3].min() == 255)
        want = rgba[..., :3] if opaque else rgba
        assert im.mode == ("RGB" if opaque else "RGBA") and pixels.shape == want.shape
        assert np.array_equal(pixels, want)
        theirs = _pillow(rgba, dpi, text)
        assert im.mode == theirs.mode and im.info == theirs.info   # dpi and every text, as Pillow writes them
        seen.add((opaque, bool(text)))
    assert len(seen) == 4


# -- the results table's drawn width, measured without drawing it (velpoly.render.table.drawn_extent) -------

def _drawn_there(lay, fig):
    """What velpoly did before: the measured table drawn in a scratch axes at its room, the axes' left and its
    rightmost text's or rule's right edge (pixels), the axes taken away."""
    from velpoly.render.canvas import renderer_of
    from velpoly.render.table import draw_results_table
    tax = draw_results_table(None, fig.add_axes(lay.rect, label="table"), layout=lay).ax
    r = renderer_of(fig)
    x0 = tax.get_window_extent(r).x0
    right = max((a.get_window_extent(r).x1 for a in (*tax.texts, *tax.lines)), default=x0)
    fig.delaxes(tax)
    return x0, right


def _generated_table(rng):
    """A Table of generated cells: rich quantities (subscripts, a link's subscript of a subscript), numbers,
    units, vectors, long and empty cells, marks of footnotes."""
    from velpoly.tables import Table
    names = ["$V_{B}$", "$\\omega_{3}$", "$A_{C_{4}}$", "$V_{P₂}$", "$\\alpha_{12}$", "|$V_{BA}$|", "$R_{B/C}$", "x"]
    marks = ["", "", "†", "‡"]

    def number():
        return f"{rng.normal() * 10.0 ** int(rng.integers(-3, 6)):.{int(rng.integers(1, 7))}g}"
    header = ("quantity", "graphical", "analytic", "unit", "reference")[:int(rng.integers(3, 6))]
    rows = []
    for _ in range(int(rng.integers(3, 30))):
        cells = [str(rng.choice(names)), number(), f"{number()} ∠ {rng.uniform(0, 360):.1f}°", "mm/s²",
                 f"{number()} {rng.choice(marks)}".strip()][:len(header)]
        if rng.random() < 0.2:
            cells[int(rng.integers(1, len(cells)))] = "" if rng.random() < 0.5 else "a long cell " * 4
        rows.append(tuple(cells))
    notes = tuple((m, "omega_3", "the book's value " * int(rng.integers(1, 12))) for m in ("†", "‡"))
    title = "Results " + "of a long source " * int(rng.integers(0, 8))
    return Table(title, header, tuple(rows), notes)


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_a_table_s_drawn_width_is_measured_as_drawn_to_the_bit(style):
    """The table in the page's corner is as wide as its drawn blocks, title and footnotes: drawn_extent (probe
    texts, no axes) gives the left and right edges the table drawn in an axes at its room gives, to the bit, on
    generated mechanisms' tables and generated tables, in rooms roomy, short (rows cut), narrow (type shrunk,
    title and footnotes wrapped) and moved (as the sheet's layout moves a table)."""
    import zoo
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    import velpoly
    from velpoly.render.sheet import constructions
    from velpoly.render.style import get_style, rc_context
    from velpoly.render.table import drawn_extent, measure_results_table
    st = get_style(style)
    rng = np.random.default_rng(20 if style == "textbook" else 21)
    kinds = ["four-bar", "six-bar", "slot", "contact"] if style == "textbook" else ["six-bar"]
    rects = [(0.0106, 0.0107, 0.9788, 0.4), (0.02, 0.5, 0.97, 0.13), (0.6, 0.1, 0.25, 0.5)]
    cases = 0
    with rc_context(st):
        fig = Figure(figsize=st.figsize, dpi=72)
        FigureCanvasAgg(fig)
        specimens = [zoo.specimen(rng, k).drawn for k in kinds]
        for i, sol in enumerate(specimens + [None] * (2 if style == "textbook" else 1)):
            if sol is None:   # a generated table (beside the first specimen's mechanism: its names)
                sol, kw = specimens[0], {"table": _generated_table(rng)}
            else:
                cons = constructions(sol, "full")
                kw = dict(velocity=cons.velocity, acceleration=cons.acceleration, poleset=cons.poles)
            for j, rect in enumerate(rects[i % 2::2] if style == "slides" else rects):
                lay = measure_results_table(sol, (fig, rect), sheet="full", style=st, **kw)
                if (i + j) % 2:   # moved, as the sheet's layout moves a table
                    x, y, w, h = lay.rect
                    lay.set_position((x + rng.uniform(-0.01, 0.01), y + rng.uniform(0.0, 0.3), w, h))
                assert drawn_extent(lay, fig) == _drawn_there(lay, fig), (i, rect, lay.rect)
                assert not fig.axes
                cases += 1
    assert cases >= 3


# -- mathtext parsed without pyparsing's memo where the text is shallow (velpoly.render.style._unmemoised) ---

def _math_text(rng) -> str:
    """A generated label as velpoly writes them: plain words and $...$ with symbols, Greek letters, products,
    thin spaces, subscripts and superscripts, groups two deep (a subscript's own subscript)."""
    def atom():
        return str(rng.choice(["V", "A", "O", "B", "x", "2", "n", "t", "\\omega ", "\\alpha ", "\\theta ", "P"]))

    def script(depth):
        body = "".join(atom() for _ in range(int(rng.integers(1, 3))))
        if depth < 2 and rng.random() < 0.5:
            body += "_{" + script(depth + 1) + "}"
        return body

    def math():
        out = atom() + str(rng.choice(["_", "^"])) + "{" + script(1) + "}"
        for _ in range(int(rng.integers(0, 3))):
            out += str(rng.choice([" = ", "\\,", " \\times ", "/", " + "])) + atom()
            if rng.random() < 0.5:
                out += "_{" + script(1) + "}"
        return "$" + out + "$"
    words = ["normal component", "= 20 rad/s ccw", "misprint: 200/115 for", "(", "):", "follows from", "†"]
    return " ".join(str(rng.choice(words)) if rng.random() < 0.4 else math() for _ in range(int(rng.integers(1, 4))))


def test_a_shallow_label_parsed_without_the_memo_is_the_parse_with_it():
    """matplotlib parses mathtext with pyparsing's packrat memo on; velpoly parses its shallow labels without it
    (faster). On generated labels, both outputs (raster for Agg, vector for SVG and PDF), both styles' fonts, two
    dpi and type sizes: the very same parse (metrics, bitmap, glyphs and rules); a deep or foreign text keeps
    the memo."""
    import inspect
    from matplotlib.font_manager import FontProperties
    from matplotlib.mathtext import MathTextParser
    from pyparsing import ParserElement
    from velpoly.render.style import _SHALLOW, _unmemoised, get_style, rc_context, share_mathtext
    share_mathtext()
    raw = inspect.unwrap(MathTextParser._parse_cached)   # matplotlib's parse, under its caches and velpoly's
    memo = ParserElement.__dict__["_parse"]
    assert memo is not ParserElement._parseNoCache   # (matplotlib turned it on)

    def parsed(out, s, dpi, prop):
        p = MathTextParser("agg" if out == "raster" else "path")
        from matplotlib.ft2font import LoadFlags
        r = raw(p, s, dpi, prop, True, LoadFlags.FORCE_AUTOHINT if out == "raster" else LoadFlags.NO_HINTING)
        if out == "raster":
            return r.ox, r.oy, r.width, r.height, r.depth, np.asarray(r.image).tobytes()
        return r.width, r.height, r.depth, [(g[0].fname, *g[1:]) for g in r.glyphs], r.rects
    rng = np.random.default_rng(2026)
    for k in range(16):
        s = _math_text(rng)
        assert _SHALLOW.fullmatch(s), s
        st = get_style(("textbook", "slides")[k % 2])
        with rc_context(st):
            prop = FontProperties(family=st.font_family, size=float(rng.choice([st.small_size, st.font_size, 7.3])))
            out, dpi = ("raster", "vector")[k // 2 % 2], (72, 200)[k // 4 % 2]
            with_memo = parsed(out, s, dpi, prop)
            with _unmemoised(s):
                assert ParserElement.__dict__["_parse"] is ParserElement._parseNoCache
                without = parsed(out, s, dpi, prop)
            assert ParserElement.__dict__["_parse"] is memo
            assert without == with_memo, s
    for deep in ["${{{x}}}$", r"$\frac{a}{b}$", r"$\left(x\right)$", r"${\sqrt{x}}$", r"$\omegax$"]:
        assert not _SHALLOW.fullmatch(deep)
        with _unmemoised(deep):
            assert ParserElement.__dict__["_parse"] is memo
