"""The project's structure rules (issue 14), checked on the source text (AST, no imports).

END-STATE TESTS: these assert the tree after the issue-14 redesign (parts A and B merged).
On a branch without those parts several of them fail, by design, listing every offender:

- layering: solvers/, geometry/, postprocess/ import nothing from pipeline/; solvers/ nothing
  from postprocess/; solvers/ and geometry/ read no files (no TOML parser, no open/np.load);
- size: no module outside tests/ over 400 lines; no function with more than 12 parameters
  outside numba kernels (functions decorated with numba's jit/njit/vectorize/cfunc);
- one home per rule: one modal damping rule [4.11], one modal FRF (the factor
  1 / (m_r (w_r^2 - W^2 + 2 i zeta_r w_r W)) of [4.10]), one atomic write (the only
  os.replace / rename), and the SPEC constants of solvers/constants.py (the 6.5 kHz band top,
  the 10 dB squeal level, the thesis contact-position table) written nowhere else.

Each test names the file, line and what it found, so a failure says what to move where.
"""
from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
LAYERS = ("solvers", "geometry", "postprocess", "pipeline")
CONSTANTS = "solvers/constants.py"
MAX_LINES = 400
MAX_PARAMS = 12


def _files(*tops: str, outside_tests: bool = False) -> list[Path]:
    if outside_tests:
        tops = tuple(p.parent.name for p in ROOT.glob("*/__init__.py") if p.parent.name != "tests")
    return sorted(p for top in tops for p in (ROOT / top).rglob("*.py") if "__pycache__" not in p.parts)


def _rel(p: Path) -> str:
    return p.relative_to(ROOT).as_posix()


@functools.lru_cache(maxsize=None)
def _tree(p: Path) -> ast.Module:
    """The parsed file, every node knowing its parent (read-only: shared between tests)."""
    tree = ast.parse(p.read_text(), filename=str(p))
    for node in ast.walk(tree):
        for child in ast.iter_child_nodes(node):
            child.parent = node
    return tree


def _imports(p: Path) -> list[tuple[int, str]]:
    """(line, absolute module) of every import in the file, function-level ones included."""
    pkg = _rel(p)[:-3].split("/")
    pkg = pkg[:-1] if pkg[-1] != "__init__" else pkg[:-1]
    out = []
    for node in ast.walk(_tree(p)):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join([*pkg[: len(pkg) - node.level + 1], *([base] if base else [])])
            out += [(node.lineno, f"{base}.{a.name}" if base else a.name) for a in node.names]
    return out


@pytest.mark.parametrize("layer, forbidden", [("solvers", "pipeline"), ("geometry", "pipeline"),
                                              ("postprocess", "pipeline"), ("solvers", "postprocess")])
def test_layering(layer, forbidden):
    bad = [f"{_rel(p)}:{line} imports {mod}" for p in _files(layer) for line, mod in _imports(p)
           if mod == forbidden or mod.startswith(forbidden + ".")]
    assert not bad, f"{layer}/ must not import {forbidden}/:\n" + "\n".join(bad)


FILE_READS = {"open", "load", "loadtxt", "genfromtxt", "fromfile", "read_text", "read_bytes", "read_csv",
              "read_msh", "read_from_msh"}


@pytest.mark.parametrize("layer", ["solvers", "geometry"])
def test_numerical_layers_read_no_files(layer):
    """Numbers in, numbers out: the pipeline reads parameter files and artifacts and passes arrays."""
    bad = [f"{_rel(p)}:{line} imports {mod}" for p in _files(layer) for line, mod in _imports(p)
           if mod.split(".")[0] in ("tomllib", "tomli", "toml")]
    if layer == "solvers":  # geometry/mesher.py reads the meshes Gmsh writes: geometry's own file format
        for p in _files(layer):
            for node in ast.walk(_tree(p)):
                if isinstance(node, ast.Call):
                    f = node.func
                    name = f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""
                    if (name in FILE_READS and not (name == "load" and isinstance(f, ast.Attribute)
                                                    and ast.unparse(f.value) not in ("np", "numpy"))) \
                            or ast.unparse(f) == "gmsh.merge":
                        bad.append(f"{_rel(p)}:{node.lineno} {ast.unparse(f)}(...)")
    assert not bad, f"{layer}/ reads files:\n" + "\n".join(bad)


def test_no_module_over_400_lines():
    long = [f"{_rel(p)}: {n} lines" for p in _files(outside_tests=True)
            if (n := len(p.read_text().splitlines())) > MAX_LINES]
    assert not long, f"modules over {MAX_LINES} lines (outside tests/):\n" + "\n".join(long)


def _is_numba_kernel(fn: ast.FunctionDef) -> bool:
    for d in fn.decorator_list:
        target = d.func if isinstance(d, ast.Call) else d
        name = target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", "")
        if name in ("jit", "njit", "vectorize", "guvectorize", "cfunc", "generated_jit"):
            return True
    return False


