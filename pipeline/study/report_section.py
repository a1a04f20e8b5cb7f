"""The studies' part of the report (pipeline/stages/report.py): every study found in build/studies/
(the full version of a study when it exists, else its --quick version), its summary.md with the
headings moved under the report's "Studies" and its figures copied into the report's figures/
folder."""
from __future__ import annotations

import re
import shutil
from pathlib import Path

from pipeline.store import paths

ORDER = ("map", "damping", "contact")       # SPEC 7's order; other studies after them, by name


def study_dirs(root: Path | None = None) -> list[Path]:
    root = root or paths.build() / "studies"
    if not root.is_dir():
        return []
    done = {p.name: p for p in root.iterdir() if (p / "summary.md").is_file()}
    keep = [p for n, p in done.items() if not (n.endswith("-quick") and n[: -len("-quick")] in done)]
    rank = {n: i for i, n in enumerate(ORDER)}
    return sorted(keep, key=lambda p: (rank.get(p.name.removesuffix("-quick"), len(ORDER)), p.name))


def embed(summary: str, name: str, figdir: Path, src: Path) -> str:
    """The summary with headings two levels down (under the report's "Studies") and its figures
    copied to figdir as study_<name>_<file>."""
    def figure(m):
        target = src / m.group(2)
        if target.is_file():
            shutil.copy2(target, figdir / f"study_{name}_{target.name}")
            return f"]({figdir.name}/study_{name}_{target.name})"
        return m.group(0)

    text = re.sub(r"^(#+) ", lambda m: "##" + m.group(1) + " ", summary, flags=re.M)
    return re.sub(r"\]\((\./)?([^)/]+\.png)\)", figure, text)


def studies_section(figdir: Path) -> str:
    dirs = study_dirs()
    if not dirs:
        return ("## Studies (docs/physics.md section 7)\n\nNo study has been run yet: `make study STUDY=map` (creepage/friction map), "
                "`STUDY=damping` (wheel modal damping), `STUDY=contact` (contact-model validation); `QUICK=1` for a "
                "quick look.\n")
    parts = ["## Studies (docs/physics.md section 7)\n\nFrom build/studies/ (`make study STUDY=...`); tables beside each summary there.\n"]
    for d in dirs:
        parts.append(embed((d / "summary.md").read_text(), d.name, figdir, d))
    return "\n".join(parts)
