"""What the Snakemake rules need from the package: config subsets, source dependencies, job logs.

Snakemake reruns a job when its ``params`` or its input files change.  So that a change reruns exactly
what depends on it:

- each rule's ``params`` carry only the config keys its job reads (:data:`RULE_KEYS`,
  :func:`config_subset`): ``--config samples=201`` reruns the history runs, not the benchmarks;
- the package modules a job imports, followed through the package's own imports, are inputs of that
  job (:func:`package_sources`): editing ``normal.py`` reruns every computation that uses it.

A key missing from :data:`RULE_KEYS` cannot go unnoticed: the job that reads it fails with a
``KeyError`` naming it.
"""

from __future__ import annotations

import ast
import contextlib
import hashlib
import logging
import re
import traceback
from functools import cache
from pathlib import Path

from .config import SCENE_KEYS

_SCENE = tuple(SCENE_KEYS)
_SOLVER = ("method", "rtol", "atol")

#: Rule -> the config keys its job reads (``a.b`` selects one entry of a section).
RULE_KEYS = {
    "simulate": (*_SCENE, *_SOLVER, "separations", "samples"),
    "replicate": (*_SCENE, *_SOLVER, "cases", "primary", "compliance.poisson"),
    "figure": ("primary.separation",),
    "figure_index": ("primary.separation",),
    "work_precision": (*_SCENE, "cases", "primary", "numerics.methods", "numerics.tolerances",
                       "numerics.cost_cap", "numerics.domain"),
    "stability": (*_SCENE, "numerics.methods", "numerics.stability"),
    "numerics_references": (*_SCENE, "cases", "primary", "numerics.domain", "numerics.stability"),
    "ablation": (*_SCENE, "cases", "primary"),
    "microslip_resolution": ("numerics.microslip", "validation", "bench.repeats"),
    "sweep_shard": (*_SCENE, "primary", "sweep.angle", "sweep.speed", "sweep.target"),
    "speed_table": (*_SCENE, *_SOLVER, "models", "primary", "sweep.cor_speed", "sweep.target"),
    "sweep_map": ("speed", "cases", "sweep.map_speed", "compliance.poisson"),
    "bench": (*_SCENE, "cases", "primary", "bench.repeats", "bench.domain", "bench.kernels", "bench.startup",
              "numerics.microslip", "validation"),
    "bench_sweep": ("bench.repeats", "bench.sample", "bench.lanes", "bench.million", "bench.laws", "bench.fit",
                    "validation", "kharaz_fit"),
    "bench_sweep_accuracy": ("bench.sample", "bench.lanes", "bench.million", "bench.laws"),
    "sweep_paths": ("bench.repeats", "bench.path_sizes"),
    "sweep_paths_accuracy": ("bench.path_sizes",),
    "bench_kernels": ("bench.repeats",),
    "consistency": ("consistency",),
    "readme": ("primary",),
    "laws": (*_SCENE, "samples", "laws.models", "laws.cor", "laws.speed", "laws.speeds"),
    "cor_relations": (*_SCENE, "laws.speed", "laws.relation_models", "laws.relation_cors"),
    "validation": ("validation",),
    "dem_departure": ("validation",),
    "kharaz_fit": ("validation", "kharaz_fit"),
    "planning": ("validation", "planning"),
    "compliance_map": (*_SCENE, "compliance", "primary"),
    "validation_figures": ("compliance",),
    "own_fit": ("study", "plugins", "ball_file", "ball", "surface", "contact", "fit"),
    "own_ball": ("study", "plugins", "ball_file", "ball", "surface", "contact"),
    "own_bounces": ("study", "plugins", "bounces", "samples"),  # plugins: the ball file's, which it never imports
    "own_speed": ("study", "plugins", "ranges"),
    "own_maps": ("study", "plugins", "ranges"),
    "own_bounce_figure": ("study", "contact.separation"),
    "own_plan": ("study", "plugins", "plan"),
    "own_figures": ("study", "plugins"),
    "own_page": ("study", "plugins", "contact", "bounces", "fit"),
}


#: Config sections without a schema default: absent unless the config gives them.
OPTIONAL = ("fit", "plan")


def config_subset(config: dict, rule: str, case: str | None = None) -> dict:
    """The part of ``config`` that ``rule``'s job reads (see :data:`RULE_KEYS`).

    Parameters
    ----------
    config : dict
        The validated configuration (schema defaults filled in).
    rule : str
        A key of :data:`RULE_KEYS`.
    case : str, optional
        Restrict ``cases`` to this one case (and include it even when the rule lists no ``cases``).
    """
    out: dict = {}
    for key in RULE_KEYS[rule]:
        section, _, entry = key.partition(".")
        if entry:
            out.setdefault(section, {})[entry] = config[section][entry]
        elif key in config or key not in OPTIONAL:
            out[key] = config[key]
    if case is not None:
        out["cases"] = {case: config["cases"][case]}
    return out


_PACKAGE = Path(__file__).resolve().parents[1]


@cache
def _module_file(name: str) -> Path | None:
    """The source file of ``sphereimpact.<...>`` module ``name``, or None outside the package."""
    parts = name.split(".")
    if parts[0] != _PACKAGE.name:
        return None
    base = _PACKAGE.joinpath(*parts[1:])
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


