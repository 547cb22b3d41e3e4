"""Outside check, ``velpoly solve --format markdown`` (and the demo's comparison in Markdown): Markdown
shows the names and notes of the file as written. Found by the audit: only ``|`` was escaped, so a link
named ``a_b_c`` set "b" in italics, ``*x*`` in bold, ``<arm>`` vanished as an HTML tag and a backquote
began code across the cells. Every Markdown special character is now escaped (tables.md_text; an
underscore within a word, omega_2, is text to CommonMark and stays): each cell, the tables' titles and the report's head lines, read
back (backslashes removed), are the text format's, and no special character is left bare.
On generated mechanisms of every kind with such link names and titles.
"""
from __future__ import annotations

import re

import velpoly
from velpoly.gallery import comparison_text
from velpoly.report import solution_report, solution_tables

import mechanisms
from zoo import zoo

NAMES = ("base_frame", "*crank*", "`cam`", "<arm>", "[bar](x)", "#rod", "a\\b", "c_d_e", "f*g", "h<i")
BARE = re.compile(r"(?<!\\)([`*\[\]<>#]|(?<![^\W_])_|_(?![^\W_]))")   # an underscore within a word is text
CELL = re.compile(r"(?<!\\)\|")


def read_back(text: str) -> str:
    return re.sub(r"\\([\\`*_\[\]<>|#])", r"\1", text)


def test_markdown_shows_names_and_titles_as_written():
    for sp in zoo(20261125, 8):
        mech = mechanisms.rename_links(sp.mech, NAMES)
        mech["title"] = "A *generated* mechanism_with <odd> [names] `" + sp.kind + "`"
        sol = velpoly.solve(velpoly.load(mech))
        text = solution_report(sol, "markdown")
        lines = text.splitlines()
        assert read_back(lines[0]) == mech["title"] and not BARE.search(lines[0]), lines[0]
        tables = solution_tables(sol)
        rows = [ln for ln in lines if ln.startswith("| ")]
        want = [cells for t in tables for cells in [t.header, *t.rows]]
        assert len(rows) == len(want), sp.kind
        for line, cells in zip(rows, want):
            got = [c.strip() for c in CELL.split(line)[1:-1]]
            assert len(got) == len(cells), (sp.kind, line)
            for g, c in zip(got, cells):
                assert read_back(g) == str(c).strip() and not BARE.search(g), (sp.kind, g, c)
        titles = [ln for ln in lines if ln.startswith("**")]
        assert [read_back(t[2:-2]) for t in titles] == [t.title for t in tables]
        head = comparison_text(sol, "markdown").splitlines()[0]
        assert head.startswith("# ") and read_back(head[2:]) == mech["title"] and not BARE.search(head[2:]), head
