"""velpoly.frozen.quick_init: the records it speeds up are the same frozen dataclasses as before."""
import copy
import dataclasses
import inspect
import pickle

import numpy as np
import pytest

from velpoly.frozen import quick_init
from velpoly.poles import Pole, PoleLine
from velpoly.polygons import AuxiliaryPoint, ConstructionLine, KnownVector, Vector

RECORDS = (Vector, ConstructionLine, KnownVector, AuxiliaryPoint, Pole, PoleLine)


def _reference(cls):
    """The same fields as a frozen dataclass with dataclasses' own __init__."""
    return dataclasses.make_dataclass(cls.__name__, [(f.name, f.type, dataclasses.field(default=f.default))
                                                     for f in dataclasses.fields(cls)], frozen=True)


def _values(cls, rng):
    """Generated arguments for every field: arrays, floats, strings, tuples, None."""
    pick = (lambda: rng.normal(size=2), lambda: float(rng.normal()), lambda: f"s{rng.integers(99)}",
            lambda: tuple(rng.integers(9, size=rng.integers(4)).tolist()), lambda: None)
    return [pick[rng.integers(len(pick))]() for _ in dataclasses.fields(cls)]


@pytest.mark.parametrize("cls", RECORDS, ids=lambda c: c.__name__)
def test_same_signature_fields_and_behaviour(cls):
    ref = _reference(cls)
    assert list(inspect.signature(cls.__init__).parameters.items()) == \
        list(inspect.signature(ref.__init__).parameters.items())
    rng = np.random.default_rng(20)
    names = [f.name for f in dataclasses.fields(cls)]
    required = sum(f.default is dataclasses.MISSING for f in dataclasses.fields(cls))
    for _ in range(30):
        vals = _values(cls, rng)
        cut = int(rng.integers(required, len(vals) + 1))   # some defaults left out, some given by name
        args, kw = vals[:cut], {}
        if cut > required and rng.random() < 0.5:
            k = int(rng.integers(required, cut))
            args, kw = vals[:k], dict(zip(names[k:cut], vals[k:cut]))
        got, want = cls(*args, **kw), ref(*args, **kw)
        assert vars(got) == vars(want) or all(
            np.array_equal(a, b) if isinstance(a, np.ndarray) else a == b
            for a, b in zip(vars(got).values(), vars(want).values()))
        assert list(vars(got)) == names
        for f in names:
            assert getattr(got, f) is getattr(want, f)
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(got, names[0], 1)
        assert repr(got).split("(", 1)[1] == repr(want).split("(", 1)[1]
        back = pickle.loads(pickle.dumps(got))
        assert type(back) is cls and repr(back) == repr(got)
        moved = dataclasses.replace(got, **{names[0]: "x"})
        assert moved.__dict__[names[0]] == "x" and all(getattr(moved, f) is getattr(got, f) for f in names[1:])
        assert repr(copy.copy(got)) == repr(got)
    with pytest.raises(TypeError):   # a missing argument, as dataclasses' __init__ says
        cls(*vals[:required - 1])
    with pytest.raises(TypeError):
        cls(*vals, vals[0])


def test_equality_and_hash_unchanged():
    a, b = PoleLine("l", (), None, None), PoleLine("l", (), None, None, ())
    assert a == b and hash(a) == hash(b) and a != PoleLine("m", (), None, None)


def test_refuses_what_it_cannot_make_alike():
    @dataclasses.dataclass
    class Mutable:
        x: int
    with pytest.raises(TypeError):
        quick_init(Mutable)

    @dataclasses.dataclass(frozen=True)
    class Factory:
        x: list = dataclasses.field(default_factory=list)
    with pytest.raises(TypeError):
        quick_init(Factory)

    @dataclasses.dataclass(frozen=True)
    class Post:
        x: int

        def __post_init__(self):
            pass
    with pytest.raises(TypeError):
        quick_init(Post)

    @dataclasses.dataclass(frozen=True, kw_only=True)
    class KwOnly:
        x: int
    with pytest.raises(TypeError):
        quick_init(KwOnly)
