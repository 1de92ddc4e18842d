"""The generated blocks of the README and the pages under docs/: written by the pipeline, copied in, checked by CI.

No measured number in the README or docs/ is typed by hand.  The pipeline writes each block to
``results/readme/<name>.md`` (:func:`write_snippets`); ``python -m sphereimpact.study.readme --update``
copies them between the documents' markers::

    <!-- BEGIN GENERATED <name> ... -->
    ...
    <!-- END GENERATED <name> -->

and ``--check`` (run by ``.ci/run`` after the pipeline) fails when a block disagrees with what the
pipeline wrote: exactly, except for the cells of timed columns (:data:`TIMED`), which differ from run to
run and must agree within a factor :data:`TIMING_RANGE`.  Every block of :data:`BLOCKS` stands in exactly one
document.  The charts of timings (:data:`TIMING_CHARTS`) differ from run to run too: each run writes its own
under ``results/figures/``, and ``--update`` copies them into ``paper_figures/`` beside the timings they show,
where ``--check`` requires them.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from pathlib import Path

import pandas as pd

from ..numerics.timing import BATCH, MIN_RUN, ROUND_BUDGET
from .tables import text_table
from .workflow import job_seconds

#: Generated blocks of the README and docs/.
BLOCKS = ("replication", "speed", "validation", "fit", "chung_ooi", "consistency", "runtime", "plan", "plan_checks")
#: Charts of timings: written to results/figures/ by every run, recorded in paper_figures/ by ``--update``.
TIMING_CHARTS = ("work_precision", "microslip_resolution", "sweep_paths")
#: A timed cell of a fresh run may differ from the README's by up to this factor either way.  Measured on
#: this project's 2-core machines: one timing moved by up to 1.8x between two idle runs (garbage collector
#: off), and a speed-up is the ratio of two timings.
TIMING_RANGE = 3.0
#: Table headers whose cells are timings or ratios of timings.
TIMED = ("simulate [ms]", "script [ms]", "simulate / script", "time", "impacts/s", "speed-up", "time [ms]",
         "time ratio", "time, every output", "every / fast", "bounces solved/s")

_BEGIN = re.compile(r"<!-- BEGIN GENERATED (\w+)[^>]*-->\n")
_UNITS = {"delta_m": (1e3, "mm"), "t_m": (1e3, "ms"), "t_f": (1e3, "ms"), "ve_t": (1.0, "m/s"),
          "ve_n": (1.0, "m/s"), "cor": (1.0, ""), "omega_f": (1.0, "rad/s")}


def _shown(quantity: str, value: float, digits: int) -> str:
    scale, unit = _UNITS.get(quantity, (1.0, ""))
    text = f"{value * scale:.{digits}g}".replace("-", "−")
    return f"{text} {unit}".strip()


def replication_block(config: dict, replication_csv: str, findings_md: str) -> str:
    """The replication table (every printed value, reproduced, status) and the computed findings."""
    table = pd.read_csv(replication_csv, keep_default_na=False)
    primary = config["primary"]
    rows = []
    for r in table.itertuples():
        status = f"**{r.status}**" if r.status == "discrepancy" else r.status
        note = f": {r.explanation}" if r.explanation else ""
        rows.append((f"{r.quantity}, {r.case}", r.printed, _shown(r.quantity, r.reproduced, 5), status + note))
    counts = table["status"].value_counts()
    head = (f"Reproduction: the `{primary['model']}` law, contact ending under the `{primary['separation']}` "
            "criterion, no gravity. Values are in the chapter's conventions: δ_m is the displacement of the "
            "centre (negative towards the flat; the package's `delta_m` output is the compression, positive), "
            "and v_E(t_f) is the contact point's velocity in the contact frame (I along the flat, J along its "
            "outward normal), as the chapter prints it. **match**: within half a unit of the last printed "
            "digit; **agree**: within one unit; **discrepancy**: further. "
            f"Totals: {', '.join(f'{counts.get(s, 0)} {s}' for s in ('match', 'agree', 'discrepancy'))}.")
    findings = Path(findings_md).read_text(encoding="utf-8").strip()
    return "\n\n".join([head, text_table(("printed value", "chapter", "reproduced", "status"), rows),
                        "What the replication measures about the chapter's claims (`results/replication.md`):",
                        findings]) + "\n"


def speed_block(bench_csv: str, bench_sweep_csv: str) -> str:
    """The single-impact and sweep speed tables against the hand-written baseline, equal accuracy shown."""
    # imported here, not with the module: a workflow that reads this module's constants need not import the solvers
    from ..numerics.bench import STARTUP_SCENE
    from ..numerics.reference import FINE_DIGITS

    single = pd.read_csv(bench_csv)
    repeats = int(single["repeats"].max())  # the config's bench.repeats: every single-impact row ran that many
    rows = []
    scripted = single[single["scene"].isin(single[single["contender"] == "handwritten"]["scene"])]
    for name, part in scripted.groupby("scene", sort=False):
        sim, hand = (part[part["contender"] == c].iloc[0] for c in ("simulate", "handwritten"))
        reached = "" if hand["reached"] else " (not reached)"
        rows.append((name, sim["method"], f"{sim['time'] * 1e3:.3g}", f"{hand['time'] * 1e3:.3g}",
                     f"{sim['time_ratio']:.2f}", f"{sim['error']:.1e}",
                     f"{hand['error']:.1e} at rtol {hand['rtol']:.0e}{reached}"))
    one = text_table(("scene", "simulate's method", "simulate [ms]", "script [ms]", "simulate / script",
                  "error, simulate", "error, script"), rows)
    started = single["scene"] == STARTUP_SCENE
    exact = single[~single["scene"].isin(scripted["scene"]) & ~started]
    rows = [(r.scene, r.contender, f"{r.time * 1e3:.3g}", f"{r.time_ratio:.2f}",
             f"{r.error:.1e}" if math.isfinite(r.error) else "") for r in exact.itertuples()]
    tangential = text_table(("scene", "contender", "time [ms]", "time ratio", "error"), rows)
    startup = single[started]
    start = ([
        f"A command's start (`results/bench.csv`): each contender a fresh Python process, the median of "
        f"{int(startup['repeats'].iloc[0])} runs taken in turn; `simulate --json` runs the chapter's scene, or a "
        "Hertz ball's, whole (imports, one impact, the JSON). Time ratio: over Python's start with numpy, the floor "
        "of any command.",
        text_table(("command", "time [ms]", "time ratio"),
                   [(f"`{r.contender}`", f"{r.time * 1e3:.3g}", f"{r.time_ratio:.2f}") for r in startup.itertuples()])]
             if len(startup) else [])
    table = pd.read_csv(bench_sweep_csv)
    fitted = table["evaluations"].notna() if "evaluations" in table else pd.Series(False, index=table.index)
    commanded = table["command"].notna() if "command" in table else pd.Series(False, index=table.index)
    sweeps, fits, commands = table[~fitted & ~commanded], table[fitted], table[commanded]
    rows = []
    for r in sweeps.itertuples():
        goal = "" if pd.isna(r.target_speedup) else f"{r.target_speedup:g}×"
        if pd.isna(r.speedup_over_handwritten):  # a compliant contact: the script has the rigid one only
            reached = "" if r.simulate_reached else " (not reached)"
            speedup = f"{r.speedup_over_simulate:.3g}× over `simulate`"
            contender = f"{r.simulate_error:.1e} at rtol {r.simulate_rtol:.0e}{reached} (`simulate`)"
        else:
            reached = "" if r.handwritten_reached else " (not reached)"
            speedup = f"{r.speedup_over_handwritten:.3g}×"
            contender = f"{r.handwritten_error:.1e} at rtol {r.handwritten_rtol:.0e}{reached}"
        if "target_seconds" in sweeps and pd.notna(r.target_seconds):
            goal = f"under {_seconds(r.target_seconds)}"
        rows.append((r.sweep, f"{r.scenes:,}", _seconds(r.seconds), f"{r.throughput:.3g}", speedup,
                     f"{r.worst_error:.1e}", contender, goal, _seconds(r.seconds_all),
                     "" if pd.isna(r.all_over_fast) else f"{r.all_over_fast:.2g}"))
    many = text_table(("sweep", "scenes", "time", "impacts/s", "speed-up", "error, engine", "error, script",
                   "target", "time, every output", "every / fast"), rows)
    fit_rows = [(r.sweep, f"{r.scenes:,}", _seconds(r.seconds), f"{int(r.evaluations)}", f"{r.throughput:.3g}",
                 "—" if pd.isna(r.worst_error) else f"{r.worst_error:.1e}", f"under {_seconds(r.target_seconds)}")
                for r in fits.itertuples()]
    fitting = ([
        "Fitting (`results/bench_sweep.csv`): `sphereimpact.fit.fit` of the free parameters, from the start of "
        "`kharaz_fit` in the config, to the noise-free e_t, spin and rebound angle of Kharaz's ball (the "
        "validation's, e_n given) at the validation's incidences, and to the shipped measured bounces with the COR "
        "free too (the ball calibrated to the measured e_n), each bounce solved by `simulate`; timed as "
        f"{_rounds(repeats, 'fit')}, each solving its "
        "bounces' normal motions afresh (once per fit where the COR is given: they do not depend on μ or κ; at "
        "every evaluation that moves the COR). Error: the fitted parameters' largest relative difference from "
        "those that made the curve (none made the measured bounces).",
        text_table(("fit", "bounces", "time", "model evaluations", "bounces solved/s", "error, parameters", "target"),
               fit_rows)] if fit_rows else [])
    command_rows = [(r.sweep, f"`{r.command}`", f"{r.scenes:,}", _seconds(r.seconds), f"{r.throughput:.3g}",
                     f"under {_seconds(r.target_seconds)}") for r in commands.itertuples()]
    whole = ([
        "A map as a command (`results/bench_sweep.csv`): the whole `sphereimpact sweep` in a fresh Python process "
        "(start, imports, loading the compiled kernels, the sweep with its one-at-a-time scenes shared among the "
        f"machine's CPUs, the table written), {'one run' if repeats == 1 else f'the median of {repeats} runs'}. "
        "Each scene of a damped contact is its own normal problem.",
        text_table(("map", "command", "scenes", "time", "impacts/s", "target"), command_rows)] if command_rows else [])
    return "\n\n".join([
        "One impact (`results/bench.csv`): `simulate` at its default options, each call building and checking its "
        "Scene from its fields too (method `auto`: the law's closed "
        "form where it has one, else the Taylor method where it has a series, else DOP853-scalar, scipy's DOP853 "
        "per scene in plain floats; both compiled (numba) once a process has integrated enough to repay loading "
        "them, as here) against the hand-written script (one `solve_ivp` call, scalar right-hand side, the two events, no "
        "dense output) at the loosest tolerance whose error is no larger than `simulate`'s. Error: the worst "
        "relative error over t_m, δ_m, "
        f"t_f, COR, ω_f and v_E,t against the closed form, the {FINE_DIGITS}-digit Taylor reference (eq. 4.2) or scipy's "
        "DOP853 at rtol 1e-13 (the Hertz and Hunt–Crossley laws). Times are medians over "
        f"{int(single['repeats'].iloc[0])} runs of each contender in turn, a run of at least {BATCH} calls lasting "
        f"at least {MIN_RUN * 1e3:g} ms (each row's `batch`): a run of {BATCH} quick calls right after the other "
        "contender's run paid for its first calls' cold caches.",
        one,
        "The exact microslip contact (`results/bench.csv`): one impact at the default resolution beside the "
        "rigid contact on the same scene (error: e_t's and spin's against the fine reference resolution), beside "
        "the compiled port a numba user writes by hand (one compiled call on the scene's numbers: the normal motion "
        "by fixed-step RK4 on the march's own steps, then the package's march at the same cells and steps; the "
        "target is the impact at most 2× its time), and beside its element row's march alone, the compiled kernel "
        "(numba) on the impact's own inputs. Once per process, not per impact: compiling the package's kernels (the "
        "march's, the normal motion's DOP853 and Taylor loops, the laws' forces and series, the force's extremes and "
        "sign changes, the compliant springs' stick phase and the rigid contact's grip) on a fresh machine "
        "(numba imported, an empty disk cache) and loading them from the cache that filled, each in a fresh Python "
        "process on one core, beside one other job of the pipeline. Time ratio: over the rigid contact, the impact "
        "(for the port and the march) and the load.",
        tangential,
        *start,
        "Sweeps (`results/bench_sweep.csv`): the engine on the whole sweep against the same script on a random "
        f"sample of {int(sweeps['sample'].iloc[0])} of its scenes, at equal accuracy; every contender timed as "
        f"{_rounds(repeats, 'run')} (the sweeps guide's large sweep, whose every-output-over-fast ratio is a "
        f"target, always {repeats}), each engine run made once untimed before (a process's first sweep of a size "
        "pays for its memory's first touch); speed-up = the script's time per scene × the engine's "
        "impacts per second. The engine is timed on the outputs the script computes too (`--outputs fast`), and "
        "with every output, the default (t_roll and the force's extremes besides; not on the microslip map, whose "
        "paths compute every output anyway). The script has the rigid contact only: the exact microslip map is "
        "measured against `simulate`, one scene at a time.",
        many,
        *whole,
        *fitting,
        f"Timings vary from run to run and machine to machine: CI fails when a fresh run's timed cell differs "
        f"from these by more than a factor {TIMING_RANGE:g}.",
    ]) + "\n"


def validation_block(summary_csv: str, residual_csv: str) -> str:
    """The model against Kharaz et al. (2001): each tangential model's measures against each target, and the
    points where the rigid contact fails most."""
    summary, table = pd.read_csv(summary_csv), pd.read_csv(residual_csv)
    low = float(summary["min_incidence"].iloc[0])
    met = {True: "met", False: "**missed**"}

    def cell(value: str, row, name: str) -> str:
        return f"{value} ({met[bool(getattr(row, f'{name}_met'))]})"

    rows = [(f"`{r.tangential}`", cell(f"{r.e_t_rms:.4f}", r, "e_t"), cell(f"{r.e_t_rms_all:.4f}", r, "e_t_all"),
             cell(f"{r.e_t_worst:.3f}", r, "e_t_point"), cell(f"{100 * r.spin_worst_relative:.1f} %", r, "spin"),
             cell(f"{r.rebound_angle_rms_deg:.2f}°", r, "rebound_angle"), f"{r.targets_met} of {r.targets}")
            for r in summary.itertuples()]
    first = summary.iloc[0]
    measures = text_table((
        "tangential contact", f"e_t RMS, ≥ {low:g}° (≤ {first.e_t_target:g})",
        f"e_t RMS, all angles (≤ {first.e_t_all_target:g})", f"worst e_t point (≤ {first.e_t_point_target:g})",
        f"worst spin residual (≤ {100 * first.spin_target:g} %)",
        f"rebound angle RMS (≤ {first.rebound_angle_target:g}°)", "targets met"), rows)
    rigid = table[(table["tangential"] == "rigid") & (table["incidence_deg"] >= low)]
    worst = rigid.loc[rigid.groupby("quantity")["relative"].apply(lambda x: x.abs().idxmax())]
    rows = []
    for r in worst.itertuples():
        others = table[(table["quantity"] == r.quantity) & (table["incidence_deg"] == r.incidence_deg)
                       & (table["tangential"] != "rigid")]
        rows.append((r.quantity, f"{r.incidence_deg:g}°", f"{r.measured:.4g}", f"{r.predicted:.4g} ({100 * r.relative:+.0f} %)",
                     "; ".join(f"{o.tangential} {o.predicted:.4g} ({100 * o.relative:+.0f} %)" for o in others.itertuples())))
    points = text_table(("quantity", "incidence", "measured", "rigid", "compliant"), rows)
    return "\n\n".join([
        f"Kharaz, Gorham & Salman (2001), 5 mm alumina on glass at 3.9 m/s (`results/validation_summary.csv`): "
        f"Hunt–Crossley normal contact calibrated to e_n, tangential stiffness κ = 4G*/E* = {first.kappa:.4f} from "
        f"the materials, nothing fitted to the oblique data. Spin residuals are counted where more than "
        f"{first.spin_above:g} rad/s was measured.",
        measures,
        f"Where the chapter's rigid contact misses most (at ≥ {low:g}°, `results/validation.csv`):",
        points,
    ]) + "\n"


def fit_block(fit_json: str) -> str:
    """The pipeline's fit of the Kharaz data: each free parameter with its standard error beside the value the
    paper or the materials give, the fit's chi^2 per degree of freedom and its residuals."""
    import json

    record = json.loads(Path(fit_json).read_text(encoding="utf-8"))
    reference, stats = record["reference"], record["statistics"]
    sources = {"mu": "measured by Kharaz et al.", "kappa": "4 G*/E* of the materials"}
    rows = []
    for name, p in record["parameters"].items():
        error = "unbounded" if p["stderr"] is None else f"{p['stderr']:.2g}"
        known = f"{reference[name]:.4g} ({sources[name]})" if name in reference else "—"
        rows.append((f"`{name}`", f"{p['value']:.4g}", error, "yes" if p["identifiable"] else "**no**", known))
    rms = "; ".join(f"{q} {v:.3g}" for q, v in stats["rms"].items())
    return "\n\n".join([
        f"The shipped Kharaz data fitted (`results/fit_kharaz/`, rule `kharaz_fit`): {stats['values']} measured values, "
        f"the `{reference['tangential']}` tangential contact, e_n given (the normal damping calibrated to it), "
        f"χ²/dof {stats['reduced_chi2']:.3g} with each quantity weighted by its own residual scatter; residual RMS "
        f"{rms}.",
        text_table(("parameter", "fitted", "standard error", "identifiable", "the paper / the materials"), rows),
    ]) + "\n"


