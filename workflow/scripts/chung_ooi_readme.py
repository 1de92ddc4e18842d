"""Snakemake script: the README's block of the Chung & Ooi tests (see rule chung_ooi_readme)."""
import os
from pathlib import Path

from sphereimpact.study.chung_ooi import readme_block
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "README block of the Chung & Ooi tests"):
    Path(snakemake.output.md).write_text(readme_block(os.path.dirname(snakemake.input.checks)), encoding="utf-8")
