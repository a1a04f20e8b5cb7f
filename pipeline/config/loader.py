"""Reading and validating TOML configuration.

This module is the single place in the pipeline that reads configuration
files.  Every value is checked -- by a pydantic (v2) model built from the
declarative schema (``pipeline.config.schema``: :class:`Field`,
:class:`ListOf`, nested dicts) -- so that a typo or an out-of-range number is
reported *before* hours of meshing and eigenvalue solves are spent on it.

    cfg = load("geometry/wheels/c20.toml", schemas.WHEEL)

Rules, deliberately strict: an ``int`` is accepted where a float is expected
(and converted, so ``1`` and ``1.0`` resolve -- and hash -- identically); a
bool or a string is never a number; floats must be finite; unknown keys are
errors (with a did-you-mean); missing required keys are errors; optional keys
get their default.  All problems in a file are raised together in one
:class:`ConfigError`, one line per problem naming the key, the value and what
is allowed, so the user can fix everything in one go.
"""

from __future__ import annotations

import difflib
import hashlib
import json
import os
import tomllib
from typing import Any, Mapping, NamedTuple, Sequence

from pydantic import ValidationError

from pipeline.config.schema import MISSING, REQUIRED, Field, ListOf, model_of
from geometry.outline import GeometryError

__all__ = [
    "REQUIRED",
    "MISSING",
    "Field",
    "ListOf",
    "ConfigError",
    "ConfigIssue",
    "MissingInput",
    "named_file",
    "validate",
    "load",
    "config_hash",
]

# Maximum length of a value's repr in an error message (long arrays/tables
# are shortened so that one problem stays on one readable line).
_MAX_REPR = 80


# --------------------------------------------------------------------------
# Errors
# --------------------------------------------------------------------------


class ConfigIssue(NamedTuple):
    """One problem: dotted key, offending value (or MISSING), what is allowed."""

    key: str
    value: Any
    allowed: str


