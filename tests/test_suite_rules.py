"""The suite's own settings (issue 19 item 7): velpoly's doctests are collected and run.

pyproject's pytest settings collect ``velpoly/`` beside ``tests/`` with ``--doctest-modules``; every module
whose docstrings hold an example (``>>>``) gives doctest items. (A gallery file that stops loading fails,
never skips: every test over the gallery files loads each file itself, test_render_gallery's page tests and
test_poles' gallery test included; docs/internals.md, "Tests: keeping the suite fast".)
"""
from __future__ import annotations

import doctest
import importlib
import tomllib

from paths import ROOT


def _modules_with_examples() -> set[str]:
    """The velpoly modules whose source has a ``>>>`` line."""
    out = set()
    for path in sorted((ROOT / "velpoly").rglob("*.py")):
        if any(line.lstrip().startswith(">>> ") for line in path.read_text(encoding="utf-8").splitlines()):
            rel = path.relative_to(ROOT).with_suffix("")
            out.add(".".join(rel.parts[:-1] if rel.name == "__init__" else rel.parts))
    return out


def test_doctests_are_collected(request):
    """The settings collect velpoly's doctests; every ``>>>`` in velpoly is in a docstring doctest finds (not in a
    comment or a string it never reads); where this run collected velpoly, each such module has its items."""
    opts = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["pytest"]["ini_options"]
    assert "--doctest-modules" in opts["addopts"].split() and "velpoly" in opts["testpaths"], opts
    modules = _modules_with_examples()
    assert len(modules) >= 5, modules
    finder = doctest.DocTestFinder()
    for name in modules:
        found = [t for t in finder.find(importlib.import_module(name)) if t.examples]
        assert found, f"{name}: a '>>>' line that no doctest runs"
    collected = {item.dtest.globs["__name__"] for item in request.session.items if type(item).__name__ == "DoctestItem"}
    if collected or any(str(a).rstrip("/").endswith("velpoly") for a in request.config.args):
        assert modules <= collected, modules - collected
