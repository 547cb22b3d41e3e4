import gc
import os
import sys

import matplotlib

matplotlib.use("Agg")  # headless: never open a window from the tests

sys.path.insert(0, os.path.dirname(__file__))

# The cyclic garbage collector took a tenth of the suite's time: the drawings make many objects, and the
# pages, specimens and sweeps that tests share stay alive, so every full collection walked them all again.
# It runs a fourteenth as often (still every 10000 new objects; the memory stays flat).
gc.set_threshold(10_000, 10, 10)


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
