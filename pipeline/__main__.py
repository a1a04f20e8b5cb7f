"""Command line: ``python -m pipeline <stage> [--wheel NAME] ...``.

The Makefile calls these; each stage reads its inputs, writes its artifacts
atomically and exits non-zero with a one-paragraph message on bad input.
"""
from __future__ import annotations

import argparse
import importlib
import logging
import sys

from pipeline.stages import STAGES
from pipeline.store.atomic import interrupted, watch_interrupts
from pipeline.store import paths
from pipeline.store.artifacts import ArtifactError
from pipeline.config.loader import ConfigError
from pipeline.numba_setup import skip_special
from pipeline.curve.check import check_curve
from pipeline.config.check import run_check
from pipeline.curve.stage import run_curve
from pipeline.study.screen import run_stability_map
from pipeline.study.stage import run_study
from pipeline.stages.listen import run_listen

# the stages that run numba code (pipeline/numba_setup.py)
NUMBA_STAGES = {name for name, st in STAGES.items() if st.numba}


def main(argv=None) -> int:
    """The CLI; Ctrl-C (KeyboardInterrupt) anywhere ends it with one line and exit code 130 (the
    artifacts written before are whole: every write is atomic)."""
    watch_interrupts()
    try:
        rc = _main(argv)
        if interrupted():                           # swallowed by a library on the way (pipeline.store.atomic)
            raise KeyboardInterrupt
        return rc
    except KeyboardInterrupt:
        stage = next((a for a in (sys.argv[1:] if argv is None else argv) if a in STAGES), "the stage")
        print(f"interrupted: {stage} stopped; the artifacts it had finished are kept, nothing half-written",
              file=sys.stderr)
        return 130


def _main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pipeline", description="Curve squeal pipeline stages.",
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="stages:\n" + "\n".join(f"  {k:8s} {v.help}" for k, v in STAGES.items()))
    ap.add_argument("stage", choices=list(STAGES))
    ap.add_argument("--wheel", default="c20", help="wheel parameter file geometry/wheels/<name>.toml (default c20)")
    ap.add_argument("--rail", default="bv50", help="rail parameter file geometry/rails/<name>.toml (default bv50)")
    ap.add_argument("--case", default="default", help="case file pipeline/cases/<name>.toml, or a curve's wheel "
                    "<curve>/<wheel> (build/curves/<curve>/cases/<wheel>.toml, written by the curve stage) "
                    "(default: default)")
    ap.add_argument("--workers", type=int, default=None,
                    help="processes for the harmonic solves, Dask workers of a study's local cluster (default: cores)")
    ap.add_argument("--curve", default=None, help="curve, check: a curve file's path (anywhere), or a shipped "
                                                   "curve's name (pipeline/curves/<name>.toml)")
    ap.add_argument("--no-what-ifs", action="store_true", help="curve: skip the mitigation what-ifs")
    ap.add_argument("--study", default="map", help="study file pipeline/studies/<name>.toml (default: map)")
    ap.add_argument("--quick", action="store_true", help="study: the coarser grid / shorter runs for a quick look")
    ap.add_argument("--scheduler", default=None, help="study: address of a Dask scheduler (tcp://host:port) "
                                                      "instead of a local cluster")
    ap.add_argument("--out", default=None, help="study: output folder (default build/studies/<study>[-quick])")
    ap.add_argument("--no-progress", action="store_true", help="study, curve: no progress bar")
    ap.add_argument("--distance", type=float, default=None,
                    help="listen: receiver from the track centre (m; default: the case's [listener], 7.5)")
    ap.add_argument("--height", type=float, default=None,
                    help="listen: receiver above the top of the rail (m; default: the case's [listener], 1.2)")
    ap.add_argument("--allow-silent", action="store_true",
                    help="listen: for a case that does not squeal, write the levels and a silent WAV")
    ap.add_argument("-v", "--verbose", action="count", default=0, help="more logging (-vv for debug)")
    ap.add_argument("-q", "--quiet", action="store_true", help="warnings and errors only")
    args = ap.parse_args(argv)
    level = logging.WARNING if args.quiet else (logging.INFO if args.verbose < 2 else logging.DEBUG)
    logging.basicConfig(level=level, format="%(levelname)s %(name)s: %(message)s")


    try:
        paths.curve_wheel(args.case)  # a case file's name, or a curve's wheel <curve>/<wheel>
    except ValueError as e:
        print(f"error: --case: {e}", file=sys.stderr)
        return 2

    if args.stage in NUMBA_STAGES:
        skip_special()

    try:
        if args.stage == "check" and args.curve:
            print("\n".join(check_curve(args.curve)))
        elif args.stage == "check":
            print("\n".join(run_check(args.case, args.wheel, args.rail)))
        elif args.stage == "curve":
            if not args.curve:
                raise ConfigError("--curve", detail="the curve stage needs --curve <name or path> (pipeline/curves/<name>.toml, "
                                                    "or a curve file anywhere)")
            res = run_curve(args.curve, progress_bar=not args.no_progress, what_ifs=not args.no_what_ifs)
            print(res["paths"]["md"])
        elif args.stage == "stability_map":
            print(run_stability_map(args.study, quick=args.quick))
        elif args.stage == "study":
            print(run_study(args.study, quick=args.quick, scheduler=args.scheduler, workers=args.workers,
                            out=args.out, progress=not args.no_progress))
        elif args.stage == "listen":
            run_listen(args.case, distance=args.distance, height=args.height, allow_silent=args.allow_silent)
        else:
            st = STAGES[args.stage]
            run = getattr(importlib.import_module(f".{st.module}", __package__), st.function)
            run(getattr(args, st.takes), *([args.workers] if args.stage == "modes" else []))
    except (ConfigError, ArtifactError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
