"""Inputs: TOML schemas, loading and validation, the resolved case, `make check`."""
