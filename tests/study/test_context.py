"""pipeline/study_context.py: the code hash behind a study row's inputs ignores documentation
(docstrings, comments) and follows the code."""
from pipeline.study.context import _code_text


def test_code_text_ignores_documentation_only(tmp_path):
    a, b, c = tmp_path / "a.py", tmp_path / "b.py", tmp_path / "c.py"
    a.write_text('"""Module."""\n\ndef f(x):\n    """Doc."""\n    return 2 * x  # twice\n')
    b.write_text('"""Other words."""\n\n\ndef f(x):\n    """Other doc."""\n    # a comment\n    return 2 * x\n')
    c.write_text('"""Module."""\n\ndef f(x):\n    """Doc."""\n    return 3 * x\n')
    assert _code_text(a) == _code_text(b) != _code_text(c)
    d = tmp_path / "d.toml"
    d.write_text("x = 1\n")
    assert _code_text(d) == b"x = 1\n"
