"""Snakemake script: what each DEM tangential rule costs against the exact contact (see rule dem_departure)."""
from sphereimpact.study.departure import run_departure
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "DEM rules' departure from the exact contact"):
    out = snakemake.output
    run_departure(snakemake.params.config["validation"], snakemake.input.deviations, out.kharaz, out.departure)
