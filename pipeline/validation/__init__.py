"""Validation: the calibrations (``calibrate_*``), the writers of docs/validation/ (``writers/``, run by
`make validate`; the studies they report on: ``limit_cycle_runs``, ``revolved_wheel``, ``field``, ...), the
independent references the writers and the tests compare with (``references/``: analytic solutions, published
tables, second methods), and ``make`` (what a writer needs, built through Make)."""
