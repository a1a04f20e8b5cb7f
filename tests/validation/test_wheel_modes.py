"""The wheel stage against exact and published references (docs/validation/20_wheel_plates.md and
21_c20_modes.md, their writer's ``plate_rows`` and ``c20_levels``): the harmonic FE within 1 % of Kirchhoff's
annular plate (clamped inside) and free disc; the C20 on its default mesh: every label of Table 4.1 found,
median deviation <= 5 %, worst <= 10 %, (n,0,a) <= 3 % (the mesh-convergence study's default level)."""
import pytest

pytestmark = pytest.mark.validation


def test_plates_against_kirchhoff(tmp_path):
    from pipeline.validation.writers.wheel_modes import plate_rows

    rows, worst = plate_rows(tmp_path)
    assert len(rows) == 2 + 8 + 4 and worst < 0.01


def test_c20_against_reference_with_mesh_convergence(tmp_path):
    from pipeline.validation.writers.wheel_modes import c20_levels

    levels, _ = c20_levels(tmp_path)
    factor, _, _, _, s = levels[1]                           # the default mesh
    assert factor == 1.0
    assert s["found"] == s["total"] and s["median_abs"] <= 0.05 and s["max_abs"] <= 0.10 and s["max_abs_n0a"] <= 0.03
