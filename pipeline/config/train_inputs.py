"""The noun ``Train`` of a validated vehicle file (its [bogie] and [train], ``train_schemas``), with the
checks a single key's range cannot make, each a one-line ConfigError naming file, key, value and range."""
from __future__ import annotations

from pipeline.config.loader import ConfigError
from pipeline.config.nouns import Train


def train_of(data: dict, source) -> Train:
    """Train(bogie spacing, wheelbase, cars, car length) of a validated vehicle file ``data``."""
    b, t = data["bogie"], data.get("train") or {"cars": 1, "car_length_m": None}
    cars, length = int(t["cars"]), t["car_length_m"]
    least = b["bogie_spacing_m"] + b["wheelbase_m"]
    if cars > 1 and length is None:
        raise ConfigError(str(source), [("train.car_length_m", None, f"a car length >= {least:g} m (bogie_spacing_m + "
                                         f"wheelbase_m) when train.cars = {cars} > 1")])
    if length is not None and length < least:
        raise ConfigError(str(source), [("train.car_length_m", length, f">= {least:g} m (bogie_spacing_m + "
                                         "wheelbase_m: the cars' bogies must not overlap), <= 60 m")])
    return Train(b["bogie_spacing_m"], b["wheelbase_m"], cars, length)
