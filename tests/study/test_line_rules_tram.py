"""Schall 03's tram rule applied to a tram's curves (issue 32, session 15): a vehicle file's ``category``
picks the rule; the penalties at the classes' boundaries against 16. BImSchV Anlage 2 (2014): railway
lines section 4.9 Tabelle 11 (K_L = 8 dB r < 300 m, 3 dB 300 m <= r < 500 m, 0 dB from 500 m), trams
section 5.3.2 Anmerkung 1 (K = 4 dB r < 200 m); CNOSSOS-EU's (+8 dB R <= 300 m, +5 dB to 500 m) for
both."""
from __future__ import annotations

import pytest

from pipeline.config.curve_inputs import read_vehicle
from pipeline.config.loader import ConfigError
from pipeline.study import line_classes
from pipeline.study.line_outputs import full_rows
from pipeline.study.line_rules import MISSED, OVER, rule_columns

from tests.study.conftest import ROOT

# (R m, railway K_L, tram K, CNOSSOS-EU) as the sources' tables state them
BOUNDARIES = [(199.0, 8, 4, 8), (200.0, 8, 0, 8), (299.0, 8, 0, 8), (300.0, 3, 0, 8), (300.5, 3, 0, 5),
              (499.0, 3, 0, 5), (500.0, 0, 0, 5), (500.5, 0, 0, 0)]


@pytest.mark.parametrize("R, railway, tram, cnossos", BOUNDARIES)
def test_rules_at_the_class_boundaries(R, railway, tram, cnossos):
    for category, want in (("railway", railway), ("tram", tram)):
        c = rule_columns(R, squeals=False, category=category)
        assert (c["schall03_dB"], c["cnossos_dB"]) == (want, cnossos), (R, category)
        assert c["schall03_vs_physics"] == (OVER if want else "agree: quiet")
    assert rule_columns(R, True, "tram")["schall03_vs_physics"] == ("agree: squeal, penalised" if tram else MISSED)


def test_shipped_vehicles_say_their_category():
    assert read_vehicle("tram").data["category"] == "tram"
    assert read_vehicle("c20_metro").data["category"] == "railway"      # the default: railway lines


def test_a_bad_category_is_one_line(tmp_path):
    text = (ROOT / "geometry" / "vehicles" / "tram.toml").read_text()
    (tmp_path / "tram.toml").write_text(text.replace('category = "tram"', 'category = "streetcar"'))
    with pytest.raises(ConfigError) as e:
        read_vehicle("tram", beside=tmp_path)
    msg = str(e.value)
    assert len(msg.splitlines()) == 1 and "tram.toml" in msg and "category" in msg and "streetcar" in msg
    assert "railway" in msg and "'tram'" in msg, msg


def test_line_rows_and_classes_take_the_vehicles_rule():
    """A line of both vehicles at 150 and 250 m: the rows' and the classes' Schall 03 columns are the tram's
    for the tram (4, 0 dB) and the railway's for the metro (8, 8 dB)."""
    rows = [{"radius_m": R, "squeals": 0, "vehicle": v, "friction": "dry", "note": "", "p_squeal": 0.0,
             "axles_p_squeal": 0.0, "L_pAmax_7m5": float("nan"), "L_pAmax_rolling": 80.0, "dL_squeal": 0.0}
            for v in ("tram", "c20_metro") for R in (150.0, 250.0)]
    out = full_rows(rows, {"tram": "tram", "c20_metro": "railway"})
    assert [r["schall03_dB"] for r in out] == [4.0, 0.0, 8.0, 8.0]
    assert [r["cnossos_dB"] for r in out] == [8.0] * 4
    trams = line_classes.class_rows([r for r in out if r["vehicle"] == "tram"])
    assert [(c["radius_class"], c["schall03_dB"]) for c in trams] == [("101-200", 4.0), ("201-300", 0.0)]
