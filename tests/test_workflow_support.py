"""What the rules ask of the package: config subsets and the package sources each job runs."""

import contextlib
import io
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from sphereimpact.arithmetic import SAME_ARITHMETIC, same_arithmetic
from sphereimpact.study.config import with_defaults
from sphereimpact.study.workflow import RULE_KEYS, config_subset, file_sources, package_sources

ROOT = Path(__file__).resolve().parents[1]
#: The shipped configuration with the schema's defaults filled in, as snakemake fills them before any job.
CONFIG = with_defaults(yaml.safe_load((ROOT / "config/schema.yaml").read_text()),
                       yaml.safe_load((ROOT / "config/config.yaml").read_text()))


def names(paths):
    """Each path as folder/file, e.g. ``figures/paper.py``."""
    return {"/".join(Path(p).parts[-2:]) for p in paths}


def test_subset_holds_only_the_listed_keys():
    got = config_subset(CONFIG, "sweep_shard")
    assert set(got) == {"mass", "diameter", "inertia_factor", "mu", "stiffness", "damping", "ramp", "speed",
                        "gravity", "primary", "sweep"}
    assert set(got["sweep"]) == {"angle", "speed", "target"}
    assert config_subset(CONFIG, "simulate", case="oblique60")["cases"] == {"oblique60": {"angle": 60.0}}


def test_every_listed_key_exists_in_the_config():
    for rule in RULE_KEYS:
        config_subset(CONFIG, rule)  # KeyError names a key the config lacks


def test_the_figure_catalogue_pulls_in_no_drawing_code():
    """The catalogue (read by every figure rule's plan) tracks the public API it imports, and neither the
    drawing modules nor the studies: editing a figure does not rerun the plan of every other one."""
    sources = names(package_sources("sphereimpact.figures.catalog"))
    assert {"figures/catalog.py", "impact/solve.py", "impact/planar.py"} <= sources  # planar: inside a function
    drawing = {name for name in sources if name.startswith(("figures/", "study/", "numerics/", "sweep/"))}
    assert drawing == {"figures/__init__.py", "figures/catalog.py"}


def test_the_import_scan_agrees_with_the_parser(tmp_path):
    """Source tracking scans the text for imports (a parse of every module cost a second of each snakemake
    run): on every Python file of the project, and on the awkward forms, it finds what Python's parser
    finds."""
    from sphereimpact.study.workflow import _imports, _parsed_imports

    tricky = tmp_path / "tricky.py"
    tricky.write_text('"""Docs: from os import path."""\nimport numpy as np, json as j\nfrom math import (sin,  # s\n'
                      "    cos)\nfrom collections import \\\n    OrderedDict\ndef f():\n    import csv\n"
                      "x = 'import re'\n")
    files = [tricky, *ROOT.glob("src/**/*.py"), *ROOT.glob("workflow/scripts/*.py"), *ROOT.glob("notebooks/*.py"),
             *ROOT.glob("tests/*.py"), *ROOT.glob("tools/*.py")]
    assert len(files) > 100
    for path in files:
        assert _imports(path) == _parsed_imports(path), path
    assert _imports(tricky) == {"numpy", "json", "math", "math.sin", "math.cos", "collections",
                                "collections.OrderedDict", "csv"}


def test_sources_follow_imports_through_the_package():
    figure = names(file_sources(str(ROOT / "workflow/scripts/figure.py")))
    assert {"figures/paper.py", "figures/style.py", "figures/catalog.py", "study/replication.py",
            "study/workflow.py"} <= figure
    assert "sweep/batch.py" not in figure and "numerics/stability.py" not in figure
    shard = names(file_sources(str(ROOT / "workflow/scripts/sweep_shard.py")))
    assert {"sweep/batch.py", "sweep/similarity.py", "study/sweeps.py"} <= shard
    assert not any(n.startswith("figures/") for n in shard)


def test_an_unknown_rule_is_a_key_error():
    with pytest.raises(KeyError):
        config_subset(CONFIG, "no_such_rule")


def test_conda_environment_mirrors_environment_txt():
    """`--sdm conda` must install what `pip install -r environment.txt` does (minus the workflow tools)."""
    pins = {line.split("#")[0].strip() for line in (ROOT / "environment.txt").read_text().splitlines()}
    conda = yaml.safe_load((ROOT / "workflow/envs/sphereimpact.yaml").read_text())
    pip = {p for entry in conda["dependencies"] if isinstance(entry, dict) for p in entry["pip"]}
    tool_names = ("snakemake", "pytest", "pytest-xdist", "ruff", "snakemake-executor-plugin-slurm")
    tools = {p for p in pins if p.split("==")[0] in tool_names}
    assert {p for p in pins if "==" in p} - tools == {p for p in pip if "==" in p}


