"""The friction-law registry (solvers.contact.friction_laws): each law against its formula
as printed in CONTACT's user guide (Vollebregt, sec. 'Slip velocity dependent friction')
and Polach 2005, at chosen slip speeds; the numba evaluator against the methods; the
registry's one-line errors."""
import math

import numpy as np
import pytest

from solvers.contact.friction_laws import (LAWS, PRESETS, FrictionLaw, as_law, dmu_of, from_table,
                                           get_friction_law, mu_of, preset)

S = np.array([0.0, 0.01, 0.2, 0.5, 1.0, 2.5, 7.0])      # slip speeds [m/s]


def test_coulomb_is_constant():
    law = get_friction_law("coulomb", mu=0.3)
    assert np.all(law.mu(S) == 0.3) and np.all(law.dmu(S) == 0.0)
    assert law.code == 0 and list(law.array) == [0.3] and law.is_coulomb
    assert as_law(0.3) == law and as_law(law) is law


def test_linear_law_formula():
    # mu = fkin + flin1 max(0, 1 - s/(2 sh1)) + flin2 max(0, 1 - s/(2 sh2)), sh in mm/s
    law = get_friction_law("linear", fkin=0.2, flin1=0.15, sabsh1=500.0, flin2=0.05, sabsh2=2000.0)
    want = 0.2 + 0.15 * np.maximum(0, 1 - S / 1.0) + 0.05 * np.maximum(0, 1 - S / 4.0)
    np.testing.assert_allclose(law.mu(S), want, rtol=1e-14)
    assert law.mu(0.5) == pytest.approx(0.2 + 0.075 + 0.05 * 0.875, rel=1e-14)
    assert law.dmu(0.5) == pytest.approx(-0.15 / 1.0 - 0.05 / 4.0, rel=1e-14)
    assert law.dmu(2.0) == pytest.approx(-0.05 / 4.0, rel=1e-14) and law.dmu(5.0) == 0.0
    assert law.mu_static == pytest.approx(0.4) and law.code == 2


def test_rational_law_formula():
    law = get_friction_law("rational", fkin=0.1, frat1=0.2, sabsh1=300.0, frat2=0.05, sabsh2=800.0)
    want = 0.1 + 0.2 / (1 + S / 0.3) + 0.05 / (1 + (S / 0.8) ** 2)
    np.testing.assert_allclose(law.mu(S), want, rtol=1e-14)
    h = 1e-6
    np.testing.assert_allclose(law.dmu(S[1:]), (law.mu(S[1:] + h) - law.mu(S[1:] - h)) / (2 * h), rtol=1e-6)


def test_exponential_law_halves_at_sabsh():
    law = get_friction_law("exponential", fkin=0.14, fexp1=0.19, sabsh1=1250.0)
    assert law.mu(1.25) == pytest.approx(0.14 + 0.095, rel=1e-14)      # the term halves at s = sabsh1
    np.testing.assert_allclose(law.mu(S), 0.14 + 0.19 * np.exp(-math.log(2) * S / 1.25), rtol=1e-14)
    np.testing.assert_allclose(law.dmu(S), -0.19 * math.log(2) / 1.25 * np.exp(-math.log(2) * S / 1.25),
                               rtol=1e-13)
    assert law.params == {"fkin": 0.14, "fexp1": 0.19, "sabsh1": 1250.0, "fexp2": 0.0, "sabsh2": 10000.0,
                          "memdst": 0.0, "mem_s0": 10.0}
    assert law.memory == (0.0, 0.01)


