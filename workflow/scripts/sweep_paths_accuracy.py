"""Snakemake script: the sweep-path study's untimed half (see rule sweep_paths_accuracy)."""
from sphereimpact.numerics.sweep_paths import write_accuracies
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "sweep-path study accuracy"):
    write_accuracies(snakemake.output.json, sizes=snakemake.params.config["bench"]["path_sizes"])
