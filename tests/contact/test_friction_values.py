"""Friction curves at any value (issue 26): built per value on the contact, cached by value
(pipeline.caches.friction_curves), selected by law and value (solvers.timeloop.inputs.contact_model)."""
import numpy as np
import pytest

from pipeline.caches.friction_curves import CurveCache, Friction, curve_arrays, entries_of, with_curves
from solvers.contact.friction import rf_curve
from solvers.contact.norm import approach_for_load
from solvers.timeloop.inputs import contact_model, curve_label
from pipeline.validation.references.contact import E, NU, V, hertz_case

D = 1e-3                                     # 1 mm grid: fast


@pytest.fixture(scope="module")
def static():
    _, _, h, _ = hertz_case(dx=D, dy=D)
    _, ns = approach_for_load(65e3, h, D, D)
    return ns.p


def _contact(p3, frictions, curves, extra=()):
    """A contact artifact's arrays (the keys the curves need) with the given curves (and the
    entries ``extra``: (label, mu, law, curve))."""
    return {"p3_static": p3, "dx": np.float64(D), "dy": np.float64(D), "speed": np.float64(V),
            "material_E": np.float64(E), "material_nu": np.float64(NU),
            "xi3_nodes": np.linspace(0, 1e-4, 5), "q_nodes": np.linspace(0, 1.0, 5), "A1_nodes": np.ones(5),
            "A2_nodes": np.ones(5)} | curve_arrays(entries_of(frictions, curves) + list(extra))


def test_cached_curve_is_rf_curve_bit_for_bit_and_built_once(static, tmp_path):
    """A new value costs one curve: the cache computes it with rf_curve (the same numbers, bit for
    bit, as the direct call), and the second request reads it back."""
    cache = CurveCache(tmp_path / "friction")
    ref = rf_curve(static, D, D, V, 0.33, E, NU)
    first = cache(static, D, D, V, Friction.coulomb(0.33), E, NU)
    second = cache(static, D, D, V, Friction.coulomb(0.33), E, NU)
    assert (cache.built, cache.reused) == (1, 1) and len(list((tmp_path / "friction").glob("*.npz"))) == 1
    for k in ("s", "mu_rf", "slope", "gamma"):
        assert np.array_equal(first[k], getattr(ref, k)) and np.array_equal(second[k], getattr(ref, k))
    assert float(second["gamma_sat"]) == ref.gamma_sat
    # another contact (a different pressure field) is another key: not taken from the cache
    cache(static * 1.01, D, D, V, Friction.coulomb(0.33), E, NU)
    assert (cache.built, cache.reused) == (2, 1)


def test_curve_between_its_neighbours_and_self_similar(static, tmp_path):
    """mu = 0.33 (not on the old 0.05 grid): its curve lies between those of 0.30 and 0.35 at every
    slip speed, and, with no spin, mu_RF(s; mu) / mu = f(s / mu) (the problem is self-similar):
    against the curve at 0.30 evaluated at s * 0.30 / 0.33 by the same interpolant."""
    from solvers.contact.friction import mu_rf

    cache = CurveCache(tmp_path)
    c30, c33, c35 = (cache(static, D, D, V, Friction.coulomb(m), E, NU) for m in (0.30, 0.33, 0.35))
    s = np.linspace(0, c33["s"][-1], 2001)
    m = {k: np.array([mu_rf(x, c["s"], c["mu_rf"], c["slope"]) for x in s]) for k, c in
         (("30", c30), ("33", c33), ("35", c35))}
    # equal in the linear (no-slip) start, where the interpolants differ by ~1e-6
    assert np.all(m["30"] <= m["33"] + 1e-5) and np.all(m["33"] <= m["35"] + 1e-5)
    assert np.all(m["30"][-500:] < m["33"][-500:]) and np.all(m["33"][-500:] < m["35"][-500:])
    assert m["33"][-1] == pytest.approx(0.33, rel=1e-4)
    scaled = np.array([mu_rf(x * 0.30 / 0.33, c30["s"], c30["mu_rf"], c30["slope"]) for x in s]) / 0.30
    assert np.allclose(m["33"] / 0.33, scaled, atol=2e-3)


