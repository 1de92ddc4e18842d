"""Snakemake script: one numerical study (rule work_precision, stability or ablation)."""
import logging

from sphereimpact.study import numerics

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
logging.info("running %s", snakemake.rule)
if snakemake.rule == "ablation":
    numerics.write_ablation(snakemake.params.config, snakemake.input.published, snakemake.output.csv)
else:
    getattr(numerics, f"write_{snakemake.rule}")(snakemake.params.config, snakemake.output.csv)
