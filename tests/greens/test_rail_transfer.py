"""Transfer receptances between two rail-head points (issue 26, solvers/rail/transfer.py), on
the built BV50 model (head nodes |y| = 12 and 16 mm; skipped without build/rails/bv50):

* a block from a point to itself is ``wave_table``'s point receptance (the tested routine);
* reciprocity, G_ba = G_ab^T (symmetric section matrices), between points on both sides;
* the mirror image: both points mirrored, the lateral components change sign, G' = S G S,
  S = diag(-1, 1);
* the transfer differs from the point receptances (the cross block is not a copy).
"""
from __future__ import annotations

import numpy as np
import pytest

from pipeline.validation.references.interaction import ROOT

MSH = ROOT / "build" / "rails" / "bv50" / "section.msh"
F = np.array([80.0, 400.0, 1500.0, 4000.0])


@pytest.fixture(scope="module")
def model():
    if not MSH.exists():
        pytest.skip("needs build/rails/bv50/section.msh (make rail)")
    from pipeline.stages.rail_io import build_rail_model
    from pipeline.stages.rail import load_rail_params

    pr, _ = load_rail_params("bv50")
    return build_rail_model(pr, str(MSH), contact_y=[0.012, 0.016], with_centre=False)


def G0(T, block=None):
    a = T["a"] if block is None else T["a"][:, :, block]
    return a.sum(axis=1)                                            # x = 0


def test_point_blocks_are_the_point_receptances(model):
    from solvers.rail.response import wave_table
    from solvers.rail.transfer import block_wave_table

    for y in (0.012, -0.012, -0.016):
        P = wave_table(model, F, points=[y])
        T = block_wave_table(model, F, [(y, y)])
        np.testing.assert_allclose(G0(T, 0), P["a"][:, :, 0].sum(axis=1), rtol=1e-12, atol=1e-25)


def test_reciprocity_mirror_and_difference(model):
    from solvers.rail.transfer import block_wave_table

    S = np.diag([-1.0, 1.0])
    for ya, yb in ((0.012, 0.016), (-0.012, -0.016), (0.012, -0.016)):
        T = block_wave_table(model, F, [(ya, yb), (yb, ya), (-ya, -yb), (ya, ya)])
        Gab, Gba, Gm, Gaa = G0(T, 0), G0(T, 1), G0(T, 2), G0(T, 3)
        scale = np.abs(Gab).max(axis=(1, 2))[:, None, None]
        np.testing.assert_allclose(Gba, np.swapaxes(Gab, 1, 2), rtol=0, atol=1e-9 * scale.max())
        assert np.all(np.abs(Gba - np.swapaxes(Gab, 1, 2)) <= 1e-8 * scale)
        assert np.all(np.abs(Gm - S @ Gab @ S) <= 1e-12 * scale)
        # the cross block differs from the point receptance at the higher frequencies (local deformation)
        assert np.abs(Gab[-1] - Gaa[-1]).max() > 0.05 * np.abs(Gaa[-1]).max()
