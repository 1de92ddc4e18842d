"""Which sweep path pays where: the paths that can solve the same scenes, timed against each other at equal
target, each with its worst error on a sample against an independent reference (a benchmark, not a test).

Eq. 4.2 without gravity is the one region where several paths apply (:mod:`.paths`), so the comparisons
are there, at several sweep sizes and under both criteria:

- ``one ball``: scenes sharing the chapter's damping ratio, lam log-uniform: the lam interpolant
  (``lambda-interpolant``), the plane on its one-zeta slice (``plane``), the Taylor lanes and the
  Runge-Kutta lanes;
- ``many balls``: zeta and lam drawn per scene inside the plane's domain: the plane and both lanes.

An interpolant's time includes its build: the engine builds it anew for every sweep.  The reference is the
single-impact model in plain-float DOP853 at rtol 1e-13 (:func:`.similarity.dimensionless_motion`), a code
path none of the contenders shares.  A row is ``dominated`` when another contender of the same comparison,
size and criterion is faster and at most as far from the reference; a path dominated on every row of a
comparison is one the engine should not take there.

The errors are the study's untimed half (:func:`errors`, all of them :func:`write_accuracies`): the pipeline's job
``sweep_paths_accuracy`` computes them beside the other jobs, and the timed job, which runs alone, reads them.
"""

from __future__ import annotations

import json
import logging
import math
from pathlib import Path

import numpy as np
import pandas as pd

from .timing import interleaved_seconds, steady_state
from ..contact.separation import Separation
from ..impact.scene import Scene, SolverOptions
from ..sweep import batch, plane, series_lanes
from ..sweep.outputs import NORMAL_OUTPUTS
from ..sweep.similarity import LambdaInterpolant, _errors, dimensionless_motion

log = logging.getLogger(__name__)
#: The reference: the single-impact model in plain-float DOP853, at a tolerance far below the target.
REFERENCE = SolverOptions(method="DOP853-scalar", rtol=1e-13, atol=1e-13)
#: Scenes of the sweep each contender solves once, untimed, before the study's first timing (its compiled code loaded,
#: its first call made; its errors are computed in another job).
FIRST_TOUCH = 16
#: lam range of both comparisons (the chapter's ball at 0.4 to 40 m/s) and zeta range of the many balls'.
LAM_RANGE = (2.0, 200.0)
ZETA_RANGE = (0.01, 0.5)


def scene_for(zeta: float, lam: float, separation: Separation) -> Scene:
    """The chapter's ball at normal incidence with eq. 4.2's damping ratio ``zeta`` and ramp number ``lam``
    (b = 2 zeta sqrt(k m), v = lam omega_n R / c)."""
    base = Scene(separation=separation)
    b = 2.0 * zeta * math.sqrt(base.k * base.mass)
    speed = lam * math.sqrt(base.k / base.mass) * (0.5 * base.diameter) / base.ramp
    return base.with_(b=b, speed=speed)


def _contenders(zeta, lam, separation: Separation, target: float, one_zeta: bool) -> dict:
    """name -> call solving every scene (zeta, lam) on that path, interpolants built in the call."""
    lo, hi = float(lam.min()), float(lam.max())
    gamma, modified = np.zeros(zeta.size), np.ones(zeta.size, bool)
    calls = {}
    if one_zeta:
        calls["lambda-interpolant"] = lambda: LambdaInterpolant(float(zeta[0]), lo, hi, separation, target)(lam)
    calls["plane"] = lambda: plane.PlaneInterpolant(float(zeta.min()), float(zeta.max()), lo, hi, separation,
                                                    target)(zeta, lam)
    calls["taylor-lanes"] = lambda: series_lanes.integrate(zeta, lam, separation, target)
    calls["runge-kutta-lanes"] = lambda: batch.integrate(zeta, lam, gamma, modified, separation, target)
    return calls


def _drawn(comparison: str, scenes: int, seed: int, sample: int) -> tuple:
    """(zeta, lam, the sample's rows) of one comparison's sweep of ``scenes`` scenes, drawn from ``seed``."""
    rng = np.random.default_rng(seed)
    lam = np.exp(rng.uniform(*np.log(LAM_RANGE), scenes))
    if comparison == "one ball":
        zeta = np.full(scenes, Scene().zeta)
    else:
        zeta = rng.uniform(*ZETA_RANGE, scenes)
    return zeta, lam, np.sort(rng.choice(scenes, size=min(sample, scenes), replace=False))


def errors(comparison: str, scenes: int, separation: Separation, target: float, sample: int, seed: int) -> dict:
    """The study's untimed half for one comparison: each contender's worst error on the sample against the reference
    (name -> error), the contenders called once each."""
    zeta, lam, pick = _drawn(comparison, scenes, seed, sample)
    calls = _contenders(zeta, lam, separation, target, comparison == "one ball")
    solved = [dimensionless_motion(scene_for(z, q, separation), REFERENCE) for z, q in zip(zeta[pick], lam[pick])]
    reference = {key: np.array([row[key] for row in solved]) for key in NORMAL_OUTPUTS}
    return {name: _errors({key: values[pick] for key, values in call().items()}, reference, NORMAL_OUTPUTS)
            for name, call in calls.items()}


