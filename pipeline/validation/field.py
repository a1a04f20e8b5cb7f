"""Published field observations of curve squeal, each with its source, and the tool's verdict for
the closest configuration it can model, side by side (docs/validation/92_field.md).

Only what the sources state is entered; what a source does not state (in the text that could be
read: abstracts and excerpts, cited by address) is ``None`` and shows as "n/s".  Nothing is fitted
to these observations.  ``model`` names the closest configuration the tool can model: the
base curve (its vehicle, rail and friction), radius (m) and speed (km/h; None: the design rule's of
``pipeline.study.radius``, whose cant rule holds for all) -- a verdict of the curve stage there.
The project ships a metro vehicle on the C20 wheel and a freight bogie (Y25, 920 mm wheel, BV50 new): the
heavy-haul observation is compared with the freight bogie, every other one with the metro vehicle
(trams and other cars differ in wheel, bogie and load: stated).  Each row says which of radius, speed,
squeal frequency and level (with distance and metric) its source states ('stated': R V f L, 'l' for a relative
level); a measured level is set beside the tool's L_pA at 7.5 m only when the source gives an A-weighted level
(or range) at 7.5 m from the track (``L_7p5``), with no conversion; other distances and metrics are not converted.

    .venv/bin/python -m pipeline.validation.field     # runs (or reuses) the verdicts, writes 92_field.md
"""
from __future__ import annotations

import math
import tomllib
import argparse
import logging
import sys
from pipeline.store.paths import ROOT
from pathlib import Path
from pipeline.store import paths
from pipeline.store.artifacts import ArtifactError
from pipeline.store.atomic import save_text
from pipeline.config.loader import ConfigError
from pipeline.study.radius import curve_verdict

