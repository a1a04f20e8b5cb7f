"""numba's extensions, loaded at its first compile in every process (``skip_special``).

rocket_fft (numpy.fft inside numba, solvers/partitioned.py) is a numba extension: numba runs its
entry point ``rocket_fft:_init_extension`` at the first compile or cache load of each process, and
with scipy installed that entry point also compiles scipy.special's loggamma and poch for numba
(8 signatures, not cached: ~1.5 s per process).  The project calls neither in numba code.
"""
from __future__ import annotations


def skip_special() -> None:
    """Keep rocket_fft's numpy.fft overloads (registered when it is imported) and drop the
    scipy.special signatures of its entry point.  Call it before any numba code runs."""
    import rocket_fft

    rocket_fft._init_extension = lambda: None
