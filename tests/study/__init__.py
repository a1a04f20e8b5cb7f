"""Tests of the parameter studies (SPEC 7): the results table, the study numerics
(solvers/study.py), the study definitions, the Dask runner (kill and resume through the CLI)
and the studies on the real case artifacts."""