# one dict per observation: source (author, year, journal/report, address; a value quoted from a secondary source says
# so), vehicle, radius_m and speed_kmh (number, or text for a range or class), f_hz (text), level (text: as the source
# gives it, with its distance and metric; level_partial: True for a relative level), L_7p5 (an A-weighted level, or a
# (low, high) range, the source states at 7.5 m from the track, dB(A), else None: the only level compared), squeal
# (the source reports squeal: True; expects none: False), model = (base curve, radius_m, speed_kmh or None) or None
OBSERVATIONS = [
    {"key": "melsele", "squeal": True,
     "source": "APT (rail fastening supplier), reference 'Tram return loop in Melsele, Belgium' "
               "(aptrail.com/references/be-melsele.asp), vendor's account of its own product",
     "vehicle": "Siemens tram with resilient wheels, on the damped APT-ST fastening", "radius_m": 25.0,
     "speed_kmh": "10-15", "f_hz": None,
     "level": "80.5 dB(A), 'measured maximum squeal noise' at 7.5 m from the track, 10-15 km/h (rare passages; most "
              "did not squeal); 102.7 dB(A) at 7.5 m 'calculated' by the source for a classical track (not measured)",
     "L_7p5": 80.5, "note": "return loop, R = 25 m, track embedded in pavement on a concrete slab",
     "model": ("r150", 25.0, 12.5)},
    {"key": "stuva", "squeal": True,
     "source": "STUVA for the Umweltbundesamt, 'Kurvenquietschen im Nahverkehr - Schall 03' (project record, "
               "md.tb.umwelt.info; report: F. Krueger, STUVA 1994, FE-Nr. 70413/93, as listed by de.wikipedia "
               "'Kurvenquietschen')",
     "vehicle": "urban rail (Nahverkehr): 29 curves in 11 cities", "radius_m": "25-50", "speed_kmh": None,
     "f_hz": None,
     "level": "LAmax at 7.5 m (LAm,N at 25 m) measured; mean maximum increase by squeal over rolling noise 8 dB(A) for "
              "R = 25-50 m (4.6 for 51-100 m, 1.6 for 101-200 m)",
     "L_7p5": None, "level_partial": True, "note": "an increase over rolling noise, not the squeal level itself",
     "model": ("r150", 50.0, None)},
    {"key": "tema", "squeal": True,
     "source": "'Kurvengeräusche - Phänomenologische Parameteruntersuchung', abstract in the TEMA database, record "
               "TEMA20090305536 (fid-move.de/en/search/id/tema:TEMA20090305536); authors, venue and year are not in "
               "the text that could be read",
     "vehicle": "urban rail (Schienennahverkehr), vehicle n/s", "radius_m": None, "speed_kmh": None,
     "f_hz": "1600 (about: the first dominant frequency of the example spectrum)",
     "level": "maximum levels 'um 100 bis 105 dB(A)' at the measuring point 7.5 m from the track centre when squeal "
              "occurs", "L_7p5": (100.0, 105.0),
     "note": "the 1.6 kHz matched the first radial eigenfrequency of the vehicle's wheel (admittance measurement); "
             "squeal is sporadic and loudest on the inner side of the curve", "model": ("r150", 50.0, None)},
    {"key": "kurvengeraeusche", "squeal": True,
     "source": "C. Czolbe, F. Krüger, J. Oertli, T. Thron et al. (17 authors), 'Kurvengeräusche: Messung, Bewertung und "
               "Minderungsmaßnahmen' (book on a BMWi-funded research project; its description at "
               "buch-findr.de/buecher/kurvengerausche; publisher and year not in the text read)",
     "vehicle": "rail vehicles (guideline)", "radius_m": "< 500", "speed_kmh": None,
     "f_hz": "1000-2000 (the squeal's tonal components, 'insbesondere')", "level": None, "L_7p5": None,
     "note": "curve noise (rumbling, hissing, squeal) in curves of radius below about 500 m; squeal has high levels",
     "model": ("r150", 50.0, None)},
    {"key": "wiki-tram", "squeal": True,
     "source": "German Wikipedia, 'Kurvenquietschen' (secondary source; its literature: Hubner 1973, dissertation "
               "TU Berlin; Lipinsky 1984), as stored at de.zxc.wiki/wiki/Kurvenquietschen",
     "vehicle": "tram", "radius_m": None, "speed_kmh": "14-28", "f_hz": "1572-1578",
     "level": "130 dB(A) at the inner wheel rim, axial direction, 20 km/h (85 dB(A) at the outer wheel rim)",
     "L_7p5": None, "note": "about 1578 Hz at 14 km/h and 1572 Hz at 28 km/h; main range 1500-6000 Hz",
     "model": ("r150", 50.0, 15.0)},
    {"key": "tram-clda", "squeal": True,
     "source": "Shock and Vibration 2014, article 473720, constrained layer damper for a tram (abstract, "
               "hindawi.com/journals/sv/2014/473720)",
     "vehicle": "tram with resilient wheels", "radius_m": None, "speed_kmh": None, "f_hz": "780-800",
     "level": None, "L_7p5": None,
     "note": "squeal in the small-radius curves of the line, reduced by tuned dampers on the wheels",
     "model": ("r150", 50.0, None)},
    {"key": "rudd", "squeal": True,
     "source": "Rudd, 1976, 'Wheel/rail noise - Part II: Wheel squeal', J. Sound Vib. 46(3) 381-394 (as cited by "
               "Zenzerovic 2014, ch. 2)",
     "vehicle": "rail transit cars", "radius_m": None, "speed_kmh": None, "f_hz": None,
     "level": "up to 130 dB at 0.9 m from the wheel (sound pressure level, unweighted)", "L_7p5": None,
     "note": "squeal expected where curve radius / bogie wheelbase < 100", "model": ("r150", 150.0, 50.0)},
    {"key": "staiano", "squeal": True,
     "source": "Staiano & Sastry, 1990, 'Control of wheel squeal noise in rail transit cars', Transportation Research "
               "Record 1255, 23-35 (abstract, trid.trb.org/View/312963)",
     "vehicle": "Washington Metro transit cars (yard curves)", "radius_m": None, "speed_kmh": None, "f_hz": None,
     "level": "23 dB(A) lower with a rail-head facing, squeal eliminated (first week); distance n/s", "L_7p5": None,
     "level_partial": True,
     "note": "small-radius yard curves; water on the rails stopped the squeal", "model": ("r150", 75.0, None)},
    {"key": "stockholm", "squeal": True,
     "source": "'Monitoring of rail corrugation growth due to irregular wear on a railway metro curve', journal "
               "article, 2009, Chalmers (research.chalmers.se/publication/111664)",
     "vehicle": "Stockholm metro (C20 wheels: Zenzerovic 2014, sec. 4.1.2)", "radius_m": 120.0, "speed_kmh": 30.0,
     "f_hz": None, "level": None, "L_7p5": None,
     "note": "in dry weather the pass-by discomfort is linked to the occurrence of wheel squeal; train speeds about "
             "30 km/h", "model": ("r150", 120.0, 30.0)},
    {"key": "thompson", "squeal": True,
     "source": "Thompson, 2009, Railway Noise and Vibration, Elsevier, ch. 9 (as cited by Zenzerovic 2014, ch. 2)",
     "vehicle": "guideline (all vehicles)", "radius_m": 200.0, "speed_kmh": None, "f_hz": "250-5000 (main tones)",
     "level": None, "L_7p5": None, "note": "R <= 200 m: squeal common; 200-500 m: sporadic; >= 500 m: mostly none",
     "model": ("r150", 200.0, None)},
    {"key": "meehan", "squeal": True,
     "source": "Meehan & Liu, 2018, 'Modelling and mitigation of wheel squeal noise amplitude', J. Sound Vib. 413 "
               "144-158 (abstract)",
     "vehicle": "in-service trains (field case study)", "radius_m": 300.0, "speed_kmh": None, "f_hz": None,
     "level": None, "L_7p5": None,
     "note": "many field recordings of squeal on a 300 m curve; the level rises with the angle of attack",
     "model": ("r150", 300.0, None)},
    {"key": "ostermann", "squeal": True,
     "source": "M. Ostermann, 'Noise prediction of trains in curves', thesis (abstract, "
               "scholar.archive.org/work/o4vp7izn7jhfdmur233r3j2rbq)",
     "vehicle": "Austrian heavy-rail traffic (29097 pass-bys in five curve sections)", "radius_m": "226-440",
     "speed_kmh": "60-90 (speed limits)", "f_hz": None, "level": None, "L_7p5": None,
     "note": "three types of curve squeal detected in 64 ms third-octave spectra; their occurrence, peak levels and "
             "occurrence time analysed (the values are not in the abstract)", "model": ("r150", 300.0, 70.0)},
    {"key": "verheijen", "squeal": False,
     "source": "Verheijen & van Beek, 2019, 'Clarifications and refinements to squeal noise in CNOSSOS', "
               "Inter-Noise 2019, 259(8) 1990-1997 (abstract)",
     "vehicle": "trams", "radius_m": 200.0, "speed_kmh": None, "f_hz": None, "level": None, "L_7p5": None,
     "note": "trams do not tend to squeal in curves with radii over 200 m", "model": ("r150", 300.0, None)},
    {"key": "jrc2012", "squeal": False,
     "source": "Joint Rail Conference 2012 (ASME), proceedings abstract "
               "(asmedigitalcollection.asme.org/JRC/proceedings-abstract/JRC2012/44656/161)",
     "vehicle": "n/s", "radius_m": 300.0, "speed_kmh": None, "f_hz": None, "level": None, "L_7p5": None,
     "note": "a threshold lateral creepage of 0.0045 is suggested; curves of radius above 300 m should not squeal",
     "model": ("r150", 500.0, None)},
    {"key": "fourie", "squeal": True,
     "source": "'Experimental characterisation of railway wheel squeal occurring in large-radius curves', 2016, "
               "TRID record 1416976 (trid.trb.org/view/1416976)",
     "vehicle": "heavy-haul ore wagons (trailing inner wheels)", "radius_m": 1000.0, "speed_kmh": None,
     "f_hz": None, "level": None, "L_7p5": None,
     "note": "squealing wheels under predominantly longitudinal creepage (> 1 %), little or no lateral creepage",
     "model": ("y25_r300", 1000.0, None)},
]

