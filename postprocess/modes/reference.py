"""Compare computed wheel modes with a reference table by label (n, m, class)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Match:
    n: int
    m: int
    cls: str
    f_ref: float
    f_model: float | None  # None: no computed mode carries this label

    @property
    def error(self) -> float:
        return np.nan if self.f_model is None else (self.f_model - self.f_ref) / self.f_ref


def match_modes(ref_rows, f_hz, n, m, cls) -> list[Match]:
    """For each reference mode (f, n, m, class) the computed mode with the
    same label; when a label occurs more than once (it should not), the
    one closest in frequency.  Arrays f_hz, n, m, cls describe the model."""
    out = []
    for f_ref, rn, rm, rc in ref_rows:
        cand = [i for i in range(len(f_hz)) if n[i] == rn and m[i] == rm and cls[i] == rc]
        best = min(cand, key=lambda i: abs(f_hz[i] - f_ref)) if cand else None
        out.append(Match(int(rn), int(rm), str(rc), float(f_ref), None if best is None else float(f_hz[best])))
    return out


def summary(matches: list[Match]) -> dict:
    e = np.array([mt.error for mt in matches])
    found = ~np.isnan(e)
    axial0 = [abs(mt.error) for mt in matches if mt.m == 0 and mt.cls == "a" and mt.f_model is not None]
    return {
        "found": int(found.sum()),
        "total": len(matches),
        "median_abs": float(np.median(np.abs(e[found]))) if found.any() else np.nan,
        "max_abs": float(np.max(np.abs(e[found]))) if found.any() else np.nan,
        "max_abs_n0a": float(max(axial0)) if axial0 else np.nan,
    }


def markdown_table(matches: list[Match]) -> str:
    lines = ["| (n, m, class) | reference (Hz) | model (Hz) | error |", "|---|---|---|---|"]
    for mt in matches:
        model = "not found" if mt.f_model is None else f"{mt.f_model:.1f}"
        err = "" if mt.f_model is None else f"{100 * mt.error:+.1f} %"
        lines.append(f"| ({mt.n}, {mt.m}, {mt.cls}) | {mt.f_ref:.1f} | {model} | {err} |")
    return "\n".join(lines)
