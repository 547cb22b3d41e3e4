"""velpoly: the graphical kinematics of planar mechanisms, exact and automatic.

The stable core (FORMAT.md section 4)::

    import velpoly
    m = velpoly.load("fourbar.toml")   # an immutable Mechanism (velpoly.loads(text) reads TOML text)
    s = velpoly.solve(m)               # the Solution at the reference pose
    s.to_dict()                        # the JSON of `velpoly solve --json`
    w = velpoly.sweep(m, angles)       # a driver cycle on the drawn branch

Rendering (matplotlib) lives in :mod:`velpoly.render` and is imported only
when a figure is drawn.
"""
from .errors import (ArgumentTypeError, ArgumentValueError, AssemblyError, InputError, PoseError,
                     SingularPoseError, VelpolyError)

__version__ = "0.1.0"

__all__ = ["load", "loads", "solve", "sweep", "Mechanism", "Solution", "Sweep", "VelpolyError", "InputError",
           "ArgumentTypeError", "ArgumentValueError", "PoseError", "AssemblyError", "SingularPoseError",
           "__version__"]

# The rest is imported on first use (PEP 562), so that `velpoly --help` starts without numpy.
_LAZY = {"load": "loader", "loads": "loader", "Mechanism": "model", "Solution": "solution", "solve": "solution",
         "Sweep": "sweeps", "sweep": "sweeps", "html": "html"}


def __getattr__(name):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'velpoly' has no attribute {name!r}")
    import importlib
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
