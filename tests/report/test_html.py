"""The HTML report in a real browser (headless chromium through the DevTools protocol): the page
loads, the headline block comes first, every image decodes (naturalWidth > 0), the audio element
loads its WAV (readyState >= 1, no error), and the browser logs no error.  Negative controls: a
broken image, a console error and a missing WAV are caught.  Skipped only when chromium is missing
(`make test` installs it: debian-packages.txt)."""
from __future__ import annotations

import io
import wave

import numpy as np
import pytest

from pipeline.store import paths
from pipeline.stages.report_html import render, write_html
from tests.report.cdp import find_chromium, inspect_page

pytestmark = pytest.mark.skipif(find_chromium() is None, reason="chromium is not installed (debian-packages.txt; "
                                                                 "`make test` installs it)")


def _assets(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot([0, 1], [0, 1])
    (tmp_path / "figures").mkdir()
    fig.savefig(tmp_path / "figures" / "a.png", dpi=50)
    plt.close(fig)
    t = np.arange(22050) / 44100
    pcm = (0.5 * 32767 * np.sin(2 * np.pi * 434.7 * t)).astype("<i2")
    buf = io.BytesIO()
    with wave.open(buf, "wb") as w:
        w.setnchannels(1)
        w.setsampwidth(2)
        w.setframerate(44100)
        w.writeframes(pcm.tobytes())
    (tmp_path / "figures" / "s.wav").write_bytes(buf.getvalue())


MD = """# Report

> **SQUEALS** at 434.7 Hz
>
> | L_F2 | f |
> |---:|---:|
> | 53.2 | 434.7 |

## Figures

![a figure](figures/a.png)

The sound: [s.wav](figures/s.wav).
"""


def test_synthetic_page_loads_with_images_and_audio(tmp_path):
    _assets(tmp_path)
    (tmp_path / "report.md").write_text(MD)
    out = write_html(tmp_path / "report.md", "t")
    page = inspect_page(out)
    assert page["title"] == "t" and page["first"] == "H1" and page["blockquote_index"] == 1
    assert len(page["images"]) == 1 and page["images"][0]["naturalWidth"] > 0
    assert page["images"][0]["src"].startswith("data:image/png;base64")
    assert len(page["audio"]) == 1 and page["audio"][0]["readyState"] >= 1 and page["audio"][0]["error"] is None
    assert page["audio"][0]["duration"] == pytest.approx(0.5, abs=1e-3)
    assert page["errors"] == []


def test_the_check_catches_a_broken_image_a_bad_wav_and_a_console_error(tmp_path):
    _assets(tmp_path)
    (tmp_path / "figures" / "a.png").write_bytes(b"not a png")
    (tmp_path / "figures" / "s.wav").write_bytes(b"RIFF0000WAVEjunk")
    text = render(MD, tmp_path, "bad").replace("</body>", "<script>console.error('boom')</script></body>")
    (tmp_path / "bad.html").write_text(text)
    page = inspect_page(tmp_path / "bad.html")
    assert page["images"][0]["naturalWidth"] == 0
    assert page["audio"][0]["error"] is not None or page["audio"][0]["readyState"] == 0
    assert any("boom" in e for e in page["errors"])
    with pytest.raises(FileNotFoundError):
        render(MD.replace("a.png", "missing.png"), tmp_path, "x")


def test_default_case_report_in_the_browser():
    html = paths.build() / "report" / "default" / "report.html"
    if not html.exists():
        pytest.skip("needs build/report/default/report.html (make report)")
    page = inspect_page(html)
    assert page["first"] == "H1" and page["blockquote_index"] == 1       # the headline block first
    assert len(page["images"]) >= 8 and all(i["naturalWidth"] > 0 for i in page["images"]), page["images"]
    if (paths.case_dir("default") / "listen.npz").exists():
        assert len(page["audio"]) >= 1                  # the limit cycle, and the pass-by when it was written
        assert all(a["readyState"] >= 1 and a["error"] is None for a in page["audio"]), page["audio"]
    assert page["errors"] == []
