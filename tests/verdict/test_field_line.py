"""The example line's section of the field statistics page (pipeline/validation/field_line.py; issue 32).

Fast (committed rows, < 1 s): the section's class numbers recomputed from the committed line rows
(docs/validation/96_field_line.csv, line.csv's columns) by a second method -- pandas' grouping over
pd.cut's radius bins and the energy sum written out here -- against the page's class table and the
module's own loop; the rows' p_squeal against scipy.stats over the climate file (test_field_statistics'
p_exceed); the rules' penalties against the published tables; STUVA's verdicts from the field's numbers."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pipeline.validation import field_line as fl
from pipeline.validation import field_statistics_doc as doc
from tests.verdict.test_field_statistics import STUVA_A, STUVA_B, p_exceed

BINS = [0.0, 50.0, 100.0, 200.0, 300.0, 500.0, np.inf]                      # STUVA's classes, (lo, hi]
NAMES = ["25-50", "51-100", "101-200", "201-300", "301-500", ">500"]


@pytest.fixture(scope="module")
def frame() -> pd.DataFrame:
    d = pd.read_csv(fl.DOCS / fl.ROWS_CSV, keep_default_na=False, na_values=["", "nan"],
                    dtype={"mu_onset": str, "mu_squeal_range": str, "note": str, "time_loop_wheels": str})
    for k in ("mu_onset", "mu_squeal_range", "note", "time_loop_wheels"):
        if k in d:
            d[k] = d[k].fillna("")
    d = d[d["note"] == ""].copy()
    d["cls"] = pd.cut(d["radius_m"], BINS, labels=NAMES, right=True).astype(str)
    can = (d["p_squeal"] > 0) & d["L_pAmax_7m5"].notna()
    d["L_train"] = np.where(can, 10 * np.log10(10 ** (d["L_pAmax_rolling"] / 10) + 10 ** (d["L_pAmax_7m5"] / 10)),
                            np.nan)
    d["dL_when"] = d["L_train"] - d["L_pAmax_rolling"]
    return d


@pytest.fixture(scope="module")
def grouped(frame) -> pd.DataFrame:
    g = frame.groupby(["cls", "friction"], sort=False)
    return pd.DataFrame({"curves": g.size(), "squeal_now": g["squeals"].sum(), "p": g["p_squeal"].mean(),
                         "axles": g["axles_p_squeal"].mean(), "dL": g["dL_squeal"].mean(),
                         "dL_when": g["dL_when"].mean(), "L_train": g["L_train"].mean(),
                         "cnossos": g["cnossos_dB"].mean(), "schall03": g["schall03_dB"].mean()})


@pytest.fixture(scope="module")
def page_rows() -> dict:
    """{(class, friction): cells} of the section's class table (12 cells a row)."""
    text = doc.fragment_text().split(fl.HEADING, 1)[1]
    out = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 12 and cells[0] in NAMES:
            out[(cells[0], cells[1])] = cells
    return out


def num(cell: str) -> float:
    return math.nan if cell == "-" else float(cell)


def test_class_table_against_pandas(grouped, page_rows):
    assert set(page_rows) == set(grouped.index)
    cols = {"curves": (2, 0), "squeal_now": (4, 0), "p": (5, 3), "axles": (6, 3), "dL": (7, 2), "dL_when": (8, 1),
            "L_train": (9, 1), "cnossos": (10, 1), "schall03": (11, 1)}
    for key, cells in page_rows.items():
        for col, (i, nd) in cols.items():
            want = grouped.loc[key, col]
            if pd.isna(want):
                assert cells[i] == "-", (key, col)
            else:
                assert num(cells[i]) == pytest.approx(want, abs=0.51 * 10 ** -nd), (key, col, cells[i])


def test_module_loop_against_pandas(grouped):
    stats = fl.class_stats(fl.committed_rows())
    assert list(stats) == [k for k in stats] and set(stats) == set(grouped.index)
    for key, s in stats.items():
        for col in grouped.columns:
            want = grouped.loc[key, col]
            assert (math.isnan(s[col]) and pd.isna(want)) or s[col] == pytest.approx(want, rel=1e-12, abs=1e-12)


def test_rows_share_of_passages_against_scipy(frame):
    for _, r in frame.iterrows():
        cell = r["mu_onset"]
        mu = math.inf if cell.startswith(">") else float(cell.lstrip("<"))
        text = r.get("mu_squeal_range", "") or (f"{mu!r}-" if math.isfinite(mu) else "")
        # the cells have 4 digits: the row's p lies within p's change over each end's rounding interval
        p, slack = 0.0, 2e-5
        for part in text.split():
            a, b = (float(x) if x else math.inf for x in part.split("-"))
            p += p_exceed("default", a) - p_exceed("default", b)
            slack += sum(abs(p_exceed("default", x - 5e-5) - p_exceed("default", x + 5e-5)) for x in (a, b)
                         if math.isfinite(x))
        assert abs(r["p_squeal"] - p) <= slack, (r["id"], r["friction"], r["p_squeal"], p, slack)
        if r["p_squeal"] > 0 and not math.isnan(r["L_pAmax_7m5"]):
            assert r["dL_squeal"] == pytest.approx(r["p_squeal"] * r["dL_when"], abs=5e-3, rel=3e-3)


def test_rules_from_the_published_tables(frame):
    """The line's vehicle is a railway vehicle (c20_metro): CNOSSOS-EU 2021/1226 and Schall 03 Tabelle 11."""
    for _, r in frame.iterrows():
        R = r["radius_m"]
        assert r["cnossos_dB"] == (8 if R <= 300 else 5 if R <= 500 else 0)
        assert r["schall03_dB"] == (8 if R < 300 else 3 if R < 500 else 0)


def test_stuva_verdicts_on_the_page(grouped):
    text = doc.fragment_text().split(fl.HEADING, 1)[1]
    conds = list(dict.fromkeys(k for _, k in grouped.index))
    for stat, ref, col in (("line: mean excess counting how often (dL, STUVA b)", STUVA_B, "dL"),
                           ("line: mean excess when squealing (dL_when, STUVA a)", STUVA_A, "dL_when")):
        rows = {c[1]: c for c in ([x.strip() for x in ln.strip().strip("|").split("|")] for ln in text.splitlines())
                if c[0] == stat}
        assert set(rows) == {c for c in ref if any((c, k) in grouped.index for k in conds)}, stat
        for c, cells in rows.items():
            want = []
            for k in conds:
                x = grouped.loc[(c, k), col] if (c, k) in grouped.index else math.nan
                want.append("n/a" if pd.isna(x) else ("agrees" if abs(x - ref[c]) <= 3.0 else "**disagrees**"))
            assert cells[3 + len(conds)] == " / ".join(want), (stat, c)
