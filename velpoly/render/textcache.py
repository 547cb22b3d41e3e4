"""Text measured and drawn once per process: an Agg canvas whose renderer remembers what FreeType did.

A sheet's figure is an Agg figure (:func:`velpoly.render.sheet.render`): its text is measured at 72 dpi
while the page is laid out (labels placed, the table measured, captions wrapped) and measured again and
drawn at 200 dpi for a PNG. matplotlib keeps a text's measure per renderer, and every figure (every dpi)
has a new renderer, so each sheet asks FreeType again for what an earlier one already had: the same
column heads, units and names, the same sheet drawn again (a notebook, step frames, the tests). Every
such request loads each character's glyph again (50-100 us a glyph here: docs/performance.md).

:class:`TextCanvas` is matplotlib's ``FigureCanvasAgg`` with a renderer (:class:`_Renderer`) that keeps,
for the whole process, what each of these requests depends on and what came back:

* a plain (non-math) text's width, height and descent: keyed by the string, the font properties, the
  font settings that choose the font file (``font.*``), the kerning factor, the hinting flag and the dpi;
* a font's ascent, descent and line gap (``Text._get_layout`` reads the font's OS/2 or hhea table again for
  every text it lays out, unless the renderer gives them: ``_get_font_height_metrics``), keyed alike;
* a plain text's glyph layout for drawing (``FT2Font._layout``: glyph, font and position), keyed alike
  and by the thread (matplotlib gives each thread its own font objects);
* a glyph's rendered bitmap (``FT2Font._render_glyph``), keyed by its font object, size, dpi, glyph,
  transformation matrix, load flags, antialiasing and its position's fraction of a pixel (26.6 fixed
  point, the six low bits): FreeType rasterises an outline moved by whole pixels into the same bitmap
  moved by those pixels, so the bitmap is kept with its offset from the whole-pixel position.

The SVG a sheet is written to gets the same from :func:`svg_renderer_class` (matplotlib's SVG writer sets
each text as paths: it measures the text and lays out its glyphs at a fixed 100 pt and scales them, and writes
each glyph's outline once a file; all three are kept per process, keyed alike). A sheet's texts are measured,
in every format, by the Agg renderer at its PNG's dpi (:func:`measurer`; :mod:`velpoly.render.typeset`): its
SVG's writer only draws them.

Each is a pure function of its key, so a value found is the value FreeType would give: the pixels, SVG
and PDF output are the same bytes (tests/test_textcache.py checks the three against matplotlib's own
renderer on generated texts; benchmarks/golden.sh writes every example's SVG to compare). Mathtext needs none of it:
its parses are shared already (:func:`velpoly.render.style.share_mathtext`), its glyphs go through the
glyph cache. The caches are bounded (oldest dropped first) and emptied in a forked child (a font object
reads its file through an offset shared with the parent: the gallery's workers start empty), as
matplotlib empties its own font cache there. Where matplotlib's Agg renderer is not as this module
expects (another version), :func:`canvas_class` gives matplotlib's own canvas and nothing changes.
"""
from __future__ import annotations

import codecs
import functools
import math
import os
import threading
from collections import OrderedDict

__all__ = ["canvas_class", "svg_renderer_class", "new_canvas", "measurer", "add_axes", "share_rectangle_transforms",
           "window_extent", "kept_layout", "clear", "stats", "LIMITS", "rc_reader"]

LIMITS = {"metrics": 20000, "height": 1000, "layout": 10000, "glyph": 20000, "box": 10000,
          "svg metrics": 20000, "svg glyphs": 10000, "outline": 5000}   # entries kept per cache (a glyph bitmap
# 0.3-3 KB at 200 dpi, an outline about 1 KB)

_CACHES: dict[str, OrderedDict] = {name: OrderedDict() for name in LIMITS}
_HITS = {name: [0, 0] for name in LIMITS}   # name -> [found, computed]
_RC = ("font.family", "font.style", "font.variant", "font.weight", "font.stretch", "font.size",
       "font.serif", "font.sans-serif", "font.cursive", "font.fantasy", "font.monospace",
       "font.enable_last_resort", "text.kerning_factor", "text.hinting")
_CLASS = []   # the canvas class, made once
_MEASURERS: dict = {}   # dpi -> an Agg renderer of the canvas's class that measures text (measurer)


def clear() -> None:
    """Empty every cache (and its counts), and forget the measurers (:func:`measurer`)."""
    for name, c in _CACHES.items():
        c.clear()
        _HITS[name][:] = [0, 0]
    _MEASURERS.clear()


