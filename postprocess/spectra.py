"""Spectra and levels of contact-force histories (SPEC 5 and 6): defined in ``solvers.spectra``
(the time loop's squeal measures need them, and ``solvers`` imports nothing from here)."""
from solvers.spectra import (amplitude_spectrum, dominant_frequency, final_stretch, force_level,  # noqa: F401
                             rms, window_samples)
