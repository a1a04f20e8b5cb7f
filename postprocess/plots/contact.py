"""Figure of the contact stage (contact_rf.png): the regularized friction curves."""
from __future__ import annotations

import numpy as np


def friction_curves_figure(a: dict, title: str):
    """F2/F3 vs slip velocity for every curve of the contact (the regularized friction curves)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(a["mu_values"])))
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
    fig.tight_layout()
    return fig
