"""Snakemake script: the model against Kharaz et al. (2001) (see rule validation)."""
from sphereimpact.study.validation import write_validation
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "validation against Kharaz et al. (2001)"):
    out = snakemake.output
    write_validation(snakemake.params.config, snakemake.input.data, out.residuals, out.summary, out.curves, out.maw)
