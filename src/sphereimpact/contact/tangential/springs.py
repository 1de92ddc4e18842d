"""Tangential compliance: an elastic tangential spring at the contact, capped by Coulomb friction.

The rigid model (:mod:`sphereimpact.contact.tangential.rigid`) lets the contact point slip or roll.  A real contact
first deforms tangentially: while it sticks it stores tangential strain and gives it back, which can
reverse the contact point's tangential velocity before the ball leaves (Maw, Barber & Fawcett 1976,
Wear 38:101-114).  Here the tangential force F on the ball (along t, the down-slope direction) obeys

- sticking, |F| < mu P+:  dF/dt = -k_t s + rho F,  s = v_t - omega R the contact point's slip velocity
  (with a dashpot, F = F_s - c_t s and this rule is F_s's);
- sliding, |F| = mu P+:   F = -sigma mu P+, sigma = +1 or -1 the direction of slip,

with P+ = max(P, 0) the normal force, k_t the tangential stiffness and rho a history rule:

``linear``
    k_t = kappa k, constant, for a law with a linear spring (k delta): the tangential spring of
    Cundall & Strack (1979), Geotechnique 29:47-65.  rho = 0.
``mindlin``
    k_t = 8 G* a = kappa (3/2) k delta^(1/2), a = sqrt(R delta) the contact radius, for a Hertz spring
    (k delta^(3/2)): Mindlin's no-slip stiffness (Mindlin 1949, J. Appl. Mech. 16:259-268), applied to
    force increments while the contact grows (Mindlin & Deresiewicz 1953, J. Appl. Mech. 20:327-344,
    rho = 0); while it shrinks the tangential force is scaled with the stiffness, rho = (dk_t/dt) / k_t
    (Thornton, Cummins & Cleary 2011, Powder Technol. 210:189-197).  This is LAMMPS's
    ``mindlin_rescale/force``.  With that rule the stored tangential energy F^2 / (2 k_t) never grows by
    itself: d/dt [F^2/(2 k_t)] = -F s - |dk_t/dt| F^2 / (2 k_t^2) in both directions (the increments alone
    would create energy while the contact shrinks).
``mindlin-displacement``
    The same stiffness on the total tangential displacement xi, F = -k_t xi, xi rescaled to the cap while
    sliding: rho = (dk_t/dt) / k_t at every instant.  This is LAMMPS's ``mindlin`` and EDEM's Hertz-Mindlin
    (no slip) rule (Di Renzo & Di Maio 2004, Chem. Eng. Sci. 59:525-541).  While the contact grows at a
    fixed displacement its force grows with k_t, so it stores more energy than the displacement put in.

``linear`` and ``mindlin`` take a tangential dashpot as the DEM codes have it (:mod:`.dashpot`): F = F_s - c_t s,
F_s the spring's force as above, c_t = 2 gamma sqrt(m* k_t) with gamma set from a normal COR ``dashpot_cor`` as
Kratos sets it, and the total |F| capped at mu P+ (1, the default: no dashpot); ``mindlin`` with it is Kratos's
``DEM_D_Hertz_viscous_Coulomb``.  ``mindlin-displacement`` takes none: its spring scales with k_t the force the
dashpot's slip stored while sliding (F_s ~ delta^(1/2) against c_t s ~ delta^(1/4)), so from first touch the
contact would switch between sticking and sliding without end.

kappa = k_t / k_n is the ratio of tangential to normal contact stiffness, 2 (1 - nu) / (2 - nu) for
like elastic materials (2/3 for rubber, nu = 0.5).  Maw's parameter psi_1 = kappa tan(theta) / mu
decides how an impact at incidence theta begins: sliding for psi_1 > 1, sticking below.

The normal motion does not depend on friction, so only (F, J_t, K_t) is integrated, driven by the
solved normal motion, and only while the contact sticks: J_t is the tangential impulse and K_t its time
integral, from which v_t, omega and x_t follow exactly.  Sliding phases are closed-form in the normal
impulse, as in the rigid model.  Stick and slip switch at roots located on the dense output, never by
sign() or tanh in a right-hand side: sticking ends when |F| reaches mu P+ (an event of the DOP853-scalar
integration, :mod:`sphereimpact.ode.dop853`, compiled in :mod:`.stick_kernel` to the same bits); sliding
ends when the stick rule would no longer push |F| past the moving cap, i.e. when

    g = sigma s - (d(mu P+)/dt - rho mu P+) / k_t

falls through zero (a root on the normal motion's grid; d P/dt from the law, see
:func:`sphereimpact.contact.laws.force_rate`).  A dashpot adds sigma (dc_t/dt s + c_t ds/dt - rho c_t s) / k_t to g,
with ds/dt = g_t - sigma mu P+ (1 + 1/alpha) / m while sliding: the same condition on F = F_s - c_t s, F_s holding
-sigma (mu P+ - c_t |s|).  While c_t |s| exceeds mu P+ the spring holds nothing and the contact slides on.  That is
the limit of Kratos's step as the time step vanishes (it scales spring and dashpot forces alike onto the cap, which
drives the spring's force to max(mu P+ - c_t |s|, 0)); LAMMPS instead keeps -sigma mu P+ + c_t s in the spring, which
can point along the slip.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ...ode import dop853
from ...ode.dense import is_instant
from ...errors import ImpactError
from ...ode.events import first_root
from ..laws import Spring, force_rate, spring_exponent, spring_stiffness
from ..motion import NormalMotion
from .dashpot import DASHPOT_COR, dashpot_ratio
from .base import KAPPA, POISSON, SHEAR_MODULUS, TANGENTIALS, Regime, TangentialModel, slip_per_impulse
from .rigid import MAX_PHASES, Phase, PositiveImpulse, by_phase, from_impulse

STICKING, SLIDING = Regime.STICKING, Regime.SLIDING
#: History rules of the spring's force while its stiffness changes: ``never`` (k_t constant: a linear
#: spring), ``unloading`` (scaled with k_t while the contact shrinks) or ``always`` (F = -k_t xi on the total
#: displacement xi: scaled with k_t both ways).
RESCALE = ("never", "unloading", "always")
#: Fraction of the law's time scale over which the start of an impact is probed when both P and the
#: tangential force start from zero (a Hertz or ramped law): the ratio of the stick trial force to the
#: cap converges to its limit (Maw's psi_1) as that fraction -> 0, with an error of the same order.
START_PROBE = 1e-7
#: Largest stick step, as a fraction of the contact: a step may not jump over a slip episode.
STICK_STEPS = 64
#: A switch within this fraction of t_f before separation ends the contact instead: the impulse of such a phase is
#: below round-off, and taking it started a zero-length stick and slip at each other's end (a force with a zero at
#: separation, eq. 4.2 under the penetration criterion, found a stick root 3 ulp before t_f: 54 switches, then
#: a refusal, at one rtol and a sliding end at the next).
END_SLACK = 1e-12


def history_rate(rescale: str, n: float, delta: float, delta_dot: float) -> float:
    """The history rule rho [1/s] at one instant, in plain floats (:meth:`CompliantTangential._rho`): 0 without
    rescaling, outside contact or (``unloading``) while the contact grows; else (n - 1) delta_dot / delta."""
    if rescale == "never" or delta <= 0 or (delta_dot >= 0 and rescale == "unloading"):
        return 0.0
    return (n - 1.0) * delta_dot / delta


@dataclass(frozen=True)
class CompliantPhase(Phase):
    """A rigid-model :class:`~sphereimpact.contact.tangential.Phase` (mode ``sticking`` or ``sliding`` here) and what
    the compliant contact adds.

    ``sigma`` is the slip direction of a sliding phase (F = -sigma mu P+); ``force0`` the tangential force
    [N] at t0; ``solution`` the dense output of a sticking phase, (F, J_t, K_t) scaled, in tau = t / T.
    """

    sigma: float = 0.0
    force0: float = 0.0
    solution: object = None


class CompliantTangential:
    """Tangential motion and spin of a ball with a compliant tangential contact (see module docstring).

    Parameters
    ----------
    normal : NormalMotion
        The solved normal motion; its scene has a compliant tangential model and an angle > 0.
    options : SolverOptions
        Tolerances of the sticking phases' integration (rtol, atol on the scaled state).
    rescale : str
        The history rule, one of :data:`RESCALE`.
    dashpot : bool
        The model takes a tangential dashpot, set by the scene's ``dashpot_cor`` (:mod:`.dashpot`); False: none.

    Attributes
    ----------
    phases : list of CompliantPhase
        Sticking and sliding intervals covering [0, t_f].
    t_roll : float or None
        First instant the contact sticks [s] (0 when the impact starts sticking), None if never.
    regime : str
        ``sticking`` or ``sliding``: the mode at separation.
    switches : int
        Number of stick/slip switches.
    """

    def __init__(self, normal: NormalMotion, options, rescale: str, dashpot: bool = False):
        s = normal.scene
        if rescale not in RESCALE:
            raise ValueError(f"rescale must be one of {', '.join(RESCALE)}; got {rescale!r}")
        self.normal, self.scene, self._rescale = normal, s, rescale
        self.jp = PositiveImpulse(normal)
        self._law, self._n = s.law, spring_exponent(s.law, s)
        self._w = s.frequency
        self._fs = s.mass * s.speed * self._w  # force scale [N]
        self._js = s.mass * s.speed  # impulse scale [N s]
        self._options = options
        # c_t = root_m sqrt(k_t): the dashpot's coefficient per root of stiffness [sqrt(kg)] (0: no dashpot)
        gamma = dashpot_ratio(s.parameters["dashpot_cor"], self._law.spring) if dashpot else 0.0
        self._root_m = 2.0 * gamma * np.sqrt(s.mass)
        t_f = normal.t_f
        # An undamped tangential spring rings: each half-period can stick and slip once more as P falls, so
        # the bound on switches grows with the number of tangential half-periods in the contact.
        k_max = float(self.stiffness(normal.t_m))
        ringing = t_f * np.sqrt(k_max * slip_per_impulse(s.mass, s.inertia_factor)) / np.pi
        limit = MAX_PHASES + int(4.0 * ringing)
        self.phases: list[CompliantPhase] = []
        phase = self._first_phase()
        while True:
            phase, nxt = self._run(phase)
            self.phases.append(phase)
            if nxt is None:
                break
            phase = nxt
            if len(self.phases) >= limit:
                raise ImpactError(f"more than {limit} stick-slip switches in one contact (tangential "
                                  f"{s.tangential!r}, kappa {s.kappa:g}: {ringing:.0f} tangential half-periods)")
        sticks = [p.t0 for p in self.phases if p.mode == STICKING]
        self.t_roll = sticks[0] if sticks else None
        self.regime = self.phases[-1].mode
        self.switches = len(self.phases) - 1

    # --- the normal motion's quantities that drive the tangential one ---------------------------------
    def cap(self, t):
        """Coulomb cap mu P+(t) [N]."""
        return self.scene.mu * np.maximum(self.normal.force(t), 0.0)

    def stiffness(self, t):
        """Tangential stiffness k_t(t) [N/m]: kappa times the normal spring's tangent stiffness."""
        delta, _ = self.normal.state(t)
        return self.scene.kappa * spring_stiffness(self._law, delta, self.scene)

    def dashpot(self, t):
        """The tangential dashpot's coefficient c_t(t) = 2 gamma sqrt(m* k_t) [N s/m] (0 without one)."""
        if not self._root_m:
            return 0.0 if is_instant(t) else np.zeros_like(np.asarray(t, dtype=float))
        return self._root_m * np.sqrt(self.stiffness(t))

    def _rho(self, delta, delta_dot):
        """History rule rho [1/s]: 0 without rescaling; (dk_t/dt)/k_t = (n-1) delta_dot / delta while
        unloading (``rescale='unloading'``) or at every instant (``always``)."""
        if is_instant(delta):  # one instant: plain floats
            return history_rate(self._rescale, self._n, delta, delta_dot)
        if self._rescale == "never":
            return np.zeros_like(np.asarray(delta, dtype=float))
        rate = np.minimum(delta_dot, 0.0) if self._rescale == "unloading" else np.asarray(delta_dot, dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = (self._n - 1.0) * rate / delta
        return np.where(np.asarray(delta) > 0, rho, 0.0)

    def _stick_gap(self, sigma: float, p: CompliantPhase):
        """g(t) of a sliding phase p: positive while the stick rule would push |F| past the cap."""
        s, law = self.scene, self._law

        def g(t):
            t = np.asarray(t, dtype=float)
            delta, delta_dot = self.normal.state(t)
            force = self.normal.force(t)
            accel = s.g_normal - force / s.mass
            cap = s.mu * np.maximum(force, 0.0)
            cap_rate = np.where(force > 0, s.mu * force_rate(law, delta, delta_dot, accel, s), 0.0)
            k_t = s.kappa * spring_stiffness(law, delta, s)
            v, omega = self._evaluate(p, t, with_x=False)
            slip, rho = v - omega * s.radius, self._rho(delta, delta_dot)
            with np.errstate(divide="ignore", invalid="ignore"):
                gap = sigma * slip - (cap_rate - rho * cap) / k_t
                if self._root_m:  # F = F_s - c_t s: the dashpot's share of the stick rule's rate
                    c_t = self._root_m * np.sqrt(k_t)
                    c_rate = (0.0 if self._n == 1.0 else  # c_t ~ delta^((n - 1) / 2)
                              np.where(delta > 0, 0.5 * (self._n - 1.0) * c_t * delta_dot / delta, 0.0))
                    slip_rate = s.g_tangent - sigma * cap * slip_per_impulse(s.mass, s.inertia_factor)
                    gap = gap + sigma * (c_rate * slip + c_t * slip_rate - rho * c_t * slip) / k_t
                    # the dashpot alone exceeds the cap: slide on, while the slip keeps its sense (a slip that
                    # turns between two grid points leaves the formula's sign there, so the root is found)
                    gap = np.where((c_t * np.abs(slip) > cap) & (sigma * slip > 0), 1.0, gap)
            return np.where((force > 0) & (k_t > 0), gap, 1.0)  # no cap or no spring: nothing to stick

        return g

    # --- phases ----------------------------------------------------------------------------------------
    def _first_phase(self) -> CompliantPhase:
        """Sticking, unless the stick trial force outgrows the cap from the first instant (psi_1 > 1)."""
        s, t_f = self.scene, self.normal.t_f
        slip0 = s.slip0  # the incoming spin's share: v_t - omega_0 R
        if float(self.cap(0.0)) > 0:  # the cap starts finite (kelvin-voigt): F = -c_t s0 sticks within it
            if abs(slip0) * float(self.dashpot(0.0)) <= float(self.cap(0.0)):
                return CompliantPhase(STICKING, 0.0, t_f, s.v_tangent, s.spin, 0.0)
            return CompliantPhase(SLIDING, 0.0, t_f, s.v_tangent, s.spin, 0.0, sigma=float(np.sign(slip0)))
        eps = START_PROBE / self._w
        # near t = 0, delta ~ v_n t and k_t ~ t^(n - 1), so the stick rule gives |F| = |s0| (k_t(eps) eps / n + c_t(eps))
        trial = abs(slip0) * (float(self.stiffness(eps)) * eps / self._n + float(self.dashpot(eps)))
        if trial > float(self.cap(eps)):
            return CompliantPhase(SLIDING, 0.0, t_f, s.v_tangent, s.spin, 0.0, sigma=float(np.sign(slip0)))
        return CompliantPhase(STICKING, 0.0, t_f, s.v_tangent, s.spin, 0.0)

    def _run(self, p: CompliantPhase):
        """Solve phase ``p`` to its end; return it (with t1) and the next phase, or None at separation."""
        normal, s = self.normal, self.scene
        t_f = normal.t_f
        if p.mode == SLIDING:
            grid = np.concatenate([[p.t0], normal.grid[normal.grid > p.t0]])
            t_switch = first_root(self._stick_gap(p.sigma, p), grid, direction=-1)
            if t_switch is None or t_switch >= t_f * (1.0 - END_SLACK):
                return replace(p, t1=t_f), None
            done = replace(p, t1=t_switch)
            v, omega, x = (float(q) for q in self._evaluate(done, t_switch))
            spring = -p.sigma * float(self.cap(t_switch)) + float(self.dashpot(t_switch)) * (v - omega * s.radius)
            return done, CompliantPhase(STICKING, t_switch, t_f, v, omega, x, force0=spring)
        w, opts = self._w, self._options
        slip0, inverse_mass = p.v0 - p.omega0 * s.radius, slip_per_impulse(s.mass, s.inertia_factor)
        fs, js = self._fs, self._js

        g_t = s.g_tangent

        root_m, t0, n = self._root_m, p.t0, self._n
        # k_t = kappa n k delta^(n - 1) (spring_stiffness) spelled out in the right-hand side, its constants read
        # here: it is called about a thousand times a contact, and the lookups per call were a third of its cost
        kappa, k, nk, rescale = s.kappa, float(s.k), n * s.k, self._rescale
        state = normal.state

        def rhs(tau, z):  # plain floats: DOP853-scalar's right-hand side; z[0] the spring's force F_s / fs
            t = tau / w
            delta, delta_dot = state(t)
            delta, delta_dot = float(delta), float(delta_dot)
            k_t = kappa * (k if n == 1.0 else nk * max(delta, 0.0) ** (n - 1.0))
            slip = slip0 + g_t * (t - t0) + inverse_mass * z[1] * js
            force = z[0] - root_m * math.sqrt(k_t) * slip / fs if root_m else z[0]  # F / fs
            rho = history_rate(rescale, n, delta, delta_dot)
            return [(-k_t * slip + rho * z[0] * fs) / (w * fs), force, z[1]]

        def total(tau, z):  # F / fs: the spring's force less the dashpot's
            if not root_m:
                return z[0]
            t = tau / w
            slip = slip0 + g_t * (t - p.t0) + inverse_mass * z[1] * js
            return z[0] - float(self.dashpot(t)) * slip / fs

        def upper(tau, z):  # F reaching +mu P+ (pushing the ball forward)
            return float(self.cap(tau / w)) / fs - total(tau, z)

        def lower(tau, z):  # F reaching -mu P+
            return float(self.cap(tau / w)) / fs + total(tau, z)

        for event in (upper, lower):
            event.terminal, event.direction = True, -1
        span = (p.t0 * w, t_f * w)
        z0, max_step = [p.force0 / fs, 0.0, 0.0], (span[1] - span[0]) / STICK_STEPS
        sol = self._compiled_stick(slip0, p.t0, span, z0, max_step, (upper, lower))
        if sol is None:
            sol = dop853.solve(rhs, span, z0, opts.rtol, opts.atol, events=(upper, lower), max_step=max_step)
            normal.spend_in_floats(sol.nfev)  # towards loading the compiled run, which gives the same bits
        if sol.status == -1:
            raise ImpactError(f"tangential stick phase: solver failed: {sol.message}")
        p = replace(p, solution=sol.sol)
        hits = [(float(times[0]), i) for i, times in enumerate(sol.t_events) if len(times)]
        if not hits:
            return replace(p, t1=t_f), None
        tau_switch, which = min(hits)
        t_switch = tau_switch / w
        if t_switch >= t_f * (1.0 - END_SLACK):
            return replace(p, t1=t_f), None
        done = replace(p, t1=t_switch)
        v, omega, x = (float(q) for q in self._evaluate(done, t_switch))
        force = float(self._stick_force(done, t_switch))
        sigma = -1.0 if which == 0 else 1.0  # F = +cap: the contact slips backwards
        if force == 0.0:  # the cap closed to zero with F: slip goes the contact point's way
            sigma = 1.0 if v - omega * s.radius >= 0 else -1.0
        return done, CompliantPhase(SLIDING, t_switch, t_f, v, omega, x, sigma=sigma)

    def _compiled_stick(self, slip0: float, t0: float, span, z0, max_step: float, events):
        """A stick phase's DOP853 run compiled (:func:`.stick_kernel.stick`): the Python run's steps, events and dense
        output to the bit.  None where the normal motion has no compiled form (a process that integrates in Python
        floats, a closed form with gravity, a scipy method) or an event's root had no bracket on its step: the Python
        run then runs (and raises there as it should)."""
        state = self.normal.kernel_state()
        if state is None:
            return None
        from . import stick_kernel as kernel

        s, n = self.scene, self._n
        spring = np.array([self._w, s.kappa, float(s.k), n * s.k, n, self._root_m, slip0, s.g_tangent, t0,
                           slip_per_impulse(s.mass, s.inertia_factor), self._js, self._fs, s.mu], dtype=float)
        ts, ys, coefficients, g, nfev, status, roots, where = kernel.stick(
            state.arrays(), state.force, state.params, spring, RESCALE.index(self._rescale), float(span[0]),
            float(span[1]), np.array(z0, dtype=float), float(self._options.rtol), float(self._options.atol),
            float(max_step))
        if status == kernel.NO_ROOT:
            return None
        return dop853.located(events, ts, ys, coefficients, g, int(nfev), int(status), dop853.MESSAGES[int(status)],
                              dict(zip(map(tuple, where.tolist()), roots.tolist())))

    def _stick_force(self, p: CompliantPhase, t):
        """F [N] of a sticking phase at t: the spring's force less the dashpot's."""
        spring = p.solution(np.asarray(t, dtype=float) * self._w)[0] * self._fs
        if not self._root_m:
            return spring
        v, omega = self._evaluate(p, t, with_x=False)
        return spring - self.dashpot(t) * (v - omega * self.scene.radius)

    def _evaluate(self, p: CompliantPhase, t, with_x: bool = True):
        """(v_t [m/s], omega [rad/s], x_t [m]) at t within phase p; (v_t, omega) only without ``with_x``
        (the stick-gap search, which needs no K+)."""
        s = self.scene
        t = np.asarray(t, dtype=float)
        dt = t - p.t0
        if p.mode == STICKING:
            z = p.solution(t * self._w)
            impulse, integral = z[1] * self._js, z[2] * self._js / self._w
        else:
            j0 = self.jp(p.t0)
            impulse = -p.sigma * s.mu * (self.jp(t) - j0)
            integral = (-p.sigma * s.mu * (self.jp.integral(t) - self.jp.integral(p.t0) - j0 * dt)
                        if with_x else None)
        return from_impulse(s, p, dt, impulse, integral if with_x else None)

    def at(self, t):
        """Tangential centre velocity v_t [m/s], spin omega [rad/s] and displacement x_t [m] at t [s]."""
        return by_phase(self.phases, t, self._evaluate, (3,))

    def force(self, t):
        """Tangential contact force F on the ball [N] at t [s] (negative: against the down-slope motion)."""
        def phase_force(p, instants):
            return self._stick_force(p, instants) if p.mode == STICKING else -p.sigma * self.cap(instants)

        return by_phase(self.phases, t, phase_force)


LINEAR = TANGENTIALS.register(TangentialModel(
    "linear", doc="spring k_t = kappa k capped by mu P, linear-spring laws", stiffness="k_t = kappa k, constant",
    parameters=(KAPPA, POISSON, DASHPOT_COR), spring=Spring.LINEAR,
    motion=lambda normal, options: CompliantTangential(normal, options, rescale="never", dashpot=True),
    scale_free=True))
MINDLIN = TANGENTIALS.register(TangentialModel(
    "mindlin", doc="k_t = 8 G* a on force increments, rescaled while unloading, capped by mu P, Hertz laws",
    stiffness="k_t = 8 G* a",
    parameters=(KAPPA, POISSON, SHEAR_MODULUS, DASHPOT_COR), spring=Spring.HERTZ,
    motion=lambda normal, options: CompliantTangential(normal, options, rescale="unloading", dashpot=True),
    scale_free=True))
MINDLIN_DISPLACEMENT = TANGENTIALS.register(TangentialModel(
    "mindlin-displacement", doc="k_t = 8 G* a on the total displacement, capped by mu P, Hertz laws",
    stiffness="F = -8 G* a xi", parameters=(KAPPA, POISSON, SHEAR_MODULUS), spring=Spring.HERTZ,
    motion=lambda normal, options: CompliantTangential(normal, options, rescale="always"), scale_free=True))
