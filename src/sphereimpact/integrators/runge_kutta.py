"""``DOP853-scalar`` and scipy's :func:`~scipy.integrate.solve_ivp` methods, through one driver
(:class:`sphereimpact.integrators.normal.IntegratedNormal`: events, the ramp band, landing on t_f, the budget).

``DOP853-scalar`` is DOP853's algorithm in plain floats (:mod:`sphereimpact.ode.dop853`) on a law with a scalar
formula, scipy's DOP853 on any other.
"""

from __future__ import annotations

from .normal import IntegratedNormal
from .base import INTEGRATORS, Integrator

SCALAR = INTEGRATORS.register(Integrator(
    "DOP853-scalar", "scipy's DOP853 in plain floats (its steps, without numpy's per-call cost)",
    IntegratedNormal, ivp="DOP853"))

SCIPY = tuple(INTEGRATORS.register(Integrator(name, f"scipy's solve_ivp method {name}", IntegratedNormal, ivp=name))
              for name in ("RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA"))
