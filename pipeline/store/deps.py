"""Make's source dependencies, computed from what each stage really imports.

``python pipeline/store/deps.py > build/deps.mk`` (stdlib only, run by the Makefile before the venv exists)
writes a Makefile fragment with, for every stage, the repository files whose code the
stage can reach:

    DEPS_radiate := pipeline/stages/radiate.py pipeline/config/loader.py ... solvers/radiation/thompson_jones.py

``python pipeline/store/deps.py --case pipeline/cases/<case>.toml`` prints the wheel and rail the
case names (the Makefile takes them from there, so the two cannot disagree); a curve wheel's
case file is ``$(BUILD)/curves/<curve>/cases/<wheel>.toml``.  ``--curve pipeline/curves/<curve>.toml``:
the curve's wheel (its vehicle's) and rail.  A file either names that is not there is one line naming
the file and the key that asked for it (before Make plans anything).

Reachability is followed at the level of top-level functions and classes, not whole
modules: from a stage's entry function, every name it references is resolved through the
imports in scope (module-level or inside the function) to a function, class or module of
the repository's packages, and so on transitively.  A module that is imported at all is a
dependency (its module-level code runs on import), but only the functions reached in it
are followed further.  So ``stages.radiate.run_radiate`` calling ``stages.wheel.load_wheel``
makes radiate depend on what ``load_wheel`` uses, not on the mode renderer that
``stages.wheel.run_shapes`` imports.  Over-approximations are harmless (an extra rebuild);
the analysis misses only names built at run time (``getattr(m, "f" + x)``,
``importlib``), which the stages do not use, except a package that finds its modules at run time (it says
so: ``DISCOVERS_SUBMODULES = True``, e.g. pipeline/study/kinds/): every module in it is followed, whole.

The only module names used here are the stages' entry points (``ENTRIES``, from the stage table
``pipeline/stages/__init__.py`` that the command line reads too); everything else is found from the
imports, so code moved between modules keeps its dependencies.
"""
from __future__ import annotations

import ast
import functools
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

if str(ROOT) not in sys.path:  # run as a script (pipeline/ first on the path): the package's stage table
    sys.path.insert(0, str(ROOT))
from pipeline.stages import STAGES  # noqa: E402  (standard library only, like this file)

# stage -> (entry module, entry function, the input it takes: wheel | rail | case), from the one stage table
ENTRIES = {name: (f"pipeline.{st.module}", st.function, st.takes) for name, st in STAGES.items() if st.make}


DEFS = (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)


def repo_packages(root: Path = ROOT) -> set[str]:
    """Top-level packages of the repository (folders holding an ``__init__.py``)."""
    return {p.parent.name for p in root.glob("*/__init__.py")}


_PARSED: dict[Path, tuple[tuple[int, int], ast.Module]] = {}   # path -> ((mtime_ns, size), its tree), read-only


def parse(path: Path) -> ast.Module:
    """The syntax tree of ``path``, parsed once per process while the file stays the same (mtime and size)."""
    st = path.stat()
    stamp = (st.st_mtime_ns, st.st_size)
    if path not in _PARSED or _PARSED[path][0] != stamp:
        _PARSED[path] = (stamp, ast.parse(path.read_text(), filename=str(path)))
    return _PARSED[path][1]


class Module:
    """One parsed module: its top-level definitions and, once imported, its module-level names."""

    def __init__(self, name: str, path: Path, is_package: bool):
        self.name, self.path = name, path
        self.package = name if is_package else name.rpartition(".")[0]
        self.tree = parse(path)
        self.defs = {n.name: n for n in self.tree.body if isinstance(n, DEFS)}
        self.ns: dict = {}  # names bound by module-level imports -> module name or (module, symbol)
        self.discovers = is_package and any(     # a package that imports its modules at run time
            isinstance(n, ast.Assign) and any(getattr(t, "id", "") == "DISCOVERS_SUBMODULES" for t in n.targets)
            for n in self.tree.body)


def _walk_outside_defs(body):
    """The nodes of ``body`` that run when it runs: nested function bodies excluded."""
    todo = list(body)
    while todo:
        node = todo.pop()
        yield node
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            todo += [*getattr(node, "decorator_list", []), *node.args.defaults,
                     *(d for d in node.args.kw_defaults if d is not None)]
        else:
            todo += list(ast.iter_child_nodes(node))


@functools.lru_cache(maxsize=None)
def _nodes(tree: ast.AST, outside_defs: bool = False) -> tuple:
    """Every node of ``tree`` (a parsed module's, shared through ``parse``), or those that run when its body runs."""
    return tuple(_walk_outside_defs(tree.body) if outside_defs else ast.walk(tree))


