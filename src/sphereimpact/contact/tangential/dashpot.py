"""The tangential dashpot of the DEM codes: a viscous damper beside the tangential spring, set from the normal COR.

DEM codes damp the tangential spring of a contact as they damp its normal one.  Kratos Multiphysics'
DEMApplication (``applications/DEMApplication/custom_constitutive``, ``DEM_D_Hertz_viscous_Coulomb_CL.cpp`` and
``DEM_D_Linear_viscous_Coulomb_CL.cpp``; its Chung & Ooi benchmarks run them) puts

    F_t = F_spring - c_t s,   c_t = 2 gamma sqrt(m* k_t),

s the contact point's slip velocity, k_t the tangential stiffness at this instant, m* the contact's reduced mass
(the ball's on a flat), and caps the total |F_t| at mu P.  The damping ratio gamma is the one its normal dashpot
2 gamma sqrt(m* k_n) gets from the normal COR e_n:

- a Hertz spring: Thornton, Cummins & Cleary's fit (Powder Technol. 233, 2013, 30-46) as Kratos codes it
  (``GammaForHertzThornton`` of its DEM scripts), gamma = sqrt(1 / (1 - (1 + e)^2 exp(a(e))) - 1) with a(e) a
  polynomial of degree 10 in e (:data:`THORNTON_FIT`), e taken at 0.001 below that and gamma = 0 above e = 0.999,
  as Kratos does (the fit itself gives 0.0045 at e = 1);
- a linear spring: the exact relation of the linear spring-dashpot whose force ends at P = 0 (Kratos solves it by
  bisection), here :func:`sphereimpact.contact.laws.spring_damper.events` inverted by Brent's method.

The tangential springs ``linear`` and ``mindlin`` (:mod:`.springs`) take the COR as their own parameter
``dashpot_cor`` (:data:`DASHPOT_COR`; 1: no dashpot, the elastic spring).  ``mindlin-displacement`` does not (its
docstring says why), nor does the exact elastic microslip contact.
"""

from __future__ import annotations

import math

from ...ode.roots import brent
from ..laws.base import Spring
from ..parameters import Parameter

#: a(e) of Thornton's fit, coefficients of e^1 .. e^10 as Kratos codes them.
THORNTON_FIT = (-6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18, 6276.757,
                -1489.915)
#: Kratos's range of the fit: a COR below the first is taken as it, above the second gives no damping.
THORNTON_RANGE = (0.001, 0.999)

DASHPOT_COR = Parameter(
    "dashpot_cor", "-", "normal COR e_n that sets the tangential dashpot c_t = 2 gamma(e_n) sqrt(m* k_t) as Kratos's "
    "DEM does (1: no dashpot)", "a finite number in [0.001, 1]", lambda x: (x >= 0.001) & (x <= 1.0), default=1.0,
    bounds=(0.001, 1.0))


def hertz_ratio(cor: float) -> float:
    """gamma of a Hertz contact's dashpots for the normal COR ``cor``: Thornton's fit, in Kratos's range."""
    if cor > THORNTON_RANGE[1]:
        return 0.0
    e = max(float(cor), THORNTON_RANGE[0])
    a = 0.0
    for c in reversed(THORNTON_FIT):
        a = e * (c + a)
    return math.sqrt(1.0 / (1.0 - (1.0 + e) ** 2 * math.exp(a)) - 1.0)


def linear_ratio(cor: float) -> float:
    """gamma = zeta of the linear spring-dashpot whose COR (force criterion) is ``cor``: the exact relation."""
    if cor >= 1.0:
        return 0.0
    from ..laws.spring_damper import events
    from ..separation import Separation

    def excess(zeta):
        return -float(events(zeta, Separation.FORCE)["y_f"][()]) - cor

    high = 1.0
    while excess(high) > 0:  # the COR falls with zeta: bracket the root
        high *= 2.0
    return brent(excess, 0.0, high, xtol=1e-15, rtol=4 * 2.0 ** -52)


def dashpot_ratio(cor: float, spring: Spring) -> float:
    """gamma of the tangential dashpot for the normal COR ``cor`` and the law's ``spring`` (``hertz`` or
    ``linear``), as Kratos sets it (module docstring)."""
    return hertz_ratio(cor) if spring is Spring.HERTZ else linear_ratio(cor)