def compare(comparison: str, scenes: int, separation: Separation, target: float, repeats: int, sample: int,
            seed: int, known: dict | None = None) -> list[dict]:
    """One row per contender of ``comparison`` (``one ball`` or ``many balls``) on ``scenes`` scenes: its time, and
    its error (``known``, as :func:`errors` gives it, else computed here before the timing)."""
    zeta, lam, pick = _drawn(comparison, scenes, seed, sample)
    calls = _contenders(zeta, lam, separation, target, comparison == "one ball")
    worst = known if known is not None else errors(comparison, scenes, separation, target, sample, seed)
    seconds = interleaved_seconds(calls, repeats)
    log.info("sweep paths: %s, %d scenes, %s: %s", comparison, scenes, separation,
             ", ".join(f"{name} {seconds[name]:.3g} s" for name in calls))
    return [{"comparison": comparison, "separation": separation, "scenes": scenes, "target": target,
             "path": name, "seconds": seconds[name], "us_per_scene": 1e6 * seconds[name] / scenes,
             "worst_error": worst[name], "repeats": repeats, "sample": len(pick)} for name in calls]


def _studied(sizes) -> list[tuple[str, int, Separation, int]]:
    """(comparison, scenes, criterion, seed) of every comparison of the study, in its order."""
    return [(comparison, int(scenes), separation, int(scenes) + i) for comparison in ("one ball", "many balls")
            for scenes in sizes for i, separation in enumerate(Separation)]


def _key(comparison: str, scenes: int, separation: Separation) -> str:
    return f"{comparison}, {scenes} scenes, {separation}"


def write_accuracies(json_path: str, sizes=(500, 2000, 8000, 32000), target: float = 1e-8, sample: int = 30) -> dict:
    """:func:`errors` of every comparison of the study (parameters as :func:`run`'s) into ``json_path``: the study's
    untimed half, which the pipeline runs in a job of its own (rule ``sweep_paths_accuracy``) beside the others, so
    that the timed job, which runs alone, spends its time timing."""
    out = {"target": target, "sample": sample, "errors": {}}
    for comparison, scenes, separation, seed in _studied(sizes):
        log.info("sweep paths accuracy: %s, %d scenes, %s", comparison, scenes, separation)
        out["errors"][_key(comparison, scenes, separation)] = errors(comparison, scenes, separation, target, sample,
                                                                     seed)
    Path(json_path).write_text(json.dumps(out, indent=1) + "\n")
    return out


def _dominated(table: pd.DataFrame) -> pd.Series:
    """Per row: another contender of its comparison, size and criterion is faster and as accurate."""
    out = pd.Series(False, index=table.index)
    for _, group in table.groupby(["comparison", "separation", "scenes"], sort=False):
        for i, row in group.iterrows():
            others = group.drop(index=i)
            out[i] = bool(((others["seconds"] < row["seconds"]) & (others["worst_error"] <= row["worst_error"])).any())
    return out


def run(csv_path: str, sizes=(500, 2000, 8000, 32000), target: float = 1e-8, repeats: int = 3,
        sample: int = 30, accuracy_json: str | None = None) -> pd.DataFrame:
    """Every comparison at each of ``sizes`` scenes and both criteria; writes ``csv_path``.

    Parameters
    ----------
    sizes : sequence of int
        Scenes per sweep.
    target : float
        The sweep target every contender is asked for.
    repeats : int
        Complete runs per timing, the contenders in turn within each repeat (median reported).
    sample : int
        Scenes per sweep on which each contender's error is measured against the reference.
    accuracy_json : str, optional
        The errors as :func:`write_accuracies` wrote them with the same ``sizes``, ``target`` and ``sample`` (else
        each comparison's errors are computed before its timing).
    """
    known = None
    if accuracy_json is not None:
        known = json.loads(Path(accuracy_json).read_text())
        if (known["target"], known["sample"]) != (target, sample):
            raise ValueError(f"sweep paths: {accuracy_json} holds errors at target {known['target']:g} on "
                             f"{known['sample']} scenes, not at {target:g} on {sample}: write it with the same settings")
    steady_state()
    zeta, lam, _ = _drawn("many balls", FIRST_TOUCH, 0, 1)
    for separation in Separation:  # every contender's code run once, untimed, before the first timing
        for call in _contenders(zeta, lam, separation, target, True).values():
            call()
    rows = []
    for comparison, scenes, separation, seed in _studied(sizes):
        errors_known = None
        if known is not None:
            key = _key(comparison, scenes, separation)
            if key not in known["errors"]:
                raise ValueError(f"sweep paths: {accuracy_json} holds no errors of the comparison {key!r}: write it "
                                 "with the same sizes")
            errors_known = known["errors"][key]
        rows += compare(comparison, scenes, separation, target, repeats, sample, seed, errors_known)
    table = pd.DataFrame(rows)
    table["dominated"] = _dominated(table)
    table.to_csv(csv_path, index=False, float_format="%.4g")
    return table