class Graph:
    """Function-level reachability over the repository's packages."""

    def __init__(self, root: Path = ROOT):
        self.root = root
        self.packages = repo_packages(root)
        self.modules: dict[str, Module | None] = {}
        self.files: set[Path] = set()
        self.seen: set[tuple[str, str]] = set()
        self.todo: list[tuple[str, str]] = []

    def module(self, name: str) -> Module | None:
        """The parsed repository module ``name`` (None outside the repository's packages)."""
        if name not in self.modules:
            self.modules[name] = None
            if name and name.split(".")[0] in self.packages:
                base = self.root.joinpath(*name.split("."))
                for path, pkg in ((base / "__init__.py", True), (base.with_suffix(".py"), False)):
                    if path.is_file():
                        self.modules[name] = Module(name, path, pkg)
                        break
        return self.modules[name]

    def load(self, name: str) -> Module | None:
        """Import ``name``: its parent packages and its module-level code run."""
        parts = name.split(".")
        for i in range(1, len(parts)):
            self.load(".".join(parts[:i]))
        mod = self.module(name)
        if mod is not None and mod.path not in self.files:
            self.files.add(mod.path)
            nodes = _nodes(mod.tree, outside_defs=True)
            mod.ns = self.bind(mod, nodes)
            self.refer(mod, {}, nodes)
            if mod.discovers:
                for sub in sorted(mod.path.parent.glob("[!_]*.py")):   # found at run time (importlib): all of them
                    self.load(f"{name}.{sub.stem}")
                    for fn in self.module(f"{name}.{sub.stem}").defs:
                        self.reach(f"{name}.{sub.stem}", fn)
        return mod

    def bind(self, mod: Module, nodes) -> dict:
        """Run the import statements among ``nodes``: the names they bind -> module or (module, symbol)."""
        ns: dict = {}
        for node in nodes:
            if isinstance(node, ast.Import):
                for a in node.names:
                    self.load(a.name)
                    ns[a.asname or a.name.split(".")[0]] = a.name if a.asname else a.name.split(".")[0]
            elif isinstance(node, ast.ImportFrom) and node.module != "__future__":
                base = node.module or ""
                if node.level:
                    pkg = mod.package.split(".")
                    base = ".".join([*pkg[: len(pkg) - node.level + 1], *([base] if base else [])])
                if self.load(base) is None:
                    continue  # not one of the repository's modules
                for a in node.names:
                    if a.name == "*":
                        for k in self.module(base).defs:
                            ns[k] = (base, k)
                    elif self.load(f"{base}.{a.name}") is not None:
                        ns[a.asname or a.name] = f"{base}.{a.name}"
                    else:
                        ns[a.asname or a.name] = (base, a.name)
                        self.reach(base, a.name)  # an imported name may be a constant or a re-export
        return ns

    def reach(self, module: str, name: str) -> None:
        if (module, name) not in self.seen:
            self.seen.add((module, name))
            self.todo.append((module, name))

    def refer(self, mod: Module, local: dict, nodes) -> None:
        """Mark every repository name referenced among ``nodes`` (scope: ``local``, then ``mod``) reachable."""
        for node in nodes:
            chain = []
            while isinstance(node, ast.Attribute):
                chain.insert(0, node.attr)
                node = node.value
            if not isinstance(node, ast.Name):
                continue
            target = local.get(node.id, mod.ns.get(node.id))
            if target is None:
                if node.id in mod.defs:
                    self.reach(mod.name, node.id)
            elif isinstance(target, tuple):
                self.reach(*target)
            else:
                for attr in chain:  # module.sub.symbol
                    if self.load(f"{target}.{attr}") is None:
                        self.reach(target, attr)
                        break
                    target = f"{target}.{attr}"

    def run(self) -> None:
        while self.todo:
            module, name = self.todo.pop()
            mod = self.load(module)
            if mod is None:
                continue
            if name in mod.defs:  # the whole body, nested functions and methods included
                nodes = _nodes(mod.defs[name])
                self.refer(mod, self.bind(mod, nodes), nodes)
            elif isinstance(mod.ns.get(name), tuple):  # re-exported from another module
                self.reach(*mod.ns[name])


def stage_files(module: str, function: str, root: Path = ROOT) -> list[str]:
    """The repository files (relative paths) that ``module.function`` can reach."""
    g = Graph(root)
    mod = g.load(module)
    if mod is None or function not in mod.defs:
        raise SystemExit(f"pipeline/store/deps.py: stage entry {module}.{function} not found; "
                         f"update the stage table pipeline/stages/__init__.py")
    g.reach(module, function)
    g.run()
    return sorted(p.relative_to(root).as_posix() for p in g.files)


