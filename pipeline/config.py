"""Reading and validating TOML configuration.

This module is the single place in the pipeline that reads configuration
files.  Every value is checked against a small declarative schema so that a
typo or an out-of-range number is reported *before* hours of meshing and
eigenvalue solves are spent on it.

A schema is a (possibly nested) ``dict`` that maps a key either to

* a :class:`Field` -- one scalar value (float, int, str or bool),
* a :class:`ListOf` -- a TOML array whose items are all described by one
  :class:`Field`, or
* another ``dict`` -- a TOML table (``[section]``) with its own schema.

Example::

    WHEEL_SCHEMA = {
        "name": Field(str, doc="identifier used in file names"),
        "tyre": {
            "rolling_radius": Field(float, unit="m", min=0, max=2,
                                    min_inclusive=False),
        },
        "boundary": Field(str, choices=["clamped", "axle"]),
        "n_modes": Field(int, min=1, default=60),
        "damping": ListOf(Field(float, min=0), min_len=1, default=[0.01]),
    }

    cfg = load("config/wheels/r920.toml", WHEEL_SCHEMA)

Validation rules, deliberately strict:

* An ``int`` is accepted where a float is expected (and converted to
  ``float``, so ``1`` and ``1.0`` resolve -- and hash -- identically).
* A ``bool`` is never accepted as a number and a string is never accepted as
  a number (``"0.46"`` is a mistake in a TOML file, not a float).
* Floats must be finite (TOML allows ``nan`` and ``inf``; we do not).
* Unknown keys are errors -- that is how typos get caught.
* Missing required keys are errors; optional keys get their default.

All problems in a file are collected and raised together in one
:class:`ConfigError`, one line per problem, so the user can fix everything
in one go.
"""

from __future__ import annotations

import copy
import difflib
import hashlib
import json
import math
import os
import tomllib
from dataclasses import dataclass
from typing import Any, Mapping, NamedTuple, Sequence

__all__ = [
    "REQUIRED",
    "MISSING",
    "Field",
    "ListOf",
    "ConfigError",
    "ConfigIssue",
    "validate",
    "load",
    "config_hash",
]


class _Sentinel:
    """A named singleton used as a marker value (prints as ``<name>``)."""

    def __init__(self, name: str) -> None:
        self._name = name

    def __repr__(self) -> str:
        return f"<{self._name}>"

    def __copy__(self) -> "_Sentinel":
        return self

    def __deepcopy__(self, memo: dict) -> "_Sentinel":
        return self

    def __reduce__(self) -> str:
        # Pickle by reference to the module-level name, so identity survives.
        return self._name.upper()


#: Default value of a :class:`Field` / :class:`ListOf` meaning "no default:
#: the key must be present in the file".
REQUIRED = _Sentinel("required")

#: The ``value`` reported in a :class:`ConfigIssue` for a missing key.
MISSING = _Sentinel("missing")

# Human-readable names for the four scalar kinds (used in "allowed" texts).
_KIND_NAMES = {float: "a float", int: "an integer", str: "a string", bool: "a boolean (true/false)"}

# Maximum length of a value's repr in an error message (long arrays/tables
# are shortened so that one problem stays on one readable line).
_MAX_REPR = 80


# --------------------------------------------------------------------------
# Schema objects
# --------------------------------------------------------------------------


class _Mismatch(Exception):
    """Internal: a value does not satisfy a Field; ``allowed`` says why."""

    def __init__(self, allowed: str) -> None:
        super().__init__(allowed)
        self.allowed = allowed


