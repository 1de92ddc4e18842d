"""Wall time of one call, as the median of repeats (for benchmarks only, never for pass/fail)."""

from __future__ import annotations

import gc
import statistics
import time


def median_time(call, budget: float = 0.3, max_repeats: int = 7) -> tuple[float, object]:
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


def median_seconds(call, repeats: int) -> float:
    """Median wall time [s] of ``repeats`` complete calls: the one protocol of every contender of the
    speed benchmarks (``numerics.bench``, ``sweep.bench``).

    The cyclic garbage collector is off while a call is timed, as :mod:`timeit` does: its passes land at
    random in one contender or another and moved per-scene timings by up to 1.8x between runs.
    """
    times = []
    for _ in range(repeats):
        gc.collect()
        gc.disable()
        try:
            start = time.perf_counter()
            call()
            times.append(time.perf_counter() - start)
        finally:
            gc.enable()
    return statistics.median(times)
