"""Tests of solvers/timeloop/ (the in-memory cases: pipeline/validation/references/interaction.py)."""
