"""Where a case's contact point lies on the rail model: the loaded head point of the rail file for the
profiles' contact point (a listed node of ``contact.y``, or any point of the running surface)."""
from __future__ import annotations

import numpy as np

from pipeline.config.loader import ConfigError
from pipeline.store import paths


RAIL_POINT_TOL = 1e-3  # m: a contact point this close to a node of the rail file's contact.y list takes that node


def rail_point(name: str, pr: dict, y_r: float, where: str = "") -> float:
    """The rail model's loaded head point for the contact point y^R of the profiles: the node of the
    rail file's ``contact.y`` list (mesh nodes of the rail section) on the same side of the head as
    y^R (the vertical-lateral cross receptance changes sign with the side) when |y^R| is within
    RAIL_POINT_TOL of one (the rail's receptances change little with the lateral position on the
    head, thesis section 4.2.2; the numbers of before for the listed points), else y^R itself: any
    point of the running surface has its receptances from the surface wave table
    (``pipeline.caches.rail_surface_table``).  A point off the running surface (beyond the head's widest point)
    is a one-line ConfigError (``where``: the case and offset it names)."""
    ys = np.unique(np.abs(np.asarray(pr["contact"]["y"], float)))
    if len(ys):
        i = int(np.argmin(np.abs(ys - abs(y_r))))
        if abs(ys[i] - abs(y_r)) <= RAIL_POINT_TOL:
            return float(np.copysign(ys[i], y_r))
    half = 0.5 * pr["head"]["width"]
    if abs(y_r) > half:
        raise ConfigError(str(paths.rail_file(name)), detail=(
            (f"{where}: " if where else "") + f"the contact point y^R = {1e3 * y_r:+.3f} mm of the profiles is "
            f"off the rail head's running surface (|y| <= {1e3 * half:.1f} mm, head.width / 2)"))
    return float(y_r)
