"""The driver: solve one impact with the reduced (default) or the full planar model.

The reduced model integrates the normal motion only (or uses its closed form
for kelvin-voigt) and derives tangential velocity and spin from the normal
impulse (rigid tangential contact), or integrates the tangential spring alone on
the solved normal force (compliant: ``linear``, ``mindlin``); a normal impact
(angle 0) has no tangential state at all.  The full
planar model (:mod:`sphereimpact.impact.planar`) integrates centre position,
velocity and spin with event-driven sliding/rolling, as the cross-check.
"""

from __future__ import annotations

import math
import time
import warnings
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import replace

import numpy as np

from ..choice import Choice
from ..errors import BeyondRadiusWarning, EnergyGainWarning, ImpactError
from ..integrators import normal_motion, resolve_method  # noqa: F401  (resolve_method: re-exported)
from ..contact.motion import NormalMotion
from ..integrators.normal import describe_family
from .outcome import Outcome, gains_energy
from .pair import pair_velocities
from .scene import Scene, SolverOptions
from ..contact.tangential import TANGENTIALS, Regime

class Body(Choice):
    """The rigid-body descriptions :func:`simulate` solves (``body=``, ``--body``)."""

    REDUCED = "reduced"  # the normal ODE, the tangential motion from the normal impulse: exact on the flat
    PLANAR = "planar"  # centre position, velocity and spin integrated together: the cross-check


#: The bodies, as a tuple of their names.
BODIES = tuple(Body)


#: The normal motions shared inside :func:`reusing_normal_motions`, by normal problem and options (None outside).
_SHARED: ContextVar[dict | None] = ContextVar("shared normal motions", default=None)


@contextmanager
def reusing_normal_motions():
    """Inside this block :func:`simulate` and :func:`simulate_many` (and so the sweep's single impacts and per-family
    solves, through :func:`shared_normal_motion`) solve each normal problem once: scenes that differ only in
    friction, the tangential contact or the spin
    (:attr:`~sphereimpact.impact.scene.Scene.normal_problem`) share one solved normal motion, which does not
    depend on them.  Every outcome is bit for bit the one solved afresh.  A fit of friction or tangential
    stiffness (:func:`sphereimpact.fit.fit`) runs in one, so its bounces' normal motions are solved once, not at
    every evaluation of the model.  The motions are kept until the outermost block ends (tens of kB each)."""
    shared = _SHARED.get()
    token = _SHARED.set({} if shared is None else shared)
    try:
        yield
    finally:
        _SHARED.reset(token)


def shared_normal_motion(scene: Scene, options: SolverOptions) -> NormalMotion:
    """``scene``'s normal motion: solved, or inside :func:`reusing_normal_motions` shared with the scenes of the
    same normal problem (the single impacts' and the sweep's per-family solves alike)."""
    shared = _SHARED.get()
    if shared is None:
        return normal_motion(scene, options)
    key = (scene.normal_problem, options)
    motion = shared.get(key)
    if motion is None:
        motion = shared[key] = normal_motion(scene, options)
    return motion if motion.scene is scene else motion.for_scene(scene)


#: ``SolverOptions()``, made and checked once: options are frozen, so a call given none shares these.
DEFAULT_OPTIONS = SolverOptions()


