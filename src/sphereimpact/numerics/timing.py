"""Wall time of one call, as the median of repeats (for benchmarks only, never for pass/fail)."""

from __future__ import annotations

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
