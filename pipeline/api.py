"""The Python front door for those who script (issue 33)::

    from pipeline.api import curve_verdict, line_study
    v = curve_verdict("r75")                  # a shipped curve, or a path: curve_verdict("~/project/my_curve.toml")
    print(v.headline)                         # which wheel squeals, at what frequency, how loud, what would stop it
    v.table                                   # verdict.csv as a pandas DataFrame (one row per wheel)

Both functions run exactly what ``make curve CURVE=...`` / ``make study STUDY=...`` run, through Make
itself (the Makefile builds the prerequisites -- the wheel's modes, the rail -- and reruns nothing that
is up to date), in the repository root, then read the files the stage wrote.  A relative path is taken
from the caller's working directory.  A failed run raises ``RunError`` with the stage's last line (the
one-line input error, naming file, key and value).
"""
from __future__ import annotations

import csv
import os
import re
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MAKE_NOISE = re.compile(r"make(\[\d+\])?: (\*\*\*|Entering|Leaving)")   # Make's own lines, not the stage's


class RunError(RuntimeError):
    """``make curve`` / ``make study`` failed; the message is its last line of error output."""


def _target(where: str | os.PathLike) -> str:
    """Make's CURVE=/STUDY= value: a shipped name as it is, a path made absolute (Make runs in ROOT)."""
    s = os.fspath(where)
    if isinstance(where, Path) or "/" in s or s.endswith(".toml") or s.startswith("~"):
        return str(Path(s).expanduser().resolve())
    return s


def _make(goal: str, assigns: list[str], build_dir, quiet: bool) -> Path:
    """Run ``make <goal> VAR=value ... BUILD=<build_dir>`` in the repository, its log (stdout and stderr)
    passed on to ``sys.stderr`` line by line unless ``quiet`` (also in a notebook, whose stderr is no
    file); returns the build folder."""
    build = Path(build_dir).expanduser().resolve() if build_dir is not None else ROOT / "build"
    cmd = ["make", "--no-print-directory", "-C", str(ROOT), goal, *assigns, f"BUILD={build}"]
    tail: list[str] = []
    with subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, bufsize=1) as p:
        for line in p.stdout:
            if not quiet:
                sys.stderr.write(line)
            if line.strip() and not MAKE_NOISE.match(line):
                tail = (tail + [line.rstrip()])[-20:]
    if p.returncode != 0:
        raise RunError(f"make {goal} {' '.join(assigns)}: " + (tail[-1] if tail else f"exit {p.returncode}"))
    return build


def _read_table(path: Path):
    import pandas as pd  # lazy: heavy (pandas), and only the table needs it

    return pd.read_csv(path, keep_default_na=True)


def _paragraph(md: str, start: str) -> str:
    """The first paragraph of ``md`` that begins with ``start``, Markdown emphasis removed."""
    for p in (p.strip() for p in md.split("\n\n")):
        if p.startswith(start):
            return re.sub(r"\*\*|`", "", p).strip()
    return ""


@dataclass
class CurveVerdict:
    """What ``make curve`` wrote for a curve (build/curves/<name>/)."""
    name: str
    folder: Path
    headline: str                  # the verdict in one paragraph (verdict.md's first), plain text
    stop: str                      # "What would stop it: ..." ('' when nothing squeals)
    md: Path                       # verdict.md (read first)
    csv: Path                      # verdict.csv: one row per wheel (docs/reference.md)
    json: Path                     # verdict.json: the rows with their provenance
    figures: list[Path] = field(default_factory=list)   # bogie.png (and any other figure of the curve)
    wavs: list[Path] = field(default_factory=list)      # the squealing wheels' calibrated WAVs
    html: Path | None = None       # verdict.html, where the run writes one

    @property
    def table(self):
        """verdict.csv as a pandas DataFrame (empty cells: NaN)."""
        return _read_table(self.csv)


@dataclass
class LineResult:
    """What ``make study STUDY=<line>`` wrote (build/studies/<line>/)."""
    name: str
    folder: Path
    headline: str                  # line.md's verdict paragraph, plain text
    md: Path                       # line.md
    csv: Path                      # line.csv: one row per curve and friction condition
    export: Path                   # lw_railway.csv: NoiseModelling's LW_RAILWAY rows of the squealing curves
    figures: list[Path] = field(default_factory=list)   # level_radius.png, chainage.png

    @property
    def table(self):
        """line.csv as a pandas DataFrame."""
        return _read_table(self.csv)


def curve_verdict(path_or_name: str | os.PathLike, *, build_dir=None, what_ifs: bool = True,
                  quiet: bool = False) -> CurveVerdict:
    """The verdict of a curve: a shipped name (``"r75"``: pipeline/curves/r75.toml) or a curve file anywhere
    (its vehicle beside it, or a shipped one).  Runs ``make curve CURVE=...`` (BUILD=``build_dir`` when
    given; ``what_ifs=False``: NO_WHAT_IFS=1); ``quiet``: the run's log is not shown."""
    value = _target(path_or_name)
    build = _make("curve", ["CURVE=" + value] + ([] if what_ifs else ["NO_WHAT_IFS=1"]), build_dir, quiet)
    name = Path(value).stem if value.endswith(".toml") else value
    out = build / "curves" / name
    md_text = (out / "verdict.md").read_text(encoding="utf-8")
    with open(out / "verdict.csv", newline="", encoding="utf-8") as fh:
        wavs = [Path(r["wav"]) for r in csv.DictReader(fh) if r.get("wav")]
    html = out / "verdict.html"
    return CurveVerdict(name=name, folder=out, headline=_paragraph(md_text, "**"),
                        stop=_paragraph(md_text, "What would stop it"), md=out / "verdict.md",
                        csv=out / "verdict.csv", json=out / "verdict.json", figures=sorted(out.glob("*.png")),
                        wavs=wavs, html=html if html.exists() else None)


def line_study(path_or_name: str | os.PathLike, *, build_dir=None, quick: bool = False,
               quiet: bool = False) -> LineResult:
    """A line study (``kind = "line"``): a shipped name (``"metro_line"``: pipeline/studies/metro_line.toml).
    Runs ``make study STUDY=...`` (``quick``: QUICK=1, the study's first rows; resumes an interrupted run)."""
    value = os.fspath(path_or_name)
    build = _make("study", ["STUDY=" + value] + (["QUICK=1"] if quick else []), build_dir, quiet)
    name = Path(value).stem
    out = build / "studies" / (name + ("-quick" if quick else ""))
    md_text = (out / "line.md").read_text(encoding="utf-8")
    return LineResult(name=name, folder=out, headline=_paragraph(md_text, "**"), md=out / "line.md",
                      csv=out / "line.csv", export=out / "lw_railway.csv",
                      figures=[p for p in (out / "level_radius.png", out / "chainage.png") if p.exists()])
