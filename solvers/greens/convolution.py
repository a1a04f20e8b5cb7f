"""Discrete convolutions without the instantaneous term (SPEC 3.5, [4.15]): direct, overlap-add
FFT over a whole history, and per step with a ring buffer (notes in ``solvers.greens.kernels``)."""
from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np


@numba.njit(cache=True)
def convolve_direct(g, F):
    """Reference discrete convolution without the instantaneous term:
    xi[n] = sum_{k=1}^{min(n, K-1)} g[k] @ F[n-k]; g (K, 2, 2), F (nt, 2) -> (nt, 2)."""
    K = g.shape[0]
    nt = F.shape[0]
    xi = np.zeros((nt, 2))
    for n in range(1, nt):
        x2 = 0.0
        x3 = 0.0
        kmax = min(n, K - 1)
        for k in range(1, kmax + 1):
            f2 = F[n - k, 0]
            f3 = F[n - k, 1]
            x2 += g[k, 0, 0] * f2 + g[k, 0, 1] * f3
            x3 += g[k, 1, 0] * f2 + g[k, 1, 1] * f3
        xi[n, 0] = x2
        xi[n, 1] = x3
    return xi


def convolve_fft(g: np.ndarray, F: np.ndarray) -> np.ndarray:
    """The same as ``convolve_direct`` by overlap-add FFT convolution
    (scipy.signal.oaconvolve picks the block length): exact to rounding."""
    from scipy.signal import oaconvolve  # lazy: brings in scipy

    g = np.asarray(g, float)
    F = np.asarray(F, float)
    nt = F.shape[0]
    xi = np.zeros((nt, 2))
    if nt < 2 or g.shape[0] < 2:
        return xi
    for i in range(2):
        acc = np.zeros(nt - 1)
        for j in range(2):
            acc += oaconvolve(F[: nt - 1, j], g[1:, i, j], mode="full")[: nt - 1]
        xi[1:, i] = acc
    return xi


class RingState(NamedTuple):
    """The ring convolver's state, changed in place by ``ring_step``: buf (2K, 2) the doubled ring
    of past forces, pos (1,) int the write position."""
    buf: np.ndarray
    pos: np.ndarray


def at_rest(state: tuple) -> tuple:
    """A state tuple of the same type with zeroed arrays of its own (the convolvers' ``fresh``)."""
    return type(state)(*(np.zeros_like(a) for a in state))


def rest_in_place(state: tuple) -> None:
    """Zero every array of a state tuple in place (the convolvers' ``reset``)."""
    for a in state:
        a[...] = 0


class RingConvolver(NamedTuple):
    """Per-step direct convolution with a ring buffer of past forces (rail).
    g (K, 2, 2) the kernel (g[0] unused; read only); ``state`` (RingState) advanced IN PLACE by
    ``ring_step`` / ``step(F2, F3)``, which record the force of step n and return the
    displacement at step n + 1."""
    g: np.ndarray
    state: RingState

    def step(self, F2: float, F3: float) -> tuple[float, float]:
        return ring_step(self, F2, F3)

    def reset(self) -> None:
        """Back to rest, in place."""
        rest_in_place(self.state)


def ring_convolver(g: np.ndarray) -> RingConvolver:
    """The ring convolver of kernel g (K, 2, 2), at rest."""
    g = np.ascontiguousarray(g, dtype=float)
    K = g.shape[0]
    return RingConvolver(g, RingState(np.zeros((2 * K, 2)), np.zeros(1, np.int64)))


@numba.njit(cache=True)
def ring_step(rc, F2, F3):
    """njit: record (F2, F3) of step n, return (xi2, xi3) at step n + 1 =
    sum_{k=1}^{K-1} g[k] @ F[n+1-k]."""
    g, (buf, pos) = rc
    K = g.shape[0]
    p = pos[0]
    buf[p, 0] = F2
    buf[p, 1] = F3
    buf[p + K, 0] = F2
    buf[p + K, 1] = F3
    x2 = 0.0
    x3 = 0.0
    j = p + K
    for k in range(1, K):     # F[n+1-k] sits at j = p + K - (k - 1)
        f2 = buf[j, 0]
        f3 = buf[j, 1]
        x2 += g[k, 0, 0] * f2 + g[k, 0, 1] * f3
        x3 += g[k, 1, 0] * f2 + g[k, 1, 1] * f3
        j -= 1
    pos[0] = p + 1 if p + 1 < K else 0
    return x2, x3