def _is_number(value: Any) -> bool:
    """True for int/float values, excluding bool (which subclasses int)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _fmt_num(x: float | int) -> str:
    """Format a bound for humans: 2.0 -> '2', 0.46 -> '0.46', 1e-9 -> '1e-09'."""
    if isinstance(x, float) and x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


@dataclass(frozen=True)
class Field:
    """Schema of one scalar configuration value.

    Parameters
    ----------
    kind:
        One of ``float``, ``int``, ``str``, ``bool`` (the Python types).
    unit:
        Physical unit, used only in messages and documentation (``"m"``).
    min, max:
        Optional numeric bounds (float/int kinds only).
    min_inclusive, max_inclusive:
        Whether the bounds themselves are allowed (default: yes).
    choices:
        Optional finite set of allowed values (compared with the kind, so
        ``True`` never matches a choice of ``1``).
    default:
        :data:`REQUIRED` (the default) makes the key mandatory.  Any other
        value makes it optional; the default is itself validated when the
        schema is built.  ``None`` means "optional, resolves to ``None`` when
        absent" (TOML has no null, so ``None`` can only come from here).
    doc:
        Free-text description for documentation.
    """

    kind: type
    unit: str = ""
    min: float | int | None = None
    max: float | int | None = None
    min_inclusive: bool = True
    max_inclusive: bool = True
    choices: Sequence[Any] | None = None
    default: Any = REQUIRED
    doc: str = ""

    def __post_init__(self) -> None:
        # Schema mistakes are programming errors: fail loudly (TypeError /
        # ValueError) when the schema module is imported, not at run time.
        if self.kind not in _KIND_NAMES:
            raise TypeError(f"Field kind must be one of float, int, str, bool; got {self.kind!r}")
        for name in ("min", "max"):
            bound = getattr(self, name)
            if bound is None:
                continue
            if self.kind not in (float, int):
                raise TypeError(f"Field({self.kind.__name__}) cannot have a {name} bound")
            if not _is_number(bound) or math.isnan(bound):
                raise TypeError(f"Field {name} bound must be a number; got {bound!r}")
        if self.min is not None and self.max is not None:
            empty = self.min > self.max or (
                self.min == self.max and not (self.min_inclusive and self.max_inclusive)
            )
            if empty:
                raise ValueError(f"Field bounds admit no value: min={self.min!r}, max={self.max!r}")
        if self.choices is not None:
            choices = tuple(self.choices)
            if not choices:
                raise ValueError("Field choices must not be empty")
            # Freeze the choices (a caller's list must not change the schema).
            object.__setattr__(self, "choices", choices)
            for choice in choices:
                try:
                    self._check_scalar(choice)
                except _Mismatch:
                    raise ValueError(
                        f"Field choice {choice!r} is not {_KIND_NAMES[self.kind]}"
                    ) from None
        if self.default is not REQUIRED and self.default is not None:
            try:
                # Store the normalised default (e.g. int 1 -> float 1.0).
                object.__setattr__(self, "default", self.check(self.default))
            except _Mismatch as exc:
                raise ValueError(f"Field default {self.default!r} is not {exc.allowed}") from None

    # -- description -------------------------------------------------------

    def _range_text(self) -> str:
        """'0 < value <= 2', 'value > 0', 'value <= 1' or '' (no bounds)."""
        lo_op = "<=" if self.min_inclusive else "<"
        hi_op = "<=" if self.max_inclusive else "<"
        if self.min is not None and self.max is not None:
            return f"{_fmt_num(self.min)} {lo_op} value {hi_op} {_fmt_num(self.max)}"
        if self.min is not None:
            return f"value {'>=' if self.min_inclusive else '>'} {_fmt_num(self.min)}"
        if self.max is not None:
            return f"value {hi_op} {_fmt_num(self.max)}"
        return ""

    def describe(self) -> str:
        """What is allowed, e.g. ``a float in m, 0 < value <= 2``."""
        if self.choices is not None:
            text = f"one of {list(self.choices)!r}"
            if self.unit:
                text += f" (in {self.unit})"
            return text
        text = _KIND_NAMES[self.kind]
        if self.unit:
            text += f" in {self.unit}"
        rng = self._range_text()
        if rng:
            text += f", {rng}"
        return text

    # -- checking ----------------------------------------------------------

    def _check_scalar(self, value: Any) -> Any:
        """Type check + normalisation (no bounds/choices); raises _Mismatch."""
        kind = self.kind
        if kind is float:
            if not _is_number(value):
                raise _Mismatch(self.describe())
            value = float(value) + 0.0  # int -> float; -0.0 -> 0.0 (stable hash)
            if not math.isfinite(value):
                allowed = self.describe()
                if self.choices is None:  # "a float ..." -> "a finite float ..."
                    allowed = "a finite " + allowed.removeprefix("a ")
                raise _Mismatch(allowed)
            return value
        if kind is int:
            if not isinstance(value, int) or isinstance(value, bool):
                raise _Mismatch(self.describe())
            return value
        if not isinstance(value, kind):  # str, bool
            raise _Mismatch(self.describe())
        return value

    def check(self, value: Any) -> Any:
        """Return the normalised value or raise ``_Mismatch(allowed)``."""
        value = self._check_scalar(value)
        if self.min is not None:
            if value < self.min or (value == self.min and not self.min_inclusive):
                raise _Mismatch(self.describe())
        if self.max is not None:
            if value > self.max or (value == self.max and not self.max_inclusive):
                raise _Mismatch(self.describe())
        if self.choices is not None and value not in self.choices:
            raise _Mismatch(self.describe())
        return value


@dataclass(frozen=True)
class ListOf:
    """Schema of a TOML array whose items all satisfy one :class:`Field`.

    ``ListOf(Field(float, unit="Hz", min=0), min_len=1, max_len=4)``.
    The item Field's own ``default`` is ignored; use ``default=`` here for
    the whole list (validated when the schema is built).
    """

    item: Field
    min_len: int | None = None
    max_len: int | None = None
    default: Any = REQUIRED
    doc: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.item, Field):
            raise TypeError(f"ListOf item must be a Field; got {self.item!r}")
        for name in ("min_len", "max_len"):
            n = getattr(self, name)
            if n is not None and (not isinstance(n, int) or isinstance(n, bool) or n < 0):
                raise TypeError(f"ListOf {name} must be a non-negative int; got {n!r}")
        if self.min_len is not None and self.max_len is not None and self.min_len > self.max_len:
            raise ValueError(f"ListOf min_len {self.min_len} > max_len {self.max_len}")
        if self.default is not REQUIRED and self.default is not None:
            problems: list[ConfigIssue] = []
            normalised = self._check(self.default, "default", problems)
            if problems:
                details = "; ".join(f"{p.key} = {_short_repr(p.value)} is not {p.allowed}" for p in problems)
                raise ValueError(f"ListOf default is invalid: {details}")
            # Store as a tuple so the schema cannot be mutated through it.
            object.__setattr__(self, "default", tuple(normalised))

    def describe(self) -> str:
        """E.g. ``a list of 1 to 4 items, each a float in Hz, value >= 0``."""
        lo, hi = self.min_len, self.max_len
        if lo is not None and hi is not None:
            count = f"exactly {lo}" if lo == hi else f"{lo} to {hi}"
        elif lo is not None:
            count = f"at least {lo}"
        elif hi is not None:
            count = f"at most {hi}"
        else:
            count = ""
        head = f"a list of {count} items" if count else "a list"
        return f"{head}, each {self.item.describe()}"

    def _check(self, value: Any, key: str, problems: list[ConfigIssue]) -> list:
        """Validate a whole list, appending one issue per problem."""
        if not isinstance(value, (list, tuple)):
            problems.append(ConfigIssue(key, value, self.describe()))
            return []
        n = len(value)
        if (self.min_len is not None and n < self.min_len) or (
            self.max_len is not None and n > self.max_len
        ):
            problems.append(ConfigIssue(key, value, self.describe()))
        out = []
        for i, item in enumerate(value):
            try:
                out.append(self.item.check(item))
            except _Mismatch as exc:
                problems.append(ConfigIssue(f"{key}[{i}]", item, exc.allowed))
        return out


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
        for key, value, allowed in self.errors:
            if value is MISSING:
                lines.append(f"  {key}: {allowed}")
            elif allowed.startswith("unknown key"):
                lines.append(f"  {key} = {_short_repr(value)}: {allowed}")
            else:
                lines.append(
                    f"  {key} = {_short_repr(value)} ({_toml_type(value)}): expected {allowed}"
                )
        return "\n".join(lines)

    def __reduce__(self):
        # Keep the exception picklable (multiprocessing workers re-raise it).
        return (type(self), (self.source, list(map(tuple, self.errors)), self.detail))


# --------------------------------------------------------------------------
# Validation
# --------------------------------------------------------------------------


def _default_of(entry: Field | ListOf) -> Any:
    default = entry.default
    if isinstance(entry, ListOf) and default is not None:
        return list(default)
    return copy.deepcopy(default)


def _unknown_key_text(key: str, known: Sequence[str]) -> str:
    text = "unknown key"
    close = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
    if close:
        text += f" (did you mean {close[0]!r}?)"
    return text + f"; allowed keys here: {sorted(known)!r}"


def _validate_table(data: Mapping, schema: Mapping, prefix: str, problems: list[ConfigIssue]) -> dict:
    """Validate one table; return the resolved table, appending problems."""
    out: dict[str, Any] = {}
    for key, entry in schema.items():
        if not isinstance(key, str):
            raise TypeError(f"schema keys must be strings; got {key!r} in {prefix or '<root>'}")
        dotted = f"{prefix}{key}"
        present = key in data
        value = data.get(key)

        if isinstance(entry, Mapping):
            # A sub-table.  When it is absent, validate an empty table so
            # that each required key inside is reported by name, and all
            # optional ones get their defaults.
            if not present:
                value = {}
            if not isinstance(value, Mapping):
                problems.append(
                    ConfigIssue(dotted, value, f"a table [{dotted}] with keys {sorted(entry)!r}")
                )
                continue
            out[key] = _validate_table(value, entry, dotted + ".", problems)
        elif isinstance(entry, (Field, ListOf)):
            if not present:
                if entry.default is REQUIRED:
                    problems.append(
                        ConfigIssue(dotted, MISSING, f"required key is missing (expected {entry.describe()})")
                    )
                else:
                    out[key] = _default_of(entry)
                continue
            if isinstance(entry, ListOf):
                out[key] = entry._check(value, dotted, problems)
            else:
                try:
                    out[key] = entry.check(value)
                except _Mismatch as exc:
                    problems.append(ConfigIssue(dotted, value, exc.allowed))
        else:
            raise TypeError(
                f"schema entry {dotted!r} must be a Field, ListOf or dict; got {entry!r}"
            )

    known = [k for k in schema]
    for key, value in data.items():
        if key not in schema:
            problems.append(ConfigIssue(f"{prefix}{key}", value, _unknown_key_text(str(key), known)))
    return out


def validate(data: Mapping, schema: Mapping, source: str) -> dict:
    """Validate ``data`` against ``schema``; return a new dict with defaults.

    Parameters
    ----------
    data:
        The parsed configuration (e.g. from :func:`tomllib.load`).  Not
        modified.
    schema:
        Nested dict of :class:`Field` / :class:`ListOf` / sub-dicts.
    source:
        Where ``data`` came from (normally the file path); used in messages.

    Raises
    ------
    ConfigError
        Listing *every* problem found (unknown keys, missing required keys,
        wrong types, out-of-range values, values not among the choices).
    TypeError / ValueError
        If the schema itself is malformed (a programming error).
    """
    if not isinstance(data, Mapping):
        raise ConfigError(source, detail=f"top level must be a table, got {_toml_type(data)}")
    problems: list[ConfigIssue] = []
    resolved = _validate_table(data, schema, "", problems)
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
    from geometry.outline import GeometryError

    if not os.path.exists(path):
        raise ConfigError(str(path), detail=f"no such {what}; available: {list(available)}")
    params = load(path, schema)
    try:
        check(params)
    except GeometryError as e:
        raise ConfigError(str(path), [(e.key, e.value, e.allowed)]) from None
    return params
