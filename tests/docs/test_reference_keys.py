"""docs/reference.md, the user's reference moved out of the README (issue 33), names every key of the
shipped curve, vehicle, case and study files (a key a user meets in a shipped file is explained)."""
from __future__ import annotations

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SHIPPED = ["pipeline/curves/*.toml", "geometry/vehicles/*.toml", "pipeline/cases/*.toml", "pipeline/studies/*.toml"]


def keys(data: dict) -> set[str]:
    out = set()
    for k, v in data.items():
        if isinstance(v, dict):
            out |= keys(v)             # a table's name is not a key = line; its keys are
        else:
            out.add(k)
    return out


def shipped_keys() -> dict[str, set[str]]:
    """{key: the files that set it} of every `key = value` line (parsed by tomllib, tables flattened)."""
    found: dict[str, set[str]] = {}
    for pattern in SHIPPED:
        for f in sorted(ROOT.glob(pattern)):
            for k in keys(tomllib.loads(f.read_text(encoding="utf-8"))):
                found.setdefault(k, set()).add(str(f.relative_to(ROOT)))
    return found


def test_reference_names_every_shipped_key():
    found = shipped_keys()
    assert len(found) > 50 and {"radius_m", "vehicle", "wheelbase_m", "mu", "passages_night"} <= set(found)
    text = (ROOT / "docs" / "reference.md").read_text(encoding="utf-8")
    missing = {k: sorted(v) for k, v in found.items() if not re.search(rf"(?<![A-Za-z0-9_]){re.escape(k)}(?![A-Za-z0-9_])", text)}
    assert not missing, f"keys of shipped files not in docs/reference.md: {missing}"


def test_a_key_left_out_is_found_missing():
    """The check can fail: the reference without its line-study export table misses those keys."""
    text = (ROOT / "docs" / "reference.md").read_text(encoding="utf-8")
    cut = "\n".join(ln for ln in text.splitlines() if "passages_" not in ln)
    assert "passages_night" in shipped_keys() and not re.search(r"(?<![A-Za-z0-9_])passages_night(?![A-Za-z0-9_])", cut)


def test_readme_is_a_front_door():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme.splitlines()) <= 200
    for page in ("docs/tutorial.md", "docs/reference.md", "docs/glossary.md", "docs/limitations.md", "CITATION.cff"):
        assert page in readme and (ROOT / page).exists(), page


def test_links_of_the_user_pages_resolve():
    """Every relative link of the README and the user's pages names a file of the repository, and every
    #anchor into physics.md a heading of it (GitHub's slugs: lower case, punctuation dropped, spaces as -)."""
    heads = re.findall(r"^#+ (.+)$", (ROOT / "docs" / "physics.md").read_text(encoding="utf-8"), re.M)
    slugs = {re.sub(r"[^\w\- ]", "", h.lower()).replace(" ", "-") for h in heads}
    n = 0
    for page in ("README.md", "docs/tutorial.md", "docs/glossary.md", "docs/limitations.md", "docs/reference.md"):
        for target in re.findall(r"\]\(([^)\s]+)\)", (ROOT / page).read_text(encoding="utf-8")):
            if "://" in target:
                continue
            path, _, anchor = target.partition("#")
            f = ((ROOT / page).parent / path).resolve() if path else ROOT / page
            assert f.exists(), f"{page}: link to a missing file {target}"
            if anchor and f.name == "physics.md":
                assert anchor in slugs, f"{page}: no heading #{anchor} in docs/physics.md"
            n += 1
    assert n > 20
