"""Tests for pipeline.config.loader: schema validation, error reporting, hashing."""

from __future__ import annotations

import pickle
import textwrap

import pytest

from pipeline.config.loader import (
    MISSING,
    REQUIRED,
    ConfigError,
    Field,
    ListOf,
    config_hash,
    load,
    validate,
)

# A schema shaped like the real ones (wheel/rail/case), exercising every
# feature: nested tables, bounds, choices, defaults, lists.
SCHEMA = {
    "name": Field(str, doc="identifier"),
    "boundary": Field(str, choices=["clamped", "axle"]),
    "n_modes": Field(int, min=1, max=500, default=60),
    "symmetric": Field(bool, default=False),
    "tyre": {
        "rolling_radius": Field(float, unit="m", min=0, max=2, min_inclusive=False),
        "width": Field(float, unit="m", min=0, min_inclusive=False, default=0.135),
    },
    "contact": {
        "friction": Field(float, min=0, max=1.0),
        "model": Field(str, choices=["kalker", "polach"], default="polach"),
    },
    "damping": ListOf(Field(float, min=0), min_len=1, max_len=4, default=[0.01]),
}

VALID = """\
name = "r920"
boundary = "clamped"

[tyre]
rolling_radius = 0.46

[contact]
friction = 0.3
"""


def write(tmp_path, text, name="wheel.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


def replace_line(text, old, new):
    assert old in text
    return text.replace(old, new)


def load_error(tmp_path, text) -> tuple[ConfigError, str]:
    path = write(tmp_path, text)
    with pytest.raises(ConfigError) as info:
        load(path, SCHEMA)
    return info.value, str(path)


# --------------------------------------------------------------------------
# Valid files
# --------------------------------------------------------------------------


def test_valid_file_resolves_with_defaults(tmp_path):
    cfg = load(write(tmp_path, VALID), SCHEMA)
    assert cfg == {
        "name": "r920",
        "boundary": "clamped",
        "n_modes": 60,
        "symmetric": False,
        "tyre": {"rolling_radius": 0.46, "width": 0.135},
        "contact": {"friction": 0.3, "model": "polach"},
        "damping": [0.01],
    }


def test_int_accepted_for_float_and_converted(tmp_path):
    text = replace_line(VALID, "rolling_radius = 0.46", "rolling_radius = 1")
    cfg = load(write(tmp_path, text), SCHEMA)
    assert cfg["tyre"]["rolling_radius"] == 1.0
    assert type(cfg["tyre"]["rolling_radius"]) is float


def test_bounds_inclusive_and_exclusive():
    f = Field(float, min=0, max=2, min_inclusive=False)
    data = {"x": 2}
    assert validate(data, {"x": f}, "t") == {"x": 2.0}  # max inclusive
    with pytest.raises(ConfigError):
        validate({"x": 0}, {"x": f}, "t")  # min exclusive
    g = Field(int, max=10, max_inclusive=False)
    assert validate({"x": 9}, {"x": g}, "t") == {"x": 9}
    with pytest.raises(ConfigError, match=r"value < 10"):
        validate({"x": 10}, {"x": g}, "t")


def test_validate_does_not_mutate_input_and_defaults_are_copies():
    data = {"name": "a", "boundary": "axle", "tyre": {"rolling_radius": 0.5}, "contact": {"friction": 0.1}}
    snapshot = repr(data)
    cfg1 = validate(data, SCHEMA, "t")
    cfg1["damping"].append(99.0)
    cfg2 = validate(data, SCHEMA, "t")
    assert repr(data) == snapshot
    assert cfg2["damping"] == [0.01]


def test_missing_table_with_all_defaults_is_filled_in():
    schema = {"solver": {"tol": Field(float, default=1e-10), "max_it": Field(int, default=100)}}
    assert validate({}, schema, "t") == {"solver": {"tol": 1e-10, "max_it": 100}}


def test_optional_none_default():
    schema = {"note": Field(str, default=None)}
    assert validate({}, schema, "t") == {"note": None}
    assert validate({"note": "x"}, schema, "t") == {"note": "x"}


# --------------------------------------------------------------------------
# One invalid value each: message names file, dotted key, value, allowed
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "old, new, key, value_repr, allowed",
    [
        # negative radius against a min bound > 0 (exclusive)
        ("rolling_radius = 0.46", "rolling_radius = -0.46", "tyre.rolling_radius", "-0.46",
         "a float in m, 0 < value <= 2"),
        # friction 7 against max 1.0
        ("friction = 0.3", "friction = 7", "contact.friction", "7", "a float, 0 <= value <= 1"),
        # a string where a number belongs
        ("rolling_radius = 0.46", 'rolling_radius = "0.46"', "tyre.rolling_radius", "'0.46'",
         "a float in m, 0 < value <= 2"),
        # a bool where a number belongs (bool is an int subclass in Python!)
        ("friction = 0.3", "friction = true", "contact.friction", "True",
         "a float, 0 <= value <= 1"),
        # a value not among the choices
        ('boundary = "clamped"', 'boundary = "clamp"', "boundary", "'clamp'",
         "one of ['clamped', 'axle']"),
        # nan is a float in TOML, but never a valid physical value here
        ("friction = 0.3", "friction = nan", "contact.friction", "nan",
         "a finite float, 0 <= value <= 1"),
    ],
)
def test_single_invalid_value(tmp_path, old, new, key, value_repr, allowed):
    err, path = load_error(tmp_path, replace_line(VALID, old, new))
    msg = str(err)
    assert path in msg
    assert key in msg
    assert value_repr in msg
    assert allowed in msg
    assert len(err.errors) == 1
    (issue,) = err.errors
    assert issue.key == key
    assert repr(issue.value) == value_repr
    assert issue.allowed == allowed