def stats() -> dict:
    """``{cache: (found, computed, kept)}`` since the last :func:`clear`."""
    return {name: (*_HITS[name], len(_CACHES[name])) for name in LIMITS}


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=clear)


def _get(name: str, key):
    c = _CACHES[name]
    got = c.get(key)
    if got is not None:
        _HITS[name][0] += 1
    return got


def _put(name: str, key, value):
    c = _CACHES[name]
    c[key] = value
    _HITS[name][1] += 1
    if len(c) > LIMITS[name]:
        c.popitem(last=False)
    return value


def _font_key(prop, dpi: float) -> tuple:
    """What chooses and sizes a plain text's font: the properties, the settings in force, the dpi."""
    get = rc_reader()
    return (tuple(prop.get_family()), prop.get_style(), prop.get_variant(), prop.get_weight(),
            prop.get_stretch(), prop.get_size_in_points(), str(prop.get_file()), prop.get_math_fontfamily(),
            tuple([tuple(v) if isinstance(v, list) else v for v in map(get, _RC)]), dpi)


def rc_reader():
    """A function that reads a matplotlib setting by its name, the value ``rcParams[name]`` gives: the stored value
    as ``rcParams._get`` reads it (``dict.__getitem__`` of the settings, without ``__getitem__``'s check for the
    ``backend`` entry, which no key here is, and without a Python call: a fifth of the time), where the settings
    are such a dict. The keys of text measures and parses read a dozen settings each, thousands of times a
    sheet."""
    import matplotlib
    rc = matplotlib.rcParams
    if isinstance(rc, dict) and hasattr(rc, "_get"):
        return functools.partial(dict.__getitem__, rc)
    return rc.__getitem__


_MATH_RC: list = []   # the mathtext settings (their names, read once): a math text's layout depends on them


def window_extent(text, renderer):
    """``text.get_window_extent(renderer)``, the text's layout box kept for the process (the ``box`` cache).

    matplotlib's extent is ``Text._get_layout``'s box (the lines measured and aligned at the origin, then
    rotated) translated by where the text's transform puts its position. That box is a function of the
    string, the font properties and the font settings (:func:`_font_key`), the mathtext settings, whether
    math is parsed, the rotation and its mode, the alignments, the line spacing, the figure's dpi and the
    renderer (its type and dpi): it is kept by those and translated as matplotlib translates it (the same
    float sums), so the extent is matplotlib's to the bit (tests/test_textcache.py). A label placer measures
    the same names and values on every sheet of a process, each at a few sizes. A text laid out otherwise
    (hidden, empty, wrapped, TeX, turned with its transform) or a matplotlib without these methods is
    measured by matplotlib."""
    fig = text.get_figure(root=True)
    if (fig is None or renderer is None or not text.get_visible() or not text.get_text() or text.get_wrap()
            or text.get_usetex() or text.get_transform_rotates_text()
            or not hasattr(text, "_get_layout") or not hasattr(text, "_get_multialignment")):
        return text.get_window_extent(renderer)
    import matplotlib
    if not _MATH_RC:
        _MATH_RC.extend(sorted(k for k in matplotlib.rcParams if k.startswith("mathtext.")) + ["text.hinting_factor"])
    key = (text.get_text(), _font_key(text.get_fontproperties(), fig.dpi), tuple(map(str, map(rc_reader(), _MATH_RC))),
           text.get_parse_math(), text.get_rotation(), text.get_rotation_mode(), text.get_horizontalalignment(),
           text.get_verticalalignment(), text._get_multialignment(), text.get_linespacing(), type(renderer),
           getattr(renderer, "dpi", None))
    x, y = text.get_transform().transform(text.get_unitless_position())
    return kept_layout(key, lambda: text, renderer).translated(x, y)


def kept_layout(key, make, renderer):
    """The layout box (``Text._get_layout``'s, pixels at the text's origin) kept under ``key`` in the ``box``
    cache, laid out from the text ``make()`` gives where it is not kept yet. ``key`` must name everything the
    layout depends on (:func:`window_extent`'s, or a table room's settings, string and properties); the caller
    translates the box to the text's place as matplotlib does, and measures texts matplotlib lays out
    otherwise (empty, or no ``_get_layout``) itself."""
    box = _get("box", key)
    if box is None:
        box = _put("box", key, make()._get_layout(renderer)[0])
    return box


