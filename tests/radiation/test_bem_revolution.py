"""The body-of-revolution BEM (``solvers.radiation.bem_revolution``: first block row assembled by bempp-cl, one
ring-sized problem per harmonic; the ground by the mirror symmetry of body and image) against the full
3-D solve of ``solvers.radiation.bem`` on the same mesh (a second method: the same discrete problem), free field
(equal to 1e-8, harmonics 0 to 3) and over a rigid plane (to 1e-4: the 3-D pair's matrices are mirror-
symmetric only to bempp's quadrature; measured 2e-5).  Slow: bempp compiles its numba
kernels once per process (~1-2 min per operator on a loaded machine).

    .venv/bin/python -m pytest -q --validation tests/radiation/test_bem_revolution.py
"""
from __future__ import annotations

import numpy as np
import pytest

from solvers.radiation.bem_surface import revolve

N_PHI = 14


def _body():
    """A revolved quadrilateral (a ring of trapezoidal section; r from 0.3 to 0.5 m)."""
    rz = np.array([[0.30, -0.05], [0.40, -0.06], [0.50, -0.02], [0.50, 0.03], [0.42, 0.06], [0.30, 0.04]])
    V, T, phi = revolve(rz, N_PHI)
    return V, T, phi, len(rz)


def _devices() -> list[str]:
    try:
        import bempp_cl.api as api
    except ImportError:
        return ["numba"]
    return ["numba"] + (["opencl"] if api.CPU_OPENCL_DRIVER_FOUND else [])


@pytest.mark.validation
@pytest.mark.parametrize("device", _devices())
def test_revolution_solver_equals_the_full_solve(device):
    pytest.importorskip("bempp_cl")
    from solvers.radiation import bem
    from solvers.radiation.bem_revolution import first_block_row, ground_power, harmonic_parts, revolution_power

    bem.use_device(device)

    V, T, phi, nn = _body()
    k = 2 * np.pi * 1000.0 / 343.0                       # ~ lambda / 2 elements around: the algebra, not accuracy
    prof = np.linspace(1.0, 2.0, nn) * np.exp(0.3j * np.arange(nn))
    fields = {n: np.tile(prof, N_PHI) * np.cos(n * (phi - np.pi)) for n in range(4)}
    full = bem.radiated_power(bem.grid_from_arrays(V, T), k, list(fields.values()))
    rows = first_block_row(V, T, nn, k)
    for (n, v), w in zip(fields.items(), full):
        (wr,) = revolution_power(V, T, nn, k, [v], n, rows=rows)
        assert abs(wr / w - 1) < 1e-8, (n, wr, w)
    with pytest.raises(ValueError):
        harmonic_parts(fields[1] + fields[2], nn, 1)
    plane = -0.6                                         # the ground x = -0.6 m, 0.1 m below the body
    Vm, Tm = bem.mirrored(V, T, axis=0, plane=plane)
    two = [np.concatenate([fields[n], fields[n]]) for n in (0, 2)]
    pair = bem.radiated_power(bem.grid_from_arrays(Vm, Tm), k, two)
    half = ground_power(V, T, nn, k, [fields[0], fields[2]], 0, plane, rows=rows)
    for w2, wh in zip(pair, half):                       # the pair's 3-D matrices are mirror-symmetric only to
        assert abs(wh / (0.5 * w2) - 1) < 1e-4, (wh, 0.5 * w2)    # bempp's quadrature (measured 2e-5 = 1e-4 dB)
    assert abs(half[1] / full[2] - 1) > 1e-3              # the ground does change the power
    bem.use_device("numba")


def test_block_circulant_algebra():
    """add_circulant builds A[(j, i), (k, l)] = row[i, (k - j) mod n_phi, l]; the ring matrix of harmonic
    m maps e^{i m phi} fields like the full matrix does; harmonic_parts splits cos n (phi - phi_c)."""
    from solvers.radiation.bem_revolution import _ring_matrix, add_circulant, circulant_matvec, harmonic_parts

    nn, n_phi = 3, 7
    rng = np.random.default_rng(0)
    row = rng.normal(size=(nn, n_phi * nn)) + 1j * rng.normal(size=(nn, n_phi * nn))
    full = add_circulant(np.zeros((nn * n_phi, nn * n_phi), complex), row, nn)
    j, i, k, l = 4, 1, 2, 0
    assert full[j * nn + i, k * nn + l] == row[i, ((k - j) % n_phi) * nn + l]
    z = rng.normal(size=nn * n_phi) + 1j * rng.normal(size=nn * n_phi)
    assert np.allclose(circulant_matvec(row, nn, z), full @ z)
    phi = 2 * np.pi * np.arange(n_phi) / n_phi
    x = rng.normal(size=nn) + 1j * rng.normal(size=nn)
    for m in (-2, 0, 3):
        y = full @ np.kron(np.exp(1j * m * phi), x)
        assert np.allclose(y, np.kron(np.exp(1j * m * phi), _ring_matrix(row, nn, m) @ x))
    v = np.kron(np.cos(2 * (phi - 0.3)), x)
    parts = harmonic_parts(v, nn, 2)
    assert np.allclose(parts[2], 0.5 * np.exp(-0.6j) * x) and np.allclose(parts[-2], 0.5 * np.exp(0.6j) * x)
