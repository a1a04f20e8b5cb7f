"""The squeal-critical damping of one lightly damped axial mode on the analytic beam rail with the analytic
Hertz contact (the damping study's check, tests/study/test_damping_bisection.py and the studies writer):

* ``linear_critical_damping``: the independent estimate, where the single-mode growth rate in full slip
  (``references.interaction.single_mode_growth``, frequency domain, the rail's point receptance and the
  contact stiffness at the mode's frequency, independent of the time loop) crosses zero;
* ``run_procedure``: the damping study's procedure (``solvers.study.damping_procedure``, geometric
  bisection) on the time loop (squeal: L_F2 >= 10 dB within 8 s).

The default mode: 1161 Hz, 35 kg, shape (Phi_2, Phi_3) = (1, -0.15) at the contact (kappa = Phi_3 (Phi_3 +
mu Phi_2) < 0: the geometric coupling destabilises it in full slip), mu = 0.35, gamma_y = -0.014."""
from __future__ import annotations

import numpy as np

from solvers.study import Outcome, damping_procedure
from solvers.timeloop.interaction import WheelModes, simulate

from pipeline.validation.references.greens import beam_transfer
from pipeline.validation.references.interaction import DT, V, contact_stiffness, single_mode_growth

MU, GAMMA, F_R, MASS, PHI = 0.35, -0.014, 1161.0, 35.0, (1.0, -0.15)


def wheel(zeta, f_r=F_R, mass=MASS, phi=PHI):
    return WheelModes(np.array([f_r]), np.array([mass]), np.array([zeta]), np.array([phi]))


def linear_critical_damping(contact, f_r=F_R, mass=MASS, phi=PHI, mu=MU) -> float:
    T = beam_transfer()
    R = lambda f: T(np.zeros(1), np.atleast_1d(f))[0, 0]          # noqa: E731
    z0 = 1e-4
    rate = single_mode_growth(wheel(z0, f_r, mass, phi), R, contact_stiffness(contact, 9.7e-5), mu)[0]
    w = 2 * np.pi * f_r
    return (rate + z0 * w) / w                                     # sigma = -zeta w + coupling term


def run_procedure(contact, g, rel_tol, f_r=F_R, mass=MASS, phi=PHI):
    """(the procedure's result, the runs' log [(zeta, L_F2, stop reason)])."""
    gen = damping_procedure([1e-4], [f_r], [True], rel_tol=rel_tol, zeta_max=0.1)
    batch, log = next(gen), []
    try:
        while True:
            out = []
            for q in batch:
                r = simulate(wheel(q.zeta[0], f_r, mass, phi), g, contact, dt=DT, v=V, gamma_y=GAMMA, duration=8.0)
                m = r.measures()
                out.append(Outcome(m["L_F2"], m["f_dominant"]))
                log.append((q.zeta[0], m["L_F2"], r.stop_reason))
            batch = gen.send(out)
    except StopIteration as stop:
        return stop.value, log
