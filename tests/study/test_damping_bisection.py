"""The damping procedure (solvers/study.py) on the real time loop: one lightly damped axial mode
(1161 Hz, 35 kg, shape (Phi_2, Phi_3) = (1, -0.15) at the contact: kappa = Phi_3 (Phi_3 + mu Phi_2)
< 0, the geometric coupling destabilises it in full slip) on the analytic beam rail with the
analytic Hertz contact (pipeline/validation/references/damping.py), mu = 0.35, gamma_y = -0.014.  Its squeal-critical
damping found by bisection (squeal: L_F2 >= 10 dB within 8 s) is compared with the linear
estimate, where the single-mode growth rate (references.interaction.single_mode_growth, frequency
domain, independent of the time loop) crosses zero."""
import numpy as np

from pipeline.validation.references.damping import MU, linear_critical_damping, run_procedure
from pipeline.validation.references.interaction import DT, V, beam_kernel, hertz_contact


def test_critical_damping_by_bisection_matches_the_linear_estimate():
    c = hertz_contact(MU)
    zc = linear_critical_damping(c)
    assert 1e-3 < zc < 0.05                                        # the mode squeals at zeta = 1e-4
    res, log = run_procedure(c, beam_kernel(DT, V), rel_tol=0.02)
    assert res.end.startswith("quiet") and len(res.steps) == 2
    s = res.steps[0]
    assert s.mode == 0 and s.bisection_model == "reduced" and s.L_F2 > 40
    assert s.zeta_hi / s.zeta_lo - 1 <= 0.02
    mid = np.sqrt(s.zeta_lo * s.zeta_hi)
    assert abs(mid / zc - 1) < 0.15, (s.zeta_lo, s.zeta_hi, zc)
    # the bracket is consistent: every run below it squealed, every run above it did not
    assert all(L >= 10 for z, L, _ in log if z <= s.zeta_lo) and all(L < 10 for z, L, _ in log if z >= s.zeta_hi)
    assert res.zeta[0] == s.zeta_hi and res.steps[1].L_F2 < 10
