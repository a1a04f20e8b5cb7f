"""The rail's moving Green's function from its wave table, fast (SPEC 3.4; thesis [4.3]-[4.5]).

``solvers.greens.kernels.moving_green`` (the reference) evaluates Kropp's construction at every lag k
from the transfer receptance G^R(x_k, f_m) at x_k = v k dt:

    g_mov[k] = sum_m c_m cos(2 pi m k / N_t) 2 Re G^R(x_k, f_m),   c_m = w_m / N_t,

(w_m = 2, and 1 at m = 0 and m = N_t/2; halved at k = 0).  With the receptance as a wave sum
(``solvers.rail.response.wave_table``: G(x, f_m) = sum_n a_mn exp(-i k_mn x), Im k_mn <= 0) the
term of wave n at frequency m is a geometric sequence in k,

    a_mn exp(-i k_mn v dt k) = a_mn z_mn^k,   z_mn = exp(-i k_mn v dt),  |z_mn| <= 1,

so the whole kernel is

    g_mov[k] = sum_m 2 c_m cos(2 pi m k / N_t) sum_n Re(a_mn z_mn^k),

evaluated here by running the powers z^k (one complex multiply per wave, lag and frequency,
re-anchored by an exact exp every ``ANCHOR`` lags so rounding does not accumulate) instead of
one complex exp and an einsum per (wave, distance, frequency).  The evanescent near-field waves
(most of the ~240 per frequency: |Im k| of tens to hundreds 1/m) die out within a fraction of
the kernel: a wave is dropped from lag L_mn on, where its geometric remainder
|a_mn| |z_mn|^L / (1 - |z_mn|) falls below ``tol`` * max_m |G(0, f_m)|.  The neglected part of
any lag is therefore below tol * nf * max|G(0)| * 2 / N_t * M (a bound, ~1e-13 of the kernel's
peak at tol = 1e-17); everything else is the same sum in another order.  Together this is about
20x less work than the reference, and every operation is a multiply-add in numba.

Symmetric rail: the kernel at y^R < 0 is the kernel at |y^R| with g23, g32 negated (the wave
table's mirror rule, ``solvers.rail.response.wave_table``), exactly: ``mirror``.
"""
from __future__ import annotations

import math

import numba
import numpy as np

ANCHOR = 256      # lags between exact re-evaluations of z^k


def moving_green_waves(k_table: np.ndarray, a_table: np.ndarray, v: float, dt: float, n_k: int, n_t: int,
                       tol: float = 1e-17) -> np.ndarray:
    """g_mov[k], k = 0..n_k-1, (n_k, 2, 2) m/N, of the wave table on Kropp's grid (module notes).

    k_table (nf, M) complex rad/m (Im <= 0) and a_table (nf, M, 2, 2) complex m/N: the waves at the
    grid frequencies f_m = m / (N_t dt), m = 0..nf-1 (any taper already applied to a); the
    receptance is zero on the grid above.  nf <= N_t/2 + 1.  Equals
    ``solvers.greens.kernels.moving_green(transfer, v, dt, n_k, n_t)`` with
    transfer(x, f_m) = sum_n a_mn exp(-i k_mn |x|) (tests/greens/test_moving_kernel.py: 1e-9 of
    its peak, in practice ~1e-14)."""
    k_table = np.ascontiguousarray(k_table, dtype=complex)
    a = np.ascontiguousarray(np.asarray(a_table, complex).reshape(k_table.shape + (4,)))
    nf, M = k_table.shape
    n_t, n_k = int(n_t), int(n_k)
    if n_t % 2 or n_t < 2:
        raise ValueError(f"n_t must be even, got {n_t}")
    if not 1 <= n_k <= n_t // 2 + 1:
        raise ValueError(f"n_k = {n_k} must lie in 1..N_t/2 + 1 = {n_t // 2 + 1}")
    if nf > n_t // 2 + 1:
        raise ValueError(f"the wave table has {nf} frequencies, the grid only N_t/2 + 1 = {n_t // 2 + 1}")
    if np.any(k_table.imag > 1e-12 * np.maximum(np.abs(k_table), 1.0)):
        raise ValueError("wave table: every wave must decay in +x (Im k <= 0)")
    step = float(v) * float(dt)
    w = np.full(nf, 2.0)
    w[0] = 1.0
    if nf == n_t // 2 + 1:
        w[-1] = 1.0
    coef = 2.0 * w / n_t
    g0 = float(np.abs(a.sum(axis=1)).max()) if a.size else 0.0
    g = _kernel_sum(k_table, a, coef, step, n_k, n_t, tol * g0)
    g[0] *= 0.5
    return g.reshape(n_k, 2, 2)


