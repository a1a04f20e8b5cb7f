"""Transfer receptances of the rail between two head points as a wave table (issue 26: two
contact points), the cross blocks of the rail's 2 x 2-point receptance.

``solvers.rail.response.wave_table`` gives the point receptance of each head point; the same
residue sum with the response taken at another loaded node gives the transfer receptance

    G_pq[i, j](x, f) = sum_n a[f, n, i, j] exp(-i k[f, n] |x|)   (response at p, direction i,
                                                                  to a unit force at q, direction j)

exact for the discretised section (``solvers.rail.response`` notes).  Half model: the full
section's response is (sym + anti) / 2 with the mirror signs of points on the y < 0 side: a
lateral (y) component changes sign under the mirror in the symmetric family, a vertical (z)
component in the antisymmetric one -- for the response at p and the load at q alike (for p = q
this is ``wave_table``'s rule: yz and zy change sign).  Directions as SPEC 2 (z up in the section
-> 3 down: yz, zy change sign).  Reciprocity, G_qp = G_pq^T, holds term by term (the section's
matrices are symmetric) and is checked in tests/greens/test_two_point_greens.py.
"""
from __future__ import annotations

import numpy as np

from solvers.rail.model import RailModel
from solvers.rail.reduced import wave_amplitudes

COMP = ("y", "z")


def mirror_sign(family: str, comp: str, y: float) -> float:
    """Sign of a load or response component at head point y under the half model's mirror."""
    if y >= 0:
        return 1.0
    if family == "sym":
        return -1.0 if comp == "y" else 1.0
    return -1.0 if comp == "z" else 1.0


def transfer_wave_table(model: RailModel, freqs, y_out: float, y_in: float, k_local: float = 20.0) -> dict:
    """Wave table of the transfer receptance from a load at head point y_in to the response at
    y_out (both loaded in ``model``; the static near field excluded as in ``wave_table``'s default,
    waves with |k| > k_local at w = 0).  Returns {'k': (nf, M), 'a': (nf, M, 2, 2), 'f'}:
    a[..., i, j], i the response direction at y_out, j the load direction at y_in (0 = 2
    lateral to the field side, 1 = 3 vertical down)."""
    T = block_wave_table(model, freqs, [(y_out, y_in)], k_local)
    return {"k": T["k"], "a": T["a"][:, :, 0], "f": T["f"]}


def block_wave_table(model: RailModel, freqs, blocks, k_local: float = 20.0) -> dict:
    """``transfer_wave_table`` for several (y_out, y_in) blocks at once (one eigenproblem per
    frequency and family for all of them): {'k': (nf, M), 'a': (nf, M, n_blocks, 2, 2), 'f'}."""
    freqs = np.asarray(freqs, float)
    for y in {abs(float(v)) for b in blocks for v in b}:
        if not np.any(np.isclose(y, model.point_y, atol=1e-9)):
            raise ValueError(f"head point {y} is not loaded in this model (available |y^R|: {model.point_y.tolist()})")
    omegas = 2 * np.pi * freqs
    ks, As = [], []
    for fam in ("sym", "anti"):
        rf = getattr(model, fam)
        idx_in = {key: i for i, key in enumerate(rf.in_names)}
        idx_out = {key: i for i, key in enumerate(rf.out_names)}
        pairs, slots = [], []
        for nb, (y_out, y_in) in enumerate(blocks):
            for i, a in enumerate(COMP):
                for j, b in enumerate(COMP):
                    ko, ki = (_node(model, y_out), a), (_node(model, y_in), b)
                    if ko in idx_out and ki in idx_in:
                        pairs.append((idx_out[ko], idx_in[ki]))
                        sign = mirror_sign(fam, a, y_out) * mirror_sign(fam, b, y_in) * (-1.0 if a != b else 1.0)
                        slots.append((nb, i, j, sign))
        K, A = wave_amplitudes(rf, omegas, pairs, k_local=k_local)
        amp = np.zeros(K.shape + (len(blocks), 2, 2), complex)
        for q, (nb, i, j, sign) in enumerate(slots):
            amp[:, :, nb, i, j] += 0.5 * sign * A[:, :, q]
        ks.append(K)
        As.append(amp)
    return {"k": np.concatenate(ks, axis=1), "a": np.concatenate(As, axis=1), "f": freqs}


def _node(model: RailModel, y: float) -> float:
    """The model's loaded |y| (as stored in the reduced families' names) for head point y."""
    return float(model.point_y[int(np.argmin(np.abs(model.point_y - abs(y))))])
