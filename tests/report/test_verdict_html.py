"""The curve's and the line study's verdict pages (issue 33) in headless chromium, as the case report's
(tests/report/test_html.py): the headline block first, every image decodes (naturalWidth > 0), both
WAVs (the loudest wheel's limit cycle and the pass-by) load with a duration, no console error.  And
`make` ends with the curve's headline: its dry run's last command prints headline.txt (after the curve
stage), `make headline` prints it, and the headline's numbers are verdict.csv's (r75: a1i, 435 Hz, (2,0,a), 78.3 dB(A); the
line study's test_line.py asserts the same numbers for its R = 75 m row).  The r75 verdict is made
through Make first (the r75_verdict fixture); skipped without chromium."""
from __future__ import annotations

import csv
import shutil
import subprocess

import pytest

from pipeline.store import paths
from tests.report.cdp import find_chromium, inspect_page

ROOT = paths.ROOT
R75 = paths.build() / "curves" / "r75"
needs_chromium = pytest.mark.skipif(find_chromium() is None, reason="chromium is not installed (debian-packages.txt)")


def _rows():
    from pipeline.curve.stage import read_verdict

    return read_verdict(R75 / "verdict.csv")


def _page_ok(page, n_images, n_audio):
    assert page["first"] == "H1" and page["blockquote_index"] == 1          # the headline block first
    assert len(page["images"]) == n_images and all(i["naturalWidth"] > 0 for i in page["images"]), page["images"]
    assert all(i["src"].startswith("data:image/png;base64") for i in page["images"])      # self-contained
    assert len(page["audio"]) == n_audio, page["audio"]
    assert all(a["readyState"] >= 1 and a["error"] is None and a["duration"] > 0.5 for a in page["audio"]), page["audio"]
    assert page["errors"] == []


@pytest.mark.usefixtures("r75_verdict")
@needs_chromium
def test_curve_verdict_page(tmp_path):
    """The page rebuilt from r75's verdict (in a folder of its own: it carries its figures and sounds),
    and the page the stage wrote, when it is there."""
    from pipeline.config.curve_inputs import read_curve
    from pipeline.curve.verdict_html import write_page

    for f in ("verdict.md", "bogie.png"):
        shutil.copy(R75 / f, tmp_path / f)
    rows = _rows()
    page = write_page(tmp_path, read_curve("r75"), rows, (R75 / "verdict.md").read_text())
    text = page.read_text()
    assert "The bogie in its curve" in text and "What would stop it" in text and "a1i" in text
    # bogie.png, the limit cycle's and the pass-by's figures; the two WAVs
    _page_ok(inspect_page(page), 3, 2)
    if (R75 / "verdict.html").exists():
        _page_ok(inspect_page(R75 / "verdict.html"), 3, 2)


@pytest.mark.usefixtures("r75_verdict")
@needs_chromium
def test_line_study_page(tmp_path):
    """A line's outputs written from two rows (as test_line_cells.py), the squealing one being r75's
    curve: its page has the two figures, the loudest curve's two sounds, a link to its verdict."""
    from tests.study.test_line_cells import _rows as line_rows
    from pipeline.study.line_outputs import write_outputs

    _, rows = line_rows()
    rows = [r | {"curve": "r75"} for r in rows]
    spec = {"name": "t", "curves": "t.csv", "export": {"passages_day": 1.0, "passages_evening": 1.0,
                                                      "passages_night": 1.0}}
    write_outputs(spec, str(tmp_path / "t.toml"), tmp_path, False, rows, rows)
    text = (tmp_path / "verdict.html").read_text()
    assert "1 of 2 curve conditions squeal" in text and "curves/r75/verdict.csv" in text
    _page_ok(inspect_page(tmp_path / "verdict.html"), 2, 2)


@pytest.mark.usefixtures("r75_verdict")
def test_headline_is_the_verdict_and_make_prints_it_last():
    rows = {r["wheel"]: r for r in csv.DictReader(open(R75 / "verdict.csv", newline=""))}
    a = rows["a1i"]
    head = (R75 / "headline.txt").read_text()
    assert head.startswith("curve r75 ") and f"wheel a1i at {float(a['f_squeal']):.0f} Hz" in head
    assert "435 Hz" in head and "(2,0,a)" in head and "L_pA = 78.3 dB(A) at 7.5 m" in head
    assert f"mu = {float(a['mu_threshold']):.3f}" in head and "What would stop it" in head
    assert head.splitlines()[-1] == "Open the verdict: build/curves/r75/verdict.html"
    r = subprocess.run(["make", "--no-print-directory", "headline"], cwd=ROOT, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0 and r.stdout == head, r.stderr
    # `make`'s steps after the curve file changed (a dry run, -W: as if r75.toml were newer): the curve's
    # verdict, then the headline last
    r = subprocess.run(["make", "-n", "--no-print-directory", "-W", "pipeline/curves/r75.toml"], cwd=ROOT,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    lines = r.stdout.strip().splitlines()
    assert lines[-2].strip().endswith("-m pipeline curve --curve r75")
    assert lines[-1] == "cat build/curves/r75/headline.txt && touch build/curves/r75/.headline-shown", lines
