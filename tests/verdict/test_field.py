"""The field table's bookkeeping (pipeline/validation/field.py): what each observation states, which
levels are compared with the tool's and how, and the frequency difference, against hand-worked values."""
import math

from pipeline.validation import field as F


def obs(**kw):
    base = {"radius_m": None, "speed_kmh": None, "f_hz": None, "level": None, "L_7p5": None, "squeal": True}
    base.update(kw)
    return base


def verdict(squeals=True, f=435.0, L_pA=87.1):
    return {"squeals": squeals, "wheel": "a1i", "f": f if squeals else math.nan, "mode": "(2,0,a)",
            "L_pA": L_pA if squeals else math.nan, "V": 15.0}


def test_stated_marks_each_quantity():
    assert F.stated(obs(radius_m=25.0, speed_kmh="10-15", level="80.5 dB(A) at 7.5 m")) == "R V - L"
    assert F.stated(obs(f_hz="780-800")) == "- - f -"
    assert F.complete(obs(radius_m=25.0, speed_kmh=12.0, f_hz="1500", level="80 dB(A) at 7.5 m"))
    assert not F.complete(obs(radius_m=25.0, speed_kmh=12.0, level="80 dB(A) at 7.5 m"))
    # a relative level (an increase over rolling noise, a reduction) is marked 'l' and is not complete
    rel = obs(radius_m=25.0, speed_kmh=12.0, f_hz="1500", level="8 dB(A) above rolling noise", level_partial=True)
    assert F.stated(rel) == "R V f l" and not F.complete(rel)


def test_level_compared_only_at_7p5_m():
    # 87.1 - 80.5 = +6.6 dB, no conversion
    o = obs(level="80.5 dB(A) at 7.5 m", L_7p5=80.5)
    assert F.level_difference(o, verdict()) == "+6.6 dB (tool - measured)"
    # a level at the wheel or another metric is never converted
    near = obs(level="130 dB at 0.9 m from the wheel")
    assert F.level_difference(near, verdict()).startswith("not compared")
    assert F.level_difference(o, verdict(squeals=False)).startswith("not compared")
    assert F.level_difference(obs(), verdict()) == "-"
    # a measured range: the distance to the nearer bound (87.1 - 100 = -12.9 dB), or inside it
    rng = obs(level="100-105 dB(A) at 7.5 m", L_7p5=(100.0, 105.0))
    assert F.level_difference(rng, verdict()) == "-12.9 dB from the measured range 100-105 dB(A)"
    assert F.level_difference(rng, verdict(L_pA=107.5)) == "+2.5 dB from the measured range 100-105 dB(A)"
    assert F.level_difference(rng, verdict(L_pA=101.0)).startswith("inside the measured range")
    assert F.level_compared(rng, verdict()) and not F.level_compared(rng, verdict(squeals=False))


def test_frequency_difference_from_the_measured_range():
    o = obs(f_hz="780-800")
    assert "f -345 Hz" in F.difference(o, verdict(f=435.0))          # 435 - 780
    assert "f inside" in F.difference(o, verdict(f=790.0))
    assert F.difference(obs(squeal=False), verdict(squeals=False)) == "agree: no squeal"
    assert F.difference(obs(), verdict(squeals=False)).startswith("the source reports squeal")


def test_every_observation_is_cited_and_modelled():
    keys = [o["key"] for o in F.OBSERVATIONS]
    assert len(keys) == len(set(keys)) >= 10
    for o in F.OBSERVATIONS:
        assert o["source"] and o["model"] and o["model"][0] in ("r150", "y25_r300")
        if o["L_7p5"] is not None:              # a compared level is A-weighted at 7.5 m, as the source says
            assert "dB(A)" in o["level"] and "7.5 m" in o["level"]
