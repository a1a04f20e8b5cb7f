"""The fast forms of the rail's Green's function and its convolution against their references:
``solvers.rail.moving_kernel.moving_green_waves`` vs Kropp's construction per lag
(``solvers.greens.kernels.moving_green``), and the partitioned FFT convolution
(``solvers.timeloop.partitioned``) vs the direct sum (``solvers.greens.kernels.convolve_direct``)."""
import numpy as np
import pytest

from solvers.greens.kernels import convolve_direct, moving_green, ring_convolver, ring_step
from solvers.rail.moving_kernel import mirror, moving_green_waves
from solvers.timeloop.partitioned import partitioned_convolver, partitioned_step
from pipeline.validation.references.greens import DT, V
from pipeline.validation.references.interaction import RAIL


def _transfer(K, A, n_t):
    """transfer(x, f) of the reference: the wave sum on the first nf grid points, 0 above."""
    nf = K.shape[0]

    def transfer(x, f):
        G = np.zeros((len(x), len(f), 2, 2), complex)
        e = np.exp(-1j * K[None, :, :] * np.abs(np.asarray(x))[:, None, None])     # (nx, nf, M)
        G[:, :nf] = np.einsum("xfm,fmij->xfij", e, A)
        return G

    return transfer


def _synthetic_waves(nf, M, rng):
    """Waves like a supported rail's: a few weakly damped propagating ones and many
    evanescent near-field ones (Im k from 0.01 to 500 1/m), random amplitudes ~1e-9 m/N."""
    kr = rng.uniform(0.0, 30.0, (nf, M))
    ki = -np.exp(rng.uniform(np.log(0.01), np.log(500.0), (nf, M)))
    A = 1e-9 * (rng.standard_normal((nf, M, 2, 2)) + 1j * rng.standard_normal((nf, M, 2, 2)))
    return kr + 1j * ki, A


@pytest.mark.parametrize("nf_full", [False, True])
def test_moving_kernel_equals_reference_synthetic(nf_full):
    rng = np.random.default_rng(3)
    n_t, n_k = 512, 257
    nf = n_t // 2 + 1 if nf_full else 150            # with and without the Nyquist term
    K, A = _synthetic_waves(nf, 40, rng)
    ref = moving_green(_transfer(K, A, n_t), V, DT, n_k, n_t)
    new = moving_green_waves(K, A, V, DT, n_k, n_t)
    err = np.abs(new - ref).max() / np.abs(ref).max()
    assert err < 1e-9, err
    # v = 0: the fixed-point kernel; the mirror point: cross terms negated, exactly
    ref0 = moving_green(_transfer(K, A, n_t), 0.0, DT, n_k, n_t)
    assert np.abs(moving_green_waves(K, A, 0.0, DT, n_k, n_t) - ref0).max() < 1e-9 * np.abs(ref0).max()
    Am = A.copy()
    Am[..., 0, 1] *= -1
    Am[..., 1, 0] *= -1
    np.testing.assert_array_equal(moving_green_waves(K, Am, V, DT, n_k, n_t), mirror(new))


@pytest.mark.skipif(not RAIL.exists(), reason="needs build/rails/bv50/rail.npz (make rail)")
def test_moving_kernel_equals_reference_bv50_waves():
    """The BV50's own wave table (its 1000 frequencies taken as grid points, ~240 waves each,
    the near field included) over 600 lags."""
    with np.load(RAIL) as d:
        K = d["wave_k"][:300]
        A = d["wave_a"][:300, :, 0]
    n_t, n_k = 2048, 600
    ref = moving_green(_transfer(K, A, n_t), V, DT, n_k, n_t)
    new = moving_green_waves(K, A, V, DT, n_k, n_t)
    err = np.abs(new - ref).max() / np.abs(ref).max()
    assert err < 1e-9, err


def test_moving_kernel_rejects_growing_waves():
    K = np.array([[1.0 + 0.5j]])
    with pytest.raises(ValueError, match="decay"):
        moving_green_waves(K, np.ones((1, 1, 2, 2), complex), V, DT, 10, 64)


@pytest.mark.parametrize("K,block", [(4096, 128), (4096, 32), (1000, 64), (50, 64), (300, None), (2, 2)])
def test_partitioned_convolution_equals_direct(K, block):
    rng = np.random.default_rng(K + (block or 0))
    g = rng.standard_normal((K, 2, 2)) * np.exp(-np.arange(K) / (0.3 * K))[:, None, None] * 1e-9
    F = rng.standard_normal((9000, 2)) * [2e3, 6e3] + [0.0, 500.0]
    ref = convolve_direct(g, F)
    pc = partitioned_convolver(g, block)
    xi = pc.response(F)
    err = np.abs(xi - ref).max() / np.abs(ref).max()
    assert err < 1e-9, err
    # per step (the time loop's call), and the same state as the direct ring buffer's
    rc = ring_convolver(g)
    pc.reset()
    for n in range(700):
        a = partitioned_step(pc, F[n, 0], F[n, 1])
        b = ring_step(rc, F[n, 0], F[n, 1])
        assert abs(a[0] - b[0]) + abs(a[1] - b[1]) <= 1e-9 * np.abs(ref).max()


def test_partitioned_convolver_rejects_bad_block():
    with pytest.raises(ValueError, match="power of two"):
        partitioned_convolver(np.zeros((100, 2, 2)), 48)

