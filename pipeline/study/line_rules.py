"""The noise-mapping rules for curve squeal, beside the physics' verdict (the line study, issue 27).

Both rules add a penalty to the rolling noise of a curve by its radius alone, whatever the vehicle,
speed or friction:

* **CNOSSOS-EU** (Commission Directive (EU) 2015/996, Annex II section 2.3.2 "squeal", as amended by
  Commission Delegated Directive (EU) 2021/1226): +8 dB for R <= 300 m, +5 dB for 300 m < R <= 500 m,
  added to the rolling-noise sound power (its "simple approach"; Verheijen and Van Beek, Inter-Noise
  2019, "Clarifications and refinements to squeal noise in CNOSSOS", discuss these two classes).
* **Schall 03** (16. BImSchV, Anlage 2 "Berechnung des Beurteilungspegels fuer Schienenwege (Schall
  03)", 2014, section 4.9, Tabelle 11, Zeilen 1-3, "Kurvenfahrgeraeusch bei Eisenbahnstrecken"):
  K_L = 8 dB for a curve radius < 300 m, 3 dB for 300 m to < 500 m, 0 dB from 500 m; applied to the
  rolling-noise sub-sources 1 and 2.  Its tram part (section 5.3.2, Anmerkung 1, Strassenbahnen) has a
  rule of its own: K = 4 dB on the rolling noise in curves r < 200 m without effective mitigation, 0 dB
  from 200 m; applied to a vehicle whose file says ``category = "tram"`` (``schall03_penalty``).

A rule "penalises" a curve when its penalty is > 0; the comparison with the physics is per row of
the line: squeal predicted and penalised (agree), quiet and not penalised (agree), squeal the rule
misses (penalty 0), and a penalty where the physics predicts no squeal.
"""
from __future__ import annotations

RULES = ("cnossos", "schall03")
TITLES = {"cnossos": "CNOSSOS-EU", "schall03": "Schall 03"}
SOURCES = {
    "cnossos": "Directive (EU) 2015/996 Annex II 2.3.2 as amended by Delegated Directive (EU) 2021/1226: "
               "+8 dB for R <= 300 m, +5 dB for 300 < R <= 500 m",
    "schall03": "16. BImSchV Anlage 2 (Schall 03, 2014), 4.9 Tabelle 11: K_L = 8 dB for R < 300 m, 3 dB for "
                "300 m <= R < 500 m, 0 dB from 500 m; a tram (vehicle category), 5.3.2: 4 dB for R < 200 m",
}


def cnossos_penalty(radius_m: float) -> float:
    """CNOSSOS-EU's squeal penalty (dB) of a curve of radius R (m)."""
    return 8.0 if radius_m <= 300.0 else 5.0 if radius_m <= 500.0 else 0.0


def schall03_penalty(radius_m: float, category: str = "railway") -> float:
    """Schall 03's K_L (dB) of a curve of radius R (m): railway lines, or a tram (``category`` of the
    vehicle file: ``schall03_tram``)."""
    if category == "tram":
        return schall03_tram(radius_m)
    return 8.0 if radius_m < 300.0 else 3.0 if radius_m < 500.0 else 0.0


def schall03_tram(radius_m: float) -> float:
    """Schall 03's tram penalty (dB): K = 4 dB on the rolling noise in curves r < 200 m without effective
    mitigation (16. BImSchV Anlage 2, 2014, section 5.3.2, Anmerkung 1), 0 dB otherwise."""
    return 4.0 if radius_m < 200.0 else 0.0


PENALTY = {"cnossos": cnossos_penalty, "schall03": schall03_penalty}

AGREE_SQUEAL, AGREE_QUIET, MISSED, OVER = "agree: squeal, penalised", "agree: quiet", "missed", "penalised, quiet"


def compare(penalty_db: float, squeals: bool) -> str:
    """The rule against the physics for one curve (module notes)."""
    if squeals:
        return AGREE_SQUEAL if penalty_db > 0 else MISSED
    return OVER if penalty_db > 0 else AGREE_QUIET


def rule_columns(radius_m: float, squeals: bool, category: str = "railway") -> dict:
    """{<rule>_dB: penalty, <rule>_vs_physics: the comparison} of both rules (``category``: the vehicle
    file's, railway or tram; Schall 03's rule depends on it, CNOSSOS-EU's does not)."""
    out = {}
    for r in RULES:
        p = schall03_penalty(radius_m, category) if r == "schall03" else PENALTY[r](radius_m)
        out[f"{r}_dB"] = p
        out[f"{r}_vs_physics"] = compare(p, squeals)
    return out
