"""Vehicle and curve files: validated like every input (one line per problem naming the file,
the key, the value and what is allowed; nothing solved), read into the nouns Curve and Vehicle
(``pipeline.config.curve_inputs``), and the command line's errors."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from pipeline.config import curve_inputs as inputs
from pipeline.curve import curving
from pipeline.store import paths
from pipeline.config.loader import ConfigError

ROOT = Path(__file__).resolve().parents[2]


def _write(folder: Path, name: str, text: str) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / f"{name}.toml").write_text(text)


@pytest.fixture
def dirs(tmp_path):
    """A user's project folder outside the repository: curves/ (and vehicles beside them when a test puts one)."""
    (tmp_path / "curves").mkdir()
    return tmp_path


def test_shipped_files_validate():
    for v in inputs.available_vehicles():
        assert inputs.read_vehicle(v).name == v
    for c in inputs.available_curves():
        curve = inputs.read_curve(c)
        assert curve.name == c and curve.vehicle.source == ROOT / "geometry" / "vehicles" / f"{curve.vehicle.name}.toml"


def test_curve_noun_units():
    """r75.toml: 75 m, 100 mm cant, 31 km/h, mu = 0.35, the C20 metro (65 kN per wheel, 2.0 m wheelbase)."""
    c = inputs.read_curve("r75")
    assert (c.radius, c.cant, c.speed, c.gauge) == (75.0, 0.1, 31.0 / 3.6, 1.435)
    assert (c.friction.law, c.friction.mu, c.friction.coulomb_mu) == ("coulomb", 0.35, 0.35)
    v = c.vehicle
    assert v.wheel_load_N == 65e3 and v.bogie.wheelbase_m == 2.0 and v.train.bogie_spacing_m == 10.5
    first_car = (0.0, 2.0, 10.5, 12.5)           # a car's 4 axles; the next car 23.25 m on (6 cars)
    assert v.train.axle_positions_m[:4] == first_car and len(v.train.axle_positions_m) == 4 * 6
    assert v.train.axle_positions_m[4:8] == tuple(x + 23.25 for x in first_car)
    assert v.bogie.wheels == ("a1o", "a1i", "a2o", "a2i")


def test_a_name_is_shipped_a_path_is_a_file(dirs):
    assert inputs.curve_path("r150") == ROOT / "pipeline" / "curves" / "r150.toml"
    assert inputs.curve_path("x/r150") == paths.Path("x/r150") and inputs.curve_path("my.toml") == paths.Path("my.toml")
    text = (ROOT / "pipeline" / "curves" / "r150.toml").read_text()
    _write(dirs / "curves", "mine", text)
    c = inputs.read_curve(str(dirs / "curves" / "mine.toml"))
    assert c.name == "mine" and c.source == dirs / "curves" / "mine.toml" and c.radius_m == 150.0
    # a vehicle beside the curve file is taken before the shipped one of that name
    veh = (ROOT / "geometry" / "vehicles" / "c20_metro.toml").read_text().replace("wheel_load_kN = 65.0",
                                                                                  "wheel_load_kN = 70.0")
    _write(dirs / "curves", "c20_metro", veh)
    c = inputs.read_curve(dirs / "curves" / "mine.toml")
    assert c.vehicle.source == dirs / "curves" / "c20_metro.toml" and c.vehicle.wheel_load_N == 70e3
    with pytest.raises(ConfigError, match="no such curve file"):
        inputs.read_curve(str(dirs / "curves" / "none.toml"))


def test_radius_typed_in_km_is_named(dirs):
    _write(dirs / "curves", "bad", 'name = "bad"\nvehicle = "c20_metro"\nradius_m = 0.15\nspeed_kmh = 50\n'
                                   '[friction]\nmu = 0.35\n')
    with pytest.raises(ConfigError) as e:
        inputs.read_curve(dirs / "curves" / "bad.toml")
    msg = str(e.value)
    assert "bad.toml" in msg and "radius_m = 0.15" in msg and "15 <= value <= 20000" in msg


def test_unknown_key_and_missing_mu(dirs):
    _write(dirs / "curves", "bad", 'name = "bad"\nvehicle = "c20_metro"\nradius_m = 150\nspeed_kmh = 50\n'
                                   'speed = 13.9\n[friction]\nlaw = "coulomb"\n')
    with pytest.raises(ConfigError) as e:
        inputs.read_curve(dirs / "curves" / "bad.toml")
    assert "speed = 13.9" in str(e.value)
    # the [friction] table is a case file's (issue 33): its law's keys are checked once the file's keys are known
    _write(dirs / "curves", "bad", 'name = "bad"\nvehicle = "c20_metro"\nradius_m = 150\nspeed_kmh = 50\n'
                                   '[friction]\nlaw = "coulomb"\n')
    with pytest.raises(ConfigError) as e:
        inputs.read_curve(dirs / "curves" / "bad.toml")
    assert "friction.mu" in str(e.value) and "required key is missing for friction law 'coulomb'" in str(e.value)


def test_both_loads_given_is_an_error(dirs):
    text = (ROOT / "geometry" / "vehicles" / "c20_metro.toml").read_text().replace(
        "wheel_load_kN = 65.0", "wheel_load_kN = 65.0\naxle_load_kN = 130.0")
    _write(dirs / "curves", "twice", text.replace('name = "c20_metro"', 'name = "twice"'))
    with pytest.raises(ConfigError) as e:
        inputs.read_vehicle("twice", dirs / "curves")
    assert "exactly one of load.wheel_load_kN and load.axle_load_kN" in str(e.value)


def test_command_line_error_is_one_line(dirs):
    _write(dirs / "curves", "bad", 'name = "bad"\nvehicle = "nope"\nradius_m = 150\nspeed_kmh = 50\n'
                                   '[friction]\nmu = 0.35\n')
    env = {"PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1"}
    r = subprocess.run([sys.executable, "-m", "pipeline.curve.curving", "--curve", str(dirs / "curves" / "bad.toml")],
                       cwd=ROOT, env=env, capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "no such vehicle 'nope'" in r.stderr and "Traceback" not in r.stderr
    assert "bad.toml" in r.stderr and "vehicle = 'nope'" in r.stderr          # the file and key that asked


def test_overrides_are_validated_and_change_the_curve():
    c = inputs.read_curve("r150", radius_m=300.0, mu=0.2)
    assert c.radius_m == 300.0 and c.friction.mu == 0.2 and c.vehicle.name == "c20_metro" and c.name == "r150"
    assert inputs.read_curve(c, speed_kmh=30.0).friction.mu == 0.2
    with pytest.raises(ConfigError) as e:
        inputs.read_curve("r150", radius_m=3.0)
    assert "radius_m = 3.0" in str(e.value) and "with radius_m = 3.0" in str(e.value)


def test_case_fields_validate_as_a_case():
    """A curve wheel's case-file keys plus name and time make a valid case (pipeline.config.input_schemas.CASE)."""
    from pipeline.config.loader import validate
    from pipeline.config.input_schemas import CASE

    w = curving.solve_curve("r150").wheels[1]
    case = dict(w.case_fields(), name="r150/a1i", time={"dt": 36e-6, "duration": 1.0})
    out = validate(case, CASE, "r150/a1i")
    assert out["contact"]["dy_wr"] == pytest.approx(w.dy_wr) and out["kinematics"]["gamma_y"] < 0
