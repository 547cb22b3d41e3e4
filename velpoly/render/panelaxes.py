"""A sheet panel's axes: matplotlib's Axes whose ticks are made only when something asks for them.

matplotlib's Axes makes, while it is created, the first major and the first minor tick of each axis (each
tick two lines, a grid line and two texts): ``Axes.clear`` sets the axes' clip path and grid on each axis,
and ``Axis.set_clip_path`` and ``Axis.set_tick_params`` apply them to every tick, which reading the lazy
tick lists makes. That is about half of the 6-7 ms an axes costs here (docs/performance.md), and a sheet's
panels and table (4-6 axes a sheet) turn their axis off and never draw or read a tick.

:class:`PanelAxes` is that Axes whose x and y axes (:class:`_LazyTicks`) apply a clip path and tick settings
to the ticks made so far only, keeping the settings (``Axis._major_tick_kw``, as matplotlib keeps them for
every later tick) and the clip path; a tick made later, when the axis is drawn or its ticks read, is made
from those settings and clipped by that path: the state matplotlib's ``Axis.reset_ticks`` gives (a fresh
tick from the settings, the axes' clip path set). A panel that draws no axis draws the same bytes
(benchmarks/golden.sh; tests/test_panel_axes.py draws an axis both ways).
"""
from __future__ import annotations

import contextlib

from matplotlib import axis as maxis
from matplotlib.axes import Axes

__all__ = ["PanelAxes"]

_LISTS = ("majorTicks", "minorTicks")


@contextlib.contextmanager
def _made_so_far(axis):
    """Within: ``axis``'s tick lists not made yet read as empty (no tick made to be set); after, lazy again."""
    absent = [name for name in _LISTS if name not in vars(axis)]
    for name in absent:
        vars(axis)[name] = []
    try:
        yield
    finally:
        for name in absent:
            if vars(axis).get(name) == []:
                del vars(axis)[name]


class _LazyTicks:
    """An Axis (mixed in before XAxis or YAxis) whose clip path and tick settings reach the ticks made so far,
    and a tick made later through them (module doc)."""

    def set_clip_path(self, path, transform=None):
        with _made_so_far(self):
            super().set_clip_path(path, transform)
        self._tick_clip = (path, transform)

    def set_tick_params(self, which="major", reset=False, **kwargs):
        with _made_so_far(self):
            super().set_tick_params(which, reset, **kwargs)

    def _get_tick(self, major):
        tick = super()._get_tick(major)
        clip = vars(self).get("_tick_clip")
        if clip is not None:
            tick.set_clip_path(*clip)
        return tick


class _XAxis(_LazyTicks, maxis.XAxis):
    pass


class _YAxis(_LazyTicks, maxis.YAxis):
    pass


class PanelAxes(Axes):
    """matplotlib's Axes whose axes make their ticks when first asked for (module doc)."""

    def _init_axis(self):
        super()._init_axis()
        self.xaxis.__class__, self.yaxis.__class__ = _XAxis, _YAxis
