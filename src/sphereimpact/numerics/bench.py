"""Speed at equal accuracy: ``simulate`` against the hand-written script, and the reduced model against the
planar one (a benchmark: timings are written to files, never asserted).

``simulate`` at its default options is timed beside
:func:`sphereimpact.numerics.handwritten.handwritten` run at the loosest tolerance of :data:`TOLERANCES`
whose error (against :func:`sphereimpact.numerics.reference.reference`) is no larger than
``simulate``'s.  Both are timed with one protocol, :func:`per_call_seconds`; each timed ``simulate`` call builds and
checks its Scene too, from its fields (``Scene(**scene.as_dict())``: what a user's call on a new Scene pays; a copy
by :meth:`~sphereimpact.Scene.with_` with a new approach, a map's or fit's way, costs less: ``results/bench_stages.csv``),
the script reading the scene's numbers.
"""

from __future__ import annotations

import logging
import math

import numpy as np
import pandas as pd

from ..contact.separation import Separation
from ..impact.scene import Scene, SolverOptions
from ..impact.solve import simulate
from .handwritten import handwritten
from .reference import reference, worst_error
from .timing import per_call_seconds, steady_state
from .workprecision import TARGET

log = logging.getLogger(__name__)

#: Tolerances tried for a per-scene contender, loosest first: the first whose error meets the one it is
#: compared with is timed (here and in :mod:`sphereimpact.numerics.bench_sweep`).
TOLERANCES = (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12)
#: Each law's parameters on the chapter's ball, for the per-law rows here and in the sweep benchmark.  The
#: Hertz constant 8.8e5 N/m^1.5 gives about the chapter's peak force at 3 m/s (k_linear (v_n /
#: omega_n)^(-1/2)); chi = 0.05 s/m, a COR near 0.9 there.
LAW_SCENES = {
    "linear-hunt-crossley": {"k": 6.0e4, "chi": 0.05},
    "hertz": {"k": 8.8e5},
    "hunt-crossley": {"k": 8.8e5, "chi": 0.05},
}


def bench_scenes(chapter: dict[str, Scene], domain: bool = True, laws=tuple(LAW_SCENES)) -> dict[str, Scene]:
    """The chapter's cases and, with ``domain``, scenes across the domain (30° at 3 m/s, 45° at 20 m/s)
    under both laws and at 30° and 3 m/s under each of ``laws`` (:data:`LAW_SCENES`); force criterion, no
    gravity."""
    base = next(iter(chapter.values()))
    scenes = dict(chapter)
    for model in ("modified", "kelvin-voigt") if domain else ():
        scenes[f"30deg-3ms/{model}"] = base.with_(angle=30.0, speed=3.0, model=model)
        scenes[f"45deg-20ms/{model}"] = base.with_(angle=45.0, speed=20.0, model=model)
    for model in laws:
        scenes[f"30deg-3ms/{model}"] = base.with_(angle=30.0, speed=3.0, model=model, **LAW_SCENES[model])
    return {name: s.with_(separation=Separation.FORCE, gravity=0.0) for name, s in scenes.items()}


def simulate_vs_handwritten(scenes: dict[str, Scene], repeats: int = 3) -> pd.DataFrame:
    """Two rows per scene: ``simulate`` (default options: ``method`` says what ``auto`` took, the closed form
    with rtol 0, taylor or DOP853-scalar) and the hand-written script at equal accuracy.

    Columns: ``scene``, ``model``, ``angle``, ``speed``, ``contender``, ``method``, ``rtol``, ``error``
    (worst relative error over t_m, delta_m, t_f, COR, omega_f, v_E,t), ``reached`` (False: no tolerance
    on the ladder met simulate's error; timed at the tightest), ``time`` [s per impact], ``nfev``,
    ``time_ratio`` (time / the hand-written script's time), ``repeats`` and ``batch`` (the protocol).
    """
    steady_state()
    rows = []
    default = SolverOptions()
    for name, scene in scenes.items():
        log.info("bench: %s", name)
        ref = reference(scene).outputs
        out = simulate(scene, default)
        sim_error = worst_error(out.to_dict(), ref, scene)
        for rtol in TOLERANCES:
            hand = handwritten(scene, rtol)
            hand_error = worst_error(hand, ref, scene)
            if hand_error <= sim_error:
                break
        fields = scene.as_dict()
        timed, sizes = per_call_seconds({"simulate": lambda: simulate(Scene(**fields), default),  # the Scene built too
                                         "handwritten": lambda: handwritten(scene, rtol)}, repeats)
        sim_time, hand_time = timed["simulate"], timed["handwritten"]
        base = {"scene": name, "model": scene.model, "angle": scene.angle, "speed": scene.speed, "repeats": repeats}
        rows.append(base | {"batch": sizes["simulate"], "contender": "simulate", "method": out.method, "rtol": out.rtol,
                            "error": sim_error, "reached": True, "time": sim_time, "nfev": out.nfev,
                            "time_ratio": sim_time / hand_time})
        rows.append(base | {"batch": sizes["handwritten"], "contender": "handwritten", "method": "DOP853", "rtol": rtol,
                            "error": hand_error, "reached": bool(hand_error <= sim_error), "time": hand_time,
                            "nfev": hand["nfev"], "time_ratio": 1.0})
    return pd.DataFrame(rows)