def consistency_block(consistency_csv: str, target: float = 1e-8) -> str:
    """The sweep's differential test in a sentence: rows compared, the worst error and where, agreement."""
    table = pd.read_csv(consistency_csv, keep_default_na=False)
    refused = int(table.loc[table["path"] == "refused by simulate", "rows"].sum())
    rows = table[table["path"] != "refused by simulate"]
    worst = rows.loc[rows["worst_error"].astype(float).idxmax()]
    disagree = int(rows["regime_disagrees"].astype(int).sum() + rows["beyond_radius_disagrees"].astype(int).sum())
    paths = sorted(set(rows["path"]))
    verdict = "within" if float(worst["worst_error"]) <= target else "**beyond**"
    agreement = "agree on every row" if disagree == 0 else f"**disagree on {disagree} rows**"
    return (f"Differential test (`results/consistency.csv`): {int(rows['rows'].astype(int).sum()):,} random scenes "
            f"mixed in one table and swept, every row against `simulate` of its scene at rtol 1e-12, on "
            f"{len(paths)} paths ({', '.join(f'`{p}`' for p in paths)}): worst relative error "
            f"{float(worst['worst_error']):.2g} ({worst['path']}, {worst['model']}, {worst['tangential']}, "
            f"{worst['worst_output']}), {verdict} the sweep's {target:g} target; regime and beyond_radius "
            f"{agreement}; {refused} scenes simulate refuses (outside the accepted domain) left out.\n")


