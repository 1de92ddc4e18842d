"""The contract of a solved normal motion: what the integrators produce and the tangential models read.

It sits in the contact layer, below both: an integrator (:mod:`sphereimpact.integrators`) solves a scene's
normal motion into a :class:`NormalMotion`; a tangential model (:mod:`sphereimpact.contact.tangential`)
builds its motion on one, whoever solved it.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..ode.dense import is_instant
from ..ode.events import extremes, raise_failed, roots

if TYPE_CHECKING:
    from ..impact.scene import Scene


@dataclass(frozen=True)
class KernelState:
    """A solved normal motion as compiled code reads it (:mod:`sphereimpact.contact.normal_kernel`): its dense output's
    arrays, evaluated there with the arithmetic of its Python evaluator, and the law's compiled force.

    Attributes
    ----------
    kind : int
        ``ode.dense.TAYLOR`` (a Taylor method's series: ``knots`` the steps' ends, ``starts`` their starts, ``cx``
        and ``cy`` their coefficients) or ``ode.dense.DOP853`` (``knots`` the step boundaries, ``starts`` and
        ``sizes`` the steps' starts and sizes, ``f`` their interpolants' rows in reverse order, ``y_old`` their start
        states), or a law's closed form (its ``kernel_kind``, e.g. ``spring_damper.KERNEL_KIND``: ``knots`` the
        constants its motion is evaluated from, w, d_scale and v 1); the arrays a kind does not use are empty.
    w, d_scale, v : float
        The dimensionless time's rate [1/s] and the state's scales [m], [m/s].
    force, params
        The law's compiled force kernel (checked against its scalar formula) and its parameters.
    """

    kind: int
    knots: np.ndarray
    starts: np.ndarray
    sizes: np.ndarray
    cx: np.ndarray
    cy: np.ndarray
    f: np.ndarray
    y_old: np.ndarray
    w: float
    d_scale: float
    v: float
    force: object
    params: np.ndarray

    def arrays(self) -> tuple:
        """The dense output as the compiled code takes it: (kind, knots, starts, sizes, cx, cy, f, y_old, w,
        d_scale, v)."""
        return (self.kind, self.knots, self.starts, self.sizes, self.cx, self.cy, self.f, self.y_old, self.w,
                self.d_scale, self.v)


class NormalMotion:
    """A solved normal motion: delta(t) on [0, t_f] with its events.

    Subclasses set ``scene``, ``t_m`` [s], ``t_f`` [s], ``grid`` (increasing
    sample times on [0, t_f] fine enough to bracket every event) and ``stats``,
    and implement :meth:`state`.
    """

    scene: Scene
    t_m: float
    t_f: float
    grid: np.ndarray
    stats: dict

    def state(self, t):
        """Compression delta [m] and its rate delta_dot [m/s] at time(s) t [s]."""
        raise NotImplementedError

    def kernel_state(self) -> KernelState | None:
        """This motion as compiled code reads it, when this process integrates compiled and the motion's dense output
        and law have compiled forms; else None (the caller then computes in Python, to the same bits)."""
        return None

    def spend_in_floats(self, evaluations: int) -> None:
        """Count ``evaluations`` of this motion that a computation with a compiled form made in Python floats (a compliant
        stick phase's right-hand side): a motion that has a compiled form counts them towards its process's rule for
        loading the compiled code (:mod:`sphereimpact.integrators.compiled`), as its integrator counts its own; one
        without (this default) ignores them."""

    def force(self, t):
        """Normal force P(t) [N] during contact, t in [0, t_f].

        Evaluated with the in-contact formula, so the ends are the one-sided
        limits (kelvin-voigt starts at b v_n, not 0, and ends at b delta_dot(t_f)),
        however round-off puts delta(t_f) on either side of zero.
        """
        scalar = self.scene.law.scalar
        if scalar is not None and is_instant(t):  # one instant (root and extremum searches): plain floats
            delta, delta_dot = self.state(t)
            return scalar(float(delta), float(delta_dot), self.scene)
        return self.scene.stage_force(*self.state(t))

    def force_extremes(self) -> tuple[float, float]:
        """The normal force's smallest and largest values [N] over the contact: ``force(t)`` sampled on ``grid``
        (which brackets every extremum), each extremum then refined (:func:`sphereimpact.ode.events.extremes`);
        compiled (:func:`.normal_kernel.force_extremes`, the same answer to the bit) where :meth:`kernel_state` has
        the motion.  Computed once, and kept with the motion and its copies for other scenes (:meth:`kept`)."""
        return self.kept("force extremes", self._force_extremes)

    def _force_extremes(self) -> tuple[float, float]:
        state = self.kernel_state()
        if state is not None:
            from .normal_kernel import force_extremes

            low, high = force_extremes(state.arrays(), state.force, state.params, np.asarray(self.grid, dtype=float))
            return float(low), float(high)
        return extremes(self.force, self.grid, self._forces_on(np.asarray(self.grid, dtype=float)))

    def _forces_on(self, grid: np.ndarray) -> np.ndarray:
        """The normal force [N] at each instant of the array ``grid`` [s] as the compiled kernels sample it
        (:meth:`forces_at` its states)."""
        return self.forces_at(*self.state(grid))

    def forces_at(self, delta, delta_dot) -> np.ndarray:
        """The normal force [N] at the states of the arrays ``delta`` [m] and ``delta_dot`` [m/s] as the compiled kernels
        compute it: the law's ``scalar`` formula state by state (the C library's exp, expm1 and pow, as compiled code
        calls them) where the law has one, else the vectorised ``stage_force``.  numpy's vectorised exp, expm1 and power
        are its own on processors with AVX-512 and differ from the C library's in the last bit for a few percent of
        arguments, so a vectorised sample would not be the compiled one to the bit there (a force extreme at the end of
        contact, where P is about 0)."""
        scalar, scene = self.scene.law.scalar, self.scene
        if scalar is None:
            return scene.stage_force(delta, delta_dot)
        return np.array([scalar(d, v, scene) for d, v in zip(np.asarray(delta, dtype=float).tolist(),
                                                             np.asarray(delta_dot, dtype=float).tolist())])

    def force_roots(self) -> list[float]:
        """The instants [s] in (0, t_f] where the normal force changes sign (:func:`~sphereimpact.ode.events.roots` of
        :meth:`force` on ``grid``): compiled (:func:`.normal_kernel.force_roots`, the same instants to the bit) where
        :meth:`kernel_state` has the motion."""
        grid = np.asarray(self.grid, dtype=float)
        grid = grid[grid > 0.0]
        state = self.kernel_state()
        if state is None:
            return roots(self.force, grid, values=self._forces_on(grid))
        from .normal_kernel import force_roots

        found, status, low, high = force_roots(state.arrays(), state.force, state.params, grid)
        raise_failed(status, self.force, low, high)
        return found.tolist()

    def impulse(self, t):
        """Normal impulse J(t) = integral of P from 0 to t [N s], from the momentum balance."""
        t = float(t) if is_instant(t) else np.asarray(t, dtype=float)
        return self.impulse_from(t, self.state(t)[1])

    def impulse_from(self, t, delta_dot):
        """J(t) [N s] given delta_dot [m/s] at t [s], already evaluated: m (v_n - delta_dot + g_n t)."""
        s = self.scene
        return s.mass * (s.v_normal - delta_dot + s.g_normal * t)

    def impulse_integral(self, t):
        """K(t) = integral of J from 0 to t [N s^2], exact from delta(t)."""
        s = self.scene
        t = float(t) if is_instant(t) else np.asarray(t, dtype=float)
        return s.mass * (s.v_normal * t - self.state(t)[0] + 0.5 * s.g_normal * t * t)

    def for_scene(self, scene: Scene) -> NormalMotion:
        """This motion as the motion of ``scene``, a scene with the same normal problem
        (:attr:`~sphereimpact.impact.scene.Scene.normal_problem`): a shallow copy that reads ``scene``'s friction,
        tangential contact and spin, which the normal motion itself does not depend on."""
        self.__dict__.setdefault("_kept", {})  # made before the copy, so the copy keeps into the same one
        motion = copy.copy(self)
        motion.scene = scene
        return motion

    def kept(self, key, compute):
        """``compute()``, a value derived from this normal motion alone (its samples on a grid, its force's
        extremes), computed once and kept with the motion and its copies for other scenes (:meth:`for_scene`):
        a shared normal motion is sampled once, however many scenes read it."""
        kept = self.__dict__.setdefault("_kept", {})
        if key not in kept:
            kept[key] = compute()
        return kept[key]

    def forget(self) -> None:
        """Drop what :meth:`kept` holds (and the states a dense output keeps of the single instants it was read at),
        so the next reads compute it again (a benchmark timing them)."""
        self.__dict__.pop("_kept", None)

    @property
    def delta_m(self) -> float:
        """Maximum compression [m] (at t_m)."""
        return float(self.state(self.t_m)[0])
