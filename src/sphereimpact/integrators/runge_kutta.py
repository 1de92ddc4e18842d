"""``DOP853-scalar`` and scipy's :func:`~scipy.integrate.solve_ivp` methods: steppers that one driver runs
(:class:`sphereimpact.integrators.normal.IntegratedNormal`: events, the ramp band, landing on t_f, the budget).

``DOP853-scalar`` is DOP853's algorithm in plain floats (:mod:`sphereimpact.ode.dop853`) on a law with a scalar
formula, scipy's DOP853 on any other.
"""

from __future__ import annotations

from ..ode import dop853
from .normal import IntegratedNormal
from .base import INTEGRATORS, Integrator


def _plain_floats(rhs, span, z0, rtol, atol, max_step, events, first_step):
    return dop853.solve(rhs, span, z0, rtol, atol, max_step=max_step, events=events, first_step=first_step)


def _scipy(method: str):
    """The stepper of solve_ivp's ``method``, with its dense output."""

    def stepper(rhs, span, z0, rtol, atol, max_step, events, first_step):
        from scipy.integrate import solve_ivp  # imported on use (see ode.dop853._load_tableau)

        return solve_ivp(rhs, span, z0, method=method, rtol=rtol, atol=atol, dense_output=True, max_step=max_step,
                         events=events, first_step=first_step)

    return stepper


SCALAR = INTEGRATORS.register(Integrator(
    "DOP853-scalar", "scipy's DOP853 in plain floats (its steps, without numpy's per-call cost)",
    IntegratedNormal, ivp="DOP853", stepper=_plain_floats, floats=True))

SCIPY = tuple(INTEGRATORS.register(Integrator(
    name, f"scipy's solve_ivp method {name}", IntegratedNormal, ivp=name, stepper=_scipy(name),
    multistep=name in ("BDF", "LSODA"))) for name in ("RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA"))
