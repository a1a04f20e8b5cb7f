"""Exact Kirchhoff thin-plate natural frequencies of an annular plate,
inner edge (r = b) CLAMPED, outer edge (r = a) FREE.

Independent analytic reference for the axisymmetric (Fourier-harmonic)
finite-element wheel solver.  Nothing here depends on the FE code.

Theory (classical Kirchhoff plate, no shear deformation / rotary inertia)
------------------------------------------------------------------------
Free vibration w(r, phi, t) = W(r) cos(n phi) exp(i omega t) of

    D nabla^4 w + rho h d^2w/dt^2 = 0,     D = E h^3 / (12 (1 - nu^2)),

with  nabla^2_n W = W'' + W'/r - n^2 W / r^2  and  k^4 = rho h omega^2 / D,
factorises into (nabla^2_n + k^2)(nabla^2_n - k^2) W = 0, hence

    W(r) = A J_n(kr) + B Y_n(kr) + C I_n(kr) + D K_n(kr).

Stress resultants (w downward-positive convention of Timoshenko &
Woinowsky-Krieger / Leissa; only the relative signs matter for a free edge):

    M_r     = -D [ w_rr + nu (w_r/r + w_phiphi/r^2) ]
            = -D [ W'' + nu (W'/r - n^2 W / r^2) ] cos(n phi)
    M_rphi  = -(1 - nu) D d/dr( (1/r) dw/dphi )
            = +(1 - nu) D n (W'/r - W/r^2) sin(n phi)
    Q_r     = -D d/dr (nabla^2 w) = -D (nabla^2_n W)' cos(n phi)

Kirchhoff effective (free-edge) shear  V_r = Q_r + (1/r) dM_rphi/dphi,
with (1/r) dM_rphi/dphi = +(1 - nu) D n^2 (W'/r^2 - W/r^3) cos(n phi):

    V_r = -D [ d/dr(nabla^2 w) + (1 - nu) (1/r) d/dr( (1/r) w_phiphi ) ]
        = -D [ (nabla^2_n W)' - (1 - nu) n^2 / r^2 (W' - W/r) ] cos(n phi)

    with (nabla^2_n W)' = W''' + W''/r - (1 + n^2) W'/r^2 + 2 n^2 W / r^3.

NOTE the sign of the twisting term: for w ~ cos(n phi), w_phiphi = -n^2 w,
so it enters as  -(1 - nu) n^2/r^2 (W' - W/r).  This is the natural
boundary condition of the strain energy
    U = D/2 Int[ (nabla^2 w)^2 - 2 (1 - nu) ( w_rr (w_r/r + w_phiphi/r^2)
                 - (d/dr (w_phi / r))^2 ) ] r dr dphi,
and the Rayleigh-Ritz cross-check in tests/test_annular_plate.py, which
uses only U and the kinetic energy, confirms it (flipping this sign moves
lambda^2 by 8-50 % for n >= 1).

Boundary conditions
    r = b :  W = 0,   W' = 0                         (clamped)
    r = a :  M_r = 0, V_r = 0                        (free)

For the Bessel terms, with x = k r and Z one of J_n, Y_n (s = -1) or
I_n, K_n (s = +1):  nabla^2_n Z(kr) = s k^2 Z(kr), and Bessel's equation
gives Z''(x) = -Z'(x)/x + (s + n^2/x^2) Z(x).  Dividing M_r by D k^2 and
V_r by D k^3 (positive factors) the free-edge rows are

    m(Z) = Z''(x) + nu (Z'(x)/x - n^2 Z(x)/x^2)
    v(Z) = s Z'(x) - (1 - nu) n^2 / x^2 (Z'(x) - Z(x)/x)

evaluated at x = lambda = k a; the clamped rows are Z(kb) and Z'(kb).

Numerics
--------
The 4x4 matrix [[Z(kb)], [Z'(kb)], [m(Z)(ka)], [v(Z)(ka)]] (columns J, Y, I, K)
is built from the exponentially scaled functions ive/kve: the I_n column
is multiplied by exp(-lambda), the K_n column by exp(+lambda b/a); each
column is then divided by its Euclidean norm.  All these factors are
smooth and strictly positive, so the determinant has exactly the zeros of
the physical frequency determinant, no poles and no overflow; it is
bounded by 1 (Hadamard).  Its sign changes on a fine lambda grid are
refined with brentq.

Valid range: 1e-5 <= b/a < 1 (checked against Rayleigh-Ritz for
0.01 <= b/a <= 0.95).
"""
from __future__ import annotations