def _height_metrics(prop, dpi: float) -> tuple:
    """``(ascent, descent, line gap)`` of ``prop``'s font in pixels at ``dpi``, as matplotlib 3.11's
    ``Text._get_layout`` computes them (the same tables, the same arithmetic); (None, None, None) where
    the font has neither table (matplotlib then measures "lp")."""
    from matplotlib.font_manager import fontManager, get_font
    font = get_font(fontManager._find_fonts_by_props(prop))
    for table_name, gap, ascent, descent in (("OS/2", "sTypoLineGap", "sTypoAscender", "sTypoDescender"),
                                             ("hhea", "lineGap", "ascent", "descent")):
        table = font.get_sfnt_table(table_name)
        if table is None:
            continue
        fontsize = prop.get_size_in_points()
        units_per_em = font.get_sfnt_table("head")["unitsPerEm"]
        scale = 1 / units_per_em * fontsize * dpi / 72
        return table[ascent] * scale, -table[descent] * scale, table[gap] * scale
    return None, None, None


TESTED = ((3, 11),)   # matplotlib releases whose glyph path this module follows (tests/test_textcache.py)


def _supported() -> bool:
    """matplotlib's Agg renderer draws text as this module expects (matplotlib 3.11's glyph-by-glyph path):
    a release in :data:`TESTED` (another may keep the names and change what they do) with those names."""
    import matplotlib
    if tuple(int(p) for p in matplotlib.__version__.split(".")[:2] if p.isdigit()) not in TESTED:
        return False
    from matplotlib.backends import backend_agg
    from matplotlib.ft2font import FT2Font
    from matplotlib.text import Text
    return all(hasattr(backend_agg.RendererAgg, n) for n in
               ("_draw_text_glyphs_and_boxes", "_prepare_font", "get_text_width_height_descent", "draw_text")) \
        and all(hasattr(FT2Font, n) for n in ("_layout", "_render_glyph", "_set_transform")) \
        and hasattr(backend_agg, "get_hinting_flag") \
        and "_get_font_height_metrics" in Text._get_layout.__code__.co_names


def canvas_class():
    """The Agg canvas class for a sheet's figure: :class:`TextCanvas`, or matplotlib's ``FigureCanvasAgg``
    where its renderer is not the one this module knows."""
    if not _CLASS:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        _CLASS.append(_make() if _supported() else FigureCanvasAgg)
    return _CLASS[0]


def new_canvas(fig):
    """Give ``fig`` a :func:`canvas_class` canvas (as ``FigureCanvasAgg(fig)`` does) and return it."""
    return canvas_class()(fig)


def measurer(dpi: float):
    """An Agg renderer at ``dpi`` of the canvas's class (:func:`canvas_class`: its text measures kept), to
    measure text with (one a dpi, for the process; it draws nothing: its canvas is one pixel)."""
    got = _MEASURERS.get(dpi)
    if got is None:
        from matplotlib.figure import Figure
        canvas = canvas_class()(Figure(figsize=(1 / dpi, 1 / dpi), dpi=dpi))
        got = _MEASURERS[dpi] = canvas.get_renderer()
    return got


class _Kept:
    """A patch's ``get_transform`` that gives the one transform it was made with (picklable, unlike a lambda)."""

    __slots__ = ("transform",)

    def __init__(self, transform):
        self.transform = transform

    def __call__(self):
        return self.transform


def share_rectangle_transforms(ax):
    """Let every artist added to ``ax`` clip by one transform of its background Rectangle; return ``ax``.

    matplotlib clips a line, patch or text added to an axes by the axes' background (``ax.patch``, the unit
    Rectangle in axes coordinates): ``set_clip_path`` asks the Rectangle for its transform, and
    ``Patch.get_transform`` builds it anew each time (``BboxTransformTo`` of its box, an ``Affine2D`` of its
    rotation, each composed with ``transAxes``: four transform nodes an artist, each registered with its
    parents, so that every later move of the axes invalidates them all). The axes' Rectangle never changes
    (its box is (0, 0, 1, 1), unrotated, its transform ``transAxes``), so the transform it gives is the same
    each time, value for value: kept once, it is the very transform each artist would get, and it is
    invalidated with ``transAxes`` as each new one would be. The output is the same bytes. An axes whose
    background is not such a Rectangle (another projection) is left as it is.
    """
    from matplotlib.patches import Rectangle
    patch = ax.patch
    if type(patch) is not Rectangle or patch.get_bbox().bounds != (0.0, 0.0, 1.0, 1.0) or patch.angle != 0 \
            or patch.get_transform.__class__ is _Kept:
        return ax
    patch.get_transform = _Kept(patch.get_transform())
    return ax


