"""Dense reference for TANG (the former solver of solvers/contact/tang/__init__.py, kept as a test oracle):
the same discrete equations with the influence matrix of the contact elements formed explicitly
and every Newton system solved by a dense LU.  O(n^3); small grids only.

    s = r + M p,   M = A - A(x + dx) (steady) or A (transient),
    stick s = 0, |p| <= g;  slip |p| = g, p = -g s / |s|      (solvers/contact/tang/__init__.py)

Kalker's active-set Newton method: stick unknowns (p1, p2), slip unknown theta; one Newton step,
then stick elements beyond the bound move to slip and slip elements whose slip points along the
traction move to stick; until no element changes set and the step is below tol * max(g).
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from solvers.contact.influence import tangential_kernels, Convolver


def dense_operator(contact, dx, dy, E, nu, steady):
    ix, iy = np.nonzero(contact)
    nx, ny = contact.shape
    A = tangential_kernels(nx, ny, dx, dy, E, nu)
    K = A
    if steady:
        Ash = tangential_kernels(nx, ny, dx, dy, E, nu, shift_x=1)
        K = [a - b for a, b in zip(A, Ash)]
    k = ix[:, None] - ix[None, :] + nx - 1
    l = iy[:, None] - iy[None, :] + ny - 1
    N = len(ix)
    M = np.empty((N, 2, N, 2))
    M[:, 0, :, 0] = K[0][k, l]
    M[:, 0, :, 1] = K[1][k, l]
    M[:, 1, :, 0] = K[1][k, l]
    M[:, 1, :, 1] = K[2][k, l]
    return ix, iy, M.reshape(2 * N, 2 * N)


def solve_coulomb_dense(M, r, g, tol=1e-12, max_iter=200):
    N = len(g)
    p = np.zeros((N, 2))
    stick = np.ones(N, bool)
    theta = np.zeros(N)
    gmax = float(g.max())
    for _ in range(max_iter):
        slip = ~stick
        c, sn = np.cos(theta), np.sin(theta)
        p[slip] = (g * np.array([c, sn])).T[slip]
        s = r + (M @ p.ravel()).reshape(N, 2)
        R = s.copy()
        R[slip, 0] = s[slip, 0] * sn[slip] - s[slip, 1] * c[slip]
        R[slip, 1] = 0.0
        Cb = np.tile(np.eye(2), (N, 1, 1))
        Rb = Cb.copy()
        D = np.zeros((N, 2, 2))
        Cb[slip] = 0.0
        Cb[slip, 0, 0], Cb[slip, 1, 0] = -g[slip] * sn[slip], g[slip] * c[slip]
        Rb[slip] = 0.0
        Rb[slip, 0, 0], Rb[slip, 0, 1] = sn[slip], -c[slip]
        D[slip, 0, 0] = s[slip, 0] * c[slip] + s[slip, 1] * sn[slip]
        D[slip, 1, 1] = 1.0
        Mb = M.reshape(N, 2, N, 2)
        J = np.einsum("iab,ibjc,jcd->iajd", Rb, Mb, Cb).reshape(2 * N, 2 * N)
        J += np.einsum("iab,ij->iajb", D, np.eye(N)).reshape(2 * N, 2 * N)
        dz = sla.solve(J, -R.ravel()).reshape(N, 2)
        dth = np.clip(dz[slip, 0], -0.5, 0.5)
        p[stick] += dz[stick]
        theta[slip] += dth
        change = max(np.abs(dz[stick]).max(initial=0.0), (g[slip] * np.abs(dth)).max(initial=0.0))
        c, sn = np.cos(theta), np.sin(theta)
        p[slip] = (g * np.array([c, sn])).T[slip]
        s = r + (M @ p.ravel()).reshape(N, 2)
        s_scale = max(np.abs(s).max(), np.abs(r).max(), 1e-300)
        to_slip = stick & (np.hypot(*p.T) > g * (1.0 + 1e-9))
        to_stick = slip & ((s * p).sum(axis=1) > 1e-9 * s_scale * g)
        if not to_slip.any() and not to_stick.any() and change <= tol * gmax:
            s[stick] = 0.0
            return p, s, stick
        stick[to_slip] = False
        stick[to_stick] = True
        theta[to_slip] = np.arctan2(p[to_slip, 1], p[to_slip, 0])
    raise RuntimeError("dense TANG did not converge")


def tang_dense(p3, dx, dy, v, mu, gamma_x=0.0, gamma_y=0.0, spin=0.0, material=(210e9, 0.3), *, steady=True,
               prev=None, w_offset=1.0 / 6.0):
    """Steady (prev ignored) or one transient step after the traction field prev = (p1, p2) on the
    grid (None: traction-free); ``material``: (E, nu).  Returns (p1, p2, stick) on the grid."""
    E, nu = material
    p3 = np.asarray(p3, float)
    contact = p3 > 0
    nx, ny = p3.shape
    ix, iy, M = dense_operator(contact, dx, dy, E, nu, steady)
    dt = dx / v
    x = (ix - 0.5 * (nx - 1) + w_offset) * dx
    y = (iy - 0.5 * (ny - 1)) * dy
    r = np.column_stack([(gamma_x - spin * y) * v, (gamma_y + spin * x) * v]) * dt
    if not steady and prev is not None:
        Ash = tangential_kernels(nx, ny, dx, dy, E, nu, shift_x=1)

        conv = Convolver(*Ash)
        h1, h2 = conv.transform(prev[0]), conv.transform(prev[1])
        a1 = conv.back(conv.hat[0] * h1 + conv.hat[1] * h2)
        a2 = conv.back(conv.hat[1] * h1 + conv.hat[2] * h2)
        r[:, 0] -= a1[ix, iy]
        r[:, 1] -= a2[ix, iy]
    p, s, stick = solve_coulomb_dense(M, r, mu * p3[ix, iy])
    P1, P2 = np.zeros(p3.shape), np.zeros(p3.shape)
    St = np.zeros(p3.shape, bool)
    P1[ix, iy], P2[ix, iy] = p[:, 0], p[:, 1]
    St[ix, iy] = stick
    return P1, P2, St
