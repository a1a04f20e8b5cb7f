"""Half-space influence coefficients of uniformly loaded rectangles (SPEC 4.1, 4.3).

Potential contact area: nx * ny rectangles of dx * dy (dx = v dt, SPEC 4.1);
array axis 0 is x (rolling direction, the contact travels towards +x), axis 1
is y (lateral).  A coefficient A_ab(X, Y) is the displacement component a at
the centre of an element offset by (X, Y) from the centre of a rectangle
carrying a unit uniform traction in direction b.

Both bodies are steel (same E, nu): the normal-tangential cross terms vanish
(quasi-identity, thesis 4.3.1) and the coefficients below are COMBINED
compliances of wheel + rail, twice one body's, for the displacement difference
u = u(rail) - u(wheel) under the traction p acting on the rail (SPEC 2: forces
act positive on the rail).  With G = E / (2 (1 + nu)) the point-load kernels
(Boussinesq, Cerruti; Johnson, Contact Mechanics, eqs 3.19a, 3.86a; Kalker,
Three-dimensional elastic bodies in rolling contact, 1990, ch. 1) are

    A33 = (1 - nu) / (pi G r)
    A11 = [(1 - nu) / r + nu x^2 / r^3] / (pi G)
    A22 = [(1 - nu) / r + nu y^2 / r^3] / (pi G)
    A12 = A21 = nu x y / (pi G r^3),

integrated in closed form over the loaded rectangle (Love, 1929) with the
primitives below (each a function F(s, t) with d2F/ds dt = integrand).
"""
from __future__ import annotations

import numpy as np
from scipy.fft import next_fast_len


def shear_modulus(E: float, nu: float) -> float:
    return E / (2.0 * (1.0 + nu))


def _s_asinh_t_over_s(s, t):
    """s * asinh(t / |s|), continuous (-> 0) at s = 0."""
    abs_s = np.abs(s)
    return s * np.arcsinh(t / np.where(abs_s > 0.0, abs_s, 1.0))


def _corners(F, X, Y, dx, dy):
    """Integral over the source rectangle |xi| < dx/2, |eta| < dy/2 of f(X - xi, Y - eta)
    from a primitive F of f (double difference over the corners)."""
    a, b = 0.5 * dx, 0.5 * dy
    return F(X + a, Y + b) - F(X - a, Y + b) - F(X + a, Y - b) + F(X - a, Y - b)


def _prim_inv_r(s, t):          # d2/ds dt -> 1 / r           (Love)
    return _s_asinh_t_over_s(s, t) + _s_asinh_t_over_s(t, s)


def _prim_xx(s, t):             # d2/ds dt -> s^2 / r^3
    return _s_asinh_t_over_s(t, s)


def _prim_yy(s, t):             # d2/ds dt -> t^2 / r^3
    return _s_asinh_t_over_s(s, t)


def _prim_xy(s, t):             # d2/ds dt -> s t / r^3
    return -np.hypot(s, t)


def boussinesq(X, Y, dx, dy, E, nu):
    """A33 at centre offsets (X, Y) [m] (arrays): normal displacement difference per
    unit normal pressure on a dx * dy rectangle [m/Pa] (SPEC 4.1 [4.18])."""
    G = shear_modulus(E, nu)
    return (1.0 - nu) / (np.pi * G) * _corners(_prim_inv_r, X, Y, dx, dy)


def cerruti(X, Y, dx, dy, E, nu):
    """(A11, A12, A22) at centre offsets (X, Y): tangential displacement differences
    per unit tangential traction on a dx * dy rectangle [m/Pa] (SPEC 4.3 [4.33])."""
    G = shear_modulus(E, nu)
    c = 1.0 / (np.pi * G)
    inv_r = _corners(_prim_inv_r, X, Y, dx, dy)
    a11 = c * ((1.0 - nu) * inv_r + nu * _corners(_prim_xx, X, Y, dx, dy))
    a22 = c * ((1.0 - nu) * inv_r + nu * _corners(_prim_yy, X, Y, dx, dy))
    a12 = c * nu * _corners(_prim_xy, X, Y, dx, dy)
    return a11, a12, a22


def offsets(nx, ny, dx, dy, shift_x=0):
    """Centre offsets (X, Y) of the Toeplitz kernels, shape (2nx-1, 2ny-1):
    K[k, l] belongs to the index offset (k - nx + 1 + shift_x, l - ny + 1)."""
    ix = np.arange(-(nx - 1), nx) + shift_x
    iy = np.arange(-(ny - 1), ny)
    return np.meshgrid(ix * dx, iy * dy, indexing="ij")


