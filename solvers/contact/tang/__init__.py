"""Kalker's TANG: the discretised tangential rolling contact problem with local
Coulomb friction (SPEC 4.5; Kalker 1990, ch. 2 and 5; thesis 4.3.4, footnote 3).

Grid, traction and displacement conventions as in influence.py: axis 0 is x,
the rolling direction (the contact travels towards +x, so material enters the
contact at the leading edge, high x, and leaves at the trailing edge), p is the
traction on the rail and u = u(rail) - u(wheel).  Per element I in the contact
area (p3 > 0) the slip of the rail relative to the wheel is

    s_I = w_I + (u_I(t) - u_{I+dx}(t - dt)) / dt,     dx = v dt      (SPEC 4.5)

(the particle at x_I at time t was at x_I + dx a step earlier), with the rigid
slip w1 = (gamma_x - spin y) v, w2 = (gamma_y + spin x) v (SPEC 2, [3.2]).  In
steady state u(t - dt) = u(t) and s_I = w_I - v (u_{I+dx} - u_I)/dx, the
discrete s = w - v du/dx.  Coulomb's law per element:

    stick  s_I = 0,            |p_I| <= mu p3_I
    slip   |p_I| = mu p3_I,    p_I = -mu p3_I s_I / |s_I|   (traction opposes slip)

so a positive creepage gives a negative force (F2 = -c^2 G C22 gamma_y in the
linear range; full slip F = -mu F3 w / |w|).  With a slip-speed dependent friction law
(``friction_laws``) the bound is mu(|s_I|) p3_I at the element's own slip speed, mu(0) p3_I on
stick: CONTACT's slip-velocity iteration around the solver below (``tang.falling``).

Where the rigid slip is evaluated (spin).  The difference u_I - u_{I+dx} is the
deformation the particle collects on its way from x_I + dx to x_I during the
step, so the rigid slip belongs to the same path; it matters only where w
varies along x, i.e. for spin (w2 = spin x v), where an offset f dx acts like a
lateral creepage spin f dx.  ``W_OFFSET`` (fraction of dx towards the leading
edge, default 1/6) is Kalker's choice, kept in Vollebregt's CONTACT (rigid slip
at x_I + dq/6): with it CONTACT's spin results are reproduced on the same grid.
Offsets 0, 1/6 and 1/2 (the path's midpoint) converge at first order to the
same limit under grid refinement, 1/2 with the smallest error at a given grid
(docs/validation/30_contact.md, "Spin"); ``w_offset`` selects it.

Solver.  s = r + M p (in units of displacement per step, s dt) with M = A - A(x +
dx) in steady state and M = A transient; products with M are FFT convolutions
on a window around the contact (its bounding box, grown by one element once a
breathing contact outgrew it; one forward and one inverse transform of both
traction components give the displacements on the window and one row ahead),
O(n log n).  Kalker's active-set Newton
method on these equations: elements are split into a stick set H (unknowns p1,
p2; equations s = 0) and a slip set S (unknown: the traction angle theta, |p| =
mu p3; equation: slip along the traction, t . s = 0 with t the tangent to the
traction circle).  One (inexact) Newton step, then elements of H exceeding the
traction bound move to S and elements of S whose slip points along the traction
move to H; repeat until the sets no longer change and the step is below tol
times the traction level, or is so small that quadratic convergence puts the
remaining error below it.  In the variables (dp on H, g dtheta on S) the Newton
matrix is J = P' M P + D, D = |s|/g on S: symmetric positive definite in the
transient case (M = A), solved by conjugate gradients; non-symmetric in steady
state, solved by GMRES.  Both are matrix-free (FFT products) with a
preconditioner of O(n log n) work: on H the inverse of Strang's circulant
approximation of the 2x2 Cerruti kernel (FFT on a torus of the window's size),
preceded in steady state by the exact inverse of the transport difference (I -
shift), a cumulative sum along x from the leading edge; on S (transient) the
circulant inverse of the kernel shifted by the median of D, with a diagonal
scaling for the spread of D, (steady) the diagonal 1 / (t' M_II t + D).  The
Krylov tolerance follows the Newton phase (rough while the sets move, just
accurate enough at the end); CG also stops when its last update is below 0.1
tol times the traction level where the step may be final (its contraction per
step is about 1/4: the error left is a fraction of the final step's budget).
No matrix of the size of the contact area is ever formed.  Warm starts (a
previous solution's tractions and sets) cut the Newton steps to a few; in
transient rolling the start is extrapolated from the last steps (a polynomial
of order 0 to 3: whichever would have predicted the last step best) and its
sets updated as after a Newton step, so a time step takes one Newton step, two
or three where elements change set.  A transient step runs whole in numba
(tang.pcg.transient_step: the bookkeeping on the grid of tang.steps, the
Newton-CG solve, the FFTs through rocket-fft); the displacements after a Newton
step are the sum of its CG products (A lift(x) = sum alpha_k A d_k) when the
step is linear to LINEAR tol (the traction circle's curvature below that), so
such a step needs no product of its own.  Timings and scaling: benchmarks/contact.py; agreement
with the former dense solver (pipeline/validation/references/tang_dense.py) and with CONTACT:
docs/validation/30_contact.md.
"""
from __future__ import annotations

