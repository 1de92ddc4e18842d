"""The package's layers only point down, and no module imports itself through others: every import of every
module (those inside functions too; type hints under ``TYPE_CHECKING`` are not imports) is read off its source
(the equivalent of an import-linter contract, in the suite that CI runs)."""

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "sphereimpact"
#: The layers, from the ground up (README, "What each folder holds"): a module may import its own layer and
#: those below it.
LAYERS = (
    {"errors", "registry", "parsing", "memory", "plugins", "files", "choice", "kernel_cache", "arithmetic"},  # no physics
    {"ode"},  # ODE machinery: no physics
    {"contact"},  # what the contact is: laws, tangential models, the solved normal motion's contract
    {"integrators"},  # the normal motion of one impact
    {"impact"},  # one impact: Scene, simulate, the outputs of an end state, calibration
    {"sweep"},  # many impacts
    {"fit"},  # parameters from measured bounces, through the sweep
    {"numerics"},  # the numerical studies
    {"study", "figures"},  # the pipeline's studies and their drawings
    {"cli", "__main__", "__init__"},  # the command line and the public API
)


def _module(path: Path) -> str:
    parts = path.relative_to(SRC.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _layer(module: str) -> int:
    parts = module.split(".")
    top = parts[1] if len(parts) > 1 else "__init__"
    for level, names in enumerate(LAYERS):
        if top in names:
            return level
    raise AssertionError(f"{module}: in no layer (add its folder to LAYERS)")


def _type_checking(node) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


def imports(path: Path) -> set:
    """The package modules ``path`` imports anywhere in it but under ``if TYPE_CHECKING:``."""
    module = _module(path)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = set()

    def visit(node):
        if _type_checking(node):
            return
        if isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([node.module] if node.module else []))
            if base.startswith("sphereimpact"):
                for alias in node.names:  # a name that is a module is that module; else the module it is in
                    found.add(f"{base}.{alias.name}" if (SRC.parent / f"{base}.{alias.name}".replace(".", "/")).exists()
                              or (SRC.parent / (f"{base}.{alias.name}".replace(".", "/") + ".py")).exists() else base)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names if alias.name.startswith("sphereimpact"))
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(ast.parse(path.read_text(encoding="utf-8")))
    return found - {module}


MODULES = {_module(p): p for p in sorted(SRC.rglob("*.py"))}
GRAPH = {module: {t for t in imports(path) if t in MODULES} for module, path in MODULES.items()}


@pytest.mark.parametrize("module", sorted(MODULES))
def test_a_module_imports_only_its_layer_and_those_below(module):
    upward = sorted(t for t in GRAPH[module] if _layer(t) > _layer(module))
    assert not upward, f"{module} (layer {_layer(module)}) imports upward: {upward}"


def test_no_module_imports_itself_through_others():
    """No import cycle (Tarjan's strongly connected components of the import graph)."""
    index, low, stack, on_stack, cycles = {}, {}, [], set(), []

    def connect(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in GRAPH[v]:
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for v in GRAPH:
        if v not in index:
            connect(v)
    # a package's __init__ that imports its own modules, which import siblings through the package, is not a
    # loop of behaviour: only cycles through two or more modules that are not a package and its own members
    loops = [c for c in cycles if not all(m == c[0] or m.startswith(c[0] + ".") for m in c)]
    assert not loops, f"import cycles: {loops}"


def test_the_public_api_imports_from_the_package():
    from sphereimpact import LAWS, Scene, SolverOptions, simulate  # noqa: F401
    from sphereimpact.impact.calibrate import calibrate  # noqa: F401
    from sphereimpact.sweep import sweep  # noqa: F401

    assert simulate(Scene(angle=60.0)).cor == pytest.approx(0.865, abs=1e-3)  # the chapter's oblique case
