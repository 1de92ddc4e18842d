"""The integration methods' names that other layers need without importing the integrators (which import
the scene): the default integrator and the solve_ivp method that runs a named one.  The integrators
themselves are :data:`sphereimpact.integrators.INTEGRATORS`."""

from __future__ import annotations

#: What ``auto`` integrates with when the law has neither a closed form nor a series (chosen from the
#: work-precision study).
DEFAULT_INTEGRATOR = "DOP853-scalar"


def ivp_method(method: str) -> str:
    """The :func:`scipy.integrate.solve_ivp` method that runs ``method`` where the float integrator cannot
    (the planar body, a law without a scalar formula, naive formulations): ``auto`` is
    :data:`DEFAULT_INTEGRATOR`'s.  ``ValueError`` for a method that runs on the reduced body only."""
    from .integrators import INTEGRATORS

    integrator = INTEGRATORS.named(DEFAULT_INTEGRATOR if method == "auto" else method)
    if integrator.ivp is None:
        raise ValueError(f"method {method!r} is only available for the reduced model")
    return integrator.ivp


def __getattr__(name):
    if name == "METHODS":  # every name SolverOptions.method accepts, registered integrators included
        from .integrators import method_names

        return method_names()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
