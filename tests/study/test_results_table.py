"""pipeline/results_table.py: rows round-trip exactly, a torn last line (a kill in the middle of
a write) and stale or repeated rows are dropped on open, a header of other columns is refused."""
import math

import pytest

from pipeline.store.artifacts import ArtifactError
from pipeline.study.results_table import ResultsTable

COLS = {"x": float, "n": int, "label": str}


def _row(k, x, inputs="h1"):
    return {"key": k, "inputs": inputs, "x": x, "n": 3, "label": f"a,b \"{k}\""}


def test_rows_round_trip_exactly(tmp_path):
    t = ResultsTable(tmp_path / "t.csv", COLS)
    assert t.open() == {}
    vals = [0.1 + 0.2, -1e-300, math.pi * 1e7, float("nan"), float("-inf")]
    for i, x in enumerate(vals):
        t.append(_row(f"k{i}", x))
    u = ResultsTable(tmp_path / "t.csv", COLS)
    rows = u.open({"h1"})
    assert list(rows) == [f"k{i}" for i in range(len(vals))]
    for i, x in enumerate(vals):
        got = rows[f"k{i}"]["x"]
        assert (math.isnan(got) and math.isnan(x)) or got == x          # bit-exact, repr precision
        assert rows[f"k{i}"]["n"] == 3 and rows[f"k{i}"]["label"] == f"a,b \"k{i}\""
    with pytest.raises(KeyError, match="already in the table"):
        u.append(_row("k0", 1.0))
    with pytest.raises(KeyError, match="columns the table does not"):
        u.append(_row("k9", 1.0) | {"y": 2})


def test_torn_stale_and_repeated_rows_are_dropped(tmp_path):
    p = tmp_path / "t.csv"
    t = ResultsTable(p, COLS)
    t.open()
    t.append(_row("a", 1.0))
    t.append(_row("b", 2.0, inputs="old"))
    whole = p.read_bytes()
    # a repeated key (e.g. two runs appending the same case) and a torn last line
    p.write_bytes(whole + b'a,h1,5.0,3,x\n' + b'c,h1,3.0,3,"unterminated')
    u = ResultsTable(p, COLS)
    rows = u.open({"h1"})
    assert list(rows) == ["a"] and rows["a"]["x"] == 1.0                # first 'a' kept, 'b' stale, 'c' torn
    assert p.read_bytes().count(b"\n") == 2                             # rewritten: header + a
    u.append(_row("c", 3.0))                                            # appends after a clean line
    assert list(ResultsTable(p, COLS).open({"h1"})) == ["a", "c"]
    # a malformed (short) line in the middle is dropped, the rest kept
    p.write_bytes(p.read_bytes() + b"d,h1\n" + b"e,h1,4.0,3,z\n")
    assert list(ResultsTable(p, COLS).open()) == ["a", "c", "e"]


def test_a_table_of_other_columns_is_refused(tmp_path):
    p = tmp_path / "t.csv"
    ResultsTable(p, {"x": float}).open()
    with pytest.raises(ArtifactError, match="other columns"):
        ResultsTable(p, COLS).open()
