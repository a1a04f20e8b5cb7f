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
linear range; full slip F = -mu F3 w / |w|).

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
on a window around the contact (its bounding box plus one element; one forward
and one inverse transform of both traction components give the displacements
on the window and one row ahead), O(n log n).  Kalker's active-set Newton
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
accurate enough at the end).  No matrix of the size of the contact area is
ever formed.  Warm starts (a previous solution's tractions and sets) cut the
Newton steps to a few; in transient rolling the start is extrapolated from the
last steps (constant, linear or quadratic: whichever would have predicted the
last step best), so a time step takes one or two Newton steps.  Timings and
scaling: benchmarks/contact.py; agreement with the former dense solver
(tests/contact/tang_dense.py) and with CONTACT: docs/validation/30_contact.md.
"""
from __future__ import annotations

import functools
import math
import threading
import warnings
from typing import NamedTuple

import numba
import numpy as np
from scipy import fft as sfft

from .influence import cerruti

W_OFFSET = 1.0 / 6.0        # rigid slip evaluated at x_I + W_OFFSET dx (see the module notes)
QUADRATIC = 10.0            # bound of the Newton steps' quadratic constant (relative), for stopping
TOL = 1e-8                  # default: Newton step <= TOL * traction level, no set change


class TangentialContact(NamedTuple):
    p1: np.ndarray          # traction on the rail, longitudinal [Pa] (nx, ny)
    p2: np.ndarray          # traction on the rail, lateral [Pa]
    stick: np.ndarray       # stick elements (bool)
    slip: np.ndarray        # slip elements (bool); stick | slip = contact area
    s1: np.ndarray          # slip velocity of the rail relative to the wheel [m/s]
    s2: np.ndarray
    u1: np.ndarray          # tangential displacement difference at time t [m]
    u2: np.ndarray
    F1: float               # forces on the rail [N]
    F2: float
    iterations: int         # Newton steps in total
    converged: bool
    krylov: int = 0         # Krylov (CG / GMRES) steps in total
    u_ahead: np.ndarray | None = None    # (2, nx, ny): u(x + dx, t), the next step's transport term
    history: "_History | None" = None    # transient: the last steps' changes (the next step's predictor)
    window: tuple | None = None          # (i0, i1, j0, j1): rows/columns where u1, u2, u_ahead are valid


class _History(NamedTuple):
    """Differences of the last transient steps on the grid (2, nx, ny): first dp = p_k - p_k-1 and
    second d2p = dp_k - dp_k-1 (likewise du, d2u of the displacements), and the order (0, 1, 2) of
    the polynomial extrapolation that would have predicted the last step best."""
    dp: np.ndarray
    du: np.ndarray
    d2p: np.ndarray | None
    d2u: np.ndarray | None
    order: int
    window: tuple           # the working window of the step (the differences are valid there)


def _next_history(prev: _History | None, window, dp, du) -> _History:
    if prev is None or prev.dp.shape != dp.shape or prev.window != window:
        return _History(dp, du, None, None, 1, window)
    d2p, d2u = dp - prev.dp, du - prev.du
    errors = [np.abs(dp).max(), np.abs(d2p).max()]          # constant, linear predictor
    if prev.d2p is not None:
        errors.append(np.abs(d2p - prev.d2p).max())          # quadratic
    return _History(dp, du, d2p, d2u, int(np.argmin(errors)), window)


# ----------------------------------------------------------------------------------------------
# the influence operator of a grid (FFT), cached per grid and material
# ----------------------------------------------------------------------------------------------

class TangentialOperator:
    """Cerruti influence of a (nx, ny) grid by FFT.  ``displacements(P)`` gives u = A p on the
    grid AND one row ahead (rows 0..nx, shape (2, nx + 1, ny)) for P = (p1, p2) (2, nx, ny);
    ``precondition(R)`` applies the inverse of Strang's circulant approximation of the 2x2 kernel
    on a torus of about the grid's size."""

    def __init__(self, shape, dx, dy, E, nu):
        nx, ny = shape
        self.shape = (int(nx), int(ny))
        self.dx, self.dy = float(dx), float(dy)
        ox = np.arange(-(nx - 1), nx + 1)                     # offsets -(nx-1) .. nx (one row ahead)
        oy = np.arange(-(ny - 1), ny)
        X, Y = np.meshgrid(ox * dx, oy * dy, indexing="ij")
        K = cerruti(X, Y, dx, dy, E, nu)
        self.L = (sfft.next_fast_len(2 * nx, real=True), sfft.next_fast_len(2 * ny - 1, real=True))
        c = np.zeros((3,) + self.L)
        c[np.ix_([0, 1, 2], ox % self.L[0], oy % self.L[1])] = np.stack(K)
        self.hat = np.ascontiguousarray(sfft.rfft2(c, workers=1))            # (3, Lx, Ly//2 + 1)
        i0, j0 = nx - 1, ny - 1
        self.a0 = np.array([K[0][i0, j0], K[2][i0, j0]])                     # self coefficients A11, A22
        self.a1 = np.array([K[0][i0 + 1, j0], K[2][i0 + 1, j0]])             # at offset +dx (A12 = 0 on y = 0)
        # preconditioner: Strang's circulant of the 2x2 kernel on a torus >= the grid
        T = (sfft.next_fast_len(nx, real=True), sfft.next_fast_len(ny, real=True))
        self.T = T
        mx = np.arange(T[0])
        mx = np.where(mx < (T[0] + 1) // 2, mx, mx - T[0])
        my = np.arange(T[1])
        my = np.where(my < (T[1] + 1) // 2, my, my - T[1])
        Xs, Ys = np.meshgrid(mx * dx, my * dy, indexing="ij")
        k11, k12, k22 = (sfft.rfft2(k, workers=1).real for k in cerruti(Xs, Ys, dx, dy, E, nu))
        # positive definite 2x2 symbol: floor the eigenvalues (the wrapped kernel is approximate)
        disc = np.sqrt(0.25 * (k11 - k22) ** 2 + k12 * k12)
        lmin = 0.5 * (k11 + k22) - disc
        floor = 1e-3 * float((0.5 * (k11 + k22) + disc).max())
        bump = np.maximum(floor - lmin, 0.0)
        self.scale = float(self.a0.mean())        # unit of the scaled Newton systems
        self.symbol = np.ascontiguousarray(np.stack([k11 + bump, k12, k22 + bump]) / self.scale)
        self.inv = shifted_inverse(self.symbol, 0.0)        # (3, Tx, Ty//2+1), scaled units
        self._local = threading.local()

    @property
    def buffers(self) -> "_FFTBuffers":
        """The FFT work arrays of the calling thread."""
        b = getattr(self._local, "fft", None)
        if b is None:
            b = self._local.fft = _FFTBuffers(self)
        return b

    def displacements(self, P):
        """u (2, nx + 1, ny) on the grid and one row ahead for P (2, nx, ny) (a view into a buffer
        of the operator: copy it to keep it beyond the next call).  P may be the buffer
        ``buffers.conv_in`` itself (filled in place)."""
        return self.buffers.convolve(P)

    def precondition(self, R, inv_a, inv_b=None):
        """Strang-circulant inverse symbols applied to R (4, nx, ny): fields 0, 1 with inv_a,
        2, 3 with inv_b, a pair skipped when its symbol is None (scaled units; a buffer view of
        4 fields is returned).  R may be the buffer ``buffers.prec_in`` itself."""
        return self.buffers.precondition(R, inv_a, inv_b)


@numba.njit(cache=True)
def _shifted_inverse(sym, d, out):
    for i in range(sym.shape[1]):
        for j in range(sym.shape[2]):
            a, b, c = sym[0, i, j] + d, sym[1, i, j], sym[2, i, j] + d
            det = a * c - b * b
            out[0, i, j], out[1, i, j], out[2, i, j] = c / det, -b / det, a / det


def shifted_inverse(symbol, d):
    """Inverse of the 2x2 symbol plus d I (d >= 0), per frequency."""
    out = np.empty_like(symbol)
    _shifted_inverse(symbol, float(d), out)
    return out


try:                      # pocketfft's own entry points: no argument checking per call (small grids)
    from scipy.fft._pocketfft import pypocketfft as _pocketfft
except ImportError:       # pragma: no cover
    _pocketfft = None


class _FFTBuffers:
    """Preallocated transforms of one operator.  The convolution transforms the last axis (y)
    of the nx data rows only, then axis x of the zero-padded spectrum; backwards axis x, then
    y of the nx + 1 rows wanted."""

    def __init__(self, op):
        nx, ny = op.shape
        Lx, Ly = op.L
        Tx, Ty = op.T
        self.nx, self.ny, self.Ly, self.Ty = nx, ny, Ly, Ty
        self.hat, self.inv = op.hat, op.inv
        self.rin = np.zeros((2, nx, Ly))
        self.cin = np.zeros((2, Lx, Ly // 2 + 1), complex)
        self.cmid = np.zeros_like(self.cin)
        self.cback = np.zeros_like(self.cin)
        self.rout = np.zeros((2, nx + 1, Ly))
        self.tin = np.zeros((4, Tx, Ty))
        self.tspec = np.zeros((4, Tx, Ty // 2 + 1), complex)
        self.tout = np.zeros((4, Tx, Ty))
        self.conv_in = self.rin[:, :, :ny]          # views: fill them in place to skip a copy
        self.prec_in = self.tin[:, :nx, :ny]

    def convolve(self, P):
        nx, ny = self.nx, self.ny
        if P is not self.conv_in:
            self.rin[:, :, :ny] = P
        if _pocketfft is None:   # pragma: no cover
            F = sfft.rfft2(P, s=self.cin.shape[1:2] + (self.Ly,), workers=1)
            _kernel_product(F, self.hat)
            return sfft.irfft2(F, s=self.cin.shape[1:2] + (self.Ly,), workers=1)[:, : nx + 1, :ny]
        _pocketfft.r2c(self.rin, (2,), True, 0, self.cin[:, :nx], 1)
        _pocketfft.c2c(self.cin, (1,), True, 0, self.cmid, 1)
        _kernel_product(self.cmid, self.hat)
        _pocketfft.c2c(self.cmid, (1,), False, 2, self.cback, 1)
        _pocketfft.c2r(self.cback[:, : nx + 1], (2,), self.Ly, False, 2, self.rout, 1)
        return self.rout[:, :, :ny]

    def precondition(self, R, inv_a, inv_b):
        """Fields 0, 1 of R (4, nx, ny) with the symbol inv_a, 2, 3 with inv_b; a pair whose
        symbol is None is skipped (left as it is in the output)."""
        nx, ny = self.nx, self.ny
        lo = 0 if inv_a is not None else 2
        hi = 4 if inv_b is not None else 2
        tin, tspec, tout = self.tin[lo:hi], self.tspec[lo:hi], self.tout[lo:hi]
        if R is not self.prec_in:
            tin[:, :nx, :ny] = R[lo:hi]
        if _pocketfft is None:   # pragma: no cover
            tspec[:] = sfft.rfft2(tin, workers=1)
        else:
            _pocketfft.r2c(tin, (1, 2), True, 0, tspec, 1)
        if inv_a is not None:
            _kernel_product(tspec[:2], inv_a)
        if inv_b is not None:
            _kernel_product(tspec[hi - 2:], inv_b)
        if _pocketfft is None:   # pragma: no cover
            tout[:] = sfft.irfft2(tspec, s=tin.shape[1:], workers=1)
        else:
            _pocketfft.c2r(tspec, (1, 2), self.Ty, False, 2, tout, 1)
        return self.tout[:, :nx, :ny]


@numba.njit(cache=True)
def _kernel_product(F, h):
    """F <- (h11 F1 + h12 F2, h12 F1 + h22 F2) in place (the 2x2 symmetric block symbol)."""
    for i in range(F.shape[1]):
        for j in range(F.shape[2]):
            a, b = F[0, i, j], F[1, i, j]
            F[0, i, j] = h[0, i, j] * a + h[1, i, j] * b
            F[1, i, j] = h[1, i, j] * a + h[2, i, j] * b


@functools.lru_cache(maxsize=64)
def tangential_operator(shape, dx, dy, E=210e9, nu=0.3) -> TangentialOperator:
    """The FFT influence operator of a grid (cached per grid and material)."""
    return TangentialOperator(tuple(int(n) for n in shape), float(dx), float(dy), float(E), float(nu))


# ----------------------------------------------------------------------------------------------
# element kernels (numba): compact element vectors <-> grid arrays
# ----------------------------------------------------------------------------------------------

@numba.njit(cache=True)
def _scatter(ix, iy, p, out):
    """out (2, nx, ny) <- 0, p (N, 2) on the elements."""
    out[:] = 0.0
    for k in range(ix.shape[0]):
        out[0, ix[k], iy[k]] = p[k, 0]
        out[1, ix[k], iy[k]] = p[k, 1]


@numba.njit(cache=True)
def _gather_slip(ix, iy, u, steady, r, s):
    """s (N, 2) <- r + M p from the displacements u (2, nx + 1, ny) of p."""
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        for a in range(2):
            m = u[a, i, j]
            if steady:
                m -= u[a, i + 1, j]
            s[k, a] = r[k, a] + m


@numba.njit(cache=True)
def _lift(ix, iy, stick, t, x, out):
    """Newton variables x (N, 2) -> traction increments on the grid: stick (x0, x1), slip x0 t."""
    out[:] = 0.0
    for k in range(ix.shape[0]):
        if stick[k]:
            out[0, ix[k], iy[k]] = x[k, 0]
            out[1, ix[k], iy[k]] = x[k, 1]
        else:
            out[0, ix[k], iy[k]] = x[k, 0] * t[k, 0]
            out[1, ix[k], iy[k]] = x[k, 0] * t[k, 1]


@numba.njit(cache=True)
def _jacobian_rows(ix, iy, stick, t, D, u, steady, scale, x, y):
    """y = J x (scaled by 1/scale): stick rows M dp, slip rows t . M dp + D x0 (dummy 0)."""
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        m0, m1 = u[0, i, j], u[1, i, j]
        if steady:
            m0 -= u[0, i + 1, j]
            m1 -= u[1, i + 1, j]
        if stick[k]:
            y[k, 0] = m0 / scale
            y[k, 1] = m1 / scale
        else:
            y[k, 0] = (t[k, 0] * m0 + t[k, 1] * m1) / scale + D[k] * x[k, 0]
            y[k, 1] = 0.0


@numba.njit(cache=True)
def _precondition_in(ix, iy, stick, t, sc, x, steady, slip_fft, out):
    """Fields of the preconditioner's transform: 0, 1 the stick part of x (steady: summed along x
    from the leading edge, the exact inverse of the transport difference I - shift on each grid
    line); 2, 3 (slip_fft) the slip part lifted along the tangents, scaled by sc."""
    out[:] = 0.0
    for k in range(ix.shape[0]):
        if stick[k]:
            out[0, ix[k], iy[k]] = x[k, 0]
            out[1, ix[k], iy[k]] = x[k, 1]
        elif slip_fft:
            out[2, ix[k], iy[k]] = sc[k] * x[k, 0] * t[k, 0]
            out[3, ix[k], iy[k]] = sc[k] * x[k, 0] * t[k, 1]
    if steady:
        nx = out.shape[1]
        for a in range(2):
            for j in range(out.shape[2]):
                for i in range(nx - 2, -1, -1):
                    out[a, i, j] += out[a, i + 1, j]


@numba.njit(cache=True)
def _precondition_out(ix, iy, stick, t, sc, D, mdiag, z, slip_fft, x, y):
    """y = P^-1 x from the transformed fields z: stick z[0:2]; slip sc t . z[2:4] (slip_fft) or
    the diagonal 1 / (t' M_II t + D) (scaled units)."""
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        if stick[k]:
            y[k, 0] = z[0, i, j]
            y[k, 1] = z[1, i, j]
        else:
            if slip_fft:
                y[k, 0] = sc[k] * (t[k, 0] * z[2, i, j] + t[k, 1] * z[3, i, j])
            else:
                m = t[k, 0] * t[k, 0] * mdiag[0] + t[k, 1] * t[k, 1] * mdiag[1]
                y[k, 0] = x[k, 0] / (m + D[k])
            y[k, 1] = 0.0


@numba.njit(cache=True)
def _slip_scaling(stick, t, D, mdiag, sc):
    """Median of D over the slip elements and the symmetric scaling sqrt((m + dbar) / (m + D))."""
    n = 0
    for k in range(stick.shape[0]):
        if not stick[k]:
            n += 1
    if n == 0:
        return 0.0
    vals = np.empty(n)
    n = 0
    for k in range(stick.shape[0]):
        if not stick[k]:
            vals[n] = D[k]
            n += 1
    dbar = np.median(vals)
    for k in range(stick.shape[0]):
        if not stick[k]:
            m = t[k, 0] * t[k, 0] * mdiag[0] + t[k, 1] * t[k, 1] * mdiag[1]
            sc[k] = math.sqrt((m + dbar) / (m + D[k]))
    return dbar


@numba.njit(cache=True)
def _pcg_direction(ix, iy, stick, t, sc, D, mdiag, Z, slip_fft, r, z, rz_old, d, lifted):
    """PCG: z = P^-1 r from the preconditioner's transform Z, rz = r . z, d = z + (rz / rz_old) d
    (d = z when rz_old = 0) and d lifted onto the grid for the next product.  Returns rz."""
    _precondition_out(ix, iy, stick, t, sc, D, mdiag, Z, slip_fft, r, z)
    rz = 0.0
    for k in range(r.shape[0]):
        rz += r[k, 0] * z[k, 0] + r[k, 1] * z[k, 1]
    beta = rz / rz_old if rz_old != 0.0 else 0.0
    for k in range(r.shape[0]):
        d[k, 0] = z[k, 0] + beta * d[k, 0]
        d[k, 1] = z[k, 1] + beta * d[k, 1]
    _lift(ix, iy, stick, t, d, lifted)
    return rz


@numba.njit(cache=True)
def _pcg_update(ix, iy, stick, t, D, U, steady, scale, d, q, rz, x, r, sc, slip_fft, prec_in):
    """PCG: q = J d from the displacements U of the lifted d, alpha = rz / (d . q), x += alpha d,
    r -= alpha q, and r prepared for the preconditioner.  Returns (|r|^2, d . q)."""
    _jacobian_rows(ix, iy, stick, t, D, U, steady, scale, d, q)
    dq = 0.0
    for k in range(d.shape[0]):
        dq += d[k, 0] * q[k, 0] + d[k, 1] * q[k, 1]
    if dq <= 0.0:
        return 0.0, dq
    alpha = rz / dq
    rr = 0.0
    for k in range(d.shape[0]):
        for a in range(2):
            x[k, a] += alpha * d[k, a]
            r[k, a] -= alpha * q[k, a]
            rr += r[k, a] * r[k, a]
    _precondition_in(ix, iy, stick, t, sc, r, steady, slip_fft, prec_in)
    return rr, dq


@numba.njit(cache=True)
def _residual(stick, t, s, R):
    """Newton residual: stick s, slip (t . s, 0).  Returns its max norm."""
    big = 0.0
    for k in range(s.shape[0]):
        if stick[k]:
            R[k, 0], R[k, 1] = s[k, 0], s[k, 1]
        else:
            R[k, 0] = t[k, 0] * s[k, 0] + t[k, 1] * s[k, 1]
            R[k, 1] = 0.0
        big = max(big, abs(R[k, 0]), abs(R[k, 1]))
    return big


@numba.njit(cache=True)
def _slip_geometry(stick, theta, g, s, p, t, D, scale):
    """Tractions of slip elements on their circle g (cos, sin)(theta); tangents t (all elements,
    from the traction direction); D = max(-s . n, 0) / g / scale on slip (the turning term)."""
    for k in range(theta.shape[0]):
        if stick[k]:
            th = math.atan2(p[k, 1], p[k, 0])
            D[k] = 0.0
        else:
            th = theta[k]
        c, sn = math.cos(th), math.sin(th)
        t[k, 0], t[k, 1] = -sn, c
        if not stick[k]:
            p[k, 0], p[k, 1] = g[k] * c, g[k] * sn
            D[k] = max(-(s[k, 0] * c + s[k, 1] * sn), 0.0) / max(g[k], 1e-300) / scale


@numba.njit(cache=True)
def _apply_step(stick, theta, g, dz, p, clip):
    """p += dz on stick, theta += dz0 / g (clipped) on slip; returns the largest change [Pa]."""
    change = 0.0
    for k in range(stick.shape[0]):
        if stick[k]:
            p[k, 0] += dz[k, 0]
            p[k, 1] += dz[k, 1]
            change = max(change, abs(dz[k, 0]), abs(dz[k, 1]))
        else:
            dth = dz[k, 0] / max(g[k], 1e-300)
            if dth > clip:
                dth = clip
            elif dth < -clip:
                dth = -clip
            theta[k] += dth
            p[k, 0] = g[k] * math.cos(theta[k])
            p[k, 1] = g[k] * math.sin(theta[k])
            change = max(change, g[k] * abs(dth))
    return change


@numba.njit(cache=True)
def _update_sets(stick, theta, g, p, s, rel):
    """Kalker's set update: stick elements beyond the bound -> slip (projected onto the bound);
    slip elements whose slip points along the traction -> stick.  Returns (moved to slip,
    moved to stick)."""
    s_scale = 1e-300
    for k in range(stick.shape[0]):
        s_scale = max(s_scale, abs(s[k, 0]), abs(s[k, 1]))
    n_slip = 0
    n_stick = 0
    for k in range(stick.shape[0]):
        if stick[k]:
            a = math.hypot(p[k, 0], p[k, 1])
            if a > g[k] * (1.0 + rel):
                stick[k] = False
                theta[k] = math.atan2(p[k, 1], p[k, 0])
                p[k, 0] *= g[k] / a
                p[k, 1] *= g[k] / a
                n_slip += 1
        else:
            if s[k, 0] * p[k, 0] + s[k, 1] * p[k, 1] > rel * s_scale * g[k]:
                stick[k] = True
                n_stick += 1
    return n_slip, n_stick


# ----------------------------------------------------------------------------------------------
# Krylov solvers (matrix-free, preconditioned)
# ----------------------------------------------------------------------------------------------

@numba.njit(cache=True)
def _givens(h, hnext, cs, sn, e, k):
    """GMRES: apply the previous Givens rotations to column h (k + 1), make the new one that
    zeroes hnext, and rotate the right-hand side e."""
    for j in range(k):
        a, b = h[j], h[j + 1]
        h[j] = cs[j] * a + sn[j] * b
        h[j + 1] = -sn[j] * a + cs[j] * b
    den = math.hypot(h[k], hnext)
    if den > 0.0:
        cs[k], sn[k] = h[k] / den, hnext / den
    else:
        cs[k], sn[k] = 1.0, 0.0
    h[k] = den
    e[k + 1] = -sn[k] * e[k]
    e[k] = cs[k] * e[k]


def _gmres(A, P, b, rtol, kmax, restarts=3):
    """Right-preconditioned restarted GMRES (classical Gram-Schmidt, repeated when it cancels;
    Givens rotations): x with |b - A x| <= rtol |b|.  Returns x, steps (operator applications)."""
    shape = b.shape
    n = b.size
    bflat = b.ravel()
    bn = float(np.linalg.norm(bflat))
    x = np.zeros(n)
    if bn == 0.0:
        return x.reshape(shape), 0
    steps = 0
    r = bflat.copy()
    V = np.empty((kmax + 1, n))
    Z = np.empty((kmax, n))
    H = np.zeros((kmax + 1, kmax))
    for _ in range(restarts + 1):
        beta = float(np.linalg.norm(r))
        if beta <= rtol * bn:
            break
        cs, sn = np.zeros(kmax), np.zeros(kmax)
        e = np.zeros(kmax + 1)
        e[0] = beta
        V[0] = r / beta
        k_used = 0
        for k in range(kmax):
            Z[k] = P(V[k].reshape(shape)).ravel()
            w = A(Z[k].reshape(shape)).ravel()
            steps += 1
            Vk = V[: k + 1]
            wn = float(np.linalg.norm(w))
            h = Vk @ w
            w -= h @ Vk
            hnext = float(np.linalg.norm(w))
            if hnext < 0.5 * wn:         # cancellation: re-orthogonalise (CGS2, Kahan-Parlett)
                h2 = Vk @ w
                w -= h2 @ Vk
                h += h2
                hnext = float(np.linalg.norm(w))
            _givens(h, hnext, cs, sn, e, k)
            H[: k + 1, k] = h
            k_used = k + 1
            if abs(e[k + 1]) <= rtol * bn or hnext == 0.0:
                break
            V[k + 1] = w / hnext
        y = np.zeros(k_used)
        for i in range(k_used - 1, -1, -1):
            y[i] = (e[i] - np.dot(H[i, i + 1:k_used], y[i + 1:k_used])) / H[i, i]
        x += y @ Z[:k_used]
        if abs(e[k_used]) > rtol * bn:   # not converged in this cycle: true residual, restart
            r = bflat - A(x.reshape(shape)).ravel()
            steps += 1
        else:
            break
    return x.reshape(shape), steps


# ----------------------------------------------------------------------------------------------
# the Coulomb solver
# ----------------------------------------------------------------------------------------------

class CoulombResult(NamedTuple):
    p: np.ndarray           # (N, 2) tractions
    s: np.ndarray           # (N, 2) slip [displacement per step], 0 on stick
    stick: np.ndarray       # (N,) bool
    u: np.ndarray           # (2, nx + 1, ny) displacements of the final tractions (grid + one row ahead)
    newton: int
    krylov: int
    converged: bool


def solve_coulomb(op: TangentialOperator, ix, iy, r, g, p, stick, *, steady: bool, tol=TOL,
                  max_iter=200, warm=False, u_start=None) -> CoulombResult:
    """Kalker's active-set Newton solver for s = r + M p on the contact elements (ix, iy) of the
    operator's grid (r, p: (N, 2) [m per step, Pa]; g = mu p3 (N,)), per element: stick s = 0,
    |p| <= g, or slip |p| = g, p = -g s/|s|.  M = A (transient) or A - A(x + dx) (steady).
    `p`, `stick`: start values (a previous solution, or zeros and all-stick).  Stops when no
    element changes set and the Newton step is below tol times the traction level
    (max(|p|)).  `warm`: the start is a previous solution (its sets are trusted for the first
    step); `u_start` (2, nx, ny): transient only, the displacements of the start tractions if
    known (a prediction: they start the first Newton step without a product).  Returns a
    CoulombResult."""
    ix = np.ascontiguousarray(ix, dtype=np.int64)
    iy = np.ascontiguousarray(iy, dtype=np.int64)
    N = ix.shape[0]
    r = np.ascontiguousarray(r, dtype=float).reshape(N, 2)
    g = np.ascontiguousarray(g, dtype=float)
    p = np.array(p, dtype=float).reshape(N, 2)
    stick = np.array(stick, dtype=bool)
    bufs = op.buffers
    grid = bufs.conv_in                       # the FFT input arrays, filled in place
    scale = op.scale
    mdiag = op.a0 - op.a1 if steady else op.a0.copy()
    mdiag_s = mdiag / scale
    theta = np.arctan2(p[:, 1], p[:, 0])
    t = np.zeros((N, 2))
    D = np.zeros(N)
    s = np.zeros((N, 2))
    R = np.zeros((N, 2))
    # start: slip elements on their circle, stick elements inside their bound
    p_given = p.copy() if u_start is not None else None
    _slip_geometry(stick, theta, g, s, p, t, D, scale)
    over = stick & (np.hypot(p[:, 0], p[:, 1]) > g)
    if over.any():
        p[over] *= (g[over] / np.hypot(p[over, 0], p[over, 1]))[:, None]
    if p_given is not None:       # the predicted displacements hold for the start only if it was kept
        level = max(float(np.abs(p).max(initial=0.0)), 1e-300)
        if float(np.abs(p - p_given).max(initial=0.0)) > 1e-3 * math.sqrt(tol / QUADRATIC) * level:
            u_start = None

    def slip_of(pp):
        _scatter(ix, iy, pp, grid)
        u = op.displacements(grid)
        _gather_slip(ix, iy, u, steady, r, s)
        return u

    def J(x):
        _lift(ix, iy, stick, t, x, grid)
        u = op.displacements(grid)
        y = np.empty_like(x)
        _jacobian_rows(ix, iy, stick, t, D, u, steady, scale, x, y)
        return y

    grid4 = bufs.prec_in
    sc = np.ones(N)
    inv_slip = [None]
    inv_stick = [op.inv]
    slip_fft = not steady

    def Pinv(x):
        four = slip_fft and inv_slip[0] is not None
        _precondition_in(ix, iy, stick, t, sc, x, steady, four, grid4)
        z = op.precondition(grid4, inv_stick[0], inv_slip[0] if four else None)
        y = np.empty_like(x)
        _precondition_out(ix, iy, stick, t, sc, D, mdiag_s, z, four, x, y)
        return y

    q_vec, z_vec, d_vec = np.zeros((N, 2)), np.zeros((N, 2)), np.zeros((N, 2))

    def pcg(b, rtol, kmax):
        """J x = b by preconditioned CG (transient: J symmetric positive definite), fused kernels."""
        x = np.zeros((N, 2))
        rv = b.copy()
        bn2 = float((b * b).sum())
        if bn2 == 0.0:
            return x, 0
        four = inv_slip[0] is not None
        _precondition_in(ix, iy, stick, t, sc, rv, False, four, grid4)
        Z = op.precondition(grid4, inv_stick[0], inv_slip[0])
        rz = _pcg_direction(ix, iy, stick, t, sc, D, mdiag_s, Z, four, rv, z_vec, 0.0, d_vec, grid)
        for k in range(1, kmax + 1):
            U = op.displacements(grid)
            rr, dq = _pcg_update(ix, iy, stick, t, D, U, False, scale, d_vec, q_vec, rz, x, rv, sc, four,
                                 grid4)
            if dq <= 0.0 or rr <= rtol * rtol * bn2:
                return x, k
            Z = op.precondition(grid4, inv_stick[0], inv_slip[0])
            rz = _pcg_direction(ix, iy, stick, t, sc, D, mdiag_s, Z, four, rv, z_vec, rz, d_vec, grid)
        return x, kmax

    if u_start is not None and not steady:
        _gather_slip(ix, iy, u_start, False, r, s)
        u = None
    else:
        u = slip_of(p)
    newton = krylov = 0
    converged = False
    sets_changed = not warm
    n_changed = N if not warm else 0
    few = 2                                     # set changes after which the next step may be final
    p_level = max(float(np.abs(p).max(initial=0.0)), 1e-300)
    q_lim = math.sqrt(tol / QUADRATIC)           # steps this small are final (quadratic convergence) ...
    eta_final = min(1e-3, 0.1 * tol / q_lim)      # ... if solved this accurately
    ratio = 0.0
    for newton in range(1, max_iter + 1):
        _slip_geometry(stick, theta, g, s, p, t, D, scale)
        r_max = _residual(stick, t, s, R)
        inv_stick[0] = op.inv if stick.any() else None
        if slip_fft:
            if stick.all():
                inv_slip[0] = None
            else:
                inv_slip[0] = shifted_inverse(op.symbol, _slip_scaling(stick, t, D, mdiag_s, sc))
        b = -R / scale
        if n_changed > few or (newton == 1 and steady):
            eta = 1e-2        # the sets are still moving: a rough step
        elif ratio > 0.0:     # expected step from the last step per unit residual: absolute accuracy
            eta = min(0.1, max(eta_final, 0.1 * tol * p_level / max(ratio * r_max, 1e-300)))
        else:
            eta = eta_final
        if steady:
            dz, k = _gmres(J, Pinv, b, eta, 40)
        else:
            dz, k = pcg(b, eta, 200)
        krylov += k
        change = _apply_step(stick, theta, g, dz, p, 0.5)
        ratio = change / max(r_max, 1e-300)
        u = slip_of(p)
        to_slip, to_stick = _update_sets(stick, theta, g, p, s, 1e-9)
        p_level = max(float(np.abs(p).max(initial=0.0)), 1e-300)
        final = change <= tol * p_level or (not sets_changed and change <= q_lim * p_level
                                            and eta * change <= 0.1 * tol * p_level)
        n_changed = to_slip + to_stick
        sets_changed = n_changed > 0
        if not sets_changed and final:
            converged = True
            break
        if to_slip:                   # projected tractions: the slip follows
            u = slip_of(p)
    s_out = s.copy()
    s_out[stick] = 0.0
    return CoulombResult(p, s_out, stick, u.copy(), newton, krylov, converged)


# ----------------------------------------------------------------------------------------------
# public API
# ----------------------------------------------------------------------------------------------

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


PAD = 1                     # elements around the contact's bounding box in the working window


def _window(contact, pad=PAD):
    """Bounding box of the contact elements grown by `pad`, clipped to the grid: (i0, i1, j0, j1)
    inclusive, or None without contact."""
    rows = np.flatnonzero(contact.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(contact.any(axis=0))
    nx, ny = contact.shape
    return (max(int(rows[0]) - pad, 0), min(int(rows[-1]) + pad, nx - 1),
            max(int(cols[0]) - pad, 0), min(int(cols[-1]) + pad, ny - 1))


def _inside(w, v):
    """Window w inside window v."""
    return v is not None and w[0] >= v[0] and w[1] <= v[1] and w[2] >= v[2] and w[3] <= v[3]


def _solve(p3, dx, dy, v, mu, gamma_x, gamma_y, spin, w_offset, steady, E, nu, warm, tol, full_output):
    """Common driver of tang_steady / tang_transient: the problem on the contact's window."""
    p3 = np.asarray(p3, dtype=float)
    shape = p3.shape
    nx, ny = shape
    contact = p3 > 0.0
    dt = dx / v
    ix, iy = np.nonzero(contact)
    N = ix.size
    win = _window(contact)
    if win is not None and warm is not None and warm.p1.shape == shape and warm.history is not None:
        # keep the previous step's window while the contact fits in it (a stable window keeps the
        # predictor's history and the operator): time loops with a breathing contact area
        old = warm.history.window
        tight = _window(contact, 0)
        if _inside(tight, old) and (old[1] - old[0] + 1) * (old[3] - old[2] + 1) <= \
                2 * (win[1] - win[0] + 1) * (win[3] - win[2] + 1):
            win = old
    P1, P2, S1, S2 = (np.zeros(shape) for _ in range(4))
    st = np.zeros(shape, bool)
    # rigid slip at the contact elements, times dt (rigid_slip's formula at x_I + w_offset dx)
    xc = (ix - 0.5 * (nx - 1) + w_offset) * dx
    yc = (iy - 0.5 * (ny - 1)) * dy
    r = np.empty((N, 2))
    r[:, 0] = (gamma_x - spin * yc) * v * dt
    r[:, 1] = (gamma_y + spin * xc) * v * dt
    transient_prev = (not steady) and warm is not None and warm.p1.shape == shape
    if transient_prev:                         # transport term: -u(x + dx, t - dt)
        ahead = warm.u_ahead
        if ahead is None or not _inside(win, warm.window):
            full = tangential_operator(shape, dx, dy, E, nu)
            ahead = full.displacements(np.stack([warm.p1, warm.p2]))[:, 1:]
        r[:, 0] -= ahead[0][ix, iy]
        r[:, 1] -= ahead[1][ix, iy]
    if N == 0 or mu <= 0.0:                    # no contact or no friction: traction-free, all slip
        S1[ix, iy], S2[ix, iy] = r[:, 0] / dt, r[:, 1] / dt
        zero = np.zeros(shape)
        return TangentialContact(P1, P2, st, contact.copy(), S1, S2, zero, zero.copy(), 0.0, 0.0, 0, True, 0,
                                 np.zeros((2,) + shape), None, (0, nx - 1, 0, ny - 1))
    i0, i1, j0, j1 = win
    op = tangential_operator((i1 - i0 + 1, j1 - j0 + 1), dx, dy, E, nu)
    g = mu * p3[ix, iy]
    u_start = None
    if warm is not None and warm.p1.shape == shape:
        p0 = np.column_stack([warm.p1[ix, iy], warm.p2[ix, iy]])
        stick0 = ~warm.slip[ix, iy]
        new = ~(warm.stick | warm.slip)[ix, iy]       # elements entering the contact: start sliding
        if new.any():                                 # against the rigid slip (the set update corrects)
            rn = np.hypot(r[new, 0], r[new, 1])
            ok = rn > 0.0
            idx = np.flatnonzero(new)[ok]
            p0[idx] = -(g[idx] / rn[ok])[:, None] * r[idx]
            stick0[idx] = False
        h = warm.history
        if transient_prev and h is not None and h.order > 0 and h.window == win and _inside(win, warm.window):
            dp, du = (h.dp, h.du) if h.order == 1 else (h.dp + h.d2p, h.du + h.d2u)    # predictor
            p0 += np.column_stack([dp[0][ix, iy], dp[1][ix, iy]])
            u_start = np.stack([warm.u1[i0:i1 + 1, j0:j1 + 1], warm.u2[i0:i1 + 1, j0:j1 + 1]]) \
                + du[:, i0:i1 + 1, j0:j1 + 1]
    else:
        p0, stick0 = np.zeros((N, 2)), np.ones(N, bool)
    res = solve_coulomb(op, ix - i0, iy - j0, r, g, p0, stick0, steady=steady, tol=tol, warm=warm is not None,
                        u_start=u_start)
    if not res.converged:
        warnings.warn("TANG: stick/slip sets not converged", RuntimeWarning)
    p, s = res.p, res.s
    P1[ix, iy], P2[ix, iy] = p[:, 0], p[:, 1]
    S1[ix, iy], S2[ix, iy] = s[:, 0] / dt, s[:, 1] / dt
    st[ix, iy] = res.stick
    if full_output and win != (0, nx - 1, 0, ny - 1):
        u = tangential_operator(shape, dx, dy, E, nu).displacements(np.stack([P1, P2]))
        valid = (0, nx - 1, 0, ny - 1)
        U = u[:, :nx].copy()
        ahead = np.ascontiguousarray(u[:, 1:])
    else:
        valid = win
        U = np.zeros((2, nx, ny))
        ahead = np.zeros((2, nx, ny))
        U[:, i0:i1 + 1, j0:j1 + 1] = res.u[:, : i1 - i0 + 1]
        ahead[:, i0:i1 + 1, j0:j1 + 1] = res.u[:, 1:]
    history = None
    if transient_prev:
        history = _next_history(warm.history, win, np.stack([P1 - warm.p1, P2 - warm.p2]),
                                U - np.stack([warm.u1, warm.u2]))
    dA = dx * dy
    return TangentialContact(P1, P2, st, contact & ~st, S1, S2, U[0], U[1], float(p[:, 0].sum() * dA),
                             float(p[:, 1].sum() * dA), res.newton, res.converged, res.krylov, ahead, history, valid)


def tang_steady(p3, dx, dy, v, mu, gamma_x=0.0, gamma_y=0.0, spin=0.0, E=210e9, nu=0.3, *,
                warm: TangentialContact | None = None, tol=TOL, w_offset=W_OFFSET,
                full_output=True) -> TangentialContact:
    """Steady-state rolling (du/dt = 0) with normal pressures p3 (nx, ny) [Pa] on the grid
    dx (rolling direction) x dy, rolling speed v [m/s], Coulomb coefficient mu and
    creepages gamma_x, gamma_y [-], spin [1/m].  `warm`: a previous solution as start.
    `tol`: the Newton iteration stops when no element changes set and the last step is below
    tol times the largest traction (or its remaining error is, by quadratic convergence).
    `w_offset`: where the rigid slip is evaluated, x_I + w_offset dx (module notes).
    `full_output`: u1, u2 on the whole grid (one more FFT product); False: only on the window
    around the contact (``window``), zero elsewhere."""
    return _solve(p3, dx, dy, v, mu, gamma_x, gamma_y, spin, w_offset, True, E, nu, warm, tol, full_output)


def tang_transient(p3, dx, dy, v, mu, gamma_x=0.0, gamma_y=0.0, spin=0.0, E=210e9, nu=0.3, *,
                   state: TangentialContact | None = None, tol=TOL, w_offset=W_OFFSET,
                   full_output=True) -> TangentialContact:
    """One time step dt = dx / v of transient rolling.  `state` is the previous step's
    solution (None: traction-free start); its tractions give the previous displacement
    one element ahead, u(x + dx, t - dt), and start the iteration (extrapolated from the
    last steps: the predictor that would have done best on the last step).  Call once per
    step.  `tol`, `w_offset`, `full_output` as in tang_steady (the time loop needs no
    displacements outside the contact: full_output=False saves one FFT product per step)."""
    return _solve(p3, dx, dy, v, mu, gamma_x, gamma_y, spin, w_offset, False, E, nu, state, tol, full_output)
