"""When a process integrates compiled, and the laws' compiled kernels it integrates with, checked once.

Both compiled integrators of the normal motion (DOP853's, :mod:`.dop853_kernel`, and the Taylor method's,
:mod:`.taylor_kernel`) give their Python-float twins' answers to the bit; loading them (numba and the cached
machine code) costs about a second, so a process integrates in Python floats until it has spent about that
(:data:`COMPILE_AFTER`, the rent-or-buy rule), then compiled.  A law's kernels are compiled (or loaded from numba's
disk cache) on their first use and held to the law's own formulas there, a kernel that differs refused by name.
"""

from __future__ import annotations

import sys

import numpy as np


#: Right-hand-side evaluations a process makes in Python floats, on laws with a kernel, before it loads the compiled
#: integrator: about what loading it costs (numba's start and the cached machine code, ``results/bench.csv``), so a
#: process that integrates little (one command's impact) never pays for it and one that integrates much pays at
#: most twice the least it could have (the rent-or-buy rule).  The answer is the same bit for bit either way.
COMPILE_AFTER = 150_000
_spent_in_floats = 0


def load_compiled() -> None:
    """Load the compiled integrators now (numba and their machine code: DOP853's and the Taylor method's): the
    process integrates compiled from its next motion on, as it would once it had spent :data:`COMPILE_AFTER`
    evaluations (a benchmark times that steady state)."""
    import importlib

    importlib.import_module(_KERNEL_MODULE)
    importlib.import_module(_TAYLOR_MODULE)


#: The package's kernels in groups, each compiled in one process of :func:`compile_all` when they compile at once on a
#: fresh machine: DOP853's loop and the laws' forces it calls; the Taylor method's loop, the laws' series and the
#: microslip march; the contact layer's kernels on a solved normal motion (the force's extremes and sign changes,
#: the compliant tangential contact's stick phase, the rigid contact's grip).  Their compile time: ``results/bench.csv``.
GROUPS = ("dop853", "taylor", "contact")


def compile_all(group: str | None = None) -> None:
    """Compile every kernel of the package (or load it from numba's disk cache), or those of one of :data:`GROUPS`:
    both integrators' loops, every built-in law's force and series kernels, the microslip march's, the force extremes',
    the stick phase's and the grip's (what a fresh machine compiles once; a process otherwise compiles each on its first use)."""
    import importlib

    from ..contact.laws import LAWS

    if group not in (None, *GROUPS):
        raise ValueError(f"group must be one of {', '.join(GROUPS)}, or None for every kernel; got {group!r}")
    if group in (None, "dop853"):
        importlib.import_module(_KERNEL_MODULE)
        for law in LAWS.values():
            if law.kernel is not None:
                law.kernel.load()
    if group in (None, "taylor"):
        importlib.import_module(_TAYLOR_MODULE)
        for law in LAWS.values():
            if law.series_kernel is not None:
                law.series_kernel.load(series=True)
    if group in (None, "contact"):  # the microslip march's too: it reads the normal motion by normal_kernel's code,
        importlib.import_module("sphereimpact.contact.normal_kernel")  # so one process compiles both
        importlib.import_module("sphereimpact.contact.tangential.stick_kernel")
        importlib.import_module("sphereimpact.contact.tangential.rigid_kernel")
        importlib.import_module("sphereimpact.contact.tangential.microslip_march").compile_all()


def compiled_now() -> bool:
    """Whether this process integrates a law with kernels compiled: once it has spent :data:`COMPILE_AFTER`
    evaluations in Python floats on such laws (DOP853's and the Taylor method's alike), or loaded the compiled
    integrator."""
    return _spent_in_floats >= COMPILE_AFTER or _KERNEL_MODULE in sys.modules


def expect_evaluations(evaluations: int) -> None:
    """Buy now where the demand is known: a caller about to make about ``evaluations`` right-hand-side evaluations on
    laws with kernels (a sweep's single impacts) loads the compiled integrators at once when they reach
    :data:`COMPILE_AFTER`, instead of renting Python floats until it has spent that much.  The answers are the same
    to the bit either way."""
    if evaluations >= COMPILE_AFTER and not compiled_now():
        load_compiled()


def spend_in_floats(evaluations: int) -> None:
    """Count ``evaluations`` made in Python floats on a law that has kernels (see :func:`compiled_now`)."""
    global _spent_in_floats
    _spent_in_floats += evaluations


