"""Outside check, FORMAT.md section 3 (exit status: 0 done; 2 the input is wrong; 3 it cannot be assembled;
1 is an internal error): ``velpoly gallery --source DIR`` whose examples fail for their input. Found by the
audit: any failing example made the command exit 1, an internal error's status, for a file that is not TOML
or a mechanism that cannot be assembled at its ``driver.angle``. Now the failures' worst status where each is
its input's (3 over 2), and 1 where any is velpoly's own. Generated mechanisms, drawn by a stand-in (the
command's real drawing is test_wheel's)."""
from __future__ import annotations

import copy

import velpoly.gallery as gallery

from mechanisms import in_process
from test_fuzz import to_toml
from test_gallery import fake_draw
from zoo import zoo


def _crashing_draw(bad_title):
    draw = fake_draw([])

    def crash(sol, out, **kw):
        if sol.mechanism.title == bad_title:
            raise RuntimeError("a renderer's bug")
        return draw(sol, out, **kw)
    return crash


def test_the_gallery_exits_with_its_failures_input_status(tmp_path, monkeypatch):
    good, rocker = zoo(20271201, 3)[1:]
    wrong = copy.deepcopy(good.mech)
    wrong["driver"]["link"] = "no such link"                          # exit 2: the input is wrong
    beyond = copy.deepcopy(rocker.mech)
    beyond["driver"]["angle"] = 300.0                                 # exit 3: beyond its toggles (97.8-141.7 deg)
    crashed = {**copy.deepcopy(rocker.mech), "title": "crashes"}      # exit 1: the stand-in renderer's bug
    cases = [({"a_good": good.mech, "b_wrong": wrong, "c_text": "x = = 1\n"}, 2),
             ({"a_good": good.mech, "b_wrong": wrong, "d_beyond": beyond}, 3),
             ({"a_good": good.mech, "d_beyond": beyond, "e_crashed": crashed}, 1)]
    monkeypatch.setattr(gallery, "_draw_to_file", lambda: _crashing_draw("crashes"))
    for i, (files, status) in enumerate(cases):
        src = tmp_path / f"src{i}"
        src.mkdir()
        for name, mech in files.items():
            (src / f"{name}.toml").write_text(mech if isinstance(mech, str) else to_toml(mech))
        r = in_process(["gallery", "--source", src, "-o", tmp_path / f"out{i}"])
        failed = len(files) - 1
        assert r.returncode == status, (i, r.returncode, r.stderr)
        assert f"gallery: {failed} of {len(files)} examples failed" in r.stderr, r.stderr
        assert len([x for x in r.stderr.splitlines() if x.startswith("error: ")]) == failed, r.stderr
