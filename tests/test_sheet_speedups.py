"""The cheaper computations of a sheet (issue 20, seventh session) give what the ones they replace gave.

* velpoly.render.pngfile writes the PNG itself (unfiltered rows, zlib): the file decodes to the pixels it
  was given and carries the dpi and text Pillow's writer gives, on generated images (opaque and not,
  odd sizes, noise and drawings) and metadata (Latin-1 and not).
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
