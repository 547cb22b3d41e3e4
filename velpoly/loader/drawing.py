"""The ``[drawing]`` table: presentation options, checked on load by the rules ``draw`` applies."""
from __future__ import annotations

import copy

from ..errors import InputError
from ..model import Mechanism
from .context import Ctx, table

__all__ = ["read_drawing", "check_drawing"]


def read_drawing(ctx: Ctx, data: dict) -> dict:
    """The table as given (a copy: not shared with a caller's dict)."""
    return copy.deepcopy(table(ctx, data, "drawing", required=False))


def check_drawing(ctx: Ctx, m: Mechanism) -> None:
    """The [drawing] table checked on load, by the rules ``draw`` applies (velpoly.render.options, which
    imports matplotlib only to check a colour): a file ``solve`` accepts, ``draw`` accepts too."""
    if not m.drawing:
        return
    from ..render.options import drawing_options
    try:
        drawing_options(m)
    except InputError as e:
        raise ctx.err(e.where, e.what, e.hint) from None
