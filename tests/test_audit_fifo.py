"""Outside check, FORMAT.md section 3: "a FIFO, a device or a terminal is written straight through, never
replaced", and "a failed command leaves no partial output". A multi-page PDF (``velpoly draw --steps -o X.pdf``,
``velpoly animate -o X.pdf``) into a FIFO is read complete by the reader, the FIFO stays a FIFO, and a writer that
fails sends the reader nothing.

Found by the audit: both multi-page PDFs into a FIFO failed (exit 2, ``cannot write steps.pdf: Illegal seek``)
after sending the reader a partial file (15 bytes of a PDF header): their writers (matplotlib's PdfPages,
the animation's page writer) tell and seek, which a FIFO cannot.
"""
from __future__ import annotations

import os
import stat
import threading

import pytest

from velpoly.fileio import atomic_path

import mechanisms
from test_fuzz import to_toml
from zoo import each


def read_fifo(fifo):
    got = []
    reader = threading.Thread(target=lambda: got.append(fifo.read_bytes()), daemon=True)
    reader.start()
    return reader, got


def finish(reader, fifo) -> None:
    """Let the reader end: a writer that never opened the FIFO (a refused or failed one) leaves it waiting."""
    reader.join(timeout=0.2)
    if reader.is_alive():
        try:
            os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        except OSError:   # no reader waiting after all
            pass
    reader.join(timeout=60)


def test_a_multi_page_pdf_into_a_fifo_is_read_whole(tmp_path):
    sp = next(s for s in each(20271127, 12) if s.kind.startswith("slider-crank"))
    f = tmp_path / "m.toml"
    f.write_text(to_toml(sp.mech))
    for k, args in enumerate([["draw", f, "--sheet", "velocity", "--steps"],
                              ["animate", f, "--step", "90", "--size", "320x180"]]):
        fifo = tmp_path / f"out{k}.pdf"
        os.mkfifo(fifo)
        reader, got = read_fifo(fifo)
        r = mechanisms.in_process([*args, "-o", fifo])
        finish(reader, fifo)
        assert r.returncode == 0, (args, r.stderr)
        assert got[0].startswith(b"%PDF-") and got[0].rstrip().endswith(b"%%EOF"), (args, got[0][:40])
        assert got[0].count(b"/Type /Page") - got[0].count(b"/Type /Pages") >= 2, args
        assert stat.S_ISFIFO(os.stat(fifo).st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.toml", "out0.pdf", "out1.pdf"]


@pytest.mark.parametrize("fail", [False, True])
def test_a_writer_that_seeks_into_a_fifo(tmp_path, fail):
    fifo = tmp_path / "x.bin"
    os.mkfifo(fifo)
    reader, got = read_fifo(fifo)
    with pytest.raises(RuntimeError) if fail else open(os.devnull):
        with atomic_path(fifo) as path:
            with open(path, "wb") as fp:   # a header written last, as a PDF's cross-reference offsets are
                fp.write(b"....body")
                fp.seek(0)
                fp.write(b"head")
            if fail:
                raise RuntimeError("the writer failed")
    finish(reader, fifo)
    assert got == [b"" if fail else b"headbody"]   # a failed writer sends nothing partial
