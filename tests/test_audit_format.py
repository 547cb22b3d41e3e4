"""Outside check, FORMAT.md section 5, Defaults: "`title` the file's name". Found by the audit: the
command line gave the path as typed (``velpoly solve ../m/four.toml --json`` had the title
"../m/four.toml", and the figures were headed by the path) while ``velpoly.load`` gave "four.toml".
Now both give the file's name; errors still name the file as it was given.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import velpoly
from velpoly.cli import main

import mechanisms
from test_fuzz import to_toml


@pytest.mark.parametrize("seed", range(3))
def test_the_default_title_is_the_file_s_name(tmp_path, capsys, monkeypatch, seed):
    rng = np.random.default_rng(seed)
    d = mechanisms.fourbar(theta=float(rng.uniform(10, 170)), omega=float(rng.uniform(-9, 9)))
    d.pop("title", None)
    folder = tmp_path / "deep" / f"f{seed}"
    folder.mkdir(parents=True)
    f = folder / f"mech {seed}.toml"
    f.write_text(to_toml(d))
    monkeypatch.chdir(tmp_path)
    for given in (str(f), f"deep/f{seed}/mech {seed}.toml", f"./deep/../deep/f{seed}/mech {seed}.toml"):
        assert main(["solve", given, "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["title"] == f.name
        assert velpoly.load(given).title == f.name
    d["title"] = "as written"
    f.write_text(to_toml(d))
    assert main(["solve", str(f), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["title"] == "as written"
    d["title"] = 3
    f.write_text(to_toml(d))
    assert main(["solve", f"deep/f{seed}/mech {seed}.toml"]) == 2   # errors name the file as given
    assert capsys.readouterr().err.startswith(f"error: deep/f{seed}/mech {seed}.toml: title")
