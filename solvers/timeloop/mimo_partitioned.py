"""Exact low-latency convolution of several 2 x 2 kernel blocks sharing inputs and outputs (the
rail's moving kernel at two head points, issue 26): the blocks g_oi (response at output point o to
a force at input point i, o, i in {0, 1}) of a 4 x 4 kernel, frequency-domain MIMO.

    xi_o[n+1] = sum_i sum_{k=1}^{K-1} g_oi[k] @ F_i[n+1-k]

Same overlap-save partitioning as ``solvers.timeloop.partitioned`` (head of B lags, P - 1 partitions of B
lags, zero latency), organised by signal rather than by block:

* head, lags 1..B-1, scatter form: each input's force of step n is added, times g_oi[k], into
  the accumulators of outputs n + k (a contiguous multiply-add over k without a running sum, so
  the compiler vectorises it); the accumulator of output n + 1 is then complete;
* partitions: at each block boundary ONE complex FFT per input (z = F2 + i F3, the last two
  blocks) into that input's delay line of spectra, the blocks' 2 x 2-per-bin products summed per
  output, ONE inverse FFT per output (xi2 + i xi3): 2 + 2 FFTs for four blocks instead of 8;
* an input whose forces are all zero (the second point while it is unloaded) is skipped: its
  head step when its force is zero, its products for delay-line spectra of an all-zero segment,
  an output's inverse FFT when nothing reached it.  Skipped terms are exact zeros, so the
  outputs are the same numbers as without skipping.

The result is the direct convolution to rounding (tests/greens/test_mimo_partitioned.py: 1e-9
of the output's scale against ``solvers.greens.convolution.convolve_direct``), not bit for bit the
block-by-block ``solvers.timeloop.partitioned`` convolver (another summation order).
"""
from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np
import rocket_fft  # noqa: F401  (registers numpy.fft for numba)

from solvers.greens.convolution import at_rest


class MimoState(NamedTuple):
    """State changed in place by ``mimo_step``: acc (2, 2, 2B) the outputs' head accumulators
    (output, component, position from the current block's start); X (2, P-1, 4, B+1) the inputs'
    delay lines of spectra (Re F2, Im F2, Re F3, Im F3); live (2, P-1) int: 1 where that spectrum
    is not all zero; Y (4, B+1) work; seg (2, 2B) complex the inputs' last two blocks; tail (2, B,
    2) the partitions' part of the current block's outputs; ctr (5,) int: step count, newest
    delay-line slot, bit i set while input i's current segment holds a non-zero force, ring
    position, 1 once a gathered block has switched to the scatter form; hbuf (2, 2B) the doubled ring of the gathered block's input (``MimoConvolver``)."""
    acc: np.ndarray
    X: np.ndarray
    live: np.ndarray
    Y: np.ndarray
    seg: np.ndarray
    tail: np.ndarray
    ctr: np.ndarray
    hbuf: np.ndarray


class MimoConvolver(NamedTuple):
    """Blocks ``out[b]``, ``inp[b]`` (int arrays (nb,)); head (nb, 4, B): lags 0..B-1 of (g22,
    g23, g32, g33), lag 0 unused (head[b, 0, 0] = 1 flags a head not to scatter: all zero, or gathered); H (nb, P-1, 8, B+1) the partitions' spectra (Re of g22,
    g23, g32, g33, then Im); ``state`` (MimoState, advanced IN PLACE)."""
    out: np.ndarray
    inp: np.ndarray
    head: np.ndarray
    H: np.ndarray
    ghead: np.ndarray
    state: MimoState

    def fresh(self) -> "MimoConvolver":
        """The same convolver with a state of its own, at rest."""
        return self._replace(state=at_rest(self.state))

    def response(self, F: np.ndarray) -> np.ndarray:
        """Whole history from rest (own state untouched): F (nt, 4) = (F2, F3) of inputs 0, 1 ->
        xi (nt, 4) = (xi2, xi3) of outputs 0, 1, xi[0] = 0."""
        return mimo_history(self.fresh(), np.ascontiguousarray(F, dtype=float))


