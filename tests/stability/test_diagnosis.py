"""Issue 13's diagnosis (docs/validation/65_fidelity_diagnosis.md, its writer's ``fastest_roots``): with the
contact points read flange-positive, the worn profiles, the calibrated suspension damping and the C20 fitted
to the coupling zero points, the screen's fastest root is the reference's mode wherever the reference (thesis
ch. 6) names one: (2,0,a) at -5 mm up to mu = 0.45 and the low-frequency root above, (3,0,a) at -10 mm,
(2,0,a) at -15 mm from mu = 0.3."""
import pytest


@pytest.mark.validation
def test_the_reference_mode_leads_where_the_reference_names_one():
    from pipeline.validation.writers.diagnosis import MUS, fastest_roots

    fastest = fastest_roots()
    assert all(fastest[(-5, mu)] == "(2,0,a)" for mu in MUS if mu <= 0.45) and fastest[(-5, 0.6)] == "LF"
    assert all(fastest[(-10, mu)] == "(3,0,a)" for mu in MUS)
    assert all(fastest[(-15, mu)] == "(2,0,a)" for mu in MUS if mu >= 0.3)