# what the issue asks each observation to state
STATED = (("radius_m", "R"), ("speed_kmh", "V"), ("f_hz", "f"), ("level", "L"))


def stated(o: dict) -> str:
    """Which of radius, speed, squeal frequency and level (with distance and metric) the source states: 'R V f L',
    a dash for each it does not, 'l' for a level that is relative (an increase, a reduction) or lacks its distance."""
    tags = [tag if o.get(k) is not None else "-" for k, tag in STATED]
    if tags[3] == "L" and o.get("level_partial"):
        tags[3] = "l"
    return " ".join(tags)


def complete(o: dict) -> bool:
    """The observation states all four (its level absolute, at a stated distance, in a stated metric)."""
    return stated(o).split() == [tag for _, tag in STATED]


def level_difference(o: dict, v: dict | None) -> str:
    """The tool's L_pA at 7.5 m minus the source's A-weighted level at 7.5 m (a number, or a (low, high) range: the
    distance to the nearer bound), where both exist; levels at other distances or in other metrics are not
    converted (said so)."""
    if not o.get("level"):
        return "-"
    if o.get("L_7p5") is None:
        return "not compared (no A-weighted level at 7.5 m from the track)"
    if not v or "error" in v or not v["squeals"] or not math.isfinite(v["L_pA"]):
        return "not compared (the tool does not squeal there)"
    lo, hi = (o["L_7p5"], o["L_7p5"]) if isinstance(o["L_7p5"], (int, float)) else o["L_7p5"]
    if lo == hi:
        return f"{v['L_pA'] - lo:+.1f} dB (tool - measured)"
    if lo <= v["L_pA"] <= hi:
        return f"inside the measured range {lo:g}-{hi:g} dB(A)"
    return f"{v['L_pA'] - (lo if v['L_pA'] < lo else hi):+.1f} dB from the measured range {lo:g}-{hi:g} dB(A)"


