"""The two looks of every figure: ``textbook`` and ``slides``.

``textbook``: black on white, serif type (STIX, like Times), hatched ground,
thin lines, velocity images shaded in greys; an A4 landscape page.
``slides``: colour, large sans-serif type, thicker lines, a 16:9 page.

A :class:`Style` holds every size in points (1/72 inch) or centimetres of
paper, so that figures keep their proportions at any scale of the mechanism.
"""
from __future__ import annotations

import contextlib
import os
import re
from dataclasses import dataclass

from ..errors import InputError

__all__ = ["Style", "STYLES", "get_style", "rc_context", "link_colour", "link_fill", "KIND_LABELS", "share_mathtext",
           "preload"]

# Line styles of the polygons' vectors: each kind recognisable in black and white.
KIND_LABELS = {
    "absolute": "absolute",
    "relative": "relative",
    "normal": "normal component $A^n$",
    "tangential": "tangential component $A^t$",
    "coriolis": r"Coriolis $2\,\omega \times V$",
    "slip": "slip along the path",
}


@dataclass(frozen=True)
class Style:
    """Sizes (pt unless said), fonts and colours of one look."""

    name: str
    figsize: tuple[float, float]          # inches
    font_family: str
    mathtext: str                         # rcParams['mathtext.fontset']
    font_size: float                      # point labels, captions
    small_size: float                     # construction reasons, scale bars, table
    title_size: float
    ink: str                              # lines and text
    paper: str                            # background, link bodies
    link_lw: float                        # outlines of links
    thin_lw: float                        # construction lines, hatching
    arrow_lw: float                       # polygon vectors
    head_length: float                    # arrowheads (pt)
    bar_width: float                      # links as bars (cm of paper)
    pin_radius: float                     # open pin circles (cm)
    block: tuple[float, float]            # slider block length, height (cm)
    palette: tuple[str, ...]              # link colours in file order (frame excluded)
    coloured: bool                        # fill link bodies with their colour
    image_alpha: float                    # shading of velocity/acceleration images
    kind_styles: dict                     # vector kind -> (linestyle, colour or None for ink, lw factor)
    dpi: int                              # PNG resolution


_TEXTBOOK_KINDS = {
    "absolute": ("-", None, 1.3),
    "relative": ("-", None, 0.9),
    "normal": ((0, (5, 2)), None, 0.9),
    "tangential": ((0, (1.2, 1.6)), None, 1.1),
    "coriolis": ((0, (6, 2, 1.2, 2)), None, 0.9),
    "slip": ((0, (9, 3)), None, 0.9),
}
_SLIDES_KINDS = {
    "absolute": ("-", "#222222", 1.3),
    "relative": ("-", "#1f5fbf", 1.0),
    "normal": ((0, (5, 2)), "#c0392b", 1.0),
    "tangential": ((0, (1.2, 1.6)), "#27864a", 1.2),
    "coriolis": ((0, (6, 2, 1.2, 2)), "#8e44ad", 1.0),
    "slip": ((0, (9, 3)), "#d35400", 1.0),
}