#: The pipeline's parts (``results/benchmarks/<part>/...``, one per rule file), as the runtime block names them.
PARTS = {"simulate": "the chapter's runs", "report": "tables and README blocks", "figures": "the chapter's figures",
         "numerics": "numerics: accuracy, stability, benchmarks", "sweep": "sweeps and their differential test",
         "laws": "contact laws", "validation": "validation against measurements",
         "benchmarks": "the field's benchmark tests (Chung & Ooi)", "notebook": "notebooks"}


def runtime_block(benchmark_files, root: str = "results/benchmarks") -> str:
    """What the pipeline's jobs took, per part of the pipeline, from Snakemake's benchmark files under
    ``root`` (``<root>/<part>/<rule>[/<wildcards>].tsv``): rules, jobs and the sum of their wall times."""
    rows = []
    for path in benchmark_files:
        part, rule = Path(path).relative_to(root).with_suffix("").parts[:2]
        rows.append((part, rule, job_seconds(path)))
    if not rows:
        raise ValueError(f"no benchmark files under {root}: run the pipeline first")
    table = pd.DataFrame(rows, columns=["part", "rule", "seconds"])
    order = [p for p in PARTS if p in set(table["part"])] + sorted(set(table["part"]) - set(PARTS))
    lines = []
    for part in order:
        jobs = table[table["part"] == part]
        lines.append((PARTS.get(part, part), ", ".join(f"`{r}`" for r in sorted(set(jobs["rule"]))), str(len(jobs)),
                      _seconds(float(jobs["seconds"].sum()))))
    lines.append(("**all**", f"{table['rule'].nunique()} rules", str(len(table)), _seconds(float(table["seconds"].sum()))))
    return "\n\n".join([
        f"What the last `snakemake --cores 2` took (`{root}/`, Snakemake's `benchmark:` file of each job): the "
        "sum of its jobs' wall times. Two jobs run at once but the timed ones (benchmarks, work-precision), "
        "which run alone, so the run itself takes between half this sum and all of it, plus Snakemake's own "
        "start-up.",
        text_table(("part of the pipeline", "rules", "jobs", "time"), lines),
    ]) + "\n"


