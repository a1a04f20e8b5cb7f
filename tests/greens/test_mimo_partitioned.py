"""The MIMO partitioned convolver (solvers/timeloop/mimo_partitioned.py) against the direct sum
(solvers.greens.convolution.convolve_direct) block by block: blocks of different lengths, a kernel
shorter than one block, an input that is zero over stretches (its skipped terms are exact zeros:
an output fed only by that input stays exactly 0 there)."""
from __future__ import annotations

import numpy as np
import pytest

from solvers.greens.convolution import convolve_direct
from solvers.timeloop.mimo_partitioned import mimo_convolver, mimo_step

PAIRS = [(0, 1), (1, 0), (1, 1)]


def direct(blocks, F):
    xi = np.zeros_like(F)
    for o, i, g in blocks:
        xi[:, 2 * o:2 * o + 2] += convolve_direct(g, np.ascontiguousarray(F[:, 2 * i:2 * i + 2]))
    return xi


@pytest.mark.parametrize("K, block", [(1500, 128), (1500, 16), (100, 128), (4096, 256)])
def test_mimo_convolution_equals_direct(K, block):
    rng = np.random.default_rng(K + block)
    decay = np.exp(-np.arange(K) / (0.3 * K))[:, None, None] * 1e-9
    blocks = [(o, i, rng.standard_normal((K - 37 * (o + i), 2, 2)) * decay[: K - 37 * (o + i)]) for o, i in PAIRS]
    F = rng.standard_normal((6000, 4)) * [2e3, 6e3, 1e3, 3e3] + [0.0, 500.0, 0.0, 200.0]
    F[2000:4100, 2:] = 0.0                                   # input b unloaded for a stretch
    ref = direct(blocks, F)
    xi = mimo_convolver(blocks, block).response(F)
    err = np.abs(xi - ref).max() / np.abs(ref).max()
    assert err < 1e-9, err
    # output a sees only input b (g_ab): exactly zero once b's last non-zero segment has left the
    # delay line (K rounded up to blocks, plus the two-block segment)
    quiet = xi[2000 + (K // block + 3) * block:4101, :2]
    assert np.all(quiet == 0.0) and (K > 2000 or quiet.size > 0)


def test_mimo_step_and_rejections():
    rng = np.random.default_rng(3)
    g = rng.standard_normal((300, 2, 2))
    mc = mimo_convolver([(1, 0, g)], 64)
    F = rng.standard_normal((500, 4))
    ref = direct([(1, 0, g)], F)
    for n in range(499):
        out = mimo_step(mc, *F[n])
        assert out[0] == 0.0 and out[1] == 0.0
        assert abs(out[2] - ref[n + 1, 2]) + abs(out[3] - ref[n + 1, 3]) <= 1e-12 * np.abs(ref).max()
    assert np.all(mimo_convolver([], 128).response(F) == 0.0)
    with pytest.raises(ValueError, match="power of two"):
        mimo_convolver([(0, 1, g)], 48)
    with pytest.raises(ValueError, match="distinct"):
        mimo_convolver([(0, 1, g), (0, 1, g)], 64)


def test_gathered_block_is_the_partitioned_convolver_bit_for_bit():
    """gather=True: block 0's output, with the other block feeding that output getting zero
    forces, is solvers.timeloop.partitioned's (the one-point loop's convolver) bit for bit."""
    from solvers.timeloop.partitioned import partitioned_convolver

    rng = np.random.default_rng(5)
    g = rng.standard_normal((1000, 2, 2)) * np.exp(-np.arange(1000) / 300.0)[:, None, None]
    F = rng.standard_normal((3000, 4))
    F[:, 2:] = 0.0
    blocks = [(0, 0, g), (0, 1, 0.7 * g), (1, 0, 0.5 * g), (1, 1, g)]
    xi = mimo_convolver(blocks, 128, gather=True).response(F)
    ref = partitioned_convolver(g, 128).response(F[:, :2])
    assert np.array_equal(xi[:, :2], ref)
    F[:, 2:] = rng.standard_normal((3000, 2))                # and with every input loaded: the direct sum
    ref = direct(blocks, F)
    xi = mimo_convolver(blocks, 128, gather=True).response(F)
    assert np.abs(xi - ref).max() <= 1e-9 * np.abs(ref).max()


def test_gathered_block_switches_to_scatter_when_the_second_input_loads():
    rng = np.random.default_rng(6)
    g = rng.standard_normal((700, 2, 2)) * np.exp(-np.arange(700) / 200.0)[:, None, None]
    blocks = [(0, 0, g), (0, 1, 0.7 * g), (1, 0, 0.5 * g), (1, 1, g)]
    F = rng.standard_normal((2500, 4))
    for n0 in (1000, 1023, 1030):                            # input b loads mid-block and at a block end
        F[:n0, 2:] = 0.0
        ref = direct(blocks, F)
        xi = mimo_convolver(blocks, 128, gather=True).response(F)
        assert np.abs(xi - ref).max() <= 1e-9 * np.abs(ref).max(), n0
