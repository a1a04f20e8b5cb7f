"""The pipeline with another wheel through the CLI: a copy of the default
case with the straight wheel takes its contact point from its own profiles
(the contact stage runs), and the greens stage stops with a one-line message
naming the case, the offset and why (the rail model has no receptance at
that rail point); a copy moved toward the field side into flange contact
stops every stage with a one-line message, never a traceback."""
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


def run(stage, case, env, *extra):
    return subprocess.run([sys.executable, "-m", "pipeline", stage, "--case", case, *extra], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=600)


def one_line(r) -> str:
    assert r.returncode == 2, r.stderr
    err = r.stderr.strip()
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    return err


def test_straight_wheel_default_copy_contact_from_its_profiles_then_greens_asks_for_the_wheel_only(tmp_path):
    """The straight wheel's parametric cone on the worn BV50 at dy_WR = -15 mm:
    its own rigid contact (an independent check: a 1:40 cone touches where the
    inclined head's slope is 1:40, y^W = Y - (c + dy_WR)), not the C20's +32 mm.  Its rail
    point is off the rail file's contact.y list: greens no longer stops for it (issue 25, the rail
    at any running-surface point); without the straight wheel's modes it asks for those, in one line."""
    from geometry.contact_point import TrackRail
    from pipeline.config.case_profiles import read_profile

    env = case_copy(tmp_path, "straight15")
    r = run("contact", "straight15", env, "-q")
    assert r.returncode == 0, r.stderr
    a = np.load(tmp_path / "build" / "cases" / "straight15" / "contact.npz")
    rail = TrackRail(read_profile("bv50_worn")[0], 1 / 30)
    Y = np.linspace(-0.02, 0.02, 40001)
    y_cone = Y[np.argmin(np.abs(rail.slope(Y) - 0.025))] - (-17 / 3e3 - 0.015)
    assert float(a["y_wheel"]) == pytest.approx(y_cone, abs=0.3e-3)
    assert abs(float(a["y_wheel"]) - 0.032) > 0.01 and float(a["patch_area"]) > 0
    err = one_line(run("greens", "straight15", env))
    assert "make modes WHEEL=straight" in err and "contact.y" not in err


@pytest.mark.parametrize("stage", ["contact", "greens", "radiate"])
def test_straight_wheel_in_flange_contact_stops_with_one_line(tmp_path, stage):
    env = case_copy(tmp_path, "straight25", dy=0.025)
    err = one_line(run(stage, "straight25", env))
    assert "case 'straight25', dy_WR = +25.0 mm" in err and "flange contact" in err
    assert not (tmp_path / "build" / "cases" / "straight25").exists() or not any(
        (tmp_path / "build" / "cases" / "straight25").iterdir())