def microslip_bench(scene: Scene, reference: tuple[int, int], repeats: int = 3) -> pd.DataFrame:
    """What the exact microslip contact costs: one impact at its default resolution beside the rigid contact on
    the same scene, beside the compiled port a user writes by hand (:mod:`.compiled_port`, at the impact's own
    cells and steps) and beside its element row's march alone (the compiled kernel, on the impact's own inputs).

    Rows have the bench's columns.  ``error``: one impact's, the larger of e_t's absolute and spin's relative
    error against the ``reference`` resolution (cells, time steps); NaN for the march (not an answer).  ``time``
    is per impact; ``time_ratio`` is over the row's comparison contender (the rigid contact for the impact, the
    impact for the port and the march).
    """
    from ..contact.tangential.microslip import march, march_inputs
    from .compiled_port import compiled_port, port_numbers

    steady_state()
    rows = []
    default = SolverOptions()
    rigid_scene = scene.with_(tangential="rigid")
    out, rigid = simulate(scene, default), simulate(rigid_scene, default)
    ref = simulate(scene, SolverOptions(settings={"elements": reference[0], "time_steps": reference[1]}))

    def error_of(vc_t: float, omega_f: float) -> float:
        return max(abs(vc_t - ref.vc_t) / scene.v_tangent, abs(omega_f / ref.omega_f - 1.0))

    row = out.motion.tangential
    _, inputs = march_inputs(out.motion.normal, row.time_steps)
    numbers = port_numbers(scene, row.elements, row.time_steps)
    port_vc_t, port_omega_f, port_nfev = compiled_port(*numbers)  # compiled here, outside the timing
    fields, rigid_fields = scene.as_dict(), rigid_scene.as_dict()
    timed, sizes = per_call_seconds({"microslip": lambda: simulate(Scene(**fields), default),  # each its Scene built too
                                     "rigid": lambda: simulate(Scene(**rigid_fields), default),
                                     "port": lambda: compiled_port(*numbers),
                                     "march": lambda: march(*inputs, row.elements)}, repeats)
    march_name = f"its march alone ({row.elements} cells x {row.time_steps} steps)"

    def one(contender: str, key: str, **values) -> dict:
        return {"scene": f"{scene.angle:g}deg-{scene.speed:g}ms/{scene.model}/microslip", "model": scene.model,
                "angle": scene.angle, "speed": scene.speed, "repeats": repeats, "batch": sizes[key],
                "method": out.method, "rtol": out.rtol, "reached": True, "contender": contender, "time": timed[key],
                **values}

    rows.append(one("simulate", "microslip", error=error_of(out.vc_t, out.omega_f), nfev=out.nfev,
                    time_ratio=timed["microslip"] / timed["rigid"]))
    rows.append(one("simulate, rigid contact", "rigid", method=rigid.method, rtol=rigid.rtol, error=0.0,
                    nfev=rigid.nfev, time_ratio=1.0))
    rows.append(one("compiled port (numba: RK4 normal motion, the same march)", "port", method="RK4", rtol=math.nan,
                    error=error_of(port_vc_t, port_omega_f), nfev=port_nfev, time_ratio=timed["port"] / timed["microslip"]))
    rows.append(one(march_name, "march", error=math.nan, nfev=0, time_ratio=timed["march"] / timed["microslip"]))
    return pd.DataFrame(rows)


#: The scene of the kernels' rows of the bench table: per process, not per impact.
KERNEL_SCENE = "the compiled kernels, once per process"


