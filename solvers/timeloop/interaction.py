"""Wheel/rail interaction in the time domain: the squeal time stepper (SPEC 3.5,
4.1-4.4, 6; thesis [4.13]-[4.37]).

Per time step t_d = n dt the wheel and rail displacements follow from the PAST
contact forces (Green's functions without the instantaneous term g(0)), the
normal force from the normal contact model at the resulting approach, and the
two tangential forces from the tangential point-contact model (or, as the
reference, from Kalker's transient TANG).  The contact then moves one element
dx = v dt along the rail.

Conventions (SPEC 2, 3.5)
-------------------------
Contact frame: 1 longitudinal, 2 lateral (+ toward the field side), 3 vertical
(+ toward the ground).  F = (F1, F2, F3) act on the RAIL; the wheel receives -F.
Kernel layout [..., i, j], index 0 = direction 2, 1 = direction 3 (as in
``solvers.greens.kernels``).  Structural displacements are deviations from the reference
(static) state and are convolved with the force DEVIATIONS dF = F - F_ref:

    wheel  xi^W[n] = - sum_{k>=1} g^W[k] dF[n-k]      [4.13]  (recursive modal filters)
    rail   xi^R[n] = + sum_{k>=1} g^R_mov[k] dF[n-k]  [4.15]  (partitioned FFT convolution, exact)
    xi[n]  = xi^R[n] - xi^W[n]   (displacement of the rail relative to the wheel)

Normal kinematics [4.16], [4.19]: d = xi3 + z^R - z^W + u3 with xi3 = xi3^R - xi3^W
grows when the rail moves away from the wheel (toward the ground) or the wheel
moves up.  The NORM table is parametrised by the approach (rigid penetration,
positive into contact, ``solvers.contact.norm``), so

    approach[n] = xi3_static - xi[n, 1]     (total = static + dynamic part)

and F3[n] = F3_table(approach[n]).  A rail moving down under +F3 lowers the
approach (restoring), the wheel pushed up by -F3 too: the normal contact is a
stiffening spring between the two structures.  approach <= first table node
(no pressure) is loss of contact: F = 0 exactly, the tangential deformation is
released (u = 0) and contact is found again when the approach turns positive.

Tangential kinematics [4.25]-[4.31]: slip of the rail relative to the wheel
(Kalker's convention, as in ``solvers.contact.tang``: u = u(rail) - u(wheel),
traction on the rail, F_tau = -mu F3 s_tau / s)

    s1 = (gamma_x + (u1[n] - u1[n-1]) / dx) v
    s2 = (gamma_y + (u2[n] - u2[n-1]) / dx + sign * (xi2[n] - xi2[n-1]) / dx) v
    u_tau = A_tau F_tau,   F_tau = -mu_RF(s) F3 s_tau / s,   s = |(s1, s2)|.

``sign`` (argument ``slip_sign``) is +1 by default.  The thesis prints [4.30]
with a MINUS sign in front of the structural term and the SPEC repeats it;
with xi2 = xi2^R - xi2^W (SPEC 4.2) and u = u(rail) - u(wheel) entering with
+ (as it must for the contact spring to relax: s = w + A dF/dt), consistency
demands the same sign for both, because the slip is the relative velocity of
the rail's and the wheel's surface particles, and the structural motion moves
those particles exactly as the contact deformation does.  The energy balance
decides it: the power the contact forces put into the structures is
F2 d(xi2)/dt (rail +F2, wheel -F2), and with s2 = w2 + ... + d(xi2)/dt the
friction work -F2 s2 >= 0 is dissipated, while with the printed minus sign a
RISING friction curve (the micro-slip branch of mu_RF, slope mu'(0) F3 ~
6e5 N s/m here) acts as a NEGATIVE damper on the lateral wheel/rail motion:
every lightly damped axial wheel mode is then unstable in micro-slip, i.e. at
the smallest creepages, contrary to the thesis' results (squeal needs larger
creepage).  slip_sign = -1 reproduces the printed equation
(docs/validation/60_interaction.md compares).

Tangential compliance (SPEC 4.3, [4.32]-[4.35]): A_tau(approach) from the
contact stage's table (unit-force limit of [4.32]-[4.35]: full-slip traction
shaped like the pressure, 2/3 of the peak half-space deformation; without the
cross influence A_12 the compliance depends on the pressure SHAPE only, i.e.
on the approach), updated every step.  The Python reference driver can
evaluate [4.32]-[4.35] literally instead (``compliance='exact'``: previous
step's forces, current pressure, with the cross term).

The tangential equations: with b_tau = gamma_tau v - u_tau[n-1]/dt (+ the
structural term for tau = 2) and c_tau = A_tau/dt, s_tau = b_tau + c_tau F_tau,
so with k_tau = c_tau F3 and m(sigma) = mu_RF(sigma)/sqrt(sigma^2 + eps^2)

    s_tau = b_tau / (1 + k_tau m(sigma)),   F_tau = -F3 m(sigma) s_tau,

and sigma = |s| is the root in (0, |b|] of the scalar equation

    H(sigma) = 1/sqrt(sum_tau b_tau^2 / D_tau(sigma)^2) - 1 = 0,
    D_tau(sigma) = sigma + k_tau mu_RF(sigma) sigma/sqrt(sigma^2 + eps^2).

D_tau is strictly increasing for a non-decreasing mu_RF (Coulomb), so H rises strictly
from -1 (sigma -> 0) to >= 0 (sigma = |b|): a unique root, bracketed, found by
Newton's method safeguarded by bisection (warm-started with the previous
step's sigma; 2-5 iterations).  A falling law's curve (issue 26, ``solvers.contact.falling``)
keeps D_tau increasing while its slope stays above -1/k_tau = -dt/(A_tau F3) (about -0.45 s/m
for the default contact at dt = 36 us; the falling laws of the validation reach -0.16 s/m); H
still runs from -1 to >= 0, so a root is always bracketed, and where a steeper slope allows
several, the safeguarded Newton started from the last step's sigma follows the branch of the
last step.  For c_1 = c_2 H is (sigma + k mu_RF(sigma))/|b|
- 1, Newton on a monotone, nearly linear function.  The direction s_tau/s needs
no regularisation for the regularised friction curves: mu_RF(0) = 0 with a
finite slope, so F = -F3 (mu_RF(s)/s) s is smooth through s = 0 (eps = 0, the
default for such curves); for a curve with mu(0) > 0 (pure Coulomb) the
direction is s_tau/sqrt(s^2 + eps^2) with eps = 1e-9 m/s, a viscous
regularisation below eps.  |b| = 0 gives s = 0 and F = 0 exactly (no NaN).

Traction and spin (issue 26): gamma_x enters the rigid slip w1 above; spin phi [1/m] enters the
point contact as equivalent creepages (gamma_x, gamma_y) + L phi from Kalker's linear theory on
the contact's grid (``solvers.contact.spin``; ``simulate(.., spin=)``), Kalker's TANG as the
rigid slip field phi (-y, x) v.  The structures have no longitudinal direction (the wheel's
circumferential and torsional motion and the rail's longitudinal receptance are not modelled):
in direction 1 only the contact's compliance A1 deforms, so F1 changes the slip direction and
shares the friction limit with F2 but moves no structure.

Reference state and start (SPEC 3.5 "start from static equilibrium")
---------------------------------------------------------------------
``start='steady'`` (default): the reference state is the steady rolling
equilibrium under the preload: F_ref = (F1s, F2s, F_L3) with
F_tau,s = -mu_RF(|w|) F_L3 w_tau/|w|, w = (gamma_x, gamma_y) v at t = 0, the
static approach xi3_static (the table's approach for F_L3), u = A F_ref.  Its
structural deflection (including the quasi-static part of the rigid-body /
suspension modes, which are in the wheel's modal set) is the static deflection
the convolutions of the deviations leave out, so the state is an exact
equilibrium of the discrete model: nothing moves unless it is disturbed.  The
disturbance is ``kick``: an impulse (N s, default 0.01 N s lateral) given to
the structures as an extra force kick/dt during the first step (the same
impulse at any dt), from which an unstable mode grows.  ``start='static'``:
F_ref = (0, 0, F_L3), u = 0 (the wheel stands on the rail under its load, the
creep force appears at t = 0 as a step): the step excites everything, and the
quasi-static cross compliance of the half wheelset on its soft primary
suspension (roll mode, G32 ~ -1e-7 m/N at the tread) turns the creep force into
a vertical deflection, so F3 settles away from the preload (69 kN instead of
65 kN in the default case); an option, not the default.

Time discretisation: besides the explicit coupling (displacements from past
forces), the rule g(0) = 0 drops the first sample of the rail's kernel, which
holds a share of the rail's static compliance proportional to dt (2 % of the
vertical one at 36 us for BV50): modes dominated by the track stiffness (the
wheelset bouncing on the track, ~80 Hz) converge to first order in dt, wheel
modes in the kHz range much faster (validation doc).

Drivers
-------
``simulate(...)`` runs
* normal='table', tangential='point': the whole time loop inside numba
  (``timeloop.kernel.run_point``), O(modes + B + K / B) per step for a rail kernel of K lags
  and head B (benchmarks/interaction.py);
* normal='norm', compliance='exact' and/or tangential='kalker' (or
  driver='python'): the reference drivers, a Python loop over the steps with
  the same kinematics and the same njit building blocks (with the table's
  pressures, Kalker's steps run compiled, ``timeloop.kalker``, while the
  contact keeps its window): per-step NORM
  (warm-started active set, ``solvers.contact.norm``, ~0.7 ms per step; it
  agrees with the table to the table's interpolation error: exactly at the
  nodes, ~1e-5 over a run with the contact stage's 41 nodes, < 1e-6 with the
  table refined over the visited range by ``refine_table``), the literal
  compliance [4.32]-[4.35] per step, and Kalker's transient TANG per step
  (``tang_transient`` with the table's or NORM's pressures, the structural
  lateral velocity added to the rigid slip: gamma_y + sign (xi2[n] -
  xi2[n-1])/dx; FFT-based Newton-Krylov, warm-started and extrapolated from
  the last steps, tolerance KALKER_TOL, displacements on the contact's window
  only, the step compiled whole: about 0.35-0.5 ms per step on the default
  contact, 8 s of rolling in 96-125 s, docs/benchmarks.md).

Output: every ``store_every``-th step (decimated history) plus the last
``final`` seconds at full rate (for the spectra); early stop when a limit
cycle is reached or the motion has decayed (``StopRule``); never beyond
``duration`` (at most 8 s, SPEC 6).  Squeal measures [6.3]-[6.4] with
``squeal_measures`` / ``InteractionResult.measures``.
"""
# The public names of the time loop; the code lives in ``solvers.timeloop``, one idea a module:
# inputs (wheel, contact, reference state, loop parameters), stop (the early-stop rule), kernel
# (the numba loop), reference (the Python reference loop), result (recording, result, squeal
# measures), driver (settings, ``simulate``).
from solvers.contact.friction import mu_and_slope  # noqa: F401  (the point model's friction curve, for tests)
from solvers.timeloop.driver import RunSettings, rail_convolver, simulate, wheel_filter  # noqa: F401
from solvers.timeloop.inputs import DEFAULT_KICK, EPS_SLIP, FULL_SLIP, KALKER_TOL, MAX_DURATION, ContactModel, LoopParams, PointTables, WheelModes, contact_model, refine_table, static_approach, steady_forces
from solvers.timeloop.kernel import point_contact  # noqa: F401
from solvers.timeloop.result import COLUMNS, InteractionResult, squeal_measures  # noqa: F401
from solvers.timeloop.stop import STOP_REASONS, StopRule  # noqa: F401
