"""A curve's wheel as an ordinary case file: written where paths.case_file finds it, valid
against the case schema with the operating point's values; an operating point outside a case's
range is one line naming the curve file and the key."""
import pytest

from pipeline.store import paths
from pipeline.config.loader import ConfigError, load
from pipeline.config.input_schemas import CASE
from pipeline.curve.cases import wheel_case, write_case
from pipeline.curve.operating import CurveInfo, WheelPoint

INFO = CurveInfo(name="r150", radius=150.0, speed_kmh=40.0, cant=0.05, gauge=1.445, wheel="c20", rail="bv50",
                 vehicle="metro", friction={"mu": 0.35}, wheelbase=2.2, contact_spacing=1.5,
                 sources=("pipeline/curves/r150.toml",))
POINT = WheelPoint("a1i", -0.0123, 0.0081, 0.0012, -0.0093, 0.4, 0.029, 0.011, -0.09, 61234.5, 1)


def test_wheel_case_round_trip(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    case = wheel_case(INFO, POINT)
    path = write_case(case)
    assert path == str(paths.case_file("r150/a1i")) == str(tmp_path / "curves/r150/cases/a1i.toml")
    c = load(path, CASE)
    assert c["contact"]["dy_wr"] == pytest.approx(-0.0123, abs=1e-12)
    assert c["kinematics"]["gamma_y"] == pytest.approx(-0.0093, abs=1e-15)
    assert c["kinematics"]["gamma_x"] == pytest.approx(0.0012, abs=1e-15)
    assert c["kinematics"]["speed"] == pytest.approx(40.0 / 3.6)
    assert c["loading"]["preload"] == pytest.approx(61234.5)
    assert c["friction"]["mu"] == 0.35 and c["wheel"] == "c20" and c["rail"] == "bv50"
    mtime = (tmp_path / "curves/r150/cases/a1i.toml").stat().st_mtime_ns
    write_case(case)                         # unchanged: not rewritten (Make's timestamps)
    assert (tmp_path / "curves/r150/cases/a1i.toml").stat().st_mtime_ns == mtime


def test_operating_point_out_of_range_is_one_line(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    with pytest.raises(ConfigError) as e:
        wheel_case(INFO, POINT._replace(dy_wr=0.045))
    msg = str(e.value)
    assert "pipeline/curves/r150.toml" in msg and "dy_wr = 0.045" in msg and "a1i" in msg and "\n" not in msg
    assert not (tmp_path / "curves").exists()
