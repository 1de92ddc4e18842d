"""``taylor``: the Taylor-series method on a law's series recurrence (:mod:`sphereimpact.ode.series`)."""

from __future__ import annotations

from .normal import CONDITIONED_ZETA_MAX, TaylorNormal
from ..errors import SeriesOverflowError
from .base import INTEGRATORS, Integrator


def _cannot(scene):
    return None if scene.law.series is not None else f"needs a law with a series; model {scene.model!r} has none"


def _declines(scene):
    """Beyond the accuracy contract's damping ratio an explicit method creeps either way, and the
    Runge-Kutta path is the one measured there."""
    zeta = scene.family.get("zeta", 0.0)
    return None if zeta <= CONDITIONED_ZETA_MAX else f"damping ratio {zeta:g} > {CONDITIONED_ZETA_MAX:g}"


TAYLOR = INTEGRATORS.register(Integrator(
    "taylor", "Taylor series of the law's recurrence, steps from the last two coefficients", TaylorNormal,
    cannot=_cannot, declines=_declines, overflows=(SeriesOverflowError,)))
