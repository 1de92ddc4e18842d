# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Replicating Chapter 4: oblique impact of an elastic sphere on a rigid flat
#
# This notebook walks through what `snakemake --cores 2` produced: the summary of every case,
# force model and separation criterion, the comparison with each value the chapter prints, and
# the redrawn Figs 4.2–4.8. It runs from the repository root and only reads `results/` and
# `paper_figures/`; nothing here re-simulates.
#
# **The model.** A rigid sphere (I = α m R²) strikes a rigid flat vertically, on a flat inclined at the
# angle of each case. The normal force is the linear spring-damper of eq. 4.1 (the chapter's "previous"
# model, called `kelvin-voigt` in the package) or the chapter's eq. 4.2 (`modified`), whose damping is ramped
# in by 1 − exp(−c δ/R). Coulomb friction μP acts at the contact point. Because the flat is rigid and has no
# tangential compliance, the normal motion does not depend on friction: the package integrates only δ(t) and
# gets the tangential velocity and spin from the normal impulse. The parameters this run used:

# %%
import math

import pandas as pd
import yaml
from IPython.display import Image, Markdown, display

from sphereimpact.figures.catalog import FIGURES
from sphereimpact.study.replication import RESOLUTION, pulls

config = yaml.safe_load(open("results/config.yaml"))  # the configuration the pipeline ran
summary = pd.read_csv("results/summary.csv")
replication = pd.read_csv("results/replication.csv", keep_default_na=False)
display(Markdown(
    f"m = {config['mass'] * 1e3:g} g, D = {config['diameter'] * 1e3:g} mm, α = {config['inertia_factor']:g}, "
    f"k = {config['stiffness']:g} N/m, b = {config['damping']:g} N s/m, c = {config['ramp']:g}, "
    f"μ = {config['mu']:g}, approach speed {config['speed']:g} m/s, g = {config['gravity']:g} m/s²; cases: "
    + ", ".join(f"{name} ({case['angle']:g}°)" for name, case in config["cases"].items()) + "."))

# %% [markdown]
# ## Every case, model and separation criterion
#
# Times in seconds, lengths in metres (`delta_m` is the compression, positive; the chapter prints the
# centre's displacement, negative), velocities in m/s in the contact frame (t along the flat, n away from
# it). `force`: contact ends when P returns to 0 (a contact cannot pull); `penetration`: when δ returns
# to 0.

# %%
columns = ["case", "model", "separation", "t_m", "delta_m", "t_f", "ve_t", "ve_n", "omega_f", "cor", "regime",
           "force_min", "force_max"]
summary[columns]

# %% [markdown]
# Where the two separation criteria differ, the force would pull before δ returns to 0. A force counts as
# pulling only beyond the solver's resolution relative to the peak force (`RESOLUTION` in
# `sphereimpact.study.replication`, printed below); a smaller negative minimum is round-off at the event.

# %%
held = summary[summary.separation == "penetration"].assign(
    pulls=lambda f: [pulls(a, b) for a, b in zip(f.force_min, f.force_max)])
display(Markdown(f"Resolution: {RESOLUTION:g} of the peak force."))
display(held[["case", "model", "force_min", "force_max", "vc_n", "pulls"]])
cors = summary[summary.separation == config["primary"]["separation"]].pivot_table(
    index="case", columns="model", values="cor")
v_n = {name: config["speed"] * math.cos(math.radians(case["angle"])) for name, case in config["cases"].items()}
display(Markdown("COR by case and law (primary criterion): " + "; ".join(
    f"{case} (v_n = {v_n[case]:.3g} m/s): " + ", ".join(f"{m} {cors.loc[case, m]:.4f}" for m in cors.columns)
    for case in cors.index) + ". The linear law's COR does not depend on v_n; the modified law's does."))

# %% [markdown]
# ## The chapter's printed values
#
# `match`: the reproduction rounds to the printed value (within half a unit of its last digit);
# `agree`: within one unit; `discrepancy`: otherwise. Every non-match is explained by computing
# the alternatives (see `results/replication.md` for the full table of hypotheses).

# %%
replication[["id", "printed", "reproduced", "status", "explanation"]]

# %%
counts = replication.status.value_counts()
display(Markdown(f"**{counts.get('match', 0)} match, {counts.get('agree', 0)} agree, "
                 f"{counts.get('discrepancy', 0)} discrepancy** out of {len(replication)} printed values."))
for _, row in replication[replication.status != "match"].iterrows():
    display(Markdown(f"- `{row.id}`: printed {row.printed}; reproduced {row.reproduced:.5g} ({row.status}). "
                     f"{row.explanation}."))

# %% [markdown]
# What the hypotheses show: each printed value recomputed under every hypothesis (✓ where it matches the
# print), read from the report the pipeline wrote.

# %%
report = open("results/replication.md", encoding="utf-8").read()
display(Markdown(report[report.index("## Hypotheses tested"):]))

# %% [markdown]
# ## The figures
#
# Histories are drawn under the separation criterion the table above uses (`primary.separation` in the
# config), so a figure and the table show the same contact; the other criterion's end is marked on each
# figure, and in Figs 4.7 and 4.8 a thin line continues a law to δ = 0 where that criterion ends it
# elsewhere, with the least force it would reach. The chapter's printed values are marked in red; each
# figure's caption, with its numbers read from the run files, is in `paper_figures/README.md`.

# %%
for name, spec in FIGURES.items():
    if spec.case in config["cases"] and all(m in config["models"] for m in spec.models):
        display(Image(filename=f"paper_figures/{name}.png"))

# %% [markdown]
# In Figs 4.7 and 4.8 the previous model (dashed) starts at P = b v_n, not 0, and, held to δ = 0 (thin
# line), pulls, as the chapter says; under the force criterion its contact ends at P = 0 with δ > 0 instead.
# The modified model (solid) starts from zero. Whether it also pulls at the end is measured, case by case,
# in the figures' thin lines, the table above and the findings: near δ = 0, P ≈ δ(k + c b δ̇/R), which is negative
# whenever the rebound speed exceeds kR/(c b). The chapter's conclusion that the modified model has no
# negative force holds only for the cases whose rebound stays below that speed.
