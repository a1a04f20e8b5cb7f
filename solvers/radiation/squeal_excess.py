"""Squeal's excess over rolling noise at a receiver (pure numerics), as the field measures it.

STUVA's survey (docs/validation/92_field.md) gives the mean increase of the pass-by's maximum level
L_A,max by squeal two ways: over the passages that squeal only, and over all passages (those without
squeal adding 0 dB).  With squeal in a share p of the passages and, when it squeals, the pass-by's
level (rolling and squeal together) L_k for each of the equally likely squealing states k:

    dL_when   = mean_k (L_k - L_rolling)        (the excess when it squeals)
    dL_all    = p * dL_when                     (the expectation over all passages)

(the arithmetic mean of level differences, as the survey's mean increase is; ``energetic=True``
averages the energies instead: 10 lg(mean_k 10^(L_k/10)) - L_rolling).
"""
from __future__ import annotations

import numpy as np

from solvers.radiation.rolling_cnossos import db_sum


def squeal_excess(levels_with_squeal, level_rolling: float, p: float = 1.0, energetic: bool = False) -> float:
    """The expected excess (dB) of the pass-by's level over rolling noise alone, over all passages
    (module notes).  ``levels_with_squeal``: the pass-by's levels (dB) in the squealing states (each the
    energy sum of rolling and squeal, so >= level_rolling); ``p`` in [0, 1]: the share of passages that
    squeal.  No squealing state or p = 0: 0 dB."""
    if not 0.0 <= p <= 1.0:
        raise ValueError(f"share of squealing passages p = {p!r}: must be in [0, 1]")
    L = np.atleast_1d(np.asarray(levels_with_squeal, float))
    L = L[np.isfinite(L)]
    if L.size == 0 or p == 0.0:
        return 0.0
    if not np.isfinite(level_rolling):
        raise ValueError(f"rolling level {level_rolling!r} dB: must be finite")
    when = (10.0 * np.log10(np.mean(10.0 ** (L / 10.0))) if energetic else float(np.mean(L))) - level_rolling
    return float(p * when)


def climate_excess(level_rolling: float, level_squeal: float, p: float) -> float:
    """The expected excess over the friction climate (STUVA's method that counts how often squeal occurs):
    a share ``p`` of the passages squeal, each at the pass-by level of rolling noise and squeal together
    (energy sum of ``level_rolling`` and ``level_squeal``, dB), the others at rolling noise alone.  NaN
    ``level_squeal`` (no wheel squeals anywhere in the climate): 0 dB."""
    if not np.isfinite(level_squeal):
        return 0.0
    return squeal_excess([db_sum(level_rolling, level_squeal)], level_rolling, p)
