"""Element kernels of TANG's Newton solver in numba (notes in ``solvers.contact.tang``): compact
element vectors <-> grid arrays, the Newton matrix's rows, the preconditioner's two halves, the
fused CG steps, and the stick/slip geometry and set updates."""
from __future__ import annotations

import math

import numba
import numpy as np


@numba.njit(cache=True)
def scatter(ix, iy, p, out):
    """out (2, nx, ny) <- 0, p (N, 2) on the elements."""
    out[:] = 0.0
    for k in range(ix.shape[0]):
        out[0, ix[k], iy[k]] = p[k, 0]
        out[1, ix[k], iy[k]] = p[k, 1]


@numba.njit(cache=True)
def gather_slip(ix, iy, u, steady, r, s):
    """s (N, 2) <- r + M p from the displacements u (2, nx + 1, ny) of p."""
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        for a in range(2):
            m = u[a, i, j]
            if steady:
                m -= u[a, i + 1, j]
            s[k, a] = r[k, a] + m


@numba.njit(cache=True)
def lift(ix, iy, stick, t, x, out):
    """Newton variables x (N, 2) -> traction increments on the grid: stick (x0, x1), slip x0 t."""
    out[:] = 0.0
    for k in range(ix.shape[0]):
        if stick[k]:
            out[0, ix[k], iy[k]] = x[k, 0]
            out[1, ix[k], iy[k]] = x[k, 1]
        else:
            out[0, ix[k], iy[k]] = x[k, 0] * t[k, 0]
            out[1, ix[k], iy[k]] = x[k, 0] * t[k, 1]


@numba.njit(cache=True)
def jacobian_rows(ix, iy, stick, t, D, u, steady, scale, x, y):
    """y = J x (scaled by 1/scale): stick rows M dp, slip rows t . M dp + D x0 (dummy 0)."""
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        m0, m1 = u[0, i, j], u[1, i, j]
        if steady:
            m0 -= u[0, i + 1, j]
            m1 -= u[1, i + 1, j]
        if stick[k]:
            y[k, 0] = m0 / scale
            y[k, 1] = m1 / scale
        else:
            y[k, 0] = (t[k, 0] * m0 + t[k, 1] * m1) / scale + D[k] * x[k, 0]
            y[k, 1] = 0.0


@numba.njit(cache=True)
def precondition_in(ix, iy, stick, t, sc, x, steady, slip_fft, out):
    """Fields of the preconditioner's transform: 0, 1 the stick part of x (steady: summed along x
    from the leading edge, the exact inverse of the transport difference I - shift on each grid
    line); 2, 3 (slip_fft) the slip part lifted along the tangents, scaled by sc."""
    out[:] = 0.0
    for k in range(ix.shape[0]):
        if stick[k]:
            out[0, ix[k], iy[k]] = x[k, 0]
            out[1, ix[k], iy[k]] = x[k, 1]
        elif slip_fft:
            out[2, ix[k], iy[k]] = sc[k] * x[k, 0] * t[k, 0]
            out[3, ix[k], iy[k]] = sc[k] * x[k, 0] * t[k, 1]
    if steady:
        nx = out.shape[1]
        for a in range(2):
            for j in range(out.shape[2]):
                for i in range(nx - 2, -1, -1):
                    out[a, i, j] += out[a, i + 1, j]


@numba.njit(cache=True)
def precondition_out(ix, iy, stick, t, sc, D, mdiag, z, slip_fft, x, y):
    """y = P^-1 x from the transformed fields z: stick z[0:2]; slip sc t . z[2:4] (slip_fft) or
    the diagonal 1 / (t' M_II t + D) (scaled units)."""
    for k in range(ix.shape[0]):
        i, j = ix[k], iy[k]
        if stick[k]:
            y[k, 0] = z[0, i, j]
            y[k, 1] = z[1, i, j]
        else:
            if slip_fft:
                y[k, 0] = sc[k] * (t[k, 0] * z[2, i, j] + t[k, 1] * z[3, i, j])
            else:
                m = t[k, 0] * t[k, 0] * mdiag[0] + t[k, 1] * t[k, 1] * mdiag[1]
                y[k, 0] = x[k, 0] / (m + D[k])
            y[k, 1] = 0.0


