"""numba's extensions, loaded at its first compile in every process (``skip_special``).

rocket_fft (numpy.fft inside numba, solvers/timeloop/partitioned.py) is a numba extension: numba runs its
entry point ``rocket_fft:_init_extension`` at the first compile or cache load of each process, and
with scipy installed that entry point also compiles scipy.special's loggamma and poch for numba
(8 signatures, not cached: ~1.5 s per process).  The project calls neither in numba code.
Importing rocket_fft itself costs ~0.5 s, which the stages without numpy.fft in numba (contact,
greens) need not pay: its overloads are registered when it is imported, and the one module that
uses them (solvers/timeloop/partitioned.py) imports it.
"""
from __future__ import annotations
import sys


def skip_special() -> None:
    """Skip numba's extension entry points (rocket_fft's is the only one installed; its numpy.fft
    overloads come with ``import rocket_fft``, done by the modules that use them) and so the
    scipy.special signatures and the import of rocket_fft where it is not used.  Call it before any
    numba code runs."""
    from numba.core import entrypoints  # lazy: brings in numba

    entrypoints._already_initialized = True   # numba's init_all() then loads no entry point
    if "rocket_fft" in sys.modules:           # already imported: its entry point would be skipped anyway
        sys.modules["rocket_fft"]._init_extension = lambda: None
