"""``DOP853-scalar`` and scipy's :func:`~scipy.integrate.solve_ivp` methods: steppers that one driver runs
(:class:`sphereimpact.integrators.normal.IntegratedNormal`: events, the ramp band, landing on t_f, the budget).

``DOP853-scalar`` is DOP853's algorithm in plain floats on a law with a scalar formula, scipy's DOP853 on any
other: compiled (:mod:`.dop853_kernel`) for a law with a kernel once the process has integrated enough to repay
loading it (:data:`COMPILE_AFTER`), else in Python (:mod:`sphereimpact.ode.dop853`), the same answer to the bit.
"""

from __future__ import annotations

import sys

import numpy as np

from ..ode import dop853
from .normal import IntegratedNormal
from .base import INTEGRATORS, Integrator
from .event_kinds import EventKind


#: Right-hand-side evaluations a process makes in Python floats, on laws with a kernel, before it loads the compiled
#: integrator: about what loading it costs (numba's start and the cached machine code, ``results/bench.csv``), so a
#: process that integrates little (one command's impact) never pays for it and one that integrates much pays at
#: most twice the least it could have (the rent-or-buy rule).  The answer is the same bit for bit either way.
COMPILE_AFTER = 150_000
_spent_in_floats = 0


def load_compiled() -> None:
    """Load the compiled integrator now (numba and its machine code): the process integrates compiled from its next
    motion on, as it would once it had spent :data:`COMPILE_AFTER` evaluations (a benchmark times that steady
    state)."""
    import importlib

    importlib.import_module(_KERNEL_MODULE)


def _plain_floats(rhs, span, z0, rtol, atol, max_step, events, first_step):
    """DOP853 in plain floats: compiled (:func:`_compiled`) where the law has a kernel, once the process has spent
    :data:`COMPILE_AFTER` evaluations in Python floats or loaded the compiled integrator; else in Python."""
    global _spent_in_floats
    law = rhs.scene.law
    if law.kernel is not None and (_spent_in_floats >= COMPILE_AFTER or _KERNEL_MODULE in sys.modules):
        return _compiled(rhs, span, z0, rtol, atol, max_step, events, first_step)
    sol = dop853.solve(rhs, span, z0, rtol, atol, max_step=max_step, events=events, first_step=first_step)
    if law.kernel is not None:
        _spent_in_floats += sol.nfev
    return sol


_KERNEL_MODULE = "sphereimpact.integrators.dop853_kernel"
#: The laws whose kernels this process has compiled and checked against their scalar formulas.
_CHECKED: dict = {}
#: Relative difference from the scalar formula a kernel may show at the check's states (the built-in kernels show
#: none: tests/test_kernels.py).
KERNEL_AGREEMENT = 1e-12


def _checked_kernel(scene, scales):
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
        _CHECKED[key] = _by_address(compiled)
    return _CHECKED[key]


def _by_address(kernel):
    """``kernel`` (a numba dispatcher compiled for :data:`~sphereimpact.contact.laws.kernels.SIGNATURE`) as its
    compiled function's address, which numba reads off the object at each call: passed as the dispatcher, each
    call of the integrator looked the address up in numba's code library again."""
    from numba.core.types import CompileResultWAP

    from ..contact.laws.kernels import SIGNATURE

    return CompileResultWAP(kernel.get_compile_result(SIGNATURE))  # compiled for it, its return cast if need be


def _compiled(rhs, span, z0, rtol, atol, max_step, events, first_step):
    """The normal motion by the compiled DOP853 (:func:`~.dop853_kernel.integrate`) on the law's kernel: the
    steps, states and events of :func:`sphereimpact.ode.dop853.solve` on ``rhs`` to the bit (tests/test_kernels.py),
    which ``rhs`` is not called for; its budget is charged with the evaluations made.  The driver's events say
    which they are (``event.kind``); the compiled loop locates their roots too, by the same search."""
    from . import dop853_kernel as kernel  # _KERNEL_MODULE

    scene = rhs.scene
    law_kernel = scene.law.kernel
    band = [e for e in events if e.kind is EventKind.BAND]
    lam, edge = (band[0].lam, band[0].edge) if band else (0.0, 0.0)
    ts, ys, coefficients, g, nfev, status, roots, where = kernel.integrate(
        _checked_kernel(scene, rhs.scales), np.array(law_kernel.parameters(scene), dtype=float),
        np.array(rhs.scales, dtype=float),
        float(span[0]), float(span[1]), np.array(z0, dtype=float), float(rtol), float(atol), float(max_step),
        float(first_step) if first_step is not None else 0.0,
        np.array([e.kind for e in events], dtype=np.int64),
        np.array([getattr(e, "direction", 0) for e in events], dtype=np.int64), float(lam), float(edge),
        max(rhs.left, 0))
    rhs.spend(nfev if status != kernel.BUDGET else rhs.left + 1)
    if status == kernel.OVERFLOW:
        raise OverflowError("the contact force left the finite numbers")
    messages = {kernel.TERMINAL: "A termination event occurred.",
                kernel.FINISHED: "The solver successfully reached the end of the integration interval.",
                kernel.STEP_TOO_SMALL: "Required step size is less than spacing between numbers."}
    return dop853.located(events, ts, ys, coefficients, g, int(nfev), int(status), messages[status],
                          dict(zip(map(tuple, where.tolist()), roots.tolist())))


def _scipy(method: str):
    """The stepper of solve_ivp's ``method``, with its dense output."""

    def stepper(rhs, span, z0, rtol, atol, max_step, events, first_step):
        from scipy.integrate import solve_ivp  # imported on use: a third of a second a command need not pay

        return solve_ivp(rhs, span, z0, method=method, rtol=rtol, atol=atol, dense_output=True, max_step=max_step,
                         events=events, first_step=first_step)

    return stepper


SCALAR = INTEGRATORS.register(Integrator(
    "DOP853-scalar", "scipy's DOP853 in plain floats (its steps, without numpy's per-call cost; compiled for a law "
    "with a kernel once a process has integrated enough to repay loading it)",
    IntegratedNormal, ivp="DOP853", stepper=_plain_floats, floats=True))

SCIPY = tuple(INTEGRATORS.register(Integrator(
    name, f"scipy's solve_ivp method {name}", IntegratedNormal, ivp=name, stepper=_scipy(name),
    multistep=name in ("BDF", "LSODA"))) for name in ("RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA"))
