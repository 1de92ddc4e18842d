# Validate the configuration before any job runs; helpers shared by the rules.
import os

from snakemake.utils import validate

from sphereimpact.arithmetic import pin_arithmetic
from sphereimpact.figures.captions import CAPTIONS
from sphereimpact.figures.catalog import FIGURES
from sphereimpact.fit import FIT_FILES, PLAN_FILES
from sphereimpact.study.chung_ooi_definition import variant_tests
from sphereimpact.study.config_check import check_config
from sphereimpact.study.readme import TIMING_CHARTS
from sphereimpact.study.workflow import config_subset, file_sources, source_digest


# Every job computes with the same arithmetic on any x86-64 processor with AVX2 (numpy without its AVX-512 routines,
# OpenBLAS's Haswell kernels): the same bytes on every such machine.  A variable the user set is kept.
pin_arithmetic()
# A sweep in a job keeps its one-at-a-time scenes in its own process (sphereimpact.sweep.processes.JOBS_VARIABLE):
# Snakemake's scheduler, which runs jobs side by side, owns the cores.  A value the user set is kept.
os.environ.setdefault("SPHEREIMPACT_JOBS", "1")

# Fail at once, naming every bad key; then let snakemake fill the schema's defaults.
check_config(config, f"{workflow.basedir}/config/schema.yaml")
validate(config, schema="../../config/schema.yaml")

CASES = list(config["cases"])
MODELS = list(config["models"])
PUBLISHED = "config/published.yaml"
ENV = "../envs/sphereimpact.yaml"


def params_for(rule, case=None):
    """Only the config keys the rule's job reads, so that other edits do not rerun it."""
    return config_subset(config, rule, case)


def code(*files):
    """A digest of the package sources that project files (scripts, notebooks) run, followed through the
    package's own imports, as a rule's param: editing any of them reruns the job (snakemake's params trigger;
    a rule's script itself is tracked by snakemake) without listing some 50 files as the job's inputs."""
    return source_digest(p for f in files for p in file_sources(f"{workflow.basedir}/{f}"))


def notebook_code(wildcards):
    """The package sources a notebook and its runner import."""
    return code("workflow/scripts/notebook.py", f"notebooks/{wildcards.name}.py")


def run_files(ext):
    return expand("results/runs/{case}_{model}.{ext}", case=CASES, model=MODELS, ext=ext)


def drawable_figures():
    """Chapter figures whose case and force models are configured."""
    return [
        name
        for name, spec in FIGURES.items()
        if spec.case in CASES and all(m in MODELS for m in spec.models)
    ]


def figure_outputs():
    return expand("paper_figures/{fig}.{ext}", fig=drawable_figures(), ext=["png", "pdf"])


#: Notebook -> the results it reads.
NOTEBOOKS = {
    "replication": ["results/config.yaml", "results/summary.csv", "results/replication.csv"],
    "numerics": [
        "results/config.yaml",
        "results/work_precision.csv",
        "results/bench.csv",
        "results/bench_stages.csv",
        "results/bench_profile.csv",
        "results/stability.csv",
        "results/ablation.csv",
        "results/figures/work_precision.png",
        "paper_figures/stability.png",
        "results/microslip_resolution.csv",
        "results/figures/microslip_resolution.png",
    ],
    "laws": [
        "results/config.yaml",
        "results/laws_fitted.csv",
        "results/laws.csv",
        "results/cor_relations.csv",
        "paper_figures/laws_cor_speed.png",
        "paper_figures/laws_force.png",
    ],
    "validation": [
        "results/config.yaml",
        "results/validation.csv",
        "results/validation_summary.csv",
        "results/validation_curves.csv",
        "results/validation_maw.csv",
        "results/compliance_map.csv",
        "results/fit_kharaz/fit.json",
        "results/fit_kharaz/fit.png",
        "paper_figures/validation_kharaz.png",
        "paper_figures/validation_maw.png",
        "paper_figures/compliance_map.png",
    ],
    "chung_ooi": [
        "results/config.yaml",
        "results/chung_ooi/checks.csv",
        "results/chung_ooi/deviations.csv",
        *expand("results/chung_ooi/test{n}.csv", n=config["chung_ooi"]["tests"]),
        *expand("paper_figures/chung_ooi_test{n}.png", n=config["chung_ooi"]["tests"]),
        "results/chung_ooi/departure.csv",
        "paper_figures/dem_departure.png",
    ],
    "sweeps": [
        "results/config.yaml",
        "results/sweep/angle_speed.csv",
        "results/sweep/speed.csv",
        "results/bench_sweep.csv",
        "results/sweep_paths.csv",
        "results/compliance_map.csv",
        "paper_figures/spin_map.png",
        "paper_figures/cor_speed.png",
        "paper_figures/contact_speed.png",
        "results/figures/sweep_paths.png",
    ],
}


def notebook_inputs(wildcards):
    extra = figure_outputs() if wildcards.name == "replication" else []
    return NOTEBOOKS[wildcards.name] + extra


def captions(*names):
    """Each figure's caption (sphereimpact.figures.captions), for the report's caption template figure.rst."""
    return {name: CAPTIONS[name][1] for name in names}


def chapter_runs(fig):
    """The run files chapter figure ``fig`` draws, in its laws' order."""
    spec = FIGURES[fig]
    return [f"results/runs/{spec.case}_{model}.csv" for model in spec.models]


def figure_runs(wildcards):
    return chapter_runs(wildcards.fig)


def chapter_outputs():
    """Every table, figure and page of the replication (what `snakemake --cores 2` regenerates)."""
    return [
        "results/summary.csv",
        "results/summary.md",
        "results/replication.csv",
        "results/replication.md",
        *figure_outputs(),
        "results/bench.csv",
        "results/ablation.csv",
        "paper_figures/stability.png",
        *expand("results/figures/{study}.png", study=TIMING_CHARTS),
        *expand("paper_figures/{map}.png", map=["spin_map", "cor_speed", "contact_speed"]),
        "results/bench_sweep.csv",
        "results/cor_relations.csv",
        *expand("paper_figures/{fig}.png", fig=["laws_cor_speed", "laws_force"]),
        *expand("paper_figures/{fig}.png", fig=["validation_kharaz", "validation_maw", "compliance_map"]),
        "paper_figures/README.md",
        "paper_figures/plan_kharaz.png",
        "results/plan/checks.csv",
        "results/readme/plan.md",
        "results/readme/plan_checks.md",
        "results/readme/replication.md",
        "results/readme/speed.md",
        "results/readme/validation.md",
        "results/readme/consistency.md",
        "results/readme/fit.md",
        "results/consistency.csv",
        *expand("results/notebooks/{name}.html", name=config["notebooks"]),
        *expand("paper_figures/chung_ooi_test{n}.png", n=config["chung_ooi"]["tests"]),
        "results/readme/chung_ooi.md",
        "paper_figures/dem_departure.png",
        "results/readme/dem_departure.md",
    ]