def test_contact_model_selects_by_law_and_value(static):
    class Law:                                   # anything with .name and .params (a FrictionLaw)
        name, params = "linear", {"fkin": 0.3, "flin1": 0.1, "sabsh1": 300.0}

    fr = [Friction.coulomb(0.3), Friction.coulomb(0.33), Friction.of("linear", Law.params)]
    curves = [{"s": np.array([0.0, 0.1 * i + 0.1]), "mu_rf": np.array([0.0, 0.3 + i]), "slope": np.zeros(2),
               "gamma_sat": 0.01 * i} for i in range(3)]
    arrays = _contact(static, fr[:2], curves[:2], [(fr[2].label, 0.4, "linear", curves[2])])
    assert list(arrays["rf_label"]) == ["coulomb(mu=0.3)", "coulomb(mu=0.33)", fr[2].label]
    assert fr[2].label.startswith("linear(fkin=0.3, flin1=0.1, sabsh1=300")
    assert contact_model(arrays, 0.33).mu_nodes[-1] == 1.3
    assert contact_model(arrays, 0.1 + 0.2).mu_nodes[-1] == 0.3          # 0.30000000000000004
    assert contact_model(arrays, Law()).mu_nodes[-1] == 2.3
    assert contact_model(arrays, fr[2]).mu_nodes[1] == 2.3   # the stored curve (a falling law's tail node after it)
    with pytest.raises(ValueError, match=r"no friction curve for coulomb\(mu=0.34\)"):
        contact_model(arrays, 0.34)
    # an artifact of before (no rf_label): Coulomb curves named by mu_values
    old = {k: v for k, v in arrays.items() if k not in ("rf_label", "rf_law")}
    assert contact_model(old, 0.33).mu_nodes[-1] == 1.3
    assert curve_label(0.35) == "coulomb(mu=0.35)" == Friction.coulomb(0.35).label


def test_with_curves_adds_the_missing_values_only(static, tmp_path, monkeypatch):
    """A study's grid on a case's contact: the stored curve is kept as it is (same arrays), the
    missing values are built through the case's cache (build/cases/<case>/friction/)."""
    monkeypatch.setenv("SQUEAL_BUILD_DIR", str(tmp_path))
    own = rf_curve(static, D, D, V, 0.35, E, NU)._asdict()
    con = _contact(static, [Friction.coulomb(0.35)], [own])
    out = with_curves("x", con, [0.33, 0.35, 0.05, 0.65, 0.33])
    assert list(out["rf_label"]) == ["coulomb(mu=0.35)", "coulomb(mu=0.33)", "coulomb(mu=0.05)", "coulomb(mu=0.65)"]
    assert np.array_equal(out["mu_values"], [0.35, 0.33, 0.05, 0.65])
    assert np.array_equal(contact_model(out, 0.35).mu_nodes, own["mu_rf"])
    for mu in (0.05, 0.33, 0.65):
        assert contact_model(out, mu).mu_nodes[-1] == pytest.approx(mu, rel=1e-4)
    assert len(list((tmp_path / "cases" / "x" / "friction").glob("*.npz"))) == 3
    assert with_curves("x", out, [0.05]) == out                   # nothing missing: nothing built


def test_a_falling_law_curve_is_built_cached_and_selected_unflattened(static, tmp_path):
    """A case with CONTACT's exponential falling law (preset contact_tractcurv): its curve is the
    registry law's rf_curve (bit for bit), rises to a peak and falls, and contact_model hands the
    time loop the falling branch as built (nothing makes it monotone)."""
    from pipeline.caches.friction_curves import resolve_friction
    from solvers.contact.friction_laws import preset

    f = resolve_friction({"preset": "contact_tractcurv"}, "x.toml")
    ref = rf_curve(static, D, D, V, preset("contact_tractcurv"), E, NU)
    cache = CurveCache(tmp_path)
    curve = cache(static, D, D, V, f, E, NU)
    assert np.array_equal(curve["mu_rf"], ref.mu_rf) and np.array_equal(curve["s"], ref.s)
    arrays = _contact(static, [Friction.coulomb(0.33), f], [rf_curve(static, D, D, V, 0.33, E, NU)._asdict(), curve])
    cm = contact_model(arrays, f)
    peak = int(np.argmax(cm.mu_nodes))
    assert 0 < peak < len(cm.mu_nodes) - 1 and cm.mu_nodes[-1] < cm.mu_nodes[peak] - 0.02
    n = len(ref.mu_rf)                        # contact_model appends the law's tail node (s = inf) after the curve
    assert cm.mu_nodes[peak] <= f.mu + 1e-9 and np.array_equal(cm.mu_nodes[:n], ref.mu_rf)
    assert len(cm.mu_nodes) == n + 1 and np.isinf(cm.s_nodes[-1]) and cm.mu_nodes[-1] == pytest.approx(0.14, rel=0.01)
    assert contact_model(arrays, preset("contact_tractcurv")).mu_nodes[-1] == cm.mu_nodes[-1]   # the law itself
    assert contact_model(arrays, 0.33).mu_nodes[-1] == pytest.approx(0.33, rel=1e-4)
