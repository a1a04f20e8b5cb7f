"""pipeline/study_context.py: the code hash behind a study row's inputs ignores documentation
(docstrings, comments) and follows the code."""
from pipeline.store.code_hash import code_text as _code_text


def test_code_text_ignores_documentation_only(tmp_path):
    a, b, c = tmp_path / "a.py", tmp_path / "b.py", tmp_path / "c.py"
    a.write_text('"""Module."""\n\ndef f(x):\n    """Doc."""\n    return 2 * x  # twice\n')
    b.write_text('"""Other words."""\n\n\ndef f(x):\n    """Other doc."""\n    # a comment\n    return 2 * x\n')
    c.write_text('"""Module."""\n\ndef f(x):\n    """Doc."""\n    return 3 * x\n')
    assert _code_text(a) == _code_text(b) != _code_text(c)
    d = tmp_path / "d.toml"
    d.write_text("x = 1\n")
    assert _code_text(d) == b"x = 1\n"


def test_context_builds_a_study_grid_curves_once(default_case):
    """A study's friction values off the old 0.05 grid get their curves on the case's contact
    (pipeline.caches.friction_curves, cached by value): the case's own curve is the contact stage's, bit for bit,
    a new value's ends on its plateau, and loading again reads the cache (no new file)."""
    import numpy as np

    from pipeline.store import artifacts, paths
    from pipeline.study.context import load_context
    from solvers.timeloop.inputs import contact_model

    ctx = load_context(default_case, radiation=False, mus=[0.33, 0.35])
    con, _ = artifacts.load_npz(paths.case_dir(default_case) / "contact.npz", "contact")
    assert np.array_equal(contact_model(ctx.contact, ctx.mu).mu_nodes, contact_model(con, ctx.mu).mu_nodes)
    cm = contact_model(ctx.contact, 0.33)
    assert cm.mu == 0.33 and abs(cm.mu_nodes[-1] - 0.33) < 1e-4 * 0.33
    files = sorted((paths.case_dir(default_case) / "friction").glob("*.npz"))
    again = load_context(default_case, radiation=False, mus=[0.33])
    assert sorted((paths.case_dir(default_case) / "friction").glob("*.npz")) == files
    assert np.array_equal(contact_model(again.contact, 0.33).mu_nodes, cm.mu_nodes)
    assert ctx.friction.label == "coulomb(mu=0.35)"
