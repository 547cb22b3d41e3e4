"""Make docs/figures/html_sheet.png, the README's screenshot of `velpoly html`.

    python3 docs/html_screenshot.py [OUT.png]

Builds the page of Problem 1.4.4 (the six-bar of the README's static sheet), opens it in headless
Chromium at the crank's drawn angle (30 deg) and step 8 of the construction (the acceleration polygon's
first intersection, for C), and writes a 1280 x 960 screenshot reduced
to 60 %. Nothing else is needed than velpoly, Pillow and Debian's `chromium` package.
"""
from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import velpoly  # noqa: E402
from velpoly.html import page  # noqa: E402

FRAGMENT = "#angle=30&step=8"
SIZE = (1280, 960)


def main(out: Path) -> None:
    from PIL import Image
    browser = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
    if not browser:
        sys.exit("needs chromium (apt-get install chromium)")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        sheet = tmp / "sheet.html"
        sheet.write_text(page(velpoly.load(ROOT / "velpoly" / "examples" / "problem_1_4_4_sixbar.toml")), encoding="utf-8")
        shot = tmp / "shot.png"
        subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                        "--disable-background-networking", "--disable-component-update", "--disable-sync",
                        "--hide-scrollbars", f"--user-data-dir={tmp / 'profile'}", "--virtual-time-budget=3000",
                        f"--window-size={SIZE[0]},{SIZE[1]}", f"--screenshot={shot}",
                        sheet.as_uri() + FRAGMENT], check=True, capture_output=True, timeout=120)
        img = Image.open(shot).convert("RGB")
        img = img.resize((SIZE[0] * 3 // 5, SIZE[1] * 3 // 5), Image.LANCZOS)
        img = img.quantize(colors=128, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        out.parent.mkdir(parents=True, exist_ok=True)
        img.save(out, optimize=True)
    print(out)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "figures" / "html_sheet.png")
