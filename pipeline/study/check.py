"""``make check STUDY=<name>`` (``python -m pipeline.study.check <name>``): everything a study would
refuse, without computing: the study file (its kind's schema, the cases it names) and what its kind
checks besides (``check(spec)`` of pipeline/study/kinds/<kind>.py: a line study's CSV of curves, every row and
column, and each row's curve file).  One line per problem (file, key or line and column, value, what is
allowed), exit code 2."""
from __future__ import annotations

import sys
from pipeline.study.kinds import kind_module, load_study
from pipeline.config.loader import ConfigError


def check_study(name: str) -> str:
    """A one-line summary of a valid study; ConfigError otherwise."""
    spec, src = load_study(name)
    check = getattr(kind_module(spec["kind"]), "check", None)    # what the kind adds (a line's CSV of curves)
    return f"{src}: ok ({spec['kind']} study{', ' + check(spec) if check else ''})"


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
