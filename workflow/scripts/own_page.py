"""Snakemake script: an own study's page (see rule own_page)."""
import os

from sphereimpact.study.own_outputs import write_page
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "the study's page"):
    inp, out = snakemake.input, snakemake.output
    here = os.path.dirname(out.md)
    fit = (inp.fit[1], os.path.relpath(inp.fit[3], here)) if inp.fit else None
    plan = (inp.plan[1], os.path.relpath(inp.plan[3], here)) if inp.plan else None
    figures = {os.path.splitext(os.path.basename(p))[0]: os.path.relpath(p, here) for p in inp.figures}
    write_page(snakemake.params.config, inp.ball, inp.outcomes, inp.speed, inp.maps, figures, out.md, out.html,
               list(inp.benchmarks), fit, plan)
