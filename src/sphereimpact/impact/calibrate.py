"""Set a law's damping from a measured coefficient of restitution, and stiffness from a contact time.

A user measures the COR of their ball at one speed, not a damping coefficient.  :func:`calibrate` finds
the value of the law's own damping parameter (``ContactLaw.damping``: b, chi, ...) for which this
impact's normal COR is the one asked for, by a one-dimensional root find on the law itself (Brent's
method in log(damping), each evaluation an impact solved at rtol 1e-12), not by an approximate formula.
The published formulas (``ContactLaw.cor_relations``) are reported beside it and can be chosen instead.
With a contact time as well, the stiffness is fitted too (an outer root find on log k, the COR held by
the inner one).

The normal COR is -delta_dot(t_f) / v_n of the normal motion; it depends on the approach speed's normal
component, not on the angle or friction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace


from ..contact.laws import Relation
from ..errors import ImpactError
from ..integrators.normal import IntegratedNormal
from ..ode.roots import brent
from .inputs import as_number
from .scene import Scene, SolverOptions

#: Calibrated COR and contact time are met to this relative accuracy.
ACCURACY = 1e-9
#: The impacts solved inside the root finds: tight, so the calibrated outputs hold ACCURACY.
TIGHT = SolverOptions(method="DOP853-scalar", rtol=1e-12, atol=1e-12)
#: Bracket expansion: factor per try and most tries (4^40 ~ 1e24 either side of the start).
GROWTH, TRIES = 4.0, 40


@dataclass(frozen=True)
class Calibration:
    """The calibrated scene and what was fitted.

    Attributes
    ----------
    scene : Scene
        The input scene with its law's damping (and, with a contact time, ``k``) set.
    parameter : str
        The damping parameter set (``b``, ``chi``, ...).
    value : float
        Its value, in the law's units.
    cor : float
        The normal COR the calibrated scene gives (solved at rtol 1e-12).
    relation : Relation
        ``exact`` or the published relation used.
    relations : dict
        Every published relation the law declares (:class:`Relation`) -> the damping value it gives for this COR.
    contact_time : float or None
        The contact time t_f [s] of the calibrated scene when the stiffness was fitted too.
    """

    scene: Scene
    parameter: str
    value: float
    cor: float
    relation: Relation
    relations: dict = field(default_factory=dict)
    contact_time: float | None = None


def options_for(cor: float) -> SolverOptions:
    """TIGHT with atol scaled to the COR sought: the COR is |y_f|, y the dimensionless rate, whose absolute
    error is about atol, so a COR of 1e-3 held to ACCURACY relative needs atol 1e-3 x TIGHT's (at 1e-12
    the fitted kelvin-voigt damping's COR erred by 1.2e-9 there, against its closed form)."""
    return replace(TIGHT, atol=max(1e-16, TIGHT.atol * min(1.0, cor)))


def normal_cor(scene: Scene, options: SolverOptions = TIGHT) -> float:
    """The normal coefficient of restitution -delta_dot(t_f) / v_n of ``scene`` (of the relative motion, with a
    partner sphere)."""
    normal = IntegratedNormal(scene.reduced, options)
    return -float(normal.state(normal.t_f)[1]) / scene.v_normal


def contact_time(scene: Scene, options: SolverOptions = TIGHT) -> float:
    """The contact time t_f [s] of ``scene``."""
    return IntegratedNormal(scene.reduced, options).t_f


def check_measurement(law, cor, relation: Relation | str = Relation.EXACT, contact_time=None) -> tuple[float, Relation]:
    """The measured ``cor`` as a number and its ``relation`` as a :class:`Relation` (its word accepted), once
    checked against ``law`` without solving anything (what :func:`calibrate` and a study's config check refuse
    alike).

    Raises
    ------
    ValueError
        A relation that is not known or not the law's, a COR outside (0, 1) for a damped law, or an elastic law
        given anything but COR 1 with a contact time.
    """
    cor, relation = as_number("cor", cor), Relation.parse(relation, "cor_relation")
    if law.damping is None:
        if contact_time is not None and cor == 1.0:
            return cor, relation
        raise ValueError(f"cor: model {law.name!r} has no damping parameter to calibrate (it is elastic, "
                         "COR 1); choose a damped law" + (", or give cor 1 with contact_time" if contact_time
                                                          is None else ""))
    if not (math.isfinite(cor) and 0.0 < cor < 1.0):
        raise ValueError(f"cor must be a finite number in (0, 1) for the damped model {law.name!r} "
                         f"(1 is the elastic limit, damping 0); got {cor!r}")
    if relation is not Relation.EXACT and relation not in law.cor_relations:
        available = ", ".join([Relation.EXACT, *law.cor_relations])
        raise ValueError(f"cor_relation {relation.value!r} is not available for model {law.name!r} "
                         f"(its relations: {available})")
    return cor, relation


def calibrate(scene: Scene, cor, relation: Relation | str = Relation.EXACT, contact_time=None) -> Calibration:
    """Set ``scene``'s damping so that its normal COR is ``cor`` (and, with ``contact_time``, its k too).

    Parameters
    ----------
    scene : Scene
        Ball, law and approach; its damping (and k, if ``contact_time`` is given) is replaced.
    cor : float
        The normal COR to reach, in (0, 1) for a law with damping; 1 for an elastic law with
        ``contact_time``.
    relation : Relation or str
        ``exact`` (root find, to 1e-9) or one of the law's ``cor_relations`` (the published formula as is), a
        :class:`Relation` or its word.
    contact_time : float, optional
        The contact time t_f [s] to reach as well, by fitting the stiffness k.

    Returns
    -------
    Calibration

    Raises
    ------
    ValueError
        A COR outside (0, 1), a law without damping, a relation the law lacks, or a COR or contact time
        that the law cannot reach at this speed, naming the parameter.
    """
    cor, relation = check_measurement(scene.law, cor, relation, contact_time)
    if scene.law.damping is None:
        return _fit_stiffness(scene, None, relation, as_number("contact_time", contact_time))
    if contact_time is not None:
        return _fit_stiffness(scene, cor, relation, as_number("contact_time", contact_time))
    return _calibrate_damping(scene, cor, relation)


