"""The stability screen against the time loop (docs/validation/66_stability.md and 66_stability_falling.md,
their writer's ``run_case``, ``run_falling`` and ``screened_check``): at the three positions every (n,0,a)
and track pole growing faster than 1/s within 20 % of the growth rate measured in the time loop's linear
phase (windowed demodulation; with a falling law, the matrix pencil of
pipeline/validation/references/growth.py), the screen's fastest pole the mode the loop squeals at, and a
screened study missing no squealing case of the full one."""
import pytest

pytestmark = pytest.mark.validation
CASES = ("dy05", "dy10", "default")


@pytest.fixture(scope="module")
def writer():
    from pipeline.validation.writers import stability

    stability.build()
    return stability


def _axial_or_track(lab):
    return lab.endswith(",0,a)") or lab == "track"


@pytest.mark.parametrize("case", CASES)
def test_screen_against_the_time_loop(writer, case):
    rows, squeal, f, _ = writer.run_case(case)
    assert rows[0][0] == squeal, (case, rows[0], squeal, f)          # the fastest pole is the squealing mode
    for lab, fr, s, m in rows:
        if abs(s) >= 1.0 and _axial_or_track(lab):
            assert m == pytest.approx(s, rel=0.2), (case, lab, s, m)


@pytest.mark.parametrize("case", CASES)
def test_screen_against_the_time_loop_with_a_falling_law(writer, case):
    for name, _, _, rows, _ in writer.run_falling(case):
        for lab, fr, s, m, _ in rows:
            if abs(s) >= 1.0 and _axial_or_track(lab):
                assert m == pytest.approx(s, rel=0.2), (case, name, lab, s, m)


def test_a_screened_study_misses_no_squeal(writer):
    text, missed, differ = writer.screened_check()
    assert "none missed" in text, text                               # the maps exist (built above)
    assert not missed and not differ, (missed[:5], differ[:5])
