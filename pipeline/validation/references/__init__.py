"""Independent references the checks compare with: exact solutions (Hertz, Carter, Kirchhoff plates,
beams on a damped foundation, linear curving), published tables (``data/``: the thesis' C20
eigenfrequencies, Kalker's creep coefficients; CONTACT's printed results), second methods (the dense
TANG solver) and the in-memory cases built on them.  Shared by tests/, the validation writers
(``pipeline.validation.writers``) and benchmarks/; they import nothing from tests/."""