import numpy as np
from scipy import special
from scipy.optimize import brentq

__all__ = [
    "annular_plate_frequencies",
    "nondimensional",
    "frequency_determinant",
    "mode_coefficients",
    "mode_shape",
    "flexural_rigidity",
]


def flexural_rigidity(E, h, nu):
    """D = E h^3 / (12 (1 - nu^2))."""
    return E * h ** 3 / (12.0 * (1.0 - nu ** 2))


def _columns(lam, beta, n, nu):
    """Scaled (unnormalised) boundary matrices and column scale factors.

    lam may be a scalar or a 1-D array.  Returns M of shape (..., 4, 4),
    M[..., :, j] = scale_j * (physical column j) with scale = (1, 1,
    exp(-lam), exp(lam b/a)).  Physical rows: W and W'/k at r = b,
    M_r/(D k^2) and V_r/(D k^3) at r = a; columns: Z = J_n, Y_n, I_n, K_n.
    """
    lam = np.asarray(lam, dtype=float)
    xb = lam * beta
    xa = lam
    nn = float(n * n)

    def free_rows(z, dz, x, s):
        # Z'' from Bessel's equation: Z'' = -Z'/x + (s + n^2/x^2) Z
        d2z = -dz / x + (s + nn / (x * x)) * z
        m = d2z + nu * (dz / x - nn * z / (x * x))
        v = s * dz - (1.0 - nu) * nn / (x * x) * (dz - z / x)
        return m, v

    cols = []
    # J_n, Y_n (s = -1), unscaled; Z' = (Z_{n-1} - Z_{n+1}) / 2
    for f in (special.jv, special.yv):
        zb = f(n, xb)
        dzb = 0.5 * (f(n - 1, xb) - f(n + 1, xb))
        za = f(n, xa)
        dza = 0.5 * (f(n - 1, xa) - f(n + 1, xa))
        m, v = free_rows(za, dza, xa, -1.0)
        cols.append((zb, dzb, m, v))
    eb = np.exp(xb - xa)  # <= 1
    # I_n column times exp(-lam):  I' = (I_{n-1} + I_{n+1}) / 2
    zb = special.ive(n, xb) * eb
    dzb = 0.5 * (special.ive(n - 1, xb) + special.ive(n + 1, xb)) * eb
    za = special.ive(n, xa)
    dza = 0.5 * (special.ive(n - 1, xa) + special.ive(n + 1, xa))
    m, v = free_rows(za, dza, xa, +1.0)
    cols.append((zb, dzb, m, v))
    # K_n column times exp(+lam*beta):  K' = -(K_{n-1} + K_{n+1}) / 2
    zb = special.kve(n, xb)
    dzb = -0.5 * (special.kve(n - 1, xb) + special.kve(n + 1, xb))
    za = special.kve(n, xa)
    dza = -0.5 * (special.kve(n - 1, xa) + special.kve(n + 1, xa))
    m, v = free_rows(za, dza, xa, +1.0)
    cols.append((zb, dzb, m * eb, v * eb))

    # M[..., row, col]
    return np.stack([np.stack(c, axis=-1) for c in cols], axis=-1)


def _normalised_matrix(lam, beta, n, nu):
    """Column-normalised boundary matrix and the column norms."""
    M = _columns(lam, beta, n, nu)
    norms = np.linalg.norm(M, axis=-2)  # Euclidean norm of each column
    return M / norms[..., None, :], norms


def frequency_determinant(lam, beta, n, nu):
    """Pole-free, column-normalised frequency determinant at lambda = k a
    (scalar or array); beta = b / a.  Zero exactly at natural frequencies,
    |det| <= 1."""
    Mn, _ = _normalised_matrix(lam, beta, int(abs(n)), nu)
    d = np.linalg.det(Mn)
    return float(d) if np.ndim(d) == 0 else d


