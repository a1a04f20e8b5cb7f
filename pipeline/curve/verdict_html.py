"""A curve's verdict as one self-contained page, build/curves/<curve>/verdict.html, and its headline in
plain text, headline.txt (what `make` prints last, issue 33).

The page is Markdown rendered as the case report's (``pipeline.stages.report_html.render``: every
figure and WAV embedded as a data URI, it opens from anywhere): the headline first (which wheel,
its frequency and wheel mode, L_pA at the receiver, what would stop it), the bogie in its curve
(bogie.png), the table per wheel, the loudest wheel's sound (listen_<receiver>.wav) and the
pass-by's (passby_<receiver>.wav, same folder), the what-ifs.  Everything is taken from verdict.md's
text and the rows the stage computed, so the page and verdict.md cannot disagree."""
from __future__ import annotations

import math
import os
import re
from pathlib import Path

from pipeline.config.nouns import Curve
from pipeline.curve.verdict_report import loudest
from pipeline.stages.report_html import render
from pipeline.store import paths
from pipeline.store.atomic import save_text

LISTEN = re.compile(r"\s*Listen: `[^`]*`\.?")


def _paragraphs(md: str) -> dict:
    """verdict.md cut into its parts: 'title' (the H1), 'verdict' (the paragraphs before the table),
    'stop' (the "What would stop it" paragraph or ''), 'table' (its lines) and 'tail'."""
    parts = md.strip("\n").split("\n\n")
    table = next(i for i, p in enumerate(parts) if p.lstrip().startswith("|"))
    before = parts[1:table]
    stop = [p for p in before if p.startswith("What would stop it")]
    return {"title": parts[0], "verdict": [LISTEN.sub("", p) for p in before if p not in stop],
            "stop": stop[0] if stop else "", "table": parts[table], "tail": "\n\n".join(parts[table + 1:])}


def _plain(text: str) -> str:
    return re.sub(r"\*\*|`", "", text).strip()


def sounds(row: dict | None) -> list[tuple[str, Path]]:
    """(title, WAV) of the loudest wheel's sound at the receiver and of the pass-by beside it, those that exist."""
    if row is None or not row.get("wav"):
        return []
    wav = Path(row["wav"])
    tag = wav.stem.removeprefix("listen_")
    found = [(f"the squeal of wheel {row['wheel']} at the receiver ({tag}; its limit cycle)", wav),
             (f"the pass-by ({tag})", wav.with_name(f"passby_{tag}.wav"))]
    return [(t, p) for t, p in found if p.exists()]


def headline(info: Curve, rows: list[dict], md: str, page: Path) -> str:
    """The verdict in three lines of plain text, the page's path last."""
    loud, parts = loudest(rows), _paragraphs(md)
    where = f"curve {info.name} ({info.vehicle.name}, R = {info.radius:g} m, {info.speed_kmh:g} km/h)"
    if loud is None:
        first = f"{where}: no wheel squeals (L_F2 < 10 dB re 1 N at every wheel)."
        stop = ""
    else:
        lpa = f"{loud['L_pA']:.1f} dB(A)" if math.isfinite(loud["L_pA"]) else "not computed"
        first = (f"{where} SQUEALS: wheel {loud['wheel']} at {loud['f_squeal']:.0f} Hz, wheel mode "
                 f"{loud['mode'] or '-'}, L_pA = {lpa} at 7.5 m (L_F2 = {loud['L_F2']:.1f} dB re 1 N).")
        stop = _plain(parts["stop"]) or "What would stop it: not computed (the what-ifs were not run)."
    return "\n".join(x for x in (first, stop, f"Open the verdict: {shown(page)}") if x) + "\n"


def shown(path: Path) -> str:
    """The page's path relative to the repository (where `make` runs) when inside it, else absolute."""
    try:
        return Path(path).resolve().relative_to(paths.ROOT).as_posix()
    except ValueError:
        return str(Path(path).resolve())


def page_markdown(info: Curve, rows: list[dict], md: str, out: Path) -> str:
    """The page's Markdown (module notes); links relative to ``out``."""
    parts, loud = _paragraphs(md), loudest(rows)
    quote = parts["verdict"] + ([parts["stop"]] if parts["stop"] else [])
    blocks = [parts["title"], "\n>\n".join("> " + p.replace("\n", "\n> ") for p in quote)]
    blocks += ["## The bogie in its curve", "![the leading bogie in the curve, its contact points](bogie.png)",
               "## Every wheel", parts["table"]]
    snd = sounds(loud)
    if snd:
        blocks.append("## Listen")
        for title, wav in snd:
            png = wav.with_suffix(".png")
            blocks.append(f"{title[0].upper() + title[1:]}: [{wav.name}]({os.path.relpath(wav, out)})")
            if png.exists():
                blocks.append(f"![{wav.stem}]({os.path.relpath(png, out)})")
    blocks.append("## What would stop it")
    each = [f"- wheel **{r['wheel']}** ({r['f_squeal']:.0f} Hz, {r['mode'] or '-'}): friction below mu = "
            f"{r['mu_threshold']:.3f}; modal damping {r['zeta_needed'] or '-'}" for r in rows
            if r["squeals"] and math.isfinite(r["mu_threshold"])]
    blocks.append(parts["stop"] or ("Nothing to stop: no wheel squeals." if loud is None else
                                    "The what-ifs were not run (`NO_WHAT_IFS=1`)."))
    if each:
        blocks.append("Each squealing wheel (verdict.csv's `mu_threshold`, `zeta_needed`):\n\n" + "\n".join(each))
    blocks.append(parts["tail"])
    return "\n\n".join(b for b in blocks if b) + "\n"


def write_page(out: Path, info: Curve, rows: list[dict], md: str) -> Path:
    """verdict.html and headline.txt in ``out`` (atomic); returns the page's path."""
    page = out / "verdict.html"
    save_text(render(page_markdown(info, rows, md, out), out, f"Curve {info.name}: verdict"), page)
    save_text(headline(info, rows, md, page), out / "headline.txt")
    return page
