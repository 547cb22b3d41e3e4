import os
import sys

import matplotlib

matplotlib.use("Agg")  # headless: never open a window from the tests

sys.path.insert(0, os.path.dirname(__file__))
