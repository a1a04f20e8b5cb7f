"""Curves made from another one for the studies (radius study, field comparison): the base curve's
vehicle, rail, gauge and friction with another radius, speed and cant -- a ``Curve`` in memory, its
curve file written as a record beside the study's results."""
from __future__ import annotations

import tomllib
from pathlib import Path

import tomli_w

from pipeline.config.nouns import Curve
from pipeline.store.atomic import save_text
from pipeline.config.curve_inputs import curve_of, read_curve
from pipeline.config.curve_schemas import CURVE
from pipeline.config.loader import validate
from pipeline.store import paths


def radius_curve(base: str | Path, folder: Path, radius: float, speed_kmh: float, cant: float,
                 name: str | None = None) -> Curve:
    """The base curve (a shipped name or a curve file's path) with ``radius_m``, ``speed_kmh`` and
    ``cant_mm`` replaced, named ``name`` (default ``<base>-R<radius>``), its vehicle the base curve's;
    its record ``<folder>/<name>.toml`` written (unchanged files are not rewritten)."""
    src = read_curve(base)                               # the base is valid (ConfigError otherwise)
    data = tomllib.loads(src.source.read_text())
    name = name or f"{src.name}-R{radius:g}"
    data.update(name=name, radius_m=float(radius), speed_kmh=float(speed_kmh), cant_mm=round(1e3 * cant, 1),
                description=f"{data.get('description', src.name)}; radius study: R = {radius:g} m, "
                            f"{speed_kmh:g} km/h, cant {1e3 * cant:.0f} mm")
    text = f"# made from {paths.shown(src.source)} by pipeline/curve/curvefiles.py\n" + tomli_w.dumps(data)
    path = Path(folder) / f"{name}.toml"
    if not (path.exists() and path.read_text() == text):
        save_text(text, path)
    return curve_of(validate(data, CURVE, str(path)), path, name, src.vehicle)
