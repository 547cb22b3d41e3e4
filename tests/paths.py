"""Where the tests find the repository's files: the built-in examples (the gallery's mechanism files,
shipped with the package in velpoly/examples/) and the gallery's generated page and figures."""
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "velpoly" / "examples"          # every gallery *.toml, package data
GALLERY = ROOT / "gallery"                        # the generated README.md and figures/
GALLERY_FILES = sorted(EXAMPLES.glob("*.toml"))
# the files with the book's printed answers (a [reference] table): the tests that compare them run on these, and
# test_gallery names the others, so that a file losing its answers fails there rather than being skipped
BOOK_FILES = [p for p in GALLERY_FILES if "reference" in tomllib.loads(p.read_text(encoding="utf-8"))]
SIXBAR = EXAMPLES / "problem_1_4_4_sixbar.toml"   # the demo's example and FORMAT.md section 1's file


def example(stem: str) -> Path:
    """The built-in example file ``velpoly/examples/STEM.toml``."""
    return EXAMPLES / f"{stem}.toml"

assert GALLERY_FILES, f"no example files in {EXAMPLES}: a test over them would pass having checked nothing"