def add_axes(fig, rect, **kw):
    """``fig.add_axes(rect, **kw)``, a :class:`~velpoly.render.panelaxes.PanelAxes` (its ticks made when first asked
    for), its artists clipped by one kept transform (:func:`share_rectangle_transforms`)."""
    from .panelaxes import PanelAxes
    return share_rectangle_transforms(fig.add_axes(rect, axes_class=PanelAxes, **kw))


_MATRICES: dict = {}   # (angle, slant, extend) -> FreeType's 16.16 matrix of a glyph, as matplotlib computes it


def _matrix(angle, slant, extend):
    """(matrix, its four integers, cos, sin) of a glyph drawn at ``angle`` degrees, slanted and extended, as
    matplotlib's Agg renderer computes it."""
    key = (angle, slant, extend)
    got = _MATRICES.get(key)
    if got is None:
        import numpy as np
        cos, sin = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        m = (0x10000 * np.array([[cos, -sin], [sin, cos]]) @ [[extend, extend * slant], [0, 1]]).round().astype(int)
        got = _MATRICES[key] = (m, tuple(m.ravel().tolist()), cos, sin)
    return got


def _layout(renderer, s, prop, mtext, flags) -> tuple:
    """A plain text's glyphs for drawing, ``(font, glyph index, x, y)`` each (``FT2Font._layout``), kept."""
    features = mtext.get_fontfeatures() if mtext is not None else None
    language = mtext.get_language() if mtext is not None else None
    key = (s, _font_key(prop, renderer.dpi), flags, threading.get_ident(),   # its fonts are this thread's
           tuple(features) if isinstance(features, list) else features,
           tuple(language) if isinstance(language, list) else language)
    items = _get("layout", key)
    if items is None:
        font = renderer._prepare_font(prop)
        laid = font._layout(s, flags=flags, features=features, language=language)
        items = _put("layout", key, tuple((it.ft_object, it.glyph_index, it.x, it.y) for it in laid))
    return items


def _draw_glyphs(renderer, gc, x, y, angle, glyphs, load_flags, mode) -> None:
    """matplotlib's ``RendererAgg._draw_text_glyphs_and_boxes`` for the glyphs, each glyph's bitmap kept by
    its fraction of a pixel (module doc)."""
    antialiased = gc.get_antialiased()
    height, dpi = renderer.height, renderer.dpi
    draw = renderer._renderer.draw_text_image
    for font, size, glyph_index, slant, extend, dx, dy in glyphs:   # dy is upwards
        m, mkey, cos, sin = _matrix(angle, slant, extend)
        px = round(0x40 * (x + dx * cos - dy * sin))
        py = round(0x40 * (height - y + dx * sin + dy * cos))   # FreeType's y is upwards
        key = (font, size, dpi, glyph_index, mkey, px & 63, py & 63, load_flags, antialiased)
        got = _get("glyph", key)
        if got is None:
            font.set_size(size, dpi)
            font._set_transform(m, [px, py])
            bitmap = font._render_glyph(glyph_index, load_flags, mode)
            buffer = bitmap.buffer
            if not antialiased:
                buffer *= 0xff
            got = _put("glyph", key, (buffer, bitmap.left - (px >> 6), bitmap.top - (py >> 6)))
        buffer, left, top = got
        # draw_text_image's y is downwards & the bitmap bottom side
        draw(buffer, left + (px >> 6), int(height) - (top + (py >> 6)) + buffer.shape[0], 0, gc)


def _make():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    renderer_class = _renderer_class()

    class TextCanvas(FigureCanvasAgg):
        """matplotlib's Agg canvas, its renderer kept text per process (module doc)."""

        def get_renderer(self):
            w, h = self.get_width_height(physical=True)
            key = w, h, self.figure.dpi
            if self._lastKey != key:
                self.renderer = renderer_class(w, h, self.figure.dpi)
                self._lastKey = key
            return self.renderer

    if _svg_supported():
        def print_svg(self, filename, *, bbox_inches_restore=None, metadata=None, **_):
            """matplotlib's ``FigureCanvasSVG.print_svg`` (the same steps), its renderer
            :func:`svg_renderer_class`'s: the SVG text written as paths, kept per process."""
            from matplotlib import cbook
            from matplotlib.backends.backend_mixed import MixedModeRenderer
            with cbook.open_file_cm(filename, "w", encoding="utf-8") as fh:
                if not cbook.file_requires_unicode(fh):
                    fh = codecs.getwriter("utf-8")(fh)
                dpi = self.figure.dpi
                self.figure.dpi = 72
                width, height = self.figure.get_size_inches()
                renderer = MixedModeRenderer(
                    self.figure, width, height, dpi,
                    svg_renderer_class()(width * 72, height * 72, fh, image_dpi=dpi, metadata=metadata,
                                         figure=self.figure),
                    bbox_inches_restore=bbox_inches_restore)
                self.figure.draw(renderer)
                renderer.finalize()
        TextCanvas.print_svg = print_svg

    return TextCanvas


