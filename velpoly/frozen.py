"""Frozen dataclasses made quickly: an ``__init__`` that fills the instance's ``__dict__`` directly.

A frozen dataclass's own ``__init__`` sets each field through ``object.__setattr__`` (its own
``__setattr__`` refuses): about 0.3 us a field here, 2-4 us for a 5- to 12-field record. The
polygons and the pole set make some 70 such records an instant (every arrow, line and pole), a
tenth of the instant's time. :func:`quick_init` gives such a class an ``__init__`` with the same
signature (the same parameters, order and defaults) that writes the fields into ``__dict__`` in
one pass: the same instance (``==``, ``repr``, ``hash``, ``dataclasses.replace``, pickling and the
refusal to set a field afterwards all as before), in a third of the time.

Only plain fields qualify: every field in ``__init__``, no ``default_factory``, no keyword-only
field, no ``__post_init__``, no ``__slots__`` (a class that has any of these is refused with a
``TypeError`` when it is defined).
"""
from __future__ import annotations

import dataclasses

__all__ = ["quick_init"]


def quick_init(cls):
    """``cls`` (a frozen dataclass) with an ``__init__`` that writes ``self.__dict__`` directly.

    >>> from dataclasses import dataclass
    >>> @quick_init
    ... @dataclass(frozen=True)
    ... class Arrow:
    ...     tail: float
    ...     head: float
    ...     label: str = ""
    >>> Arrow(0.0, 1.0), Arrow(0.0, head=2.0, label="V_B") == Arrow(0.0, 2.0, "V_B")
    (Arrow(tail=0.0, head=1.0, label=''), True)
    >>> Arrow(0.0)
    Traceback (most recent call last):
    TypeError: Arrow.__init__() missing 1 required positional argument: 'head'
    """
    params = getattr(cls, "__dataclass_params__", None)
    if params is None or not params.frozen:
        raise TypeError(f"quick_init: {cls.__name__} is not a frozen dataclass")
    if hasattr(cls, "__post_init__") or "__slots__" in cls.__dict__:
        raise TypeError(f"quick_init: {cls.__name__} has __post_init__ or __slots__")
    names, args, defaults = [], [], {}
    for f in dataclasses.fields(cls):
        if not f.init or f.kw_only or f.default_factory is not dataclasses.MISSING:
            raise TypeError(f"quick_init: field {f.name!r} of {cls.__name__} is not a plain field "
                            "(init=False, kw_only or default_factory)")
        names.append(f.name)
        if f.default is dataclasses.MISSING:
            args.append(f.name)
        else:
            defaults[f"_default_{f.name}"] = f.default
            args.append(f"{f.name}=_default_{f.name}")
    body = "\n".join(f"    _q_d[{n!r}] = {n}" for n in names) or "    pass"
    src = f"def __init__(self, {', '.join(args)}):\n    _q_d = self.__dict__\n{body}\n"
    namespace = dict(defaults)
    exec(src, namespace)   # noqa: S102 - the source is built from the field names alone
    init = namespace["__init__"]
    init.__qualname__ = f"{cls.__qualname__}.__init__"
    init.__module__ = cls.__module__
    init.__doc__ = f"{cls.__name__}({', '.join(names)}): the fields written into ``__dict__`` directly."
    init.__annotations__ = {f.name: f.type for f in dataclasses.fields(cls)} | {"return": None}
    cls.__init__ = init
    return cls
