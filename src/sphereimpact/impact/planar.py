"""The full planar rigid-body model, the cross-check of the reduced model.

State, in the global frame (X horizontal, Y up, origin at the first contact
point): centre position (X, Y), centre velocity (VX, VY) and spin omega
(positive in the sense friction spins the ball).  The flat's outward normal is
n = (sin beta, cos beta) and the tangent t = (cos beta, -sin beta), so
delta = R - C.n and the slip of the contact point is s = V.t - omega R.

Newton-Euler: m dV/dt = P n + F t + m (0, -g),  I domega/dt = -F R.
The tangential force F switches between modes by events, never by sign():
sliding (s > 0): F = -mu max(P, 0); rolling (s = 0): F keeps s = 0, which
takes F = -m g sin(beta) alpha / (1 + alpha); rolling ends when mu max(P, 0)
can no longer supply that.  Each mode is a separate solve_ivp segment.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import ImpactError
from ..integrators.normal import check_rebound, horizon, no_separation_message, separation_function, substep_grid
from ..integrators import ivp_method
from ..ode.events import extremes
from .scene import Scene, SolverOptions
from ..contact.tangential import MAX_PHASES, Regime, phase_index
from ..contact.tangential.rigid import RIGID


#: The least compression scale v_n T [radii] the planar body resolves: its delta = R - C.n is a difference of
#: O(R) coordinates, so round-off of 2e-16 R in C errs delta by 2e-16 / depth relative (2e-10 here: about the
#: default tolerance; a chapter ball at 1e-30 m/s, depth 1e-32, never found its separation).
RESOLVED_DEPTH = 1e-6


class SegmentedMotion:
    """An impact integrated as a sequence of solve_ivp segments, one per tangential mode (``sliding`` with the sign
    of its slip, or ``rolling``; a compliant contact's ``sticking``), each ended by its switch event; the first
    segment's maximum compression and the last's separation are events too.  The shared loop of the planar bodies
    (:class:`PlanarMotion`, :class:`sphereimpact.impact.planar_pair.PlanarPairMotion`): a subclass gives
    ``_segment(mode, sigma, t0, t_end, z)`` (solve_ivp's result, events: max compression, separation, switch),
    ``_switched(mode, z)`` (the next mode, sign and state at a switch), ``_contact(z)`` (delta, delta_dot, P), the
    state's size and the reduced scene.

    Attributes
    ----------
    t_m, t_f : float
        Maximum compression and separation [s].
    t_roll : float or None
        First instant the contact point stops slipping (rolls or sticks) [s], None if never.
    regime : str
        The mode at separation (``none`` without tangential motion).
    switches : int
        Changes of mode.
    grid : ndarray
        Sample times bracketing every event, ending at t_f.
    stats : dict
        method, rtol, atol, nfev.
    end : ndarray
        The state at separation.
    """

    #: Segments an impact may take before it is refused (a compliant contact's ringing may raise it).
    max_phases = MAX_PHASES

    def _run(self, options: SolverOptions, z, mode: str, sigma: float) -> None:
        s = self.scene
        t0, t_end = 0.0, horizon(s)
        self._segments, self._modes, self._sigmas, t_m, nfev = [], [], [], None, 0
        self.t_roll = 0.0 if mode != Regime.SLIDING and s.has_tangential_motion else None
        while True:
            sol = self._segment(mode, sigma, t0, t_end, z)
            nfev += sol.nfev
            if sol.status == -1:
                raise ImpactError(f"solver {self._options['method']} failed: {sol.message}")
            self._segments.append((t0, float(sol.t[-1]), sol.sol, sol.t))
            self._modes.append(mode)
            self._sigmas.append(sigma)
            if t_m is None and len(sol.t_events[0]):
                t_m = float(sol.t_events[0][0])
            if len(sol.t_events[1]):
                break
            if sol.status == 0 or not len(sol.t_events[2]):
                raise ImpactError(no_separation_message(s, t_end))
            t0 = float(sol.t_events[2][0])
            if mode == Regime.SLIDING and self.t_roll is None:
                self.t_roll = t0
            mode, sigma, z = self._switched(mode, sol.y_events[2][0].copy())
            if len(self._segments) >= self.max_phases:
                raise ImpactError(f"more than {self.max_phases} stick-slip switches in one contact")
        if t_m is None:
            raise ImpactError("separation found before maximum compression: event missed")
        self.end = sol.y_events[1][0]
        check_rebound(s, options, float(self._contact(self.end)[1]))
        self.t_m, self.t_f = t_m, float(sol.t_events[1][0])
        self.regime = mode if s.has_tangential_motion else Regime.NONE
        self.switches = len(self._segments) - 1 if s.has_tangential_motion else 0
        steps = np.concatenate([seg[3] for seg in self._segments])
        grid = np.unique(substep_grid(steps))
        self.grid = np.append(grid[(grid >= 0) & (grid < self.t_f)], self.t_f)
        self.stats = {"method": self._options["method"], "rtol": options.rtol, "atol": options.atol,
                      "nfev": int(nfev)}

    def _which(self, t):
        """Each instant's segment index."""
        return phase_index([SimpleNamespace(t0=seg[0]) for seg in self._segments], t)

    def _state(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.empty((len(self.end), t.size))
        which = self._which(t)
        for i, (_, _, dense, _) in enumerate(self._segments):
            mask = which == i
            if mask.any():
                out[:, mask] = dense(t[mask])
        return out

    def force(self, t):
        return self._contact(self._state(t))[2]

    def force_extremes(self) -> tuple[float, float]:
        """The normal force's smallest and largest values [N] over the contact (sampled on ``grid``, then refined:
        :func:`~sphereimpact.ode.events.extremes`)."""
        return extremes(self.force, self.grid)

    def ends(self) -> dict:
        """What an outcome reads of the motion (:meth:`~sphereimpact.impact.outcome.Outcome.from_motion`): delta at
        t_m (``delta_m``) and vc_n, vc_t, omega and u_t at t_f, floats (SI), from one :meth:`kinematics` call."""
        both = self.kinematics(np.array([self.t_m, self.t_f]))
        return {"delta_m": float(both["delta"][0]), **{key: float(both[key][1]) for key in ("vc_n", "vc_t", "omega", "u_t")}}


class PlanarMotion(SegmentedMotion):
    """Integrate one impact with the full planar model (see module docstring).

    Parameters
    ----------
    scene : Scene
    options : SolverOptions
        A solve_ivp method (``closed`` is not available for this model).
    """

    def __init__(self, scene: Scene, options: SolverOptions):
        self.scene = scene
        depth = scene.v_normal / scene.frequency / scene.radius  # compression scale v_n T in radii
        if depth < RESOLVED_DEPTH:
            raise ValueError(f"body 'planar': this scene compresses the ball by about {depth:.3g} R, below the "
                             f"{RESOLVED_DEPTH:g} R its absolute coordinates resolve (delta = R - C.n loses its digits); "
                             "body 'reduced' solves it")
        tilt = scene.tilt  # the flat's inclination; the approach's incidence sets the initial velocity
        self._n = np.array([math.sin(tilt), math.cos(tilt)])
        self._t = np.array([math.cos(tilt), -math.sin(tilt)])
        radius, length = scene.radius, scene.speed / scene.frequency
        scale = np.array([length, length, scene.speed, scene.speed, scene.speed / radius])
        self._options = dict(method=ivp_method(options.method), rtol=options.rtol, atol=options.atol * scale,
                             max_step=options.max_step, dense_output=True)
        self._hold = scene.mass * scene.g_tangent * scene.inertia_factor / (1 + scene.inertia_factor)
        velocity = scene.v_tangent * self._t - scene.v_normal * self._n
        if scene.angle == scene.incidence_deg:  # the chapter's vertical drop: exactly (0, -v)
            velocity = np.array([0.0, -scene.speed])
        z = np.array([radius * self._n[0], radius * self._n[1], velocity[0], velocity[1], scene.spin])
        slip0 = scene.slip0
        mode = Regime.SLIDING if scene.has_tangential_motion and (slip0 != 0 or self._hold > 0) else Regime.ROLLING
        self._run(options, z, mode, -1.0 if slip0 < 0 else 1.0)

    def _switched(self, mode: str, z):
        if mode == Regime.SLIDING:
            z[4] = float(z[2:4] @ self._t) / self.scene.radius  # exactly on the constraint
            return Regime.ROLLING, 1.0, z
        return Regime.SLIDING, 1.0, z  # gravity along the flat outgrows friction: the contact point slips down-slope

    def _contact(self, z, force=None):
        """(delta, delta_dot, P) of state(s) z; ``force`` the law as a function of (delta, delta_dot): by default
        ``stage_force`` (any shape), ``ContactLaw.in_floats`` for one state (the same values, no numpy per call)."""
        s = self.scene
        delta = s.radius - (self._n[0] * z[0] + self._n[1] * z[1])
        delta_dot = -(self._n[0] * z[2] + self._n[1] * z[3])
        return delta, delta_dot, (force or s.stage_force)(delta, delta_dot)  # in-contact formula, as NormalMotion's

    def _segment(self, mode: str, sigma: float, t0: float, t_end: float, z0):
        s = self.scene
        n_vec, t_vec, radius = self._n, self._t, s.radius
        mu, hold, sep = sigma * s.mu, self._hold, separation_function(s)
        one = s.law.in_floats(s.reduced)  # the law on one state, in floats

        def rhs(t, z):
            _, _, p = self._contact(z, one)  # smooth past separation, as in the reduced model
            f = -mu * max(float(p), 0.0) if mode == Regime.SLIDING else -hold
            ax, ay = (p * n_vec + f * t_vec) / s.mass
            return [z[2], z[3], ax, ay - s.gravity, -f * radius / s.inertia]

        def max_compression(t, z):
            return -(n_vec @ z[2:4])

        def separation(t, z):
            delta, delta_dot, _ = self._contact(z, one)
            return sep(delta, delta_dot)

        def switch(t, z):
            if mode == Regime.SLIDING:  # sigma times the slip falls through zero
                return sigma * (t_vec @ z[2:4] - z[4] * radius)
            if hold > 0:
                return s.mu * max(float(self._contact(z, one)[2]), 0.0) - hold
            return 1.0

        for event in (max_compression, separation, switch):
            event.direction = -1
        separation.terminal = switch.terminal = True
        return solve_ivp(rhs, (t0, t_end), z0, events=(max_compression, separation, switch), **self._options)

    def tangential_force(self, t):
        """Friction force on the ball along the flat [N] at t [s], as the segment's mode sets it."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        which = self._which(t)
        sliding = np.array([mode == Regime.SLIDING for mode in self._modes])[which]
        sigma = np.array(self._sigmas)[which]
        if not self.scene.has_tangential_motion:
            return np.zeros_like(t)
        return np.where(sliding, -sigma * self.scene.mu * np.maximum(self.force(t), 0.0), -self._hold)

    def kinematics(self, t) -> dict:
        """delta, delta_dot, vc_t, vc_n, omega, u_t at t [s] (arrays, SI)."""
        z = self._state(t)
        delta, delta_dot, _ = self._contact(z)
        radius = self.scene.radius
        return {"delta": delta, "delta_dot": delta_dot, "vc_t": self._t @ z[2:4], "vc_n": self._n @ z[2:4],
                "omega": z[4], "u_t": self._t @ (z[0:2] - radius * self._n[:, None])}


#: The tangential contacts this body implements: model -> its motion ``(scene, options)``.  A model is served
#: only if it is one of these objects (compared by identity, so a registered copy under another name, or a
#: model claiming a capability, is not mistaken for the rigid Coulomb contact written here).
CONTACTS = ((RIGID, PlanarMotion),)


def planar_motion(model):
    """The planar body's motion for tangential ``model`` (a TangentialModel), or None where it has none."""
    return next((motion for known, motion in CONTACTS if known is model), None)

