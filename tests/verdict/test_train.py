"""The whole train (pipeline/curve/train.py, issue 32/33): the vehicle files' [train] (wheel count
2 x 2 x 2 bogies x cars), a bad train key one line naming file, key, value and range; receivers from
a curve file; the rolling-noise pass-by against the line-source hand calculation from CNOSSOS-EU's
sound power; the trailing bogie equal to the leading one when nothing couples them to the car body."""
import dataclasses
import math
import shutil
from pathlib import Path

import pytest

from pipeline.config import cnossos
from pipeline.config.curve_inputs import read_curve
from pipeline.config.loader import ConfigError
from pipeline.curve import train
from solvers.radiation import passby_train as pt

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("curve,cars", [("r75", 6), ("y25_r300", 20)])
def test_wheel_count(curve, cars):
    t = read_curve(curve).vehicle.train
    assert t.cars == cars
    x = t.axle_positions_m
    assert 2 * len(x) == 2 * 2 * 2 * cars                     # wheels: 2 per axle, 2 axles per bogie, 2 bogies
    assert x[-1] == pytest.approx((cars - 1) * t.car_length_m + t.bogie_spacing_m + t.wheelbase_m)
    assert sorted(x) == list(x) and len(set(x)) == len(x)


def _user_files(tmp_path, vehicle_edit, curve_edit=lambda s: s):
    v = (ROOT / "geometry/vehicles/c20_metro.toml").read_text()
    (tmp_path / "c20_metro.toml").write_text(vehicle_edit(v))
    c = (ROOT / "pipeline/curves/r75.toml").read_text()
    (tmp_path / "mine.toml").write_text(curve_edit(c.replace('name = "r75"', 'name = "mine"')))
    return tmp_path / "mine.toml"


@pytest.mark.parametrize("old,new,key,value", [
    ("cars = 6 ", "cars = 0 ", "train.cars", "0"),
    ("car_length_m = 23.25", "car_length_m = 11.0", "train.car_length_m", "11"),
    ("car_length_m = 23.25", "car_length_m = 230.0", "train.car_length_m", "230"),
])
def test_bad_train_key_is_one_line(tmp_path, old, new, key, value):
    path = _user_files(tmp_path, lambda s: s.replace(old, new))
    with pytest.raises(ConfigError) as e:
        read_curve(path)
    msg = str(e.value)
    assert "\n" not in msg.strip(), msg
    assert "c20_metro.toml" in msg and key in msg and value in msg and ("60" in msg or ">=" in msg), msg


def test_receivers_from_the_curve_file(tmp_path):
    path = _user_files(tmp_path, lambda s: s, lambda s: s.replace("speed_kmh = 31.0", "speed_kmh = 31.0\n"
                                                                  "receivers_m = [7.5, 25.0]"))
    c = read_curve(path)
    assert c.data["receivers_m"] == [7.5, 25.0]
    assert read_curve("r75").data["receivers_m"] == [7.5]     # the default
    levels = train.passby(c, [], 0.39, c.data["receivers_m"])
    assert [lv["receiver_m"] for lv in levels] == [7.5, 25.0]
    assert all(lv["dL_squeal"] == 0.0 and lv["L_pAmax_train"] == lv["L_pAmax_rolling"] for lv in levels)
    assert levels[1]["L_pAmax_rolling"] < levels[0]["L_pAmax_rolling"]
    bad = _user_files(tmp_path, lambda s: s, lambda s: s.replace("speed_kmh = 31.0", "speed_kmh = 31.0\n"
                                                                 "receivers_m = [0.5]"))
    with pytest.raises(ConfigError) as e:
        read_curve(bad)
    assert "receivers_m" in str(e.value) and "0.5" in str(e.value) and "\n" not in str(e.value).strip()


def test_rolling_passby_against_the_line_source_hand_calculation():
    """L_pAeq over T_p of a train of rolling-noise point sources (CNOSSOS-EU's L_W of one car, its
    4 axles) = the line source's L_W' - 10 lg(4 rho) + 10 lg(0.505) (dipole), W' = W_car / car length."""
    c = read_curve("r75")
    f, L_W = cnossos.rolling_power_bands(
        cnossos.load_tables().vehicle_from_refs(roughness="5", contact="4", transfer="4", n_axles=4.0), {
            "transfer": "4", "rail_roughness": "4"}, 31.0)
    L_WA_car = pt.a_weighted_sum(f, L_W)                        # nominal centres: A(f) within 0.01 dB
    rho = math.hypot(7.5, train.RECEIVER_HEIGHT - 0.5)
    hand = L_WA_car - 10 * math.log10(c.vehicle.train.car_length_m) - 10 * math.log10(4 * rho) + 10 * math.log10(0.505)
    lv = train.passby(c, [], 0.39, [7.5])[0]
    assert lv["L_pAeq_rolling"] == pytest.approx(hand, abs=0.02)
    assert 60.0 < lv["L_pAmax_rolling"] < 80.0                  # a metro at 31 km/h (ISO 3095 records: 65-75)


def test_trailing_bogie_is_the_leading_one_without_secondary_yaw():
    """The trailing bogie differs from the leading one only through the car body's chord (+-s/2R) felt by
    the secondary yaw stiffness: with that stiffness 0 both bogies solve to the same state."""
    from solvers.curving import solve
    from solvers.curving.summary import wheel_points

    c, v, veh, trk, prof, law, names = train.build_problem("r150")
    free = dataclasses.replace(veh, secondary_yaw=0.0)
    lead = wheel_points(solve(prof, free, trk, law), law.mu)
    trail = wheel_points(solve(prof, dataclasses.replace(free, bogie_spacing=-free.bogie_spacing), trk, law), law.mu)
    for a, b in zip(lead, trail):
        assert a["angle_of_attack"] == pytest.approx(b["angle_of_attack"], abs=1e-9)


def test_wheel_case_passby_is_the_vehicles_train():
    """A curve wheel's case: the listen stage's pass-by is that wheel in every car of the vehicle's train
    (before: two wheels 12.5 m apart whatever the vehicle)."""
    from pipeline.curve.cases import case_dict
    from tests.verdict.test_cases import POINT

    pb = case_dict(read_curve("r75"), POINT)["listener"]["passby"]
    assert pb == {"n_bogies": 6, "bogie_spacing": 23.25}
    pb = case_dict(read_curve("y25_r300"), POINT)["listener"]["passby"]
    assert pb == {"n_bogies": 20, "bogie_spacing": 14.0}