def level_compared(o: dict, v: dict | None) -> bool:
    """A measured level at 7.5 m was set beside the tool's."""
    return o.get("L_7p5") is not None and bool(v) and "error" not in v and bool(v["squeals"]) \
        and math.isfinite(v["L_pA"])


def vehicle_of(base: str) -> str:
    """The vehicle named by the shipped curve ``base``."""
    return str(tomllib.loads((ROOT / "pipeline" / "curves" / f"{base}.toml").read_text())["vehicle"])


def fmt(x, spec=".0f", unit=""):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "n/s"
    return f"{x:{spec}}{unit}" if not isinstance(x, str) else x


def table_markdown(verdicts: dict) -> str:
    """The side-by-side table; ``verdicts``: model tuple -> {'squeals', 'wheel', 'f', 'mode', 'L_pA', 'screen'}."""
    rows = ["| source | vehicle | R (m) | V (km/h) | measured f (Hz) | measured level (distance, metric) | stated | "
            "tool: closest configuration | tool: squeals (wheel) | tool f (Hz), mode | tool L_pA at 7.5 m | "
            "level: tool - measured | difference |",
            "|" + "---|" * 13]
    for o in OBSERVATIONS:
        v = verdicts.get(o["model"]) if o["model"] else None
        speed = f"{v['V']:g}" if v and "V" in v else f"{o['model'][2]:g}" if o["model"] and o["model"][2] else "design"
        conf = (f"{vehicle_of(o['model'][0])} ({o['model'][0]}), R = {o['model'][1]:g} m, {speed} km/h"
                if o["model"] else "-")
        if v is None:
            tool = ("not run", "-", "-")
        elif "error" in v:
            tool = (f"not computed: {v['error']}", "-", "-")
        else:
            tool = (f"yes ({v['wheel']})" if v["squeals"] else ("no (screen unstable, quiet time loop)"
                                                                 if v.get("screen") else "no"),
                    f"{v['f']:.0f}, {v['mode']}" if v["squeals"] else "-",
                    f"{v['L_pA']:.1f} dB(A)" if v["squeals"] and math.isfinite(v["L_pA"]) else "-")
        rows.append(f"| {o['source']} | {o['vehicle']} | {fmt(o['radius_m'])} | {fmt(o['speed_kmh'])} | "
                    f"{fmt(o['f_hz'])} | {fmt(o['level'])} | {stated(o)} | {conf} | {tool[0]} | {tool[1]} | "
                    f"{tool[2]} | {level_difference(o, v)} | {difference(o, v)} |")
    return "\n".join(rows)


