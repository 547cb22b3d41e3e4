"""The README's walkthroughs work as written (issue 18, item 9): each TOML file in it loads and solves,
the numbers quoted in the prose are what velpoly prints, and the Python snippets run."""
import re

import pytest

import velpoly
from paths import ROOT
from velpoly.cli import main

README = (ROOT / "README.md").read_text(encoding="utf-8")


def blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", README, flags=re.S)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("readme")
    toml = blocks("toml")
    ex36, lever = next(t for t in toml if "Example 3.6" in t), next(t for t in toml if "Slotted lever" in t)
    (tmp / "ex36.toml").write_text(ex36, encoding="utf-8")
    (tmp / "lever.toml").write_text(lever, encoding="utf-8")
    return tmp


def _solve(capsys, path, *args):
    """What ``velpoly solve PATH ARGS`` prints, run in this process (``velpoly.cli.main``, what the command
    runs: the same text without a subprocess's second of imports; the command's exit status as the shell sees
    it is test_cli's test_solve_exit_0)."""
    capsys.readouterr()
    rc = main(["solve", str(path), *args])
    out, err = capsys.readouterr()
    assert rc == 0 and err == "", err
    return out


def test_the_four_bar_tutorial(files, capsys):
    out = _solve(capsys, files / "ex36.toml")
    # "ω3 = 6.7018 (book 6.702), V_B = 602.121∠149.213° (book 602.137∠149.213°)"
    assert re.search(r"^omega_3 +6\.702 +6\.7018 ", out, flags=re.M)
    assert re.search(r"^V_B +602\.137 ∠ 149\.213° +602\.121 ∠ 149\.213° ", out, flags=re.M)
    compass = out.split("Compass constructions", 1)[1].split("\n\n", 1)[0]
    assert compass.splitlines()[3].startswith("B ") and compass.splitlines()[3].rstrip().endswith('side = "right"')


def test_the_slotted_lever_tutorial_prints_what_the_readme_shows(files, capsys):
    out = _solve(capsys, files / "lever.toml")
    shown = next(b for b in blocks("text") if "A^c_A3/A4" in b).strip().splitlines()
    printed = out.split("Reference values", 1)[1].splitlines()
    assert [line.split() for line in shown] == [line.split() for line in printed[1:2] + printed[3:3 + len(shown) - 1]]
    assert "A (on 2 and 3)" in out and "A₄" in out
    m = velpoly.load(files / "lever.toml")
    assert m.driver.omega == pytest.approx(-2 * 3.141592653589793, rel=1e-15)   # "60 rpm clockwise"
    assert velpoly.solve(m).omega["4"] == pytest.approx(-1.2083, abs=5e-5)          # "ω4 = -1.2083 (cw)"


def test_the_python_snippets_run(files, monkeypatch):
    monkeypatch.chdir(files)
    for code in blocks("python"):
        if "IPython" in code:
            pytest.importorskip("IPython")
        exec(compile(code, "README.md", "exec"), {})
