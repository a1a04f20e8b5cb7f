"""The wheel solver against Kirchhoff's plates (docs/validation/20_wheel_plates.md, its writer's ``plate_rows``):
the harmonic FE within 1 % of the annular plate (clamped inside, n = 0..3, 0 and 1 nodal circles) and of the
free disc through the axis (n = 0..3).  The C20's criteria of docs/validation/21_c20_modes.md (every label of
Table 4.1 found, median deviation <= 5 %, worst <= 10 %, (n,0,a) <= 3 % on the default mesh) are asserted by
tests/test_c20_reference.py."""
import pytest

pytestmark = pytest.mark.validation


def test_plates_against_kirchhoff(tmp_path):
    from pipeline.validation.writers.wheel_modes import plate_rows

    rows, worst = plate_rows(tmp_path)
    assert len(rows) == 2 + 8 + 4 and worst < 0.01