def difference(o: dict, v: dict | None) -> str:
    """The difference in words: occurrence (the source's squeal, or its expectation of none, against the
    tool's verdict), then the frequency when both give one."""
    if v is None or "error" in v:
        return "not compared (no verdict for the configuration)"
    if o["squeal"] and v["squeals"]:
        parts = ["both squeal"]
    elif o["squeal"]:
        parts = ["the source reports squeal, the tool does not"]
    elif v["squeals"]:
        parts = ["the tool squeals where the source expects none"]
    else:
        parts = ["agree: no squeal"]
    if o["f_hz"] and v["squeals"]:
        lo, hi = (float(x) for x in (o["f_hz"].split()[0].split("-") * 2)[:2])
        f = v["f"]
        parts.append("f inside the measured range" if lo <= f <= hi else
                     f"f {f - (lo if f < lo else hi):+.0f} Hz from the measured range (another wheel)")
    return "; ".join(parts)


def tally(verdicts: dict) -> str:
    """In how many observations the tool's occurrence agrees with the source's, and where not."""
    n = agree = 0
    missed, extra = set(), set()
    for o in OBSERVATIONS:
        v = verdicts.get(o["model"]) if o["model"] else None
        if v is None or "error" in v:
            continue
        n += 1
        agree += bool(v["squeals"]) == bool(o["squeal"])
        if o["squeal"] and not v["squeals"]:
            missed.add(o["model"][1])
        if v["squeals"] and not o["squeal"]:
            extra.add(o["model"][1])
    full = sum(complete(o) for o in OBSERVATIONS)
    text = (f"Completeness: {full} of {len(OBSERVATIONS)} observations state all of radius, speed, squeal frequency "
            "and an absolute level with its distance and metric (column 'stated': R V f L; a dash for what the text "
            "that could be read does not state, 'l' for a relative level or one without its distance).  The issue asks "
            f"for at least five such observations: {'met' if full >= 5 else 'not met'} (the sources searched and what "
            "each gave: 'Sources searched' below).  Occurrence: the tool's verdict agrees with the source in "
            f"{agree} of {n} observations.")
    if missed:
        loud = sorted({m[1] for m, v in verdicts.items() if v and "error" not in v and v["squeals"]})
        text += (f"  Where the source reports squeal, the tool's vehicle is quiet at mu = 0.35 at R = "
                 f"{', '.join(f'{r:g}' for r in sorted(missed))} m; it squeals here only at R = "
                 f"{', '.join(f'{r:g}' for r in loud) or 'none'} m (the radius study: docs/validation/91_verdict.md).  "
                 "The inner leading wheel's creepages (gamma_x, gamma_y of a1i, from each curve's verdict.csv) "
                 f"show why: {creep_text(verdicts)}; where it is quiet, its longitudinal creepage is large beside "
                 "the lateral one or the lateral creepage is small.  A source's other "
                 "vehicle, wheel, profiles, track or friction are not modelled.")
    if extra:
        text += f"  The tool squeals where the source expects none at R = {', '.join(f'{r:g}' for r in sorted(extra))} m."
    compared = [o["key"] for o in OBSERVATIONS if level_compared(o, verdicts.get(o["model"]))]
    at_7p5 = [o["key"] for o in OBSERVATIONS if o.get("L_7p5") is not None]
    text += (f"  Level: {len(compared)} of the {len(at_7p5)} A-weighted level(s) at 7.5 m ({', '.join(at_7p5)}) "
             "compared with the tool's" + ("" if len(compared) == len(at_7p5) else
                                           "; the others are where the tool's vehicle does not squeal") + ".")
    return text + ("  Frequency: where both squeal the tool's frequency is the C20 wheel's mode, not the source "
                   "vehicle's wheel.")