def _rounds(repeats: int, what: str) -> str:
    """How a benchmark's rows were timed (:func:`~..numerics.timing.interleaved_runs`): ``repeats`` rounds (the
    config's ``bench.repeats``), or fewer where a round takes longer than its budget.  Worded from the setting, not
    from the rounds a run took, so that the text is the same in every run."""
    if repeats == 1:
        return f"one complete {what}"
    return (f"the median of {repeats} complete {what}s, or of fewer where one round of its contenders takes over "
            f"{ROUND_BUDGET:g} s (each row's `repeats` says how many ran)")


def _seconds(value: float) -> str:
    """A time [s] as text, in ms below a second; empty where it was not measured."""
    if math.isnan(value):
        return ""
    return f"{value * 1e3:.3g} ms" if value < 1 else f"{value:.3g} s"


def write_snippets(config: dict, replication_csv: str, findings_md: str, bench_csv: str, bench_sweep_csv: str,
                   validation_summary_csv: str, validation_csv: str, consistency_csv: str, fit_json: str,
                   replication_out: str, speed_out: str, validation_out: str, consistency_out: str,
                   fit_out: str) -> None:
    """Write the README's generated blocks (see the module docstring)."""
    Path(fit_out).write_text(fit_block(fit_json), encoding="utf-8")
    Path(replication_out).write_text(replication_block(config, replication_csv, findings_md), encoding="utf-8")
    Path(speed_out).write_text(speed_block(bench_csv, bench_sweep_csv), encoding="utf-8")
    Path(validation_out).write_text(validation_block(validation_summary_csv, validation_csv), encoding="utf-8")
    Path(consistency_out).write_text(consistency_block(consistency_csv), encoding="utf-8")


