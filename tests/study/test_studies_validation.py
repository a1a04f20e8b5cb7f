"""The studies against independent references (docs/validation/80_studies.md, its writer's
``map_vs_simulate`` and ``damping_vs_linear``): a one-point map per contact position run as a study is the
simulate stage's run to the last bit; the damping procedure's bisection ends quiet with a bracket of 2 % that
agrees with the single-mode linear estimate of the critical damping within 15 % for four mode variants."""
import pytest

pytestmark = pytest.mark.validation


def test_the_study_runner_reproduces_the_simulate_stage():
    from pipeline.validation.writers.studies import map_vs_simulate

    same, lines = map_vs_simulate()
    assert len(same) == 3 and all(same), lines


def test_bisection_against_the_linear_estimate_for_four_modes():
    from pipeline.validation.writers.studies import damping_vs_linear

    damp, _ = damping_vs_linear(plot=False)
    assert len(damp) == 4
    for d in damp:
        assert d["end"].startswith("quiet") and d["hi"] / d["lo"] - 1 <= 0.02, d
        assert abs(d["dev"]) < 0.15, d
