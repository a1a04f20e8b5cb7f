"""Published field observations of curve squeal, each with its source, and the tool's verdict for
the closest configuration it can model, side by side (docs/validation/92_field.md).

Only what the sources state is entered; what a source does not state (in the text that could be
read: abstracts and excerpts, cited by address) is ``None`` and shows as "n/s".  Nothing is fitted
to these observations.  ``model`` names the closest configuration the tool can model: the
vehicle file, radius (m) and speed (km/h) -- a verdict of the curve stage at that point.
"""
from __future__ import annotations

import math

# one dict per observation: source (author, year, journal/report, address), vehicle, radius_m, speed_kmh,
# f_hz (text), level (text, with distance and metric), note, model = (vehicle, radius_m, speed_kmh) or None
OBSERVATIONS = [
    {"key": "stockholm",
     "source": "'Monitoring of rail corrugation growth due to irregular wear on a railway metro curve', journal "
               "article, 2009, Chalmers (research.chalmers.se/publication/111664)",
     "vehicle": "Stockholm metro (C20 wheels: Zenzerovic 2014, sec. 4.1.2)", "radius_m": 120.0, "speed_kmh": 30.0,
     "f_hz": None, "level": None,
     "note": "in dry weather the pass-by discomfort is linked to the occurrence of wheel squeal; train speeds about "
             "30 km/h", "model": ("metro", 120.0, 30.0)},
    {"key": "rudd",
     "source": "Rudd, 1976, 'Wheel/rail noise - Part II: Wheel squeal', J. Sound Vib. 46(3) 381-394 (as cited by "
               "Zenzerovic 2014, ch. 2)",
     "vehicle": "rail transit cars", "radius_m": None, "speed_kmh": None, "f_hz": None,
     "level": "up to 130 dB at 0.9 m from the wheel (sound pressure level)",
     "note": "squeal expected where curve radius / bogie wheelbase < 100", "model": ("metro", 150.0, 30.0)},
    {"key": "tram-clda",
     "source": "Shock and Vibration 2014, article 473720, constrained layer damper for a tram "
               "(hindawi.com/journals/sv/2014/473720)",
     "vehicle": "tram with resilient wheels", "radius_m": None, "speed_kmh": None, "f_hz": "780-800",
     "level": None, "note": "squeal in the small-radius curves of the line, reduced by tuned dampers on the wheels",
     "model": ("tram", 25.0, 15.0)},
    {"key": "wiki-tram",
     "source": "German Wikipedia, 'Kurvenquietschen' (secondary source; its literature: Hubner 1973, dissertation "
               "TU Berlin; Lipinsky), as stored at de.zxc.wiki/wiki/Kurvenquietschen",
     "vehicle": "tram", "radius_m": None, "speed_kmh": 14.0, "f_hz": "1572-1578",
     "level": "130 dB(A) at the inner wheel rim, axial direction, 20 km/h (85 dB(A) at the outer wheel rim)",
     "note": "about 1578 Hz at 14 km/h and 1572 Hz at 28 km/h; main range 1500-6000 Hz",
     "model": ("tram", 25.0, 15.0)},
    {"key": "meehan",
     "source": "Meehan & Liu, 2018, 'Modelling and mitigation of wheel squeal noise amplitude', J. Sound Vib. 413 "
               "144-158",
     "vehicle": "in-service trains (field case study)", "radius_m": 300.0, "speed_kmh": None, "f_hz": None,
     "level": None, "note": "many field recordings of squeal on a 300 m curve; the level rises with the angle of "
                            "attack", "model": ("metro", 300.0, 60.0)},
    {"key": "jrc2012",
     "source": "Joint Rail Conference 2012 (ASME), proceedings abstract "
               "(asmedigitalcollection.asme.org/JRC/proceedings-abstract/JRC2012/44656/161)",
     "vehicle": "n/s", "radius_m": 300.0, "speed_kmh": None, "f_hz": None, "level": None,
     "note": "a threshold lateral creepage of 0.0045 is suggested; curves of radius above 300 m should not squeal",
     "model": ("metro", 500.0, 70.0)},
    {"key": "fourie",
     "source": "'Experimental characterisation of railway wheel squeal occurring in large-radius curves', 2016, "
               "TRID record 1416976 (trid.trb.org/view/1416976)",
     "vehicle": "heavy-haul ore wagons (trailing inner wheels)", "radius_m": 1000.0, "speed_kmh": None,
     "f_hz": None, "level": None,
     "note": "squealing wheels under predominantly longitudinal creepage (> 1 %), little or no lateral creepage",
     "model": ("metro", 1000.0, 70.0)},
    {"key": "thompson",
     "source": "Thompson, 2009, Railway Noise and Vibration, Elsevier, ch. 9 (as cited by Zenzerovic 2014, ch. 2)",
     "vehicle": "guideline (all vehicles)", "radius_m": 200.0, "speed_kmh": None, "f_hz": "250-5000 (main tones)",
     "level": None, "note": "R <= 200 m: squeal common; 200-500 m: sporadic; >= 500 m: mostly none",
     "model": ("metro", 200.0, 40.0)},
    {"key": "verheijen",
     "source": "Verheijen & van Beek, 2019, 'Clarifications and refinements to squeal noise in CNOSSOS', "
               "Inter-Noise 2019, 259(8) 1990-1997",
     "vehicle": "trams", "radius_m": 200.0, "speed_kmh": None, "f_hz": None, "level": None,
     "note": "trams do not tend to squeal in curves with radii over 200 m", "model": ("tram", 200.0, 40.0)},
    {"key": "staiano",
     "source": "Staiano & Sastry, 1990, 'Control of wheel squeal noise in rail transit cars', Transportation Research "
               "Record 1255, 23-35",
     "vehicle": "Washington Metro transit cars (yard curves)", "radius_m": None, "speed_kmh": None, "f_hz": None,
     "level": "23 dB(A) lower with a rail-head facing, squeal eliminated (first week)",
     "note": "small-radius yard curves; water on the rails stopped the squeal", "model": ("metro", 75.0, 15.0)},
]