class ReducedMotion:
    """Normal motion plus the tangential motion it drives, as one contact motion.

    The tangential motion is the scene's tangential model's (:data:`sphereimpact.contact.tangential.TANGENTIALS`):
    from the normal impulse (``rigid``) or integrated on the solved normal force (the compliant models); a
    normal impact has none.
    """

    def __init__(self, normal: NormalMotion, options: SolverOptions):
        self.normal, self.scene = normal, normal.scene
        self.t_m, self.t_f, self.grid, self.stats = normal.t_m, normal.t_f, normal.grid, normal.stats
        if not self.scene.has_tangential_motion:
            self.tangential, self.t_roll, self.regime, self.switches = None, None, Regime.NONE, 0
            return
        self.tangential = TANGENTIALS[self.scene.tangential].motion(normal, options)
        self.t_roll, self.regime = self.tangential.t_roll, self.tangential.regime
        self.switches = self.tangential.switches

    def tangential_force(self, t):
        """Tangential contact force on the ball [N] at t [s] (0 for a normal impact)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.zeros_like(t) if self.tangential is None else self.tangential.force(t)

    def force(self, t):
        return self.normal.force(t)

    def force_extremes(self) -> tuple[float, float]:
        """The normal force's smallest and largest values [N], the normal motion's
        (:meth:`~sphereimpact.contact.motion.NormalMotion.force_extremes`)."""
        return self.normal.force_extremes()

    def ends(self) -> dict:
        """What an outcome reads of the motion (:meth:`~sphereimpact.impact.outcome.Outcome.from_motion`): delta at
        t_m (``delta_m``) and vc_n, vc_t, omega and u_t at t_f, floats (SI): :meth:`kinematics`' values, the
        tangential motion read at t_f alone (its value at an instant does not depend on the others asked with it)."""
        delta, delta_dot = self.normal.state(np.array([self.t_m, self.t_f]))  # as kinematics reads them, to the bit
        if self.tangential is None:
            v_t = omega = u_t = 0.0
        else:
            v_t, omega, u_t = (float(q[0]) for q in self.tangential.at(np.array([self.t_f])))
        return {"delta_m": float(delta[0]), "vc_n": float(-delta_dot[1]), "vc_t": v_t, "omega": omega, "u_t": u_t}

    def kinematics(self, t) -> dict:
        """delta, delta_dot, vc_t, vc_n, omega, u_t at t [s] (arrays, SI)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        delta, delta_dot = self.normal.state(t)
        if self.tangential is None:
            v_t = omega = u_t = np.zeros_like(t)
        else:
            v_t, omega, u_t = self.tangential.at(t)
        return {"delta": delta, "delta_dot": delta_dot, "vc_t": v_t, "vc_n": -delta_dot,
                "omega": omega, "u_t": u_t}


def simulate(scene: Scene, options: SolverOptions | None = None, body: str = "reduced",
             strict: bool = False) -> Outcome:
    """Simulate one impact.

    Parameters
    ----------
    scene : Scene
        Ball, flat, contact law and approach.
    options : SolverOptions, optional
        Method and tolerances; defaults to :class:`SolverOptions()`.
    body : {'reduced', 'planar'}
        ``reduced`` (exact on the flat and cheapest) or the full planar rigid-body model; with a partner sphere,
        ``planar`` frees both centres and turns the normal with the line of centres, which the reduction holds
        fixed (:mod:`sphereimpact.impact.planar_pair`).  (The force law is ``scene.model``.)
    strict : bool
        Refuse (``ImpactError``) a result whose maximum compression exceeds the radius, instead of
        returning it flagged (``Outcome.beyond_radius``) with a :class:`BeyondRadiusWarning`.

    Returns
    -------
    Outcome

    Raises
    ------
    TypeError
        ``scene`` is not a Scene or ``options`` not a SolverOptions.
    ValueError
        Unknown body, ``closed`` with a law without a closed form, or a compliant tangential model with
        body ``planar``.
    ImpactError
        The ball never separates, an event was missed, or (strict) delta_m exceeds the radius.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a sphereimpact.Scene, e.g. Scene(angle=60.0); got {type(scene).__name__}")
    if scene.has_partner and body != Body.PLANAR:  # one sphere on the flat, then each body's velocities from the impulses
        return pair_outcome(simulate(scene.reduced, options, body, strict), scene)
    options = DEFAULT_OPTIONS if options is None else options
    if not isinstance(options, SolverOptions):
        raise TypeError("options must be a sphereimpact.SolverOptions, e.g. SolverOptions(rtol=1e-10), or None; "
                        f"got {type(options).__name__}")
    body = Body.parse(body, "body")
    if body == Body.PLANAR:
        from .planar import CONTACTS, planar_motion

        motion_of = planar_motion(TANGENTIALS[scene.tangential])
        if scene.has_partner:  # both centres free: the pair's own planar model (which refuses what it has not)
            from .planar_pair import PlanarPairMotion

            motion_of = PlanarPairMotion
        if motion_of is None:
            served = ", ".join(model.name for model, _ in CONTACTS)
            raise ValueError(f"body 'planar' has the {served} tangential contact only on the flat; tangential "
                             f"{scene.tangential!r} is solved by body 'reduced' (exact: the normal motion does "
                             "not depend on friction)")
    start = time.perf_counter()
    try:
        if body == Body.REDUCED:
            motion = ReducedMotion(shared_normal_motion(scene, options), options)
        else:
            motion = motion_of(scene, options)
        outcome = Outcome.from_motion(motion, time.perf_counter() - start)
    except ImpactError:
        raise
    except (ArithmeticError, RuntimeError) as err:  # a safety net, without a context manager's cost on every call
        raise _left_double(scene, err) from None
    if scene.has_partner:  # each body's end from the two-body motion itself, not from the reduction's impulses
        s = motion.scene
        work = {"work_t": motion.work_t, "energy_gained": bool(gains_energy(
            motion.work_t, s.mass, s.speed, s.inertia_factor * s.mass * s.radius ** 2, s.spin))}
        outcome = replace(outcome, scene=scene, **motion.bodies, **work)
    return _checked(outcome, strict)


def _left_double(scene: Scene, err: Exception) -> ImpactError:
    """The ImpactError of arithmetic ``err`` that left double precision, naming ``scene``'s family."""
    return ImpactError(f"the computation left double precision ({type(err).__name__}: {err}; "
                       f"{describe_family(scene)}criterion '{scene.separation}'): the scene lies outside what the "
                       "model computes")


