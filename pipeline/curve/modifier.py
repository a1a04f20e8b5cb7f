"""The friction-modifier what-if of a squealing wheel (issue 33): the same wheel, creepages and
contact with the rail's top treated by a friction modifier, i.e. the friction law of the preset
``MODIFIER`` (``solvers.contact.friction_laws.PRESETS``: "hpf", high positive friction, its source
quoted there: Eadie, Santoro & Kalousek, Wear 2008; Meehan & Liu, JSV 2018; level and slope
assumed) instead of the curve's own.

Its friction curve is built on the wheel's stored contact (``pipeline.caches.friction_curves.
with_curves``, cached by value); the stability screen and one time-loop run (as the friction
what-if's confirmations, ``what_ifs.CaseModels.simulate``) answer it.  Where the modifier still
squeals, its L_pA is estimated from the wheel's own: the same wheel mode radiates a sound power
proportional to the contact force squared (radiate stage: W = |F|^2 x the unit-force power), so
L_pA(modifier) = L_pA + L_F2(modifier) - L_F2, flagged as an estimate, and given only when the
squeal frequency stays within 5 % of the wheel's (the same mode); no radiate/listen stage is run.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from solvers.contact.friction_laws import PRESETS, preset
from solvers.stability.mitigation import growing_wheel_root
from pipeline.caches.friction_curves import with_curves
from pipeline.config.nouns import FrictionLaw
from pipeline.curve.what_ifs import CaseModels

MODIFIER = "hpf"          # the preset that stands for a top-of-rail friction modifier
SAME_MODE = 0.05          # relative frequency window of "the same squealing mode" (as the study's mode match)


def modifier_law(name: str = MODIFIER) -> FrictionLaw:
    """The resolved FrictionLaw of preset ``name``, as a curve file's ``[friction] preset = name``
    resolves (``pipeline.caches.friction_curves.resolve_friction``)."""
    law = preset(name)
    return FrictionLaw.of(law.name, law.params, name)


@dataclass
class ModifierWhatIf:
    preset: str
    source: str
    friction: str = ""                        # the law, for people
    screen_sigma: float = math.nan            # fastest growing wheel-mode pole (1/s), NaN: none grows
    screen_mode: str = ""
    run: dict = field(default_factory=dict)   # the time loop: mu, L_F2, f, squeals
    L_pA: float = math.nan                    # estimate (module notes); NaN when quiet or another mode
    note: str = ""

    @property
    def quiet(self) -> bool:
        return bool(self.run) and not self.run["squeals"]

    def text(self) -> str:
        """For verdict.md: 'with a friction modifier: quiet' or its level."""
        head = f"with a friction modifier (preset {self.preset}): "
        if self.note and not self.run:
            return head + self.note
        if self.quiet:
            scr = ("the screen finds no growing wheel mode" if not math.isfinite(self.screen_sigma) else
                   f"the screen's {self.screen_mode} grows at {self.screen_sigma:+.1f}/s")
            return head + f"**quiet** (L_F2 = {self.run['L_F2']:.1f} dB re 1 N in the time loop; {scr})"
        lvl = (f"L_pA about **{self.L_pA:.1f} dB(A)** (estimated from the wheel's level and the change of L_F2)"
               if math.isfinite(self.L_pA) else "L_pA not estimated: " + self.note)
        return head + f"still squeals at {self.run['f']:.0f} Hz, L_F2 = {self.run['L_F2']:.1f} dB re 1 N, {lvl}"


def modifier_what_if(models: CaseModels, row: dict, name: str = MODIFIER) -> ModifierWhatIf:
    """The wheel of ``models`` (a CaseModels of a stored case) with the friction of preset ``name``
    (module notes); ``row``: the wheel's verdict row (its L_F2, f_squeal, L_pA)."""
    law = modifier_law(name)
    out = ModifierWhatIf(name, PRESETS[name]["source"], law.text)
    ctx = models.ctx
    if ctx.friction is not None and ctx.friction.config() == law.config():
        out.note = "the curve's friction is already this modifier"
        return out
    con = with_curves(ctx.case, ctx.contact, [law])
    mod = CaseModels.of_context(dataclasses.replace(ctx, contact=con, friction=law, mu=law.mu))
    r = growing_wheel_root(mod.roots(law.mu))
    if r is not None:
        out.screen_sigma, out.screen_mode = float(r.sigma), ctx.label(r.mode)
    out.run = mod.simulate(law.mu)
    if out.run["squeals"]:
        f0 = float(row.get("f_squeal", math.nan))
        if math.isfinite(f0) and abs(out.run["f"] - f0) <= SAME_MODE * f0 and math.isfinite(row.get("L_pA", math.nan)):
            out.L_pA = float(row["L_pA"]) + out.run["L_F2"] - float(row["L_F2"])
        else:
            out.note = f"it squeals at {out.run['f']:.0f} Hz, not the wheel's {f0:.0f} Hz (another mode)"
    return out
