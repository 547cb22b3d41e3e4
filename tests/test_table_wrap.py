"""A results table's footnotes and title wrap within the table's width, measured line by line.

The wrap first guesses the characters a line holds from the text's mean letter width; a line of wider
letters than the mean (capitals, digits, a book's quantities set as mathtext) ran past the column's edge,
out of a narrow side column and off the page. Here notes and titles are generated from narrow and wide
words in a seeded order (the wide ones last, where the mean underestimates them), and every line set is
measured as matplotlib draws it.
"""
from __future__ import annotations

import numpy as np
import pytest
from matplotlib.figure import Figure

from velpoly.render import table
from velpoly.render.style import get_style, rc_context

NARROW = ("fill", "it", "till", "jilt", "lift", "I.", "tilt,", "1.1")
WIDE = ("MWMW", "WOMB", "MOW", "=400×2", "omega_5", "alpha_3", "−12.787/60", "MAXIMUM")
TITLE_WIDE = ("MWMW", "WOMB", "MOW", "=400×2", "$5", "MAXIMUM", "(W/M)")


def _text(rng, wide=WIDE) -> str:
    """A note of 10-16 narrow words, then as many ``wide`` ones."""
    n = int(rng.integers(10, 17))
    return " ".join([str(rng.choice(NARROW)) for _ in range(n)] + [str(rng.choice(wide)) for _ in range(n)])


@pytest.mark.parametrize("style", ["textbook", "slides"])
def test_footnotes_and_title_wrap_within_the_width(style):
    rng = np.random.default_rng(20261127)
    with rc_context(get_style(style)):
        fig = Figure(figsize=(11.69, 8.27), dpi=72)
        room = table._Room(fig, (0.05, 0.05, 0.3, 0.4))
        for size, width_pt in ((7.0, 130.0), (10.0, 220.0)):
            notes = [(mark, "V_B", _text(rng)) for mark in table.MARKS[:2]]
            lines = [line for ls in table._footnote_lines(room, notes, width_pt, size).values() for line in ls]
            assert len(lines) > 2 * 2
            wide = [(line, w) for line in lines
                    if (w := room.points(room.extent(0, 0, line, fontsize=size).width)) > width_pt
                    and " " in line.strip()]
            assert not wide, (size, width_pt, wide)
            title = table._Title(room, _text(rng, TITLE_WIDE), size, width_pt)   # a user's text, set literally
            assert title.lines > 1
            for line in title.text.split("\n"):
                drawn = room.points(room.extent(0, 1, line, **title.kw).width)
                assert drawn <= width_pt or " " not in line, (size, width_pt, line)