@numba.njit(cache=True, fastmath=True)
def _kernel_sum(K, A, coef, step, n_k, n_t, eps):
    """sum_m coef_m cos(2 pi m k / N_t) sum_n Re(A_mn z_mn^k) (module notes).  One power z^k per
    wave (shared by its four components), the waves' data contiguous per component (structure of
    arrays), so that the sum over the active waves is a vectorised loop (fastmath: reassociated
    sums, ~1e-16 of the kernel's peak)."""
    nf, M = K.shape
    g = np.zeros((n_k, 4))
    s = np.zeros((n_k, 4))
    ar = np.empty((4, M))
    ai = np.empty((4, M))
    qr = np.empty(M)
    qi = np.empty(M)
    zr = np.empty(M)
    zi = np.empty(M)
    length = np.empty(M, np.int64)
    for m in range(nf):
        # active length of every wave: |a| |z|^L / (1 - |z|) < eps from L on
        for n in range(M):
            amax = 0.0
            for c in range(4):
                amax = max(amax, abs(A[m, n, c]))
            d = -K[m, n].imag * step              # decay per lag (>= 0)
            if amax == 0.0:
                length[n] = 0
            elif d <= 0.0:
                length[n] = n_k
            else:
                rem = amax / (1.0 - math.exp(-d)) if d < 700.0 else amax
                L = math.log(rem / eps) / d + 1.0 if rem > eps else 0.0
                length[n] = n_k if L >= n_k else int(L)
        order = np.argsort(-length)    # a new array: "order[:] = ..." costs ~2.5 s of compiling (its shape check)
        n_act = 0
        while n_act < M and length[order[n_act]] > 0:
            n_act += 1
        for j in range(n_act):                    # the active waves, longest first
            n = order[j]
            z = np.exp(-1j * K[m, n] * step)
            zr[j] = z.real
            zi[j] = z.imag
            for c in range(4):
                ar[c, j] = A[m, n, c].real
                ai[c, j] = A[m, n, c].imag
        s[:, :] = 0.0
        k0 = 0
        while k0 < n_k:
            while n_act > 0 and length[order[n_act - 1]] <= k0:
                n_act -= 1
            if n_act == 0:
                break
            for j in range(n_act):                # exact anchor: q = z^k0
                e = np.exp(-1j * K[m, order[j]] * (step * k0))
                qr[j] = e.real
                qi[j] = e.imag
            k1 = min(n_k, k0 + ANCHOR)
            for k in range(k0, k1):
                while n_act > 0 and length[order[n_act - 1]] <= k:
                    n_act -= 1
                s0 = 0.0
                s1 = 0.0
                s2 = 0.0
                s3 = 0.0
                for j in range(n_act):            # Re(a z^k), then z^(k+1)
                    a = qr[j]
                    b = qi[j]
                    s0 += ar[0, j] * a - ai[0, j] * b
                    s1 += ar[1, j] * a - ai[1, j] * b
                    s2 += ar[2, j] * a - ai[2, j] * b
                    s3 += ar[3, j] * a - ai[3, j] * b
                    qr[j] = a * zr[j] - b * zi[j]
                    qi[j] = a * zi[j] + b * zr[j]
                s[k, 0] = s0
                s[k, 1] = s1
                s[k, 2] = s2
                s[k, 3] = s3
            k0 = k1
        cm = coef[m]
        th = 2.0 * math.pi / n_t
        for k in range(n_k):
            ck = cm * math.cos(th * ((k * m) % n_t))
            for c in range(4):
                g[k, c] += ck * s[k, c]
    return g


def mirror(g: np.ndarray) -> np.ndarray:
    """The kernel (or receptance: the dtype is kept) of the mirror-image head point (y^R -> -y^R):
    g23 and g32 change sign."""
    out = np.array(g, copy=True)
    out[..., 0, 1] *= -1.0
    out[..., 1, 0] *= -1.0
    return out
