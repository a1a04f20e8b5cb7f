"""Figure of the contact stage (contact_rf.png): the regularized friction curves (and, for the report,
the case's operating slip on them)."""
from __future__ import annotations

import numpy as np


def friction_curves_figure(a: dict, title: str):
    """F2/F3 vs slip velocity for every curve of the contact (the regularized friction curves)."""
    import matplotlib  # lazy: brings in matplotlib
    from matplotlib.figure import Figure  # no pyplot (its import is half a second of a stage's time)

    fig = Figure(figsize=(6.5, 4))
    ax = fig.subplots()
    colours = matplotlib.colormaps["viridis"](np.linspace(0, 0.9, len(a["mu_values"])))
    labels = a["rf_label"] if "rf_label" in a else [f"mu = {mu:.2f}" for mu in a["mu_values"]]
    for i, label in enumerate(labels):
        n = a["rf_n"][i]
        ax.plot(a["rf_s"][i, :n], a["rf_mu"][i, :n], color=colours[i], label=str(label))
    ax.set_xlabel("slip velocity s (m/s)")
    ax.set_ylabel("mu_RF = F2 / F3")
    ax.set_xlim(0, float(a["rf_s"][:, -1].max()) * 0.35)
    ax.set_title(f"Regularized friction curves, {title}")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    fig.subplots_adjust(left=0.12, right=0.97, bottom=0.12, top=0.92)  # fixed: tight_layout costs 0.3 s
    return fig


def operating_point(a: dict, v: float, gamma_y: float, gamma_x: float, mu: float) -> tuple[float, float]:
    """(s, mu_RF(s)): the steady slip speed s = |(gamma_x, gamma_y)| v of the case (m/s; rigid slip,
    docs/physics.md section 2) and the regularized friction coefficient there on the curve of ``mu``
    (NaN when ``a`` holds no curve for that mu)."""
    s = float(np.hypot(gamma_x, gamma_y) * v)
    i = np.flatnonzero(np.isclose(a["mu_values"], mu, atol=1e-9))
    if not i.size:
        return s, float("nan")
    n = int(a["rf_n"][i[0]])
    return s, float(np.interp(s, a["rf_s"][i[0], :n], a["rf_mu"][i[0], :n]))


def mark_operating_slip(fig, a: dict, s: float, mu: float):
    """The friction curves figure (``friction_curves_figure``) with the case's steady slip ``s`` (m/s)
    marked: a vertical line, and the point on the curve of ``mu`` when the contact holds one."""
    ax = fig.axes[0]
    _, m = operating_point(a, 1.0, 0.0, s, mu)
    ax.axvline(s, color="C3", lw=1, ls="--")
    if np.isfinite(m):
        ax.plot([s], [m], "o", color="C3", ms=7, label=f"operating slip {s:.3f} m/s")
    ax.set_xlim(0, max(ax.get_xlim()[1], 1.3 * s))
    ax.legend(fontsize=7, ncol=2)
    return fig
