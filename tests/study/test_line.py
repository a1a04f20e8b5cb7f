"""The line study (issue 27): its CSV validated before any work (one line per problem), the rules'
radius classes, and a 3-curve line end to end through the CLI on a local Dask cluster: the squealing
curve's verdict equals the curve stage's (r75: the C20 metro at 75 m, 31 km/h, 100 mm cant, mu = 0.35),
the table, plots, rule comparison and NoiseModelling export written, and a rerun resumes."""
import csv
import json
import math
import os
import subprocess
import sys

import pytest

from tests.study.conftest import ROOT

STUDY = """name = "{name}"
kind = "line"
curves = "{name}.csv"
base_curve = "r150"
[friction]
dry_mu = 0.35
wet_mu = 0.15
"""
HEAD = "id,chainage_m,radius_m,cant_mm,length_m,speed_kmh,vehicle,friction\n"


def _write(tmp_path, name, rows):
    d = tmp_path / "studies"
    d.mkdir(exist_ok=True)
    (d / f"{name}.toml").write_text(STUDY.format(name=name))
    (d / f"{name}.csv").write_text("# a test line\n" + HEAD + rows)
    return dict(os.environ, SQUEAL_STUDY_DIR=str(d), OMP_NUM_THREADS="1")


def _cli(env, *args, module=("-m", "pipeline")):
    return subprocess.run([sys.executable, *module, *args], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=600)


def test_rules_radius_classes():
    """The penalties at and around the class boundaries, as the cited tables state them."""
    from pipeline.study.line_rules import cnossos_penalty, compare, schall03_penalty

    assert [cnossos_penalty(r) for r in (40, 300, 300.01, 500, 500.01, 1000)] == [8, 8, 5, 5, 0, 0]
    assert [schall03_penalty(r) for r in (40, 299.99, 300, 499.99, 500, 1000)] == [8, 8, 3, 3, 0, 0]
    assert compare(0.0, True) == "missed" and compare(3.0, False) == "penalised, quiet"


def test_bad_csv_is_one_line_per_problem(tmp_path):
    rows = ("C1,0,12,0,50,30,c20_metro,dry\n"          # radius below the curve schema's 15 m
            "C2,500,200,abc,50,30,c20_metro,dry\n"     # cant not a number
            "C3,900,200,0,50,30,tram9,damp\n")         # no such vehicle, no such friction condition
    env = _write(tmp_path, "bad_line", rows)
    out = tmp_path / "out"
    r = _cli(env, "study", "--study", "bad_line", "--no-progress", "--out", str(out))
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 4, r.stderr
    assert all("bad_line.csv" in ln for ln in lines)
    assert "line 3, radius_m = '12'" in lines[0] and "[15, 20000] m" in lines[0]
    assert "line 4, cant_mm = 'abc'" in lines[1] and "mm" in lines[1]
    assert "line 5, vehicle = 'tram9'" in lines[2] and "c20_metro" in lines[2]
    assert "line 5, friction = 'damp'" in lines[3] and "'dry', 'wet'" in lines[3]
    assert not (out / "table.csv").exists()                          # nothing computed
    c = _cli(env, "bad_line", module=("-m", "pipeline.study.check"))  # make check STUDY=bad_line
    assert c.returncode == 2 and c.stderr.strip().splitlines() == lines


def _table(path):
    with open(path, newline="") as fh:
        return {r["key"]: {k: v for k, v in r.items() if k not in ("wall_s", "worker")} for r in csv.DictReader(fh)}