def _n_params(fn) -> int:
    a = fn.args
    names = [x.arg for x in (*a.posonlyargs, *a.args)]
    n = len(names) + len(a.kwonlyargs) + (a.vararg is not None) + (a.kwarg is not None)
    if isinstance(getattr(fn, "parent", None), ast.ClassDef) and names[:1] in (["self"], ["cls"]):
        n -= 1
    return n


def test_no_function_over_12_parameters_outside_numba_kernels():
    bad = []
    for p in _files(outside_tests=True):
        for node in ast.walk(_tree(p)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and not _is_numba_kernel(node):
                if (n := _n_params(node)) > MAX_PARAMS:
                    bad.append(f"{_rel(p)}:{node.lineno} {node.name}: {n} parameters")
    assert not bad, f"functions with more than {MAX_PARAMS} parameters (group them in a named structure):\n" \
        + "\n".join(bad)


def test_the_parameter_counter_sees_numba_kernels_and_methods():
    src = ("import numba\n@numba.njit(cache=True)\ndef k(a,b,c,d,e,f,g,h,i,j,k,l,m): pass\n"
           "class C:\n    def m(self, a, *b, c, **d): pass\n")
    tree = ast.parse(src)
    for node in ast.walk(tree):
        for child in ast.iter_child_nodes(node):
            child.parent = node
    k, m = (n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef))
    assert _is_numba_kernel(k) and _n_params(k) == 13
    assert not _is_numba_kernel(m) and _n_params(m) == 4


# --------------------------------------------------------------------------- one home per rule
def _functions(files):
    """(file, function node) of every function, innermost first for nested ones."""
    for p in files:
        for node in ast.walk(_tree(p)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                yield p, node


def _enclosing_function(node):
    while node is not None and not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
        node = getattr(node, "parent", None)
    return node


def _consts(node) -> list:
    return [n.value for n in ast.walk(node) if isinstance(n, ast.Constant)
            and isinstance(n.value, (int, float, complex)) and not isinstance(n.value, bool)]


def test_one_modal_damping_rule():
    """[4.11]: zeta = 1e-3 (n = 0), 1e-2 (n = 1), 1e-4 (n >= 2).  A home of the rule is a function
    holding the three values itself, or a short module-level expression holding them (a table)."""
    rule = {1e-3, 1e-2, 1e-4}
    homes = []
    for p in _files(*LAYERS):
        tree = _tree(p)
        for stmt in tree.body:  # a module-level table: a short expression holding the three values
            if not isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                small = [n for n in ast.walk(stmt) if rule <= set(_consts(n)) and len(ast.unparse(n)) <= 300]
                if small:
                    homes.append(f"{_rel(p)}:{stmt.lineno} module level: {ast.unparse(small[-1])[:80]}")
        for fn in (n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))):
            own = {n.value for n in ast.walk(fn) if isinstance(n, ast.Constant) and _enclosing_function(n) is fn
                   and isinstance(n.value, float)}
            if rule <= own:
                homes.append(f"{_rel(p)}:{fn.lineno} {fn.name}")
    named = [f"{_rel(p)}:{fn.lineno}" for p, fn in _functions(_files(*LAYERS)) if fn.name == "modal_damping"]
    assert homes, "no home of the modal damping rule [4.11] found (a function holding 1e-3, 1e-2 and 1e-4)"
    assert len(homes) == 1, "the modal damping rule [4.11] is written in:\n" + "\n".join(homes)
    assert len(named) <= 1, "modal_damping is defined in:\n" + "\n".join(named)


def _modal_frf_sites(p: Path) -> list[str]:
    """The products 2j * zeta * w * W (the damping term of the modal FRF) in ``p``: one per 2j
    factor whose product chain mentions zeta."""
    sites = []
    for node in ast.walk(_tree(p)):
        if isinstance(node, ast.Constant) and isinstance(node.value, complex) and node.value == 2j:
            chain = node
            while isinstance(getattr(chain, "parent", None), ast.BinOp) and isinstance(chain.parent.op, ast.Mult):
                chain = chain.parent
            if "zeta" in ast.unparse(chain).lower():
                fn = _enclosing_function(node)
                sites.append(f"{_rel(p)}:{node.lineno} {fn.name if fn else '<module>'}: {ast.unparse(chain)}")
    return sites


def test_one_modal_frf():
    sites = [s for p in _files(*LAYERS) for s in _modal_frf_sites(p)]
    assert len(sites) == 1, "the modal FRF 1/(m_r (w_r^2 - W^2 + 2 i zeta_r w_r W)) is written in:\n" + "\n".join(sites)


def test_the_frf_finder_finds_a_copy(tmp_path):
    p = tmp_path / "x.py"
    p.write_text("def h(m, w, W, zeta):\n    return 1 / (m * (w**2 - W**2 + 2j * zeta * w * W))\n"
                 "def g(f, t):\n    return np.exp(-2j * np.pi * f * t)\n")
    global ROOT
    old, ROOT = ROOT, tmp_path
    try:
        assert len(_modal_frf_sites(p)) == 1
    finally:
        ROOT = old


