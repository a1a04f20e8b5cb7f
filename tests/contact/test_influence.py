"""Half-space influence coefficients against direct quadrature of the point-load
solutions (Boussinesq, Cerruti) and the FFT convolution against the dense matrix."""
import numpy as np
import pytest
from scipy.integrate import dblquad

from solvers.contact.influence import (Convolver, boussinesq, cerruti, dense_matrix, normal_kernel,
                                       strang_inverse_symbol, tangential_kernels)
from pipeline.validation.references.contact import E, G, NU

DX, DY = 0.5e-3, 0.3e-3


def _point_kernels():
    r = lambda s, t: np.hypot(s, t)
    c = 1 / (np.pi * G)     # combined wheel + rail
    return {
        "33": lambda t, s: c * (1 - NU) / r(s, t),
        "11": lambda t, s: c * ((1 - NU) / r(s, t) + NU * s * s / r(s, t) ** 3),
        "12": lambda t, s: c * NU * s * t / r(s, t) ** 3,
        "22": lambda t, s: c * ((1 - NU) / r(s, t) + NU * t * t / r(s, t) ** 3),
    }


@pytest.mark.parametrize("X,Y", [(1.0e-3, 0.6e-3), (-2.5e-3, 0.9e-3), (0.5e-3, -3e-3)])
def test_closed_forms_match_quadrature(X, Y):
    f = _point_kernels()
    a11, a12, a22 = cerruti(X, Y, DX, DY, E, NU)
    ours = {"33": boussinesq(X, Y, DX, DY, E, NU), "11": a11, "12": a12, "22": a22}
    for k, fun in f.items():
        ref = dblquad(fun, X - DX / 2, X + DX / 2, Y - DY / 2, Y + DY / 2, epsabs=0, epsrel=1e-11)[0]
        assert ours[k] == pytest.approx(ref, rel=1e-8), k


def test_self_coefficient_love():
    # centre of a square of side 2c: int int 1/r = 8 c ln(1 + sqrt 2) (Love)
    c = 0.25e-3
    ref = (1 - NU) / (np.pi * G) * 8 * c * np.log(1 + np.sqrt(2))
    assert boussinesq(0.0, 0.0, 2 * c, 2 * c, E, NU) == pytest.approx(ref, rel=1e-13)


def test_kernels_symmetry_and_positive_definite():
    nx, ny = 7, 6
    K33 = normal_kernel(nx, ny, DX, DY, E, NU)
    K11, K12, K22 = tangential_kernels(nx, ny, DX, DY, E, NU)
    assert K33.shape == (2 * nx - 1, 2 * ny - 1)
    for K in (K33, K11, K22):
        assert np.allclose(K, K[::-1, ::-1]) and np.allclose(K, K[::-1, :])
    assert np.allclose(K12, -K12[::-1, :]) and np.allclose(K12[:, ny - 1], 0.0)
    A = np.block([[dense_matrix(K11), dense_matrix(K12)], [dense_matrix(K12), dense_matrix(K22)]])
    assert np.allclose(A, A.T, rtol=0, atol=1e-12 * A.max())
    assert np.linalg.eigvalsh(A).min() > 0 and np.linalg.eigvalsh(dense_matrix(K33)).min() > 0


def test_fft_convolution_equals_dense_and_shift():
    nx, ny = 9, 5
    rng = np.random.default_rng(1)
    p = rng.random((nx, ny))
    K = normal_kernel(nx, ny, DX, DY, E, NU)
    assert np.allclose(Convolver(K)(p).ravel(), dense_matrix(K) @ p.ravel(), rtol=1e-12, atol=0)
    # shifted kernel: displacement one element ahead, u(x_i + dx)
    Ks = normal_kernel(nx, ny, DX, DY, E, NU, shift_x=1)
    Kbig = normal_kernel(nx + 1, ny, DX, DY, E, NU)
    pb = np.vstack([p, np.zeros((1, ny))])
    assert np.allclose(Convolver(Ks)(p), Convolver(Kbig)(pb)[1:], rtol=1e-12)
    assert (strang_inverse_symbol(K) > 0).all()
