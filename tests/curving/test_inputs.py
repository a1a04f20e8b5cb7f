"""Vehicle and curve files: validated like every input (one line per problem naming the file,
the key, the value and what is allowed; nothing solved), and the command line's errors."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from pipeline.curve import curving
from pipeline.store import paths
from pipeline.config.loader import ConfigError

ROOT = Path(__file__).resolve().parents[2]


def _write(folder: Path, name: str, text: str) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.toml").write_text(text)


@pytest.fixture
def dirs(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_CURVE_DIR", str(tmp_path / "curves"))
    monkeypatch.setenv("SQUEAL_VEHICLE_DIR", str(tmp_path / "vehicles"))
    for v in paths.available(ROOT / "geometry" / "vehicles"):
        _write(tmp_path / "vehicles", v, (ROOT / "geometry" / "vehicles" / f"{v}.toml").read_text())
    return tmp_path


def test_shipped_files_validate():
    for v in curving.available_vehicles():
        curving.load_vehicle(v)
    for c in curving.available_curves():
        assert curving.load_vehicle(curving.load_curve(c)["vehicle"])


def test_radius_typed_in_km_is_named(dirs):
    _write(dirs / "curves", "bad", 'name = "bad"\nvehicle = "c20_metro"\nradius_m = 0.15\nspeed_kmh = 50\n'
                                   '[friction]\nmu = 0.35\n')
    with pytest.raises(ConfigError) as e:
        curving.load_curve("bad")
    msg = str(e.value)
    assert "bad.toml" in msg and "radius_m = 0.15" in msg and "15 <= value <= 20000" in msg


def test_unknown_key_and_missing_mu(dirs):
    _write(dirs / "curves", "bad", 'name = "bad"\nvehicle = "c20_metro"\nradius_m = 150\nspeed_kmh = 50\n'
                                   'speed = 13.9\n[friction]\nlaw = "coulomb"\n')
    with pytest.raises(ConfigError) as e:
        curving.load_curve("bad")
    assert "speed = 13.9" in str(e.value) and "friction.mu" in str(e.value)


def test_both_loads_given_is_an_error(dirs):
    text = (ROOT / "geometry" / "vehicles" / "c20_metro.toml").read_text().replace(
        "wheel_load_kN = 65.0", "wheel_load_kN = 65.0\naxle_load_kN = 130.0")
    _write(dirs / "vehicles", "twice", text.replace('name = "c20_metro"', 'name = "twice"'))
    with pytest.raises(ConfigError) as e:
        curving.load_vehicle("twice")
    assert "exactly one of load.wheel_load_kN and load.axle_load_kN" in str(e.value)


def test_command_line_error_is_one_line(dirs):
    _write(dirs / "curves", "bad", 'name = "bad"\nvehicle = "nope"\nradius_m = 150\nspeed_kmh = 50\n'
                                   '[friction]\nmu = 0.35\n')
    env = {"SQUEAL_CURVE_DIR": str(dirs / "curves"), "SQUEAL_VEHICLE_DIR": str(dirs / "vehicles"),
           "PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1"}
    r = subprocess.run([sys.executable, "-m", "pipeline.curve.curving", "--curve", "bad"], cwd=ROOT, env=env,
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "Traceback" not in r.stderr
    assert "bad.toml: vehicle = 'nope': no such vehicle file" in r.stderr


def test_overrides_are_validated_and_change_the_curve():
    c = curving.load_curve("r150", radius_m=300.0, mu=0.2)
    assert c["radius_m"] == 300.0 and c["friction"]["mu"] == 0.2 and c["vehicle"] == "c20_metro"
    with pytest.raises(ConfigError) as e:
        curving.load_curve("r150", radius_m=3.0)
    assert "radius_m = 3.0" in str(e.value) and "with radius_m = 3.0" in str(e.value)


def test_case_fields_validate_as_a_case():
    """A curve wheel's case-file keys plus name and time make a valid case (pipeline.config.input_schemas.CASE)."""
    from pipeline.config.loader import validate
    from pipeline.config.input_schemas import CASE

    w = curving.solve_curve("r150").wheels[1]
    case = dict(w.case_fields(), name="r150/a1i", time={"dt": 36e-6, "duration": 1.0})
    out = validate(case, CASE, "r150/a1i")
    assert out["contact"]["dy_wr"] == pytest.approx(w.dy_wr) and out["kinematics"]["gamma_y"] < 0
