"""Snakemake script: an own study's speed figure and maps (see rule own_figures)."""
from sphereimpact.figures.own import curves_and_maps
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "speed figure and maps"):
    out = snakemake.output
    curves_and_maps(snakemake.input.speed, snakemake.input.maps, snakemake.input.ball, snakemake.params.config["study"],
                    {"speed": out.speed, "spin_map": out.spin_map, "rebound_map": out.rebound_map},
                    snakemake.params.config.get("plugins", ()))