def test_missing_required_key(tmp_path):
    err, path = load_error(tmp_path, replace_line(VALID, "friction = 0.3\n", ""))
    msg = str(err)
    assert path in msg
    assert "contact.friction: required key is missing" in msg
    assert "a float, 0 <= value <= 1" in msg  # says what would be allowed
    assert err.errors == [("contact.friction", MISSING, err.errors[0].allowed)]
    assert err.errors[0].allowed.startswith("required key is missing")


def test_unknown_key_is_reported_with_suggestion(tmp_path):
    err, path = load_error(tmp_path, replace_line(VALID, "rolling_radius", "rolling_raduis"))
    msg = str(err)
    assert path in msg
    assert "tyre.rolling_raduis = 0.46" in msg
    assert "unknown key" in msg
    assert "did you mean 'rolling_radius'?" in msg
    # ... and the real key is then missing: both are reported.
    assert {e.key for e in err.errors} == {"tyre.rolling_raduis", "tyre.rolling_radius"}


def test_int_field_rejects_float_and_bool():
    schema = {"n": Field(int, min=1)}
    for bad in (3.0, True):
        with pytest.raises(ConfigError) as info:
            validate({"n": bad}, schema, "case.toml")
        assert info.value.errors == [("n", bad, "an integer, value >= 1")]


def test_bool_field_rejects_int():
    with pytest.raises(ConfigError, match=r"flag = 1 \(integer\): expected a boolean"):
        validate({"flag": 1}, {"flag": Field(bool)}, "t")


def test_table_expected_but_scalar_given():
    with pytest.raises(ConfigError) as info:
        validate({"tyre": 0.46}, {"tyre": {"rolling_radius": Field(float)}}, "t")
    assert info.value.errors[0].key == "tyre"
    assert "a table [tyre]" in info.value.errors[0].allowed


def test_list_of_length_and_items(tmp_path):
    # Top-level key, so it must come before the first [table] header.
    text = 'damping = [0.1, "x", -1, 2, 3]\n' + VALID
    err, path = load_error(tmp_path, text)
    by_key = {e.key: e for e in err.errors}
    assert set(by_key) == {"damping", "damping[1]", "damping[2]"}
    assert by_key["damping"].allowed == "a list of 1 to 4 items, each a float, value >= 0"
    assert by_key["damping[1]"].value == "x"
    assert by_key["damping[2]"].value == -1
    assert "damping[2] = -1 (integer): expected a float, value >= 0" in str(err)


def test_list_of_rejects_scalar():
    schema = {"f": ListOf(Field(float), min_len=2, max_len=2)}
    with pytest.raises(ConfigError) as info:
        validate({"f": 1.0}, schema, "t")
    assert info.value.errors == [("f", 1.0, "a list of exactly 2 items, each a float")]
    assert validate({"f": [1, 2.5]}, schema, "t") == {"f": [1.0, 2.5]}


# --------------------------------------------------------------------------
# Several errors: all reported together
# --------------------------------------------------------------------------


