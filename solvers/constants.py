"""The SPEC's numbers that more than one stage needs: one home for each.

Every module that uses one of these imports it from here (``tests/test_layering``
greps for copies).  Units SI unless the name says otherwise.
"""
from __future__ import annotations

# SPEC 3.2 / thesis 4.2: the band of the structural models (the rail's WFE model
# stops at 6.5 kHz; the wheel's Green's functions are band-limited to the same top).
F_MAX_HZ = 6500.0
# SPEC 3.2: the lowest frequency of the rail receptance table (thesis Fig. 4.6).
RAIL_F_MIN_HZ = 25.0
# SPEC 6 ([6.3]-[6.4]): a case squeals when the lateral force level L_F2 >= this (dB re 1 N).
SQUEAL_LEVEL_DB = 10.0
# SPEC 2 (thesis [4.1]): wheelset lateral offset dy_WR -> (y^W, y^R) as printed in the
# thesis (m).  Stages read the contact point of a case through one function
# (``pipeline.contact_stage``); nothing else indexes this table.
THESIS_CONTACT_POSITIONS = {-0.005: (0.005, -0.016), -0.010: (-0.004, -0.012),
                            -0.015: (-0.032, 0.012)}
