"""Benchmarks: `make bench` -> docs/benchmarks.md.

Runs each benchmark module's ``run() -> str`` (a markdown section) and
writes them under a header naming the machine.  `python -m benchmarks wheel`
runs a subset and only prints it (docs/benchmarks.md is written by full runs);
`python -m benchmarks contact --update` runs a subset and replaces those sections (by their
'## ' title) in docs/benchmarks.md, keeping the others.
"""
from __future__ import annotations

import importlib
import os
import platform
import sys
import time
from pathlib import Path
from pipeline.store.atomic import save_text


ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "benchmarks.md"
SUITES = ["wheel", "contact", "friction_laws", "rail", "greens", "fast_rail", "any_point", "interaction", "radiation",
          "stability", "study", "study_cases", "fresh_make", "friction", "two_point", "line", "line_climate",
          "curve_risk", "bem"]


def machine() -> str:
    cpu = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = ""
    try:
        kb = int(Path("/proc/meminfo").read_text().split()[1])
        mem = f", {kb / 2**20:.0f} GiB RAM"
    except (OSError, ValueError, IndexError):
        pass
    return f"{cpu}, {os.cpu_count()} cores{mem}, {platform.system()} {platform.release()}, Python {platform.python_version()}"



def update_sections(text: str, sections: list[str]) -> str:
    """Replace the sections of a benchmarks document whose '## ' title line matches."""
    for sec in sections:
        title = sec.splitlines()[0]
        start = text.find("\n" + title + "\n")
        if start < 0:
            text = text.rstrip("\n") + "\n\n" + sec + "\n"
            continue
        end = text.find("\n## ", start + 1)
        text = text[:start + 1] + sec + "\n" + (text[end:] if end >= 0 else "")
    return text


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    update = "--update" in args
    chosen = [a for a in args if a != "--update"]
    names = chosen or SUITES
    sections = []
    for name in names:
        try:
            mod = importlib.import_module(f"benchmarks.{name}")
        except ModuleNotFoundError:
            print(f"benchmarks.{name}: not present, skipped", file=sys.stderr)
            continue
        t0 = time.perf_counter()
        sections.append(mod.run().strip())
        print(f"{name}: {time.perf_counter() - t0:.0f} s", file=sys.stderr)
    text = f"""# Benchmarks

Machine: {machine()}.
Produced by `make bench` (`python -m benchmarks`) on {time.strftime('%Y-%m-%d')}; wall-clock figures of single
runs unless a section says otherwise.

""" + "\n\n".join(sections) + "\n"
    print(text)
    if chosen and update and OUT.exists():
        save_text(update_sections(OUT.read_text(), sections), OUT)
    if not chosen:
        save_text(text, OUT)
    return 0


if __name__ == "__main__":
    sys.exit(main())