def _relations(scene: Scene, cor: float) -> dict:
    return {name: float(relation(cor, scene.reduced)) for name, relation in scene.law.cor_relations.items()}


def _calibrate_damping(scene: Scene, cor: float, relation: Relation) -> Calibration:
    law = scene.law
    name = law.damping
    relations = _relations(scene, cor)
    options = options_for(cor)
    if relation is not Relation.EXACT:
        calibrated = scene.with_(**{name: relations[relation]})
        return Calibration(calibrated, name, relations[relation], normal_cor(calibrated, options), relation,
                           relations)

    def excess(log_value: float) -> float:  # COR(damping) - cor, decreasing in the damping
        return normal_cor(scene.with_(**{name: math.exp(log_value)}), options) - cor

    start = relations.get(Relation.HUNT_CROSSLEY) or getattr(scene, name) or 1.0
    low, high = _bracket(excess, math.log(start), f"cor {cor!r} with model {scene.model!r} at v_n = "
                                                  f"{scene.v_normal:.6g} m/s (damping parameter {name})", cor)
    value = math.exp(brent(excess, low, high, xtol=1e-15, rtol=4 * 2.0**-52))
    calibrated = scene.with_(**{name: value})
    reached = normal_cor(calibrated, options)
    if abs(reached - cor) > ACCURACY * cor:
        raise ImpactError(f"cor: calibration reached {reached!r}, not {cor!r} to {ACCURACY:g} (model {scene.model!r})")
    return Calibration(calibrated, name, value, reached, Relation.EXACT, relations)


def _bracket(excess, start: float, what: str, target: float) -> tuple[float, float]:
    """(low, high) in log(damping) with excess(low) > 0 > excess(high), expanding from ``start``.

    Where the expansion reaches a damping at which the contact no longer ends (e.g. an over-damped
    kelvin-voigt contact under the penetration criterion), the bracket is sought by bisection between the
    last damping that separates and that one; if none in between falls below the COR, it is unreachable.
    """
    step = math.log(GROWTH)
    low = high = start
    value_high = _safe(excess, high)
    if value_high is None:  # the start itself does not separate: come down first
        for _ in range(TRIES):
            high -= step
            value_high = _safe(excess, high)
            if value_high is not None:
                break
        else:
            raise ValueError(f"cannot reach {what}: no damping tried lets the contact end")
    low = high
    for _ in range(TRIES):
        if value_high is not None and value_high < 0:
            break
        if value_high is None:  # past the separating range: bisect back towards the last good damping
            mid = 0.5 * (low + high)
            value_mid = _safe(excess, mid)
            if high - low < 1e-12:
                break
            if value_mid is None:
                high = mid
            elif value_mid < 0:
                high, value_high = mid, value_mid
            else:
                low = mid
            continue
        low, high = high, high + step
        value_high = _safe(excess, high)
    if value_high is None or not value_high < 0:
        floor = excess(low) + target
        raise ValueError(f"cannot reach {what}: the nearest this law comes before the contact stops ending is "
                         f"{floor:.6g}; choose another value, separation criterion or law")
    for _ in range(TRIES):
        if excess(low) > 0:
            return low, high
        low -= step
    raise ValueError(f"cannot reach {what}: the COR stays below it however small the damping")


def _safe(excess, log_value: float):
    """excess(log_value), or None where the impact does not end (a damping too large to separate)."""
    try:
        return excess(log_value)
    except ImpactError:
        return None


def _fit_stiffness(scene: Scene, cor: float | None, relation: Relation, target_time: float) -> Calibration:
    """k (and the damping, for a COR) such that t_f = ``target_time`` and the COR holds."""
    if not (math.isfinite(target_time) and target_time > 0):
        raise ValueError(f"contact_time must be a finite number > 0 s; got {target_time!r}")

    def at(log_k: float):
        trial = scene.with_(k=math.exp(log_k))
        return trial if cor is None else _calibrate_damping(trial, cor, relation).scene

    def excess(log_k: float) -> float:  # t_f(k) - target, decreasing in k
        return contact_time(at(log_k)) - target_time

    what = f"contact_time {target_time!r} s with model {scene.model!r} (stiffness k)"
    low, high = _bracket(excess, math.log(scene.k), what, target_time)
    log_k = brent(excess, low, high, xtol=1e-15, rtol=4 * 2.0**-52)
    fitted = at(log_k)
    reached = contact_time(fitted)
    if abs(reached - target_time) > ACCURACY * target_time:
        raise ImpactError(f"contact_time: fit reached {reached!r} s, not {target_time!r} s to {ACCURACY:g}")
    name = scene.law.damping
    value = getattr(fitted, name) if name else math.nan
    options = TIGHT if cor is None else options_for(cor)
    return Calibration(fitted, name or "k", value if name else fitted.k, normal_cor(fitted, options), relation,
                       _relations(fitted, cor) if cor is not None else {}, reached)