@numba.njit(cache=True)
def _kth(v, k):
    """The k-th smallest value of v (0-based; Hoare's quickselect, v reordered in place).  np.median's
    numba implementation takes ~1.6 s to compile in every fresh build; this, a tenth of it."""
    lo, hi = 0, v.shape[0] - 1
    while lo < hi:
        pivot = v[(lo + hi) // 2]
        i, j = lo, hi
        while i <= j:
            while v[i] < pivot:
                i += 1
            while v[j] > pivot:
                j -= 1
            if i <= j:
                v[i], v[j] = v[j], v[i]
                i += 1
                j -= 1
        if k <= j:
            hi = j
        elif k >= i:
            lo = i
        else:
            break
    return v[k]


@numba.njit(cache=True)
def _median(v):
    """np.median(v) (the same arithmetic: the middle value, or the mean of the two), v reordered."""
    n = v.shape[0]
    half = n // 2
    if n % 2 == 1:
        return _kth(v, half)
    a = _kth(v, half - 1)
    b = v[half]
    for k in range(half + 1, n):                   # after the select, v[half:] >= a: its least
        b = min(b, v[k])
    return (a + b) / 2


@numba.njit(cache=True)
def slip_scaling(stick, t, D, mdiag, sc):
    """Median of D over the slip elements and the symmetric scaling sqrt((m + dbar) / (m + D))."""
    n = 0
    for k in range(stick.shape[0]):
        if not stick[k]:
            n += 1
    if n == 0:
        return 0.0
    vals = np.empty(n)
    n = 0
    for k in range(stick.shape[0]):
        if not stick[k]:
            vals[n] = D[k]
            n += 1
    dbar = _median(vals)
    for k in range(stick.shape[0]):
        if not stick[k]:
            m = t[k, 0] * t[k, 0] * mdiag[0] + t[k, 1] * t[k, 1] * mdiag[1]
            sc[k] = math.sqrt((m + dbar) / (m + D[k]))
    return dbar


@numba.njit(cache=True)
def pcg_direction(ix, iy, stick, t, sc, D, mdiag, Z, slip_fft, r, z, rz_old, d, lifted):
    """PCG: z = P^-1 r from the preconditioner's transform Z, rz = r . z, d = z + (rz / rz_old) d
    (d = z when rz_old = 0) and d lifted onto the grid for the next product.  Returns rz."""
    precondition_out(ix, iy, stick, t, sc, D, mdiag, Z, slip_fft, r, z)
    rz = 0.0
    for k in range(r.shape[0]):
        rz += r[k, 0] * z[k, 0] + r[k, 1] * z[k, 1]
    beta = rz / rz_old if rz_old != 0.0 else 0.0
    for k in range(r.shape[0]):
        d[k, 0] = z[k, 0] + beta * d[k, 0]
        d[k, 1] = z[k, 1] + beta * d[k, 1]
    lift(ix, iy, stick, t, d, lifted)
    return rz


@numba.njit(cache=True)
def pcg_update(ix, iy, stick, t, D, U, steady, scale, d, q, rz, x, r, sc, slip_fft, prec_in):
    """PCG: q = J d from the displacements U of the lifted d, alpha = rz / (d . q), x += alpha d,
    r -= alpha q, and r prepared for the preconditioner.  Returns (|r|^2, d . q, max |alpha d|,
    max |x|)."""
    jacobian_rows(ix, iy, stick, t, D, U, steady, scale, d, q)
    dq = 0.0
    for k in range(d.shape[0]):
        dq += d[k, 0] * q[k, 0] + d[k, 1] * q[k, 1]
    if dq <= 0.0:
        return 0.0, dq, 0.0, 0.0
    alpha = rz / dq
    rr = dmax = xmax = 0.0
    for k in range(d.shape[0]):
        for a in range(2):
            x[k, a] += alpha * d[k, a]
            r[k, a] -= alpha * q[k, a]
            rr += r[k, a] * r[k, a]
            dmax = max(dmax, abs(d[k, a]))
            xmax = max(xmax, abs(x[k, a]))
    precondition_in(ix, iy, stick, t, sc, r, steady, slip_fft, prec_in)
    return rr, dq, abs(alpha) * dmax, xmax


@numba.njit(cache=True)
def residual(stick, t, s, R):
    """Newton residual: stick s, slip (t . s, 0).  Returns its max norm."""
    big = 0.0
    for k in range(s.shape[0]):
        if stick[k]:
            R[k, 0], R[k, 1] = s[k, 0], s[k, 1]
        else:
            R[k, 0] = t[k, 0] * s[k, 0] + t[k, 1] * s[k, 1]
            R[k, 1] = 0.0
        big = max(big, abs(R[k, 0]), abs(R[k, 1]))
    return big


@numba.njit(cache=True)
def slip_geometry(stick, theta, g, s, p, t, D, scale):
    """Tractions of slip elements on their circle g (cos, sin)(theta); tangents t (all elements,
    from the traction direction); D = max(-s . n, 0) / g / scale on slip (the turning term)."""
    for k in range(theta.shape[0]):
        if stick[k]:
            th = math.atan2(p[k, 1], p[k, 0])
            D[k] = 0.0
        else:
            th = theta[k]
        c, sn = math.cos(th), math.sin(th)
        t[k, 0], t[k, 1] = -sn, c
        if not stick[k]:
            p[k, 0], p[k, 1] = g[k] * c, g[k] * sn
            D[k] = max(-(s[k, 0] * c + s[k, 1] * sn), 0.0) / max(g[k], 1e-300) / scale


@numba.njit(cache=True)
def apply_step(stick, theta, g, dz, p, clip):
    """p += dz on stick, theta += dz0 / g (clipped) on slip; returns the largest change [Pa]."""
    change = 0.0
    for k in range(stick.shape[0]):
        if stick[k]:
            p[k, 0] += dz[k, 0]
            p[k, 1] += dz[k, 1]
            change = max(change, abs(dz[k, 0]), abs(dz[k, 1]))
        else:
            dth = dz[k, 0] / max(g[k], 1e-300)
            if dth > clip:
                dth = clip
            elif dth < -clip:
                dth = -clip
            theta[k] += dth
            p[k, 0] = g[k] * math.cos(theta[k])
            p[k, 1] = g[k] * math.sin(theta[k])
            change = max(change, g[k] * abs(dth))
    return change


@numba.njit(cache=True)
def update_sets(stick, theta, g, p, s, rel):
    """Kalker's set update: stick elements beyond the bound -> slip (projected onto the bound);
    slip elements whose slip points along the traction -> stick.  Returns (moved to slip,
    moved to stick)."""
    s_scale = 1e-300
    for k in range(stick.shape[0]):
        s_scale = max(s_scale, abs(s[k, 0]), abs(s[k, 1]))
    n_slip = 0
    n_stick = 0
    for k in range(stick.shape[0]):
        if stick[k]:
            a = math.hypot(p[k, 0], p[k, 1])
            if a > g[k] * (1.0 + rel):
                stick[k] = False
                theta[k] = math.atan2(p[k, 1], p[k, 0])
                p[k, 0] *= g[k] / a
                p[k, 1] *= g[k] / a
                n_slip += 1
        else:
            if s[k, 0] * p[k, 0] + s[k, 1] * p[k, 1] > rel * s_scale * g[k]:
                stick[k] = True
                n_stick += 1
    return n_slip, n_stick


@numba.njit(cache=True)
def start_on_bounds(stick, theta, g, s, p, t, D, scale, p_given):
    """The start of a solve: slip elements on their circle (slip_geometry), stick elements beyond
    their bound scaled onto it.  Returns (traction level max |p|, largest change from p_given)."""
    slip_geometry(stick, theta, g, s, p, t, D, scale)
    level = moved = 0.0
    for k in range(stick.shape[0]):
        if stick[k]:
            a = math.hypot(p[k, 0], p[k, 1])
            if a > g[k]:
                p[k, 0] *= g[k] / a
                p[k, 1] *= g[k] / a
        level = max(level, abs(p[k, 0]), abs(p[k, 1]))
        moved = max(moved, abs(p[k, 0] - p_given[k, 0]), abs(p[k, 1] - p_given[k, 1]))
    return max(level, 1e-300), moved


@numba.njit(cache=True)
def newton_system(stick, theta, g, s, p, t, D, scale, R, b, mdiag, sc):
    """One Newton step's system: geometry (slip_geometry), residual R and right-hand side b = -R /
    scale, and (transient preconditioner) the slip elements' scaling sc (slip_scaling).  Returns
    (max |R|, number of stick elements, median D on slip)."""
    slip_geometry(stick, theta, g, s, p, t, D, scale)
    r_max = residual(stick, t, s, R)
    n_stick = 0
    for k in range(stick.shape[0]):
        b[k, 0] = -R[k, 0] / scale
        b[k, 1] = -R[k, 1] / scale
        n_stick += stick[k]
    dbar = slip_scaling(stick, t, D, mdiag, sc) if n_stick < stick.shape[0] else 0.0
    return r_max, n_stick, dbar


@numba.njit(cache=True)
def step_and_scatter(ix, iy, stick, theta, g, dz, p, clip, out):
    """apply_step, then the new tractions on the grid (scatter).  Returns the largest change."""
    change = apply_step(stick, theta, g, dz, p, clip)
    scatter(ix, iy, p, out)
    return change


@numba.njit(cache=True)
def slip_and_sets(ix, iy, u, steady, r, s, stick, theta, g, p, rel):
    """gather_slip from the displacements u of p, then the set update (update_sets).  Returns
    (moved to slip, moved to stick, traction level max |p|)."""
    gather_slip(ix, iy, u, steady, r, s)
    n_slip, n_stick = update_sets(stick, theta, g, p, s, rel)
    level = 1e-300
    for k in range(p.shape[0]):
        level = max(level, abs(p[k, 0]), abs(p[k, 1]))
    return n_slip, n_stick, level


@numba.njit(cache=True)
def forcing_term(rough, ratio, r_max, tol, p_level, eta_final):
    """The Krylov tolerance of a Newton step: 1e-2 while the sets still move (rough); else the
    accuracy the expected step (last step per unit residual, ratio, times the residual r_max)
    needs for an absolute error of 0.1 tol p_level, between eta_final and 0.1."""
    if rough:
        return 1e-2
    if ratio > 0.0:
        return min(0.1, max(eta_final, 0.1 * tol * p_level / max(ratio * r_max, 1e-300)))
    return eta_final


@numba.njit(cache=True)
def after_step(ix, iy, u, steady, r, s, stick, theta, g, p, change, err, tol, q_lim, sets_changed):
    """After a Newton step of largest change `change` [Pa] and Krylov error err, from the
    displacements u of the new tractions: the slip and the set update (slip_and_sets), then
    Kalker's stop: no element changed set, and the step is below tol times the traction level,
    or (the sets were already unchanged before it) below q_lim times it with the Krylov error
    below 0.1 tol (quadratic convergence makes the remaining error smaller).  Returns (moved to
    slip, elements that changed set, traction level, converged)."""
    to_slip, to_stick, p_level = slip_and_sets(ix, iy, u, steady, r, s, stick, theta, g, p, 1e-9)
    final = change <= tol * p_level or (not sets_changed and change <= q_lim * p_level
                                        and err <= 0.1 * tol * p_level)
    n_changed = to_slip + to_stick
    return to_slip, n_changed, p_level, n_changed == 0 and final
