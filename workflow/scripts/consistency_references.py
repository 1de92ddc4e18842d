"""Snakemake script: one block of the differential test's references (see rule consistency_references)."""
from sphereimpact.numerics.consistency import reference_shard
from sphereimpact.study.workflow import job_log

with job_log(snakemake.log[0], "consistency references"):
    settings = snakemake.params.config["consistency"]
    reference_shard(settings["rows"], settings["seed"], snakemake.params.shard,
                    snakemake.params.shards).to_parquet(snakemake.output.parquet, index=False)
