"""Outside check, FORMAT.md section 3: a wrong input is exit 2 with one line naming the file, whatever it is. A
"file" without end (``/dev/zero``, ``/dev/urandom``, ``/dev/full``) or a huge one is refused after reading a
bounded amount (velpoly.loader.source.MAX_BYTES), with one line, in a moment.

Found by the audit: ``velpoly solve /dev/zero`` (or ``/dev/full``) read on without end, growing until the system
killed it (exit 137 after filling the memory of the machine).
"""
from __future__ import annotations

import pytest

import velpoly
from velpoly.loader.source import MAX_BYTES

import mechanisms
from test_fuzz import to_toml


@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom", "/dev/full"])
def test_an_endless_input_is_refused(device):
    r = mechanisms.in_process(["solve", device])
    assert r.returncode == 2 and r.stderr.splitlines()[0] == f"error: {device}: larger than 16 MB: not a mechanism " \
                                                              f"file", r.stderr
    with pytest.raises(velpoly.InputError, match="larger than"):
        velpoly.load(device)


def test_a_huge_file_is_refused_and_one_just_below_the_bound_is_read(tmp_path):
    text = to_toml(mechanisms.fourbar())
    small = tmp_path / "padded.toml"   # a mechanism file padded with a comment to the bound: still read
    small.write_text(text + "#" * (MAX_BYTES - len(text.encode()) - 1) + "\n")
    assert velpoly.load(small).driver.link == "2"
    big = tmp_path / "big.toml"
    big.write_text(text + "#" * (MAX_BYTES - len(text.encode())) + "\n")
    with pytest.raises(velpoly.InputError, match="larger than 16 MB"):
        velpoly.load(big)


def test_newlines_are_read_as_before(tmp_path):
    text = to_toml(mechanisms.fourbar())
    for newline in ("\r\n", "\r"):   # Windows' and old Macs' line ends, read as text mode reads them
        f = tmp_path / "m.toml"
        f.write_bytes(("\ufeff" + text.replace("\n", newline)).encode())
        assert velpoly.load(f).points == velpoly.loads(text).points
