"""The damping procedure (solvers/study.py) on the real time loop: one lightly damped axial mode
(1161 Hz, 35 kg, shape (Phi_2, Phi_3) = (1, -0.15) at the contact: kappa = Phi_3 (Phi_3 + mu Phi_2)
< 0, the geometric coupling destabilises it in full slip) on the analytic beam rail with the
analytic Hertz contact (tests/interaction), mu = 0.35, gamma_y = -0.014.  Its squeal-critical
damping found by bisection (squeal: L_F2 >= 10 dB within 8 s) is compared with the linear
estimate, where the single-mode growth rate (tests.interaction.single_mode_growth, frequency
domain, independent of the time loop) crosses zero."""
import numpy as np

from solvers.timeloop.interaction import WheelModes, simulate
from solvers.study import Outcome, damping_procedure
from pipeline.validation.references.greens import beam_transfer
from pipeline.validation.references.interaction import DT, V, beam_kernel, contact_stiffness, hertz_contact, single_mode_growth

MU, GAMMA, F_R, MASS, PHI = 0.35, -0.014, 1161.0, 35.0, (1.0, -0.15)


def wheel(zeta):
    return WheelModes(np.array([F_R]), np.array([MASS]), np.array([zeta]), np.array([PHI]))


def linear_critical_damping(contact) -> float:
    T = beam_transfer()
    R = lambda f: T(np.zeros(1), np.atleast_1d(f))[0, 0]          # noqa: E731
    z0 = 1e-4
    rate = single_mode_growth(wheel(z0), R, contact_stiffness(contact, 9.7e-5), MU)[0]
    w = 2 * np.pi * F_R
    return (rate + z0 * w) / w                                     # sigma = -zeta w + coupling term


def run_procedure(contact, g, rel_tol):
    gen = damping_procedure([1e-4], [F_R], [True], rel_tol=rel_tol, zeta_max=0.1)
    batch, log = next(gen), []
    try:
        while True:
            out = []
            for q in batch:
                r = simulate(wheel(q.zeta[0]), g, contact, dt=DT, v=V, gamma_y=GAMMA, duration=8.0)
                m = r.measures()
                out.append(Outcome(m["L_F2"], m["f_dominant"]))
                log.append((q.zeta[0], m["L_F2"], r.stop_reason))
            batch = gen.send(out)
    except StopIteration as stop:
        return stop.value, log


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
