"""The contact of the three SPEC 2 positions with the real C20 tread and
BV50 head profiles: static NORM solution and the regularized friction curves
for mu = 0.10 .. 0.60, written to docs/validation/31_contact_positions.md
(make validate)."""
from pathlib import Path

import numpy as np
import pytest
from pipeline.atomic import save_text

pytestmark = pytest.mark.validation
DOCS = Path(__file__).resolve().parents[2] / "docs" / "validation"


def test_three_positions_friction_curves():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from pipeline.config import load
    from pipeline.contact_stage import build_contact, contact_position
    from solvers.constants import THESIS_CONTACT_POSITIONS
    from pipeline.paths import case_file
    from pipeline.rail_stage import load_rail_params
    from pipeline.schemas import CASE
    from pipeline.wheel_stage import load_wheel

    c = load(case_file("default"), CASE)
    pw, _ = load_wheel(c["wheel"])
    pr, _ = load_rail_params(c["rail"])
    fig, axs = plt.subplots(2, 3, figsize=(13, 7))
    rows = ["| dy_WR | y^W / y^R (mm) | grid | approach (um) | contact elements | p_max (GPa) | "
            "full slip at mu = 0.3 (gamma_y) |", "|---|---|---|---|---|---|---|"]
    for col, dy in enumerate(sorted(THESIS_CONTACT_POSITIONS, reverse=True)):
        c["contact"]["dy_wr"] = dy
        a = build_contact(c, pw, pr)
        p = a["p3_static"]
        assert p.min() >= 0 and abs(p.sum() * a["dx"] * a["dy"] - c["loading"]["preload"]) < 1e-6 * c["loading"]["preload"]
        for i, mu in enumerate(a["mu_values"]):
            n = a["rf_n"][i]
            s, m = a["rf_s"][i, :n], a["rf_mu"][i, :n]
            assert np.all(np.diff(m) >= -1e-9) and m[0] == 0 and m[-1] == pytest.approx(mu, rel=2e-3)
            axs[0, col].plot(s, m, color=plt.cm.viridis(i / 11), label=f"{mu:.2f}")
        i03 = int(np.argmin(abs(a["mu_values"] - 0.3)))
        yw, yr = contact_position(dy)
        axs[0, col].set_title(f"dy_WR = {1e3 * dy:.0f} mm (y^W {1e3 * yw:+.0f}, y^R {1e3 * yr:+.0f} mm)")
        axs[0, col].set_xlim(0, 0.25)
        axs[0, col].set_xlabel("slip velocity (m/s)")
        axs[0, col].grid(alpha=0.3)
        im = axs[1, col].imshow(p.T / 1e9, origin="lower", aspect="equal",
                                extent=[1e3 * a["x"][0], 1e3 * a["x"][-1], 1e3 * a["y"][0], 1e3 * a["y"][-1]])
        fig.colorbar(im, ax=axs[1, col], label="p3 (GPa)", shrink=0.8)
        axs[1, col].set_xlabel("x (mm)")
        axs[1, col].set_ylabel("y (mm)")
        rows.append(f"| {1e3 * dy:.0f} mm | {1e3 * yw:+.0f} / {1e3 * yr:+.0f} | {len(a['x'])} x {len(a['y'])} | "
                    f"{1e6 * a['xi3_static']:.1f} | {int((p > 0).sum())} | {p.max() / 1e9:.2f} | "
                    f"{a['rf_gamma_sat'][i03]:.4f} |")
    axs[0, 0].set_ylabel("mu_RF = F2 / F3")
    axs[0, 2].legend(title="mu", fontsize=7, ncol=2)
    fig.tight_layout()
    DOCS.mkdir(parents=True, exist_ok=True)
    fig.savefig(DOCS / "contact_positions.png", dpi=90)
    plt.close(fig)
    text = f"""## Contact at the three nominal positions (C20 on BV50)

Test: `tests/contact/test_positions_validation.py` (validation suite). For each contact position of SPEC 2 the
contact stage's own function (`pipeline.contact_stage.build_contact`) builds the gap from the C20 tread and BV50
head profiles on the 0.5 mm grid (dx = v dt), solves NORM for the 65 kN preload and computes the regularized
friction curves for mu = 0.10 .. 0.60 with Kalker's TANG; checked: pressures >= 0, the force equals the
preload, every curve rises monotonically from 0 to mu. (The thesis' positions come from measured worn profiles;
this project's C20 has a worn 23 mm flange so that y^W = -32 mm lies on the tread, see the wheel file.)

{chr(10).join(rows)}

![friction curves and static pressures](validation/contact_positions.png)
"""
    save_text(text, DOCS / "31_contact_positions.md")