def test_three_curve_line(tmp_path):
    """R = 75 m dry (mu = 0.35) squeals at its inner leading wheel as `make curve CURVE=r75` does ((2,0,a),
    435 Hz, L_pA 78.3 dB(A)); R = 150 m wet (mu = 0.15) and R = 600 m dry are quiet; the rules: both
    penalise R = 75 m and 150 m, neither R = 600 m."""
    name = "t_line3"
    env = _write(tmp_path, name, "A,100,75,100,50,31,c20_metro,dry\nW,300,150,102,70,44.1,c20_metro,wet\n"
                                 "B,600,600,64,180,70,c20_metro,dry\n")
    out = tmp_path / "out"
    r = _cli(env, "study", "--study", name, "--workers", "1", "--no-progress", "--out", str(out))
    assert r.returncode == 0, r.stderr[-3000:]
    rows = {(x["id"], x["friction"]): x for x in csv.DictReader(open(out / "line.csv"))}
    a = rows[("A", "dry")]
    assert a["squeals"] == "1" and a["wheel"] == "a1i" and a["mode"] == "(2,0,a)"
    # `python -m pipeline curve --curve r75` writes for a1i: f_squeal 435.297 Hz, L_F2 49.977 dB, L_W 104.29 dB,
    # L_pA 78.3374 dB(A) (verdict.csv, 6 digits)
    assert float(a["f_squeal"]) == pytest.approx(435.297, abs=1e-3)
    assert float(a["L_F2"]) == pytest.approx(49.977, abs=1e-3)
    assert float(a["L_W"]) == pytest.approx(104.29, abs=1e-2)
    assert float(a["L_pA"]) == pytest.approx(78.3374, abs=1e-4)
    assert "a1i" in a["unstable_wheels"] and "a1i" in a["time_loop_wheels"]
    assert a["cnossos_dB"] == "8" and a["schall03_dB"] == "8" and a["cnossos_vs_physics"].startswith("agree")
    for k in (("W", "wet"), ("B", "dry")):
        assert rows[k]["squeals"] == "0" and rows[k]["note"] == ""
    assert rows[("B", "dry")]["cnossos_vs_physics"] == "agree: quiet"
    # the climate's columns (issue 32, tests/study/test_line_risk.py): R = 75 m squeals in part of the default
    # climate (its onset 0.3374 at a1i, as `make curve CURVE=r75`), R = 600 m never (quiet up to the scan's cut)
    assert (a["climate"], a["wheel_onset"], a["mu_onset"], a["mode_onset"]) == ("default", "a1i", "0.3374", "(2,0,a)")
    assert 0 < float(a["p_squeal"]) < 0.1 and float(a["dL_squeal"]) > 0 and float(a["L_pAmax_7m5"]) > 70
    b = rows[("B", "dry")]
    assert b["p_squeal"] == "0" and b["mu_onset"] == ">0.4" and b["L_pAmax_7m5"] == "" and b["dL_squeal"] == "0"
    assert 55 < float(b["L_pAmax_rolling"]) < 95
    text = (out / "line.csv").read_text() + (out / "line_classes.csv").read_text()
    assert "nan" not in text.lower() and "inf" not in text.lower()
    # line_classes.csv recomputed from line.csv: per radius class and condition, the mean p_squeal and dL_squeal
    classes = {(x["radius_class"], x["friction"]): x for x in csv.DictReader(open(out / "line_classes.csv"))}
    assert set(classes) == {("51-100", "dry"), ("101-200", "wet"), ("> 500", "dry")}
    for (cls, fr), x in classes.items():
        r = next(v for v in rows.values() if v["friction"] == fr and
                 {"51-100": 75.0, "101-200": 150.0, "> 500": 600.0}[cls] == float(v["radius_m"]))
        assert x["curves"] == "1" and float(x["p_squeal"]) == pytest.approx(float(r["p_squeal"]), rel=1e-5, abs=1e-9)
        assert float(x["dL_squeal"]) == pytest.approx(float(r["dL_squeal"]), rel=1e-5, abs=1e-9)
        assert float(x["cnossos_dB"]) == float(r["cnossos_dB"]) and float(x["schall03_dB"]) == float(r["schall03_dB"])
    assert rows[("W", "wet")]["schall03_vs_physics"] == "penalised, quiet"
    # the verdict of the squealing row is the curve stage's (its verdict.csv, screen first)
    from pipeline.curve.stage import read_verdict

    v = {w["wheel"]: w for w in read_verdict(ROOT / "build" / "curves" / a["curve"] / "verdict.csv")}
    assert float(a["L_W"]) == pytest.approx(v["a1i"]["L_W"], abs=1e-4)
    # band levels: their power sum is the wheel's L_W (what falls outside 50 Hz-10 kHz aside)
    bands = [float(a[c]) if a[c] else -math.inf                 # an empty cell: no sound in the band
             for c in a if c.startswith("L_W_") and c.endswith("Hz")]
    assert len(bands) == 24
    total = 10 * math.log10(sum(10 ** (b / 10) for b in bands if math.isfinite(b)))
    assert total == pytest.approx(float(a["L_W"]), abs=0.5)
    # the export: one LW_RAILWAY row, reading back into the band levels within 0.01 dB
    from postprocess.exports import band_levels_of_record, lw_railway_columns

    exp = list(csv.DictReader(open(out / "lw_railway.csv")))
    assert len(exp) == 1 and list(exp[0]) == lw_railway_columns()
    from postprocess.exports import NM_BANDS_HZ, NO_SOURCE_DB

    back = band_levels_of_record(exp[0], "D", 31.0, 1.0)
    kept = [float(exp[0][f"HZD{f}"]) > NO_SOURCE_DB for f in NM_BANDS_HZ]   # bands above the table's floor
    assert sum(kept) >= 10
    for x, y, k in zip(back, bands, kept):
        if k:
            assert x == pytest.approx(y, abs=0.01)
    md = (out / "line.md").read_text()
    assert md.startswith("# Line") and "**1 of 3 curve conditions squeal**" in md
    for png in ("level_radius.png", "chainage.png"):
        assert (out / png).stat().st_size > 10_000
    assert "<audio" in (out / "verdict.html").read_text()      # the page (tests/report/test_verdict_html.py)
    # resumable: a row lost (as if the run had been killed before it finished) is the only one run again
    text = (out / "table.csv").read_text().splitlines()
    (out / "table.csv").write_text("\n".join(text[:-1]) + "\n")
    r = _cli(env, "study", "--study", name, "--workers", "1", "--no-progress", "--out", str(out))
    assert r.returncode == 0, r.stderr[-3000:]
    runs = [json.loads(x) for x in (out / "runs.jsonl").read_text().splitlines()]
    assert runs[-1]["done_before"] == 2 and runs[-1]["submitted"] == 1