_KERNEL_MODULE = "sphereimpact.integrators.dop853_kernel"
_TAYLOR_MODULE = "sphereimpact.integrators.taylor_kernel"
#: The laws whose kernels this process has compiled and checked against their scalar formulas.
_CHECKED: dict = {}
#: Relative difference from the scalar formula a kernel may show at the check's states (the built-in kernels show
#: none: tests/test_kernels.py).
KERNEL_AGREEMENT = 1e-12


def checked_kernel(scene, scales):
    """The compiled kernel of ``scene``'s law, checked on its first use in the process against the law's scalar
    formula at states across the scene's contact (compression and rate of either sign, scaled by ``scales``): a
    kernel that numba cannot compile, or that is not the scalar formula, is refused by name (ValueError), never
    integrated in its place."""
    law = scene.law
    key = (law.name, law.kernel)
    if key not in _CHECKED:
        try:
            compiled = law.kernel.load()
        except Exception as err:  # numba's typing and lowering errors, an unknown module or name
            lines = [line.strip() for line in str(err).splitlines() if line.strip()]
            reason = lines[1] if len(lines) > 1 and lines[0].startswith("Failed in") else "".join(lines[:1])
            raise ValueError(f"law {law.name!r}: its kernel does not compile ({type(err).__name__}: {reason}); fix "
                             "it, or declare no kernel (the law then integrates in Python floats)") from None
        params = np.array(law.kernel.parameters(scene), dtype=float)
        d_scale, v = scales[0], scales[1]
        for x, y in ((0.5, 1.0), (1.0, 0.3), (0.2, -0.8), (-0.01, -1.0), (0.0, 0.5)):
            mine, theirs = compiled(x * d_scale, y * v, params), law.scalar(x * d_scale, y * v, scene)
            if not abs(mine - theirs) <= KERNEL_AGREEMENT * max(abs(theirs), 1e-300):
                raise ValueError(f"law {law.name!r}: its kernel gives P = {mine!r} N where its scalar formula gives "
                                 f"{theirs!r} N (delta {x * d_scale:.3g} m, delta_dot {y * v:.3g} m/s): a kernel must "
                                 "be the scalar formula compiled")
        from ..contact.laws.kernels import SIGNATURE  # numba: imported with the compiled path

        _CHECKED[key] = _Address(compiled, SIGNATURE)
    return _CHECKED[key]


def checked_series_kernel(scene):
    """The compiled series kernel of ``scene``'s law (``ContactLaw.series_kernel``), checked on its first use in the
    process against the law's ``series`` at two states, to the bit: one that does not compile, or is not that
    recurrence, is refused by name (ValueError)."""
    law = scene.law
    key = ("series", law.name, law.series_kernel)
    if key not in _CHECKED:
        try:
            compiled = law.series_kernel.load(series=True)
        except Exception as err:  # numba's typing and lowering errors, an unknown module or name
            raise ValueError(f"law {law.name!r}: its series kernel does not compile ({type(err).__name__}); fix it, "
                             "or declare none (the Taylor method then runs its series in Python floats)") from None
        numbers = {name: float(value) for name, value in scene.family.items()}
        packed = np.array(law.series_kernel.parameters(scene), dtype=float)
        for x, y, gamma in ((0.3, 0.7, 0.0), (0.8, -0.4, 0.01)):
            xs, ys = np.empty(11), np.empty(11)
            compiled(x, y, packed, gamma, 10, xs, ys)
            if (xs.tolist(), ys.tolist()) != tuple(map(list, law.series(x, y, numbers, gamma, 10))):
                raise ValueError(f"law {law.name!r}: its series kernel's coefficients differ from its series at "
                                 f"x {x}, y {y}: a series kernel must be the series compiled")
        from ..contact.laws.kernels import SERIES_SIGNATURE  # numba: imported with the compiled path

        _CHECKED[key] = _Address(compiled, SERIES_SIGNATURE)
    return _CHECKED[key]


class _Address:
    """A compiled kernel as the compiled integrators take it: numba's first-class function, its type
    (``_numba_type_``, numba's typing hook) and address (``__wrapper_address__``) held once.  Passed as the
    dispatcher (or numba's ``CompileResultWAP``), each call of an integrator looked the address up in numba's code
    library, or built the function's type, again."""

    def __init__(self, kernel, signature):
        from numba.core import types

        compiled = kernel.get_compile_result(signature)  # compiled for it, its return cast if need be
        self._numba_type_ = types.FunctionType(compiled.signature)
        self._address = compiled.library.get_pointer_to_function(compiled.fndesc.llvm_cfunc_wrapper_name)
        self._call = compiled.entry_point

    def __wrapper_address__(self) -> int:
        return self._address

    def __call__(self, *args):
        return self._call(*args)
