"""Onset and climate risk (issue 32): the pure numerics against closed forms and a second method.

* ``find_onset`` on growth functions with a known first zero crossing (and none, and one below the range);
* ``exceedance`` / ``risk.p_exceed`` of a climate of uniform conditions against the closed form
  P(mu > x) = sum_c w_c clip((b_c - x) / (b_c - a_c), 0, 1), and of the shipped default climate
  (truncated normals) against the climate's own sampler (``Climate.sample``, 400 000 samples);
* ``risk.median_level`` against the closed-form median of a uniform condition through a linear table.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.config.climate import load_climate
from pipeline.curve import risk
from solvers.stability.onset import exceedance, find_onset, unstable_windows, weighted_median

UNIFORM = """name = "u2"
[[condition]]
name = "dry"
share = 0.6
mu_range = [0.3, 0.5]
[condition.source]
share = "test"
mu = "test"
[[condition]]
name = "wet"
share = 0.4
mu_range = [0.1, 0.2]
[condition.source]
share = "test"
mu = "test"
"""


def test_find_onset_first_crossing():
    # two humps: the first upward zero crossing at 0.3137, a second window above 0.6
    g = lambda mu: (mu - 0.3137) * 100 if mu < 0.45 else (mu - 0.6) * 50   # noqa: E731
    on = find_onset(g, 0.1, 0.8, 7, xtol=1e-6)
    assert on.mu == pytest.approx(0.3137, abs=1e-5) and not on.below and on.text() == "0.3137"
    assert find_onset(lambda mu: -1.0 - mu, 0.1, 0.8).text() == ">0.8"
    assert find_onset(lambda mu: 1.0, 0.1, 0.8).text() == "<0.1"


def test_find_onset_quiet_levels_skip_growth():
    """A cheap ``quiet`` test (true where growth <= 0) gives the same onset, the same bits, with growth
    evaluated only at the bracket's upper level and by brentq."""
    g = lambda mu: (mu - 0.3137) * 100 if mu < 0.45 else (mu - 0.6) * 50   # noqa: E731
    asked = []

    def counted(mu):
        asked.append(mu)
        return g(mu)

    full = find_onset(g, 0.1, 0.8, 7, xtol=1e-6)
    fast = find_onset(counted, 0.1, 0.8, 7, xtol=1e-6, quiet=lambda mu: g(mu) <= 0)
    assert fast.mu == full.mu and fast.evaluations < full.evaluations
    assert min(asked) == pytest.approx(0.3) and 0.1 not in asked and 0.2 not in asked
    assert find_onset(lambda mu: -1.0 - mu, 0.1, 0.8, quiet=lambda mu: True).text() == ">0.8"


def test_unstable_windows_of_two_humps():
    """Growing on (0.3137, 0.45) and again above 0.6: both windows, the second open; cut at a top level;
    a monotonic growth's single window is (onset, inf) with the onset's own bits."""
    g = lambda mu: (mu - 0.3137) * 100 if mu < 0.45 else (mu - 0.6) * 50   # noqa: E731
    on = find_onset(g, 0.1, 0.8, 7, xtol=1e-6)
    (a1, b1), (a2, b2) = unstable_windows(g, on, 0.8, 7, xtol=1e-6, quiet=lambda mu: g(mu) <= 0)
    assert (a1, b2) == (on.mu, math.inf) and b1 == pytest.approx(0.45, abs=1e-5) and a2 == pytest.approx(0.6, abs=1e-5)
    assert unstable_windows(g, on, 0.5, 7, xtol=1e-6) == ((on.mu, b1),)
    mono = find_onset(lambda mu: mu - 0.33, 0.1, 0.8, 7)
    assert unstable_windows(lambda mu: mu - 0.33, mono, 0.8, 7) == ((mono.mu, math.inf),)
    assert unstable_windows(lambda mu: 1.0, find_onset(lambda mu: 1.0, 0.1, 0.8, 7), 0.8, 7) == ((0.1, math.inf),)
    assert unstable_windows(lambda mu: -1.0, find_onset(lambda mu: -1.0, 0.1, 0.8, 7), 0.8, 7) == ()


def test_exceedance_uniform_closed_form(tmp_path):
    f = tmp_path / "u2.toml"
    f.write_text(UNIFORM)
    c = load_climate(f)
    for x in (0.05, 0.15, 0.25, 0.35, 0.5, 0.7):
        want = 0.6 * np.clip((0.5 - x) / 0.2, 0, 1) + 0.4 * np.clip((0.2 - x) / 0.1, 0, 1)
        assert risk.p_exceed(c, x) == pytest.approx(want, abs=1e-12)
    assert risk.p_exceed(c, math.inf) == 0.0


