"""The declarative schema of a TOML configuration, and its pydantic (v2) model.

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

:func:`model_of` turns a schema into a pydantic model (strict types, bounds,
``allow_inf_nan=False``, unknown keys forbidden, every table validated even
when absent so that its required keys are named); ``pipeline.config.loader`` runs it
and words its errors.  A Field describes itself (``describe()``) in the words
the error messages use: ``a float in m, 0 < value <= 2``.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Annotated, Any, Mapping, Optional, Sequence

from pydantic import AfterValidator, BaseModel, ConfigDict, create_model, Field as PydanticField
from pydantic_core import PydanticCustomError


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

#: The ``value`` reported in a ``ConfigIssue`` for a missing key.
MISSING = _Sentinel("missing")

# Human-readable names for the four scalar kinds (used in "allowed" texts).
KIND_NAMES = {float: "a float", int: "an integer", str: "a string", bool: "a boolean (true/false)"}


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

    ``kind``: ``float``, ``int``, ``str`` or ``bool``; ``unit``: physical unit
    (messages and documentation only); ``min``, ``max``: numeric bounds,
    inclusive unless ``min_inclusive`` / ``max_inclusive`` is false;
    ``choices``: a finite set of allowed values; ``default``: :data:`REQUIRED`
    (the key must be present), a value (validated when the schema is built) or
    ``None`` (optional, resolves to ``None``); ``doc``: description.

    Strict: an ``int`` is accepted where a float is expected (and converted,
    so ``1`` and ``1.0`` resolve -- and hash -- identically; -0.0 becomes 0.0);
    a bool or a string is never a number; floats must be finite.
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
        # Schema mistakes are programming errors: fail loudly when the schema module is imported.
        if self.kind not in KIND_NAMES:
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
            if self.min > self.max or (self.min == self.max and not (self.min_inclusive and self.max_inclusive)):
                raise ValueError(f"Field bounds admit no value: min={self.min!r}, max={self.max!r}")
        if self.choices is not None:
            choices = tuple(self.choices)  # frozen: a caller's list must not change the schema
            if not choices:
                raise ValueError("Field choices must not be empty")
            object.__setattr__(self, "choices", choices)
            for choice in choices:
                if self.normalise(choice) is None:
                    raise ValueError(f"Field choice {choice!r} is not {KIND_NAMES[self.kind]}")
        if self.default is not REQUIRED and self.default is not None:
            value = self.normalise(self.default)
            if value is None or not self.admits(value):
                raise ValueError(f"Field default {self.default!r} is not {self.describe()}")
            object.__setattr__(self, "default", value)  # normalised (int 1 -> float 1.0)

    # -- description -------------------------------------------------------

    def range_text(self) -> str:
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

    def describe(self, finite: bool = False) -> str:
        """What is allowed, e.g. ``a float in m, 0 < value <= 2`` (``finite``: the
        wording for a NaN/inf value, ``a finite float ...``)."""
        if self.choices is not None:
            text = f"one of {list(self.choices)!r}"
            return text + (f" (in {self.unit})" if self.unit else "")
        text = KIND_NAMES[self.kind]
        if finite:
            text = "a finite " + text.removeprefix("a ")
        if self.unit:
            text += f" in {self.unit}"
        rng = self.range_text()
        return text + (f", {rng}" if rng else "")

    # -- checking (schema definitions; files are checked by the pydantic model) --

    def normalise(self, value: Any) -> Any:
        """The value as this kind (int -> float), or None when it is not of the kind."""
        if self.kind is float:
            return float(value) + 0.0 if _is_number(value) and math.isfinite(value) else None
        if self.kind is int:
            return value if isinstance(value, int) and not isinstance(value, bool) else None
        return value if isinstance(value, self.kind) else None

    def admits(self, value: Any) -> bool:
        """Bounds and choices (for a normalised value)."""
        if self.min is not None and (value < self.min or (value == self.min and not self.min_inclusive)):
            return False
        if self.max is not None and (value > self.max or (value == self.max and not self.max_inclusive)):
            return False
        return self.choices is None or value in self.choices

    def annotation(self):
        """The pydantic type of this field: strict kind, bounds, finiteness, choices."""
        bounds = {}
        if self.min is not None:
            bounds["ge" if self.min_inclusive else "gt"] = self.min
        if self.max is not None:
            bounds["le" if self.max_inclusive else "lt"] = self.max
        if self.kind is float:
            bounds["allow_inf_nan"] = False
        checks = [PydanticField(strict=True, **bounds)]
        if self.kind is float:
            checks.append(AfterValidator(lambda v: v + 0.0))  # -0.0 -> 0.0 (a stable hash)
        if self.choices is not None:
            choices = self.choices

            def one_of(v):
                if v not in choices:
                    raise PydanticCustomError("choice", "not one of the choices")
                return v
            checks.append(AfterValidator(one_of))
        return Annotated[self.kind, *checks]


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
            items = [self.item.normalise(v) for v in self.default]
            if not self.length_ok(items) or any(v is None or not self.item.admits(v) for v in items):
                raise ValueError(f"ListOf default {self.default!r} is not {self.describe()}")
            object.__setattr__(self, "default", tuple(items))  # the schema cannot be mutated through it

    def length_ok(self, value: Sequence) -> bool:
        n = len(value)
        return not ((self.min_len is not None and n < self.min_len) or (self.max_len is not None and n > self.max_len))

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


def _frozen(schema: Mapping) -> tuple:
    """The schema as nested tuples of (key, entry): a value to memoise the model on."""
    if not isinstance(schema, Mapping):
        return schema
    return tuple((key, _frozen(entry)) for key, entry in schema.items())


def model_of(schema: Mapping) -> type[BaseModel]:
    """The pydantic model of a schema (nested models for tables; built once per
    distinct schema *value*).  Keys become aliases (any TOML key works, also one
    that is a BaseModel attribute)."""
    return _model(_frozen(schema), "Config")


@functools.lru_cache(maxsize=64)
def _model(schema: tuple, name: str) -> type[BaseModel]:
    fields = {}
    for i, (key, entry) in enumerate(schema):
        if not isinstance(key, str):
            raise TypeError(f"schema keys must be strings; got {key!r} in {name}")
        if isinstance(entry, tuple):
            # an absent table is validated as an empty one: its required keys are named, its defaults filled in
            sub = _model(entry, f"{name}.{key}")
            fields[f"f{i}"] = (sub, PydanticField(alias=key, default_factory=dict, validate_default=True))
        elif isinstance(entry, Field):
            if entry.default is REQUIRED:
                fields[f"f{i}"] = (entry.annotation(), PydanticField(alias=key))
            elif entry.default is None:
                fields[f"f{i}"] = (Optional[entry.annotation()], PydanticField(alias=key, default=None))
            else:
                fields[f"f{i}"] = (entry.annotation(), PydanticField(alias=key, default=entry.default))
        elif isinstance(entry, ListOf):
            items = list[entry.item.annotation()]
            if entry.default is REQUIRED:
                fields[f"f{i}"] = (items, PydanticField(alias=key))
            elif entry.default is None:
                fields[f"f{i}"] = (items | None, PydanticField(alias=key, default=None))
            else:
                fields[f"f{i}"] = (items, PydanticField(alias=key, default_factory=lambda d=entry.default: list(d)))
        else:
            raise TypeError(f"schema entry {name}.{key!r} must be a Field, ListOf or dict; got {entry!r}")
    config = ConfigDict(strict=True, extra="forbid", populate_by_name=False)
    return create_model(name.replace(".", "_"), __config__=config, **fields)
