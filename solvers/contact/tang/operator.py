"""The FFT influence operator of TANG (notes in ``solvers.contact.tang``): Cerruti's influence of a
grid by FFT convolution on the contact's window and one row ahead, and the Strang-circulant
preconditioner, cached per grid and material (``functools.lru_cache``: keyed by value)."""
from __future__ import annotations

import functools
import threading

import numba
import numpy as np
import rocket_fft
from scipy import fft as sfft

from solvers.contact.influence import cerruti


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


class _FFTBuffers:
    """Preallocated transforms of one operator (``arrays``: the tuple the compiled solver takes).
    The convolution transforms the last axis (y) of the nx data rows only, then axis x of the
    zero-padded spectrum; backwards axis x, then y of the nx + 1 rows wanted."""

    def __init__(self, op):
        nx, ny = op.shape
        Lx, Ly = op.L
        Tx, Ty = op.T
        self.nx, self.ny = nx, ny
        self.hat = op.hat
        rin = np.zeros((2, nx, Ly))
        cin = np.zeros((2, Lx, Ly // 2 + 1), complex)
        tin = np.zeros((4, Tx, Ty))
        self.arrays = (rin, cin, np.zeros_like(cin), np.zeros_like(cin), np.zeros((2, nx + 1, Ly)),
                       tin, np.zeros((4, Tx, Ty // 2 + 1), complex), np.zeros((4, Tx, Ty)))
        self.conv_in = rin[:, :, :ny]            # views: fill them in place to skip a copy
        self.prec_in = tin[:, :nx, :ny]

    def convolve(self, P):
        if P is not self.conv_in:
            self.conv_in[:] = P
        return fft_convolve(self.arrays, self.hat, self.ny)

    def precondition(self, R, inv_a, inv_b):
        """Fields 0, 1 of R (4, nx, ny) with the symbol inv_a, 2, 3 with inv_b; a pair whose
        symbol is None is skipped (left as it is in the output)."""
        if R is not self.prec_in:
            self.prec_in[:] = R
        a = inv_a if inv_a is not None else _NO_SYMBOL
        b = inv_b if inv_b is not None else _NO_SYMBOL
        return fft_precondition(self.arrays, a, b, inv_a is not None, inv_b is not None, self.nx, self.ny)


_AX_X, _AX_Y, _AX_XY = np.array([1]), np.array([2]), np.array([1, 2])
_NO_SYMBOL = np.zeros((3, 1, 1))    # stands for a symbol not applied


@numba.njit(cache=True)
def fft_convolve(bufs, hat, ny):
    """u (2, nx + 1, ny) on the grid and one row ahead of the tractions in bufs[0][:, :, :ny]
    (a view into bufs[4]): pocketfft (rocket-fft) transforms of _FFTBuffers' arrays."""
    rin, cin, cmid, cback, rout = bufs[0], bufs[1], bufs[2], bufs[3], bufs[4]
    nx = rin.shape[1]
    rocket_fft.r2c(rin, cin[:, :nx], _AX_Y, True, 1.0, 1)
    rocket_fft.c2c(cin, cmid, _AX_X, True, 1.0, 1)
    _kernel_product(cmid, hat)
    rocket_fft.c2c(cmid, cback, _AX_X, False, 1.0 / cin.shape[1], 1)
    rocket_fft.c2r(cback[:, : nx + 1], rout, _AX_Y, False, 1.0 / rout.shape[2], 1)
    return rout[:, :, :ny]


@numba.njit(cache=True)
def fft_precondition(bufs, inv_a, inv_b, use_a, use_b, nx, ny):
    """The Strang-circulant symbols on the preconditioner's fields bufs[5][:, :nx, :ny]: fields
    0, 1 with inv_a (use_a), 2, 3 with inv_b (use_b).  Returns a view (4, nx, ny) into bufs[7]."""
    tin, tspec, tout = bufs[5], bufs[6], bufs[7]
    lo = 0 if use_a else 2
    hi = 4 if use_b else 2
    if hi > lo:
        rocket_fft.r2c(tin[lo:hi], tspec[lo:hi], _AX_XY, True, 1.0, 1)
        if use_a:
            _kernel_product(tspec[0:2], inv_a)
        if use_b:
            _kernel_product(tspec[2:4], inv_b)
        rocket_fft.c2r(tspec[lo:hi], tout[lo:hi], _AX_XY, False, 1.0 / (tin.shape[1] * tin.shape[2]), 1)
    return tout[:, :nx, :ny]


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
