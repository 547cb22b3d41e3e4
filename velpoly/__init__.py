"""velpoly: the graphical kinematics of planar mechanisms, exact and automatic.

The stable core (FORMAT.md section 4)::

    import velpoly
    m = velpoly.load("fourbar.toml")   # an immutable Mechanism
    s = velpoly.solve(m)               # the Solution at the reference pose
    s.to_dict()                        # the JSON of `velpoly solve --json`
    w = velpoly.sweep(m, angles)       # a driver cycle on the drawn branch

Rendering (matplotlib) lives in :mod:`velpoly.render` and is imported only
when a figure is drawn.
"""
from .errors import AssemblyError, InputError, PoseError, SingularPoseError, VelpolyError
from .loader import load
from .model import Mechanism
from .solution import Solution, solve
from .sweep import Sweep, sweep
from . import poles  # noqa: F401,E402  (registers the JSON section and tables of the instant centres)
from . import polygons  # noqa: F401,E402  (registers the "graphical" JSON section and the polygon tables)

__version__ = "0.1.0"

__all__ = ["load", "solve", "sweep", "Mechanism", "Solution", "Sweep", "VelpolyError", "InputError",
           "PoseError", "AssemblyError", "SingularPoseError", "__version__"]
