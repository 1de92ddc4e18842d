# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Sweeps: the chapter's ball at every angle and speed
#
# A validated impact model invites the next questions: at 45°? at 20 m/s? with μ = 0.4? This notebook reads
# the sweep tables the pipeline wrote (`results/sweep/`, `results/bench_sweep.csv`) and the maps drawn from
# them. Nothing here re-simulates.
#
# **How the engine works.** In dimensionless form (τ = ω_n t, x = δ ω_n / v_n), the normal problem depends
# only on ζ = b/(2√(km)) and λ = c v_n/(ω_n R). Each scene takes the first of the engine's paths
# (`sphereimpact.sweep.paths`, listed below in their order) that can solve it; the table's `path` column
# says which one did.
#
# Tangential velocity and spin follow from the normal impulse, as in the single-impact core. Every path is
# held to the sweep's accuracy target against the single-impact reference on every output
# (tests/test_sweep.py); the benchmark below measures the error it reaches, and the last section what each
# path costs where several could serve.

# %%
import math

import numpy as np
import pandas as pd
import yaml
from IPython.display import Image, Markdown, display

from sphereimpact.figures.sweeps import grip_boundary
from sphereimpact.sweep.paths import PATHS

config = yaml.safe_load(open("results/config.yaml"))  # the configuration the pipeline ran
angle_speed = pd.read_csv("results/sweep/angle_speed.csv")
speed = pd.read_csv("results/sweep/speed.csv")
bench = pd.read_csv("results/bench_sweep.csv")
map_speed = float(config["sweep"]["map_speed"])
display(Markdown("\n".join(f"{i}. `{name}`: {summary}" for i, (name, summary) in enumerate(PATHS.items(), 1))))
display(Markdown(f"Angle × speed sweep: **{len(angle_speed)} scenes**, "
                 f"{angle_speed.angle.nunique()} angles × {angle_speed.speed.nunique()} speeds, solved by "
                 + ", ".join(f"{name} ({count})" for name, count in angle_speed.path.value_counts().items()) + "."))

# %% [markdown]
# ## Spin and slip against angle
#
# At small angles the contact point stops slipping before the ball leaves: it grips, rolls, and leaves with
# v_t = vt0/(1 + α) and no slip. Past the boundary tan β = (1 + 1/α) μ (1 + e), it slides throughout, and
# friction's impulse is μ times the normal impulse. The spin peaks at the boundary.

# %%
display(Image(filename="paper_figures/spin_map.png"))
at = angle_speed[np.isclose(angle_speed.speed, map_speed)].sort_values("angle")
boundary = grip_boundary(at)
oblique = {name: case["angle"] for name, case in config["cases"].items() if case["angle"] > 0}
sides = ", ".join(f"{name} ({angle:g}°) {'slides' if boundary is None or angle > boundary else 'grips'}"
                  for name, angle in oblique.items())
display(Markdown(f"At {map_speed:g} m/s: grip/slide boundary at **{boundary:.2f}°**, maximum spin "
                 f"{at.omega_f.max():.1f} rad/s at {at.loc[at.omega_f.idxmax(), 'angle']:g}° of this grid. "
                 f"The chapter's cases: {sides}." if boundary is not None else
                 f"At {map_speed:g} m/s there is no grip/slide boundary on this grid."))

# %% [markdown]
# The dotted curves are the same ball with a compliant tangential contact (a tangential spring κk, κ = 2/3
# for rubber, `results/compliance_map.csv`, drawn when the map is at the chapter's speed). Below the grip
# boundary the contact point no longer grips: it sticks, stores tangential strain and gives it back, so the
# spin rises above the rigid model's and the contact point leaves slipping backwards; past the boundary the
# two coincide (notebook `validation`).

# %%
compliant_map = pd.read_csv("results/compliance_map.csv")
rubber = compliant_map[np.isclose(compliant_map.kappa, 2 * (1 - config["compliance"]["poisson"])
                                  / (2 - config["compliance"]["poisson"]))]
