"""``make check STUDY=<name>`` (``python -m pipeline.study.check <name>``): everything a study would
refuse, without computing: the study file (its kind's schema, the cases it names) and, for a line
study, its CSV of curves (every row and column, ``pipeline.study.line_input``) and each row's curve
file.  One line per problem (file, key or line and column, value, what is allowed), exit code 2."""
from __future__ import annotations

import sys
from pipeline.study.definition import load_study
from pipeline.study.line_input import check
from pipeline.config.loader import ConfigError


def check_study(name: str) -> str:
    """A one-line summary of a valid study; ConfigError otherwise."""
    spec, src = load_study(name)
    if spec["kind"] == "line":
        rows = check(spec)
        return f"{src}: ok (line study, {len(rows)} curves from {spec['curves']})"
    return f"{src}: ok ({spec['kind']} study)"


def main(argv=None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print("usage: python -m pipeline.study.check <study>", file=sys.stderr)
        return 2
    try:
        print(check_study(args[0]))
    except ConfigError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
