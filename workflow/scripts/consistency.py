"""Snakemake script: the differential test of the sweep's paths (see rule consistency)."""
from sphereimpact.numerics.consistency import run
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "consistency"):
    settings = snakemake.params.config["consistency"]
    run(snakemake.output.csv, snakemake.input.references, settings["rows"], settings["seed"])
