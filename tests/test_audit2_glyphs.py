"""Outside check, a figure of a file whose names or title hold a character the fonts lack (FORMAT.md section 3:
"Warnings ... are lines ``warning: FILE: ...``"; names are any strings). Found by the audit: matplotlib's
UserWarning "Glyph 128640 (\\N{ROCKET}) missing from font(s) DejaVu Sans." came with its source line
(``got = _put("metrics", ...)``), once for every text drawn with it: a title with an emoji printed 24 lines of
library internals on stderr. Now one line per character: ``warning: FILE: the fonts have no glyph for '🚀'
(U+1F680): it is drawn as a box``. On a generated mechanism with such a title and link name
(a CJK character: test_fuzz.to_toml writes an emoji as surrogate escapes, which TOML refuses).
"""
from __future__ import annotations

import velpoly  # noqa: F401

import mechanisms
from mechanisms import in_process
from test_fuzz import to_toml
from zoo import zoo


def test_a_missing_glyph_is_one_warning_line_per_character(tmp_path):
    mech = mechanisms.rename_links(zoo(20261125, 1)[0].mech, ("frame", "crank漢", "coupler", "rocker"))
    mech["title"] = "Four-bar 漢 of 漢"   # a character no font of the figures has (the emoji too: U+1F680)
    f = tmp_path / "kanji.toml"
    f.write_text(to_toml(mech))
    out = tmp_path / "kanji.svg"
    r = in_process(["draw", f, "--sheet", "displacement", "-o", out])
    assert r.returncode == 0 and out.exists(), r.stderr
    assert r.stderr.splitlines() == [f"warning: {f}: the fonts have no glyph for '漢' (U+6F22): it is drawn as a box"]
