"""Outside check, FORMAT.md section 3: a write error is exit 2 ``cannot write OUT: REASON``, also for standard
output. Every command's standard output, the help and ``--version`` included, refused by a full disk: exit 2,
``error: ... cannot write standard output: No space left on device`` and its hint on standard error, no traceback.

Found by the audit: ``velpoly --help > /dev/full``, ``velpoly COMMAND --help``, ``velpoly --version`` exited 0
(argparse swallows the write error), and ``velpoly > /dev/full`` (no command: the help, exit 2) said nothing.
"""
from __future__ import annotations

import contextlib
import errno
import io

import pytest

from velpoly.cli import build_parser, main

from test_fuzz import to_toml
from zoo import each


class Full(io.StringIO):
    """Standard output on a full disk: every write and flush fails as ``/dev/full``'s do."""

    def write(self, text):
        raise OSError(errno.ENOSPC, "No space left on device")

    def flush(self):
        raise OSError(errno.ENOSPC, "No space left on device")


def run_full(args):
    err = io.StringIO()
    with contextlib.redirect_stdout(Full()), contextlib.redirect_stderr(err):
        rc = main([str(a) for a in args])
    return rc, err.getvalue()


def commands():
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    return sorted(sub.choices)


def test_every_command_s_standard_output_on_a_full_disk_is_exit_2(tmp_path):
    runs = [["--help"], ["--version"], []] + [[c, "--help"] for c in commands()]
    runs += [["examples"], ["examples", "crank_slider"]]
    for k, sp in enumerate(each(20271127, 4)):   # generated mechanisms: their tables and JSON
        f = tmp_path / f"m{k}.toml"
        f.write_text(to_toml(sp.mech))
        runs += [["solve", f], ["solve", f, "--json"], ["solve", f, "--format", "csv"]]
    for args in runs:
        rc, err = run_full(args)
        lines = err.splitlines()
        assert rc == 2 and len(lines) == 2, (args, rc, err)
        assert lines[0].startswith("error: ") and lines[0].endswith("cannot write standard output: No space left "
                                                                    "on device"), (args, err)
        assert lines[1].startswith("hint: "), (args, err)


@pytest.mark.parametrize("args", [["--help"], ["solve", "--help"], ["--version"]])
def test_help_to_a_reader_that_went_away_is_exit_0(args):
    class Gone(Full):
        def write(self, text):
            raise BrokenPipeError(errno.EPIPE, "Broken pipe")

        def flush(self):
            raise BrokenPipeError(errno.EPIPE, "Broken pipe")
    err = io.StringIO()
    with contextlib.redirect_stdout(Gone()), contextlib.redirect_stderr(err):
        assert main(args) == 0
    assert err.getvalue() == ""