def mimo_convolver(blocks, block: int = 128, gather: bool = False) -> MimoConvolver:
    """The convolver of ``blocks``: a sequence of (out, inp, g), g (K_b, 2, 2) (lag 0 unused;
    kernels of other lengths padded with zeros to the longest), out, inp in {0, 1}, each pair at
    most once (none: a convolver of zeros); ``block``: head and partition length B, a power of two >= 2.
    gather: the first block's head summed as ``solvers.timeloop.partitioned.partitioned_step`` sums it
    (running sums over a ring of its input), so that its output, while the other blocks feeding
    the same output get zero forces, is ``partitioned_convolver(g, block)``'s bit for bit (the
    partitions' spectra, products and FFTs are the same operations in the same order).  At the
    first non-zero force of input 1 the block switches to the scatter form (its last B - 1 inputs
    scattered once from the ring): from then on its output is exact to rounding only.  At rest."""
    B = int(block)
    if B < 2 or B & (B - 1):
        raise ValueError(f"block = {block} must be a power of two >= 2")
    blocks = list(blocks)
    pairs = [(int(o), int(i)) for o, i, _ in blocks]
    if len(set(pairs)) != len(pairs) or any(o not in (0, 1) or i not in (0, 1) for o, i in pairs):
        raise ValueError(f"blocks must be distinct (out, inp) pairs in {{0, 1}}, got {pairs}")
    gs = [np.ascontiguousarray(g, dtype=float) for _, _, g in blocks]
    for g in gs:
        if g.ndim != 3 or g.shape[1:] != (2, 2) or g.shape[0] < 1:
            raise ValueError(f"kernel must have shape (K, 2, 2), got {g.shape}")
    K = max([g.shape[0] for g in gs], default=1)
    n = max(-(-K // B) - 1, 0)
    nb = len(gs)
    head = np.zeros((nb, 4, B))
    H = np.zeros((nb, n, 8, B + 1))
    for b, g in enumerate(gs):
        flat = np.zeros((max(K, B), 4))
        flat[: g.shape[0]] = g.reshape(-1, 4)
        head[b, :, 1:] = flat[1:B].T
        if not np.any(head[b]):
            head[b, 0, 0] = 1.0                             # flag: an all-zero head, nothing to scatter
        for p in range(1, n + 1):
            part = np.zeros((2 * B, 4))
            seg = flat[p * B:(p + 1) * B]
            part[: len(seg)] = seg
            S = np.fft.rfft(part, axis=0).T
            H[b, p - 1, :4] = S.real
            H[b, p - 1, 4:] = S.imag
    if gather and nb and pairs[0] != (0, 0):
        raise ValueError(f"gather: the first block must be (0, 0), got {pairs[0]}")
    ghead = np.zeros((4, B if gather and nb else 0))
    ghead[:, : B - 1] = head[0, :, 1:][:, ::-1] if ghead.shape[1] else 0.0
    state = MimoState(np.zeros((2, 2, 2 * B)), np.zeros((2, n, 4, B + 1)), np.zeros((2, n), np.int64),
                      np.zeros((4, B + 1)), np.zeros((2, 2 * B), complex), np.zeros((2, B, 2)), np.zeros(5, np.int64),
                      np.zeros((2, 2 * B)))
    return MimoConvolver(np.array([o for o, _ in pairs], np.int64), np.array([i for _, i in pairs], np.int64),
                         head, H, ghead, state)


@numba.njit(cache=True, inline="always")
def _scatter(h, a2, a3, f2, f3):
    """a2[k] += g22[k] f2 + g23[k] f3, a3[k] += g32[k] f2 + g33[k] f3, k = 1..B-1 (a2, a3: views
    starting at the current position, so that the index is the loop's own and the loop vectorises)."""
    h0 = h[0]
    h1 = h[1]
    h2 = h[2]
    h3 = h[3]
    for k in range(1, h0.shape[0]):
        a2[k] += h0[k] * f2 + h1[k] * f3
        a3[k] += h2[k] * f2 + h3[k] * f3


@numba.njit(cache=True)
def _gather(h, hbuf, p, F2, F3):
    """``solvers.timeloop.partitioned.partitioned_step``'s head, the same operations in the same order
    (four running sums per component; views, so that the indices need no wraparound test).  Not
    inlined: inside the time loop its eight running sums would compete for registers with the
    loop's state (measured 250 ns a step slower)."""
    B = h.shape[1]
    hbuf[0, p] = F2
    hbuf[1, p] = F3
    hbuf[0, p + B] = F2
    hbuf[1, p + B] = F3
    h0 = h[0]
    h1 = h[1]
    h2 = h[2]
    h3 = h[3]
    u = hbuf[0, p + 2:]
    w = hbuf[1, p + 2:]
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
        a2 += h0[i] * u[i] + h1[i] * w[i]
        a3 += h2[i] * u[i] + h3[i] * w[i]
        b2 += h0[i + 1] * u[i + 1] + h1[i + 1] * w[i + 1]
        b3 += h2[i + 1] * u[i + 1] + h3[i + 1] * w[i + 1]
        c2 += h0[i + 2] * u[i + 2] + h1[i + 2] * w[i + 2]
        c3 += h2[i + 2] * u[i + 2] + h3[i + 2] * w[i + 2]
        d2 += h0[i + 3] * u[i + 3] + h1[i + 3] * w[i + 3]
        d3 += h2[i + 3] * u[i + 3] + h3[i + 3] * w[i + 3]
        i += 4
    while i < m:
        a2 += h0[i] * u[i] + h1[i] * w[i]
        a3 += h2[i] * u[i] + h3[i] * w[i]
        i += 1
    return (a2 + b2) + (c2 + d2), (a3 + b3) + (c3 + d3)


@numba.njit(cache=True)
def _catch_up(h, acc, hbuf, n0, r0):
    """Switch of a gathered block to the scatter form before step n0 (position r0 in its block):
    scatter the inputs n0 - j, j = 1..B-2, still in the ring, into the accumulators of the outputs
    n0 + 1.. they reach (lags k = j + 1..B-1)."""
    B = h.shape[1]
    for j in range(1, B - 1):
        if n0 - j < 0:
            break
        p = (n0 - j) & (B - 1)
        f2 = hbuf[0, p]
        f3 = hbuf[1, p]
        for k in range(j + 1, B):
            acc[0, r0 - j + k] += h[0, k] * f2 + h[1, k] * f3
            acc[1, r0 - j + k] += h[2, k] * f2 + h[3, k] * f3


@numba.njit(cache=True)
def _accumulate(H, X, Y):
    """Y += H X per bin (``solvers.timeloop.partitioned._accumulate``)."""
    for j in range(Y.shape[1]):
        x2r = X[0, j]
        x2i = X[1, j]
        x3r = X[2, j]
        x3i = X[3, j]
        Y[0, j] += H[0, j] * x2r - H[4, j] * x2i + H[1, j] * x3r - H[5, j] * x3i
        Y[1, j] += H[0, j] * x2i + H[4, j] * x2r + H[1, j] * x3i + H[5, j] * x3r
        Y[2, j] += H[2, j] * x2r - H[6, j] * x2i + H[3, j] * x3r - H[7, j] * x3i
        Y[3, j] += H[2, j] * x2i + H[6, j] * x2r + H[3, j] * x3i + H[7, j] * x3r


@numba.njit(cache=True)
def _next_block(mc):
    """At a block boundary: each live input's segment spectrum into its delay line, then each
    output's partition sum and one inverse FFT (overlap-save tail of the next B outputs)."""
    out, inp, head, H, ghead, (acc, X, live, Y, seg, tail, ctr, hbuf) = mc
    B = head.shape[2]
    n = H.shape[1]
    N = 2 * B
    slot = ctr[1] - 1
    if slot < 0:
        slot = n - 1
    ctr[1] = slot
    for i in range(2):
        if (ctr[2] >> i) & 1:
            Z = np.fft.fft(seg[i])
            for j in range(B + 1):
                a = Z[j]
                b = Z[(N - j) % N].conjugate()
                x2 = 0.5 * (a + b)
                x3 = -0.5j * (a - b)
                X[i, slot, 0, j] = x2.real
                X[i, slot, 1, j] = x2.imag
                X[i, slot, 2, j] = x3.real
                X[i, slot, 3, j] = x3.imag
            live[i, slot] = 1
        else:
            live[i, slot] = 0
    for o in range(2):
        Y[:, :] = 0.0
        used = False
        for b in range(out.shape[0]):
            if out[b] != o:
                continue
            i = inp[b]
            for p in range(n):                      # partition p + 1 meets the input p + 1 blocks back
                s = slot + p
                if s >= n:
                    s -= n
                if live[i, s]:
                    _accumulate(H[b, p], X[i, s], Y)
                    used = True
        if used:
            W = np.empty(N, np.complex128)
            for j in range(B + 1):
                W[j] = complex(Y[0, j] - Y[3, j], Y[1, j] + Y[2, j])
            for j in range(1, B):
                W[N - j] = complex(Y[0, j] + Y[3, j], Y[2, j] - Y[1, j])
            w = np.fft.ifft(W)
            for r in range(B):
                tail[o, r, 0] = w[B + r].real
                tail[o, r, 1] = w[B + r].imag
        else:
            tail[o, :, :] = 0.0
    live_now = 0
    for i in range(2):                              # the current block becomes the previous one
        nz = False
        for r in range(B):
            v = seg[i, B + r]
            seg[i, r] = v
            if v != 0.0:
                nz = True
        if nz:
            live_now |= 1 << i
    ctr[2] = live_now


@numba.njit(cache=True)
def mimo_step(mc, F2a, F3a, F2b, F3b):
    """njit: record the forces of step n at inputs 0 (a) and 1 (b); return (xi2, xi3) of outputs
    0 and 1 at step n + 1 (module notes)."""
    out, inp, head, H, ghead, (acc, X, live, Y, seg, tail, ctr, hbuf) = mc
    B = head.shape[2]
    n = ctr[0]
    r = n & (B - 1)
    g2 = 0.0
    g3 = 0.0
    gathering = ghead.shape[1] > 0 and ctr[4] == 0
    if gathering and (F2b != 0.0 or F3b != 0.0):   # input 1 loaded: block 0 to the scatter form
        _catch_up(head[0], acc[0], hbuf, n, r)
        ctr[4] = 1
        gathering = False
    if gathering:                                   # block (0, 0) gathered (``mimo_convolver``)
        g2, g3 = _gather(ghead, hbuf, ctr[3], F2a, F3a)
        ctr[3] = ctr[3] + 1 if ctr[3] + 1 < B else 0
    for b in range(out.shape[0]):
        if inp[b] == 0:
            f2 = F2a
            f3 = F3a
        else:
            f2 = F2b
            f3 = F3b
        if (f2 != 0.0 or f3 != 0.0) and head[b, 0, 0] == 0.0 and not (b == 0 and gathering):
            o = out[b]
            _scatter(head[b], acc[o, 0, r:], acc[o, 1, r:], f2, f3)
    ctr[0] = n + 1
    if H.shape[1] > 0:
        seg[0, B + r] = F2a + 1j * F3a
        seg[1, B + r] = F2b + 1j * F3b
        if F2a != 0.0 or F3a != 0.0:
            ctr[2] |= 1
        if F2b != 0.0 or F3b != 0.0:
            ctr[2] |= 2
        if r == B - 1:
            _next_block(mc)
    r1 = (n + 1) & (B - 1)
    xa2 = acc[0, 0, r + 1]
    xa3 = acc[0, 1, r + 1]
    xb2 = acc[1, 0, r + 1]
    xb3 = acc[1, 1, r + 1]
    if gathering:                                   # (gathered + 0) + tail: partitioned_step's sum
        xa2 = g2 + xa2
        xa3 = g3 + xa3
    xa2 += tail[0, r1, 0]
    xa3 += tail[0, r1, 1]
    xb2 += tail[1, r1, 0]
    xb3 += tail[1, r1, 1]
    if r == B - 1:                                  # accumulators move one block on
        for o in range(2):
            for c in range(2):
                for k in range(B):
                    acc[o, c, k] = acc[o, c, B + k]
                    acc[o, c, B + k] = 0.0
    return xa2, xa3, xb2, xb3


@numba.njit(cache=True)
def mimo_history(mc, F):
    """njit: the outputs (nt, 4) for a whole history F (nt, 4) from the current state."""
    nt = F.shape[0]
    xi = np.zeros((nt, 4))
    for n in range(nt - 1):
        a2, a3, b2, b3 = mimo_step(mc, F[n, 0], F[n, 1], F[n, 2], F[n, 3])
        xi[n + 1, 0] = a2
        xi[n + 1, 1] = a3
        xi[n + 1, 2] = b2
        xi[n + 1, 3] = b3
    return xi
