"""The plates the wheel solver is checked on against Kirchhoff's exact solutions (``annular_plate``,
``free_disc``): an annular plate clamped inside and a free solid disc through the axis, their dimensions,
steel, and their cross-sections as mesher segments (tests/test_harmonic_plate.py,
tests/test_axis_regularity.py, the wheel-modes writer)."""
from __future__ import annotations

import numpy as np

from geometry.outline import Segment

E, NU, RHO = 210e9, 0.3, 7850.0
A, B, H = 0.4, 0.1, 0.004            # annular plate: outer and inner radius, thickness (m)
N_THICK = 2                          # elements through the thickness
L_ELEM = 3.5 * H                     # element length along the radius
DISC_A, DISC_H = 0.2, 0.002          # free solid disc: radius, thickness (m)


def plate_segments():
    """The annular plate's section (r, z): inner edge (clamped), bottom, outer edge, top."""
    zt = np.linspace(0.0, H, N_THICK + 1)
    nl = int(round((A - B) / L_ELEM))
    rl = np.linspace(B, A, nl + 1)
    st = H / N_THICK
    return [
        Segment("inner", np.column_stack([np.full(N_THICK + 1, B), zt[::-1]]), st),
        Segment("bottom", np.column_stack([rl, np.zeros(nl + 1)]), L_ELEM),
        Segment("outer", np.column_stack([np.full(N_THICK + 1, A), zt]), st),
        Segment("top", np.column_stack([rl[::-1], np.full(nl + 1, H)]), L_ELEM),
    ]


def disc_segments(nl: int = 30, nt: int = 2):
    """The free disc's section: bottom, edge, top and the axis (r = 0)."""
    r = np.linspace(0, DISC_A, nl + 1)
    z = np.linspace(0, DISC_H, nt + 1)
    return [
        Segment("bottom", np.column_stack([r, np.zeros_like(r)]), DISC_A / nl),
        Segment("edge", np.column_stack([np.full_like(z, DISC_A), z]), DISC_H / nt),
        Segment("top", np.column_stack([r[::-1], np.full_like(r, DISC_H)]), DISC_A / nl),
        Segment("axis", np.column_stack([np.zeros_like(z), z[::-1]]), DISC_H / nt),
    ]