def kernel_bench(repeats: int = 3) -> pd.DataFrame:
    """The compiled kernels' cost once per process (:func:`kernel_seconds`), as rows of the bench table: their
    compilation on a fresh machine (``time_ratio`` over the load) and their load from the disk cache; ``error``
    NaN (not an answer).  Each is a fresh process on one core: the pipeline runs it beside other jobs."""
    compiled, loaded = kernel_seconds(repeats)
    once = {"scene": KERNEL_SCENE, "repeats": repeats, "batch": 1, "error": math.nan, "nfev": 0}
    return pd.DataFrame([once | {"contender": "compile (fresh disk cache)", "time": compiled,
                                 "time_ratio": compiled / loaded},
                         once | {"contender": "load (from the disk cache)", "time": loaded, "time_ratio": 1.0}])


#: A fresh process's first use of the compiled kernels: numba imported, every kernel compiled or loaded (the
#: microslip march's, the normal motion's two integrators, every built-in law's force and series:
#: :func:`sphereimpact.integrators.compiled.compile_all`).
_FIRST_USE = ("import time; start = time.perf_counter(); "
              "from sphereimpact.integrators.compiled import compile_all; compile_all(); "
              "print(time.perf_counter() - start)")


def kernel_seconds(repeats: int = 3) -> tuple[float, float]:
    """Seconds [s] a fresh process takes to import numba and compile the package's kernels into an empty disk cache
    (``NUMBA_CACHE_DIR``, a temporary folder: what a fresh machine pays once), and the median over ``repeats``
    processes to load them from the cache that run filled (what every later process pays)."""
    import os
    import tempfile

    with tempfile.TemporaryDirectory() as cache:
        env = os.environ | {"NUMBA_CACHE_DIR": cache}

        def first_use() -> float:
            return float(fresh_run(("-c", _FIRST_USE), "the kernels' compilation", env))

        compiled = first_use()
        loaded = float(np.median([first_use() for _ in range(repeats)]))
    return compiled, loaded


def fresh_run(arguments, what: str, env=None) -> str:
    """The standard output of a fresh Python process (this interpreter) run with ``arguments``; RuntimeError naming
    ``what`` when it fails."""
    import subprocess
    import sys

    run = subprocess.run([sys.executable, *arguments], env=env, capture_output=True, text=True)
    if run.returncode:
        raise RuntimeError(f"{what} failed: {run.stderr.strip()[-500:]}")
    return run.stdout


#: The scene of the start-up rows of the bench table: each contender a fresh Python process.
STARTUP_SCENE = "a command's start, fresh process"
#: The start-up contenders: Python's own start with numpy, the floor of any command, and ``simulate --json`` of the
#: chapter's scene and of a Hertz ball (each whole run: start, imports, one impact, the JSON), as arguments of the
#: interpreter.
STARTUP = {"python -c 'import numpy'": ("-c", "import numpy"),
           "sphereimpact simulate --json": ("-m", "sphereimpact", "simulate", "--json", "--chapter-ball"),
           "sphereimpact simulate --json, a Hertz ball (DOP853-scalar)": (
               "-m", "sphereimpact", "simulate", "--json", "--model", "hertz", "--modulus", "1e8", "--mass", "0.145",
               "--diameter", "0.063", "--speed", "3")}


def startup_bench(repeats: int = 3) -> pd.DataFrame:
    """Seconds [s] a command takes from a fresh process (:data:`STARTUP`): the median over ``repeats`` runs of each
    contender, taken in turn.  Rows have the bench's columns; ``time_ratio`` is over numpy's start."""
    import time

    seconds: dict = {name: [] for name in STARTUP}
    for _ in range(repeats):
        for name, arguments in STARTUP.items():
            start = time.perf_counter()
            fresh_run(arguments, name)
            seconds[name].append(time.perf_counter() - start)
    floor = float(np.median(seconds["python -c 'import numpy'"]))
    return pd.DataFrame([{"scene": STARTUP_SCENE, "contender": name, "repeats": repeats, "batch": 1,
                          "error": math.nan, "nfev": 0, "time": float(np.median(times)),
                          "time_ratio": float(np.median(times)) / floor} for name, times in seconds.items()])


