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
    """Collect twice (an object's finaliser that raises is still reported by pytest's unraisable-exception
    check, which runs after this), then freeze what is left: that check's own five full collections would
    otherwise walk every shared page and specimen again, at the end of each worker."""
    gc.collect()
    gc.collect()
    gc.freeze()
