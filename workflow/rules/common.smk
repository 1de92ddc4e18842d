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


def figure_runs(wildcards):
    _, case, models, _ = FIGURES[wildcards.fig]
    return [f"results/runs/{case}_{model}.csv" for model in models]
