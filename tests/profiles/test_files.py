"""Profile files: round trip, smoothing against a circle, and every bad-file
error naming the file and the line (also through the pipeline's loader)."""
import numpy as np
import pytest

from geometry.profiles import MIN_POINTS, ProfileError, build_profile, format_profile, profile_from_text

R = 0.3  # m: a rail crown


def crown(n=141, half=0.035):
    y = np.linspace(-half, half, n)
    return y, np.sqrt(R**2 - y**2) - R


def text_of(y_mm, z_mm, units="mm", kind="rail"):
    lines = [f"# kind: {kind}", "# source: test", f"# units: {units}", "# noise_mm: 0", "y,z"]
    return "\n".join(lines + [f"{a},{b}" for a, b in zip(y_mm, z_mm)]) + "\n"


def test_round_trip_and_interpolation():
    y, z = crown()
    meta = {"kind": "rail", "source": "R300 crown", "noise_mm": 0, "note": "x"}
    p = profile_from_text(format_profile(meta, y, z), "crown.csv", "crown")
    assert p.kind == "rail" and p.meta["note"] == "x" and "interpolating" in p.smoothing
    yy = np.linspace(-0.03, 0.03, 97)
    assert np.allclose(p(yy), np.sqrt(R**2 - yy**2) - R, atol=1e-9)  # the file's 1 nm print precision
    assert np.allclose(p.curvature(yy), -R**2 / (R**2 - yy**2) ** 1.5, rtol=2e-2)
    assert np.isnan(p(0.036)) and np.isnan(p(-0.0351))
    assert np.allclose(np.diff(p.y), 5e-5)


@pytest.mark.parametrize("noise_mm", [0.01, None])
def test_smoothing_recovers_the_curvature_of_a_noisy_circle(noise_mm):
    """Measured-like data (0.01 mm noise every 0.2 mm): interpolated, the
    curvature is off by a factor of hundreds; smoothed (noise level stated or
    GCV), its RMS error over the crown is below 20 % of 1/R and the heights
    are within 5 um of the circle (half the noise)."""
    rng = np.random.default_rng(3)
    y, z = crown(351)
    zn = z + 1e-5 * rng.standard_normal(len(z))
    raw = build_profile(y, zn, "rail", "raw", "t", 0.0)
    smooth = build_profile(y, zn, "rail", "smooth", "t", noise_mm)
    yy = np.linspace(-0.02, 0.02, 41)
    rms = lambda p: np.sqrt(np.mean((p.curvature(yy) * R + 1) ** 2))  # noqa: E731
    assert rms(raw) > 100 and rms(smooth) < 0.2
    assert np.abs(smooth(yy) - (np.sqrt(R**2 - yy**2) - R)).max() < 5e-6


def test_non_monotonic_y_names_file_and_line():
    y, z = crown()
    y_mm, z_mm = 1e3 * y, 1e3 * z
    y_mm[40] = y_mm[38]
    with pytest.raises(ProfileError, match=r"bad\.csv line 46: y = .* does not increase \(line 45"):
        profile_from_text(text_of(y_mm, z_mm), "bad.csv", "bad")


def test_nan_names_file_and_line():
    y, z = crown()
    z_mm = 1e3 * z
    z_mm[10] = np.nan
    with pytest.raises(ProfileError, match=r"bad\.csv line 16: z = nan is not a finite number"):
        profile_from_text(text_of(1e3 * y, z_mm), "bad.csv", "bad")


def test_too_few_points_names_file_and_line():
    y, z = crown(MIN_POINTS - 1)
    with pytest.raises(ProfileError, match=rf"bad\.csv line {5 + MIN_POINTS - 1}: only {MIN_POINTS - 1} points"):
        profile_from_text(text_of(1e3 * y, 1e3 * z), "bad.csv", "bad")


@pytest.mark.parametrize("units,scale,looks", [("mm", 1.0, "m"), ("m", 1e3, "mm")])
def test_units_off_by_1000_names_file_line_and_the_likely_unit(units, scale, looks):
    """Metres under 'units: mm' (span 0.07) and mm under 'units: m' (70 m)."""
    y, z = crown()
    with pytest.raises(ProfileError, match=rf"bad\.csv line 146: .*look like {looks} \(units off by 1000\)"):
        profile_from_text(text_of(y * scale, z * scale, units), "bad.csv", "bad")


def test_header_errors():
    y, z = crown()
    txt = text_of(1e3 * y, 1e3 * z)
    with pytest.raises(ProfileError, match=r"bad\.csv line 1: kind 'tyre' is not one of wheel, rail"):
        profile_from_text(txt.replace("kind: rail", "kind: tyre"), "bad.csv", "bad")
    with pytest.raises(ProfileError, match="header key '# source: ...' is missing"):
        profile_from_text(txt.replace("# source: test\n", ""), "bad.csv", "bad")
    with pytest.raises(ProfileError, match=r"bad\.csv line 7: expected two numbers"):
        profile_from_text(txt.replace("\n-34.", "\n-34.,1,2\n-34.", 1), "bad.csv", "bad")


def test_pipeline_loader_reports_file_and_line(tmp_path, monkeypatch):
    """A bad file in geometry/profiles/ is a ConfigError (one line in the CLI)."""
    import pipeline.config.case_profiles as P
    from pipeline.config.loader import ConfigError

    y, z = crown()
    z_mm = 1e3 * z
    z_mm[3] = np.inf
    (tmp_path / "broken.csv").write_text(text_of(1e3 * y, z_mm))
    monkeypatch.setattr(P, "PROFILES", tmp_path)
    with pytest.raises(ConfigError) as e:
        P.read_profile("broken")
    assert str(e.value) == f"{tmp_path / 'broken.csv'}: line 9: z = inf is not a finite number"
    with pytest.raises(ConfigError, match="no such profile 'nothere'; available: \\['broken'\\]"):
        P.read_profile("nothere")
