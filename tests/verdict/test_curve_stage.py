"""The curve stage end to end on a shipped curve (slow: the stages of four wheels), and a bad curve
file's one-line message."""
import csv
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def run_cli(*args, env=None):
    e = dict(os.environ, **(env or {}))
    return subprocess.run([sys.executable, "-m", "pipeline", *args], cwd=ROOT, capture_output=True, text=True,
                          env=e, timeout=1800)


def test_bad_curve_file_is_one_line(tmp_path):
    (tmp_path / "curves").mkdir()
    text = (ROOT / "pipeline" / "curves" / "r150.toml").read_text().replace("radius_m = 150.0", "radius_m = -5.0")
    (tmp_path / "curves" / "bad.toml").write_text(text)
    build = tmp_path / "build"
    r = run_cli("curve", "--curve", str(tmp_path / "curves" / "bad.toml"), env={"SQUEAL_BUILD_DIR": str(build)})
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert "bad.toml" in lines[0] and "radius_m" in lines[0] and "-5" in lines[0]
    assert "Traceback" not in r.stderr
    assert not (build / "curves").exists()


def test_missing_curve_is_one_line(tmp_path):
    r = run_cli("curve", "--curve", "no_such_curve", env={"SQUEAL_BUILD_DIR": str(tmp_path)})
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "no_such_curve" in r.stderr


@pytest.mark.validation
def test_shipped_curve_end_to_end():
    """`python -m pipeline curve --curve r75` (the metro vehicle, R = 75 m, 31 km/h, mu = 0.35):
    four wheels in verdict.csv with the curving operating points in the case files, the inner
    leading wheel squealing at a wheel mode, confirmed by the time loop, with its WAV and the
    what-ifs (a friction threshold below the curve's mu; a damping)."""
    r = run_cli("curve", "--curve", "r75", "--no-progress")
    assert r.returncode == 0, r.stderr[-2000:]
    out = ROOT / "build" / "curves" / "r75"
    rows = {row["wheel"]: row for row in csv.DictReader(open(out / "verdict.csv"))}
    assert set(rows) == {"a1o", "a1i", "a2o", "a2i"}
    from pipeline.config.loader import load
    from pipeline.curve.curving import solve_curve
    from pipeline.config.input_schemas import CASE

    sol = {w.wheel: w for w in solve_curve("r75").wheels}
    for wid, row in rows.items():
        c = load(out / "cases" / f"{wid}.toml", CASE)
        assert c["contact"]["dy_wr"] == pytest.approx(sol[wid].dy_wr, abs=1e-12)
        assert c["kinematics"]["gamma_y"] == pytest.approx(sol[wid].gamma_y, abs=1e-15)
        assert float(row["gamma_y"]) == pytest.approx(sol[wid].gamma_y, rel=1e-5)
    for row in rows.values():                                # the time loop confirms the screen here
        assert (row["screen_sigma"] != "") == (row["squeals"] == "1"), row
    a1i = rows["a1i"]
    assert a1i["squeals"] == "1" and float(a1i["L_F2"]) >= 10.0
    assert a1i["mode"].endswith(",a)")                       # an axial wheel mode
    assert 20.0 < float(a1i["L_pA"]) < 130.0
    assert Path(a1i["wav"]).exists()
    assert 0.0 < float(a1i["mu_threshold"]) < 0.35
    assert a1i["zeta_needed"]
    md = (out / "verdict.md").read_text()
    assert "Loudest" in md and f"Listen: `{a1i['wav']}`" in md and a1i["wav"].endswith("listen_7.5m.wav")
    assert (out / "bogie.png").stat().st_size > 10_000
    import json

    doc = json.loads((out / "verdict.json").read_text())
    assert doc["__provenance__"]["kind"] == "curve-verdict" and [r["wheel"] for r in doc["payload"]] == list(rows)
