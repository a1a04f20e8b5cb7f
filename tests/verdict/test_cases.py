"""A curve's wheel as a resolved case built in memory (issue 34): the same ResolvedCase as reading its
written case file back (so the stages see what ``make CASE=<curve>/<wheel>`` would), the record written
where paths.case_file finds it, and an operating point outside a case's range one line naming the
curve file and the key."""
import dataclasses

import pytest

from pipeline.store import paths
from pipeline.config.case import resolve_case
from pipeline.config.curve_inputs import read_curve
from pipeline.config.loader import ConfigError, load
from pipeline.config.input_schemas import CASE
from pipeline.config.nouns import WheelOperatingPoint
from pipeline.curve.cases import wheel_case, write_case

NAN = float("nan")
CURVE = read_curve("r150")
POINT = WheelOperatingPoint("a1i", 1, "inner", -0.0123, -0.0056667, 0.0081, 0.0012, -0.0093, 0.4, 0.029, 0.011,
                            -0.09, 0.39, 61234.5, 5e3, 60123.0, 1e3, -2e3, 0.1, 6e-3, 4e-3, 1, NAN, NAN, NAN, NAN,
                            NAN, NAN, 50 / 3.6, 0.35, "coulomb", "c20", "bv50", None, None)


def test_wheel_case_in_memory_equals_its_record(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    rc = wheel_case(CURVE, POINT)
    assert rc.name == "r150/a1i" and rc.friction is CURVE.friction        # resolved once, with the curve
    c = rc.case
    assert c["contact"]["dy_wr"] == -0.0123 and c["kinematics"]["gamma_y"] == -0.0093
    assert c["kinematics"]["gamma_x"] == 0.0012 and c["kinematics"]["spin"] == 0.4
    assert c["kinematics"]["speed"] == 50.0 / 3.6 and c["loading"]["preload"] == 60123.0   # the tread contact's N
    assert c["friction"]["mu"] == 0.35 and c["wheel"] == "c20" and c["rail"] == "bv50"
    path = write_case(rc)
    assert path == str(paths.case_file("r150/a1i")) == str(tmp_path / "curves/r150/cases/a1i.toml")
    assert load(path, CASE) == c                                          # the record is what ran
    back = resolve_case("r150/a1i")                                       # read back as `make CASE=...` would
    assert back.case == c and back.config == rc.config and back.friction == rc.friction
    assert back.contact.y_wheel == rc.contact.y_wheel and back.contact.y_rail == rc.contact.y_rail
    mtime = (tmp_path / "curves/r150/cases/a1i.toml").stat().st_mtime_ns
    write_case(rc)                           # unchanged: not rewritten (Make's timestamps)
    assert (tmp_path / "curves/r150/cases/a1i.toml").stat().st_mtime_ns == mtime


def test_operating_point_out_of_range_is_one_line(tmp_path, monkeypatch):
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    with pytest.raises(ConfigError) as e:
        wheel_case(CURVE, dataclasses.replace(POINT, dy_wr=0.045))
    msg = str(e.value)
    assert "pipeline/curves/r150.toml" in msg and "dy_wr = 0.045" in msg and "a1i" in msg and "\n" not in msg
    assert not (tmp_path / "curves").exists()


def test_what_if_coefficients_are_the_contacts_not_its_labels():
    """The what-ifs' Coulomb curves by coefficient: contact.npz's ``mu_values`` of its Coulomb curves
    (``rf_law``), to the last bit -- a label holds 10 digits (0.1234567891 for 0.123456789123)."""
    import numpy as np

    from pipeline.caches.friction_curves import curve_arrays
    from pipeline.config.nouns import FrictionLaw
    from pipeline.curve.what_ifs import CaseModels

    curve = {"s": np.zeros(3), "mu_rf": np.zeros(3), "slope": np.zeros(3), "gamma_sat": 0.0}
    laws = [FrictionLaw.coulomb(0.123456789123), FrictionLaw.of("exponential", {"fkin": 0.14, "fexp1": 0.19,
                                                                             "sabsh1": 1250.0})]
    con = curve_arrays([(f.label, f.mu, f.law, curve) for f in laws])
    assert con["rf_label"][0] == "coulomb(mu=0.1234567891)"
    ctx = type("Ctx", (), {"contact": con, "spin": 0.0, "friction": laws[0]})()
    assert CaseModels.of_context(ctx).mus.tolist() == [0.123456789123]
