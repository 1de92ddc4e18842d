"""The full planar two-body model of a ball striking a partner sphere: the cross-check of the pair's reduction.

The reduction (:mod:`sphereimpact.impact.pair`) solves the pair as one sphere on a flat whose normal is the line of
centres at first touch, held fixed.  Here both centres are free and the normal turns with the line of centres.
Two free bodies under equal and opposite contact forces move as their centre of mass (at constant velocity) and
their relative motion, so the state is the relative position d = c1 - c2 and velocity v = v1 - v2 [m, m/s] in the
frame of the first touch (n0 = d / |d| then, t0 along the incoming tangential motion) and the reduced spin
w* = (R1 w1 + R2 w2) / R* [rad/s] (both spins in the ball's rotational sense, as ``Scene.partner_spin``):

    m* dv/dt = P n + F t,   n = d / |d|, t = (n_y, -n_x),   delta = R1 + R2 - |d|,   delta_dot = -v.n,
    dw*/dt = -F (R1^2 / I1 + R2^2 / I2) / R*,   slip s = v.t - w* R*,

with P the scene's law at (delta, delta_dot) (its parameters the contact's, at R*: ``Scene.reduced``).  The
tangential force F switches by events, as the planar body on the flat does: sliding, F = -sigma mu max(P, 0);
rolling (s = 0), F = F_r, the force that keeps s = 0 while t turns, -(v . dt/dt) / K with
K = 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2 (0 in the reduction, whose t does not turn); rolling ends where mu max(P, 0)
can no longer supply |F_r|.  Each body's spin follows from the angular impulse, each centre's velocity from the
momentum; the outputs are read in the frame of the first touch, as the reduction's are, but for the tangential
force's work W = int F s dt, integrated (the power of the contact forces is -P delta_dot + F s; the first touch's
frame would mix the turning normal's work into it).  The lever arms are R1 and R2, as in the reduction: the two
contact points then lie delta apart along n, and the angular momentum about a fixed point changes by int delta F dt.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from ..contact.tangential import Regime
from ..integrators import ivp_method
from ..integrators.normal import separation_function
from .planar import SegmentedMotion
from .scene import Scene, SolverOptions

#: The least compression scale v_n T [in R1 + R2] the model resolves: delta = R1 + R2 - |d| is a difference of
#: O(R1 + R2) numbers (as the planar body on the flat, :data:`sphereimpact.impact.planar.RESOLVED_DEPTH`).
RESOLVED_DEPTH = 1e-6


class PlanarPairMotion(SegmentedMotion):
    """Integrate one impact of a ball on a partner sphere with both centres free (see module docstring).

    Exposes the relative motion as the reduced sphere's (``scene`` is :attr:`Scene.reduced`, ``kinematics`` its
    delta, delta_dot, relative centre velocity in the first touch's frame and w*), so that
    :meth:`~sphereimpact.impact.outcome.Outcome.from_motion` reads it; :attr:`bodies` holds each body's end state
    and :attr:`line_turn` the angle the line of centres turned [rad].

    Parameters
    ----------
    pair : Scene
        A scene with a partner sphere and the rigid tangential contact.
    options : SolverOptions
        A solve_ivp method and tolerances.
    """

    def __init__(self, pair: Scene, options: SolverOptions):
        s = self.scene = pair.reduced
        self.pair = pair
        r1, r2 = pair.radius, 0.5 * pair.partner_diameter
        self._r1, self._r2, self._reach = r1, r2, r1 + r2
        i1 = pair.inertia_factor * pair.mass * r1 * r1
        i2 = pair.partner_inertia_factor * pair.partner_mass * r2 * r2
        self._lever = r1 * r1 / i1 + r2 * r2 / i2  # spin's share of the slip per unit tangential impulse [1/kg]
        self._k = 1.0 / pair.mass + 1.0 / pair.partner_mass + self._lever
        self._i1, self._i2 = i1, i2
        depth = s.v_normal / s.frequency / self._reach
        if depth < RESOLVED_DEPTH:
            raise ValueError(f"body 'planar': this scene compresses the pair by about {depth:.3g} (R1 + R2), below "
                             f"the {RESOLVED_DEPTH:g} its coordinates resolve; body 'reduced' solves it")
        length = s.v_normal / s.frequency
        scale = np.array([length, length, s.speed, s.speed, s.speed / s.radius, s.mass * s.speed ** 2])
        # first step a small part of the contact: solve_ivp's own guess, from the state's O(R1 + R2) magnitudes,
        # overshoots the contact of stiff spheres into overflowing trial forces
        self._options = dict(method=ivp_method(options.method), rtol=options.rtol, atol=options.atol * scale,
                             max_step=options.max_step, dense_output=True, first_step=1e-3 / s.frequency)
        # d, v, w* and the tangential force's work W = int F s dt [J]: first touch at d = (0, R1 + R2)
        z = np.array([0.0, self._reach, s.v_tangent, -s.v_normal, s.spin, 0.0])
        slip0 = s.slip0
        # no friction, or no tangential motion at all (the line of centres never turns): F = 0 throughout, no switch
        self._free = s.mu == 0 or not s.has_tangential_motion
        self._run(options, z, Regime.SLIDING if slip0 != 0 or self._free else Regime.ROLLING, -1.0 if slip0 < 0 else 1.0)
        end = self.end
        self.line_turn = abs(math.atan2(end[0], end[1]))
        self.work_t = float(end[5])
        self.bodies = self._bodies(end)

    def _switched(self, mode: str, z):
        if mode == Regime.SLIDING:
            _, _, _, t_vec = self._geometry(z)
            z[4] = float(z[2:4] @ t_vec) / self.scene.radius  # exactly on the constraint
            return Regime.ROLLING, 1.0, z
        return Regime.SLIDING, -math.copysign(1.0, self._rolling_force(z)), z  # slips the way F_r pushed

    # --- geometry and forces ----------------------------------------------------------------------------
    def _geometry(self, z):
        """(|d|, delta, n, t) of state(s) z."""
        dist = np.hypot(z[0], z[1])
        n_vec = np.array([z[0] / dist, z[1] / dist])
        return dist, self._reach - dist, n_vec, np.array([n_vec[1], -n_vec[0]])

    def _contact(self, z):
        """(delta, delta_dot, P) of state(s) z."""
        _, delta, n_vec, _ = self._geometry(z)
        delta_dot = -(n_vec[0] * z[2] + n_vec[1] * z[3])
        return delta, delta_dot, self.scene.stage_force(delta, delta_dot)

    def _rolling_force(self, z) -> float:
        """F_r [N]: the tangential force that keeps the slip at 0 while the line of centres turns."""
        dist, _, n_vec, _ = self._geometry(z)
        v = np.asarray(z[2:4], dtype=float)
        n_rate = (v - n_vec * float(n_vec @ v)) / dist
        t_rate = np.array([n_rate[1], -n_rate[0]])
        return -float(v @ t_rate) / self._k

    def _segment(self, mode: str, sigma: float, t0: float, t_end: float, z0):
        s = self.scene
        m_star, lever, r_star = s.mass, self._lever, s.radius
        sep = separation_function(s)

        def force(z, p):
            if self._free:
                return 0.0
            return -sigma * s.mu * max(float(p), 0.0) if mode == Regime.SLIDING else self._rolling_force(z)

        def rhs(t, z):
            _, _, n_vec, t_vec = self._geometry(z)
            _, _, p = self._contact(z)  # smooth past separation, as in the reduced model
            f = force(z, p)
            a = (p * n_vec + f * t_vec) / m_star
            slip = t_vec[0] * z[2] + t_vec[1] * z[3] - z[4] * r_star
            return [z[2], z[3], a[0], a[1], -f * lever / r_star, f * slip]

        def max_compression(t, z):
            return self._contact(z)[1]

        def separation(t, z):
            delta, delta_dot, _ = self._contact(z)
            return sep(delta, delta_dot)

        def switch(t, z):
            if self._free:
                return 1.0
            if mode == Regime.SLIDING:  # sigma times the slip falls through zero
                _, _, _, t_vec = self._geometry(z)
                return sigma * (float(t_vec @ z[2:4]) - z[4] * r_star)
            return s.mu * max(float(self._contact(z)[2]), 0.0) - abs(self._rolling_force(z))

        for event in (max_compression, separation, switch):
            event.direction = -1
        separation.terminal = switch.terminal = True
        return solve_ivp(rhs, (t0, t_end), z0, events=(max_compression, separation, switch), **self._options)

    def _bodies(self, z) -> dict:
        """Each body's velocity in the first touch's frame (t0 = x, n0 = y) and spin at the end state z: the centre
        of mass keeps its velocity, the spins share the angular impulse (R_i / I_i each)."""
        pair, s = self.pair, self.scene
        m1, m2 = pair.mass, pair.partner_mass
        v_cm = m1 * np.array([s.v_tangent, -s.v_normal]) / (m1 + m2)  # the partner at rest before
        v = np.array([z[2], z[3]])
        v1, v2 = v_cm + m2 / (m1 + m2) * v, v_cm - m1 / (m1 + m2) * v
        impulse = (s.spin - z[4]) * s.radius / self._lever  # the tangential impulse's angular share [N s]
        return {"vc_t": float(v1[0]), "vc_n": float(v1[1]), "omega_f": pair.spin - impulse * self._r1 / self._i1,
                "partner_vc_t": float(v2[0]), "partner_vc_n": float(v2[1]),
                "partner_omega_f": pair.partner_spin - impulse * self._r2 / self._i2}

    # --- the relative motion, as a reduced motion ---------------------------------------------------------
    def tangential_force(self, t):
        """The tangential contact force on the ball [N] at t [s], along the turning t."""
        z = self._state(t)
        which = self._which(np.atleast_1d(t))
        p = np.maximum(self._contact(z)[2], 0.0)
        if self._free:
            return np.zeros_like(p)
        rolling = np.array([self._rolling_force(z[:, i]) for i in range(z.shape[1])])
        sliding = np.array([mode == Regime.SLIDING for mode in self._modes])[which]
        return np.where(sliding, -np.array(self._sigmas)[which] * self.scene.mu * p, rolling)

    def kinematics(self, t) -> dict:
        """delta, delta_dot, the relative centre velocity along t0 and n0, w* and the relative displacement along
        t0 at t [s] (arrays, SI): the reduced sphere's quantities."""
        z = self._state(t)
        delta, delta_dot, _ = self._contact(z)
        return {"delta": delta, "delta_dot": delta_dot, "vc_t": z[2], "vc_n": z[3], "omega": z[4], "u_t": z[0]}
