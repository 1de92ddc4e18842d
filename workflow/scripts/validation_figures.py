"""Snakemake script: the validation figures (see rule validation_figures)."""
from sphereimpact.figures.validation import compliance_map, kharaz, maw
from sphereimpact.contact.tangential import kappa_from_poisson
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "validation figures"):
    inp, out, section = snakemake.input, snakemake.output, snakemake.params.config["compliance"]
    kharaz(inp.curves, inp.data, inp.summary, [out.kharaz])
    maw(inp.curves, inp.maw, [out.maw])
    compliance_map(inp.map, kappa_from_poisson(section["poisson"]), section["tolerance"], [out.map])
