"""The BV50 rail against analytic beams at the tolerances docs/validation/40_rail.md states (its writer's
``free_rail_rows`` and ``rail_response.beam_data`` / ``beam_ratios``): the free rail's waves at low k within
2 % of beam theory (Euler-Bernoulli, Timoshenko kappa 0.4, bar, Saint-Venant torsion, the same mesh's section
properties); up to 500 Hz the vertical point receptance within 10 % of the Timoshenko beam on a Winkler
foundation (+ the lateral-torsional beam's twist off the centre line), the lateral one within 15 % of the
lateral-torsional beam on the pad's lateral and rocking stiffness."""
import pytest

pytestmark = pytest.mark.validation


@pytest.fixture(scope="module")
def c():
    from pipeline.validation.writers.rail import context

    return context()


def test_free_rail_against_beam_theory(c):
    from pipeline.validation.writers.rail import free_rail_rows

    rows, worst = free_rail_rows(c)
    assert len(rows) > 10 and worst < 0.02, f"free rail vs beam theory: {100 * worst:.2f} % (tolerance 2 %)"


def test_supported_rail_against_the_analytic_beams(c):
    from pipeline.validation.writers.rail_response import beam_data, beam_ratios

    _, worst_v, worst_l = beam_ratios(beam_data(c))
    assert worst_v < 0.10, f"vertical receptance vs TBOEF (+ twist) up to 500 Hz: {100 * worst_v:.1f} % (10 %)"
    assert worst_l < 0.15, f"lateral receptance vs lateral-torsional beam up to 500 Hz: {100 * worst_l:.1f} % (15 %)"
