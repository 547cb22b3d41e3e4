"""A sheet's texts set by one measure in every format: the SVG, the PNG and the PDF of a sheet are one layout.

A sheet is laid out once, before its format is chosen (:func:`velpoly.render.sheet.render`: the labels placed,
the table measured, the captions wrapped, measured at 72 dpi), and then written. The writer still lays out each
text's own lines as it draws them: matplotlib's ``Text._get_layout`` puts the lines about the text's anchor by
its alignment from the text's width, height and descent and the font's ascent, descent and line gap, asked of
the renderer drawing (``get_text_width_height_descent``, ``_get_font_height_metrics``); a text's frame (the
circle of a link number, the box of a caption) is sized from that layout, and a legend packs its entries by
it. Each writer measures otherwise: Agg with FreeType's hinted glyphs at the PNG's dpi, the SVG and PDF writers
with the unhinted outlines, so the same text drawn was up to a point or two wider in one format than in
another (a table's title 193.1 pt wide in the PNG, 197.6 pt in the SVG; a link number's circle not the same).

A sheet's figure (:func:`sheet_figure`) is drawn by every writer with its text measures replaced
(:func:`measured`): the writer's own renderer, its text measures the Agg measure at the sheet's ``text_dpi``
(the PNG's dpi of the style: what the PNG, and so the gallery and the README, has always shown), scaled to
the writer's pixels. Its texts, their
frames and its legends then stand in the SVG and the PDF where they stand in the PNG, at the same size; the
writer only draws the glyphs (tests/test_format_layout.py compares every text drawn in the three formats).
The PNG itself is drawn by Agg at that dpi, whose measure is that one already: it is drawn as before, the same
bytes. The measures are :mod:`velpoly.render.textcache`'s, kept for the process.
"""
from __future__ import annotations

from .textcache import measurer, new_canvas

__all__ = ["sheet_figure", "TextMeasure", "Measured", "measured"]

_FIGURE: list = []   # the figure class, made once (matplotlib is imported only when a sheet is drawn)


class TextMeasure:
    """The Agg measure at ``dpi`` in a writer's pixels (module doc): a text's width, height and descent are
    ``measurer(dpi)``'s times ``k``, the writer's pixels per pixel at ``dpi`` (``k = points_to_pixels(72) / dpi``:
    a vector writer's pixel is a point); a font's ascent, descent and line gap likewise. A TeX text is measured
    by the writer (``own``: its own measure)."""

    def __init__(self, writer, dpi: float, own):
        self.writer, self.dpi, self.own = writer, dpi, own

    def _scale(self) -> float:
        return self.writer.points_to_pixels(72.0) / self.dpi

    def get_text_width_height_descent(self, s, prop, ismath):
        if ismath == "TeX":
            return self.own(s, prop, ismath)
        k = self._scale()
        w, h, d = measurer(self.dpi).get_text_width_height_descent(s, prop, ismath)
        return w * k, h * k, d * k

    def _get_font_height_metrics(self, prop):
        metrics = getattr(measurer(self.dpi), "_get_font_height_metrics", None)
        got = metrics(prop) if metrics is not None else (None, None, None)
        if None in got:   # matplotlib then measures "lp" (get_text_width_height_descent above)
            return None, None, None
        k = self._scale()
        return tuple(v * k for v in got)


class Measured:
    """A renderer whose text measures are :class:`TextMeasure`'s at ``dpi``; everything else (drawing, its state,
    attributes set on it) is the renderer's: an Agg renderer at another dpi (a sheet drawn without rendering at
    72 dpi, or saved at another resolution), which its canvas keeps to measure the layout with as it is."""

    def __init__(self, renderer, dpi: float):
        measure = TextMeasure(renderer, dpi, renderer.get_text_width_height_descent)
        object.__setattr__(self, "_writer", renderer)
        object.__setattr__(self, "get_text_width_height_descent", measure.get_text_width_height_descent)
        object.__setattr__(self, "_get_font_height_metrics", measure._get_font_height_metrics)

    def __getattr__(self, name):
        return getattr(self._writer, name)

    def __setattr__(self, name, value):   # the renderer's state (matplotlib sets its rasterizing depth)
        setattr(self._writer, name, value)


def measured(renderer, dpi: float | None):
    """``renderer`` with its texts measured as at ``dpi`` (:class:`TextMeasure`): itself where it is an Agg
    renderer at ``dpi`` (its measure is that one) or ``dpi`` is None; a vector writer's (matplotlib's
    ``MixedModeRenderer``, made for the one file it writes) given the measure as its own (no proxy between
    it and the thousands of paths it draws); any other renderer through :class:`Measured`."""
    from matplotlib.backends.backend_agg import RendererAgg
    from matplotlib.backends.backend_mixed import MixedModeRenderer
    if dpi is None or (isinstance(renderer, RendererAgg) and renderer.dpi == dpi):
        return renderer
    if type(renderer) is MixedModeRenderer:
        measure = TextMeasure(renderer, dpi, renderer._renderer.get_text_width_height_descent)
        renderer.get_text_width_height_descent = measure.get_text_width_height_descent
        renderer._get_font_height_metrics = measure._get_font_height_metrics
        return renderer
    return Measured(renderer, dpi)


def _figure_class():
    if not _FIGURE:
        from matplotlib.figure import Figure

        class SheetFigure(Figure):
            """A sheet's figure: every writer draws it with its texts measured at :attr:`text_dpi`
            (:mod:`velpoly.render.typeset`)."""

            text_dpi: float | None = None

            def draw(self, renderer):
                return super().draw(measured(renderer, self.text_dpi))

        _FIGURE.append(SheetFigure)
    return _FIGURE[0]


def sheet_figure(figsize, text_dpi: float):
    """A sheet's Figure of ``figsize`` inches: 72 dpi (its layout is measured at the dpi vector output is written
    at), on velpoly's text canvas (:func:`velpoly.render.textcache.new_canvas`), its texts set by the Agg
    measure at ``text_dpi`` in every format it is written in (module doc)."""
    fig = _figure_class()(figsize=figsize, dpi=72)
    fig.text_dpi = text_dpi
    new_canvas(fig)
    return fig
