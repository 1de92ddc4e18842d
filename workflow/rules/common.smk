# Validate the configuration before any job runs; helpers shared by the rules.
from snakemake.utils import validate

from sphereimpact.figures.paper import FIGURES
from sphereimpact.study.config import check_config


# Fail at once, naming every bad key; then let snakemake fill the schema's defaults.
check_config(config, workflow.source_path("../../config/schema.yaml"))
validate(config, schema="../../config/schema.yaml")

CASES = list(config["cases"])
MODELS = list(config["models"])
PUBLISHED = "config/published.yaml"
ENV = "../envs/sphereimpact.yaml"


def config_for_case(case):
    """The config restricted to one case, so that editing another case does not rerun a job."""
    return {k: v for k, v in config.items() if k != "cases"} | {"cases": {case: config["cases"][case]}}


def run_files(ext):
    return expand("results/runs/{case}_{model}.{ext}", case=CASES, model=MODELS, ext=ext)


def drawable_figures():
    """Chapter figures whose case and force models are configured."""
    return [
        name
        for name, (_, case, models, _) in FIGURES.items()
        if case in CASES and all(m in MODELS for m in models)
    ]


def figure_outputs():
    return expand("paper_figures/{fig}.{ext}", fig=drawable_figures(), ext=["png", "pdf"])


#: Notebook -> the results it reads.
NOTEBOOKS = {
    "replication": ["results/summary.csv", "results/replication.csv"],
    "numerics": [
        "results/work_precision.csv",
        "results/bench.csv",
        "results/stability.csv",
        "results/ablation.csv",
        "paper_figures/work_precision.png",
        "paper_figures/stability.png",
    ],
    "sweeps": [
        "results/sweep/angle_speed.csv",
        "results/sweep/speed.csv",
        "results/bench_sweep.csv",
        "paper_figures/spin_map.png",
        "paper_figures/cor_speed.png",
        "paper_figures/contact_speed.png",
    ],
}


def notebook_inputs(wildcards):
    extra = figure_outputs() if wildcards.name == "replication" else []
    return NOTEBOOKS[wildcards.name] + extra


def figure_runs(wildcards):
    _, case, models, _ = FIGURES[wildcards.fig]
    return [f"results/runs/{case}_{model}.csv" for model in models]
