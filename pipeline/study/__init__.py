"""The parameter studies of SPEC 7, one package: a study file pipeline/studies/<name>.toml
names its kind, and

* ``stage``: ``python -m pipeline study --study NAME`` (load, validate, run or resume, log);
* ``kinds``: one module per study kind, found by name (its schema ``SCHEMA`` and its ``run``): ``map``,
  ``damping``, ``contact`` (the three kinds of SPEC 7) and ``line`` (with ``line_input``, ``line_worker``,
  ``line_rules``, ``line_outputs``: a line of curves, each curve's verdict screen first, the CNOSSOS-EU and
  Schall 03 penalties beside it); ``schemas``: the parts the kinds' schemas share; ``check``: ``make check
  STUDY=``;
* ``tasks``: the typed task records a kind hands to the workers;
* ``context``: a contact position's data (artifacts), loaded once and scattered to the workers;
* ``worker``: a task run on a Dask worker -> one row;
* ``runner``: tasks on Dask, rows appended to the ``results_table`` as they finish (resumable);
* ``screen``, ``agreement``, ``reference``: the stability screen over a map study's grid and its
  agreement with the time loop's map; the thesis' reference behaviour per contact position;
* ``report``: the studies' part of the case report.

The pure numerics of the studies (grids, the damping procedure, creepage signals, harmonic
fits) are ``solvers.study``; their figures ``postprocess.plots.study``.
"""
