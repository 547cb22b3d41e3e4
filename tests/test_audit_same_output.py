"""Outside check, FORMAT.md section 3 (outputs never replace their input; nothing partial): two outputs of one
command are two files. ``velpoly sweep``'s ``-o``, ``--csv`` and ``--gif`` naming one file (the same path, through
a symbolic link or a hard link) is exit 2 naming both options, refused before any work: nothing is written and the
file is left as it was.

Found by the audit: ``velpoly sweep m.toml --csv c.svg -o c.svg`` wrote the CSV, then the plot over it, and
exited 0 (printing c.svg twice): the CSV was lost.
"""
from __future__ import annotations

import os

import mechanisms
from test_fuzz import to_toml
from zoo import each


def test_two_outputs_naming_one_file_are_refused(tmp_path):
    os.chdir(tmp_path)
    (tmp_path / "old.csv").write_text("mine\n")
    os.symlink("old.csv", tmp_path / "link.svg")
    os.link("old.csv", tmp_path / "hard.svg")
    (tmp_path / "a.gif").symlink_to("old.csv")
    cases = [(["--csv", "c.svg", "-o", "c.svg"], "-o", "--csv"), (["--csv", "./c.svg", "-o", "c.svg"], "-o", "--csv"),
             (["-o", "link.svg", "--csv", "old.csv"], "-o", "--csv"), (["-o", "hard.svg", "--csv", "old.csv"], "-o", "--csv"),
             (["--csv", "old.csv", "--gif", "a.gif"], "--csv", "--gif"),
             (["-o", "p.svg", "--csv", "old.csv", "--gif", "a.gif"], "--csv", "--gif")]
    for k, sp in enumerate(each(20271127, 3)):
        f = tmp_path / f"m{k}.toml"
        f.write_text(to_toml(sp.mech))
        for args, first, second in cases:
            before = sorted(p.name for p in tmp_path.iterdir())
            r = mechanisms.in_process(["sweep", f.name, "--step", "30", *args])
            assert r.returncode == 2, (args, r.stderr)
            line = r.stderr.splitlines()[0]
            assert line.startswith(f"error: {f.name}: ") and f"{first} and {second} name the same file" in line, line
            assert sorted(p.name for p in tmp_path.iterdir()) == before and r.stdout == ""
            assert (tmp_path / "old.csv").read_text() == "mine\n"
