"""The case report as one self-contained HTML page beside report.md (build/report/<case>/report.html):
the Markdown rendered (markdown-it-py, CommonMark with tables), every figure embedded as a data URI,
the WAV in an <audio> element (embedded too), the headline block first, a small stylesheet.  It opens
from anywhere (mail it, put it on a web server) without its figures folder.  Tested in headless
chromium (tests/report/test_html.py: every image and the audio load, no console errors)."""
from __future__ import annotations

import base64
import html
import mimetypes
import re
from pathlib import Path

from pipeline.store import artifacts

STYLE = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; max-width: 1100px; margin: 2em auto;
       padding: 0 1em; color: #222; line-height: 1.45; }
h1 { border-bottom: 2px solid #c33; padding-bottom: .2em; }
h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
blockquote { background: #fff4f0; border-left: 6px solid #c33; margin: 1em 0; padding: .6em 1em; font-size: 1.1em; }
table { border-collapse: collapse; margin: .8em 0; font-size: .9em; }
th, td { border: 1px solid #ccc; padding: .2em .5em; }
th { background: #f3f3f3; }
img { max-width: 100%; height: auto; display: block; margin: .5em 0; }
audio { width: 100%; margin: .5em 0; }
code { background: #f5f5f5; padding: 0 .2em; }
"""


def _data_uri(path: Path) -> str:
    mime = mimetypes.guess_type(path.name)[0] or "application/octet-stream"
    if path.suffix == ".wav":
        mime = "audio/wav"
    return f"data:{mime};base64,{base64.b64encode(path.read_bytes()).decode('ascii')}"


def render(markdown: str, base: Path, title: str) -> str:
    """HTML of ``markdown`` with its local figures (relative to ``base``) embedded; a link to a .wav
    becomes an <audio controls> element.  A figure that does not exist raises FileNotFoundError
    (a report must not ship a broken image)."""
    from markdown_it import MarkdownIt  # lazy: brings in markdown_it

    md = MarkdownIt("commonmark", {"html": False}).enable("table")
    tokens = md.parse(markdown)
    for tok in tokens:
        for child in tok.children or ():
            if child.type == "image":
                src = child.attrGet("src")
                if src and not re.match(r"^[a-z]+:", src):
                    child.attrSet("src", _data_uri(base / src))
    body = md.renderer.render(tokens, md.options, {})

    def audio(m):
        path = base / html.unescape(m.group(1))
        return (f'<audio controls preload="auto" src="{_data_uri(path)}">your browser cannot play WAV</audio>'
                f"<code>{m.group(2)}</code>")

    body = re.sub(r'<a href="([^"]+\.wav)">([^<]*)</a>', audio, body)
    return (f'<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
            f'<meta name="viewport" content="width=device-width, initial-scale=1">\n<title>{html.escape(title)}</title>\n'
            f"<style>{STYLE}</style>\n</head>\n<body>\n{body}</body>\n</html>\n")


def write_html(md_path: Path, title: str) -> Path:
    """report.html beside ``md_path`` (atomic)."""
    out = md_path.with_suffix(".html")
    text = render(md_path.read_text(), md_path.parent, title)
    with artifacts.atomic_write(out) as tmp:
        tmp.write_text(text)
    return out