def test_every_figure_has_a_caption_and_the_committed_index_holds_them():
    """paper_figures/README.md (committed, rewritten by every run; `.ci/run` fails when the full pipeline writes
    it otherwise) is the folder's index a reader sees: it holds every figure the pipeline draws, each with its
    caption."""
    from sphereimpact.figures.captions import CAPTIONS
    from sphereimpact.figures.catalog import FIGURES
    from sphereimpact.figures.numerics import CHARTS
    from sphereimpact.figures.sweeps import MAPS

    targets = (ROOT / "workflow/rules/common.smk").read_text()  # chapter_outputs(): what the pipeline makes
    chung_ooi = {f"chung_ooi_test{n}" for n in range(1, 9)}
    drawn = {*FIGURES, *CHARTS, *MAPS, "laws_cor_speed", "laws_force", "validation_kharaz", "validation_maw",
             "compliance_map", "plan_kharaz", "dem_departure", *chung_ooi}
    assert set(CAPTIONS) == drawn
    assert all(f'"{name}"' in targets or f'"paper_figures/{name}.png"' in targets or name in FIGURES
               or name in CHARTS or name in chung_ooi
               for name in drawn)  # each one the pipeline asks for (the charts and tests by pattern)
    index = (ROOT / "paper_figures/README.md").read_text()
    assert all(f"**{name}.png**: {caption}" in index for name, (_, caption) in CAPTIONS.items())


def test_the_config_offers_every_notebook_and_the_replication_runs_them_all():
    """``notebooks`` chooses the notebooks executed (the test config one, to keep the suite short): its allowed
    names and the schema's default are the notebooks the project ships, and the shipped config runs every one."""
    schema = yaml.safe_load((ROOT / "config/schema.yaml").read_text())["properties"]["notebooks"]
    shipped = sorted(p.stem for p in (ROOT / "notebooks").glob("*.py"))
    assert sorted(schema["items"]["enum"]) == shipped and sorted(schema["default"]) == shipped
    assert sorted(CONFIG["notebooks"]) == shipped
    rules = (ROOT / "workflow/rules/common.smk").read_text()
    assert sorted(re.findall(r'^    "(\w+)": \[', rules[rules.index("NOTEBOOKS = {"):], re.M)) == shipped


def test_building_the_jobs_imports_no_solver():
    """Every snakemake start (each dry run, the tests' many) reads the Snakefile: the package modules its rules
    import give constants and checks, and must not pull in the solvers' scipy (half a second a start)."""
    import subprocess
    import sys

    lines = [line for path in sorted((ROOT / "workflow/rules").glob("*.smk")) for line in path.read_text().splitlines()
             if re.match(r"(from|import) sphereimpact", line)]
    assert lines  # the scan reads the rules' own imports
    script = "\n".join([*lines, "import sys", "print(sorted(m for m in ('scipy.integrate', 'scipy.optimize') "
                        "if m in sys.modules))"])
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True, cwd=ROOT)
    assert run.stdout.strip() == "[]"


def test_the_jobs_arithmetic_is_pinned_to_avx2_only_where_the_processor_has_it():
    assert same_arithmetic(frozenset({"sse2", "avx2", "fma", "avx512f"})) == SAME_ARITHMETIC
    assert same_arithmetic(frozenset({"sse2", "avx2", "fma"})) == SAME_ARITHMETIC
    assert same_arithmetic(frozenset({"sse2", "avx"})) == {}  # OpenBLAS's Haswell kernels would not run
    assert same_arithmetic(frozenset()) == {}  # another architecture, or no /proc/cpuinfo


#: How many of 20000 arguments numpy's vectorised exp, expm1, log and power evaluate otherwise than the C library
#: (math); printed by a process of its own.
DIFFERING_BITS = (
    "import math, numpy as np\n"
    "x = np.random.default_rng(3).uniform(1e-3, 3.0, 20000)\n"
    "pairs = [(np.exp(x), math.exp), (np.expm1(-x), lambda v: math.expm1(-v)), (np.log(x), math.log),\n"
    "         (x ** 1.5, lambda v: v ** 1.5)]\n"
    "print(sum(int((a != np.array([f(v) for v in x.tolist()])).sum()) for a, f in pairs))\n")


def test_under_the_jobs_arithmetic_numpys_elementary_functions_are_the_c_librarys():
    """In a fresh process with the pipeline's variables (a job's), and in this test process (pinned by
    tests/conftest.py), numpy's elementary functions equal the C library's on every one of 20000 arguments, whatever
    the processor (with AVX-512 and without the variables, numpy's own routines differ on a few percent of them)."""
    env = os.environ | same_arithmetic()
    differing = subprocess.run([sys.executable, "-c", DIFFERING_BITS], env=env, capture_output=True, text=True,
                               check=True)
    assert differing.stdout.strip() == "0", differing.stderr
    assert {name: os.environ.get(name) for name in same_arithmetic()} == same_arithmetic()
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(DIFFERING_BITS, {})
    assert printed.getvalue().strip() == "0"
