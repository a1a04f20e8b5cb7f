"""The pipeline with another wheel through the CLI: a copy of the default
case with the straight wheel stops every stage with a one-line message
naming the case, the offset and why (flange contact), never a traceback;
the same wheel at a tread offset runs the contact stage."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def case_copy(tmp_path, name, dy=None):
    text = (ROOT / "pipeline" / "cases" / "default.toml").read_text()
    text = text.replace('name = "default"', f'name = "{name}"').replace('wheel = "c20"', 'wheel = "straight"')
    if dy is not None:
        text = text.replace("dy_wr = -0.015", f"dy_wr = {dy}")
    cases = tmp_path / "cases"
    cases.mkdir(exist_ok=True)
    (cases / f"{name}.toml").write_text(text)
    return dict(os.environ, SQUEAL_CASE_DIR=str(cases), SQUEAL_BUILD_DIR=str(tmp_path / "build"))


@pytest.mark.parametrize("stage", ["contact", "greens", "radiate"])
def test_straight_wheel_default_copy_stops_with_one_line(tmp_path, stage):
    env = case_copy(tmp_path, "straight15")
    r = subprocess.run([sys.executable, "-m", "pipeline", stage, "--case", "straight15"], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 2, r.stderr
    err = r.stderr.strip()
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    assert "case 'straight15', dy_WR = -15.0 mm" in err and "flange contact" in err
    assert not (tmp_path / "build" / "cases" / "straight15").exists() or not any(
        (tmp_path / "build" / "cases" / "straight15").iterdir())


def test_straight_wheel_on_the_tread_runs_the_contact_stage(tmp_path):
    env = case_copy(tmp_path, "straight00", dy=0.0)
    r = subprocess.run([sys.executable, "-m", "pipeline", "contact", "--case", "straight00", "-q"], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    a = np.load(tmp_path / "build" / "cases" / "straight00" / "contact.npz")
    assert abs(float(a["y_wheel"])) < 0.01 and float(a["patch_area"]) > 0