def normal_kernel(nx, ny, dx, dy, E, nu, shift_x=0):
    """Toeplitz kernel of A33, shape (2nx-1, 2ny-1):
    u3[i, j] = sum_kl K[i - k + nx - 1, j - l + ny - 1] p3[k, l]."""
    return boussinesq(*offsets(nx, ny, dx, dy, shift_x), dx, dy, E, nu)


def tangential_kernels(nx, ny, dx, dy, E, nu, shift_x=0):
    """Toeplitz kernels (K11, K12, K22) of the Cerruti coefficients, each (2nx-1, 2ny-1).
    shift_x = 1 gives the displacement one element ahead (x + dx) of each
    element, used by the rolling (transport) term of TANG."""
    return cerruti(*offsets(nx, ny, dx, dy, shift_x), dx, dy, E, nu)


def dense_matrix(kernel):
    """Dense (N, N) matrix, N = nx ny (C order: I = i ny + j), of a Toeplitz kernel."""
    kx, ky = kernel.shape
    nx, ny = (kx + 1) // 2, (ky + 1) // 2
    i, j = np.divmod(np.arange(nx * ny), ny)
    return kernel[(i[:, None] - i[None, :] + nx - 1), (j[:, None] - j[None, :] + ny - 1)]


class Convolver:
    """Fast u = A p for a Toeplitz kernel on the (nx, ny) grid by zero-padded FFT
    (circulant embedding on a fast FFT size >= 2n - 1, O(N log N)); several kernels
    share one transform."""

    def __init__(self, *kernels):
        kx, ky = kernels[0].shape
        self.nx, self.ny = (kx + 1) // 2, (ky + 1) // 2
        self.shape = (next_fast_len(kx, real=True), next_fast_len(ky, real=True))
        self.hat = [self._embed(k) for k in kernels]

    def _embed(self, kernel):
        nx, ny = self.nx, self.ny
        c = np.zeros(self.shape)
        # circulant column: c[m, n] = kernel at offset (m, n), negative offsets wrapped to the end
        c[:nx, :ny] = kernel[nx - 1:, ny - 1:]
        c[-(nx - 1):, :ny] = kernel[:nx - 1, ny - 1:] if nx > 1 else c[:0, :ny]
        c[:nx, -(ny - 1):] = kernel[nx - 1:, :ny - 1] if ny > 1 else c[:nx, :0]
        if nx > 1 and ny > 1:
            c[-(nx - 1):, -(ny - 1):] = kernel[:nx - 1, :ny - 1]
        return np.fft.rfft2(c)

    def transform(self, p):
        return np.fft.rfft2(p, s=self.shape)

    def back(self, q_hat):
        return np.fft.irfft2(q_hat, s=self.shape)[: self.nx, : self.ny]

    def __call__(self, p, which=0):
        return self.back(self.transform(p) * self.hat[which])


def strang_inverse_symbol(kernel, floor=1e-3):
    """1 / eigenvalues of Strang's circulant approximation of a Toeplitz kernel on a
    torus of fast FFT size >= (nx, ny) (offsets wrapped at half the torus): an SPD
    preconditioner for the conjugate-gradient solvers, applied to r (nx, ny) as
    irfft2(rfft2(r, s=torus) * symbol)[:nx, :ny]."""
    kx, ky = kernel.shape
    nx, ny = (kx + 1) // 2, (ky + 1) // 2
    Lx, Ly = next_fast_len(nx, real=True), next_fast_len(ny, real=True)
    mx = np.arange(Lx)
    mx = np.where(mx < (Lx + 1) // 2, mx, mx - Lx)
    my = np.arange(Ly)
    my = np.where(my < (Ly + 1) // 2, my, my - Ly)
    ox = np.clip(mx + nx - 1, 0, kx - 1)            # offsets beyond the kernel: decayed, use the edge
    oy = np.clip(my + ny - 1, 0, ky - 1)
    c = kernel[ox[:, None], oy[None, :]] * ((np.abs(mx) < nx)[:, None] & (np.abs(my) < ny)[None, :])
    lam = np.fft.rfft2(c).real
    return 1.0 / np.maximum(lam, floor * lam.max())