def stages(scenes: dict[str, Scene], repeats: int = 3) -> pd.DataFrame:
    """Where one impact's time goes, stage by stage, for each scene (same protocol as the bench).

    Rows per scene: ``build`` (building and checking the Scene from its fields), ``copy`` (:meth:`Scene.with_`'s copy with
    a new approach, as a map or a fit makes its scenes: the approach checked again), ``normal`` (the normal motion:
    closed form or integration), ``tangential`` (the tangential motion and spin on it), ``outcome`` (outputs: force
    extremes, kinematics at t_m and t_f), ``simulate`` (the whole call on a Scene built in it: the stages plus
    checks) and ``handwritten`` (the script, at simulate's tolerance).  Columns: ``scene``, ``stage``, ``time`` [s per
    impact], ``share`` (of simulate's time), ``batch`` (calls per timed run, :func:`batch_size`).
    """
    from ..impact.outcome import Outcome
    from ..integrators import normal_motion, resolve_method
    from ..impact.solve import ReducedMotion

    steady_state()
    rows = []
    default = SolverOptions()
    for name, scene in scenes.items():
        log.info("bench: %s", name)
        options = resolve_method(scene, default)
        normal = normal_motion(scene, options)
        motion = ReducedMotion(normal, options)
        # each timed call does all its work: nothing kept with the normal motion by the call before
        fields = scene.as_dict()
        times, sizes = per_call_seconds({"build": lambda: Scene(**fields), "copy": scene.with_,
                                         "normal": lambda: normal_motion(scene, options),
                                         "tangential": lambda: (normal.forget(), ReducedMotion(normal, options)),
                                         "outcome": lambda: (normal.forget(), Outcome.from_motion(motion, 0.0)),
                                         "simulate": lambda: simulate(Scene(**fields), default),
                                         "handwritten": lambda: handwritten(scene, default.rtol)}, repeats)
        rows += [{"scene": name, "stage": stage, "time": seconds, "share": seconds / times["simulate"],
                  "batch": sizes[stage]} for stage, seconds in times.items()]
    return pd.DataFrame(rows)


def profile_call(scene: Scene, calls: int = 200, top: int = 12) -> pd.DataFrame:
    """A profile of ``simulate(scene)``: the ``top`` functions by own time over ``calls`` calls.

    Columns: ``function`` (file:line(name), the package's path shortened), ``calls`` and ``own_us`` per
    impact, ``share`` of the profiled total.  Under the profiler small calls weigh more than they cost
    without it: the shares say where the time goes, not how much there is.
    """
    import cProfile
    import pstats

    simulate(scene)  # imports and caches out of the profile
    profiler = cProfile.Profile()
    profiler.enable()
    for _ in range(calls):
        simulate(scene)
    profiler.disable()
    stats = pstats.Stats(profiler).stats
    total = sum(entry[2] for entry in stats.values())
    rows = []
    for (path, line, function), (_, count, own, _, _) in stats.items():
        where = path.split("site-packages/")[-1].split("src/")[-1]
        rows.append({"function": f"{where}:{line}({function})", "calls": count / calls,
                     "own_us": own / calls * 1e6, "share": own / total})
    frame = pd.DataFrame(rows).sort_values("own_us", ascending=False, kind="stable")
    return frame.head(top).reset_index(drop=True)


def cheapest(frame: pd.DataFrame, target: float = TARGET) -> pd.DataFrame:
    """Per case, model and body of a work-precision table: the fastest point whose error meets ``target``."""
    ok = frame[(frame["status"] == "ok") & (frame["error"] <= target)]
    best = ok.loc[ok.groupby(["case", "model", "body"])["time"].idxmin()]
    return best[["case", "model", "body", "method", "rtol", "error", "time", "nfev"]].reset_index(drop=True)


def speedups(frame: pd.DataFrame, target: float = TARGET) -> pd.DataFrame:
    """Reduced over planar at equal accuracy, and the closed form over both (kelvin-voigt), from one
    work-precision table (so the timings share a machine state)."""
    best = cheapest(frame, target)
    rows = []
    for (case, model), group in best.groupby(["case", "model"], sort=True):
        times = dict(zip(group["body"], group["time"]))
        for _, row in group.iterrows():
            rows.append({**row.to_dict(), "target": target,
                         "speedup_over_planar": times["planar"] / row["time"] if "planar" in times else None,
                         "closed_speedup": times["reduced"] / times["closed"] if "closed" in times else None})
    return pd.DataFrame(rows)
