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


_FINALISERS = '''
import gc, sys
import conftest
seen = []
sys.unraisablehook = lambda u: seen.append(str(u.exc_value))

class Cycle:
    def __init__(self, word):
        self.me, self.word = self, word

class Raises(Cycle):
    def __del__(self):
        raise RuntimeError(self.word)

class Makes(Cycle):
    def __del__(self):
        Raises("made by a finaliser")   # a new cycle, made while the full collection runs finalisers

held = [Raises("dead long ago"), Makes("")]
gc.collect()   # both in the oldest generation, as a session's shared objects are at its end
held.clear()
conftest.collect_before_the_check()
gc.freeze()
for _ in range(5):   # pytest's unraisable-exception check: five full collections, after the freeze
    gc.collect()
print(sorted(seen))
'''


def test_the_collections_before_the_freeze_leave_no_finaliser_unreported(tmp_path):
    """tests/conftest.py freezes the heap at the end of each worker, so pytest's unraisable-exception check
    (five full collections after it) walks nothing old: every finaliser that raises must have run before the
    freeze. A cycle dead in the oldest generation and a cycle that another finaliser made during the full
    collection are both reported (one full collection and a young one; the second full collection it replaces
    walked the whole heap again, about a second a worker). In a process of its own: the freeze is for good."""
    import subprocess
    import sys
    r = subprocess.run([sys.executable, "-c", _FINALISERS], capture_output=True, text=True, timeout=60,
                       cwd=tmp_path, env={"PYTHONPATH": str(ROOT / "tests"), "PATH": "/usr/bin:/bin"})
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "['dead long ago', 'made by a finaliser']", r.stdout + r.stderr


def test_the_second_worker_imports_the_test_modules_from_the_end_and_only_for_the_whole_folder(monkeypatch):
    """conftest.pytest_collection: on xdist's gw1, with the tests folder (or the checkout) asked for, every test
    module not yet imported is imported, in reverse order of its name, before the collection; on another
    worker, alone, or with some files asked for, nothing is (the collection's own order is left)."""
    from pathlib import Path
    from types import SimpleNamespace

    import conftest
    tests = Path(conftest.__file__).parent
    imported = []
    monkeypatch.setattr(conftest.importlib, "import_module", imported.append)
    monkeypatch.setattr(conftest, "sys", SimpleNamespace(modules={"test_cli": None}))   # one imported already

    def session(*args, ignore=None):
        opts = {"ignore": ignore, "ignore_glob": None}
        return SimpleNamespace(config=SimpleNamespace(args=list(args), getoption=opts.get,
                                                      invocation_params=SimpleNamespace(dir=tests.parent)))

    want = [p.stem for p in sorted(tests.glob("test_*.py"), reverse=True) if p.stem != "test_cli"]
    assert len(want) > 50 and want[0] > want[-1]
    for worker, args, ignore, expected in [("gw1", ("tests", "velpoly"), None, want), ("gw1", (str(tests),), None, want),
                                           ("gw1", (".",), None, want), ("gw0", ("tests",), None, []),
                                           ("gw1", ("tests/test_cli.py",), None, []),
                                           ("gw1", ("tests",), ["tests/test_cli.py"], []), (None, ("tests",), None, [])]:
        if worker is None:
            monkeypatch.delenv("PYTEST_XDIST_WORKER", raising=False)
        else:
            monkeypatch.setenv("PYTEST_XDIST_WORKER", worker)
        imported.clear()
        conftest.pytest_collection(session(*args, ignore=ignore))
        assert imported == expected, (worker, args, ignore)


def test_hypothesis_text_is_drawn_from_every_character_utf_8_encodes_named_by_category():
    """No test asks hypothesis for ``st.text()`` without an alphabet (its own, ``characters(codec="utf-8")``, costs
    about 3 CPU s a process in a fresh checkout: tests/texts.py); texts.CHARS, the alphabet they use instead, is
    every code point but the surrogates, the characters UTF-8 encodes."""
    import re
    from hypothesis.strategies._internal.lazy import unwrap_strategies
    import texts
    bare = [(path.name, n) for path in sorted((ROOT / "tests").glob("*.py"))
            if path.name not in ("texts.py", "test_suite_rules.py")   # (their docstrings name it)
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
            if re.search(r"\bst\.text\((?!alphabet=)(\)|\w+=)", line)]
    assert not bare, bare
    assert unwrap_strategies(texts.CHARS).intervals.intervals == ((0, 0xD7FF), (0xE000, 0x10FFFF))
    assert all(chr(c).encode("utf-8") for c in (0, 0xD7FF, 0xE000, 0x10FFFF))


def test_conftest_chooses_the_headless_backend_without_importing_matplotlib():
    """tests/conftest.py makes matplotlib draw headless (Agg) through ``MPLBACKEND``, read at matplotlib's import,
    and imports neither matplotlib nor numpy itself: the xdist controller loads it before it starts the workers
    and runs no test (importing them there cost 0.7 CPU s before the first worker started)."""
    import subprocess
    import sys

    import matplotlib
    assert matplotlib.get_backend().lower() == "agg"   # this process's, chosen through the variable
    r = subprocess.run([sys.executable, "-c", "import os, sys, conftest; print(os.environ['MPLBACKEND'], "
                        "sorted({'matplotlib', 'numpy'} & set(sys.modules)))"], capture_output=True, text=True,
                       timeout=60, env={"PYTHONPATH": str(ROOT / "tests"), "PATH": "/usr/bin:/bin",
                                        "MPLBACKEND": "TkAgg"})
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "Agg []", r.stdout


def test_the_files_of_quick_tests_are_collected_last(request):
    """conftest.LAST names test files that exist, and their tests come after every other test collected (xdist
    hands the single tests out in that order: the workers end on quick ones together)."""
    import conftest
    names = [item.path.name for item in request.session.items]
    assert conftest.LAST and all((ROOT / "tests" / name).is_file() for name in conftest.LAST), conftest.LAST
    last = [name in conftest.LAST for name in names]
    assert last == sorted(last), "a test of another file is collected after one of conftest.LAST's"


def test_no_test_unfreezes_the_heap():
    """No test module calls ``gc.unfreeze``: conftest.py freezes what the collection left (150 000 objects) and
    test_safety's ``heap_frozen`` what the tests before it left, so that the full collections of the tests
    after them do not walk those objects again; an unfreeze puts them all back for the rest of the worker's
    run (test_safety's did until issue 19 item 7). Read as syntax: a call of ``unfreeze`` however it is
    reached (``gc.unfreeze()``, a name imported from gc, ``getattr(gc, "unfreeze")``)."""
    import ast
    calls = []
    for path in sorted((ROOT / "tests").glob("*.py")):
        text = path.read_text(encoding="utf-8")
        if "unfreeze" not in text:
            continue
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Call):
                f = node.func
                name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else None
                if name == "unfreeze" or (name == "getattr" and any(
                        isinstance(a, ast.Constant) and a.value == "unfreeze" for a in node.args)):
                    calls.append(f"{path.name}:{node.lineno}")
    assert not calls, calls
