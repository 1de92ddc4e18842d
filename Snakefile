# Replication of Chapter 4 (oblique impact of an elastic sphere on a rigid flat).
# `snakemake --cores 2` regenerates every table and figure; see README.md.
# `snakemake --cores 2 --report results/report.html` then builds the HTML report of every figure and table.
from snakemake.utils import min_version

min_version("9.0")


configfile: "config/config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/report.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/numerics.smk"
include: "workflow/rules/sweep.smk"
include: "workflow/rules/laws.smk"
include: "workflow/rules/validation.smk"
include: "workflow/rules/notebook.smk"
include: "workflow/rules/own.smk"
include: "workflow/rules/benchmarks.smk"


if config["study"] == "chapter4":

    rule all:
        input:
            chapter_outputs(),
            "results/readme/runtime.md",
        default_target: True

else:  # a study of one's own ball: its own files only

    rule all:
        input:
            f"results/studies/{config['study']}/index.html",
            f"results/studies/{config['study']}/index.md",
        default_target: True
