"""The example line (`make study STUDY=metro_line`) end to end: 30 curves on dry and wet rail, its table, plots
and NoiseModelling rows (one per squealing row); slow, `make validate` (its fragment docs/validation/94_line.md
is written by pipeline/validation/line_doc.py)."""
import csv
import subprocess
import sys

import pytest

from tests.study.conftest import ROOT


@pytest.mark.validation
def test_example_line_and_its_fragment():
    r = subprocess.run([sys.executable, "-m", "pipeline", "study", "--study", "metro_line", "--no-progress"],
                       cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]
    out = ROOT / "build" / "studies" / "metro_line"
    rows = list(csv.DictReader(open(out / "line.csv")))
    assert len(rows) == 60 and {x["friction"] for x in rows} == {"dry", "wet"}
    for f in ("line.md", "level_radius.png", "chainage.png", "lw_railway.csv", "lw_railway_sections.csv"):
        assert (out / f).exists(), f
    sq = [x for x in rows if x["squeals"] == "1"]
    assert len(list(csv.DictReader(open(out / "lw_railway.csv")))) == len(sq)
