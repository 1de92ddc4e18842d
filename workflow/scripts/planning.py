"""Snakemake script: the measurement-plan study (see rule planning)."""
import os

from sphereimpact.study.planning import planning_study
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "plan measurements"):
    out = snakemake.output
    planning_study(snakemake.params.config, snakemake.input.data, snakemake.input.schema,
                   {"kharaz": os.path.dirname(out.kharaz[0]), "figure": out.figure, "checks": out.checks,
                    "tennis": os.path.dirname(out.tennis[0]), "plan_md": out.plan_md, "checks_md": out.checks_md})
