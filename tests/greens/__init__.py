"""Tests of solvers/wheel/receptance.py and solvers/greens/ (references: pipeline/validation/references/greens.py)."""
