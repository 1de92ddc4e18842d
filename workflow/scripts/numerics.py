"""Snakemake script: one numerical study (rule work_precision, ablation or microslip_resolution)."""
from sphereimpact.study.numerics import write_study
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], f"study {snakemake.rule}"):
    write_study(snakemake.rule, snakemake.params.config, snakemake.output.csv,
                published=getattr(snakemake.input, "published", None),
                references=getattr(snakemake.input, "references", None))
