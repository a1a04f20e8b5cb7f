"""pipeline/study_report.py: the report's studies part takes each study's summary (the full
version over the --quick one), moves its headings under the report's "Studies" and copies its
figures."""
from pipeline.study.report_section import embed, study_dirs


def test_studies_are_embedded_with_their_figures(tmp_path):
    root = tmp_path / "studies"
    for name in ("contact", "map", "map-quick", "damping-quick", "empty"):
        (root / name).mkdir(parents=True)
    for name in ("contact", "map", "map-quick", "damping-quick"):
        (root / name / "summary.md").write_text(f"# Study {name}\n\n## part\n\n![fig](fig_{name}.png)\n![gone](x.png)\n")
        (root / name / f"fig_{name}.png").write_bytes(b"png")
    dirs = study_dirs(root)
    assert [d.name for d in dirs] == ["map", "damping-quick", "contact"]     # SPEC 7 order; quick only alone
    figs = tmp_path / "figures"
    figs.mkdir()
    text = embed((root / "map" / "summary.md").read_text(), "map", figs, root / "map")
    assert text.startswith("### Study map\n\n#### part")
    assert "](figures/study_map_fig_map.png)" in text and (figs / "study_map_fig_map.png").read_bytes() == b"png"
    assert "](x.png)" in text                                                   # a missing figure stays as it was
