"""Snakemake script: one shard of the angle x speed sweep (see rule sweep_shard)."""
import logging

from sphereimpact.study.sweeps import write_shard

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
logging.info("shard %d of %d", snakemake.params.shard, snakemake.params.shards)
write_shard(snakemake.params.config, snakemake.params.shard, snakemake.params.shards, snakemake.output.csv)
