"""Tests of the Thompson-Jones radiation model (solvers/radiation/thompson_jones.py) and
of the force spectra (solvers/spectra.py)."""
