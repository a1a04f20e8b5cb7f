"""Figure of the contact stage (contact_rf.png): the regularized friction curves, with the case's
operating slip when given."""
from __future__ import annotations

import numpy as np


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


def friction_curves_figure(a: dict, title: str, operating: tuple[float, float] | None = None):
    """mu_RF = F2/F3 vs slip velocity for every curve of the contact (the regularized friction curves); ``operating``
    = (s, mu): the case's steady slip, marked on its curve."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(a["mu_values"])))
    labels = a["rf_label"] if "rf_label" in a else [f"mu = {mu:.2f}" for mu in a["mu_values"]]
    for i, label in enumerate(labels):
        n = a["rf_n"][i]
        ax.plot(a["rf_s"][i, :n], a["rf_mu"][i, :n], color=colours[i], label=str(label))
    xmax = float(a["rf_s"][:, -1].max()) * 0.35
    if operating is not None:
        s, mu = operating
        s_, m_ = operating_point(a, 1.0, 0.0, s, mu)
        ax.axvline(s, color="C3", lw=1, ls="--")
        if np.isfinite(m_):
            ax.plot([s], [m_], "o", color="C3", ms=7, label=f"operating slip {s:.3f} m/s")
        xmax = max(xmax, 1.3 * s)
    ax.set_xlabel("slip velocity s (m/s)")
    ax.set_ylabel("mu_RF = F2 / F3")
    ax.set_xlim(0, xmax)
    ax.set_title(f"Regularized friction curves, {title}")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig
