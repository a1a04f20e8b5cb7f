"""The line study's climate columns (issue 32, ``pipeline.study.line_risk``, ``line_classes``): a line
row's risk equals the curve stage's own verdict of the same curve (r75: its wheels' contact and greens
stages, ``risk.add_risk`` with the full onset scan and level tables), the fast scan's cut, the radius
classes recomputed by a second method, and
the rules' penalties at the classes' boundaries as the texts give them."""
import math

import numpy as np
import pytest

from pipeline.study import line_classes as lc
from pipeline.study.line_rules import cnossos_penalty, schall03_penalty


def _line_risk(curve):
    from pipeline.curve.screen_first import run_screen_first
    from pipeline.study.line_risk import risk_columns

    return risk_columns(curve, run_screen_first(curve, write=False, figures=False)["rows"])


@pytest.fixture(scope="module")
def stage_r75():
    """The curve stage's risk of r75 (``stage.run_stages`` contact and greens, ``risk.add_risk``)."""
    from pipeline.config.case import given
    from pipeline.curve import risk
    from pipeline.curve.cases import wheel_case
    from pipeline.curve.stage import operating_row, run_stages, solve

    sol = solve("r75")
    cases = [wheel_case(sol.curve, p) for p in sol.wheels]
    rows = [operating_row(p) for p in sol.wheels]
    with given(cases):
        for rc in cases:
            run_stages(rc.name, ["contact", "greens"])
        _, shares = risk.add_risk(sol.curve, sol.wheels, rows)
    return sol.curve, rows, shares


def test_r75_row_is_the_curve_stages(stage_r75):
    """p_squeal, axles, the worst wheel's onset and the loudest median level: the curve stage's numbers."""
    curve, rows, shares = stage_r75
    got = _line_risk(curve)
    assert got["climate"] == "default"
    assert got["p_squeal"] == pytest.approx(shares["passages"], rel=1e-12, abs=1e-15)
    assert got["axles_p_squeal"] == pytest.approx(shares["axles"], rel=1e-12, abs=1e-15)
    worst = min((r for r in rows if r["mu_onset"][:1] not in "<>"), key=lambda r: float(r["mu_onset"]))
    assert (got["wheel_onset"], got["mu_onset"], got["mode_onset"]) == (worst["wheel"], worst["mu_onset"],
                                                                        worst["mode_onset"])
    assert got["f_onset"] == pytest.approx(worst["f_onset"], rel=1e-12)
    loud = max(r["L_pAmax_7m5"] for r in rows if math.isfinite(r["L_pAmax_7m5"]))
    assert got["L_pAmax_7m5"] == pytest.approx(loud, rel=1e-9)
    # r75 squeals in part of the default climate (onset 0.337 < 0.35, the dry condition's top)
    assert 0.0 < got["p_squeal"] < 0.1 and got["dL_squeal"] > 0.0
    # the excess: STUVA's method with the frequency, from the energy sum of rolling and squeal levels
    both = 10 * math.log10(10 ** (got["L_pAmax_rolling"] / 10) + 10 ** (loud / 10))
    assert got["dL_squeal"] == pytest.approx(got["p_squeal"] * (both - got["L_pAmax_rolling"]), rel=1e-9)


def test_fast_scan_stops_above_the_climate():
    """The onset scan's cut: the first grid level at or above the climate's highest level (default: dry to
    0.35 -> 0.4), and the level steps cut after the first at or above the climate's top (0.35)."""
    from pipeline.curve.risk import curve_climate
    from pipeline.config.curve_inputs import read_curve
    from pipeline.study.line_risk import level_steps, top_level

    assert top_level(curve_climate(read_curve("r75"))) == pytest.approx(0.4, abs=1e-12)
    assert level_steps(0.3374, 0.35) == (0.02,)
    assert level_steps(0.2, 0.35) == (0.02, 0.05, 0.15)
    assert level_steps(0.1, 0.35) == (0.02, 0.05, 0.15, 0.3)


def test_rules_at_class_boundaries():
    """CNOSSOS-EU (Directive (EU) 2015/996 Annex II 2.3.2 as amended): 8 dB for R <= 300 m, 5 dB for
    300 < R <= 500 m; Schall 03 (2014) Tabelle 11: 8 dB for R < 300 m, 3 dB for 300 <= R < 500 m."""
    for R, c, s in ((25, 8, 8), (299.9, 8, 8), (300, 8, 3), (300.1, 5, 3), (499.9, 5, 3), (500, 5, 0),
                    (500.1, 0, 0), (1000, 0, 0)):
        assert (cnossos_penalty(R), schall03_penalty(R)) == (c, s), R
    assert [lc.radius_class(R) for R in (20, 25, 50, 50.5, 100, 101, 200, 300, 300.5, 500, 501)] == \
        ["< 25", "25-50", "25-50", "51-100", "51-100", "101-200", "101-200", "201-300", "301-500", "301-500", "> 500"]


def test_classes_by_a_second_method():
    """class_rows against a recomputation with numpy (np.digitize on the class edges, masks)."""
    rng = np.random.default_rng(32)
    n = 80
    R = rng.uniform(25, 700, n)
    R[:6] = [50, 100, 200, 300, 500, 40]
    rows = []
    for i in range(n):
        p = float(rng.choice([0.0, rng.uniform(0, 1)]))
        rows.append({"radius_m": float(R[i]), "friction": ["dry", "wet"][i % 2], "squeals": int(rng.random() < 0.3),
                     "p_squeal": p, "axles_p_squeal": p / 2, "L_pAmax_7m5": float(rng.uniform(70, 100)) if p else math.nan,
                     "L_pAmax_rolling": float(rng.uniform(60, 80)), "dL_squeal": float(rng.uniform(0, 5)) * p,
                     "cnossos_dB": cnossos_penalty(R[i]), "schall03_dB": schall03_penalty(R[i]), "note": ""})
    rows.append(dict(rows[0], note="no steady curving state", p_squeal=math.nan))   # left out
    got = {(x["radius_class"], x["friction"]): x for x in lc.class_rows(rows)}
    k = np.digitize(R, [50.0, 100.0, 200.0, 300.0, 500.0], right=True)          # 0: 25-50 ... 5: > 500
    labels = ["25-50", "51-100", "101-200", "201-300", "301-500", "> 500"]
    fr = np.array([r["friction"] for r in rows[:n]])
    P = np.array([r["p_squeal"] for r in rows[:n]])
    L = np.array([r["L_pAmax_7m5"] for r in rows[:n]])
    D = np.array([r["dL_squeal"] for r in rows[:n]])
    C = np.array([r["cnossos_dB"] for r in rows[:n]])
    seen = 0
    for j, lab in enumerate(labels):
        for f in ("dry", "wet"):
            m = (k == j) & (fr == f)
            if not m.any():
                continue
            seen += 1
            g = got[(lab, f)]
            assert g["curves"] == m.sum()
            assert g["p_squeal"] == pytest.approx(P[m].mean(), rel=1e-12)
            assert g["dL_squeal"] == pytest.approx(D[m].mean(), rel=1e-12, abs=1e-15)
            assert g["cnossos_dB"] == pytest.approx(C[m].mean(), rel=1e-12)
            can = L[m & (P > 0)]
            assert (math.isnan(g["L_pAmax_7m5"]) and can.size == 0) or g["L_pAmax_7m5"] == pytest.approx(np.median(can))
    assert seen == len(got)
