"""A line study as one self-contained page, build/studies/<line>/verdict.html (issue 33): line.md rendered as
the case report is (``pipeline.stages.report_html.render``: figures and WAVs embedded as data URIs),
its verdict (how many curve conditions squeal, the loudest) first as the headline block, the level
against radius and the chainage figures, the loudest curve's sound at the receiver and its pass-by,
a link to every squealing curve's verdict.csv, then line.md's tables (the rules, every curve)."""
from __future__ import annotations

import math
import os
import re
from pathlib import Path

from pipeline.curve.verdict_html import sounds
from pipeline.stages.report_html import render
from pipeline.store import paths
from pipeline.store.atomic import save_text


def loudest_sound_row(rows: list[dict]) -> dict | None:
    """{'wheel', 'wav'} of the loudest squealing row's wheel (its listen_<receiver>.wav), or None."""
    sq = [r for r in rows if r.get("squeals") and not r.get("note") and r.get("wheel")]
    if not sq:
        return None
    loud = max(sq, key=lambda r: r["L_pA"] if math.isfinite(r["L_pA"]) else -1e9)
    wavs = sorted(paths.case_dir(f"{loud['curve']}/{loud['wheel']}").glob("listen_*.wav"))
    return {"wheel": f"{loud['wheel']} of curve {loud['id']} ({loud['friction']})", "wav": str(wavs[0])} if wavs else None


def page_markdown(md: str, rows: list[dict], out: Path) -> str:
    """line.md with its verdict paragraph as a block quote, the sounds and the curves' links after its figures."""
    parts = [p for p in re.split(r"\n{2,}", md) if p.strip()]
    i = next((k for k, p in enumerate(parts) if k > 0 and p.startswith("**")), None)
    if i is not None:
        parts[i] = "> " + parts[i].replace("\n", "\n> ")
    extra = []
    snd = sounds(loudest_sound_row(rows))
    if snd:
        extra.append("## Listen: the loudest curve")
        for title, wav in snd:
            extra.append(f"{title[0].upper() + title[1:]}: [{wav.name}]({os.path.relpath(wav, out)})")
    links = [f"- [{r['id']} ({r['friction']}, R = {r['radius_m']:g} m): verdict.csv]"
             f"({os.path.relpath(paths.curve_dir(r['curve']) / 'verdict.csv', out)})"
             for r in rows if r.get("squeals") and not r.get("note")]
    if links:
        extra.append("## The squealing curves' verdicts\n\n" + "\n".join(links))
    first_h2 = next((k for k, p in enumerate(parts) if p.startswith("## ")), len(parts))
    return "\n\n".join(parts[:first_h2] + extra + parts[first_h2:])


def write_page(out: Path, md: str, rows: list[dict], name: str) -> Path:
    """verdict.html in ``out`` (atomic); returns its path."""
    page = out / "verdict.html"
    save_text(render(page_markdown(md, rows, out), out, f"Line {name}: which curves squeal"), page)
    return page