def _renderer_class():
    from matplotlib.backends import backend_agg
    from matplotlib.backends.backend_agg import RendererAgg
    from matplotlib.ft2font import RenderMode

    class _Renderer(RendererAgg):
        """matplotlib's Agg renderer, whose text measures, layouts, font heights and glyph bitmaps are kept
        (module doc)."""

        def get_text_width_height_descent(self, s, prop, ismath):
            if ismath:   # mathtext (its parses are shared) or TeX: matplotlib's own
                return super().get_text_width_height_descent(s, prop, ismath)
            key = (s, _font_key(prop, self.dpi))
            got = _get("metrics", key)
            if got is None:
                got = _put("metrics", key, super().get_text_width_height_descent(s, prop, ismath))
            return got

        def _get_font_height_metrics(self, prop):
            # Text._get_layout's hook (matplotlib 3.11): the font's ascent, descent and line gap that
            # _get_layout computes itself from the font's OS/2 or hhea table where a renderer has none,
            # by the same arithmetic, at this renderer's dpi (the figure's while it measures or draws)
            key = _font_key(prop, self.dpi)
            got = _get("height", key)
            if got is None:
                got = _put("height", key, _height_metrics(prop, self.dpi))
            return got

        def draw_text(self, gc, x, y, s, prop, angle, ismath=False, mtext=None):
            if ismath:
                return super().draw_text(gc, x, y, s, prop, angle, ismath, mtext)
            items = _layout(self, s, prop, mtext, backend_agg.get_hinting_flag())
            size = prop.get_size_in_points()
            self._draw_text_glyphs_and_boxes(
                gc, x, y, angle, ((font, size, index, 0, 1, dx, dy) for font, index, dx, dy in items), [])

        def _draw_text_glyphs_and_boxes(self, gc, x, y, angle, glyphs, boxes):
            mode = RenderMode.NORMAL if gc.get_antialiased() else RenderMode.MONO
            _draw_glyphs(self, gc, x, y, angle, glyphs, backend_agg.get_hinting_flag(), mode)
            if boxes:
                super()._draw_text_glyphs_and_boxes(gc, x, y, angle, (), boxes)

    return _Renderer


def _svg_supported() -> bool:
    """matplotlib's SVG writer sets text as paths as this module expects (matplotlib 3.11's ``RendererSVG`` and
    ``TextToPath``, :data:`TESTED`): the names :func:`svg_renderer_class` follows."""
    from matplotlib.backends import backend_svg
    from matplotlib.textpath import TextToPath
    return all(hasattr(TextToPath, n) for n in ("get_glyphs_with_font", "get_text_width_height_descent",
                                                "_get_font", "_get_glyph_repr", "FONT_SCALE", "DPI")) \
        and all(hasattr(backend_svg.RendererSVG, n) for n in ("_draw_text_as_path", "_update_glyph_map_defs")) \
        and "_text2path" in backend_svg.RendererSVG._draw_text_as_path.__code__.co_names


def _text_key(s, prop) -> tuple:
    """What a plain text's glyphs at TextToPath's fixed size depend on: the string, the font chosen (the
    properties and settings, :func:`_font_key`, less the size), the hinting factor."""
    import matplotlib
    font = _font_key(prop, None)
    return s, font[:5] + font[6:], matplotlib.rcParams["text.hinting_factor"], threading.get_ident()


def _outline(path_of, glyph_repr, vertices, codes) -> str:
    """A glyph's outline as the SVG writer sets it in its ``<defs>`` (``RendererSVG._update_glyph_map_defs``:
    FreeType's units, not simplified), kept by the glyph and the very outline arrays it was set from."""
    key = (glyph_repr, id(vertices), id(codes))
    got = _get("outline", key)
    if got is None or got[0] is not vertices or got[1] is not codes:
        from matplotlib.path import Path
        got = _put("outline", key, (vertices, codes, path_of(Path(vertices * 64, codes), simplify=False)))
    return got[2]


