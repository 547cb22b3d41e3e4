"""PNG files of figures: the pixels ``savefig`` draws, written in a tenth of the time.

``savefig(format="png")`` hands Pillow the RGBA buffer at zlib level 6, and Pillow tries five row
filters on every row to pick one: for an A4 sheet at 200 dpi that took 0.24 s (a quarter of drawing the
sheet). :func:`save_png` draws the same pixels (``savefig(format="rgba")``: the same dpi, face colour
and renderer) and writes the PNG itself (:func:`png_bytes`): an opaque figure as RGB (every alpha is
255: the same image, a quarter less data), every row unfiltered (a drawing on white paper is long runs of
the same bytes, which deflate finds without a filter: the file is smaller than with Pillow's adaptive
filters at the same level), zlib level :data:`LEVEL`, and the metadata matplotlib writes (``Software``,
the dpi). The six-bar's full sheet: 0.035 s and 342 KB, against matplotlib's 0.24 s and 414 KB (Pillow
at level 1 with its filters: 0.1 s, 372 KB); it decodes to the same pixels (tests/test_sheet_speedups.py).
"""
from __future__ import annotations

import io
import struct
import zlib

__all__ = ["save_png", "png_bytes"]

LEVEL = 3   # zlib level: 0.036 s for an A4 sheet at 200 dpi (1: 0.030 s, 3 % larger; 4: 0.08 s, 6 % smaller)


def save_png(fig, target, dpi: float, metadata: dict | None = None) -> None:
    """Write ``fig`` as a PNG at ``dpi`` into ``target`` (a path or a binary file object)."""
    import matplotlib
    import numpy as np
    raw = io.BytesIO()
    fig.savefig(raw, format="rgba", dpi=dpi)
    data = raw.getbuffer()
    # the Agg canvas of savefig: int(width) x int(height) pixels of the figure's box at that dpi
    w, h = int(fig.bbox_inches.width * dpi), int(fig.bbox_inches.height * dpi)
    if w * h * 4 != len(data):   # not the canvas expected: matplotlib's own writer
        fig.savefig(target, format="png", dpi=dpi, metadata=metadata)
        return
    rgba = np.frombuffer(data, np.uint8).reshape(h, w, 4)
    meta = {"Software": f"Matplotlib version{matplotlib.__version__}, https://matplotlib.org/", **(metadata or {})}
    out = png_bytes(rgba, dpi, {k: v for k, v in meta.items() if v is not None})
    if hasattr(target, "write"):
        target.write(out)
    else:
        with open(target, "wb") as f:
            f.write(out)


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(data, zlib.crc32(kind)))


def _text(key: str, value: str) -> bytes:
    """A text chunk as Pillow's ``PngInfo.add_text`` makes it: tEXt in Latin-1, else uncompressed iTXt."""
    try:
        return _chunk(b"tEXt", key.encode("latin-1") + b"\0" + value.encode("latin-1"))
    except UnicodeEncodeError:
        return _chunk(b"iTXt", key.encode("latin-1") + b"\0\0\0\0\0" + value.encode("utf-8"))


def png_bytes(rgba, dpi: float, text: dict) -> bytes:
    """The PNG file of the ``(height, width, 4)`` uint8 RGBA pixels ``rgba``: RGB where every alpha is 255,
    unfiltered rows at zlib level :data:`LEVEL`, ``dpi`` (as Pillow writes it: pixels a metre, rounded) and the
    ``text`` chunks (``{key: value}``)."""
    import numpy as np
    h, w = rgba.shape[:2]
    rgba = np.ascontiguousarray(rgba, np.uint8)
    opaque = bool((rgba.view("<u4") >= 0xFF000000).all())   # every alpha 255 (the pixels' last bytes)
    channels = 3 if opaque else 4
    rows = np.empty((h, 1 + w * channels), np.uint8)
    rows[:, 0] = 0   # filter type None on every row
    pixels = rows[:, 1:].reshape(h, w, channels)
    for c in range(channels):   # a channel at a time: 4 times faster than the pixels' 3 bytes at a time
        pixels[..., c] = rgba[..., c]
    per_metre = int(dpi / 0.0254 + 0.5)
    head = struct.pack(">IIBBBBB", w, h, 8, 2 if opaque else 6, 0, 0, 0)
    return b"".join([b"\x89PNG\r\n\x1a\n", _chunk(b"IHDR", head),
                     _chunk(b"pHYs", struct.pack(">IIB", per_metre, per_metre, 1)),
                     *(_text(k, str(v)) for k, v in text.items()),
                     _chunk(b"IDAT", zlib.compress(rows.data, LEVEL)), _chunk(b"IEND", b"")])