def test_exceedance_default_climate_against_sampling():
    c = load_climate("default")
    _, mu = c.sample(400_000, rng=7)
    for x in (0.12, 0.2, 0.27, 0.3, 0.33):
        p = risk.p_exceed(c, x)
        sd = math.sqrt(p * (1 - p) / mu.size)
        assert abs(p - np.mean(mu > x)) < 5 * sd + 1e-9, (x, p, np.mean(mu > x))


def test_median_level_uniform(tmp_path):
    # one uniform condition [0.2, 0.6], onset 0.3: levels above are uniform on [0.3, 0.6], median 0.45;
    # through the linear table L = 90 + 20 (mu - 0.3): median 93 dB
    f_text = UNIFORM.replace("share = 0.6\nmu_range = [0.3, 0.5]", "share = 1.0\nmu_range = [0.2, 0.6]")
    f_text = f_text[:f_text.index('[[condition]]\nname = "wet"')]
    (tmp_path / "u1.toml").write_text(f_text)
    c = load_climate(tmp_path / "u1.toml")
    table = [{"mu": m, "squeals": True, "L_pA": 90 + 20 * (m - 0.3)} for m in (0.3, 0.45, 0.6)]
    assert risk.median_level(c, 0.3, table) == pytest.approx(93.0, abs=0.05)
    assert risk.p_exceed(c, 0.3) == pytest.approx(0.75)
    assert weighted_median([3, 1, 2], [1, 1, 1]) == 2


def test_curve_shares():
    c = load_climate("default")
    on = {"a1o": math.inf, "a1i": 0.25, "a2o": math.inf, "a2i": 0.3}
    s = risk.curve_risk(c, on)
    assert s["passages"] == pytest.approx(risk.p_exceed(c, 0.25))
    assert s["axles"] == pytest.approx(0.5 * (risk.p_exceed(c, 0.25) + risk.p_exceed(c, 0.3)))
    assert exceedance(0.0, [1.0], [0.1], [0.2]) == 1.0


def test_curve_names_its_climate(tmp_path):
    """A curve's ``[friction] climate`` (a shipped name or a path beside the curve file) is the risk's
    climate, not a friction parameter (the wheels' cases keep the law alone); none named: 'default';
    an unknown one: one ConfigError naming the climate file."""
    from pipeline.config.curve_inputs import read_curve
    from pipeline.config.loader import ConfigError
    from pipeline.store.paths import ROOT

    text = (ROOT / "pipeline" / "curves" / "r75.toml").read_text()
    (tmp_path / "c20_metro.toml").write_text((ROOT / "geometry" / "vehicles" / "c20_metro.toml").read_text())
    (tmp_path / "u2.toml").write_text(UNIFORM)
    for name, want in (('"dry_only"', "dry_only"), ('"u2.toml"', "u2")):
        (tmp_path / "c.toml").write_text(text.replace("\nmu = 0.35\n", f"\nmu = 0.35\nclimate = {name}\n"))
        c = read_curve(tmp_path / "c.toml")
        assert risk.curve_climate(c).name == want and c.friction.params == {"mu": 0.35}
    assert risk.curve_climate(read_curve("r75")).name == "default"
    (tmp_path / "c.toml").write_text(text.replace("\nmu = 0.35\n", '\nmu = 0.35\nclimate = "nowhere"\n'))
    with pytest.raises(ConfigError, match="nowhere.toml"):
        risk.curve_climate(read_curve(tmp_path / "c.toml"))


def test_make_check_refuses_an_unknown_climate_naming_the_key(tmp_path):
    """`make check CURVE=` refuses what the curve stage would refuse before its work: an unknown climate, in one
    line naming the curve file, the key and the value."""
    from pipeline.config.loader import ConfigError
    from pipeline.curve.check import check_curve
    from pipeline.store.paths import ROOT

    text = (ROOT / "pipeline" / "curves" / "r75.toml").read_text()
    (tmp_path / "c20_metro.toml").write_text((ROOT / "geometry" / "vehicles" / "c20_metro.toml").read_text())
    (tmp_path / "c.toml").write_text(text.replace("\nmu = 0.35\n", '\nmu = 0.35\nclimate = "nowhere"\n'))
    with pytest.raises(ConfigError) as e:
        check_curve(str(tmp_path / "c.toml"))
    msg = str(e.value)
    assert "\n" not in msg and "c.toml" in msg and "friction.climate = 'nowhere'" in msg