def case_inputs(path: Path) -> tuple[str, str]:
    """(wheel, rail) named by the case file ``path`` (its top-level keys ``wheel``, ``rail``); a
    curve wheel's file (``<build>/curves/<curve>/cases/<wheel>.toml``) that is not there yet asks
    for ``make curve`` (one line)."""
    path = Path(path)
    if not path.exists() and path.parent.name == "cases" and path.parent.parent.parent.name == "curves":
        curve = path.parent.parent.name
        raise SystemExit(f"{path}: no case file for the curve wheel {curve}/{path.stem}: "
                         f"run make curve CURVE={curve} first")
    try:
        data = tomllib.loads(path.read_text())
        if not {"wheel", "rail"} <= set(data):
            raise KeyError(sorted({"wheel", "rail"} - set(data)))
    except (OSError, tomllib.TOMLDecodeError, KeyError) as e:
        raise SystemExit(f"{path}: cannot read the case's keys 'wheel' and 'rail' ({type(e).__name__}: {e})") from e
    return _named(path, "wheel", data, "geometry/wheels", "wheel"), _named(path, "rail", data, "geometry/rails", "rail")


def _named(source: Path, key: str, data: dict, folder: str, what: str, default: str | None = None) -> str:
    """The name under ``key`` in ``data`` (the file ``source``) of an input file <folder>/<name>.toml, checked
    to be there: otherwise one line naming ``source``, the key, the value and the files there (as
    ``pipeline.config.named_file`` words it).  A missing key: ``default`` (the Python stage names a
    required one)."""
    name = str(data.get(key, default) or "")
    if not name or (ROOT / folder / f"{name}.toml").is_file():
        return name
    have = sorted(p.stem for p in (ROOT / folder).glob("*.toml"))
    raise SystemExit(f"{source}: {key} = {name!r}: no such {what} file {folder}/{name}.toml; available: {have}")


def curve_inputs(path: Path) -> tuple[str, str]:
    """(wheel, rail) of the curve file ``path``: its vehicle file's ``wheel`` and its own ``rail``; the
    vehicle, wheel and rail files checked to be there and the vehicle's ``name`` to be its file's (a
    curve, a line and the build name a vehicle by its file): one line otherwise, naming the file and key."""
    path = Path(path)
    if not path.is_file():
        have = sorted(p.stem for p in path.parent.glob("*.toml"))
        raise SystemExit(f"{path}: no such curve file (available: {have})")

    def read(p: Path) -> dict:
        try:
            return tomllib.loads(p.read_text())
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
            raise SystemExit(f"{p}: cannot read it ({type(e).__name__}: {e})") from e

    data = read(path)
    vehicle = str(data.get("vehicle") or "")
    beside = path.parent / f"{vehicle}.toml"            # a user's vehicle beside the curve file comes first
    if vehicle and beside.is_file() and beside.resolve() != path.resolve():
        vpath = beside
    else:
        vehicle = _named(path, "vehicle", data, "geometry/vehicles", "vehicle")
        if not vehicle:
            raise SystemExit(f"{path}: vehicle: required (a vehicle file beside it or geometry/vehicles/<vehicle>.toml)")
        vpath = Path("geometry/vehicles") / f"{vehicle}.toml"
    v = read(ROOT / vpath)
    if v.get("name") != vehicle:
        raise SystemExit(f"{vpath}: name = {v.get('name')!r}: expected the file's name {vehicle!r} (a vehicle is "
                         "named by its file: rename one to match the other)")
    return (_named(vpath, "wheel", v, "geometry/wheels", "wheel", "c20"),
            _named(path, "rail", data, "geometry/rails", "rail", "bv50"))


def makefile_fragment(root: Path = ROOT) -> str:
    """``DEPS_<stage> := files`` for every stage, and an empty rule for each file."""
    lines = ["# generated by pipeline/store/deps.py from the stages' imports; do not edit"]
    every = set()
    for stage, (module, function, _) in ENTRIES.items():
        files = stage_files(module, function, root)
        every.update(files)
        lines.append(f"DEPS_{stage} := {' '.join(files)}")
    # a file moved or deleted must not stop Make before this fragment is regenerated
    lines += [f"{f}:" for f in sorted(every)]
    return "\n".join(lines) + "\n"


def main(argv: list[str]) -> int:
    """``deps.py``: print the fragment (the Makefile writes it to a temporary file and renames it);
    ``deps.py --case FILE``: print the case's wheel and rail."""
    if argv[:1] == ["--case"] and len(argv) == 2:
        print(*case_inputs(Path(argv[1])))
    elif argv[:1] == ["--curve"] and len(argv) == 2:
        print(*curve_inputs(Path(argv[1])))
    elif not argv:
        sys.stdout.write(makefile_fragment())
    else:
        print("usage: python pipeline/store/deps.py [--case pipeline/cases/<case>.toml | "
              "--curve pipeline/curves/<curve>.toml]", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