worst = rubber.loc[rubber.spin_difference.abs().idxmax()]
display(Markdown(f"Compliant against rigid at {config['speed']:g} m/s: largest spin difference "
                 f"{100 * worst.spin_difference:+.1f} % at {worst.angle:g}°; identical within "
                 f"{100 * config['compliance']['tolerance']:g} % from {rubber[rubber.rigid_within].angle.min():g}° on."))

# %% [markdown]
# ## COR against speed
#
# The linear law's COR, exp(−ζπ/√(1−ζ²)) for an under-damped contact, does not depend on speed. The modified
# law's damping is ramped in over δ ~ R/c, so a slower impact spends relatively more of its contact with
# little damping, and its COR rises towards 1. The chapter's two cases have different normal approach speeds
# v cos β, which is why it finds two different CORs for one law.

# %%
display(Image(filename="paper_figures/cor_speed.png"))
zeta = config["damping"] / (2 * math.sqrt(config["stiffness"] * config["mass"]))
linear = math.exp(-zeta * math.pi / math.sqrt(1 - zeta**2)) if zeta < 1 else float("nan")
kv = speed[speed.model == "kelvin-voigt"].cor
display(Markdown(f"Linear law: closed form {linear:.6f} (ζ = {zeta:.4f}); the sweep's values span "
                 f"{kv.min():.6f} to {kv.max():.6f}. Modified law: COR from "
                 f"{speed[speed.model == 'modified'].cor.min():.4f} to {speed[speed.model == 'modified'].cor.max():.4f} "
                 f"over {speed.speed.min():g} to {speed.speed.max():g} m/s."))
beyond = speed[speed.beyond_radius.astype(bool)]
display(Markdown(
    "Within the model everywhere on this speed range: the maximum compression stays below the radius."
    if beyond.empty else
    f"**Outside the model** above {beyond.speed.min():g} m/s ({', '.join(sorted(set(beyond.model)))}): the maximum "
    f"compression exceeds the radius R = {config['diameter'] / 2 * 1e3:g} mm, the centre would pass the flat's "
    "plane. Those points are drawn, and flagged in the table's `beyond_radius` column."))
pivot = speed.pivot_table(index="speed", columns="model", values="cor")
pivot.iloc[np.unique(np.linspace(0, len(pivot) - 1, 6).round().astype(int))]

# %% [markdown]
# ## Contact time and peak force
#
# Both laws give a contact time close to the undamped half period π√(m/k) at every speed. The peak force grows
# nearly linearly with speed: the spring is linear, and the damping adds a share that the modified law's ramp
# keeps smaller at low speed.

# %%
display(Image(filename="paper_figures/contact_speed.png"))
half = math.pi * math.sqrt(config["mass"] / config["stiffness"])
display(Markdown(f"Undamped half period π√(m/k) = {half * 1e3:.4g} ms; contact times in the table: "
                 f"{speed.t_f.min() * 1e3:.4g} to {speed.t_f.max() * 1e3:.4g} ms."))

# %% [markdown]
# ## Throughput
#
# Impacts per second of the sweep engine against two per-scene contenders, measured side by side in one run.
# Each contender runs on a random sample of the sweep at the loosest tolerance whose worst error is no larger
# than the engine's, so all are equally accurate (errors and tolerances are in the same row):
# - the hand-written script a competent user writes: one `solve_ivp` call per scene with a scalar right-hand
#   side, the two events and no dense output, plus the impulse algebra. Every speed-up is against this one;
# - the package's `simulate`, which also builds histories and checks.
#
# All three are timed with one protocol: the median of the same number of complete runs. Peak memory is that
# of the engine, traced in a separate run.

# %%
bench