_SVG: list = []   # the SVG renderer class, made once


# a glyph outline's transform in the SVG's defs, as matplotlib's RendererSVG writes it (its outlines are in 1/64 pt)
GLYPH_SCALE = "scale(0.015625)"


def _kept_text_to_path():
    """matplotlib's ``TextToPath`` whose plain texts' measures and glyphs are kept for the process (the text of
    :func:`svg_renderer_class`'s renderer: each a pure function of its key)."""
    from collections import OrderedDict as Ordered
    from matplotlib.textpath import TextToPath

    class _TextToPath(TextToPath):
        def get_text_width_height_descent(self, s, prop, ismath):
            if ismath:
                return super().get_text_width_height_descent(s, prop, ismath)
            key = _text_key(s, prop)
            got = _get("svg metrics", key)
            if got is None:
                font = self._get_font(prop)
                font.set_text(s, 0.0, flags=self._get_hinting_flag())
                w, h = font.get_width_height()
                got = _put("svg metrics", key, (w / 64.0, h / 64.0, font.get_descent() / 64.0))
            scale = prop.get_size_in_points() / self.FONT_SCALE
            w, h, d = got
            return w * scale, h * scale, d * scale

        def get_glyphs_with_font(self, font, s, glyph_map=None, return_new_glyphs_only=False, *, features=None,
                                 language=None):
            key = (font, s, tuple(features) if isinstance(features, list) else features,
                   tuple(language) if isinstance(language, list) else language)
            got = _get("svg glyphs", key)
            if got is None:
                glyphs, paths, _ = super().get_glyphs_with_font(font, s, features=features, language=language)
                got = _put("svg glyphs", key, (tuple(glyphs), paths))
            glyphs, paths = got
            glyph_map = Ordered() if glyph_map is None else glyph_map
            new = Ordered() if return_new_glyphs_only else glyph_map
            for glyph_repr, *_ in glyphs:
                if glyph_repr not in glyph_map:
                    new[glyph_repr] = paths[glyph_repr]
            return list(glyphs), new, []

    return _TextToPath


def svg_renderer_class():
    """matplotlib's ``RendererSVG`` whose text, written as paths, is kept for the process: a plain text's
    measure at ``TextToPath``'s fixed size (its width, height and descent, which matplotlib scales by the
    type size), its glyphs' places and outlines (``TextToPath.get_glyphs_with_font``: every size shares them,
    matplotlib sets text as paths at 100 pt and scales it), each glyph outline's path data, and the font's
    ascent, descent and line gap (``Text._get_layout``'s hook, as the Agg renderer here). Each is a pure function
    of its key (the string, the font chosen, the hinting factor, the thread), so the file is the same bytes
    (tests/test_drawspeed2.py); a mathtext's parse is shared already (:func:`velpoly.render.style.share_mathtext`)."""
    if _SVG:
        return _SVG[0]
    from matplotlib.backends.backend_svg import RendererSVG
    _TextToPath = _kept_text_to_path()

    class _SVGRenderer(RendererSVG):
        """matplotlib's SVG renderer, its text as paths kept per process (:func:`svg_renderer_class`)."""

        def __init__(self, *args, figure=None, **kw):
            super().__init__(*args, **kw)
            self._text2path = _TextToPath()
            self._figure = figure

        def _get_font_height_metrics(self, prop):
            # Text._get_layout's hook: what it computes from the font's tables at the figure's dpi (72 while
            # the SVG is written), kept as the Agg renderer's are
            dpi = self._figure.dpi
            key = _font_key(prop, dpi)
            got = _get("height", key)
            if got is None:
                got = _put("height", key, _height_metrics(prop, dpi))
            return got

        def _update_glyph_map_defs(self, glyph_map_new):
            writer = self.writer
            if glyph_map_new:
                writer.start("defs")
                for glyph_repr, (vertices, codes) in glyph_map_new.items():
                    writer.element("path", id=self._adjust_glyph_repr(glyph_repr),
                                   d=_outline(self._convert_path, glyph_repr, vertices, codes),
                                   transform=GLYPH_SCALE)
                writer.end("defs")
                self._glyph_map.update(glyph_map_new)

    _SVG.append(_SVGRenderer)
    return _SVGRenderer
