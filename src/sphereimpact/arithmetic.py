"""One arithmetic for numpy and OpenBLAS on every x86-64 processor with AVX2 and FMA, so that the pipeline's tables and
figures, and the tests that compare them with a computation of their own, are the same bytes on any such machine.

Where a processor has AVX-512, numpy evaluates exp, expm1, log and power on arrays with its own AVX-512 routines,
which differ from the C library's in the last bit for a few percent of arguments, and OpenBLAS takes its SkylakeX
kernels, which sum in another order; both move results at the round-off level, and what follows from them (an
adaptive step count, the larger of two differences near 1e-10, a figure's pixels) differs from an AVX2 machine's.
Pinned to AVX2 (:data:`SAME_ARITHMETIC`), numpy's elementary functions are the C library's (as the compiled kernels'
are) and OpenBLAS's kernels are one set.  Both variables are read when numpy is imported, so they are set in the
environment of a process before it imports numpy: this module imports only the standard library.
"""

from __future__ import annotations

import os
from collections.abc import MutableMapping
from pathlib import Path

#: numpy's dispatch without its AVX-512 targets (numpy 2.4's names; a name this numpy or processor lacks is
#: ignored), and OpenBLAS's Haswell kernels (AVX2 and FMA).
SAME_ARITHMETIC = {"NPY_DISABLE_CPU_FEATURES": "X86_V4 AVX512_ICL AVX512_SPR", "OPENBLAS_CORETYPE": "Haswell"}


def cpu_flags(cpuinfo: str = "/proc/cpuinfo") -> frozenset[str]:
    """The processor's feature flags as Linux lists them (empty where there is no such file)."""
    try:
        text = Path(cpuinfo).read_text()
    except OSError:
        return frozenset()
    line = next((line for line in text.splitlines() if line.startswith("flags")), "")
    return frozenset(line.partition(":")[2].split())


def same_arithmetic(flags: frozenset[str] | None = None) -> dict[str, str]:
    """The environment variables that pin numpy and OpenBLAS to AVX2 on this processor (``flags``: its features, read
    from /proc/cpuinfo by default): :data:`SAME_ARITHMETIC` where it has AVX2 and FMA; empty otherwise (OpenBLAS
    cannot run Haswell kernels there) and on other architectures, whose last bits are their own."""
    flags = cpu_flags() if flags is None else flags
    return dict(SAME_ARITHMETIC) if {"avx2", "fma"} <= flags else {}


def pin_arithmetic(environ: MutableMapping[str, str] = os.environ) -> dict[str, str]:
    """Set :func:`same_arithmetic`'s variables in ``environ`` where it does not set them already (a value the user
    chose is kept), for the processes started from it; returns the variables now in effect there."""
    for name, value in same_arithmetic().items():
        environ.setdefault(name, value)
    return {name: environ[name] for name in SAME_ARITHMETIC if name in environ}
