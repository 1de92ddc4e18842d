"""Normal contact force laws, in a registry keyed by name.

Every law is written with delta >= 0 as compression [m] and delta_dot its rate
[m/s] (> 0 while compressing), and returns the force P [N] the flat pushes on
the ball along the outward normal.  Outside contact (delta < 0) there is no
force, and the exponential of the modified law is never evaluated there (it
would overflow for large negative delta).

The chapter prints eq. 4.1 as P = k delta - b delta_dot and eq. 4.2 with
exp(+100 delta / R) because its delta is the (negative) displacement of the
centre; with delta as compression both read as below.

To add a law, write a function ``f(delta, delta_dot, p)`` (``p`` has the
attributes ``k``, ``b``, ``radius``, ``ramp``) and register it::

    FORCE_MODELS["my-law"] = ForceModel("my-law", f, linear=False, doc="...", continued=f_smooth)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class ForceModel:
    """A named normal force law.

    Attributes
    ----------
    name : str
        Registry key.
    force : callable
        ``force(delta, delta_dot, p) -> P`` [N], numpy-vectorised.
    linear : bool
        True when P is linear in (delta, delta_dot) inside contact, so that the
        normal motion has a closed form (:mod:`sphereimpact.closed`).
    doc : str
        One line for help texts and reports.
    continued : callable
        ``continued(delta, delta_dot, p)``: the in-contact formula continued
        smoothly a little past delta = 0.  Integrators use it for their stages,
        and the force during contact is evaluated with it, so that the ends of
        [0, t_f] are one-sided limits whatever side of zero round-off puts delta.  The step that
        crosses separation evaluates stages just past it; there the physical
        law is 0 and its kink (or, for kelvin-voigt, jump) spoils that step's
        interpolant, and with it the rebound velocity (measured: COR error
        8.9e-11 at rtol 1e-12 with the kink, 8.4e-13 without).  Separation
        events use ``force``.
    ramp_rate : callable or None
        ``ramp_rate(p) -> c / R`` [1/m] for a law whose damping is switched on by a ramp in
        u = (c / R) delta (the modified law's 1 - exp(-u)); None for a law without one.  Integrators
        bound their steps where the ramp switches off (see :class:`sphereimpact.normal.IntegratedNormal`).
    """

    name: str
    force: Callable
    linear: bool
    doc: str
    continued: Callable
    ramp_rate: Callable | None = None


def kelvin_voigt(delta, delta_dot, p):
    """Eq. 4.1, the chapter's "previous" model: P = k delta + b delta_dot [N] for delta > 0.

    P jumps to b v_n at first touch and turns negative (pulls) before delta
    returns to zero.
    """
    delta = np.asarray(delta, dtype=float)
    return np.where(delta > 0, p.k * delta + p.b * np.asarray(delta_dot, dtype=float), 0.0)


def modified(delta, delta_dot, p):
    """Eq. 4.2, the chapter's model: P = k delta + b delta_dot (1 - exp(-c delta / R)) [N].

    The ramp 1 - exp(-c delta / R) (c = ``p.ramp``, 100 in the chapter) makes P
    start from zero.  It is evaluated as ``-expm1`` of a non-positive argument,
    so it is exact for small delta and cannot overflow.
    """
    delta = np.asarray(delta, dtype=float)
    inside = np.maximum(delta, 0.0)
    ramp = -np.expm1(-p.ramp * inside / p.radius)
    return np.where(delta > 0, p.k * inside + p.b * np.asarray(delta_dot, dtype=float) * ramp, 0.0)


def kelvin_voigt_continued(delta, delta_dot, p):
    """k delta + b delta_dot for every delta (the linear law's own continuation)."""
    return p.k * np.asarray(delta, dtype=float) + p.b * np.asarray(delta_dot, dtype=float)


#: 1/n! for the Taylor continuation of the ramp.
_INVERSE_FACTORIALS = tuple(1.0 / math.factorial(n) for n in range(1, 9))


def ramp_continued(u):
    """1 - exp(-u) for u >= 0; for u < 0 its degree-8 Taylor polynomial, with u clipped at -1.

    No exponential is evaluated outside contact, the value is bounded, and
    the function is smooth to 8th order across u = 0 (the error of the
    polynomial is below 1e-16 for |u| < 0.01, far more than one step overshoots).
    """
    u = np.asarray(u, dtype=float)
    ramp = np.atleast_1d(-np.expm1(-np.maximum(u, 0.0)))
    negative = np.atleast_1d(u < 0)
    if negative.any():  # only the stages past separation pay for the polynomial
        w = np.minimum(-np.atleast_1d(u)[negative], 1.0)  # w = -u in (0, 1]
        poly = np.zeros_like(w)
        for c in reversed(_INVERSE_FACTORIALS):  # sum_{n=1..8} w^n / n!, by Horner
            poly = (poly + c) * w
        ramp[negative] = -poly
    return ramp.reshape(u.shape)


def modified_continued(delta, delta_dot, p):
    """Eq. 4.2 with the ramp continued past delta = 0 by :func:`ramp_continued`."""
    delta = np.asarray(delta, dtype=float)
    return p.k * delta + p.b * np.asarray(delta_dot, dtype=float) * ramp_continued(p.ramp * delta / p.radius)


FORCE_MODELS: dict[str, ForceModel] = {
    "kelvin-voigt": ForceModel(
        "kelvin-voigt", kelvin_voigt, linear=True,
        doc="eq. 4.1, linear spring-damper P = k delta + b delta_dot (the chapter's 'previous' model)",
        continued=kelvin_voigt_continued),
    "modified": ForceModel(
        "modified", modified, linear=False,
        doc="eq. 4.2, P = k delta + b delta_dot (1 - exp(-c delta/R)) (the chapter's model, c = ramp)",
        continued=modified_continued, ramp_rate=lambda p: p.ramp / p.radius),
}