def write_runtime(root: str, out: str) -> None:
    """Write the runtime block from every benchmark file under ``root`` (each job's latest run)."""
    Path(out).write_text(runtime_block(sorted(str(p) for p in Path(root).rglob("*.tsv")), root), encoding="utf-8")


def blocks(text: str) -> dict[str, tuple[int, int]]:
    """name -> (start, end) character span of each generated block's body in ``text``."""
    spans = {}
    for match in _BEGIN.finditer(text):
        name = match.group(1)
        end = text.find(f"<!-- END GENERATED {name} -->", match.end())
        if end < 0:
            raise ValueError(f"README: block {name!r} has no END marker")
        spans[name] = (match.end(), end)
    return spans


def update(readme: str, snippets: str) -> str:
    """``readme``'s text with every block replaced by ``snippets/<name>.md``."""
    text = Path(readme).read_text(encoding="utf-8")
    for name, (start, end) in sorted(blocks(text).items(), key=lambda item: -item[1][0]):
        text = text[:start] + Path(snippets, f"{name}.md").read_text(encoding="utf-8") + text[end:]
    return text


def record_charts(figures: str, into: str) -> None:
    """Copy each chart of :data:`TIMING_CHARTS` from ``figures`` (a run's ``results/figures``) into ``into``
    (``paper_figures``), each written whole or not at all."""
    from ..files import copy_file

    for name in TIMING_CHARTS:
        copy_file(Path(figures, f"{name}.png"), Path(into, f"{name}.png"))