RENAMES = {("os", "replace"), ("os", "rename"), ("shutil", "move")}


def test_one_atomic_write():
    """Every rename-into-place is inside the one helper, ``atomic_write`` (pipeline/)."""
    files = _files(*{p.parent.name for p in ROOT.glob("*/__init__.py")})
    helpers = [f"{_rel(p)}:{fn.lineno}" for p, fn in _functions(files) if fn.name == "atomic_write"]
    bad = []
    for p in files:
        for node in ast.walk(_tree(p)):
            if not isinstance(node, ast.Call) or not isinstance(node.func, ast.Attribute):
                continue
            f = node.func
            module_call = isinstance(f.value, ast.Name) and (f.value.id, f.attr) in RENAMES
            path_method = f.attr in ("replace", "rename") and len(node.args) == 1 and not node.keywords
            fn = _enclosing_function(node)
            if (module_call or path_method) and not (fn is not None and fn.name == "atomic_write"):
                bad.append(f"{_rel(p)}:{node.lineno} {ast.unparse(node)}")
    assert len(helpers) == 1, "atomic_write is defined in:\n" + "\n".join(helpers)
    assert not bad, "renames outside pipeline's atomic_write (use it instead):\n" + "\n".join(bad)


def _signal(node) -> str:
    """The identifiers in ``node`` (names, attributes, identifier-like strings such as keys)."""
    out = []
    for n in ast.walk(node):
        if isinstance(n, ast.Name):
            out.append(n.id)
        elif isinstance(n, ast.Attribute):
            out.append(n.attr)
        elif isinstance(n, ast.arg):
            out.append(n.arg)
        elif isinstance(n, ast.Constant) and isinstance(n.value, str) and n.value.isidentifier():
            out.append(n.value)
    return " ".join(out).lower()


def _squeal_scope(node):
    """What a numeric literal belongs to: its dict entry, or the statement's expression
    (with an assignment's targets); None inside an f-string's formatting."""
    up = node
    while not isinstance(getattr(up, "parent", None), (ast.stmt, type(None))):
        parent = up.parent
        if isinstance(parent, ast.FormattedValue):
            return None
        if isinstance(parent, ast.Dict):
            if up in parent.values:
                i = parent.values.index(up)
                return ast.Tuple(elts=[k for k in (parent.keys[i], up) if k is not None])
            i = parent.keys.index(up)
            return ast.Tuple(elts=[up, parent.values[i]])
        up = parent
    stmt = up.parent
    if isinstance(stmt, ast.Assign):
        return ast.Tuple(elts=[*stmt.targets, up])
    if isinstance(stmt, (ast.AnnAssign, ast.AugAssign)):
        return ast.Tuple(elts=[stmt.target, up])
    return up


def _spec_constant_copies(p: Path) -> list[str]:
    found = []
    for node in ast.walk(_tree(p)):
        if not isinstance(node, ast.Constant) or isinstance(node.value, bool) \
                or not isinstance(node.value, (int, float)):
            continue
        if node.value == 6500:
            found.append(f"{_rel(p)}:{node.lineno} the band top {node.value!r} (F_MAX_HZ)")
        elif node.value == 10 and (scope := _squeal_scope(node)) is not None:
            # the squeal level: a 10 in an expression, assignment or dict entry about squeal / L_F2
            if "squeal" in _signal(scope) or "l_f2" in _signal(scope):
                found.append(f"{_rel(p)}:{node.lineno} the squeal level 10 (SQUEAL_LEVEL_DB): "
                             f"{ast.unparse(scope)[:120]}")
    for node in ast.walk(_tree(p)):
        if isinstance(node, ast.Dict):
            keys = {_literal(k) for k in node.keys if k is not None}
            if len(keys & {-0.005, -0.01, -0.015}) >= 2:
                found.append(f"{_rel(p)}:{node.lineno} the thesis contact-position table (THESIS_CONTACT_POSITIONS)")
        elif isinstance(node, ast.Tuple) and _literal(node) in ((-0.032, 0.012), (0.005, -0.016), (-0.004, -0.012)) \
                and not isinstance(node.parent, ast.Dict):
            found.append(f"{_rel(p)}:{node.lineno} a thesis contact position {ast.unparse(node)}")
    return found


def _literal(node):
    try:
        return ast.literal_eval(node)
    except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
        return None


def test_spec_constants_live_in_solvers_constants():
    copies = [c for p in _files(*LAYERS) if _rel(p) != CONSTANTS for c in _spec_constant_copies(p)]
    assert not copies, f"SPEC constants written outside {CONSTANTS} (import them from there):\n" + "\n".join(copies)


def test_solvers_constants_holds_them():
    found = _spec_constant_copies(ROOT / CONSTANTS)
    assert any("F_MAX_HZ" in f for f in found) and any("SQUEAL_LEVEL_DB" in f for f in found) \
        and any("THESIS_CONTACT_POSITIONS" in f for f in found), found
