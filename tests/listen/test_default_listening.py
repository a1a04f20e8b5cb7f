"""The default case's listening (docs/validation/75_listening.md, its writer's ``default_section``): the
calibrated WAV read back independently (pipeline/validation/references/wavcheck.py: scipy's reader, pyfar's
IEC 61260-1 filter bank) against the stage's own numbers (--validation)."""
import pytest


@pytest.mark.validation
def test_default_case_wav_reads_back_as_its_levels():
    from pipeline.validation.writers.listening import default_section

    _, m = default_section()
    assert m is not None, "the default case's radiate artifact is not available"
    a = m["a"]
    # the default case squeals (README): a silent default is a failure, not a reason to skip
    assert bool(a["meaningful"]), f"the default case does not squeal (L_F2 = {float(a['L_F2']):.1f} dB)"
    assert abs(m["f_wav"] / float(a["f_sound"]) - 1) < 0.005
    assert abs(m["L_wav"] - float(a["L_p"])) < 0.5
    assert abs(m["bsum"] - float(a["L_p"])) < 0.1
    assert m["fb_dev"] < 0.5 and m["fb_sum"] < 0.1
