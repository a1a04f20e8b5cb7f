"""Calibrations and the writers of docs/validation (run by `make validate`), published data they compare with."""
