"""The example line (`make study STUDY=metro_line`) end to end and its validation fragment
docs/validation/94_line.md (the rule comparison with its plots; the screen-first verdict against the curve
stage over the radius study's curves): slow, `make validate`."""
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
    r = subprocess.run([sys.executable, "-m", "pipeline.validation.line_doc"], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]
    text = (ROOT / "docs" / "validation" / "94_line.md").read_text()
    assert "CNOSSOS-EU" in text and "Schall 03" in text and "Screen first against the curve stage" in text
