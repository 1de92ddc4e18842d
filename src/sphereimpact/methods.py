"""The integration methods of the normal motion, by name, and which scipy method runs each where the
plain-float integrator cannot."""

from __future__ import annotations

#: Integration methods: ``auto`` (the default) is the law's closed form where it has one, else ``taylor``
#: where the law has a series and the damping ratio is within the accuracy contract's (<= 100), else
#: ``DOP853-scalar``; ``closed`` is the exact linear solution (kelvin-voigt only); ``taylor`` is the
#: Taylor-series method (:mod:`sphereimpact.taylor`, laws with a ``series``); ``DOP853-scalar`` is scipy's
#: DOP853 run in plain floats (:mod:`sphereimpact.dop853`: the same steps, 2-3x cheaper) on a law with a
#: scalar formula; the others are :func:`scipy.integrate.solve_ivp` methods.
METHODS = ("auto", "closed", "taylor", "DOP853-scalar", "RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA")
#: What ``auto`` integrates with when the law has neither a closed form nor a series (chosen from the
#: work-precision study).
DEFAULT_INTEGRATOR = "DOP853-scalar"


def ivp_method(method: str) -> str:
    """The :func:`scipy.integrate.solve_ivp` method that runs ``method`` where the float integrator cannot
    (the planar body, a law without a scalar formula, naive formulations): ``auto`` and ``DOP853-scalar``
    are DOP853's algorithm."""
    return "DOP853" if method in ("auto", DEFAULT_INTEGRATOR) else method
