"""Snakemake script: the sweep-path study (see rule sweep_paths)."""
from sphereimpact.study.workflow import job_log
from sphereimpact.numerics.sweep_paths import run

with job_log(snakemake.log[0], "sweep-path study"):
    bench = snakemake.params.config["bench"]
    run(snakemake.output.csv, sizes=bench["path_sizes"], repeats=bench["repeats"],
        accuracy_json=snakemake.input.accuracy)
