"""Sweep throughput against per-scene solving, measured side by side in one run (a benchmark, not a test).

For each sweep: the engine's impacts per second on the whole sweep, and two per-scene contenders on a
random sample of it, each at the loosest tolerance on :data:`TOLERANCES` whose worst error on the sample
is no larger than the engine's (equal accuracy, shown in the same row):

- ``handwritten``: what a competent user writes, one plain ``solve_ivp`` call per scene with a scalar
  right-hand side and no dense output (:func:`sphereimpact.numerics.handwritten.handwritten`).  Every
  speed-up the project states is against this one;
- ``simulate``: the package's single-impact path, which adds histories, force extremes and checks.  The
  exact microslip map (:data:`MICROSLIP_MAP`) is measured against it alone: the script has the rigid contact only.

One timing protocol for all three: the median of ``repeats`` complete runs, the three timed in turn within
each repeat (the engine builds its interpolants anew in every run; nothing is cached), fewer where a round
takes more than :data:`~.timing.ROUND_BUDGET` (:func:`~.timing.interleaved_runs`; ``repeats`` is the rounds
run) but on the sweeps guide's large sweep, whose all-over-fast ratio is a target; each engine run made once
untimed before (a process's first sweep of a size pays for its memory's first touch).  A contender that misses
the engine's error at the tightest tolerance is flagged (``<contender>_reached`` False) and timed there; the
ladder is walked from the loosest only for one that meets it there.
Gravity-free scenes under the force criterion only (the baseline's impulse algebra assumes both).  The
engine's speed-up is measured on :data:`~sphereimpact.sweep.engine.FAST_OUTPUTS` (every output of ``simulate``
but t_roll and the force extremes; the script computes less still), and the engine is also timed with every
output, the default (``seconds_all``, and ``all_over_fast``, its time over the fast outputs'), except on the
microslip map, whose paths compute every output anyway.  A fit's row (:func:`measure_fit`) times a fit instead, and
a command's row (:func:`measure_command`) a whole ``sphereimpact sweep`` in a fresh process.

A row's untimed half, the sample's references and errors and the contenders' tolerances (:func:`accuracy`), is the
pipeline's job ``bench_sweep_accuracy`` (:func:`write_accuracies`), run beside the others; the timed job, which runs
alone, takes it back and times.
"""

from __future__ import annotations

import json
import logging
import math
import tracemalloc
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from .bench import LAW_SCENES, TOLERANCES, fresh_run
from .handwritten import handwritten
from .reference import relative_errors
from .timing import ROUND_BUDGET, interleaved_runs, steady_state
from ..fit import fit, read_measured, with_values
from ..impact.ball import Ball
from ..impact.scene import Scene, SolverOptions
from ..errors import BeyondRadiusWarning
from ..impact.solve import simulate
from ..parsing import parse_range
from ..sweep.engine import FAST_OUTPUTS, SCENE_COLUMNS, grid, scene_of, sweep

log = logging.getLogger(__name__)
KEYS = ("t_m", "delta_m", "t_f", "vc_t", "vc_n", "ve_t", "ve_n", "omega_f", "cor")
#: The per-scene reference: scipy's DOP853 at rtol 1e-13, not the package's default integrator.
REFERENCE = SolverOptions(method="DOP853", rtol=1e-13, atol=1e-13)
#: Per-scene contenders: name -> solve(scene, rtol) -> outputs.
CONTENDERS = {
    "handwritten": lambda scene, rtol: handwritten(scene, rtol),
    "simulate": lambda scene, rtol: simulate(scene, SolverOptions(rtol=rtol, atol=rtol)).to_dict(),
}


def _worst(outputs, refs, scenes) -> float:
    return max(max(relative_errors(o, r, s, KEYS).values()) for o, r, s in zip(outputs, refs, scenes))


