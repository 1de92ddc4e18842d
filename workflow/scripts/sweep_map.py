"""Snakemake script: one sweep map (see rule sweep_map)."""
import logging

from sphereimpact.figures.sweeps import contact_speed, cor_speed, spin_map

logging.basicConfig(filename=snakemake.log[0], level=logging.INFO)
name, out = snakemake.wildcards.map, [snakemake.output.png]
logging.info("drawing %s", name)
if name == "spin_map":
    spin_map(snakemake.input.angle_speed, snakemake.input.published, snakemake.params.map_speed, out)
elif name == "cor_speed":
    cor_speed(snakemake.input.speed, out)
else:
    contact_speed(snakemake.input.speed, out)
