import gc
import importlib
import os
import sys
from pathlib import Path

import pytest

# Headless: never open a window from the tests. Told through matplotlib's environment variable, which it reads
# when the tests first import it (in each xdist worker; subprocesses inherit it), rather than by importing it
# here: the xdist controller, which runs no test, imported matplotlib and numpy (0.7 CPU s) before it started
# the workers.
os.environ["MPLBACKEND"] = "Agg"
if "matplotlib" in sys.modules:   # imported already (by a plugin): its backend is chosen at its import
    sys.modules["matplotlib"].use("Agg")

sys.path.insert(0, os.path.dirname(__file__))

# The cyclic garbage collector took a tenth of the suite's time: the drawings make many objects, and the
# pages, specimens and sweeps that tests share stay alive, so every full collection walked them all again.
# It runs a fourteenth as often (still every 10000 new objects; the memory stays flat).
gc.set_threshold(10_000, 10, 10)


def pytest_collection(session):
    """On the second xdist worker, import the test modules about to be collected in reverse order first. Each
    worker rewrites the asserts of every test module it imports (pytest's assertion rewriting: an AST pass, 4
    CPU s for all of them here) unless the other has written the rewritten module's cache already: in a fresh
    checkout both workers collect at once, and went through the modules in the same order, each rewriting all of
    them; from both ends, each rewrites about half. A module that fails to import here is left to the
    collection, which imports it again and reports the error."""
    if os.environ.get("PYTEST_XDIST_WORKER") != "gw1" or session.config.getoption("ignore") \
            or session.config.getoption("ignore_glob"):
        return
    here = Path(__file__).parent.resolve()
    start = session.config.invocation_params.dir
    if not any((start / a.split("::")[0]).resolve() in (here, here.parent) for a in session.config.args):
        return   # only some files asked for: leave the collection's order alone
    for path in sorted(here.glob("test_*.py"), reverse=True):
        if path.stem not in sys.modules:
            try:
                importlib.import_module(path.stem)
            except (Exception, pytest.skip.Exception, pytest.fail.Exception):
                sys.modules.pop(path.stem, None)


# Files of many quick tests (none over 0.2 s on main 7d0e9a2; 3.1 s in all), collected last. xdist's loadgroup
# hands out its groups first, then the other tests one by one in the collection's order, so these are what both
# workers end on: neither stands idle while the other finishes a test of seconds dealt out just before (on
# 7d0e9a2 gw1 stood 2.4 s idle at the end, while gw0 ran test_toggle_targets' 2.7 s).
LAST = ("test_kinematics.py", "test_textbook_input.py", "test_errors.py")


def pytest_collection_modifyitems(items):
    """Move the tests of ``LAST``'s files to the end of the collection, each part in its own order."""
    items.sort(key=lambda item: item.path.name in LAST)


def pytest_collection_finish(session):
    """Collect the garbage, then freeze what the start and the collection left (the modules imported, the
    tests, their parameters: 150 000 objects, alive until the worker ends): every full collection during the
    tests walked them again (five drawing files in one process, two pairs side by side: the oldest
    generation's collections 1.88, 2.11 -> 1.53, 1.56 CPU s, this hook 0.1 s). A finaliser that raises in
    what the collection left is still reported (this collection runs it; the first test's check reports it).
    Nothing unfreezes them (test_safety's ``heap_frozen`` freezes what the tests before it left, for good;
    test_suite_rules checks that no test calls ``gc.unfreeze``)."""
    gc.collect()
    gc.freeze()


def pytest_sessionfinish(session):
    """Collect the garbage, then freeze what is left: pytest's unraisable-exception check, which runs after
    this, makes five full collections that would otherwise walk every shared page and specimen again, at the
    end of each worker. An object's finaliser that raises is still reported by that check: the full
    collection runs the finalisers of every dead object, and the young collection after it (generations 0
    and 1, where every object the finalisers made is) those of the cycles they left, as a second full
    collection did at the cost of walking the whole heap again (about a second a worker)."""
    collect_before_the_check()
    gc.freeze()


def collect_before_the_check():
    """The garbage collections pytest_sessionfinish makes before it freezes (test_suite_rules checks that a
    finaliser that raises, and one in a cycle another finaliser made, are still reported)."""
    gc.collect()
    gc.collect(1)


# -- the browser ---------------------------------------------------------------------------------------
@pytest.fixture(scope="session")
def browser():
    """One headless Chromium a test process (tests/browser.py), for the interactive page's tests (test_html,
    test_html_apart: one xdist group, so one worker starts it once)."""
    from browser import Browser, find_chromium
    exe = find_chromium()
    if not exe:
        if os.environ.get("VELPOLY_REQUIRE_BROWSER") == "1":
            pytest.fail("VELPOLY_REQUIRE_BROWSER=1 but no chromium: install Debian's chromium package")
        pytest.skip("no chromium (set VELPOLY_REQUIRE_BROWSER=1 to make this a failure)")
    b = Browser(exe, size=(1280, 900))
    yield b
    b.close()
