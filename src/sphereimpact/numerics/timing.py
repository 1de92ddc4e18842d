"""Wall time of one call, as the median of repeats (for benchmarks only, never for pass/fail)."""

from __future__ import annotations

import gc
import math
import statistics
import time


def steady_state() -> None:
    """Load the compiled integrator before timing (:func:`sphereimpact.integrators.compiled.load_compiled`): a
    process integrates in Python floats until it has integrated enough to repay loading the compiled loop, so
    without this a benchmark's first points would time the one and its later points the other (the same answers).
    Every speed benchmark times the steady state of a process that integrates much."""
    from ..integrators.compiled import load_compiled

    load_compiled()


#: Seconds a work-precision or stability point is repeated for (at least 3 runs unless one run exceeds it).  Every
#: run of every point of the work-precision table recorded at 0.05 s: taken at 0.02 s, the points' medians move by 0
#: (median) and 9.5 % (90th percentile), on a chart of decades, and the table costs 48 s instead of 69 s.
BUDGET = 0.02


def median_time(call, budget: float = BUDGET, max_repeats: int = 7) -> tuple[float, object]:
    """Run ``call()`` at least 3 times (once if a single run exceeds ``budget`` s), until ``budget`` is spent
    or ``max_repeats`` is reached; return (median seconds, last result)."""
    times, result = [], None
    while True:
        start = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - start)
        spent = sum(times)
        if times[0] > budget or len(times) >= max_repeats or (len(times) >= 3 and spent > budget):
            return statistics.median(times), result


def _timed(call) -> float:
    """Wall time [s] of one call with the cyclic garbage collector off, as :mod:`timeit` does: its passes
    would land at random in one contender or another.  No collection before the call: in a process holding
    pandas and scipy one costs more than the impact it would precede."""
    gc.disable()
    try:
        start = time.perf_counter()
        call()
        return time.perf_counter() - start
    finally:
        gc.enable()


def median_seconds(call, repeats: int) -> float:
    """Median wall time [s] of ``repeats`` complete calls: the one protocol of every contender of the
    speed benchmarks (``numerics.bench``, ``numerics.bench_sweep``), garbage collector off (:func:`_timed`)."""
    return statistics.median(_timed(call) for _ in range(repeats))


#: Seconds of one round of contenders past which it is not repeated (:func:`interleaved_runs`).  Four complete fits in
#: a row (bench_sweep's fit rows, 3.9 s and 5 to 5.9 s) spread by 9 % and 20 %, no less than one round from the
#: next: a median of three rounds that long narrows nothing a reader uses, and cost the timed job 20 s.  The sweeps
#: guide's large sweep, whose all-over-fast ratio is a target, runs its three rounds whatever they take
#: (:func:`~.bench_sweep.sweeps`).
ROUND_BUDGET = 3.0


def interleaved_runs(calls: dict, repeats: int, budget: float = ROUND_BUDGET) -> tuple[dict, int]:
    """(name -> median wall time [s], rounds run) of ``calls`` (name -> callable), the contenders timed in turn
    within each round (protocol of :func:`median_seconds` otherwise): a slow spell of a shared machine then
    falls on all of them alike.  Timed one after the other, simulate and the script it is compared with once
    came out 0.94 and 1.48 of each other in two runs a minute apart.

    ``repeats`` rounds, or fewer once the rounds so far took more than ``budget`` seconds each on average: a round
    that long is thousands of impacts (a 10^6-scene sweep, a fit) whose time a second and third round reproduce
    within the machine's spread, so they bought nothing but minutes of the pipeline (the rows report the rounds
    they ran)."""
    times = {name: [] for name in calls}
    for done in range(1, repeats + 1):
        for name, call in calls.items():
            times[name].append(_timed(call))
        if sum(sum(values) for values in times.values()) > budget * done:
            break
    return {name: statistics.median(values) for name, values in times.items()}, done


def interleaved_seconds(calls: dict, repeats: int) -> dict:
    """Median wall time [s] of each of ``calls`` over ``repeats`` rounds, whatever their length
    (:func:`interleaved_runs` without its budget)."""
    return interleaved_runs(calls, repeats, budget=math.inf)[0]


#: Fewest calls per timed run: one impact takes milliseconds, so each run times a batch.
BATCH = 10
#: Least wall time [s] of a contender's timed run: a contender that takes less than this for :data:`BATCH` calls is
#: run in batches this long (:func:`batch_size`).  The contenders are timed in turn, so each run starts right after the
#: other's, its caches holding the other's code and data: its first calls cost several times the later ones, which a
#: run of a few quick calls would report as their cost (the measurements: the commit that set this).  Each row reports
#: its contender's batch.
MIN_RUN = 0.01
#: Most calls per timed run (a contender of a few microseconds).
MAX_BATCH = 1000


def batch_size(call) -> int:
    """Calls per timed run of ``call``: :data:`BATCH`, or as many as last :data:`MIN_RUN` s (at most
    :data:`MAX_BATCH`), judged from :data:`BATCH` untimed calls (which also warm it)."""
    start = time.perf_counter()
    for _ in range(BATCH):
        call()
    each = (time.perf_counter() - start) / BATCH
    return BATCH if each * BATCH >= MIN_RUN else min(MAX_BATCH, math.ceil(MIN_RUN / max(each, 1e-9)))


def per_call_seconds(calls: dict, repeats: int) -> tuple[dict, dict]:
    """(name -> median over ``repeats`` runs of the time of one run, divided by its calls [s per call], name -> calls
    per run, :func:`batch_size`), the contenders ``calls`` (name -> callable) timed in turn within each run
    (:func:`interleaved_seconds`; garbage collector off while timed)."""
    sizes = {name: batch_size(call) for name, call in calls.items()}
    batches = {name: (lambda call=call, n=sizes[name]: [call() for _ in range(n)]) for name, call in calls.items()}
    return {name: seconds / sizes[name] for name, seconds in interleaved_seconds(batches, repeats).items()}, sizes