import numpy as np

# The code lives one idea a module: tang.state (solution, problem, options, predictor history),
# tang.operator (FFT influence products, preconditioner), tang.kernels (numba element kernels),
# tang.newton (the active-set Newton method, steady: GMRES), tang.pcg (transient: the Newton
# method with its CG compiled whole), tang.rolling (one step's problem on the contact's window),
# tang.steps (its bookkeeping on the grid, numba).
from solvers.contact.friction_laws import FrictionLaw
from solvers.contact.tang.newton import CoulombResult, solve_coulomb  # noqa: F401
from solvers.contact.tang.operator import TangentialOperator, shifted_inverse, tangential_operator  # noqa: F401
from solvers.contact.tang.rolling import solve_rolling
from solvers.contact.tang.state import QUADRATIC, TOL, W_OFFSET, Rolling, TangentialContact, TangOptions  # noqa: F401


def rigid_slip(shape, dx, dy, v, gamma_x=0.0, gamma_y=0.0, spin=0.0, origin=(0.0, 0.0), x_offset=0.0):
    """Rigid slip w1, w2 [m/s] at the element centres shifted by x_offset [m] along x (SPEC 2,
    [3.2]; TANG evaluates it at x_I + W_OFFSET dx, see the module notes); x, y measured from
    `origin` relative to the grid centre."""
    nx, ny = shape
    x = (np.arange(nx) - 0.5 * (nx - 1)) * dx + x_offset - origin[0]
    y = (np.arange(ny) - 0.5 * (ny - 1)) * dy - origin[1]
    w1 = (gamma_x - spin * y[None, :]) * v + 0.0 * x[:, None]
    w2 = (gamma_y + spin * x[:, None]) * v + 0.0 * y[None, :]
    return w1, w2


def tang_steady(p3, dx, dy, v, mu, gamma_x=0.0, gamma_y=0.0, spin=0.0, *,
                warm: TangentialContact | None = None, **options) -> TangentialContact:
    """Steady-state rolling (du/dt = 0) with normal pressures p3 (nx, ny) [Pa] on the grid
    dx (rolling direction) x dy [m], rolling speed v [m/s], Coulomb coefficient mu (or a
    ``FrictionLaw``: the local coefficient mu(|s|) at the local slip speed, ``tang.falling``)
    and creepages gamma_x, gamma_y [-], spin [1/m].  `warm`: a previous solution as start.
    ``options``: the fields of ``TangOptions`` (E, nu, tol, w_offset, full_output)."""
    mu, law = _coefficient(mu)
    return solve_rolling(p3, Rolling(dx, dy, v, mu, gamma_x, gamma_y, spin), True, warm, TangOptions(**options),
                         law)


def tang_transient(p3, dx, dy, v, mu, gamma_x=0.0, gamma_y=0.0, spin=0.0, *,
                   state: TangentialContact | None = None, **options) -> TangentialContact:
    """One time step dt = dx / v of transient rolling.  `state` is the previous step's
    solution (None: traction-free start); its tractions give the previous displacement
    one element ahead, u(x + dx, t - dt), and start the iteration (extrapolated from the
    last steps: the predictor that would have done best on the last step).  Call once per
    step.  ``options`` as in tang_steady (the time loop needs no displacements outside the
    contact: full_output=False saves one FFT product per step).  `mu` a Coulomb coefficient or a
    ``FrictionLaw``: the local coefficient mu(|s|) at each element's slip speed of this step
    (instantaneous, CONTACT's MEMDST = 0; ``tang.falling.transient_falling``)."""
    mu, law = _coefficient(mu)
    if law is not None and law.memory[0] > 0.0:
        raise ValueError(f"tang_transient: friction law '{law.name}' with memdst = {law.params['memdst']:g} mm: "
                         "transient TANG takes the instantaneous law (memdst = 0); tang_steady takes the memory")
    return solve_rolling(p3, Rolling(dx, dy, v, mu, gamma_x, gamma_y, spin), False, state, TangOptions(**options),
                         law)


def _coefficient(mu):
    """(mu, law): a float or the 'coulomb' law -> (its mu, None), exactly today's path; a
    slip-speed dependent law -> (mu(0), law)."""
    if isinstance(mu, FrictionLaw):
        if mu.is_coulomb:
            return float(mu.array[0]), None
        return mu.mu_static, mu
    return mu, None
