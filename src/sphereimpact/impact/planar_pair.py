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

A compliant tangential contact (the springs of :mod:`sphereimpact.contact.tangential.springs`: ``linear``,
``mindlin``, ``mindlin-displacement``) adds the spring's force F to the state, held along the turning t as the DEM
codes rotate theirs into the new tangent plane (in the plane of motion that keeps its magnitude): sticking,
dF/dt = -k_t s + rho F, until |F| reaches mu max(P, 0); sliding, F = -sigma mu max(P, 0), until the stick rule no
longer pushes |F| past the moving cap,

    g = sigma s - (mu dP/dt - rho mu P) / k_t,   dP/dt from the law at delta_ddot = -P / m* - (v.t)^2 / |d|,

falls through zero: the reduced model's rules (k_t, rho and the first phase as there), with the slip and the
compression of the turning frame.  A tangential dashpot (``dashpot_cor`` below 1, the DEM codes' of
:mod:`sphereimpact.contact.tangential.dashpot`) makes the force F_s - c_t s, F_s the spring's, and adds the reduced
model's dashpot terms to g, the slip's rate while sliding being -sigma mu max(P, 0) K - (v.n)(v.t) / |d| here (the
turn's share).  The exact microslip contact is the reduced model's only.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from ..contact.laws import force_rate, spring_exponent, spring_stiffness
from ..contact.tangential import TANGENTIALS, Regime
from ..contact.tangential.dashpot import dashpot_ratio
from ..contact.tangential.rigid import MAX_PHASES, RIGID
from ..contact.tangential.springs import LINEAR, MINDLIN, MINDLIN_DISPLACEMENT, START_PROBE, history_rate
from ..integrators import ivp_method
from ..integrators.normal import separation_function
from .planar import SegmentedMotion
from .scene import Scene, SolverOptions

#: The least compression scale v_n T [in R1 + R2] the model resolves: delta = R1 + R2 - |d| is a difference of
#: O(R1 + R2) numbers (as the planar body on the flat, :data:`sphereimpact.impact.planar.RESOLVED_DEPTH`).
RESOLVED_DEPTH = 1e-6
#: The compliant tangential contacts the pair's model implements, each with its history rule (``rescale`` of
#: :class:`~sphereimpact.contact.tangential.springs.CompliantTangential`); served only as these very objects.
SPRINGS = ((LINEAR, "never"), (MINDLIN, "unloading"), (MINDLIN_DISPLACEMENT, "always"))
#: Every tangential contact the pair's model implements.
CONTACTS = (RIGID, *(model for model, _ in SPRINGS))


def serves(model) -> bool:
    """Whether the pair's planar model implements tangential ``model`` (a TangentialModel; by identity)."""
    return any(model is known for known in CONTACTS)


class PlanarPairMotion(SegmentedMotion):
    """Integrate one impact of a ball on a partner sphere with both centres free (see module docstring).

    Exposes the relative motion as the reduced sphere's (``scene`` is :attr:`Scene.reduced`, ``kinematics`` its
    delta, delta_dot, relative centre velocity in the first touch's frame and w*), so that
    :meth:`~sphereimpact.impact.outcome.Outcome.from_motion` reads it; :attr:`bodies` holds each body's end state
    and :attr:`line_turn` the angle the line of centres turned [rad].

    Parameters
    ----------
    pair : Scene
        A scene with a partner sphere and a tangential contact of :data:`CONTACTS`.
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
        model = TANGENTIALS[s.tangential]
        if not serves(model):
            raise ValueError(f"body 'planar' has the {', '.join(m.name for m in CONTACTS)} tangential contacts for two "
                             f"spheres; tangential {s.tangential!r} is solved by body 'reduced'")
        #: the spring's history rule, None for the rigid contact
        self._rescale = next((rule for known, rule in SPRINGS if known is model), None)
        # c_t = root_m sqrt(k_t): the dashpot's coefficient per root of stiffness [sqrt(kg)] (0: none), as the reduced
        # model sets it (a spring that takes no dashpot has no dashpot_cor)
        cor = s.parameters.get("dashpot_cor")
        self._root_m = 0.0 if cor is None else 2.0 * dashpot_ratio(cor, s.law.spring) * math.sqrt(s.mass)
        depth = s.v_normal / s.frequency / self._reach
        if depth < RESOLVED_DEPTH:
            raise ValueError(f"body 'planar': this scene compresses the pair by about {depth:.3g} (R1 + R2), below "
                             f"the {RESOLVED_DEPTH:g} its coordinates resolve; body 'reduced' solves it")
        length = s.v_normal / s.frequency
        scale = [length, length, s.speed, s.speed, s.speed / s.radius, s.mass * s.speed ** 2]
        if self._rescale is not None:  # the spring's force F [N], at its scale m* v omega_n
            scale.append(s.mass * s.speed * s.frequency)
            self._n = spring_exponent(s.law, s)
            # an undamped tangential spring rings (as the reduced model allows): each half-period of it may stick and
            # slip once more, about sqrt(k_t K) T / pi of them at the compression scale's stiffness
            k_t = float(self._stiffness(length))
            self.max_phases = MAX_PHASES + int(4.0 * math.sqrt(k_t * self._k) / s.frequency)
        scale = np.array(scale)
        # first step a small part of the contact: solve_ivp's own guess, from the state's O(R1 + R2) magnitudes,
        # overshoots the contact of stiff spheres into overflowing trial forces
        self._options = dict(method=ivp_method(options.method), rtol=options.rtol, atol=options.atol * scale,
                             max_step=options.max_step, dense_output=True, first_step=1e-3 / s.frequency)
        # d, v, w* and the tangential force's work W = int F s dt [J]: first touch at d = (0, R1 + R2)
        z = [0.0, self._reach, s.v_tangent, -s.v_normal, s.spin, 0.0] + ([0.0] if self._rescale is not None else [])
        slip0 = s.slip0
        # no friction, or no tangential motion at all (the line of centres never turns): F = 0 throughout, no switch
        self._free = s.mu == 0 or not s.has_tangential_motion
        if self._free:
            mode = Regime.SLIDING
        elif self._rescale is not None:
            mode = self._first_spring_mode(slip0)
        else:
            mode = Regime.SLIDING if slip0 != 0 else Regime.ROLLING
        self._run(options, np.array(z), mode, -1.0 if slip0 < 0 else 1.0)
        end = self.end
        self.line_turn = abs(math.atan2(end[0], end[1]))
        self.work_t = float(end[5])
        self.bodies = self._bodies(end)

    def _first_spring_mode(self, slip0: float) -> str:
        """A spring's first phase, as the reduced model decides it: where the cap starts finite, sticking if the
        dashpot's force |s0| c_t fits within it; else sticking unless the stick trial force |s0| (k_t t / n + c_t)
        outgrows the cap at t = START_PROBE T (Maw's psi_1 > 1)."""
        s = self.scene
        cap = s.mu * max(float(s.stage_force(0.0, s.v_normal)), 0.0)
        if cap > 0:
            return Regime.STICKING if abs(slip0) * self._dashpot(0.0) <= cap else Regime.SLIDING
        eps = START_PROBE / s.frequency
        delta = s.v_normal * eps
        trial = abs(slip0) * (self._stiffness(delta) * eps / self._n + self._dashpot(delta))
        return Regime.SLIDING if trial > s.mu * max(float(s.stage_force(delta, s.v_normal)), 0.0) else Regime.STICKING

    def _stiffness(self, delta):
        """k_t [N/m] at compression(s) delta: kappa times the normal spring's tangent stiffness."""
        return self.scene.kappa * spring_stiffness(self.scene.law, delta, self.scene)

    def _dashpot(self, delta):
        """The tangential dashpot's c_t = root_m sqrt(k_t) [N s/m] at compression(s) delta (0 without one)."""
        return self._root_m * np.sqrt(self._stiffness(delta)) if self._root_m else 0.0

    def _spring_force(self, z):
        """A sticking spring's force on the ball [N] at state(s) z: the spring's less the dashpot's, F_s - c_t s."""
        _, delta, _, t_vec = self._geometry(z)
        if not self._root_m:
            return z[6]
        return z[6] - self._dashpot(delta) * (t_vec[0] * z[2] + t_vec[1] * z[3] - z[4] * self.scene.radius)

    def _switched(self, mode: str, z):
        if self._rescale is not None:  # a spring: F continuous at the cap either way, the spring holding F + c_t s
            delta, _, p = self._contact(z)
            cap, slip = self.scene.mu * max(float(p), 0.0), self._slip(z)
            if mode == Regime.SLIDING:
                z[6] = -self._sigmas[-1] * cap + float(self._dashpot(delta)) * slip
                return Regime.STICKING, 1.0, z
            force = float(self._spring_force(z))
            sigma = -1.0 if force > 0 else 1.0  # F = +cap: the contact slips backwards
            if force == 0.0:  # the cap closed to zero with F: slip goes the contact point's way
                sigma = 1.0 if slip >= 0 else -1.0
            z[6] = -sigma * cap + float(self._dashpot(delta)) * slip
            return Regime.SLIDING, sigma, z
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

    def _contact(self, z, force=None, geometry=None):
        """(delta, delta_dot, P) of state(s) z; ``force`` the law as a function of (delta, delta_dot): by default
        ``stage_force`` (any shape), ``ContactLaw.in_floats`` for one state (the same values, no numpy per call);
        ``geometry`` z's :meth:`_geometry` where the caller has it."""
        _, delta, n_vec, _ = geometry or self._geometry(z)
        delta_dot = -(n_vec[0] * z[2] + n_vec[1] * z[3])
        return delta, delta_dot, (force or self.scene.stage_force)(delta, delta_dot)

    def _slip(self, z) -> float:
        """s = v.t - w* R* [m/s] of one state z."""
        _, _, _, t_vec = self._geometry(z)
        return float(t_vec @ z[2:4]) - z[4] * self.scene.radius

    def _stick_gap(self, sigma: float, z) -> float:
        """g of a sliding spring at state z (see module docstring): positive while the stick rule would push |F|
        past the cap; 1 where there is no cap or no spring."""
        s = self.scene
        dist, delta, n_vec, t_vec = self._geometry(z)
        delta_dot = -float(n_vec @ z[2:4])
        p = float(s.stage_force(delta, delta_dot))
        k_t = float(self._stiffness(delta))
        if p <= 0 or k_t <= 0:
            return 1.0
        along = float(t_vec @ z[2:4])
        delta_ddot = -p / s.mass - along * along / dist
        rho = history_rate(self._rescale, self._n, delta, delta_dot)
        cap, slip = s.mu * p, along - z[4] * s.radius
        cap_rate = s.mu * float(force_rate(s.law, delta, delta_dot, delta_ddot, s))
        gap = sigma * slip - (cap_rate - rho * cap) / k_t
        if not self._root_m:
            return gap
        # F = F_s - c_t s: the dashpot's share of the stick rule's rate, as the reduced model's
        c_t = float(self._dashpot(delta))
        if c_t * abs(slip) > cap and sigma * slip > 0:  # the dashpot alone exceeds the cap: slide on
            return 1.0
        c_rate = 0.0 if self._n == 1.0 else 0.5 * (self._n - 1.0) * c_t * delta_dot / delta  # c_t ~ delta^((n-1)/2)
        slip_rate = -sigma * cap * self._k + delta_dot * along / dist  # the turn's share: -(v.n)(v.t) / |d|
        return gap + sigma * (c_rate * slip + c_t * slip_rate - rho * c_t * slip) / k_t

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

        spring, sticking = self._rescale is not None, mode == Regime.STICKING
        one = s.law.in_floats(s.reduced)  # the law on one state, in floats

        def force(z, p):
            if self._free:
                return 0.0
            if mode == Regime.SLIDING:
                return -sigma * s.mu * max(float(p), 0.0)
            return float(self._spring_force(z)) if sticking else self._rolling_force(z)

        def rhs(t, z):
            geometry = self._geometry(z)
            _, _, n_vec, t_vec = geometry
            delta, delta_dot, p = self._contact(z, one, geometry)  # smooth past separation, as in the reduced model
            f = force(z, p)
            a = (p * n_vec + f * t_vec) / m_star
            slip = t_vec[0] * z[2] + t_vec[1] * z[3] - z[4] * r_star
            rates = [z[2], z[3], a[0], a[1], -f * lever / r_star, f * slip]
            if spring:  # the stick rule on the spring's force while sticking; F slaved to the cap while sliding
                k_t = float(self._stiffness(delta))
                rho = history_rate(self._rescale, self._n, float(delta), float(delta_dot))
                rates.append(-k_t * slip + rho * z[6] if sticking and not self._free else 0.0)
            return rates

        def max_compression(t, z):
            return self._contact(z, one)[1]

        def separation(t, z):
            delta, delta_dot, _ = self._contact(z, one)
            return sep(delta, delta_dot)

        def switch(t, z):
            if self._free:
                return 1.0
            if spring:  # |F| reaches the cap while sticking; the stick rule stops outgrowing it while sliding
                if sticking:
                    return s.mu * max(float(self._contact(z, one)[2]), 0.0) - abs(float(self._spring_force(z)))
                return self._stick_gap(sigma, z)
            if mode == Regime.SLIDING:  # sigma times the slip falls through zero
                _, _, _, t_vec = self._geometry(z)
                return sigma * (float(t_vec @ z[2:4]) - z[4] * r_star)
            return s.mu * max(float(self._contact(z, one)[2]), 0.0) - abs(self._rolling_force(z))

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
        sliding = np.array([mode == Regime.SLIDING for mode in self._modes])[which]
        held = (self._spring_force(z) if self._rescale is not None else
                np.array([self._rolling_force(z[:, i]) for i in range(z.shape[1])]))
        return np.where(sliding, -np.array(self._sigmas)[which] * self.scene.mu * p, held)

    def kinematics(self, t) -> dict:
        """delta, delta_dot, the relative centre velocity along t0 and n0, w* and the relative displacement along
        t0 at t [s] (arrays, SI): the reduced sphere's quantities."""
        z = self._state(t)
        delta, delta_dot, _ = self._contact(z)
        return {"delta": delta, "delta_dot": delta_dot, "vc_t": z[2], "vc_n": z[3], "omega": z[4], "u_t": z[0]}