def test_polach_law_and_contact_equivalence():
    law = get_friction_law("polach", mu0=0.36, A=0.38, B=0.7)
    np.testing.assert_allclose(law.mu(S), 0.36 * ((1 - 0.38) * np.exp(-0.7 * S) + 0.38), rtol=1e-14)
    # CONTACT's user guide: fkin = A mu0, fexp1 = (1 - A) mu0, sabsh1 = ln2 / B (mm/s); its tractcurv
    # example prints these rounded (0.1368, 0.2232, 990.)
    expo = get_friction_law("exponential", fkin=0.38 * 0.36, fexp1=0.62 * 0.36, sabsh1=1e3 * math.log(2) / 0.7)
    np.testing.assert_allclose(law.mu(S), expo.mu(S), rtol=1e-13)
    np.testing.assert_allclose(law.dmu(S), expo.dmu(S), rtol=1e-12)
    rounded = preset("contact_polach")
    np.testing.assert_allclose(rounded.mu(S), law.mu(S), rtol=5e-3)


def test_numba_evaluator_matches_methods():
    for key in PRESETS:
        law = preset(key)
        for s in S:
            assert mu_of(law.code, law.array, s) == law.mu(s)
            assert mu_of(law.code, law.array, -s) == law.mu(s)          # |s|
            assert dmu_of(law.code, law.array, s) == law.dmu(s)


def test_positive_friction_presets_rise():
    for key in ("hpf", "vhpf"):
        law = preset(key)
        assert np.all(np.diff(law.mu(S)) >= 0) and law.mu(S[-1]) > law.mu_static
        assert PRESETS[key]["assumed"] and "Eadie" in PRESETS[key]["source"]


def test_every_law_documented():
    for name, law in LAWS.items():
        assert law.name == name and law.reference and law.formula
        for p in law.params:
            assert p.unit and p.doc and p.lo < p.hi


def test_unknown_law_lists_known():
    with pytest.raises(ValueError, match=r"unknown friction law 'stribeck'; known: coulomb, exponential, "
                                         r"linear, polach, rational"):
        get_friction_law("stribeck", mu=0.3)


def test_missing_parameter_named():
    with pytest.raises(ValueError, match=r"'exponential': missing parameter 'sabsh1' \[mm/s\]"):
        get_friction_law("exponential", fkin=0.14, fexp1=0.19)


def test_out_of_range_parameter_named():
    with pytest.raises(ValueError, match=r"'polach': A = 1.5 out of range 0 < A <= 1"):
        get_friction_law("polach", mu0=0.5, A=1.5, B=0.6)
    with pytest.raises(ValueError, match=r"'coulomb': mu = 0 out of range 0 < mu <= 1"):
        get_friction_law("coulomb", mu=0)
    with pytest.raises(ValueError, match=r"'linear': sabsh1 = -3.0 out of range"):
        get_friction_law("linear", fkin=0.2, flin1=0.1, sabsh1=-3.0)
    with pytest.raises(ValueError, match=r"'linear': unknown parameter 'fexp1'"):
        get_friction_law("linear", fkin=0.2, fexp1=0.1, sabsh1=3.0)
    with pytest.raises(ValueError, match=r"mu\(0\) = 1.2 out of range"):
        get_friction_law("exponential", fkin=0.7, fexp1=0.5, sabsh1=100.0)
    with pytest.raises(ValueError, match=r"'rational': mu\(s\) reaches -0.1"):
        get_friction_law("rational", fkin=0.2, frat1=-0.3, sabsh1=100.0, frat2=0.5)
    with pytest.raises(ValueError, match=r"mu = 'x' is not a number"):
        get_friction_law("coulomb", mu="x")
    with pytest.raises(ValueError, match=r"unknown friction preset 'oily'"):
        preset("oily")


def test_presets_by_name():
    assert get_friction_law("hpf") == preset("hpf")
    assert isinstance(preset("polach_dry"), FrictionLaw)


def test_case_file_table():
    assert from_table({"mu": 0.3}) == get_friction_law("coulomb", mu=0.3)
    assert from_table({"law": "polach", "mu0": 0.5, "A": 0.4, "B": 0.6}).code == 5
    assert from_table({"preset": "hpf"}) == preset("hpf")
    with pytest.raises(ValueError, match=r"preset = 'hpf' stands alone; remove mu"):
        from_table({"preset": "hpf", "mu": 0.3})
    with pytest.raises(ValueError, match=r"'coulomb': missing parameter 'mu'"):
        from_table({})