# %%
fits = bench["evaluations"].notna() if "evaluations" in bench else pd.Series(False, index=bench.index)
scripted = bench["speedup_over_handwritten"].notna()
for _, row in bench[scripted].iterrows():
    goal = "" if pd.isna(row.target_speedup) else (
        f" (target {row.target_speedup:g}×: {'met' if row.speedup_over_handwritten >= row.target_speedup else '**missed**'})")
    reached = ("" if row.handwritten_reached
               else " — the script never reached the engine's error, so it ran at its tightest tolerance")
    display(Markdown(f"- {row.sweep}: **{row.speedup_over_handwritten:,.0f}×** over the hand-written script{goal}, "
                     f"{row.speedup_over_simulate:,.0f}× over `simulate`; {row.throughput:,.0f} impacts/s; worst "
                     f"error {row.worst_error:.1e} (script {row.handwritten_error:.1e} at rtol "
                     f"{row.handwritten_rtol:.0e}{reached}); peak memory {row.peak_memory_mb:.0f} MB"))
for _, row in bench[~scripted & ~fits].iterrows():  # a compliant contact: the script has the rigid one only
    met = "met" if row.seconds <= row.target_seconds else "**missed**"
    display(Markdown(f"- {row.sweep}: {row.scenes:,} scenes in **{row.seconds:.3g} s** (target under "
                     f"{row.target_seconds:g} s: {met}), {row.speedup_over_simulate:,.0f}× over `simulate` one scene at a "
                     f"time; worst error {row.worst_error:.1e} (`simulate` {row.simulate_error:.1e} at rtol "
                     f"{row.simulate_rtol:.0e})"))

# %% [markdown]
# The fit of μ and κ to a Kharaz curve evaluates its model, a sweep of the curve's bounces, a few dozen times; the
# bounces' normal motions do not depend on μ or κ, so each is solved once per fit and shared by every evaluation
# (`sphereimpact.impact.solve.reusing_normal_motions`).

# %%
for _, row in bench[fits].iterrows():
    met = "met" if row.seconds <= row.target_seconds else "**missed**"
    display(Markdown(f"- {row.sweep}: **{row.seconds:.3g} s** (target under {row.target_seconds:g} s: {met}), "
                     f"{int(row.evaluations)} evaluations of the model over {row.scenes} bounces; the fitted "
                     f"parameters within {row.worst_error:.1e} (relative) of those that made the curve"))

# %% [markdown]
# Every sweep's time includes building its interpolant on every call (nothing is cached). The one-ball sweep
# interpolates in λ alone: one batched solve of Chebyshev nodes over the whole λ range, which also locates the
# tension onset, and one more on the tension side of it. The many-ball sweep (k, b and m drawn per scene, so
# each scene has its own ζ and λ) interpolates on the (ζ, λ) plane: some 1500 nodes in one call of the
# batched Taylor lanes, a piece for the penetration criterion's outputs over the whole rectangle and one for
# the end where the force pulls, continued analytically past δ = 0 so that it needs no cut along the tension
# onset. On a few thousand scenes the build is most of the time; on a million it is amortised.
# The input and output tables are held whole, so the peak memory of a large sweep grows with its size; the
# integration's own working memory is bounded by the chunk size.

# %% [markdown]
# ## Which path pays where
#
# Only eq. 4.2 without gravity has several paths that can solve the same scenes. `results/sweep_paths.csv`
# times them against each other at the sweep's target, each interpolant's build included (the engine builds
# it anew for every sweep), with each one's worst error on a sample against plain-float DOP853 at rtol
# 1e-13. A row is *dominated* when another path of its comparison, size and criterion is faster and at most
# as far from the reference.

# %%
display(Image(filename="results/figures/sweep_paths.png"))
paths = pd.read_csv("results/sweep_paths.csv")
always = sorted(name for name, rows in paths.groupby("path") if rows.dominated.all())
fastest = paths.loc[paths.groupby(["comparison", "separation", "scenes"], sort=False).seconds.idxmin()]
display(Markdown(f"Dominated on every row: {', '.join(always) or 'none'}; worst error of any path "
                 f"{paths.worst_error.max():.1e} against the target {paths.target.max():g}. "
                 "The fastest path of each comparison:"))
fastest[["comparison", "separation", "scenes", "path", "us_per_scene", "worst_error"]]
