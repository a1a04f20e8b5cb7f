"""Exact low-latency convolution of the rail's moving kernel in the time loop (SPEC 3.5: "FFT
block convolution for the rail ... if it is shown to match the direct convolution").

The time loop needs, at every step n, the displacement of the NEXT step from the forces up to
now (g[0] excluded, ``solvers.greens.kernels`` module notes):

    xi[n+1] = sum_{k=1}^{K-1} g[k] @ F[n+1-k],      g (K, 2, 2).

Direct evaluation (``solvers.greens.kernels.ring_step``) costs 4 (K - 1) multiply-adds per step.  Here
the kernel is cut into a head of B lags and P - 1 partitions of B lags (uniformly partitioned
overlap-save, zero latency):

* head, lags 1..B-1: direct, from a ring buffer of the last B forces (4 (B - 1) multiply-adds);
* partition p = 1..P-1, lags pB..pB+B-1: its contribution to the outputs of block b (steps
  bB..bB+B-1) uses forces of blocks b-p-1 and b-p only, all known when block b starts.  At
  every block boundary one FFT of size 2B turns the last two input blocks into a spectrum
  (kept in a frequency-domain delay line of P - 1 spectra), the spectra are multiplied by the
  partitions' spectra H_p (2 x 2 per bin) and summed, and one inverse FFT gives the tail of all
  B outputs of the block (the last B samples of the circular convolution are the linear ones).

Both force components travel in one complex FFT (z = F2 + i F3, split by Hermitian symmetry)
and both outputs come back in one inverse FFT (xi2 + i xi3), so a block costs two complex FFTs
of 2B points plus 4 (P - 1)(B + 1) complex multiply-adds: per step about 32 (P - 1) + 8 B flops
plus the FFTs, against 8 K for the direct sum (K = 4096, B = 128: ~2000 against 32768).  The
result is the direct convolution to rounding (FFT round-off, ~1e-15 of the output's scale;
tests/greens/test_partitioned.py checks 1e-9 on a random force history).  B >= K - 1 leaves no
partition: the convolver is then the plain direct sum (the reference).

FFTs inside numba come from rocket-fft (numpy.fft for numba; requirements.txt).
"""
from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np
import rocket_fft  # noqa: F401  (registers numpy.fft for numba)

from solvers.greens.convolution import at_rest, rest_in_place

DEFAULT_BLOCK = 128


class PartitionedState(NamedTuple):
    """The partitioned convolver's state, changed in place by ``partitioned_step``: hbuf, X, Y,
    seg, tail, ctr as described in ``PartitionedConvolver``."""
    hbuf: np.ndarray
    X: np.ndarray
    Y: np.ndarray
    seg: np.ndarray
    tail: np.ndarray
    ctr: np.ndarray


class PartitionedConvolver(NamedTuple):
    """Coefficients (head, H: read only) and ``state`` (PartitionedState, advanced IN PLACE)
    of the partitioned convolution (module notes).  ``step(F2, F3)``
    records the force of step n and returns the displacement at step n + 1; pass the tuple to
    ``partitioned_step`` inside numba.

    head (4, B): the lags k = 1..B-1 of (g22, g23, g32, g33) in reverse order (column i holds lag
    B - 1 - i; the last column is unused), so that the head sum runs forward over the doubled
    ring hbuf (2, 2B) of the last B forces (rows F2, F3; F[n] at p and p + B); H (P-1, 8, B+1) spectra of the partitions (rows: Re of g22, g23, g32,
    g33, then their Im); X (P-1, 4, B+1) delay line of input spectra (Re F2, Im F2, Re F3,
    Im F3); Y (4, B+1) their sum (Re, Im of the xi2 and xi3 spectra): real arrays, so the
    multiply-adds over the bins vectorise; seg (2B,) complex last two input blocks (F2 + i F3);
    tail (B, 2) the partitions' contribution to the current block's outputs; ctr (3,) int:
    step count, ring position, newest delay-line slot."""
    head: np.ndarray
    H: np.ndarray
    state: PartitionedState

    @property
    def block(self) -> int:
        return self.head.shape[1]

    def step(self, F2: float, F3: float) -> tuple[float, float]:
        return partitioned_step(self, F2, F3)

    def reset(self) -> None:
        """Back to rest, in place."""
        rest_in_place(self.state)

    def fresh(self) -> "PartitionedConvolver":
        """The same convolver with a state of its own, at rest."""
        return self._replace(state=at_rest(self.state))

    def response(self, F: np.ndarray) -> np.ndarray:
        """Whole history from rest (own state untouched): xi (nt, 2), xi[0] = 0."""
        return partitioned_history(self.fresh(), np.ascontiguousarray(F, dtype=float))


