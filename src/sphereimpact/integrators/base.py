"""What an integrator of the normal motion is: a name, the scenes it can serve, and how it solves one."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from ..registry import Registry


def _always(scene) -> None:
    return None


@dataclass(frozen=True)
class Integrator:
    """One way of solving a scene's normal motion into a :class:`~sphereimpact.contact.motion.NormalMotion`.

    Parameters
    ----------
    name : str
        What users give as ``SolverOptions.method`` and ``--method``.
    summary : str
        One line for the documentation: the algorithm and where it applies.
    solve : callable
        ``solve(scene, options) -> NormalMotion``.
    cannot : callable
        ``cannot(scene) -> str | None``: why this integrator cannot serve ``scene`` (a phrase that follows
        "method 'NAME'"), None when it can.
    declines : callable
        ``declines(scene) -> str | None``: why ``auto`` passes it by on a scene it can serve (outside the
        domain its accuracy was measured on), None when ``auto`` takes it.
    overflows : tuple of exception types
        Failures after which ``auto`` moves on to the next integrator (the result lies beyond this one's
        arithmetic, not beyond the model).
    ivp : str or None
        The :func:`scipy.integrate.solve_ivp` method that runs this algorithm where a plain-float or
        reduced-only path cannot (the planar body, naive formulations); None: the reduced body only.
    stepper : callable or None
        For a step-by-step integrator that :class:`~sphereimpact.integrators.normal.IntegratedNormal` drives
        (events, ramp band, landing on t_f, budget): ``stepper(rhs, span, z0, rtol, atol, max_step, events,
        first_step)`` returning what :func:`scipy.integrate.solve_ivp` returns with ``dense_output=True``.
        None: the integrator solves the motion its own way (``closed``, ``taylor``).
    floats : bool
        The stepper works in plain Python floats on the law's ``scalar`` formula; for a law without one the
        driver runs the integrator named by ``ivp`` instead (the same algorithm in numpy).
    multistep : bool
        The stepper restarts at low order (BDF, LSODA): its landing on t_f is no better than its interpolant,
        so the driver takes no Newton correction there.
    drive : callable or None
        The driver's whole work done another way where it can be: ``drive(run, band)`` returning the dense output,
        the step ends, tau_m, tau_f, y at t_f and the evaluations (what the driver computes, to the bit), or None
        where the driver must run (DOP853-scalar's compiled drive, :func:`~.dop853_kernel.drive`).
    """

    name: str
    summary: str
    solve: Callable
    cannot: Callable = _always
    declines: Callable = _always
    overflows: tuple = ()
    ivp: str | None = None
    stepper: Callable | None = None
    floats: bool = False
    multistep: bool = False
    drive: Callable | None = None


#: The integrators by name, in registration order (the order of ``--method``'s help).
INTEGRATORS = Registry(Integrator, "integrator", "method")

#: What ``auto`` tries, in order: the first that can serve the scene and does not decline it (exact first,
#: then the cheapest at equal accuracy in the work-precision study).
AUTO_ORDER = ("closed", "taylor", "DOP853-scalar")
#: The last of them, which serves every law: what ``auto`` means where a method must be named (the planar body,
#: a law without a closed form or a series).
DEFAULT_INTEGRATOR = AUTO_ORDER[-1]