def per_scene(solve, scenes: list[Scene], refs: list[dict], error: float) -> dict:
    """The loosest tolerance at which ``solve`` meets ``error`` on ``scenes``, and its worst error there.

    The tightest tolerance is tried first: a contender that misses ``error`` there is not reached (the looser ones
    are not walked: most contenders miss the sweep's accuracy by their floor, and the walk was most of the
    benchmark's time); one that meets it is walked from the loosest.

    Returns
    -------
    dict
        ``rtol``, ``error`` (worst on the sample), ``reached`` (False: the tightest tolerance missed ``error``; timed
        there).
    """
    tightest = TOLERANCES[-1]
    worst = _worst([solve(s, tightest) for s in scenes], refs, scenes)
    if worst > error:
        return {"rtol": tightest, "error": worst, "reached": False}
    for rtol in TOLERANCES[:-1]:
        looser = _worst([solve(s, rtol) for s in scenes], refs, scenes)
        if looser <= error:
            return {"rtol": rtol, "error": looser, "reached": True}
    return {"rtol": tightest, "error": worst, "reached": True}


def accuracy(scenes: pd.DataFrame, sample_size: int = 60, seed: int = 0, contenders=None,
             memory: bool = True) -> dict:
    """The untimed half of a sweep's row (see the module docstring): the engine's worst error on a random sample of
    the sweep ``scenes`` against the per-scene reference (:data:`REFERENCE`), each of ``contenders`` (default
    :data:`CONTENDERS`) at the loosest tolerance that meets it (:func:`per_scene`), the sample's scenes, and the
    engine's peak memory while it sweeps (``memory`` False: NaN; tracing slows a sweep of many small allocations
    tenfold).  The pipeline computes it in a job of its own (rule ``bench_sweep_accuracy``), beside the others, so
    that the timed job, which runs alone, spends its time timing (:func:`measure` takes it back).

    Returns
    -------
    dict
        ``scenes`` (the sweep's count), ``worst_error``, ``sample`` (each sampled scene as the sweep's table gives
        it: :data:`~sphereimpact.sweep.engine.SCENE_COLUMNS`, plain values), ``chosen`` (contender -> ``rtol``,
        ``error``, ``reached``), ``peak_memory_mb``.

    Random scenes include compressions beyond the radius: the sweep's table flags them, so the per-scene references
    and contenders do not warn about each one.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondRadiusWarning)
        peak = math.nan
        if memory:
            tracemalloc.start()
        table = sweep(scenes, outputs=FAST_OUTPUTS, chapter_ball=True)  # the chapter's ball where the scenes are silent
        if memory:
            peak = tracemalloc.get_traced_memory()[1]
            tracemalloc.stop()
        pick = np.sort(np.random.default_rng(seed).choice(len(table), size=min(sample_size, len(table)),
                                                          replace=False))
        outputs = table.iloc[pick].to_dict("records")
        sample = [{key: _plain(row[key]) for key in SCENE_COLUMNS} for row in outputs]
        scenes_of = [scene_of(row) for row in sample]
        n = len(table)
        del table
        refs = [simulate(s, REFERENCE).to_dict() for s in scenes_of]
        error = _worst(outputs, refs, scenes_of)
        chosen = {label: per_scene(solve, scenes_of, refs, max(error, TOLERANCES[-1]))
                  for label, solve in (contenders or CONTENDERS).items()}
    return {"scenes": n, "worst_error": error, "sample": sample, "chosen": chosen, "peak_memory_mb": peak / 2**20}


def _plain(value):
    """A table cell as a plain Python value (JSON's): numpy's scalars as float, int, bool."""
    return value.item() if isinstance(value, np.generic) else value


def measure(name: str, scenes: pd.DataFrame, target_speedup: float | None, sample_size: int = 60,
            seed: int = 0, repeats: int = 3, contenders=None, every_output: bool = True, memory: bool = True,
            known: dict | None = None, budget: float = ROUND_BUDGET) -> dict:
    """One benchmark row for the sweep ``scenes`` (see the module docstring), against ``contenders`` (default
    :data:`CONTENDERS`; the hand-written baseline has the rigid contact only): its :func:`accuracy` (``known``, as
    the pipeline's accuracy job wrote it, else computed here with ``sample_size``, ``seed`` and ``memory``), then
    the engine and the contenders timed in turn, ``repeats`` rounds or fewer past ``budget`` seconds a round
    (:func:`~.timing.interleaved_runs`).  ``every_output`` False skips timing the engine with every output (a sweep
    whose paths compute them all anyway: ``seconds_all`` left empty).

    Each engine run is made once untimed first: a process's first sweep of a size pays for its memory's first touch
    and for loading the kernels its paths take (the 10^6-scene sweep's first run took twice its next), which a single
    timed round would report as the sweep's time."""
    contenders = contenders or CONTENDERS
    log.info("sweep bench: %s (%d scenes)", name, len(scenes))
    known = known or accuracy(scenes, sample_size, seed, contenders, memory)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", BeyondRadiusWarning)
        sample, chosen = [scene_of(row) for row in known["sample"]], known["chosen"]
        # the engine and the contenders in turn within each repeat: a slow spell of the machine falls on all alike
        calls = {"engine": lambda: sweep(scenes, outputs=FAST_OUTPUTS, chapter_ball=True)} | (
            {"engine_all": lambda: sweep(scenes, chapter_ball=True)} if every_output else {}) | {
            label: (lambda solve=solve, rtol=chosen[label]["rtol"]: [solve(s, rtol) for s in sample])
            for label, solve in contenders.items()}
        for engine in ("engine", "engine_all"):
            if engine in calls:
                calls[engine]()
        seconds, rounds = interleaved_runs(calls, repeats, budget)
    n = known["scenes"]
    throughput = n / seconds["engine"]
    every = seconds.get("engine_all", math.nan)
    row = {"sweep": name, "scenes": n, "seconds": seconds["engine"], "throughput": throughput,
           "worst_error": known["worst_error"], "repeats": rounds, "sample": len(sample), "seconds_all": every,
           "all_over_fast": every / seconds["engine"]}
    for label, got in chosen.items():
        per = seconds[label] / len(sample)
        row |= {f"{label}_rtol": got["rtol"], f"{label}_error": got["error"], f"{label}_reached": got["reached"],
                f"{label}_throughput": 1.0 / per, f"speedup_over_{label}": throughput * per}
    return row | {"target_speedup": target_speedup, "peak_memory_mb": known["peak_memory_mb"]}


#: The microslip map's ball: the chapter's, with an elastic Hertz contact (E* 10^8 Pa) and the exact elastic microslip
#: tangential contact of rubber (kappa 2/3).
MICROSLIP_MAP = {"model": "hertz", "modulus": 1e8, "tangential": "microslip", "kappa": 2.0 / 3.0}
#: The large sweep of docs/sweeps.md, as its command line gives it (`sphereimpact sweep --angle 0:89:0.1 ...`).
GUIDE_SWEEP = {"angle": "0:89:0.1", "speed": "0.5:30:0.05", "mu": "0.4"}


def guide_sweep() -> pd.DataFrame:
    """The scenes of :data:`GUIDE_SWEEP` (526 581), every combination of its ranges, as the command line."""
    return grid(**{name: parse_range(text) for name, text in GUIDE_SWEEP.items()})


#: The targets [s] of the exact microslip contact's issue: "a 10^5-scene microslip angle x speed map in seconds"
#: (read as under 10 s) and "a fit of the 140-point Kharaz curve in under 10 s"; and of the compiled kernels' issue:
#: "a fit of mu, kappa and the COR from 23 bounces under 10 s" (Kharaz's measured bounces).
MICROSLIP_MAP_TARGET_SECONDS = FIT_TARGET_SECONDS = DATA_FIT_TARGET_SECONDS = 10.0
def measure_fit(name: str, truth: Ball, start: dict, incidences, repeats: int = 3) -> dict:
    """One benchmark row: :func:`~sphereimpact.fit.fit` of the parameters in ``start`` (from those values) to the
    noise-free curve of ``truth``: e_t, |omega_f| and the rebound angle at each of ``incidences`` [deg], each
    bounce solved by ``simulate`` alone at its default options.

    ``seconds`` is the median of ``repeats`` complete fits, or of fewer (:func:`~.timing.interleaved_runs`; each
    solves its bounces' normal motions afresh);
    ``worst_error`` the largest relative difference of the fitted parameters from the values that made the curve;
    ``throughput`` the bounces the fit's model evaluations solved per second; ``target_seconds``
    :data:`FIT_TARGET_SECONDS`.
    """
    log.info("sweep bench: %s (%d bounces)", name, len(incidences))
    scene = truth.scene
    bounces = [simulate(scene.with_(incidence=float(theta))) for theta in incidences]
    table = pd.DataFrame({"speed": scene.speed, "incidence": np.asarray(incidences, dtype=float),
                          "e_t": [b.e_t for b in bounces],
                          "abs_omega_f": [abs(b.omega_f) for b in bounces],
                          "rebound_angle": [b.rebound_angle for b in bounces]})
    free = list(start)
    # the truth's own curve: its ball is the benchmark's, described or not
    row, result = _timed_fit(name, read_measured(table, source=name), with_values(truth, start), free, repeats,
                             FIT_TARGET_SECONDS, chapter_ball=True)
    return row | {"worst_error": max(abs(result.parameters[n].value / getattr(scene, n) - 1.0) for n in free)}


def _timed_fit(name: str, measured, ball, free: list, repeats: int, target: float, **options) -> tuple:
    """(the row, the last result) of ``repeats`` complete fits of ``free`` to ``measured`` from ``ball``, timed by the
    benchmarks' protocol (:func:`~.timing.interleaved_seconds`): the fit rows' shared part, ``worst_error`` empty."""
    results = []
    seconds, rounds = interleaved_runs({"fit": lambda: results.append(fit(measured, ball, free, **options))},
                                       repeats)
    seconds = seconds["fit"]
    evaluations, bounces = results[-1].statistics["evaluations"], len(measured.bounces)
    return ({"sweep": name, "scenes": bounces, "seconds": seconds, "throughput": evaluations * bounces / seconds,
             "worst_error": math.nan, "repeats": rounds, "evaluations": evaluations, "target_seconds": target},
            results[-1])


def measure_data_fit(name: str, measured, ball, free: list, repeats: int = 3) -> dict:
    """One benchmark row: :func:`~sphereimpact.fit.fit` of ``free`` (from ``ball``'s values) to ``measured`` bounces
    (a :class:`~sphereimpact.fit.Measured`), each bounce solved by ``simulate`` alone at its default options.

    ``seconds`` is the median of ``repeats`` complete fits, or of fewer (as :func:`measure_fit`);
    ``throughput`` the bounces the fit's model evaluations solved per second; ``worst_error`` empty (measured data:
    no values made them); ``target_seconds`` :data:`DATA_FIT_TARGET_SECONDS`.
    """
    log.info("sweep bench: %s (%d bounces)", name, len(measured.bounces))
    return _timed_fit(name, measured, ball, free, repeats, DATA_FIT_TARGET_SECONDS)[0]


#: The damped microslip map of the compiled kernels' issue (43): Kharaz's ball with the issue's Hunt-Crossley chi over
#: incidence x speed (10 309 scenes, each its own normal problem: no similarity serves a damped contact), every output.
DAMPED_MAP = {"chi": "0.02", "incidence": "1:85:0.5", "speed": "1:7:0.1"}
DAMPED_MAP_TARGET_SECONDS = 10.0


def damped_map_command(scene: Scene) -> list[str]:
    """``sphereimpact sweep``'s arguments (without ``--out``) for :data:`DAMPED_MAP` on ``scene``'s ball: its law (a
    Hertz spring with a ``chi``), modulus, mass, diameter, inertia factor, friction, tangential model and its shear
    modulus, each value as Python prints it (the scene's to the bit)."""
    flags = {"model": scene.model, "modulus": repr(scene.modulus), "mass": repr(scene.mass),
             "diameter": repr(scene.diameter), "inertia-factor": repr(scene.inertia_factor), "mu": repr(scene.mu),
             "tangential": scene.tangential, "shear-modulus": repr(scene.shear_modulus), **DAMPED_MAP}
    return ["sweep", *(part for name, value in flags.items() for part in (f"--{name}", value))]


def measure_command(name: str, arguments: list[str], repeats: int = 3,
                    target_seconds: float = DAMPED_MAP_TARGET_SECONDS) -> dict:
    """One benchmark row: the command ``sphereimpact`` ``arguments`` whole, each run a fresh Python process (start,
    imports, loading the compiled kernels, the work on every CPU, the table written to a temporary file), the
    median of ``repeats`` runs; ``scenes`` is the table's rows, ``command`` the command line.  The process runs as a
    user's: without the pipeline's ``SPHEREIMPACT_JOBS`` (its timed job runs alone)."""
    import os
    import tempfile
    import time

    from ..sweep.processes import JOBS_VARIABLE

    env = {name: value for name, value in os.environ.items() if name != JOBS_VARIABLE}

    log.info("sweep bench: %s (a command)", name)
    seconds = []
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "table.csv"
        for _ in range(repeats):
            start = time.perf_counter()
            fresh_run(("-m", "sphereimpact", *arguments, "--out", str(out), "--force"), name, env)
            seconds.append(time.perf_counter() - start)
        with out.open(encoding="utf-8") as table:
            scenes = sum(1 for _ in table) - 1
    median = float(np.median(seconds))
    return {"sweep": name, "command": " ".join(["sphereimpact", *arguments]), "scenes": scenes, "seconds": median,
            "throughput": scenes / median, "repeats": repeats, "target_seconds": target_seconds}


def sweeps(lanes: int = 20_000, million: bool = True, laws=tuple(LAW_SCENES)) -> list[tuple]:
    """The benchmark's sweeps, in its rows' order: (name, scenes, target speed-up or None, :func:`measure`'s
    options, the row's extra cells).  See :func:`run` for the parameters."""
    rng = np.random.default_rng(1)
    varied = pd.DataFrame({"angle": rng.uniform(0, 89, lanes), "speed": rng.uniform(0.5, 30, lanes),
                           "k": rng.uniform(2e4, 2e5, lanes), "b": rng.uniform(2, 30, lanes),
                           "mass": rng.uniform(0.05, 0.5, lanes)})
    one_ball = grid(angle=np.arange(0, 90, 1.0), speed=np.arange(0.5, 30.01, 0.5))
    listed = [
        # target: 1000x, the contact-laws issue's (the batched integrator's own target was 300x)
        ("k, b, m per scene, modified ((zeta, lam) plane)", varied, 1000, {}, {}),
        ("angle x speed, one ball, modified (similarity)", one_ball, 1000, {}, {}),
        ("angle x speed, one ball, kelvin-voigt (closed form)", one_ball.assign(model="kelvin-voigt"), None, {}, {}),
    ]
    for law in laws:  # the modified law's one-ball grid: a law without a kernel is interpolated in chi v_n
        listed.append((f"angle x speed, one ball, {law}", one_ball.assign(model=law, **LAW_SCENES[law]), None, {}, {}))
    if million:
        # the exact elastic microslip contact over a map of one ball: one simulate per incidence, scaled
        listed.append(("10^5 scenes, hertz, microslip, angle x speed (similar scenes)",
                       grid(angle=np.linspace(1, 85, 316), speed=np.linspace(0.5, 30, 316)).assign(**MICROSLIP_MAP),
                       None, {"contenders": {"simulate": CONTENDERS["simulate"]}, "every_output": False,
                              "memory": False}, {"target_seconds": MICROSLIP_MAP_TARGET_SECONDS}))
        listed.append(("10^6 scenes, modified, angle x speed",
                       grid(angle=np.linspace(0, 89, 1000), speed=np.linspace(0.5, 30, 1000)), 1000, {}, {}))
        flags = " ".join(f"--{name.replace('_', '-')} {text}" for name, text in GUIDE_SWEEP.items())
        # its every-output-over-fast ratio is a target (issue 43): its rounds are always `repeats`, whatever they take
        listed.append((f"the sweeps guide's large sweep ({flags})", guide_sweep(), None, {"budget": math.inf}, {}))
    return listed


def write_accuracies(json_path: str, sample: int = 60, lanes: int = 20_000, million: bool = True,
                     laws=tuple(LAW_SCENES)) -> dict:
    """:func:`accuracy` of every sweep of :func:`sweeps` (parameters as :func:`run`'s), by name, into ``json_path``:
    the untimed half of the benchmark, which :func:`run` takes back (``accuracies``)."""
    out = {}
    for name, scenes, _, options, _ in sweeps(lanes, million, laws):
        log.info("sweep bench accuracy: %s (%d scenes)", name, len(scenes))
        out[name] = accuracy(scenes, sample, contenders=options.get("contenders"), memory=options.get("memory", True))
    Path(json_path).write_text(json.dumps(out, indent=1) + "\n")
    return out


def run(csv_path: str, repeats: int = 3, sample: int = 60, lanes: int = 20_000, million: bool = True,
        laws=tuple(LAW_SCENES), fit_of: tuple | None = None, data_fit_of: tuple | None = None,
        accuracies: dict | None = None, command_of: tuple | None = None) -> pd.DataFrame:
    """Every benchmark sweep; writes ``csv_path``.

    Parameters
    ----------
    repeats : int
        Complete runs per timing, for the engine and for each contender alike.
    sample : int
        Scenes of each sweep on which the per-scene contenders are timed.
    lanes : int
        Random scenes of the many-ball sweep (k, b, m, angle and speed drawn per scene: the engine's (zeta, lam)
        plane).
    million : bool
        Also time a 10^6-scene one-ball sweep, and the sweeps guide's large sweep (:data:`GUIDE_SWEEP`).
    laws : sequence of str
        Laws of :data:`LAW_SCENES` to time on the one-ball angle x speed sweep each (the path the engine
        takes for them: interpolation in their family's number, per family, or batched lanes if the law
        has a kernel).
    fit_of : (Ball, dict, array) or None
        Also time a fit (:func:`measure_fit`): the ball whose curve is fitted, the free parameters' start values,
        the incidences [deg].
    data_fit_of : (str, Measured, Ball, list) or None
        Also time a fit to measured bounces (:func:`measure_data_fit`): the row's name, the bounces, the ball it
        starts from, the free parameters.
    accuracies : dict or None
        Each sweep's :func:`accuracy` by name, as :func:`write_accuracies` wrote them with the same ``sample``,
        ``lanes``, ``million`` and ``laws`` (else each is computed before its timing).  ValueError if a sweep's is
        missing or was drawn on another sample size.
    command_of : (str, list of str) or None
        Also time a whole command (:func:`measure_command`): the row's name and ``sphereimpact``'s arguments.
    """
    steady_state()
    rows = []
    for name, scenes, target, options, extra in sweeps(lanes, million, laws):
        known = None
        if accuracies is not None:
            known = accuracies.get(name)
            if known is None or len(known["sample"]) != min(sample, len(scenes)):
                raise ValueError(f"accuracies: no accuracy of the sweep {name!r} on a sample of {sample} scenes; "
                                 "write them with the same sample, lanes, million and laws (write_accuracies)")
        rows.append(measure(name, scenes, target, sample_size=sample, repeats=repeats, known=known, **options)
                    | extra)
    if fit_of is not None:
        truth, start, incidences = fit_of
        rows.append(measure_fit(f"fit of {', '.join(start)} to a {len(incidences)}-incidence Kharaz curve "
                                f"({truth.scene.model}, {truth.scene.tangential})", truth, start, incidences,
                                repeats))
    if data_fit_of is not None:
        rows.append(measure_data_fit(*data_fit_of, repeats))
    if command_of is not None:
        rows.append(measure_command(*command_of, repeats))
    frame = pd.DataFrame(rows)
    frame.to_csv(csv_path, index=False, float_format="%.4g")
    return frame