def creep_text(verdicts: dict) -> str:
    """The a1i creepages of the metro's configurations, by radius: 'R = 25 m: +0.023 / -0.059 (quiet)'."""
    seen = {}
    for m, v in sorted(verdicts.items(), key=lambda kv: kv[0][1]):
        if m[0] == "r150" and v and v.get("creep_a1i") and m[1] not in seen:
            gx, gy = v["creep_a1i"]
            seen[m[1]] = f"R = {m[1]:g} m: {gx:+.4f} / {gy:+.4f} ({'squeals' if v['squeals'] else 'quiet'})"
    return "; ".join(seen.values())


def verdict_of(run: dict) -> dict:
    """The loudest wheel's verdict of a curve run (``radius.curve_verdict``), or the quiet summary."""
    rows = run["rows"]
    sq = [r for r in rows if r["squeals"]]
    loud = max(sq, key=lambda r: r["L_pA"] if math.isfinite(r["L_pA"]) else -1e9) if sq else None
    return {"V": run["V"], "squeals": loud is not None, "wheel": loud["wheel"] if loud else "",
            "f": loud["f_squeal"] if loud else math.nan, "mode": loud["mode"] if loud else "",
            "L_pA": loud["L_pA"] if loud else math.nan,
            "screen": any(math.isfinite(r["screen_sigma"]) for r in rows),
            "creep_a1i": next(((r["gamma_x"], r["gamma_y"]) for r in rows if r["wheel"] == "a1i"), None)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline.validation.field", description=__doc__.split("\n\n")[0])
    ap.add_argument("--rerun", action="store_true", help="run every curve again (default: reuse newer verdicts)")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    folder = paths.build() / "studies" / "radius" / "curves"
    verdicts = {}
    for o in OBSERVATIONS:
        m = o["model"]
        if m and m not in verdicts:
            try:
                verdicts[m] = verdict_of(curve_verdict(m[0], folder, m[1], m[2], reuse=not args.rerun))
            except (ConfigError, ArtifactError) as e:   # no steady curving state, an artifact not built: stated
                verdicts[m] = {"error": str(e).split(": ", 1)[-1]}
    md = ("## Against the field: published observations of curve squeal\n\n"
          "Published field observations (vehicle, curve radius, speed, measured squeal frequency and level with "
          "its distance and metric, as far as the source states them; n/s: not stated in the text that could be "
          "read) beside the curve stage's verdict (`make curve`) for the closest configuration the tool can model: "
          "the C20 metro vehicle (`geometry/vehicles/c20_metro.toml`) on the BV50 rail with mu = 0.35 (the heavy-haul "
          "row: the Y25 freight bogie of `pipeline/curves/y25_r300.toml` on the new BV50 head), at the "
          "observation's radius and speed (the design rule's speed and cant of `pipeline/study/radius.py` where "
          "the source gives none).  Nothing is fitted to these observations; the differences are stated.\n\n"
          + table_markdown(verdicts) + "\n\n" + tally(verdicts) + "\n\n" + NOTES +
          "\nWritten by `.venv/bin/python -m pipeline.validation.field`.\n")
    save_text(md, Path(paths.ROOT) / "docs" / "validation" / "92_field.md")
    print(md)
    return 0


NOTES = """What the comparison can and cannot say:

* Sources: only what the stored text of each source (abstracts, project and database records, a vendor's reference
  page, an encyclopedia entry, a book's description) states is entered; a number from memory or from a secondary
  source's paraphrase is not.
* Occurrence: the sources that state where squeal is (not) expected (radius rules) are compared with the
  tool's verdict at those radii; one metro vehicle and one friction coefficient cannot stand for the spread of
  vehicles, wheel profiles and rail conditions behind those rules.  Where an urban-rail or tram source states no
  radius (or only a class, < 500 m), the tool's vehicle is run at 50 m, in the class 25-50 m where the STUVA survey
  of urban-rail curves found the largest increase by squeal (yard curves: 75 m; Rudd's transit cars: the shipped
  150 m case); the tool's vehicle squeals only at 50 and 75 m.
* Frequency: the tool's squeal frequency is a C20 wheel mode; a tram's resilient wheel or another wheel
  squeals at its own modes, so a frequency difference there reflects the wheel, not the model.
* Level: the tool's L_pA is that of the squealing wheel alone at 7.5 m and 1.2 m (ISO 3095 position; rigid
  ground, image source: `pipeline/stages/listen.py`).  It is compared only with an A-weighted level the source
  states at 7.5 m from the track (Melsele; the TEMA record's 100-105 dB(A) maximum levels), with no conversion:
  no source read gives an absolute squeal level in dB(A) at another distance from the track (STUVA's LAm,N at 25 m
  is a mean level over the pass-by, and only its increase is stated), so no distance law is applied.  Levels at
  the wheel rim (130 dB(A)) or at 0.9 m from the wheel (130 dB, unweighted), increases over rolling noise and
  reductions by a measure are near-field, of another metric or relative, and are not converted.  A measured
  maximum level is that of the whole train passing (every wheel, rolling noise); the tool's is one wheel's.  At
  Melsele the measured 80.5 dB(A) is a tram on resilient wheels over a highly damped rail fastening, squealing in
  rare passages; the tool's vehicle has solid C20 wheels on an ordinary track, so a level difference there would
  reflect wheel and track as much as the model (the source's own figure for a classical track, 102.7 dB(A), is a
  calculation, not a measurement, and is not compared).
* Mechanism: squeal from longitudinal creepage on large radii (ore wagons at 1000 m) is outside what the
  lateral-creepage screen looks for.

Sources searched (for observations stating all four quantities), and what the readable text gave:

* Field papers and reports that tabulate radius, speed, frequency and level (TCRP Report 23, Nelson 1997; the UIC
  'Combating curve squeal' Phase II report, Oertli 2005; Meehan & Liu 2018, J. Sound Vib. 413; Eadie & Santoro,
  'Top of rail friction control for curve noise mitigation and corrugation rate reduction'; Panulinova et al.
  2016, Noise & Health 18(85) 329-337, Kosice trams; the Porto light-rail measurements, POMA 8 040001): stored
  only as their first page (front matter, contents, abstract).  What those pages state is entered above where
  it is an observation (Meehan & Liu: 300 m); Eadie & Santoro state reductions of 6.3 to 22.8 dB(A) (mean 12.0)
  by friction modifiers at European transit sites, with no radius, speed or frequency per site.
* German and Austrian records (UBA/STUVA project records, the TEMA database, the BMVI research information system
  FIS 'Kurvengeräusche im Schienenverkehr', the Austrian VIF project report sections, the ÖBB BEGEL project page):
  the STUVA and TEMA rows above; the FIS text cites Potsdam tram measurements at 7.5 m and 30 km/h ([Hech02] there)
  but its readable part ends before the level; the VIF report names tonal squeal components in the 0.8 and 1 kHz
  third-octave bands of Austrian suburban trains, with no radius or level in that section.
* Newspaper and operator pages (Bern, Berlin, Freiburg, Frankfurt, Munich, Tours): levels without distance or
  metric (e.g. 102-105 'Dezibel' for a Bern tram in the Zytglogge curve), not entered.
* Public code (find_string over GitHub sources for 'curve squeal', 'Kurvenquietschen', 'Kurvengeräusch', 'squeal
  frequency'): simulators, games and one squeal-detection package (Biel recordings, no published curve data);
  no paper text or data set with the four quantities.
"""


if __name__ == "__main__":
    import sys

    sys.exit(main())