def _roots(beta, n, nu, count, lam_min=0.05, dlam=0.01):
    """First `count` roots lambda of the frequency determinant, ascending.

    The grid starts at lambda = 0.05 (the fundamental of the n = 1 mode
    tends to zero, logarithmically, as b/a -> 0; at b/a = 1e-5 it is still
    lambda ~ 1.1) and extends until `count` sign changes were found.  The
    roots are ~pi/(1 - b/a) apart in lambda, so dlam = 0.01 cannot step
    over a pair of roots.
    """
    n = int(abs(n))
    roots = []
    lo, hi = lam_min, max(15.0, 10.0 / (1.0 - beta))
    lam_cap = 100.0 + 20.0 * (count + n + 2) / (1.0 - beta)
    while True:
        grid = np.arange(lo, hi + 0.5 * dlam, dlam)
        vals = frequency_determinant(grid, beta, n, nu)
        for i in np.nonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) <= 0)[0]:
            if vals[i] == 0.0:
                r = grid[i]
            elif vals[i + 1] == 0.0:
                continue  # picked up as vals[i] == 0 in the next interval
            else:
                r = brentq(frequency_determinant, grid[i], grid[i + 1],
                           args=(beta, n, nu), xtol=1e-13, rtol=1e-15)
            roots.append(r)
            if len(roots) >= count:
                return np.array(roots[:count])
        if hi > lam_cap:
            raise RuntimeError("found only %d of %d roots" % (len(roots), count))
        lo, hi = grid[-1], 2.0 * hi


def nondimensional(a, b, n, nu, count=3):
    """Lowest `count` frequency parameters lambda^2 = omega a^2 sqrt(rho h / D)
    for n nodal diameters (s = 0, 1, 2, ... nodal circles)."""
    if not (0.0 < b < a):
        raise ValueError("need 0 < b < a")
    if b / a < 1e-5:
        # Y_n(kb), K_n(kb) ~ (kb)^-n swamp J_n, I_n: the 4x4 determinant
        # loses all significant digits for n >= 2 below b/a ~ 1e-7.
        raise ValueError("b/a < 1e-5 is outside the validated range")
    if count < 1:
        raise ValueError("count must be >= 1")
    lam = _roots(b / a, n, nu, count)
    return lam ** 2


def annular_plate_frequencies(a, b, h, E, nu, rho, n, count=3):
    """Lowest `count` natural frequencies [Hz] for harmonic n (n nodal diameters).

    a, b : outer (free) and inner (clamped) radius [m];  h thickness [m];
    E [Pa], nu, rho [kg/m^3] (volumetric; mass per area = rho h).
    f = lambda^2 / (2 pi a^2) sqrt(D / (rho h)).
    """
    lam2 = nondimensional(a, b, n, nu, count)
    D = flexural_rigidity(E, h, nu)
    return lam2 / (2.0 * np.pi * a ** 2) * np.sqrt(D / (rho * h))


def mode_coefficients(a, b, n, nu, lam):
    """Coefficients (A, B, C, D) of W(r) = A J_n(kr) + B Y_n(kr) + C I_n(kr)
    + D K_n(kr), k = lam / a, for a root lam (null vector of the boundary
    matrix, smallest right singular vector).  Normalised so that
    max |W| on [b, a] is about 1 (sign arbitrary).  Needs lam < ~700
    (I_n overflow in double precision)."""
    beta = b / a
    lam = float(lam)
    Mn, norms = _normalised_matrix(lam, beta, int(abs(n)), nu)
    _, _, vt = np.linalg.svd(Mn)
    # Mn[:, j] = scale_j / norms_j * physical column j
    scale = np.array([1.0, 1.0, np.exp(-lam), np.exp(lam * beta)])
    c = vt[-1] * scale / norms  # physical coefficients
    r = np.linspace(b, a, 201)
    w = mode_shape(a, n, lam, c, r)
    return c / np.max(np.abs(w))


def mode_shape(a, n, lam, coeffs, r):
    """Evaluate W(r) for the given coefficients."""
    k = lam / a
    x = k * np.asarray(r, dtype=float)
    A, B, C, D = coeffs
    n = int(abs(n))
    return (A * special.jv(n, x) + B * special.yv(n, x)
            + C * special.iv(n, x) + D * special.kv(n, x))
