"""Import of measured profiles: a MiniProf .whl export (header block, blank
line, X/Y rows) of S1002 measured on the other side with z downward, and a
plain CSV; the imported file reproduces the profile."""
import numpy as np
import pytest

from geometry.standard_profiles import s1002


def miniprof_text(y_mm, z_mm, coldef="X,Y"):
    head = ["FileName=S1002_left.whl", "ProgramName=MiniProf", "Date=2014-03-01", "Side=Left",
            f"ColumnDef={coldef}", f"XYPoints={len(y_mm)}", ""]
    if coldef == "X,Y":
        rows = [f"{a:9.4f} {b:9.4f}" for a, b in zip(y_mm, z_mm)]
    else:  # angle column first, comma separated, comments
        rows = [f"0.0, {a:.4f}, {b:.4f}   ! point" for a, b in zip(y_mm, z_mm)]
    return "\n".join(head + rows) + "\n"


@pytest.fixture
def profiles_dir(tmp_path, monkeypatch):
    import pipeline.config.case_profiles as P

    out = tmp_path / "profiles"
    out.mkdir()
    monkeypatch.setattr(P, "PROFILES", out)
    return P


@pytest.mark.parametrize("coldef", ["X,Y", "A,X,Y"])
def test_miniprof_whl_mirrored_and_z_down(profiles_dir, tmp_path, coldef):
    P = profiles_dir
    y = np.arange(-62.0, 60.0, 0.2)
    z = s1002(y)
    # as measured on the left wheel: lateral axis reversed, z downward, tape circle at X = 70 (from the back face)
    src = tmp_path / "S1002_left.whl"
    src.write_text(miniprof_text((70.0 - y)[::-1], -z[::-1], coldef))
    path = P.import_profile(str(src), "wheel", "s1002_measured", mirror_y=True, flip_z=True, y0=-70.0)
    assert path.name == "s1002_measured.csv"
    prof, _ = P.read_profile("s1002_measured")
    assert prof.kind == "wheel" and "MiniProf export S1002_left.whl" in prof.source
    assert prof.meta["miniprof_side"] == "Left"
    yy = np.linspace(-0.060, 0.055, 300)
    assert np.abs(prof(yy) - 1e-3 * s1002(1e3 * yy)).max() < 3e-6  # GCV smoothing of 0.1 um-rounded exact data


def test_plain_csv_and_wrong_orientation(profiles_dir, tmp_path):
    from pipeline.config.loader import ConfigError

    P = profiles_dir
    y = np.arange(-62.0, 60.0, 0.5)
    src = tmp_path / "wheel.csv"
    src.write_text("y_mm;z_mm\n" + "\n".join(f"{a};{b}" for a, b in zip(y, s1002(y))))
    P.import_profile(str(src), "wheel", "plain", noise=0.0)
    prof, _ = P.read_profile("plain")
    assert prof(0.0) == pytest.approx(0.0, abs=1e-9) and prof(-0.055) == pytest.approx(0.028, abs=1e-6)
    with pytest.raises(ConfigError, match=r"wheel\.csv: line \d+: the flange \(highest z\) is at the field-side end"):
        P.import_profile(str(src), "wheel", "mirrored", mirror_y=True)


def test_unsupported_miniprof_variants(tmp_path):
    from geometry.miniprof import parse_miniprof
    from geometry.profiles import ProfileError

    with pytest.raises(ProfileError, match="multi-part MiniProf file"):
        parse_miniprof("[FileInfo]\nVersion=1\n", "x.mpt")
    with pytest.raises(ProfileError, match="old-style MiniProf"):
        parse_miniprof("MINIPROF 2.0\n\n1 2\n", "x.ban")
    with pytest.raises(ProfileError, match=r"x\.ban line 3: expected numbers"):
        parse_miniprof("ColumnDef=X,Y\n\n1.0 2.0x\n", "x.ban")
