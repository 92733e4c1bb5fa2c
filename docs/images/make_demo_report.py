"""The README's picture: Figs. 9 and 10 of the demo's report, one above the other.

    axlebox demo && python3 docs/images/make_demo_report.py axlebox-demo/report
"""
import sys
from pathlib import Path

from PIL import Image


OUT = Path(__file__).with_name("demo_report.png")


def main(report: Path, out: Path = OUT) -> Path:
    parts = [Image.open(report / f"{name}_48kmh.png").convert("RGB")
             for name in ("fig09_time", "fig10_envelope")]
    width = max(p.width for p in parts)
    sheet = Image.new("RGB", (width, sum(p.height for p in parts)), "white")
    y = 0
    for p in parts:
        sheet.paste(p, (0, y))
        y += p.height
    sheet = sheet.quantize(colors=64)          # line plots: a small palette keeps the file small
    sheet.save(out, optimize=True)
    return out


if __name__ == "__main__":
    print(main(Path(sys.argv[1] if len(sys.argv) > 1 else "axlebox-demo/report")))
