"""``DOP853-scalar`` and scipy's :func:`~scipy.integrate.solve_ivp` methods: steppers that one driver runs
(:class:`sphereimpact.integrators.normal.IntegratedNormal`: events, the ramp band, landing on t_f, the budget).

``DOP853-scalar`` is DOP853's algorithm in plain floats on a law with a scalar formula, scipy's DOP853 on any
other: compiled (:mod:`.dop853_kernel`) for a law with a kernel once the process has integrated enough to repay
loading it (:mod:`.compiled`), else in Python (:mod:`sphereimpact.ode.dop853`), the same answer to the bit.  Compiled,
the driver's whole work is one call (:func:`_compiled_drive`).
"""

from __future__ import annotations

import numpy as np

from ..ode import dop853
from ..ode.dense import StackedDOP853
from . import normal as driver
from .normal import IntegratedNormal
from .base import INTEGRATORS, Integrator
from .compiled import checked_kernel, compiled_now, spend_in_floats
from .event_kinds import EventKind


def _plain_floats(rhs, span, z0, rtol, atol, max_step, events, first_step):
    """DOP853 in plain floats: compiled (:func:`_compiled`) where the law has a kernel, once the process integrates
    compiled (:func:`.compiled.compiled_now`); else in Python."""
    law = rhs.scene.law
    if _integrates_compiled(law):
        return _compiled(rhs, span, z0, rtol, atol, max_step, events, first_step)
    sol = dop853.solve(rhs, span, z0, rtol, atol, max_step=max_step, events=events, first_step=first_step)
    if law.kernel is not None:
        spend_in_floats(sol.nfev)
    return sol


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
        checked_kernel(scene, rhs.scales), np.array(law_kernel.parameters(scene), dtype=float),
        np.array(rhs.scales, dtype=float),
        float(span[0]), float(span[1]), np.array(z0, dtype=float), float(rtol), float(atol), float(max_step),
        float(first_step) if first_step is not None else 0.0,
        np.array([e.kind for e in events], dtype=np.int64),
        np.array([getattr(e, "direction", 0) for e in events], dtype=np.int64), float(lam), float(edge),
        max(rhs.left, 0))
    rhs.spend(nfev if status != kernel.BUDGET else rhs.left + 1)
    if status == kernel.OVERFLOW:
        raise OverflowError("the contact force left the finite numbers")
    return dop853.located(events, ts, ys, coefficients, g, int(nfev), int(status), dop853.MESSAGES[int(status)],
                          dict(zip(map(tuple, where.tolist()), roots.tolist())))


def _drive(run, band):
    """The whole normal motion by the compiled drive (:func:`_compiled_drive`) where the law has a kernel and the
    process integrates compiled; else None (the driver runs it, on :func:`_plain_floats`)."""
    return _compiled_drive(run, band) if _integrates_compiled(run.scene.law) else None


def _integrates_compiled(law) -> bool:
    """Whether this process integrates ``law`` compiled: it has a kernel, and the process has loaded the compiled
    loop (:func:`.compiled.compiled_now`).  The one rule of both the runs and the drive."""
    return law.kernel is not None and compiled_now()


def _compiled_drive(run, band):
    """:class:`~.normal.IntegratedNormal`'s work in one compiled call (:func:`~.dop853_kernel.drive`): its runs of
    :func:`_compiled`, the ramp band and the landing, the same arithmetic, so the same dense output, steps, times
    and evaluations to the bit (tests/test_kernels.py); None where the drive stops short (a failure, a missed event,
    the budget), and the driver then runs the motion and says why."""
    from . import dop853_kernel as kernel  # _KERNEL_MODULE

    scene = run.scene
    ts, f, y_old, t_old, h, steps, tau_m, tau_f, rate_f, nfev, status = kernel.drive(
        checked_kernel(scene, run.rhs.scales), np.array(scene.law.kernel.parameters(scene), dtype=float),
        np.array(run.rhs.scales, dtype=float), float(run.end), float(run.rtol), float(run.atol), float(run.max_step),
        int(run.separation.kind), float(band.lam) if band is not None else 0.0,
        np.array([driver.BAND_RESTART, driver.BAND_STEP, driver.BAND_SPEED, driver.LANDING_DELTA], dtype=float),
        driver.LANDINGS, driver.MAX_NFEV)  # read at each call: the driver's policy, whatever it is then
    if status != kernel.DRIVEN:
        return None
    return StackedDOP853(ts, f, y_old, t_old, h), steps, float(tau_m), float(tau_f), float(rate_f), int(nfev)


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
    IntegratedNormal, ivp="DOP853", stepper=_plain_floats, floats=True,
    drive=_drive))

SCIPY = tuple(INTEGRATORS.register(Integrator(
    name, f"scipy's solve_ivp method {name}", IntegratedNormal, ivp=name, stepper=_scipy(name),
    multistep=name in ("BDF", "LSODA"))) for name in ("RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA"))