STYLES = {
    "textbook": Style(
        name="textbook", figsize=(11.69, 8.27), font_family="STIXGeneral", mathtext="stix",
        font_size=10.0, small_size=7.5, title_size=13.0, ink="black", paper="white",
        link_lw=0.9, thin_lw=0.45, arrow_lw=0.9, head_length=6.0, bar_width=0.26, pin_radius=0.11,
        block=(0.95, 0.55), palette=("0.55", "0.70", "0.45", "0.80", "0.62", "0.38", "0.75", "0.50"),
        coloured=False, image_alpha=0.35, kind_styles=_TEXTBOOK_KINDS, dpi=200),
    "slides": Style(
        name="slides", figsize=(13.333, 7.5), font_family="DejaVu Sans", mathtext="dejavusans",
        font_size=15.0, small_size=11.0, title_size=20.0, ink="#222222", paper="white",
        link_lw=1.6, thin_lw=0.8, arrow_lw=1.8, head_length=10.0, bar_width=0.36, pin_radius=0.15,
        block=(1.2, 0.7), palette=("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                                   "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"),
        coloured=True, image_alpha=0.3, kind_styles=_SLIDES_KINDS, dpi=120),
}


def get_style(style) -> Style:
    """The :class:`Style` named ``style`` (or ``style`` itself if it is one)."""
    if isinstance(style, Style):
        return style
    try:
        return STYLES[style]
    except (KeyError, TypeError):
        raise InputError(f"unknown style {style!r}; valid styles: " + ", ".join(STYLES), where="--style") from None


def link_colour(m, options, style: Style, link: str) -> str:
    """The colour of ``link``: ``[drawing] link_colours``, else the style's palette in file order."""
    if link in options.link_colours:
        return options.link_colours[link]
    moving = [k.name for k in m.links if not k.frame]
    i = moving.index(link) if link in moving else 0
    return style.palette[i % len(style.palette)]


def link_fill(m, options, style: Style, link: str):
    """The fill of a link's body: white in the textbook style, a light tint of its colour on slides."""
    if not style.coloured and link not in options.link_colours:
        return style.paper
    from matplotlib.colors import to_rgb
    r, g, b = to_rgb(link_colour(m, options, style, link))
    return (1 - 0.28 * (1 - r), 1 - 0.28 * (1 - g), 1 - 0.28 * (1 - b))


@contextlib.contextmanager
def rc_context(style: Style):
    """matplotlib settings of the style, and those that make the output reproducible (and the mathtext
    parses shared by every figure: :func:`share_mathtext`)."""
    import matplotlib
    share_mathtext()
    rc = {
        "font.family": [style.font_family, "DejaVu Sans"],
        "mathtext.fontset": style.mathtext,
        "font.size": style.font_size,
        "axes.unicode_minus": True,
        "svg.hashsalt": "velpoly",
        "svg.fonttype": "path",
        "pdf.fonttype": 42,
        "path.simplify": False,
        "hatch.linewidth": style.thin_lw,
        "hatch.color": style.ink,
        "text.color": style.ink,
        "legend.frameon": False,
    }
    with matplotlib.rc_context(rc):
        yield


MATHTEXT_SHARED = 2048   # mathtext parses kept for every figure of the process (matplotlib keeps 50 a renderer)


def share_mathtext() -> bool:
    """Let every figure of the process share the mathtext it has parsed (once; True where it is so).

    matplotlib caches a parse (a label such as ``$V_{B}$`` laid out at a dpi in a font) per parser, and
    every renderer has its own parser: a sheet's texts are parsed again for every figure, even the same
    sheet drawn twice, at 10-15 ms a parse, a fifth of a gallery's drawing. The cache here is keyed by what
    the parse depends on: the parser's output type, the text, the dpi, the font, antialiasing, the glyph
    loading flags, and the ``mathtext.*`` and hinting settings in force; a parse found is the very
    result matplotlib's own cache would hand back (the same object, read only by the renderers). Where
    matplotlib's parser is not as expected (another version), nothing is changed.
    """
    import matplotlib
    from matplotlib.mathtext import MathTextParser
    cached = MathTextParser.__dict__.get("_parse_cached")
    if getattr(cached, "_velpoly_shared", False):
        return True
    if cached is None or not callable(cached) or not hasattr(cached, "cache_info"):
        return False
    import collections
    import functools

    from .textcache import rc_reader
    store: collections.OrderedDict = collections.OrderedDict()
    keys = sorted(k for k in matplotlib.rcParams if k.startswith("mathtext.")) + ["text.hinting_factor"]

    @functools.wraps(cached)
    def parse(self, s, dpi, prop, antialiased, load_glyph_flags):
        settings = tuple(map(str, map(rc_reader(), keys)))
        key = (self._output_type, s, dpi, prop, antialiased, load_glyph_flags, settings)
        got = store.get(key)
        if got is None:
            with _unmemoised(s):
                got = store[key] = cached(self, s, dpi, prop, antialiased, load_glyph_flags)
            if len(store) > MATHTEXT_SHARED:
                store.popitem(last=False)
        else:
            store.move_to_end(key)
        return got

    parse._velpoly_shared = True
    parse.cache_info = cached.cache_info
    MathTextParser._parse_cached = parse
    if hasattr(os, "register_at_fork"):
        # a parse names the fonts it was laid out in, and a font reads its file through an offset that a
        # forked process shares with its parent and siblings: a forked process (the gallery's workers) that
        # used them would read glyphs at another's offset ("invalid outline", "too many hints"). It parses
        # anew, as matplotlib opens its fonts anew there (font_manager clears its font cache the same way)
        os.register_at_fork(after_in_child=store.clear)
        os.register_at_fork(after_in_child=cached.cache_clear)   # matplotlib's own, which ours fills too
    return True


_ATOM = r"(?:[^{}\\]|\\(?:(?:omega|alpha|theta|times|mathrm)(?![A-Za-z])|[,;:! ]))"   # a character, or a command
# that a velpoly label uses (a symbol, a space)
_SHALLOW = re.compile(rf"(?:{_ATOM}|\{{(?:{_ATOM}|\{{{_ATOM}*\}})*\}})*")   # (braces at most two deep)


@contextlib.contextmanager
def _unmemoised(s: str):
    """Parse ``s`` without pyparsing's packrat memo where it is shallow (:data:`_SHALLOW`: braces at most two deep,
    no command but the symbols and spaces velpoly's labels use): matplotlib turns the memo on for its mathtext
    grammar, where it keeps nested groups (``{{{{x}}}}``, ``\\frac`` in ``\\frac``) from being parsed again and
    again, but on a label such as ``$V_{B_{3}}$`` its bookkeeping costs more than it saves (pyparsing 3.3: a
    third of the parse). A memo gives what parsing again gives: the same parse (tests/test_sheet_speedups.py
    compares both on generated texts). Where pyparsing is not as expected, or ``s`` is not shallow, nothing
    changes."""
    from pyparsing import ParserElement
    memo, plain = ParserElement.__dict__.get("_parse"), getattr(ParserElement, "_parseNoCache", None)
    if memo is None or plain is None or memo is plain or not _SHALLOW.fullmatch(s):
        yield
        return
    ParserElement._parse = plain
    try:
        yield
    finally:
        ParserElement._parse = memo


def preload() -> None:
    """Load what a process's first drawing loads: matplotlib's figure, Agg canvas and font list, the
    mathtext grammar (0.5-0.7 s of CPU), velpoly's loader, solver and sheet modules, and Pillow's image
    plugins (which its first PNG loads). The gallery calls it before it forks its workers, so that they
    share it rather than each loading it."""
    import importlib
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: F401
    from matplotlib.figure import Figure  # noqa: F401
    from matplotlib.mathtext import MathTextParser
    MathTextParser("agg").parse("$x_{1}$")
    for name in ("velpoly.loader", "velpoly.solution", "velpoly.polygons", "velpoly.poles", "velpoly.render.sheet",
                 "velpoly.render.detail", "velpoly.render.pngfile", "numpy.random"):
        importlib.import_module(name)
    from PIL import Image
    Image.preinit()
    from .textcache import canvas_class
    canvas_class()
