"""Curve files made from a shipped one for the studies (radius study, field comparison): the base
curve's vehicle, rail, gauge and friction with another radius, speed and cant."""
from __future__ import annotations

import tomllib
from pathlib import Path

import tomli_w

from pipeline.store.atomic import save_text


def write_radius_curve(base: str, folder: Path, radius: float, speed_kmh: float, cant: float,
                       name: str | None = None) -> str:
    """Write ``<folder>/<name>.toml`` (default name ``<base>-R<radius>``) from the base curve
    ``pipeline/curves/<base>.toml`` with ``radius_m``, ``speed_kmh`` and ``cant_mm`` replaced;
    unchanged files are not rewritten.  Returns the name."""
    from pipeline.store import paths
    from pipeline.config.loader import load
    from pipeline.config.curve_schemas import CURVE

    src = paths.ROOT / "pipeline" / "curves" / f"{base}.toml"      # a shipped curve
    load(src, CURVE)                                  # the base is valid (ConfigError otherwise)
    data = tomllib.loads(src.read_text())
    name = name or f"{base}-R{radius:g}"
    data.update(name=name, radius_m=float(radius), speed_kmh=float(speed_kmh), cant_mm=round(1e3 * cant, 1),
                description=f"{data.get('description', base)}; radius study: R = {radius:g} m, "
                            f"{speed_kmh:g} km/h, cant {1e3 * cant:.0f} mm")
    text = f"# made from pipeline/curves/{base}.toml by pipeline/curve/curvefiles.py\n" + tomli_w.dumps(data)
    path = Path(folder) / f"{name}.toml"
    if not (path.exists() and path.read_text() == text):
        save_text(text, path)
    return name
