"""Sweep throughput against per-scene solving, measured side by side in one run (a benchmark, not a test).

For each sweep: the batched engine's impacts per second on the whole sweep, and two per-scene
baselines on a random sample, each at the loosest tolerance whose worst error on the sample is no
larger than the engine's (equal accuracy):

- ``solve_ivp``: one :func:`scipy.integrate.solve_ivp` call per scene (DOP853, the normal ODE with its
  two events, as :class:`sphereimpact.normal.IntegratedNormal` runs it) plus the impulse algebra;
  the lean per-scene approach the targets are stated against;
- ``simulate``: the package's single-impact path, which adds histories, force extremes and checks.

Gravity-free scenes only (the lean baseline's impulse algebra assumes g = 0).
"""

from __future__ import annotations

import time
import tracemalloc

import numpy as np
import pandas as pd

from ..normal import IntegratedNormal
from ..numerics.reference import outputs_from_normal, relative_errors
from ..scene import Scene, SolverOptions
from ..solve import simulate
from .engine import SCENE_COLUMNS, grid, sweep

KEYS = ("t_m", "delta_m", "t_f", "vc_t", "vc_n", "ve_t", "ve_n", "omega_f", "cor")
TOLERANCES = (1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)


def _scene(row) -> Scene:
    return Scene(**{k: (row[k] if k in ("model", "separation") else float(row[k])) for k in SCENE_COLUMNS})


def _worst(table: pd.DataFrame, refs: list[dict]) -> float:
    return max(max(relative_errors(row, ref, _scene(row), KEYS).values())
               for row, ref in zip(table.to_dict("records"), refs))


def _lean(scene: Scene, options: SolverOptions) -> dict:
    """One solve_ivp call and the impulse algebra: every sweep output of one scene."""
    normal = IntegratedNormal(scene, options)
    return outputs_from_normal(scene, normal.t_m, normal.delta_m, normal.t_f, float(normal.state(normal.t_f)[1]))


def _per_scene(solve, sample: pd.DataFrame, refs: list[dict], error: float) -> tuple[float, float, float]:
    """(rtol, seconds per scene, worst error) of the loosest per-scene tolerance meeting ``error``."""
    scenes = [_scene(row) for row in sample.to_dict("records")]
    for rtol in TOLERANCES:
        options = SolverOptions(method="DOP853", rtol=rtol, atol=rtol)
        start = time.perf_counter()
        outs = [solve(s, options) for s in scenes]
        seconds = (time.perf_counter() - start) / len(scenes)
        worst = max(max(relative_errors(o, r, s, KEYS).values()) for o, r, s in zip(outs, refs, scenes))
        if worst <= error:
            return rtol, seconds, worst
    return TOLERANCES[-1], seconds, worst


def measure(name: str, scenes: pd.DataFrame, target_speedup: float | None, sample_size: int = 60,
            seed: int = 0, repeats: int = 3) -> dict:
    """One benchmark row for the sweep ``scenes``.

    The sweep's time is the median of ``repeats`` complete runs (each builds its interpolants anew:
    nothing is cached between calls), so one noisy run on a shared machine does not decide the row.
    """
    runs = []
    for _ in range(repeats):
        start = time.perf_counter()
        table = sweep(scenes)
        runs.append(time.perf_counter() - start)
    seconds = float(np.median(runs))
    tracemalloc.start()  # a second run: tracing allocations slows numpy, so it is kept out of the timing
    sweep(scenes)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    pick = np.random.default_rng(seed).choice(len(table), size=min(sample_size, len(table)), replace=False)
    sample = table.iloc[np.sort(pick)]
    refs = [simulate(_scene(row), SolverOptions(rtol=1e-13, atol=1e-13)).to_dict()
            for row in sample.to_dict("records")]
    error = _worst(sample, refs)
    throughput = len(table) / seconds
    row = {"sweep": name, "scenes": len(table), "seconds": seconds, "throughput": throughput, "worst_error": error}
    for label, solve in (("solve_ivp", _lean), ("simulate", lambda s, o: simulate(s, o).to_dict())):
        rtol, per_scene, per_scene_error = _per_scene(solve, sample, refs, max(error, 1e-12))
        row |= {f"{label}_rtol": rtol, f"{label}_error": per_scene_error, f"{label}_throughput": 1.0 / per_scene,
                f"speedup_over_{label}": throughput * per_scene}
    return row | {"target_speedup": target_speedup, "peak_memory_mb": peak / 2**20}


def run(csv_path: str, million: bool = True) -> pd.DataFrame:
    """All benchmark sweeps; writes ``csv_path``."""
    rng = np.random.default_rng(1)
    n = 20_000
    varied = pd.DataFrame({"angle": rng.uniform(0, 89, n), "speed": rng.uniform(0.5, 30, n),
                           "k": rng.uniform(2e4, 2e5, n), "b": rng.uniform(2, 30, n), "mass": rng.uniform(0.05, 0.5, n)})
    rows = [
        measure("k, b, m per lane (batched integrator)", varied, 300),
        measure("angle x speed, one ball, modified (similarity)",
                grid(angle=np.arange(0, 90, 1.0), speed=np.arange(0.5, 30.01, 0.5)), 1000),
        measure("angle x speed, one ball, kelvin-voigt (closed form)",
                grid(angle=np.arange(0, 90, 1.0), speed=np.arange(0.5, 30.01, 0.5)).assign(model="kelvin-voigt"),
                None),
    ]
    if million:
        rows.append(measure("10^6 scenes, modified, angle x speed",
                            grid(angle=np.linspace(0, 89, 1000), speed=np.linspace(0.5, 30, 1000)), 1000))
    frame = pd.DataFrame(rows)
    frame.to_csv(csv_path, index=False, float_format="%.4g")
    return frame
