"""The report's line of the case's inputs formats its numbers (issue 33: a curve wheel's report printed
`gamma_y = -0.015402692482766116`, the steady curving's float as Python writes it)."""
from __future__ import annotations

import re

import pytest

from pipeline.store import paths


def test_curve_wheel_creepages_to_four_significant_digits():
    from pipeline.stages.report import case_line

    gy, gx = -0.015402692482766116, -0.004225022371043613
    c = {"wheel": "c20", "rail": "bv50", "contact": {"dy_wr": -0.0153061224489796},
         "kinematics": {"gamma_y": gy, "gamma_x": gx, "speed": 8.61111111111111}}
    line = case_line(paths.ROOT / "build" / "curves" / "r75" / "cases" / "a1i.toml", c, "coulomb(mu=0.35)")
    assert "0.015402692482766116" not in line and "0.0153061224489796" not in line
    # every number has at most 4 significant digits, and reads back to the input at that precision
    for num in re.findall(r"[-+]?\d+\.\d+", line):
        assert len(num.lstrip("+-0.").replace(".", "")) <= 4, (num, line)
    assert float(re.search(r"gamma_y = (\S+),", line)[1]) == pytest.approx(gy, rel=5e-4)
    assert float(re.search(r"gamma_x = (\S+) ", line)[1]) == pytest.approx(gx, rel=5e-4)
    assert "dy_WR = -15.3 mm" in line and "v = 31 km/h" in line and "dimensionless" in line
