"""Falling friction, spin and traction in the time loop (issue 26; docs/validation/67_falling_friction.md and
67_falling_friction_kalker.md, their writer's ``case_rows`` and ``kalker_runs``):

* the reference rows are the cases' own runs (the default case: (2,0,a) at the recorded L_F2 of
  tests/reference/reference_results.json, compared as tests/test_reference_results.py does);
* a falling law feeds energy in: every position squeals, at least as loud as with Coulomb friction (0.5 dB);
* spin changes the amplitude, not the occurrence (Zenzerovic, Kropp and Pieringer, JSV 2016);
* Kalker's loop against the point-contact loop: for Coulomb friction and spin the same dominant frequency
  (1 %), L_F2 within 3 dB and the change from the Coulomb reference of the same sign; with the falling law
  both loops squeal."""
import numpy as np
import pytest

from tests.test_reference_results import REF, same

pytestmark = pytest.mark.validation
CASES = ("dy05", "dy10", "default")
REFERENCE = "reference (Coulomb, case settings)"


@pytest.fixture(scope="module")
def table():
    from pipeline.validation.writers.falling_friction import case_rows

    return {(c, r["variant"]): r for c in CASES for r in case_rows(c)}


def test_reference_rows_are_the_cases_own_runs(table):
    ref = table[("default", REFERENCE)]
    assert ref["mode"] == "(2,0,a)"
    same(ref["L_F2"], REF["default"]["L_F2"], "default L_F2")


def test_a_falling_law_makes_every_position_squeal_at_least_as_loud(table):
    from pipeline.validation.writers.falling_friction import LAWS

    for c in CASES:
        ref = table[(c, REFERENCE)]
        for name in LAWS:
            assert table[(c, name)]["squeals"] and table[(c, name)]["L_F2"] >= ref["L_F2"] - 0.5, (c, name)


def test_spin_changes_the_amplitude_not_the_occurrence(table):
    spin = {k: r for k, r in table.items() if k[1].startswith("spin")}
    assert len(spin) == 2 * len(CASES)
    assert all(r["squeals"] == table[(k[0], REFERENCE)]["squeals"] for k, r in spin.items())


def test_kalker_loop_with_spin_and_a_falling_law():
    from pipeline.validation.writers.falling_friction import kalker_runs

    k_runs = kalker_runs()
    labels, out = k_runs["labels"], k_runs["measures"]
    ref = out["reference (Coulomb)|point"], out["reference (Coulomb)|kalker"]
    for label in labels[:2]:                         # Coulomb and spin: the same squeal in both loops
        p, k = out[f"{label}|point"], out[f"{label}|kalker"]
        assert abs(p["f_dominant"] - k["f_dominant"]) < 0.01 * k["f_dominant"] and abs(p["L_F2"] - k["L_F2"]) < 3.0
        if label != "reference (Coulomb)":
            assert np.sign(p["L_F2"] - ref[0]["L_F2"]) == np.sign(k["L_F2"] - ref[1]["L_F2"]), label
    fall = [out[f"{labels[2]}|{tg}"] for tg in ("point", "kalker")]
    assert all(m["L_F2"] >= 10.0 for m in fall)      # the falling law: both loops squeal (the mode: see the text)
