"""pipeline.api (issue 33): curve_verdict runs `make curve` and returns verdict.csv as a DataFrame, the
headline and the files; checked against the CSV the stage wrote, read independently (the csv module)."""
from __future__ import annotations

import csv
import math
from pathlib import Path

import pytest

from pipeline.api import ROOT, RunError, curve_verdict

TEXT = {"wheel", "screen_mode", "mode", "zeta_needed", "wav", "mu_onset", "mu_squeal_range", "mode_onset"}   # ">0.8", "0.3374-"


def csv_rows(path: Path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


@pytest.mark.usefixtures("r75_verdict")
def test_curve_verdict_r75_matches_the_stage_csv():
    # r75: the cheapest shipped curve with a squealing wheel (up to date after `make curve CURVE=r75`: ~1 s)
    v = curve_verdict("r75", quiet=True)
    assert v.csv == ROOT / "build" / "curves" / "r75" / "verdict.csv" and v.md.exists() and v.json.exists()
    rows = csv_rows(v.csv)
    df = v.table
    assert list(df.columns) == list(rows[0].keys()) and len(df) == len(rows) == 4
    for i, r in enumerate(rows):
        for k, text in r.items():
            got = df.iloc[i][k]
            if text == "":
                assert isinstance(got, float) and math.isnan(got), (k, got)
            elif k in TEXT:
                assert got == text, (k, got, text)
            else:
                assert float(got) == float(text), (k, got, text)
    loud = max((r for r in rows if r["squeals"] == "1"), key=lambda r: float(r["L_pA"]))
    assert loud["wheel"] == "a1i"
    assert f"wheel {loud['wheel']} at {float(loud['f_squeal']):.0f} Hz" in v.headline
    assert f"L_pA = {float(loud['L_pA']):.1f} dB(A)" in v.headline
    assert v.stop.startswith("What would stop it: friction below mu = " + f"{float(loud['mu_threshold']):.3f}")
    assert v.wavs == [Path(loud["wav"])] and v.wavs[0].name == "listen_7.5m.wav" and v.wavs[0].exists()
    assert v.folder / "bogie.png" in v.figures


def test_a_missing_curve_file_is_one_line(tmp_path):
    with pytest.raises(RunError) as e:
        curve_verdict(tmp_path / "nowhere.toml", quiet=True)
    msg = str(e.value)
    assert "\n" not in msg and str(tmp_path / "nowhere.toml") in msg and "no such curve file" in msg


@pytest.mark.validation
def test_line_study_quick_matches_its_csv():
    # slow (a Dask cluster and three curve verdicts, 2 min 40 s on 2 shared cores): run with --validation
    from pipeline.api import line_study

    r = line_study("metro_line", quick=True, quiet=True)
    rows = csv_rows(r.csv)
    df = r.table
    assert len(rows) == len(df) == 3 and list(df.columns) == list(rows[0].keys())
    for i, row in enumerate(rows):
        assert df.iloc[i]["id"] == row["id"] and float(df.iloc[i]["radius_m"]) == float(row["radius_m"])
        assert int(df.iloc[i]["squeals"]) == int(row["squeals"])
    n = sum(int(x["squeals"]) for x in rows)
    assert (f"{n} of 3 curve conditions squeal" in r.headline) if n else r.headline.startswith("No curve squeals")
    assert r.export.exists() and r.md.exists() and r.figures