def recorded_chart_problems(into: str) -> list[str]:
    """Each chart of :data:`TIMING_CHARTS` missing from ``into`` or not a PNG file."""
    problems = []
    for name in TIMING_CHARTS:
        path = Path(into, f"{name}.png")
        if not path.is_file() or path.read_bytes()[:8] != b"\x89PNG\r\n\x1a\n":
            problems.append(f"{path} is missing or not a PNG: `--update` records the run's chart")
    return problems


#: Units a timed cell may carry, as factors to one base unit (a time column switches from ms to s).
_CELL_UNITS = {"ms": 1e-3, "s": 1.0}


def _number(cell: str) -> float | None:
    """The first number in ``cell``, in base units when a unit of :data:`_CELL_UNITS` follows it."""
    match = re.search(r"([-−]?\d[\d,]*\.?\d*(?:e[-+]?\d+)?)\s*(ms|s)?\b", cell)
    if not match:
        return None
    return float(match.group(1).replace(",", "").replace("−", "-")) * _CELL_UNITS.get(match.group(2), 1.0)


def _timed_cells_agree(old: str, new: str) -> bool:
    a, b = _number(old), _number(new)
    if a is None or b is None:
        return old == new
    if a == b:
        return True
    return a > 0 and b > 0 and math.exp(abs(math.log(a / b))) <= TIMING_RANGE


