"""The examples ship with the package (issue 18, item 6): a wheel built from this checkout, installed in a
fresh virtual environment, lists and prints the examples and builds the gallery and an HTML page from
outside any checkout, with no repository files at hand.

Marked ``wheel`` (it runs by default; ``-m "not wheel"`` leaves it out). It skips, saying why, only where
no wheel can be built (no build backend reachable); every other failure fails.
"""
from __future__ import annotations

import importlib.metadata
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

from paths import EXAMPLES, ROOT

# one worker runs the module (its xdist group): the wheel is built and installed once
pytestmark = [pytest.mark.wheel, pytest.mark.xdist_group("wheel")]


def _build_wheel(tmp: Path) -> Path:
    """A wheel of a copy of the package (the build writes no build/ into the checkout)."""
    src = tmp / "src"
    src.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, src / name)
    shutil.copytree(ROOT / "velpoly", src / "velpoly", ignore=shutil.ignore_patterns("__pycache__"))
    dist = tmp / "dist"
    errors = []
    # the installed setuptools builds it offline, called as pip would call it (PEP 517's build_wheel of the
    # backend pyproject names) in one process, a third of pip's CPU: it needs the wheel package (the test
    # extra brings it) below setuptools 70.1; else pip's isolated build fetches a setuptools
    offline = importlib.util.find_spec("setuptools") is not None and (
        importlib.util.find_spec("wheel") is not None or _version("setuptools") >= (70, 1))
    backend = ("import sys\nfrom setuptools import build_meta\nbuild_meta.build_wheel(sys.argv[1])")
    for cmd in ([[sys.executable, "-c", backend, str(dist)]] if offline else []) + [
            [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(dist), str(src)]]:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=300, cwd=src)
        wheels = sorted(dist.glob("velpoly-*.whl"))
        if r.returncode == 0 and wheels:
            return wheels[0]
        errors.append((r.stderr or r.stdout).strip().splitlines()[-1:] or ["(no output)"])
    pytest.skip(f"cannot build a wheel here: {errors}")


def _version(name: str) -> tuple[int, ...]:
    """The installed distribution's version as numbers ((0,) where it is not installed)."""
    try:
        return tuple(int(x) for x in re.findall(r"\d+", importlib.metadata.version(name))[:3])
    except importlib.metadata.PackageNotFoundError:
        return (0,)


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """(python, velpoly script, environment, working folder) of a fresh venv holding the wheel."""
    tmp = tmp_path_factory.mktemp("wheel")
    wheel = _build_wheel(tmp)
    env_dir = tmp / "venv"
    # system site-packages give numpy, matplotlib and shapely without a network; the wheel goes on top
    venv.EnvBuilder(system_site_packages=True, with_pip=False).create(env_dir)
    bindir = env_dir / ("Scripts" if os.name == "nt" else "bin")
    python = bindir / ("python.exe" if os.name == "nt" else "python")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    # the venv's own python runs pip where it sees one (the system site-packages'): `pip --python VENV` starts
    # pip twice, its own and then the venv's (2.4-2.5 against 1.8-1.9 CPU s)
    install = ["install", "-q", "--no-deps", "--ignore-installed", "--no-index", "--disable-pip-version-check",
               str(wheel)]
    for pip in ([str(python), "-m", "pip"], [sys.executable, "-m", "pip", "--python", str(python)]):
        r = subprocess.run([*pip, *install], capture_output=True, text=True, timeout=300, env=env)
        if r.returncode == 0 or "No module named pip" not in r.stderr:
            break
    assert r.returncode == 0, r.stderr
    work = tmp / "elsewhere"
    work.mkdir()
    return python, bindir / "velpoly", env, work


def _run(installed, *args, timeout=600):   # generous: a loaded machine is slow, not wrong
    python, script, env, work = installed
    return subprocess.run([str(script), *map(str, args)], capture_output=True, text=True, cwd=work, env=env,
                          timeout=timeout)


def test_the_installed_package_is_the_wheel(installed):
    python, _, env, work = installed
    r = subprocess.run([str(python), "-c", "import velpoly; print(velpoly.__file__)"], capture_output=True,
                       text=True, cwd=work, env=env)
    assert r.returncode == 0, r.stderr
    installed_at = Path(r.stdout.strip()).resolve()
    assert ROOT not in installed_at.parents and Path(python).parent.parent.resolve() in installed_at.parents


def test_examples_lists_every_gallery_file_and_prints_one(installed):
    r = _run(installed, "examples")
    assert r.returncode == 0, r.stderr
    names = [line.split()[0] for line in r.stdout.splitlines()]
    assert sorted(names) == sorted(p.stem for p in EXAMPLES.glob("*.toml")) and len(names) >= 19
    assert "ex3_6_fourbar  " in r.stdout and "Example 3.6: four-bar" in r.stdout
    r = _run(installed, "examples", "ex3_4_slotted_lever")
    assert r.returncode == 0 and r.stdout == (EXAMPLES / "ex3_4_slotted_lever.toml").read_text(encoding="utf-8")
    # a name not there (`examples ex3_4`: exit 2 naming ex3_4_slotted_lever, from the listing shown above) is
    # test_gallery's test_examples_lists_and_prints_the_built_in_files, in that process (a third program here
    # until the suite had to fit 2 minutes: 0.3 CPU s)


def test_gallery_from_the_wheel(installed):
    work = installed[3]
    # one example keeps the test short; the whole gallery is the same path 19 times (checked by hand: 38 s)
    # (and animates one family of 7)
    r = _run(installed, "gallery", "-o", "site", "ex3_6_fourbar")
    assert r.returncode == 0, r.stderr
    site = work / "site"
    assert (site / "figures" / "ex3_6_fourbar.png").read_bytes().startswith(b"\x89PNG")
    # its family's animation (the renderer ships too), and only that one: the others were not asked for
    assert [p.name for p in (site / "figures").glob("animate-*")] == ["animate-ex3_6_fourbar.gif"]
    # the folder stands alone: the files its README links to are beside it
    assert (site / "ex3_6_fourbar.toml").read_text(encoding="utf-8") == (EXAMPLES / "ex3_6_fourbar.toml").read_text(
        encoding="utf-8")
    readme = (site / "README.md").read_text(encoding="utf-8")
    assert "](ex3_6_fourbar.toml)" in readme and "](figures/ex3_6_fourbar.png)" in readme
    assert "`velpoly gallery -o site`" in readme and "site-packages" not in readme
    # (`velpoly demo` finds its example as `examples` and the gallery do: by velpoly.gallery.example_path in
    # the package's examples/, which the wheel ships (test_examples_lists_every_gallery_file_and_prints_one);
    # what it writes is test_gallery's test_demo_writes_the_sheet_and_the_tables)


def test_html_page_from_the_wheel(installed):
    """The page's template, script and style (velpoly/html_assets) ship in the wheel."""
    work = installed[3]
    # (the file as `velpoly examples ex3_6_fourbar` prints it: test_examples_lists_every_gallery_file_and_prints_one)
    (work / "fourbar.toml").write_text((EXAMPLES / "ex3_6_fourbar.toml").read_text(encoding="utf-8"), encoding="utf-8")
    r = _run(installed, "html", "fourbar.toml", "-o", "fourbar.html", "--step", "30")
    assert r.returncode == 0, r.stderr
    page = (work / "fourbar.html").read_text(encoding="utf-8")
    assert page.lstrip().lower().startswith("<!doctype html") and "<script" in page and "http://" not in page