def fmt(x, spec=".0f", unit=""):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "n/s"
    return f"{x:{spec}}{unit}" if not isinstance(x, str) else x


def table_markdown(verdicts: dict) -> str:
    """The side-by-side table; ``verdicts``: model tuple -> {'squeals', 'wheel', 'f', 'mode', 'L_pA', 'screen'}."""
    rows = ["| source | vehicle | R (m) | V (km/h) | measured f (Hz) | measured level | tool: closest configuration | "
            "tool: squeals (wheel) | tool f (Hz), mode | tool L_pA at 7.5 m | difference |",
            "|" + "---|" * 11]
    for o in OBSERVATIONS:
        v = verdicts.get(o["model"]) if o["model"] else None
        conf = f"{o['model'][0]}, R = {o['model'][1]:g} m, {o['model'][2]:g} km/h" if o["model"] else "-"
        if v is None:
            tool = ("not run", "-", "-")
        else:
            tool = (f"yes ({v['wheel']})" if v["squeals"] else ("no (screen unstable, quiet time loop)"
                                                                 if v.get("screen") else "no"),
                    f"{v['f']:.0f}, {v['mode']}" if v["squeals"] else "-",
                    f"{v['L_pA']:.1f} dB(A)" if v["squeals"] and math.isfinite(v["L_pA"]) else "-")
        rows.append(f"| {o['source']} | {o['vehicle']} | {fmt(o['radius_m'])} | {fmt(o['speed_kmh'])} | "
                    f"{fmt(o['f_hz'])} | {fmt(o['level'])} | {conf} | {tool[0]} | {tool[1]} | {tool[2]} | "
                    f"{difference(o, v)} |")
    return "\n".join(rows)


def difference(o: dict, v: dict | None) -> str:
    """The difference in words: occurrence, frequency (when both are given), and what cannot be compared."""
    if v is None:
        return "not compared (the configuration was not run)"
    parts = []
    if o["f_hz"] and v["squeals"]:
        lo, hi = (float(x) for x in (o["f_hz"].split()[0].split("-") * 2)[:2])
        f = v["f"]
        parts.append("f inside the measured range" if lo <= f <= hi else
                     f"f {f - (lo if f < lo else hi):+.0f} Hz outside the measured range")
    if o["level"] and v["squeals"] and "0.9 m" in o["level"]:
        parts.append("levels at other distances: not compared")
    occ = "squeal" in o["note"] and ("should not" in o["note"] or "do not" in o["note"] or "mostly none" in o["note"])
    if occ:
        parts.append("the source expects no squeal here; the tool " + ("agrees" if not v["squeals"] else "disagrees"))
    elif not parts:
        parts.append("the tool " + ("squeals" if v["squeals"] else "does not squeal") +
                     "; the source gives no f or level to compare")
    return "; ".join(parts)
