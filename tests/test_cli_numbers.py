"""Numbers on the command line are plain decimal numbers, as FORMAT.md writes them.

Python's ``float`` also reads ``1_0`` (as 10), `` 1`` and ``1\u00a0`` (spaces around), and non-ASCII digits
(``\u0661``, ``\uff11``): every numeric option (``--angle``, ``--step``, ``--fps``, ``--size``) refuses them with
exit 2 and one error line naming the option, and writes nothing. Generated spellings: seeded plain numbers,
each spoiled one way.
"""
from __future__ import annotations

import numpy as np
import pytest

from mechanisms import in_process
from paths import example

OPTIONS = (("solve", "--angle", ()), ("draw", "--angle", ("-o", "OUT.svg")), ("sweep", "--step", ("-o", "OUT.svg")),
           ("animate", "--step", ("-o", "OUT.gif")), ("html", "--step", ("-o", "OUT.html")),
           ("animate", "--fps", ("-o", "OUT.gif")))


def spoiled(seed: int, count: int = 6) -> list[str]:
    """Plain numbers (``12``, ``-3.25``, ``1e2``) spoiled one way each: an underscore between digits, a space or
    tab or no-break space before or after, a digit written in Arabic-Indic, fullwidth or Devanagari."""
    rng = np.random.default_rng(seed)
    out = []
    for k in range(count):
        digits = str(int(rng.integers(10, 999)))
        way = k % 4
        if way == 0:
            at = int(rng.integers(1, len(digits)))
            out.append(digits[:at] + "_" + digits[at:])
        elif way == 1:
            out.append(" " + digits if rng.random() < 0.5 else "\t" + digits)
        elif way == 2:
            out.append(digits + str(rng.choice([" ", "\u00a0", "\n"])))
        else:
            base = int(rng.choice([0x0660, 0xFF10, 0x0966]))
            out.append("".join(chr(base + int(c)) for c in digits))
    return out


@pytest.mark.parametrize("command, option, extra", OPTIONS, ids=[f"{c} {o}" for c, o, _ in OPTIONS])
def test_numeric_options_refuse_spellings_that_are_no_plain_number(command, option, extra, tmp_path, capsys):
    from velpoly.cli import main
    f = example("ex3_4_slotted_lever")
    extra = tuple(str(tmp_path / a) if a.startswith("OUT") else a for a in extra)
    for text in spoiled(len(command) + len(option)):
        with pytest.raises(SystemExit) as e:   # argparse's own error: usage, then one line
            main([command, str(f), *extra, option, text])
        err = capsys.readouterr().err
        lines = [ln for ln in err.splitlines() if "error" in ln]
        assert e.value.code == 2 and len(lines) == 1, (option, text, err)
        assert lines[0] == f"velpoly {command}: error: argument {option}: expected " \
                           f"{'a number of frames a second' if option == '--fps' else 'a number of degrees'} " \
                           f"(plain decimal digits, as 30 or -2.5), got {text!r}", lines[0]
        assert not any(tmp_path.iterdir()), (option, text)


@pytest.mark.parametrize("text", ["inf", "-inf", "nan"])
def test_an_infinity_or_nan_typed_as_one_is_refused_naming_the_option(text, tmp_path):
    for command, option, extra in OPTIONS[:3]:
        extra = tuple(str(tmp_path / a) if a.startswith("OUT") else a for a in extra)
        r = in_process([command, example("ex3_4_slotted_lever"), *extra, option + "=" + text])
        assert r.returncode == 2 and option in r.stderr and "Traceback" not in r.stderr, (option, text, r.stderr)
        assert not any(tmp_path.iterdir())


def test_size_is_plain_digits():
    from velpoly.errors import InputError
    from velpoly.render.animate import parse_size
    assert parse_size("1280x720") == (1280, 720)
    for text in ("1_280x720", " 1280x720", "1280x720 ", "1280 x 720", "\u0661\u0662\u0668\u0660x720"):
        with pytest.raises(InputError, match="WIDTHxHEIGHT"):
            parse_size(text)
