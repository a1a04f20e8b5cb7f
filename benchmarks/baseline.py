"""The code before a change, for side-by-side benchmarks (old and new in one run).

``previous("solvers")`` extracts the package ``solvers`` (or ``postprocess``) as it was at the
revision ``BASELINE`` (``git archive``) into a temporary folder and imports it under the name
``solvers_base`` (``postprocess_base``), next to the working tree's package: both can be timed in
the same process.  The packages import their own modules relatively, so the old package runs
its own old code throughout (postprocess imports ``solvers`` absolutely: the old postprocess
uses today's solvers, whose modules it reaches did not change).  Numba caches of the old copy
go to the temporary folder.  None when git or the revision is not there (a copy of the tree
without its history): the benchmarks then leave the old rows out and say so.
"""
from __future__ import annotations

import atexit
import importlib
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# the revision before issue 15's time-loop, tone-fit, moving-kernel, rail-stage and study changes
BASELINE = "bb49c49"
_DIR: list = []


def previous(package: str, module: str | None = None):
    """The package ``package`` at ``BASELINE``, imported as ``<package>_base`` (its submodule
    ``module`` when given, e.g. previous("postprocess", "force_radiation")), or None."""
    name = f"{package}_base"
    if name in sys.modules:
        return importlib.import_module(f"{name}.{module}") if module else sys.modules[name]
    if not _DIR:
        _DIR.append(Path(tempfile.mkdtemp(prefix="bench-baseline-")))
        atexit.register(shutil.rmtree, _DIR[0], True)
    root = _DIR[0]
    try:
        tar = subprocess.run(["git", "-C", str(ROOT), "archive", f"--prefix={name}/", f"{BASELINE}:{package}"],
                             check=True, capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(root)], input=tar, check=True, capture_output=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))
    importlib.import_module(name)
    return importlib.import_module(f"{name}.{module}") if module else sys.modules[name]
