"""The screen's onset checked by the time loop (issue 32): for every wheel of the shipped curves r75 and
r150, the nonlinear time loop (``pipeline.curve.onset.level_row``: at most 8 s of rolling, SPEC 6's
L_F2 >= 10 dB criterion) squeals 0.02 above the onset the linearised screen finds and is quiet 0.02
below it; a wheel without onset in the scanned range is quiet at its top less 0.02.  A second method
(time-domain simulation of the nonlinear loop) against the first (poles of the linearised loop).
Marked ``validation`` (minutes: the quiet runs roll the full 8 s)."""
from __future__ import annotations

import math

import pytest

from pipeline.config.case import given
from pipeline.curve.cases import wheel_case
from pipeline.curve.onset import MU_HI, level_row, wheel_onset
from pipeline.curve.screen_first import screen_context
from pipeline.curve.stage import solve
from pipeline.curve.what_ifs import CaseModels

DELTA = 0.02


@pytest.mark.validation
@pytest.mark.parametrize("curve", ["r75", "r150"])
def test_onset_against_time_loop(curve):
    sol = solve(curve)
    cases = [wheel_case(sol.curve, p) for p in sol.wheels]
    bad = []
    with given(cases):
        for p, rc in zip(sol.wheels, cases):
            models = CaseModels.of_context(screen_context(rc))
            on = wheel_onset(models, p.gamma_y)
            if p.gamma_y == 0.0:
                continue
            if math.isfinite(on.mu):
                lo, hi = level_row(models, on.mu - DELTA, None), level_row(models, on.mu + DELTA, None)
                print(f"{curve}/{p.wheel}: onset {on.cell()} {on.mode} {on.f_hz:.0f} Hz; L_F2 {lo['L_F2']:.1f} dB "
                      f"at {lo['mu']:.3f}, {hi['L_F2']:.1f} dB at {hi['mu']:.3f} ({hi['f']:.0f} Hz)")
                if lo["squeals"] or not hi["squeals"]:
                    bad.append((p.wheel, on.cell(), lo, hi))
            else:
                top = level_row(models, MU_HI - DELTA, None)
                print(f"{curve}/{p.wheel}: onset {on.cell()}; L_F2 {top['L_F2']:.1f} dB at {top['mu']:.3f}")
                if top["squeals"]:
                    bad.append((p.wheel, on.cell(), top))
    assert not bad, bad