def _checked(outcome: Outcome, strict: bool) -> Outcome:
    """``outcome``, refused when an output is not finite, and flagged (warned, or refused when ``strict``)
    when the maximum compression exceeds the radius."""
    scene = outcome.scene
    bad = [key for key in outcome.output_keys() if isinstance(value := getattr(outcome, key), (float, np.floating))
           and not math.isfinite(value)]  # to_dict's floats, without building its dict
    if bad:  # never a NaN in a result
        raise ImpactError(f"no finite {', '.join(bad)} ({describe_family(scene)}criterion '{scene.separation}'): "
                          "the scene lies outside what the solver resolves")
    if outcome.beyond_radius:
        message = (f"maximum compression delta_m = {outcome.delta_m:.3g} m exceeds the radius R = "
                   f"{scene.radius:.3g} m: the centre passed the flat's plane, outside the model (lower the speed "
                   "or raise k)")
        if strict:
            raise ImpactError(message)
        warnings.warn(message, BeyondRadiusWarning, stacklevel=3)
    if outcome.energy_gained:
        energy = 0.5 * scene.mass * scene.speed ** 2 + 0.5 * scene.inertia * scene.spin ** 2
        warnings.warn(f"tangential {scene.tangential!r} made energy: its work on the ball is +{outcome.work_t:.3g} J, "
                      f"{outcome.work_t / energy:.2g} of the incoming kinetic energy (energy_gained): an artefact of "
                      "the model, not of the ball", EnergyGainWarning, stacklevel=3)
    return outcome


def simulate_many(scenes, options: SolverOptions | None = None, strict: bool = False) -> list[Outcome]:
    """Simulate several impacts: :func:`simulate` of each scene, in order, at the same options (the sweep's
    single-impact path calls it a chunk of scenes at a time).

    Raises
    ------
    ImpactError
        As :func:`simulate`, for the first scene that fails.
    """
    return [simulate(scene, options, strict=strict) for scene in scenes]


def pair_outcome(outcome: Outcome, scene: Scene) -> Outcome:
    """The outcome of ``scene``, a ball striking a partner sphere, from ``outcome``, its reduced sphere's on the
    flat (:attr:`Scene.reduced`): the ball's and the partner's velocities and spins from the impulses
    (:func:`~sphereimpact.impact.pair.pair_velocities`); every relative output as the reduced sphere's."""
    values = pair_velocities(
        {"vc_t": outcome.vc_t, "vc_n": outcome.vc_n, "omega_f": outcome.omega_f}, scene.mass, scene.radius,
        scene.inertia_factor, scene.spin, scene.partner_mass, 0.5 * scene.partner_diameter,
        scene.partner_inertia_factor, scene.partner_spin, scene.v_normal, scene.v_tangent)
    return replace(outcome, scene=scene, **{key: float(value) for key, value in values.items()})
