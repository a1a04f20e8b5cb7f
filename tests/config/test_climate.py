"""The friction climate (pipeline/config/climate.py): the shipped files, one-line errors naming
file, key, value and range, and the sampler's statistics against the analytic distribution
(scipy.stats.truncnorm / uniform: moments and quantiles computed in closed form, not by sampling)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from pipeline.config.climate import CLIMATES, load_climate
from pipeline.config.loader import ConfigError
from solvers.contact.friction_laws import get_friction_law

BASE = '''name = "t"
[[condition]]
name = "dry"
share = 0.9
law = "coulomb"
mu_mean = 0.29
mu_sd = 0.029
mu_min = 0.23
mu_max = 0.35
[condition.source]
share = "s"
mu = "m"
[[condition]]
name = "wet"
share = 0.1
law = "polach"
shape = {mu0 = 0.30, A = 0.4, B = 0.2}
mu_range = [0.12, 0.17]
[condition.source]
share = "s"
mu = "m"
law = "l"
'''


def _write(tmp_path, text, name="c.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


def _edit(*subs):
    text = BASE
    for old, new in subs:
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


# -- the shipped climates --------------------------------------------------------------------

@pytest.mark.parametrize("name", ["default", "dry_only", "tor_fm"])
def test_shipped_climates_load_with_a_source_for_every_number(name):
    c = load_climate(name)
    assert abs(math.fsum(c.shares) - 1.0) <= 1e-6
    for cond in c.conditions:
        assert cond.source.share and cond.source.mu
        assert cond.law == "coulomb" or cond.source.law
        assert 0.0 < cond.lo < cond.hi < 1.0


def test_shipped_files_are_the_files_of_the_folder():
    assert sorted(p.stem for p in CLIMATES.glob("*.toml")) == ["default", "dry_only", "tor_fm"]


def test_default_dry_level_is_chollets_published_range_and_spread():
    # Chollet (DYNOTRAIN, IAVSD 2017 book ch. 45, abstract): 0.23-0.35 in dry conditions, normal law, sd ~10 %
    dry = load_climate("default").condition("dry")
    assert (dry.mu_min, dry.mu_max) == (0.23, 0.35)
    assert dry.mu_sd == pytest.approx(0.10 * dry.mu_mean)
    assert dry.mu_mean == pytest.approx(0.5 * (0.23 + 0.35))
    # the observed range is the mean +- 2 sd of that normal law
    assert (dry.mu_max - dry.mu_mean) / dry.mu_sd == pytest.approx(2.0, abs=0.1)


def test_default_names_what_it_assumes():
    assumed = load_climate("default").assumed()
    assert {"dry.share", "humid.share", "humid.mu", "wet.mu", "leaves.share"} == set(assumed)
    assert "wet.share" not in assumed and "dry.mu" not in assumed   # Trenberth & Zhang 2018; Chollet


# -- errors: one line, the file, the key, the value, what is allowed ----------------------------

ERRORS = [
    ("shares", [("share = 0.9", "share = 0.8")], "condition[*].share", "0.9", "sum"),
    ("mu_max", [("mu_max = 0.35", "mu_max = 1.2")], "condition[0].mu_max", "1.2", "< value < 1"),
    ("mu_min", [("mu_min = 0.23", "mu_min = 0")], "condition[0].mu_min", "0", "0 < value < 1"),
    ("order", [("mu_min = 0.23", "mu_min = 0.4")], "condition[0].mu_max", "0.35", "mu_min (0.4) < value"),
    ("mean", [("mu_mean = 0.29", "mu_mean = 0.5")], "condition[0].mu_mean", "0.5", "mu_max (0.35)"),
    ("sd", [("mu_sd = 0.029", "mu_sd = -0.1")], "condition[0].mu_sd", "-0.1", "0 < value < 1"),
    ("range", [("[0.12, 0.17]", "[0.17, 0.12]")], "condition[1].mu_range", "[0.17, 0.12]", "0 < a < b < 1"),
    ("range_one", [("[0.12, 0.17]", "[0.12, 1.5]")], "condition[1].mu_range", "[0.12, 1.5]", "0 < a < b < 1"),
    ("law", [('law = "coulomb"', 'law = "stribeck"')], "condition[0].law", "'stribeck'", "'polach'"),
    ("shape_coulomb", [('law = "coulomb"', 'law = "coulomb"\nshape = {mu = 0.3}')], "condition[0].shape",
     "{'mu': 0.3}", "no shape"),
    ("shape_range", [("A = 0.4", "A = 1.4")], "condition[1].shape", "'A': 1.4", "0 < A <= 1"),
    ("scaled", [('law = "coulomb"', 'law = "hpf"'),
                ('share = "s"\nmu = "m"\n[[', 'share = "s"\nmu = "m"\nlaw = "x"\n[['),
                ("mu_max = 0.35", "mu_max = 0.9"), ("mu_mean = 0.29", "mu_mean = 0.5")],
     "condition[0].mu_max", "0.9", "fkin = 1.26"),
    ("typo", [("mu_sd = 0.029", "mu_sdd = 0.029")], "condition[0].mu_sdd", "0.029", "did you mean 'mu_sd'"),
    ("type", [("share = 0.9", 'share = "0.9"')], "condition[0].share", "'0.9'", "0 < value <= 1"),
    ("bool", [("share = 0.9", "share = true")], "condition[0].share", "True", "0 < value <= 1"),
    ("duplicate", [('name = "wet"', 'name = "dry"')], "condition[1].name", "'dry'", "not used before"),
    ("source", [('law = "l"\n', "")], "condition[1].source.law", "", "required key is missing"),
]


@pytest.mark.parametrize("case, subs, key, value, allowed", ERRORS, ids=[e[0] for e in ERRORS])
def test_an_invalid_climate_is_one_line_naming_file_key_value_range(tmp_path, case, subs, key, value, allowed):
    path = _write(tmp_path, _edit(*subs))
    with pytest.raises(ConfigError) as err:
        load_climate(path)
    text = str(err.value)
    assert "\n" not in text, text
    assert text.startswith(f"{path}: {key}"), text
    assert value in text and allowed in text, text


def test_a_missing_file_and_bad_toml_name_the_file(tmp_path):
    with pytest.raises(ConfigError, match=r"nowhere\.toml: climate file not found .*'default'"):
        load_climate(tmp_path / "nowhere.toml")
    with pytest.raises(ConfigError, match=r"c\.toml: not valid TOML"):
        load_climate(_write(tmp_path, BASE.replace("share = 0.9", "share = ")))


def test_the_base_file_is_valid_and_frozen(tmp_path):
    c = load_climate(_write(tmp_path, BASE))
    assert c.names == ("dry", "wet")
    with pytest.raises(Exception):
        c.conditions[0].share = 0.5


# -- the law at a level ----------------------------------------------------------------------

def test_a_falling_law_is_scaled_to_its_static_level_with_its_shape_kept(tmp_path):
    wet = load_climate(_write(tmp_path, BASE)).condition("wet")
    name, params = wet.law_params(0.15)
    law = get_friction_law(name, **params)
    assert law.mu_static == pytest.approx(0.15, rel=1e-12)          # mu(0) of the numba law
    assert (params["A"], params["B"]) == (0.4, 0.2)                 # Polach's shape kept
    s = np.array([0.0, 0.1, 1.0, 10.0])                             # the law is the reference law x 0.5
    assert law.mu(s) == pytest.approx(0.5 * get_friction_law("polach", mu0=0.3, A=0.4, B=0.2).mu(s), rel=1e-12)


def test_a_rising_modifier_law_takes_its_kinetic_level():
    fm = load_climate("tor_fm").condition("tor_fm")
    name, params = fm.law_params(0.2)
    law = get_friction_law(name, **params)
    assert name == "linear"
    assert law.mu(np.array([5.0]))[0] == pytest.approx(0.2, rel=1e-12)   # beyond 2 sabsh1 = 0.5 m/s: fkin
    assert law.mu_static == pytest.approx(0.2 * 0.25 / 0.35, rel=1e-12)   # the preset's ratio 0.25 / 0.35 kept


# -- the sampler against the analytic distribution -------------------------------------------

def _sampler_climate(tmp_path, mean, sd, lo, hi):
    text = _edit(("mu_mean = 0.29", f"mu_mean = {mean}"), ("mu_sd = 0.029", f"mu_sd = {sd}"),
                 ("mu_min = 0.23", f"mu_min = {lo}"), ("mu_max = 0.35", f"mu_max = {hi}"),
                 ("share = 0.9", "share = 0.7"), ("share = 0.1", "share = 0.3"))
    return load_climate(_write(tmp_path, text))


@pytest.mark.parametrize("mean, sd, lo, hi", [(0.29, 0.05, 0.23, 0.33),      # asymmetric truncation
                                              (0.29, 0.029, 0.23, 0.35)],    # Chollet's dry: +- 2 sd
                         ids=["asymmetric", "dry"])
def test_sampler_matches_the_analytic_truncated_normal_and_uniform(tmp_path, mean, sd, lo, hi):
    c = _sampler_climate(tmp_path, mean, sd, lo, hi)
    n = 400_000
    index, mu = c.sample(n, rng=20260531)
    # shares: binomial counts within 5 standard errors
    for i, share in enumerate(c.shares):
        k = np.count_nonzero(index == i)
        assert abs(k - n * share) < 5 * math.sqrt(n * share * (1 - share))
    refs = [stats.truncnorm((lo - mean) / sd, (hi - mean) / sd, loc=mean, scale=sd), stats.uniform(0.12, 0.05)]
    for i, ref in enumerate(refs):
        x = mu[index == i]
        m, v, _, kurt = (float(q) for q in ref.stats(moments="mvsk"))
        se_mean = math.sqrt(v / x.size)
        se_sd = math.sqrt((kurt + 2.0) * v * v / x.size) / (2.0 * math.sqrt(v))   # var(s^2) = (mu4 - v^2) / n
        assert abs(x.mean() - m) < 5 * se_mean, (x.mean(), m)
        assert abs(x.std() - math.sqrt(v)) < 5 * se_sd, (x.std(), math.sqrt(v))
        for p in (0.05, 0.25, 0.5, 0.75, 0.95):
            q = ref.ppf(p)
            se_q = math.sqrt(p * (1 - p) / x.size) / ref.pdf(q)
            assert abs(np.quantile(x, p) - q) < 5 * se_q, (p, np.quantile(x, p), q)
        assert ref.ppf(0.0) <= x.min() and x.max() <= ref.ppf(1.0)


def test_the_inverse_distribution_is_the_analytic_one(tmp_path):
    c = _sampler_climate(tmp_path, 0.29, 0.05, 0.23, 0.33)
    p = np.linspace(0.0, 1.0, 101)
    ref = stats.truncnorm((0.23 - 0.29) / 0.05, (0.33 - 0.29) / 0.05, loc=0.29, scale=0.05)
    assert c.condition("dry").quantile(p) == pytest.approx(ref.ppf(p), abs=1e-12)
    assert c.condition("wet").quantile(p) == pytest.approx(0.12 + 0.05 * p, abs=1e-15)


def test_the_sampler_is_deterministic_with_a_seed(tmp_path):
    c = load_climate("default")
    i1, mu1 = c.sample(1000, rng=7)
    i2, mu2 = c.sample(1000, rng=np.random.default_rng(7))
    i3, mu3 = c.sample(1000, rng=8)
    assert np.array_equal(i1, i2) and np.array_equal(mu1, mu2)
    assert not np.array_equal(mu1, mu3)
    i0, mu0 = c.sample(0, rng=7)
    assert i0.shape == mu0.shape == (0,)
