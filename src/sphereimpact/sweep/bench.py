"""Sweep throughput against per-scene solving, measured side by side in one run (a benchmark, not a test).

For each sweep: the batched engine's impacts per second on the whole sweep;
the per-scene single-impact path (``simulate``, DOP853) on a random sample,
at the loosest tolerance whose worst error on the sample is no larger than the
engine's (equal accuracy); the speed-up; and the engine's peak memory.
"""

from __future__ import annotations

import time
import tracemalloc

import numpy as np
import pandas as pd

from ..scene import Scene, SolverOptions
from ..solve import simulate
from ..numerics.reference import relative_errors
from .engine import SCENE_COLUMNS, grid, sweep

KEYS = ("t_m", "delta_m", "t_f", "vc_t", "vc_n", "ve_t", "ve_n", "omega_f", "cor")
TOLERANCES = (1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)


def _scene(row) -> Scene:
    return Scene(**{k: (row[k] if k in ("model", "separation") else float(row[k])) for k in SCENE_COLUMNS})


def _worst(table: pd.DataFrame, refs: list[dict]) -> float:
    return max(max(relative_errors(row, ref, _scene(row), KEYS).values())
               for row, ref in zip(table.to_dict("records"), refs))


def _per_scene(sample: pd.DataFrame, refs: list[dict], error: float) -> tuple[float, float, float]:
    """(rtol, seconds per scene, worst error) of the loosest per-scene tolerance meeting ``error``."""
    scenes = [_scene(row) for row in sample.to_dict("records")]
    for rtol in TOLERANCES:
        options = SolverOptions(method="DOP853", rtol=rtol, atol=rtol)
        start = time.perf_counter()
        outs = [simulate(s, options).to_dict() for s in scenes]
        seconds = (time.perf_counter() - start) / len(scenes)
        worst = max(max(relative_errors(o, r, s, KEYS).values()) for o, r, s in zip(outs, refs, scenes))
        if worst <= error:
            return rtol, seconds, worst
    return TOLERANCES[-1], seconds, worst


def measure(name: str, scenes: pd.DataFrame, target_speedup: float | None, sample_size: int = 60,
            seed: int = 0) -> dict:
    """One benchmark row for the sweep ``scenes``."""
    start = time.perf_counter()
    table = sweep(scenes)
    seconds = time.perf_counter() - start
    tracemalloc.start()  # a second run: tracing allocations slows numpy, so it is kept out of the timing
    sweep(scenes)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    pick = np.random.default_rng(seed).choice(len(table), size=min(sample_size, len(table)), replace=False)
    sample = table.iloc[np.sort(pick)]
    refs = [simulate(_scene(row), SolverOptions(rtol=1e-13, atol=1e-13)).to_dict()
            for row in sample.to_dict("records")]
    error = _worst(sample, refs)
    rtol, per_scene, per_scene_error = _per_scene(sample, refs, max(error, 1e-12))
    throughput = len(table) / seconds
    return {"sweep": name, "scenes": len(table), "seconds": seconds, "throughput": throughput,
            "worst_error": error, "per_scene_rtol": rtol, "per_scene_error": per_scene_error,
            "per_scene_throughput": 1.0 / per_scene, "speedup": throughput * per_scene,
            "target_speedup": target_speedup, "peak_memory_mb": peak / 2**20}


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