def test_all_errors_reported_together(tmp_path):
    text = """\
    name = "r920"
    boundary = "clamp"
    extra = 1

    [tyre]
    rolling_radius = -0.46

    [contact]
    friction = 7
    model = "hertz"
    """
    err, path = load_error(tmp_path, text)
    msg = str(err)
    expected = {
        "boundary": "'clamp'",
        "extra": "1",
        "tyre.rolling_radius": "-0.46",
        "contact.friction": "7",
        "contact.model": "'hertz'",
    }
    assert {e.key for e in err.errors} == set(expected)
    lines = msg.splitlines()
    assert lines[0] == f"{path}: 5 configuration errors:"
    assert len(lines) == 1 + len(expected)  # one line per problem
    for key, value in expected.items():
        assert any(line.strip().startswith(f"{key} = {value}") for line in lines[1:]), key
    assert "a float in m, 0 < value <= 2" in msg
    assert "one of ['kalker', 'polach']" in msg


def test_config_error_is_value_error_and_picklable(tmp_path):
    err, _ = load_error(tmp_path, replace_line(VALID, "friction = 0.3", "friction = 7"))
    assert isinstance(err, ValueError)
    clone = pickle.loads(pickle.dumps(err))
    assert str(clone) == str(err)
    assert clone.errors == err.errors


# --------------------------------------------------------------------------
# File-level problems
# --------------------------------------------------------------------------


def test_missing_file(tmp_path):
    path = tmp_path / "nope.toml"
    with pytest.raises(ConfigError, match="configuration file not found") as info:
        load(path, SCHEMA)
    assert str(path) in str(info.value)


def test_invalid_toml_names_file_and_line(tmp_path):
    path = write(tmp_path, 'name = "r920"\nboundary = \n')
    with pytest.raises(ConfigError) as info:
        load(path, SCHEMA)
    msg = str(info.value)
    assert msg.startswith(f"{path}: not valid TOML")
    assert "line 2" in msg


def test_non_utf8_file(tmp_path):
    path = tmp_path / "bin.toml"
    path.write_bytes(b"name = \"\xff\"\n")
    with pytest.raises(ConfigError, match="not valid TOML"):
        load(path, SCHEMA)


# --------------------------------------------------------------------------
# Schema definition errors are programming errors, raised early
# --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, exc",
    [
        (dict(kind=list), TypeError),
        (dict(kind=str, min=0), TypeError),
        (dict(kind=float, min=True), TypeError),
        (dict(kind=float, min=2, max=1), ValueError),
        (dict(kind=float, min=1, max=1, max_inclusive=False), ValueError),
        (dict(kind=float, max=1, default=2.0), ValueError),
        (dict(kind=str, choices=["a"], default="b"), ValueError),
        (dict(kind=int, choices=[1, True]), ValueError),
    ],
)
def test_bad_field_definitions(kwargs, exc):
    with pytest.raises(exc):
        Field(**kwargs)


def test_bad_list_definitions_and_schema_entries():
    with pytest.raises(ValueError):
        ListOf(Field(float, min=0), default=[-1.0])
    with pytest.raises(ValueError):
        ListOf(Field(float), min_len=3, default=[1.0])
    with pytest.raises(TypeError):
        ListOf(float)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        validate({}, {"x": float}, "t")
    assert Field(float).default is REQUIRED


# --------------------------------------------------------------------------
# config_hash
# --------------------------------------------------------------------------


def test_config_hash_is_stable_and_sensitive():
    a = {"tyre": {"rolling_radius": 0.46, "width": 0.135}, "name": "r920"}
    b = {"name": "r920", "tyre": {"width": 0.135, "rolling_radius": 0.46}}
    h = config_hash(a)
    assert h == config_hash(b)  # key order does not matter
    assert len(h) == 16 and int(h, 16) >= 0
    assert config_hash({**a, "name": "r921"}) != h
    # Known value: guards against accidental changes of the canonical form,
    # which would silently invalidate every cache.
    # sha256('{"a":1,"b":[1.5,"x"]}')[:16]
    assert config_hash({"b": [1.5, "x"], "a": 1}) == "253252306831c7a5"


def test_config_hash_int_and_float_fields_hash_alike_after_validation():
    schema = {"r": Field(float)}
    assert config_hash(validate({"r": 1}, schema, "t")) == config_hash(validate({"r": 1.0}, schema, "t"))


def test_config_hash_rejects_non_json_values():
    with pytest.raises(ValueError):
        config_hash({"x": float("nan")})
    with pytest.raises(TypeError):
        config_hash({"x": object()})
