"""A sweep's one-at-a-time scenes in several processes: the single-impact path's chunks shared among forked workers.

The single-impact path (``simulate`` per scene: a compliant contact at an angle, gravity on a slope) is sequential
work per scene, independent from scene to scene, so a machine's cores divide it.  Each chunk is solved whole by one
process, exactly as in one process (its normal problems shared within it, its rows in its order), so the table is the
same to the bit whichever process solved a chunk and however many ran.  The workers are forks of the sweeping process:
the scenes, the options and the compiled kernels it loaded are theirs without copying or compiling again; only a
chunk's index and its outputs cross between processes.  Where a process cannot fork (Windows, macOS's default, a
daemonic worker of the user's own pool), the chunks run in this process.
"""

from __future__ import annotations

import multiprocessing
import os
import warnings
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Callable, Iterator

#: Fewest chunks worth sharing among processes: below it the forks' start (about 10 ms each) and the first chunk,
#: solved here to load the kernels, are a large part of the work.
PARALLEL_MIN_CHUNKS = 4

#: The environment variable that sets ``jobs``' default, as OMP_NUM_THREADS sets OpenMP's: the pipeline sets it to 1
#: (workflow/rules/common.smk), so that its scheduler, which runs jobs side by side, owns the cores.
JOBS_VARIABLE = "SPHEREIMPACT_JOBS"

#: What a running share reads, set before the workers fork: (solve, chunks).
_SHARED: tuple | None = None


def available_cpus() -> int:
    """The CPUs this process may run on (its affinity where the system tells it, else the machine's count)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def default_jobs() -> int:
    """The processes a sweep's single impacts share when the call does not say: :data:`JOBS_VARIABLE` where it is
    set (an integer >= 1, ValueError naming it otherwise), else :func:`available_cpus`."""
    text = os.environ.get(JOBS_VARIABLE, "").strip()
    if not text:
        return available_cpus()
    if not text.isdigit() or int(text) < 1:
        raise ValueError(f"{JOBS_VARIABLE} must be an integer >= 1 (processes sharing a sweep's one-at-a-time "
                         f"scenes), or unset for every CPU this process may use; got {text!r}")
    return int(text)


def checked_jobs(jobs) -> int:
    """``jobs`` as the most processes a sweep's single impacts may share: None is :func:`default_jobs`; else an
    integer >= 1 (ValueError naming it otherwise)."""
    if jobs is None:
        return default_jobs()
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be an integer >= 1 (processes sharing the one-at-a-time scenes), or None for "
                         f"${JOBS_VARIABLE} or every CPU this process may use ({available_cpus()}); got {jobs!r}")
    return jobs


def can_fork() -> bool:
    """Whether this process can fork workers that share its memory: the fork start method exists (Linux) and this
    process is not itself a daemonic worker (which may have no children)."""
    return "fork" in multiprocessing.get_all_start_methods() and not multiprocessing.current_process().daemon


def workers_for(chunks: int, jobs: int) -> int:
    """Processes to share ``chunks`` chunks among, at most ``jobs``: 1 (this process alone) for fewer than
    :data:`PARALLEL_MIN_CHUNKS` chunks or where it cannot fork."""
    return 1 if jobs < 2 or chunks < PARALLEL_MIN_CHUNKS or not can_fork() else min(jobs, chunks - 1)


def solved_chunks(solve: Callable[[object], dict], chunks: list, jobs: int) -> Iterator[dict]:
    """``solve(chunk)`` for each of ``chunks``, yielded in their order, shared among up to ``jobs`` processes
    (:func:`workers_for`).

    The first chunk is solved in this process before any fork, so that the kernels it loads are the workers' too.
    A worker's warnings are raised again here, in order; its exception (a scene that fails, named by ``solve``)
    is raised here when its chunk's turn comes, the chunks not started cancelled.

    Raises
    ------
    RuntimeError
        When a worker process dies (killed, out of memory), naming ``jobs``.
    """
    workers = workers_for(len(chunks), jobs)
    if workers == 1:
        yield from map(solve, chunks)
        return
    yield solve(chunks[0])
    global _SHARED
    _SHARED = (solve, chunks)
    pool = ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("fork"))
    try:
        for columns, caught in pool.map(_solve_shared, range(1, len(chunks))):
            for message, category in caught:
                warnings.warn(message, category, stacklevel=2)
            yield columns
    except BrokenProcessPool:
        raise RuntimeError(f"a worker process of the sweep died (jobs {jobs}): too little memory for {workers} "
                           "processes? run it with jobs=1 (--jobs 1)") from None
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
        _SHARED = None


def _solve_shared(index: int) -> tuple[dict, list]:
    """In a worker: the chunk ``index`` of the share, and the warnings it raised as (message, category)."""
    solve, chunks = _SHARED
    with warnings.catch_warnings(record=True) as caught:
        columns = solve(chunks[index])
    return columns, [(str(w.message), w.category) for w in caught]
