"""Hypothesis's text for the tests: every character UTF-8 encodes, named by category.

``st.text()``'s own alphabet is ``characters(codec="utf-8")``: before its first example hypothesis works out
which of the 1.1 million code points that codec encodes, about 3 CPU s a process in a fresh checkout (CI's clean
clone; a checkout keeps the answer in .hypothesis/ after its first run). Those are all but the surrogates
(category Cs), the very interval set ``characters(exclude_categories=("Cs",))`` gives from hypothesis's own
character table in 0.3 s. test_suite_rules checks that no test asks for ``st.text()`` without an alphabet.
"""
from __future__ import annotations

from hypothesis import strategies as st

CHARS = st.characters(exclude_categories=("Cs",))


def text(**kw):
    """``st.text(**kw)`` drawn from the same characters, without the codec's cost."""
    return st.text(CHARS, **kw)
