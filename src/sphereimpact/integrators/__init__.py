"""The integrators of the normal motion: a registry of definitions, one file each, and the choice ``auto``.

``INTEGRATORS.register(Integrator(...))`` adds one; :func:`choose` and :func:`normal_motion` serve it to
``simulate``, the sweep's single impacts and the command line's ``--method``.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from . import closed, taylor, runge_kutta  # noqa: F401  (each registers itself, in the order of the help)
from .base import AUTO_ORDER, DEFAULT_INTEGRATOR, INTEGRATORS, Integrator

__all__ = ["AUTO_ORDER", "DEFAULT_INTEGRATOR", "INTEGRATORS", "Integrator", "choose", "ivp_method", "method_names",
           "normal_motion", "resolve_method"]


def method_names() -> tuple:
    """Every name ``SolverOptions.method`` accepts: ``auto`` and the registered integrators."""
    return ("auto", *INTEGRATORS)


def choose(scene, options):
    """The integrators that will serve ``scene`` under ``options``, in the order to try them (an iterator:
    ``auto`` asks each only when the ones before it did not serve).

    An explicit method is the only candidate, and one that cannot serve the scene is refused
    (``ValueError`` naming it and why); ``auto`` yields the :data:`AUTO_ORDER` integrators that can serve it
    and do not decline it.
    """
    if options.method != "auto":
        integrator = INTEGRATORS.named(options.method)
        reason = integrator.cannot(scene)
        if reason is not None:
            raise ValueError(f"method {integrator.name!r} {reason}")
        yield integrator
        return
    for name in AUTO_ORDER:
        integrator = INTEGRATORS[name]
        if integrator.cannot(scene) is None and integrator.declines(scene) is None:
            yield integrator


def resolve_method(scene, options):
    """``options`` with ``auto`` made concrete: the first integrator :func:`choose` offers."""
    if options.method != "auto":
        return options
    return with_method(options, next(choose(scene, options)).name)


@lru_cache(maxsize=64)
def with_method(options, name: str):
    """``options`` with ``method`` set to ``name``: SolverOptions are frozen and hashable, so the few a process uses are
    made and checked once, not on every impact."""
    return replace(options, method=name)


def normal_motion(scene, options):
    """The normal motion of ``scene`` by ``options.method``; under ``auto`` an integrator whose arithmetic
    overflows (``Integrator.overflows``: the Taylor series at lam = 5e299, say) hands over to the next."""
    overflow = None
    for integrator in choose(scene, options):
        try:
            return integrator.solve(scene, options if options.method == integrator.name
                                    else with_method(options, integrator.name))
        except integrator.overflows as err:
            if options.method != "auto":
                raise
            overflow = err
    if overflow is None:
        raise AssertionError("unreachable: auto always has an integrator that serves the scene")
    raise overflow


def ivp_method(method: str) -> str:
    """The :func:`scipy.integrate.solve_ivp` method that runs ``method`` where the float integrator cannot
    (the planar body, a law without a scalar formula, naive formulations): ``auto`` is
    :data:`DEFAULT_INTEGRATOR`'s.  ``ValueError`` for a method that runs on the reduced body only."""
    integrator = INTEGRATORS.named(DEFAULT_INTEGRATOR if method == "auto" else method)
    if integrator.ivp is None:
        raise ValueError(f"method {method!r} is only available for the reduced model")
    return integrator.ivp