def test_csv_and_vehicle_outside_the_repository(tmp_path, monkeypatch):
    """A line's CSV anywhere (``curves`` an absolute path) and a vehicle beside it that geometry/vehicles/
    does not have: the rows validate, each becomes a Curve in memory with that vehicle (the record of its
    curve file written), whose steady curving is the shipped vehicle's when the data are the same."""
    from pipeline.config.curve_inputs import read_curve
    from pipeline.curve.curving import solve_curve
    from pipeline.study.line_input import line_curves, read_rows

    mine = tmp_path / "project"
    mine.mkdir()
    (mine / "my_metro.toml").write_text((ROOT / "geometry/vehicles/c20_metro.toml").read_text()
                                        .replace('name = "c20_metro"', 'name = "my_metro"'))
    (mine / "line.csv").write_text(HEAD + "A,0,300,0,100,50,my_metro,dry\nB,0,300,0,100,50,nobody,dry\n")
    monkeypatch.setenv("SQUEAL_STUDY_DIR", str(tmp_path / "studies"))
    spec = {"name": "mine", "curves": str(mine / "line.csv"), "base_curve": "r150",
            "friction": {"dry_mu": 0.35, "wet_mu": 0.15}}
    from pipeline.config.loader import ConfigError

    with pytest.raises(ConfigError) as e:                        # 'nobody' is neither beside the CSV nor shipped
        read_rows(spec)
    assert "line 3, vehicle = 'nobody'" in str(e.value) and "my_metro" in str(e.value)
    (mine / "line.csv").write_text(HEAD + "A,0,300,0,100,50,my_metro,dry\n")
    rows = read_rows(spec)
    curves = line_curves(spec, rows, tmp_path / "curves")
    curve, text = curves[rows[0].key]
    assert curve.vehicle.source == mine / "my_metro.toml" and curve.source.read_text() == text
    ref = solve_curve(read_curve("r150", radius_m=300.0, cant_mm=0.0, speed_kmh=50.0))
    got = solve_curve(curve)
    assert [w.gamma_y for w in got.wheels] == [w.gamma_y for w in ref.wheels]
