"""Snakemake script: the README's generated blocks (see rule readme_snippets)."""
from sphereimpact.study.readme import write_snippets
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "README snippets"):
    inp, out = snakemake.input, snakemake.output
    write_snippets(snakemake.params.config, inp.replication, inp.findings, inp.bench, inp.bench_sweep,
                   inp.validation_summary, inp.validation, inp.consistency, inp.fit, out.replication, out.speed,
                   out.validation, out.consistency, out.fit)
