"""How large a sweep this machine can hold, decided before any work (CLI and config alike)."""

from __future__ import annotations

import math
import os

#: Memory a sweep holds per scene [bytes], whichever path solves it: its input and output tables and the paths'
#: working arrays.  Every path holds its working memory per chunk, never per row (the single path, gravity on a
#: slope and compliant contacts, keeps one chunk's solved motions at a time).  Marginal peaks measured with
#: tracemalloc between 2,000 and 8,000 scenes: lambda-interpolant 0.80 kB, plane (many balls) 1.82 kB,
#: family-interpolant 0.66 kB, similar 0.71 kB, single 0.63 kB (3,000 to 10,000 scenes); sized by the largest, so
#: the check holds for the path that will run.
BYTES_PER_SCENE = 2000


def available_memory() -> int | None:
    """Memory available to a new allocation [bytes] (Linux MemAvailable), or None where it cannot be read."""
    try:
        with open("/proc/meminfo") as handle:
            for line in handle:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def check_size(counts: dict, hint: str) -> int:
    """The number of scenes of a grid with ``counts`` values per parameter.

    Raises
    ------
    ValueError
        When the sweep would need more than 80 % of the available memory: the numbers (scenes, bytes,
        memory available) and ``hint``.
    """
    scenes = math.prod(counts.values())
    need = scenes * BYTES_PER_SCENE
    have = available_memory()
    if have is not None and need > 0.8 * have:
        sizes = " x ".join(f"{n} {name}" for name, n in counts.items() if n > 1)
        raise ValueError(f"sweep too large: {scenes:.3g} scenes ({sizes}) need about {need / 2**30:.3g} GiB, "
                         f"{have / 2**30:.3g} GiB are available; {hint}")
    return scenes
