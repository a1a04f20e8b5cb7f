"""Tests of the Thompson-Jones radiation model (postprocess/radiation.py) and
of the force spectra (postprocess/spectra.py)."""
