"""Outside check, ``velpoly solve --format latex``: LaTeX that typesets what the text report says, whatever the
names. Every cell, header, title and the report's head lines are text: TeX's special characters escaped, the
angle and degree signs as math, one ``&`` between columns.

Found by the audit: every vector cell came out as ``12.5 $\\angle$ 30.000$\\^{}\\circ$`` (the degree sign's ``^``
escaped again after it was made math: ``\\^`` is invalid in math mode, so no report with a velocity compiled);
a name with ``$``, ``{``, ``}`` or ``~`` (a link "$c$", a point "D$") went into the table raw (an unbalanced
``$``), the head lines ("rad/s^2", "cr_ank") were not escaped at all, and the tables' titles were left out.
"""
from __future__ import annotations

import re

import velpoly
from velpoly.report import solution_report, solution_tables

from mechanisms import rename_links
from zoo import each

NAMES = ("f$r", "c_1", "{r}", "a&b", "50%", "#3", "t~", "k^2", "<b>", "|p|", "x\\y", "é")
GOOD = re.compile(r"\\textbackslash\{\}|\\textasciitilde\{\}|\\textbar\{\}|\\textless\{\}|\\textgreater\{\}|"
                  r"\\\^\{\}|\\[&%$#_{}]|\$\\angle\$|\$\^\\circ\$|\\par$|^\\noindent\\textbf\{|^\\begin\{tabular\}\{l+\}$|"
                  r"^\\hline$|^\\end\{tabular\}$| & | \\\\$")


def test_the_latex_report_is_text_typeset_as_written():
    checked = 0
    for sp in each(20271127, 8):
        d = rename_links(sp.mech, NAMES)
        d["title"] = "A $2 {x} rig_1 at 50% & #4 ~ ^ \\"
        sol = velpoly.solve(velpoly.load(d))
        tex = solution_report(sol, "latex")
        assert len(re.findall(r"\\noindent\\textbf\{", tex)) == len(solution_tables(sol))   # every table's title
        columns = None
        for line in tex.splitlines():
            if line.startswith(r"\begin{tabular}"):
                columns = len(line) - len(r"\begin{tabular}{}")
            elif line.endswith(r" \\"):   # a row: one & between columns
                assert line.count(" & ") == columns - 1, line
            bare = GOOD.sub("", line).replace("}", "", 1 if line.startswith(r"\noindent") else 0)
            assert not set(bare) & set("\\$&%#_{}~^|<>"), (sp.kind, line, bare)
            checked += 1
        assert r"$\angle$" in tex and r"$^\circ$" in tex and r"f\$r" in tex
    assert checked > 200
