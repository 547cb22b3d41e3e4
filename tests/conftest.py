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


def _freeze_the_survivors(phase, info):
    """After each full collection, what survived it (the modules, the shared pages, specimens and sweeps; no
    garbage: the collection just freed it) goes to the permanent generation: the next full collections walk
    only what was made since, not every shared page again. An object frozen here that a later test drops
    is freed as ever by its reference count; one in a cycle (the figure a test was drawing during that
    collection) is kept to the end, unfinalised (a test's worth of memory a full collection, a few a worker;
    the workers' peak memory measured the same)."""
    if phase == "stop" and info["generation"] == 2:
        gc.freeze()


gc.callbacks.append(_freeze_the_survivors)


def pytest_sessionfinish(session):
    """Collect twice (an object's finaliser that raises is still reported by pytest's unraisable-exception
    check, which runs after this), then freeze what is left: that check's own five full collections would
    otherwise walk every shared page and specimen again, at the end of each worker."""
    gc.collect()
    gc.collect()
    gc.freeze()
