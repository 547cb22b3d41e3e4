"""Where the tests find the repository's files: the built-in examples (the gallery's mechanism files,
shipped with the package in velpoly/examples/) and the gallery's generated page and figures."""
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "velpoly" / "examples"          # every gallery *.toml, package data
GALLERY = ROOT / "gallery"                        # the generated README.md and figures/
GALLERY_FILES = sorted(EXAMPLES.glob("*.toml"))
SIXBAR = EXAMPLES / "problem_1_4_4_sixbar.toml"   # the demo's example and FORMAT.md section 1's file


def example(stem: str) -> Path:
    """The built-in example file ``velpoly/examples/STEM.toml``."""
    return EXAMPLES / f"{stem}.toml"

assert GALLERY_FILES, f"no example files in {EXAMPLES}: a test over them would pass having checked nothing"