def _short_repr(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= _MAX_REPR else text[: _MAX_REPR - 3] + "..."


def _toml_type(value: Any) -> str:
    """Name of a value's type in TOML vocabulary (for error messages)."""
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "string"
    if isinstance(value, dict):
        return "table"
    if isinstance(value, (list, tuple)):
        return "array"
    return type(value).__name__  # datetime, date, time, ...


def issue_text(key: str, value: Any, allowed: str) -> str:
    """One problem as a ConfigError prints it: ``key = value (type): expected allowed``, or without
    'expected' where ``allowed`` says what is wrong ('unknown key ...', 'not ...', 'no ...')."""
    if value is MISSING:
        return f"{key}: {allowed}"
    if allowed.startswith("unknown key") or allowed.startswith("not ") or allowed.startswith("no "):
        return f"{key} = {_short_repr(value)}: {allowed}"
    return f"{key} = {_short_repr(value)} ({_toml_type(value)}): expected {allowed}"


class ConfigError(ValueError):
    """Invalid configuration; the message names the file and every problem.

    Attributes
    ----------
    source:
        The file (or other origin) that was being read.
    errors:
        List of :class:`ConfigIssue` ``(key, value, allowed)`` tuples; empty
        for file-level problems (missing file, TOML syntax error), which are
        described by ``detail`` instead.
    """

    def __init__(self, source: str, errors: Sequence[tuple] = (), detail: str | None = None) -> None:
        self.source = str(source)
        self.errors = [ConfigIssue(*e) for e in errors]
        self.detail = detail
        super().__init__(self._format())

    def _format(self) -> str:
        if self.detail is not None:
            return f"{self.source}: {self.detail}"
        n = len(self.errors)
        lines = [f"{self.source}: {n} configuration error{'s' if n != 1 else ''}:"]
        lines += [f"  {issue_text(*e)}" for e in self.errors]
        if n == 1:                  # one problem: one line
            return f"{self.source}: {lines[1].strip()}"
        return "\n".join(lines)

    def __reduce__(self):
        # Keep the exception picklable (multiprocessing workers re-raise it).
        return (type(self), (self.source, list(map(tuple, self.errors)), self.detail))


class MissingInput(ConfigError):
    """An input file named by another file (a wheel, rail, vehicle, profile ...) that is not there;
    ``named_file`` turns it into an error naming the file and key that asked for it."""

    def __init__(self, path, what: str, available: Sequence[str], detail: str | None = None) -> None:
        self.path, self.what, self.available = str(path), what, list(available)
        super().__init__(self.path, detail=detail or f"no such {what}; available: {self.available}")

    def __reduce__(self):
        return (type(self), (self.path, self.what, self.available, self.detail))


def named_file(source, key: str, value, load_named):
    """``load_named(value)``, where ``value`` is the name the file ``source`` gives under ``key``; a
    missing file is a one-line ConfigError naming ``source``, the key, the value and what is there:
    ``<source>: wheel = 'c21': no such wheel file <path>; available: ['c20', 'straight']``."""
    try:
        return load_named(value)
    except MissingInput as e:
        raise ConfigError(str(source), [(key, value, f"no such {e.what} file {e.path}; available: "
                                                     f"{e.available}")]) from None


# --------------------------------------------------------------------------
# Validation: the pydantic model, its errors in the schema's words
# --------------------------------------------------------------------------


def _unknown_key_text(key: str, known: Sequence[str]) -> str:
    text = "unknown key"
    close = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
    if close:
        text += f" (did you mean {close[0]!r}?)"
    return text + f"; allowed keys here: {sorted(known)!r}"


def _dotted(loc: Sequence) -> str:
    out = ""
    for part in loc:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def _issue(error: dict, schema: Mapping) -> ConfigIssue:
    """One pydantic error as (dotted key, value, what is allowed)."""
    loc, kind, value = error["loc"], error["type"], error.get("input")
    entry, table = schema, schema
    for part in loc:
        table = entry
        entry = entry[part] if isinstance(entry, Mapping) and part in entry else \
            (entry.item if isinstance(entry, ListOf) and isinstance(part, int) else None)
    key = _dotted(loc)
    if entry is None and kind != "extra_forbidden":  # not expected; say what pydantic said
        return ConfigIssue(key, value, error["msg"])
    if kind == "extra_forbidden":
        return ConfigIssue(key, value, _unknown_key_text(str(loc[-1]), list(table)))
    if isinstance(entry, Mapping):
        return ConfigIssue(key, value, f"a table [{key}] with keys {sorted(entry)!r}")
    if kind == "missing":
        return ConfigIssue(key, MISSING, f"required key is missing (expected {entry.describe()})")
    if isinstance(entry, Field):
        return ConfigIssue(key, value, entry.describe(finite=kind == "finite_number" and entry.choices is None))
    return ConfigIssue(key, value, entry.describe())  # a ListOf given something that is not a list


def _length_issues(data: Mapping, schema: Mapping, prefix: str = "") -> list[ConfigIssue]:
    """Lists of the wrong length (checked here so that they are reported together with
    their items' problems)."""
    out = []
    for key, entry in schema.items():
        value = data.get(key) if isinstance(data, Mapping) else None
        if isinstance(entry, Mapping) and isinstance(value, Mapping):
            out += _length_issues(value, entry, f"{prefix}{key}.")
        elif isinstance(entry, ListOf) and isinstance(value, (list, tuple)) and not entry.length_ok(value):
            out.append(ConfigIssue(f"{prefix}{key}", value, entry.describe()))
    return out


def _with_tables(data: Mapping, schema: Mapping) -> dict:
    """A copy of ``data`` with every absent table of the schema present and empty, so that the
    model validates it (naming its required keys, filling its defaults) under its own key."""
    out = dict(data)
    for key, entry in schema.items():
        if isinstance(entry, Mapping) and key not in out:
            out[key] = {}
        if isinstance(entry, Mapping) and isinstance(out[key], Mapping):
            out[key] = _with_tables(out[key], entry)
    return out


def validate(data: Mapping, schema: Mapping, source: str) -> dict:
    """Validate ``data`` (e.g. from :func:`tomllib.load`, not modified) against
    ``schema`` (nested dict of :class:`Field` / :class:`ListOf` / sub-dicts);
    return a new dict with the defaults filled in.  ``source`` (normally the
    file path) names the origin in messages.

    Raises :class:`ConfigError` listing *every* problem (unknown keys, missing
    required keys, wrong types, out-of-range values, values not among the
    choices, lists of the wrong length); TypeError / ValueError when the schema
    itself is malformed (a programming error).
    """
    model = model_of(schema)
    if not isinstance(data, Mapping):
        raise ConfigError(source, detail=f"top level must be a table, got {_toml_type(data)}")
    problems = _length_issues(data, schema)
    try:
        resolved = model.model_validate(_with_tables(data, schema)).model_dump(by_alias=True)
    except ValidationError as exc:
        problems = [_issue(e, schema) for e in exc.errors()] + problems
    if problems:
        raise ConfigError(source, problems)
    return resolved


def load(path: str | os.PathLike, schema: Mapping) -> dict:
    """Read the TOML file at ``path``, validate it and return the resolved dict.

    Raises :class:`ConfigError` (naming the file) when the file is missing or
    unreadable, is not valid TOML (with the parser's line/column message), or
    does not satisfy ``schema``.
    """
    source = os.fspath(path)
    try:
        with open(source, "rb") as fh:
            raw = fh.read()
    except FileNotFoundError:
        raise ConfigError(source, detail="configuration file not found") from None
    except IsADirectoryError:
        raise ConfigError(source, detail="is a directory, not a configuration file") from None
    except OSError as exc:
        raise ConfigError(source, detail=f"cannot read configuration file: {exc.strerror or exc}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError(
            source, detail=f"not valid TOML: file is not UTF-8 text (byte offset {exc.start})"
        ) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        # The message already contains "(at line L, column C)".
        raise ConfigError(source, detail=f"not valid TOML: {exc}") from None
    return validate(data, schema, source)


# --------------------------------------------------------------------------
# Hashing
# --------------------------------------------------------------------------


def config_hash(cfg: Mapping) -> str:
    """Stable 16-hex-digit digest of a resolved configuration (a cache key).

    The configuration is serialised as canonical JSON (sorted keys, no
    whitespace, UTF-8) and hashed with SHA-256; the first 16 hex digits are
    returned.  Key order therefore does not matter, but values do, including
    their type (``1`` and ``1.0`` differ -- :func:`validate` normalises float
    fields so that this does not bite).  Raises ``TypeError`` for values JSON
    cannot represent exactly (e.g. numpy scalars) and ``ValueError`` for
    NaN/inf, rather than hashing something ambiguous.
    """
    canonical = json.dumps(
        cfg, sort_keys=True, separators=(",", ":"), ensure_ascii=False, allow_nan=False
    )
    return hashlib.sha256(canonical.encode("utf-8")).hexdigest()[:16]


def load_geometry(path, schema: Mapping, check, what: str, available: Sequence[str]) -> dict:
    """Load a geometry parameter file and run the geometry's own consistency
    check ``check(params)`` (which raises geometry.outline.GeometryError);
    both kinds of problem come out as ConfigError naming the file.  ``what``
    ('wheel', 'rail') and ``available`` make the missing-file message."""
    if not os.path.exists(path):
        raise MissingInput(path, what, available)
    params = load(path, schema)
    key = (getattr(check, "__module__", ""), getattr(check, "__qualname__", repr(check)), config_hash(params))
    if key in _CHECKED:                 # the same parameters passed this check before in this process
        return params
    try:
        check(params)
    except GeometryError as e:
        raise ConfigError(str(path), [(e.key, e.value, e.allowed)]) from None
    _CHECKED.add(key)
    return params


_CHECKED: set = set()   # load_geometry: (check, parameters' hash) that passed (a study asks ~10 times per case)
