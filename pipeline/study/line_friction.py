"""A line study's friction conditions beyond a Coulomb coefficient (issue 33): the CSV's ``friction``
cell may also name a friction preset (``solvers.contact.friction_laws.PRESETS``, e.g. ``hpf``: the
top-of-rail friction modifier) or ``base``: the base curve file's own ``[friction]`` table, any law
of the registry with its parameters (e.g. a falling law).  ``dry`` and ``wet`` keep the study
file's Coulomb coefficients (they are also preset names: the study's meaning wins).

Each condition becomes the row's curve's ``[friction]`` table, validated and resolved as a curve
file's (``pipeline.config.curve_schemas.FRICTION``, ``pipeline.caches.friction_curves.resolve_friction``).
"""
from __future__ import annotations

from pathlib import Path

from solvers.contact.friction_laws import PRESETS
from pipeline.config.curve_schemas import CURVE
from pipeline.config.loader import ConfigError, load
from pipeline.caches.friction_curves import resolve_friction

BASE = "base"


def law_condition(cell: str, base_file: Path) -> tuple[str, float, tuple] | None:
    """(condition, its coefficient at zero slip, its [friction] table as sorted items) of a CSV cell
    naming a preset or ``base`` (module notes); None for another cell (dry, wet, a number, a typo:
    ``line_input.read_rows`` judges those).  A base curve whose file is missing or whose friction
    is refused: a ConfigError naming that file."""
    name = cell.strip().lower()
    if name in PRESETS:
        table = {"preset": name}
        return name, float(resolve_friction(table, str(base_file)).mu), tuple(table.items())
    if name != BASE:
        return None
    if not base_file.exists():
        raise ConfigError(str(base_file), detail="no such base curve file (the friction condition 'base' "
                                                 "takes its [friction])")
    table = {k: v for k, v in load(base_file, CURVE)["friction"].items() if v is not None}
    law = resolve_friction(table, str(base_file))
    return f"{BASE}:{law.preset or law.name}", float(law.mu), tuple(sorted(table.items()))


def allowed() -> str:
    """The friction cells a line's CSV accepts, for its error lines."""
    return (f"'dry', 'wet', a Coulomb coefficient 0 < mu <= 1, a friction preset ({', '.join(sorted(PRESETS))}) "
            f"or '{BASE}' (the base curve's [friction])")
