"""Snakemake script: one failure-mode study (see rule stability_study)."""
from sphereimpact.study.numerics import write_stability
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"stability study {snakemake.wildcards.study}"):
    write_stability(snakemake.params.config, snakemake.output.csv, snakemake.wildcards.study,
                    snakemake.input.references or None)
