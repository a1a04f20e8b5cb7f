"""The BEM check's record (``pipeline.validation.bem_table``): a fragment's tables read back into rows (the seed of
the CSV cache: the earlier form without solver/load/mode columns and the present form), rendered
again to the same text, and merged with new rows (new ones replace, a free-field-only run keeps the
ground of the same mesh)."""
from __future__ import annotations

import math

from pipeline.validation import bem_table as bt

OLD = """intro

| mode | f (Hz) | force | vertices (wheel) | L_W simple (dB) | BEM free | BEM + ground | Delta free (dB) | Delta ground (dB) | wall free / ground (s) |
|---|---|---|---|---|---|---|---|---|---|
| (2,0,a) | 434.1 | lateral | 912 | 99.8 | 100.0 | 101.0 | +0.2 | +1.2 | 148 / 172 |
| (3,0,a) | 1147.9 | radial | 2052 | 90.7 | 89.2 | 89.2 | -1.5 | -1.4 | 447 / 617 |

| element size along the outline (mm) | vertices around | vertices | Delta free (dB) | wall (s) |
|---|---|---|---|---|
| 30 | 24 | 912 | +0.24 | 93 |
| 15 | 48 | 3360 | +1.00 | 325 |
"""


def test_fragment_rows_round_trip():
    wheel, conv = bt.rows_from_fragment(OLD)
    assert [(r["mode"], r["force"], r["solver"]) for r in wheel] == [("(2,0,a)", "lateral", "3-D"),
                                                                    ("(3,0,a)", "radial", "3-D")]
    assert wheel[1]["dL_ground"] == -1.4 and wheel[1]["wall_ground_s"] == 617.0 and wheel[0]["vertices"] == 912.0
    assert conv[1]["ds_max"] == 0.015 and conv[1]["mode"] == "(2,0,a)" and conv[1]["dL_free"] == 1.0
    text = bt.wheel_table(wheel) + "\n\n" + bt.conv_table(conv) + "\n"
    w2, c2 = bt.rows_from_fragment(text)                     # the present form reads back the same rows
    assert w2 == wheel and c2 == conv
    fe = dict(conv[0], ds_max=0.0)                           # every node of the FE outline
    assert bt.rows_from_fragment(bt.conv_table([fe]))[1][0]["ds_max"] == 0.0
    assert "| (3,0,a) | 1147.9 | radial | 2052 | 3-D | 90.7 | 89.2 | 89.2 | -1.5 | -1.4 | 447 / 617 | 4-10 |" in text


def test_merge_keeps_the_ground_of_the_same_mesh():
    wheel, _ = bt.rows_from_fragment(OLD)
    new = dict(wheel[0], L_W_bem_free=100.4, dL_free=0.6, L_W_bem_ground=math.nan, dL_ground=math.nan,
               wall_ground_s=math.nan)
    merged = bt.merge_wheel(wheel, [new])
    assert len(merged) == 2
    assert merged[0]["dL_free"] == 0.6 and merged[0]["dL_ground"] == 1.2       # ground kept: same vertices
    finer = dict(new, vertices=1000.0)
    assert math.isnan(bt.merge_wheel(wheel, [finer])[0]["dL_ground"])         # another mesh: not kept
    rev = dict(wheel[0], solver=bt.SOLVER_REV, dL_free=0.3)
    assert len(bt.merge_wheel(wheel, [rev])) == 3                            # both solvers' rows stay