def partitioned_convolver(g: np.ndarray, block: int | None = DEFAULT_BLOCK) -> PartitionedConvolver:
    """The convolver of kernel g (K, 2, 2) (g[0] unused) with head/partition length ``block``
    (a power of two; None or >= K: direct sum only).  State at rest."""
    g = np.ascontiguousarray(g, dtype=float)
    if g.ndim != 3 or g.shape[1:] != (2, 2) or g.shape[0] < 1:
        raise ValueError(f"kernel must have shape (K, 2, 2), got {g.shape}")
    K = g.shape[0]
    B = K if block is None or block >= K else int(block)
    if B < K and (B < 2 or B & (B - 1)):
        raise ValueError(f"block = {block} must be a power of two >= 2 (or None for the direct sum)")
    flat = g.reshape(K, 4)
    head = np.zeros((4, B))
    head[:, : B - 1] = flat[1:B][::-1].T
    P = -(-K // B)
    n = max(P - 1, 0)
    H = np.zeros((n, 8, B + 1))
    for p in range(1, P):
        part = np.zeros((2 * B, 4))
        seg = flat[p * B:(p + 1) * B]
        part[: len(seg)] = seg
        S = np.fft.rfft(part, axis=0).T                 # (4, B + 1)
        H[p - 1, :4] = S.real
        H[p - 1, 4:] = S.imag
    state = PartitionedState(np.zeros((2, 2 * B)), np.zeros((n, 4, B + 1)), np.zeros((4, B + 1)),
                             np.zeros(2 * B, complex), np.zeros((B, 2)), np.zeros(3, np.int64))
    return PartitionedConvolver(head, H, state)


@numba.njit(cache=True)
def _next_block(pc):
    """At a block boundary: the new input segment's spectrum into the delay line, then the
    partitions' contribution to the next B outputs (overlap-save)."""
    head, H, (hbuf, X, Y, seg, tail, ctr) = pc
    B = head.shape[1]
    n = H.shape[0]
    N = 2 * B
    Z = np.fft.fft(seg)
    slot = ctr[2] - 1
    if slot < 0:
        slot = n - 1
    ctr[2] = slot
    for j in range(B + 1):                           # F2, F3 spectra from the joint FFT
        a = Z[j]
        b = Z[(N - j) % N].conjugate()
        x2 = 0.5 * (a + b)
        x3 = -0.5j * (a - b)
        X[slot, 0, j] = x2.real
        X[slot, 1, j] = x2.imag
        X[slot, 2, j] = x3.real
        X[slot, 3, j] = x3.imag
    Y[:, :] = 0.0
    for p in range(n):                               # partition p + 1 meets the input p + 1 blocks back
        s = slot + p
        if s >= n:
            s -= n
        _accumulate(H[p], X[s], Y)
    W = np.empty(N, np.complex128)                  # Y2 + i Y3 over the whole circle (Hermitian halves)
    for j in range(B + 1):
        W[j] = complex(Y[0, j] - Y[3, j], Y[1, j] + Y[2, j])
    for j in range(1, B):
        W[N - j] = complex(Y[0, j] + Y[3, j], Y[2, j] - Y[1, j])
    w = np.fft.ifft(W)
    for r in range(B):
        tail[r, 0] = w[B + r].real
        tail[r, 1] = w[B + r].imag
    for r in range(B):                               # the current block becomes the previous one
        seg[r] = seg[B + r]


@numba.njit(cache=True)
def _accumulate(H, X, Y):
    """Y += H X per bin: (Y2, Y3) = [[H22, H23], [H32, H33]] (X2, X3), complex, as real arrays."""
    for j in range(Y.shape[1]):
        x2r = X[0, j]
        x2i = X[1, j]
        x3r = X[2, j]
        x3i = X[3, j]
        Y[0, j] += H[0, j] * x2r - H[4, j] * x2i + H[1, j] * x3r - H[5, j] * x3i
        Y[1, j] += H[0, j] * x2i + H[4, j] * x2r + H[1, j] * x3i + H[5, j] * x3r
        Y[2, j] += H[2, j] * x2r - H[6, j] * x2i + H[3, j] * x3r - H[7, j] * x3i
        Y[3, j] += H[2, j] * x2i + H[6, j] * x2r + H[3, j] * x3i + H[7, j] * x3r


@numba.njit(cache=True, inline="always")
def partitioned_step(pc, F2, F3):
    """njit: record (F2, F3) of step n, return (xi2, xi3) at step n + 1 (module notes)."""
    head, H, (hbuf, X, Y, seg, tail, ctr) = pc
    B = head.shape[1]
    n = ctr[0]
    p = ctr[1]
    hbuf[0, p] = F2
    hbuf[1, p] = F3
    hbuf[0, p + B] = F2
    hbuf[1, p + B] = F3
    # head: lag k = B - 1 - i meets F[n+1-k] at q + i, q = p + 2 (forward over both arrays); four
    # independent partial sums, so the additions do not wait on each other
    q = p + 2
    m = B - 1
    a2 = 0.0
    b2 = 0.0
    c2 = 0.0
    d2 = 0.0
    a3 = 0.0
    b3 = 0.0
    c3 = 0.0
    d3 = 0.0
    i = 0
    while i + 3 < m:
        a2 += head[0, i] * hbuf[0, q + i] + head[1, i] * hbuf[1, q + i]
        a3 += head[2, i] * hbuf[0, q + i] + head[3, i] * hbuf[1, q + i]
        b2 += head[0, i + 1] * hbuf[0, q + i + 1] + head[1, i + 1] * hbuf[1, q + i + 1]
        b3 += head[2, i + 1] * hbuf[0, q + i + 1] + head[3, i + 1] * hbuf[1, q + i + 1]
        c2 += head[0, i + 2] * hbuf[0, q + i + 2] + head[1, i + 2] * hbuf[1, q + i + 2]
        c3 += head[2, i + 2] * hbuf[0, q + i + 2] + head[3, i + 2] * hbuf[1, q + i + 2]
        d2 += head[0, i + 3] * hbuf[0, q + i + 3] + head[1, i + 3] * hbuf[1, q + i + 3]
        d3 += head[2, i + 3] * hbuf[0, q + i + 3] + head[3, i + 3] * hbuf[1, q + i + 3]
        i += 4
    while i < m:
        a2 += head[0, i] * hbuf[0, q + i] + head[1, i] * hbuf[1, q + i]
        a3 += head[2, i] * hbuf[0, q + i] + head[3, i] * hbuf[1, q + i]
        i += 1
    x2 = (a2 + b2) + (c2 + d2)
    x3 = (a3 + b3) + (c3 + d3)
    ctr[1] = p + 1 if p + 1 < B else 0
    n1 = n + 1
    ctr[0] = n1
    if H.shape[0] > 0:                               # B is a power of two here: n % B = n & (B - 1)
        r = n & (B - 1)
        seg[B + r] = F2 + 1j * F3
        if r == B - 1:                               # input block complete: tails of the next block
            _next_block(pc)
        r1 = n1 & (B - 1)
        x2 += tail[r1, 0]
        x3 += tail[r1, 1]
    return x2, x3


@numba.njit(cache=True)
def partitioned_history(pc, F):
    """njit: xi[n] = sum_{k>=1} g[k] F[n-k] for a whole history F (nt, 2) from the current state."""
    nt = F.shape[0]
    xi = np.zeros((nt, 2))
    for n in range(nt - 1):
        a, b = partitioned_step(pc, F[n, 0], F[n, 1])
        xi[n + 1, 0] = a
        xi[n + 1, 1] = b
    return xi
