"""Exterior acoustic radiation by the boundary element method (bempp-cl), for checking the radiation
stage's simple model (thesis sec. 5.1: the reference compared its model with a BEM, unit lateral and
radial forces near the (n,0,a) modes, free field and over a reflecting ground).

Conventions (bempp's): time factor e^{-i w t}, Green's function e^{ikr} / (4 pi r), normals pointing
OUT of the body into the fluid.  Linearised Euler: -i w rho v = -grad p, so the normal derivative of
the pressure on the surface is q = dp/dn = i w rho v_n (v_n outward normal velocity).  Exterior
Burton-Miller formulation (coupling eta = i / k, no irregular frequencies):

    (1/2 I - K + eta W) p = -(V + eta (1/2 I + K')) q

with V, K, K', W bempp's single-layer, double-layer, adjoint double-layer and hypersingular operators
on continuous piecewise-linear (P1) spaces.  Radiated power W = 1/2 Re(conj(v)^T M p), M the P1 mass
matrix.  A rigid ground plane is an image body: the body and its mirror image in the plane (with the
mirrored velocity) radiate into free space twice the power the body radiates into the half space.

Analytic references: a pulsating sphere of radius a (v_n = v), Re z = rho c (ka)^2 / (1 + (ka)^2),
W = 1/2 Re z v^2 4 pi a^2; an oscillating (rigidly translating) sphere (v_n = v cos theta),
z_1 = i rho c h_1(ka) / h_1'(ka), W = 1/2 Re z_1 v^2 4 pi a^2 / 3 (h_1 the outgoing spherical Hankel
function).
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import lu_factor, lu_solve
from scipy.special import spherical_jn, spherical_yn


def _api():
    import bempp_cl.api as api  # lazy: brings in bempp_cl

    return api


def use_device(name: str) -> None:
    """bempp-cl's backend for the operators assembled from now on: "numba" (always there) or "opencl"
    (needs pyopencl and an OpenCL CPU driver such as pocl; bempp picks it by default when present)."""
    api = _api()
    if name not in ("numba", "opencl"):
        raise ValueError(f"bempp device {name!r}: 'numba' or 'opencl'")
    if name == "opencl" and not api.CPU_OPENCL_DRIVER_FOUND:
        raise ValueError("bempp device 'opencl': no OpenCL CPU driver found (pyopencl and pocl)")
    api.DEFAULT_DEVICE_INTERFACE = name


def device() -> str:
    """bempp-cl's backend in use ("numba" or "opencl")."""
    return _api().DEFAULT_DEVICE_INTERFACE


def grid_from_arrays(vertices: np.ndarray, triangles: np.ndarray):
    """A bempp grid from vertices (N, 3) and triangles (T, 3) (counter-clockwise seen from outside)."""
    return _api().Grid(np.ascontiguousarray(np.asarray(vertices, float).T),
                       np.ascontiguousarray(np.asarray(triangles, np.uint32).T))


def mirrored(vertices: np.ndarray, triangles: np.ndarray, axis: int = 2, plane: float = 0.0):
    """The body and its image in the plane x_axis = ``plane`` as one triangle mesh (vertices, triangles;
    the image's triangles reordered so that its normals point out of it, its vertices after the
    body's in the same order)."""
    v = np.asarray(vertices, float)
    t = np.asarray(triangles, int)
    vi = v.copy()
    vi[:, axis] = 2 * plane - vi[:, axis]
    return np.vstack([v, vi]), np.vstack([t, t[:, ::-1] + len(v)])


def _weak_forms(grid, k: float, test=None):
    """Galerkin matrices of the Burton-Miller equation on ``grid`` (P1 trial functions, test functions
    ``test``: P1 on the whole grid by default): dense left-hand side A, right-hand side B (acting on
    q = dp/dn) and the sparse mass matrix M, rows = the test space's dofs."""
    api = _api()
    space = api.function_space(grid, "P", 1)
    test = space if test is None else test
    hz = api.operators.boundary.helmholtz
    ident = api.operators.boundary.sparse.identity(space, space, test)
    V = hz.single_layer(space, space, test, k)
    K = hz.double_layer(space, space, test, k)
    Kp = hz.adjoint_double_layer(space, space, test, k)
    W = hz.hypersingular(space, space, test, k)
    eta = 1j / k
    A = np.asarray((0.5 * ident - K + eta * W).weak_form().A)
    B = np.asarray((V + eta * (0.5 * ident + Kp)).weak_form().A)
    return A, B, ident.weak_form().A


def radiated_power(grid, k: float, vns, rho: float = 1.21, c: float = 343.0) -> list[float]:
    """Radiated power [W] of the body ``grid`` vibrating with each outward normal velocity amplitude
    field of ``vns`` (complex, per vertex (P1 coefficients), m/s) at wavenumber k [1/m]: the
    Burton-Miller equation above (operators assembled once for all fields), solved by dense LU."""
    A, B, M = _weak_forms(grid, k)
    lu = lu_factor(A)
    out = []
    for vn in vns:
        vn = np.asarray(vn, complex)
        p = lu_solve(lu, -(B @ (1j * k * c * rho * vn)))
        out.append(0.5 * float(np.real(np.conj(vn) @ (M @ p))))
    return out


def _h(n, x):
    return spherical_jn(n, x) + 1j * spherical_yn(n, x)


def _dh(n, x):
    return spherical_jn(n, x, derivative=True) + 1j * spherical_yn(n, x, derivative=True)


def pulsating_sphere_power(a: float, k: float, v: float = 1.0, rho: float = 1.21, c: float = 343.0) -> float:
    """Power [W] of a sphere of radius a pulsating with normal velocity amplitude v (exact)."""
    ka = k * a
    return 0.5 * rho * c * ka**2 / (1 + ka**2) * v**2 * 4 * np.pi * a**2


def oscillating_sphere_power(a: float, k: float, v: float = 1.0, rho: float = 1.21, c: float = 343.0) -> float:
    """Power [W] of a rigid sphere of radius a translating with velocity amplitude v (exact, n = 1)."""
    z = 1j * rho * c * _h(1, k * a) / _dh(1, k * a)
    return 0.5 * float(np.real(z)) * v**2 * 4 * np.pi * a**2 / 3


def level(power: float) -> float:
    """Sound power level, dB re 1e-12 W."""
    return float(10 * np.log10(power / 1e-12))
