"""A forked process (the gallery's workers) opens its fonts anew: it keeps no font of its parent's open.

matplotlib reads a font file through a file offset that a forked process shares with its parent and its
siblings; two workers reading glyphs of one inherited font read at each other's offsets ("FT_Load_Glyph
failed: invalid outline / too many hints", seen in 1 gallery build of 3 from a process that had drawn
before). matplotlib clears its font cache in a forked child; the mathtext parses velpoly shares across
figures (velpoly.render.style.share_mathtext) name the fonts they were laid out in and are cleared too.
"""
from __future__ import annotations

import gc
import os
import sys

import pytest

import velpoly
from paths import example

pytestmark = pytest.mark.skipif(not hasattr(os, "fork") or not os.path.isdir("/proc/self/fd"),
                                reason="needs fork and /proc")


def open_fonts() -> list[str]:
    """The font files this process has open."""
    out = []
    for fd in os.listdir("/proc/self/fd"):
        try:
            target = os.readlink(f"/proc/self/fd/{fd}")
        except OSError:
            continue
        if target.endswith((".ttf", ".otf", ".pfb", ".afm")):
            out.append(target)
    return out


def test_a_forked_process_keeps_no_font_of_its_parent_open(tmp_path):
    from velpoly.render import draw_to_file
    sol = velpoly.solve(velpoly.load(example("ex3_6_fourbar")))
    for out in ("a.png", "a.svg"):   # mathtext parsed for the raster and the vector output
        # the velocity sheet: the same five font files open as after the full sheet (DejaVu Sans and its
        # oblique, STIX General and its italic, LastResort), in two thirds of the CPU
        draw_to_file(sol, tmp_path / out, "velocity")
    assert open_fonts(), "the parent has drawn: its fonts are open"
    pid = os.fork()
    if pid == 0:   # the child: its answer is its exit status (no pytest machinery here)
        try:
            gc.collect()
            os._exit(min(len(open_fonts()), 100))
        finally:
            os._exit(101)
    _, status = os.waitpid(pid, 0)
    assert os.WEXITSTATUS(status) == 0, f"{os.WEXITSTATUS(status)} of the parent's font files open in the child"
    # that a child forked after its parent drew draws the same bytes as the parent is test_gallery's
    # test_the_gallery_drawn_in_worker_processes_is_the_one_drawn_in_one (its one-process build draws first,
    # in the test's process; its pool's workers, forked from it, then draw every figure again)