#: Import statements at the start of a line (indented ones too: imports inside functions count): ``import
#: a.b, c`` and ``from .x import y, (z, ...)``.  A scan of the text, not a parse: a snakemake run resolves the
#: sources of every rule's scripts, and parsing the package's syntax trees cost a second of each run; the
#: scan agrees with :func:`_parsed_imports` on every file of the project (tests/test_workflow_support.py).
_IMPORT = re.compile(r"^[ \t]*(?:import[ \t]+([^\n#;]*)|from[ \t]+(\.*)([\w.]*)[ \t]+import[ \t]+"
                     r"(\([^)]*\)|(?:[^\n#;\\]|\\\n)*))", re.M)


def _package_of(path: Path) -> str:
    """The package a relative import in ``path`` starts from: its folder (an __init__.py's own package)."""
    return ".".join(path.parent.relative_to(_PACKAGE.parent).parts) if _PACKAGE in path.parents else ""


def _absolute(package: str, level: int, module: str) -> str:
    if not level:
        return module
    anchor = package.split(".")[: len(package.split(".")) - level + 1]
    return ".".join([*anchor, module] if module else anchor)


@cache
def _imports(path: Path) -> frozenset[str]:
    """Absolute names of the modules ``path`` imports (relative imports resolved inside the package), and
    ``base.name`` for each ``from base import name`` (``from . import batch`` names a module)."""
    package, names = _package_of(path), set()
    for match in _IMPORT.finditer(_code(path.read_text(encoding="utf-8"))):
        plain, dots, module, imported = match.groups()
        if plain is not None:
            names.update(name.split(" as ")[0].strip() for name in plain.split(","))
            continue
        base = _absolute(package, len(dots), module)
        names.add(base)
        for item in re.sub(r"#[^\n]*|\\\n", " ", imported).strip("() \t\n").split(","):
            item = item.split(" as ")[0].strip()
            if item and item != "*":
                names.add(f"{base}.{item}")
    return frozenset(names)


def _code(text: str) -> str:
    """``text`` with its string literals blanked (a docstring's example ``from x import y`` is not code)."""
    return _STRING.sub(lambda m: '""' + "\n" * m.group(0).count("\n"), text)


_STRING = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'')


def _parsed_imports(path: Path) -> frozenset[str]:
    """What :func:`_imports` finds, by Python's own parser: the reference its scan is tested against."""
    package, names = _package_of(path), set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = _absolute(package, node.level, node.module or "")
            names.add(base)
            names.update(f"{base}.{a.name}" for a in node.names if a.name != "*")
    return frozenset(names)


@cache
def _closure(module: str) -> tuple[str, ...]:
    seen: set[Path] = set()
    named: set[str] = set()
    todo = [module]
    while todo:
        name = todo.pop()
        if name in named:
            continue
        named.add(name)
        parts = name.split(".")
        # a module's parent packages run their __init__ first
        for i in range(1, len(parts) + 1):
            path = _module_file(".".join(parts[:i]))
            if path is not None and path not in seen:
                seen.add(path)
                todo.extend(_imports(path))
    return tuple(sorted(str(p) for p in seen))


def file_sources(path: str) -> list[str]:
    """Package source files that the script or notebook at ``path`` runs: every package module it
    imports, directly or through other package modules (see :func:`package_sources`)."""
    return package_sources(*_imports(Path(path)))


def source_digest(paths) -> str:
    """The SHA-256 of the text of the source files ``paths`` (in sorted order, each with its name within the
    package): it changes exactly when one of them does, so a rule that takes it as a param reruns then."""
    digest = hashlib.sha256()
    for path in sorted(set(paths)):
        digest.update(_file_digest(path))
    return digest.hexdigest()


@cache
def _file_digest(path: str) -> bytes:
    """One source file's name within the package and the SHA-256 of its text, once per process (a Snakefile asks
    for the same files' digests once per rule)."""
    resolved = Path(path).resolve()
    name = resolved.relative_to(_PACKAGE.parent) if resolved.is_relative_to(_PACKAGE.parent) else resolved.name
    return str(name).encode() + b"\0" + hashlib.sha256(resolved.read_bytes()).digest() + b"\0"


def package_sources(*modules: str) -> list[str]:
    """Source files of ``modules`` and of every package module they import, directly or not.

    Parameters
    ----------
    *modules : str
        Dotted names, e.g. ``"sphereimpact.study.runs"``.

    Returns
    -------
    list of str
        Absolute paths, sorted; the files of the package as installed (an editable install points at
        ``src/``).
    """
    return sorted({p for m in modules for p in _closure(m)})


@contextlib.contextmanager
def job_log(path: str, what: str):
    """Log to ``path`` for the duration of one job; an exception's traceback is written there too.

    Snakemake shows the ``log:`` file of a failed job, so the traceback must reach it (Python would
    print it to the job's standard error only).  The exception is re-raised, so the job still fails.
    """
    logging.basicConfig(filename=path, level=logging.INFO, format="%(asctime)s %(levelname)s %(message)s",
                        force=True)
    logging.info("start: %s", what)
    try:
        yield
    except BaseException:
        logging.error("failed: %s\n%s", what, traceback.format_exc())
        raise
    logging.info("done: %s", what)


def job_seconds(path: str) -> float:
    """The wall time [s] of one job, from the benchmark file Snakemake's ``benchmark:`` directive wrote
    (tab-separated, its ``s`` column)."""
    with open(path, encoding="utf-8") as handle:
        header, values = handle.readline().rstrip("\n").split("\t"), handle.readline().rstrip("\n").split("\t")
    try:
        return float(values[header.index("s")])
    except (ValueError, IndexError) as err:
        raise ValueError(f"{path}: not a Snakemake benchmark file (no wall time in its 's' column)") from err