def differences(readme_block: str, fresh: str) -> list[str]:
    """Where a README block disagrees with the pipeline's: exact, but timed cells within TIMING_RANGE."""
    old, new = readme_block.splitlines(), fresh.splitlines()
    if len(old) != len(new):
        return [f"{len(old)} lines in the README, {len(new)} written by the pipeline"]
    found, headers = [], []
    for i, (a, b) in enumerate(zip(old, new), 1):
        if not a.startswith("|"):
            headers = []  # a table's first row is its header
        elif not headers:
            headers = [c.strip() for c in a.strip("|").split("|")]
        if a == b:
            continue
        if not (a.startswith("| ") and b.startswith("| ")):
            found.append(f"line {i}: README {a!r} but the pipeline wrote {b!r}")
            continue
        cells_a, cells_b = a.strip("|").split("|"), b.strip("|").split("|")
        if len(cells_a) != len(cells_b):
            found.append(f"line {i}: README {a!r} but the pipeline wrote {b!r}")
            continue
        for header, x, y in zip(headers or [""] * len(cells_a), cells_a, cells_b):
            x, y = x.strip(), y.strip()
            if x != y and not (header in TIMED and _timed_cells_agree(x, y)):
                what = f"timed beyond a factor {TIMING_RANGE:g}" if header in TIMED else "differs"
                found.append(f"line {i}, column {header!r}: README {x!r}, pipeline {y!r} ({what})")
    return found


def check(documents, snippets: str) -> list[str]:
    """Every disagreement between the generated blocks of ``documents`` (the README and the docs/ pages; one path
    is one document) and ``snippets/<name>.md``; empty when they agree and each block of :data:`BLOCKS` stands in
    exactly one document."""
    documents = [documents] if isinstance(documents, (str, Path)) else list(documents)
    problems, seen = [], {}
    for document in documents:
        text = Path(document).read_text(encoding="utf-8")
        for name, (start, end) in blocks(text).items():
            if name in seen:
                problems.append(f"{document}: block {name!r} stands in {seen[name]} too")
            seen[name] = document
            fresh = Path(snippets, f"{name}.md")
            if not fresh.is_file():
                problems.append(f"{fresh} is missing: run `snakemake --cores 2` first")
                continue
            problems += [f"{document}: {name}: {d}"
                         for d in differences(text[start:end], fresh.read_text(encoding="utf-8"))]
    problems += [f"no document has the generated block {name!r}" for name in BLOCKS if name not in seen]
    return problems


def main(argv=None) -> int:
    """``python -m sphereimpact.study.readme (--check | --update)``: the README and docs/*.md against
    results/readme, the recorded timing charts of paper_figures against results/figures."""
    parser = argparse.ArgumentParser(prog="python -m sphereimpact.study.readme", allow_abbrev=False,
                                     description="Check or update the generated blocks of the README and docs/, "
                                                 "and the recorded timing charts.")
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--check", action="store_true", help="exit 1 when a block disagrees with the pipeline's")
    mode.add_argument("--update", action="store_true", help="copy the pipeline's blocks and timing charts in")
    parser.add_argument("documents", nargs="*", help="default: README.md and docs/*.md")
    parser.add_argument("--snippets", default="results/readme", help="the pipeline's blocks (default %(default)s)")
    parser.add_argument("--figures", default="results/figures",
                        help="the pipeline's timing charts (default %(default)s)")
    parser.add_argument("--recorded", default="paper_figures",
                        help="where the recorded timing charts are kept (default %(default)s)")
    args = parser.parse_args(argv)
    documents = args.documents or ["README.md", *sorted(str(p) for p in Path("docs").glob("*.md"))]
    try:
        if args.update:
            from ..files import write_text

            for document in documents:
                write_text(document, update(document, args.snippets))
            record_charts(args.figures, args.recorded)
            return 0
        problems = check(documents, args.snippets) + recorded_chart_problems(args.recorded)
    except (OSError, ValueError) as err:
        parser.exit(2, f"readme: error: {err}\n")
    for problem in problems:
        print(f"readme: {problem}", file=sys.stderr)
    if problems:
        print("readme: the documents disagree with the results; `python -m sphereimpact.study.readme --update` "
              "copies the pipeline's blocks and charts in", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
