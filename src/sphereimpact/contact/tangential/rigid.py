"""Tangential velocity, spin and displacement from the normal impulse (reduced model).

No ODE is integrated here.  Friction is Coulomb: while the contact point slips
in direction sigma (sigma = sign of the slip s = v_t - omega R, +1 forward) the
flat pushes against it with mu P+, where P+ = max(P, 0) (a tensile force, which
the kelvin-voigt law produces before delta returns to zero, presses nothing and
so carries no friction).  So with J+(t) the integral of P+ and K+(t) the
integral of J+, over a sliding phase that starts at t0:

    v_t(t)   = v_t0 + g_t (t - t0) - sigma mu (J+(t) - J+(t0)) / m
    omega(t) = omega0 + sigma mu R (J+(t) - J+(t0)) / I
    x_t(t)   = x_t0 + v_t0 (t - t0) + g_t (t - t0)^2 / 2 - sigma mu (K+(t) - K+(t0) - J+(t0)(t - t0)) / m

Incoming spin omega_0 sets the first slip, v_t - omega_0 R: topspin can make it
negative (the flat then drives the ball forward) or zero (the ball rolls from
the start).  The ball grips when s reaches zero, found as a root on the normal motion's
dense output (no sign() in any right-hand side).  While rolling, v_t = omega R
and the friction needed is m g_t alpha / (1 + alpha) (zero without gravity);
the ball slips again when mu P+ falls below that.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, replace

import numpy as np

from ...ode.dense import SMALL, is_instant
from ...errors import ImpactError
from ...ode.events import first_root, raise_failed
from ...ode.roots import falling_root
from ..motion import NormalMotion
from .base import TANGENTIALS, Regime, SweptTangential, TangentialModel, slip_per_impulse

#: More mode switches than this in one contact means something is wrong.
MAX_PHASES = 50


@dataclass(frozen=True)
class Phase:
    """One sliding or rolling interval [t0, t1] [s], the tangential state at t0 (SI), and the direction of
    slip ``sigma`` of a sliding phase (+1: the contact point slips forward, friction F = -sigma mu P+)."""

    mode: str
    t0: float
    t1: float
    v0: float
    omega0: float
    x0: float
    sigma: float = 1.0


def phase_index(phases, t) -> np.ndarray:
    """Index of the phase (objects with ``t0``, in time order) that holds each instant of the array t."""
    starts = np.array([p.t0 for p in phases])
    return np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(phases) - 1)


def by_phase(phases, t, evaluate, rows: tuple = ()) -> np.ndarray:
    """``evaluate(phase, instants)`` on each phase's share of the instants t [s], assembled in t's order.

    ``rows`` is the leading shape of what ``evaluate`` returns per instant (``(3,)`` for v_t, omega, x_t).
    """
    t = np.atleast_1d(np.asarray(t, dtype=float))
    out, which = np.zeros((*rows, t.size)), phase_index(phases, t)
    for i, p in enumerate(phases):
        mask = which == i
        if mask.any():
            out[..., mask] = evaluate(p, t[mask])
    return out


def kick(v, omega, impulse, mass, radius, alpha):
    """(v + J_t / m, omega - J_t R / I): the centre's velocity [m/s] and spin [rad/s] after a tangential impulse
    J_t [N s] at the contact point, I = alpha m R^2 (written J_t / (alpha m R): no R^2 to underflow).

    The impulse algebra, once: the single impact's phases (:func:`from_impulse`), the sweep's and the
    references' end states (:func:`impulse_outcome`) all call it.  Floats or arrays.
    """
    return v + impulse / mass, omega - impulse / (alpha * mass * radius)


def from_impulse(scene, p, dt, impulse, integral=None):
    """(v_t [m/s], omega [rad/s]) and, given ``integral``, x_t [m], at dt [s] into phase p from the tangential
    impulse on the ball since its start (``impulse`` J_t [N s]) and that impulse's time integral (K_t [N s^2]):

        v = v0 + g_t dt + J_t / m,   omega = omega0 - J_t R / I,   x = x0 + v0 dt + g_t dt^2 / 2 + K_t / m.

    How the rigid (J_t = -mu dJ+) and the compliant tangential motions turn impulse into motion
    (:func:`kick`, with gravity along the flat).
    """
    s = scene
    v, omega = kick(p.v0 + s.g_tangent * dt, p.omega0, impulse, s.mass, s.radius, s.inertia_factor)
    if integral is None:
        return v, omega
    return v, omega, p.x0 + p.v0 * dt + 0.5 * s.g_tangent * dt * dt + integral / s.mass


def impulse_outcome(v_t, spin, impulse, mass, radius, alpha, mu):
    """The rigid contact's end state from the friction-carrying normal impulse alone (no gravity along the
    flat): the one impulse algebra of the single impact's references and the sweep's fast paths.

    The contact slides throughout when mu (1 + 1/alpha) J+ / m < |s0| (s0 = v_t - spin R, its first slip);
    otherwise it grips and rolls with the angular momentum about the contact point kept.

    Parameters
    ----------
    v_t, spin : float or array
        Incoming tangential velocity of the centre [m/s] and spin [rad/s].
    impulse : float or array
        J+, the integral of the positive normal force over the contact [N s].
    mass, radius, alpha, mu : float or array
        Ball mass [kg], radius [m], inertia factor I / (m R^2) and friction coefficient.

    Returns
    -------
    vc_t, omega, ve_t, slides : arrays
        Rebound tangential velocity of the centre [m/s], spin [rad/s], of the contact point [m/s] (0 when it
        rolls), and whether the contact slid throughout.
    """
    slip0 = np.asarray(v_t - spin * radius)
    sigma = np.where(slip0 < 0, -1.0, 1.0)  # the direction the contact point first slips
    slides = mu * slip_per_impulse(mass, alpha) * impulse < np.abs(slip0)
    slid_v, slid_omega = kick(v_t, spin, -sigma * mu * impulse, mass, radius, alpha)
    vc_t = np.where(slides, slid_v, (v_t + alpha * radius * spin) / (1.0 + alpha))  # rolling: L about the contact
    omega = np.where(slides, slid_omega, vc_t / radius)
    return vc_t, omega, np.where(slides, vc_t - omega * radius, 0.0), slides


def _at(f, t) -> np.ndarray:
    """f at the instants of the array t, one instant at a time for a few (the scalar path is cheaper)."""
    if t.size <= SMALL:
        return np.array([f(instant) for instant in t.tolist()], dtype=float)
    return np.asarray(f(t), dtype=float)


def pushing_throughout(normal: NormalMotion) -> tuple[float, float, float] | None:
    """(0, t_f, J(0)) [s, s, N s] where the force criterion's force pushes over all of [0, t_f] (P(t_m) > 0, t_f > 0):
    :meth:`PositiveImpulse.one_interval` read off the motion without building the PositiveImpulse (what a compiled
    reader of J+ needs of it); None where that takes the PositiveImpulse's cuts (the penetration criterion's force may
    pull), not a different answer."""
    if normal.scene.separation.on_force and _pushes_at_maximum(normal):
        return 0.0, normal.t_f, float(normal.impulse(0.0))
    return None


def _pushes_at_maximum(normal: NormalMotion) -> bool:
    """Whether the contact lasts and the force pushes at maximum compression: where it has no sign change on (0, t_f),
    it pushes throughout."""
    return normal.t_f > 0.0 and normal.force(normal.t_m) > 0


def push_terms(normal: NormalMotion, pushing: tuple | None) -> tuple | None:
    """:meth:`PositiveImpulse.kernel_terms` of the one pushing interval ``pushing`` (a, b, J(a)) of ``normal``: None where
    the motion has no kernel state or ``pushing`` is None."""
    state = None if pushing is None else normal.kernel_state()
    if state is None:
        return None
    scene = normal.scene
    numbers = np.array([*pushing, scene.mass, scene.v_normal, scene.g_normal], dtype=float)
    return state.arrays(), state.force, state.params, numbers


class PositiveImpulse:
    """J+(t) and K+(t): the impulse of max(P, 0) and its time integral.

    P changes sign only at its roots on (0, t_f); on each interval where it is
    positive J+ follows the exact impulse J(t) of the normal motion, elsewhere
    it stays constant.  Evaluation is vectorised over the intervals (cumulative
    sums and a binary search), so a contact whose force flickers about zero
    thousands of times (a slow creep back to delta = 0) costs no more than a few.
    """

    def __init__(self, normal: NormalMotion):
        self._n = normal
        # Under the force criterion contact ends at the first P = 0: P >= 0 all along, nothing to cut
        inner = [] if normal.scene.separation.on_force else normal.force_roots()
        # without a sign change on (0, t_f) the force there has the sign it has at maximum compression, inside
        if not inner and _pushes_at_maximum(normal):
            self._one_interval(normal.t_f)  # the force criterion's: _cut's arrays for one interval, in floats
        else:
            self._cut(inner)

    def _cut(self, inner: list) -> None:
        """The intervals where P > 0 between the force's sign changes ``inner`` [s]: J and K at their ends, J+ and K+ at
        their starts, as arrays (any number of intervals)."""
        normal = self._n
        cuts = [0.0] + inner + [normal.t_f]
        cuts = np.array(sorted(set(c for c in cuts if c <= normal.t_f)))
        mids = 0.5 * (cuts[:-1] + cuts[1:])
        positive = _at(normal.force, mids) > 0
        self._a, self._b = cuts[:-1][positive], cuts[1:][positive]
        self.intervals = list(zip(self._a.tolist(), self._b.tolist()))
        if positive.all() and cuts.size <= SMALL:  # intervals tiling [0, t_f] (the force criterion's one): J and K
            # at each cut once, each instant as _at reads it alone
            j, k = _at(normal.impulse, cuts), _at(normal.impulse_integral, cuts)
            (self._ja, self._jb), (self._ka, self._kb) = (j[:-1], j[1:]), (k[:-1], k[1:])
        else:
            self._ja, self._jb = _at(normal.impulse, self._a), _at(normal.impulse, self._b)
            self._ka, self._kb = _at(normal.impulse_integral, self._a), _at(normal.impulse_integral, self._b)
        gained = self._jb - self._ja  # J+ gained over each interval
        self._before = np.concatenate([[0.0], np.cumsum(gained)])  # J+ at each interval's start, and at the end
        # K+ at each interval's start: the previous intervals' pieces plus the constant stretches between them
        pieces = (self._before[:-1] - self._ja) * (self._b - self._a) + self._kb - self._ka
        gaps = self._before[1:-1] * (self._a[1:] - self._b[:-1])
        self._k_start = np.concatenate([[0.0], np.cumsum(pieces[:-1] + gaps)]) if self._a.size else np.zeros(0)

    def _one_interval(self, t_f: float) -> None:
        """The arrays of ``__init__`` for the force pushing over all of [0, t_f], each value as it computes them: J and K
        read at 0 and t_f one instant at a time, J+ gained, and K+ at the start 0."""
        normal = self._n
        (j0, j1), (k0, k1) = ([f(0.0), f(t_f)] for f in (normal.impulse, normal.impulse_integral))
        self.intervals = [(0.0, t_f)]
        self._a, self._b = np.array([0.0]), np.array([t_f])
        self._ja, self._jb, self._ka, self._kb = (np.array([float(value)]) for value in (j0, j1, k0, k1))
        self._before = np.array([0.0, float(self._jb[0] - self._ja[0])])
        self._k_start = np.zeros(1)

    def one_interval(self) -> tuple[float, float, float] | None:
        """(a, b, J(a)) [s, s, N s] of the one interval the force pushes over, J+ = J - J(a) on it; None for none or
        more (the penetration criterion's force may pull between pushes)."""
        if len(self.intervals) != 1:
            return None
        return (*self.intervals[0], float(self._ja[0]))

    def _locate(self, t):
        """Index of the last interval starting at or before each t (-1 before the first), and t clipped to it."""
        i = np.searchsorted(self._a, t, side="right") - 1
        j = np.maximum(i, 0)
        return i, j, np.clip(t, self._a[j], self._b[j])

    def __call__(self, t):
        """J+(t) [N s]."""
        if is_instant(t) and len(self.intervals) == 1:  # one instant, one pushing interval: J(t) - J(a)
            a, b = self.intervals[0]
            return float(self._n.impulse(min(max(float(t), a), b)) - self._ja[0]) if t > a else 0.0
        t = np.asarray(t, dtype=float)
        if not self._a.size:
            return np.zeros_like(t)
        i, j, c = self._locate(t)
        return np.where(i < 0, 0.0, self._before[j] + self._n.impulse(c) - self._ja[j])

    def from_impulse(self, t, impulse) -> np.ndarray:
        """J+ [N s] at the instants of the array t, given the normal impulse J [N s] there (:meth:`NormalMotion.impulse
        <sphereimpact.contact.motion.NormalMotion.impulse>`, read off a state the caller has already evaluated):
        the values of :meth:`__call__` to the bit, without evaluating the motion again (J at an instant inside a
        pushing interval is J(t); past one, its end's, which is kept)."""
        t = np.asarray(t, dtype=float)
        if not self._a.size:
            return np.zeros_like(t)
        i, j, c = self._locate(t)
        return np.where(i < 0, 0.0, self._before[j] + np.where(c == t, impulse, self._jb[j]) - self._ja[j])

    def instants(self, impulses) -> np.ndarray:
        """The first instants [s] at which J+ reaches each of ``impulses`` [N s] (0 for 0; t_f for an impulse
        J+ never reaches): bracketed on the solver's grid (J+ never decreases), then Newton's method on
        dJ+/dt = P+, kept inside the bracket (:func:`sphereimpact.ode.roots.falling_root`); J+ and P+ compiled
        (:func:`.rigid_kernel.positive_impulses`, :func:`~.rigid_kernel.impulse_gaps`) where the normal motion has a
        :meth:`~sphereimpact.contact.motion.NormalMotion.kernel_state` and its force pushes over one interval."""
        normal = self._n
        impulses = np.asarray(impulses, dtype=float)
        times = np.append(normal.grid[normal.grid < normal.t_f], normal.t_f)
        terms = self.kernel_terms()
        if terms is None:
            on_grid = self(times)
        else:
            from .rigid_kernel import impulse_gaps, positive_impulses

            arrays, force, params, pushing = terms
            on_grid = positive_impulses(arrays, pushing, times)
        upper = np.clip(np.searchsorted(on_grid, impulses, side="left"), 1, times.size - 1)
        low, high = times[upper - 1], times[upper]
        gap_low, gap_high = impulses - on_grid[upper - 1], impulses - on_grid[upper]
        inside = (gap_low > 0) & (gap_high <= 0)
        t = np.where(gap_high > 0, high, low)  # beyond J+(t_f): t_f; at a sample: that sample
        if inside.any():
            i = np.flatnonzero(inside)
            start = self._first_guess(times, on_grid, impulses[i], upper[i])
            # J+ is read off the motion's state, m (v0 - v): its round-off, a few ulp of m v0, ends the search
            f_tol = 8.0 * np.finfo(float).eps * normal.scene.mass * normal.scene.v_normal
            levels = impulses[i]
            gaps = ((lambda s: (levels - self(s), -np.maximum(normal.force(s), 0.0))) if terms is None
                    else (lambda s: impulse_gaps(arrays, force, params, pushing, levels, s)))
            t[i] = falling_root(gaps, low[i], high[i], gap_low[i], gap_high[i], start=start, f_tol=f_tol)
        return np.where(impulses <= 0, 0.0, t)

    def kernel_terms(self) -> tuple | None:
        """(the normal motion's arrays, its law's compiled force kernel and parameters, the numbers of the one pushing
        interval, :data:`.rigid_kernel.PUSHING`) as :mod:`.rigid_kernel` takes them, or None where the motion has no
        :meth:`~sphereimpact.contact.motion.NormalMotion.kernel_state` or the force pushes over more than one
        interval (the Python searches then serve, to the same bits)."""
        return push_terms(self._n, self.one_interval())

    def _first_guess(self, times, on_grid, impulses, upper) -> np.ndarray:
        """Where J+ reaches each impulse, to start Newton from: the secant of its grid interval, but in the
        first interval, where J+ grows as a power p of the time (2 for a linear spring, 2.5 for Hertz), the
        power law through J+(t1) with p read off J+(t1 / 2) (the secant started Newton far to the left of a
        small impulse's instant, and it needed a dozen steps to come back)."""
        low, high = times[upper - 1], times[upper]
        j_low, j_high = on_grid[upper - 1], on_grid[upper]
        with np.errstate(invalid="ignore", divide="ignore"):
            guess = low + (impulses - j_low) / (j_high - j_low) * (high - low)
            first = upper == 1
            if first.any() and on_grid[1] > 0:
                half = float(self(0.5 * times[1]))
                power = np.log2(on_grid[1] / half) if half > 0 else 1.0
                guess = np.where(first, times[1] * (impulses / on_grid[1]) ** (1.0 / power), guess)
        return np.clip(guess, low, high)

    def integral(self, t):
        """K+(t) = integral of J+ from 0 to t [N s^2]."""
        if is_instant(t) and len(self.intervals) == 1:  # one instant, one pushing interval: plain floats
            (a, b), t = self.intervals[0], float(t)
            if t <= a:
                return 0.0
            c, ja = min(t, b), float(self._ja[0])  # the array path's arithmetic, in its order
            inside = -ja * (c - a) + float(self._n.impulse_integral(c)) - float(self._ka[0])
            return inside + (float(self._jb[0]) - ja) * max(t - b, 0.0)
        t = np.asarray(t, dtype=float)
        if not self._a.size:
            return np.zeros_like(t)
        i, j, c = self._locate(t)
        inside = (self._k_start[j] + (self._before[j] - self._ja[j]) * (c - self._a[j])
                  + self._n.impulse_integral(c) - self._ka[j])
        after = self._before[j + 1] * np.maximum(t - self._b[j], 0.0)
        return np.where(i < 0, 0.0, inside + after)


def _grid_from(normal: NormalMotion, t0: float) -> np.ndarray:
    """The normal motion's grid [s] from t0 on: t0, then its instants after it."""
    return np.concatenate([[t0], normal.grid[normal.grid > t0]])


class TangentialMotion:
    """Tangential motion and spin of the ball over the contact of ``normal``.

    Parameters
    ----------
    normal : NormalMotion
        A solved normal motion; its scene must have tangential motion (angle > 0).

    Attributes
    ----------
    phases : list of Phase
        Sliding and rolling intervals covering [0, t_f].
    t_roll : float or None
        First instant [s] the contact point stops slipping, None if it never does.
    regime : str
        ``sliding`` or ``rolling``: the mode at separation.
    switches : int
        Number of sliding/rolling switches.
    """

    def __init__(self, normal: NormalMotion):
        scene = normal.scene
        self.normal, self.scene = normal, scene
        self.jp = PositiveImpulse(normal)
        m, mu, alpha = scene.mass, scene.mu, scene.inertia_factor
        self._hold = m * scene.g_tangent * alpha / (1.0 + alpha)  # friction needed to keep rolling [N]
        slip0 = scene.slip0
        if slip0 != 0 or self._hold > 0:  # no normal force yet to hold the ball against gravity: it slips down
            phase = Phase(Regime.SLIDING, 0.0, normal.t_f, scene.v_tangent, scene.spin, 0.0, -1.0 if slip0 < 0 else 1.0)
        else:  # the incoming spin rolls the ball from the start
            phase = Phase(Regime.ROLLING, 0.0, normal.t_f, scene.v_tangent, scene.spin, 0.0)
        self.phases, self.t_roll = [], None if phase.mode == Regime.SLIDING else 0.0
        while True:
            if phase.mode == Regime.SLIDING and self._slides_throughout(phase):
                t_switch = None
            elif phase.mode == Regime.SLIDING:  # sigma s falls through zero when the contact point stops slipping
                t_switch = self._grip(phase, _grid_from(normal, phase.t0))
            elif self._hold > 0:
                t_switch = first_root(lambda t: mu * np.maximum(normal.force(t), 0.0) - self._hold,
                                      _grid_from(normal, phase.t0), direction=-1)
            else:
                t_switch = None
            if t_switch is None or t_switch >= normal.t_f:
                self.phases.append(phase)
                break
            self.phases.append(replace(phase, t1=t_switch))
            v, omega, x = (float(q) for q in self._evaluate(self.phases[-1], t_switch))
            if phase.mode == Regime.SLIDING:
                self.t_roll = t_switch if self.t_roll is None else self.t_roll
                phase = Phase(Regime.ROLLING, t_switch, normal.t_f, v, v / scene.radius, x)
            else:  # gravity along the flat outgrows friction: the contact point slips down-slope
                phase = Phase(Regime.SLIDING, t_switch, normal.t_f, v, omega, x, 1.0)
            if len(self.phases) >= MAX_PHASES:
                raise ImpactError(f"more than {MAX_PHASES} stick-slip switches in one contact")
        self.regime = self.phases[-1].mode
        self.switches = len(self.phases) - 1

    def _grip(self, p: Phase, grid: np.ndarray) -> float | None:
        """The first instant [s] on ``grid`` where sigma times the slip of sliding phase ``p`` falls through zero, or
        None: compiled (:func:`.rigid_kernel.grip`, the same instant to the bit) where the normal motion has a
        :meth:`~sphereimpact.contact.motion.NormalMotion.kernel_state` and its force pushes over one interval."""
        j0 = self.jp(p.t0)
        terms = self.jp.kernel_terms()
        if terms is None:
            return first_root(lambda t: p.sigma * self._slip(p, t, j0), grid, direction=-1)
        from .rigid_kernel import grip

        s = self.scene
        arrays, _, _, pushing = terms
        phase = np.array([p.sigma, s.mu, s.mass, s.radius, s.inertia_factor, p.v0, p.omega0, p.t0, s.g_tangent, j0])
        t, status, low, high = grip(arrays, pushing, phase, np.asarray(grid, dtype=float))
        raise_failed(status, lambda t: p.sigma * self._slip(p, t, j0), low, high)
        return None if math.isnan(t) else float(t)

    def _slides_throughout(self, p: Phase) -> bool:
        """Whether sliding phase ``p`` lasts to t_f, decided without a search where that is exact: from t = 0
        without gravity along the flat the slip s0 - sigma mu (1 + 1/alpha) J+ / m falls with J+ alone, so the
        contact slides throughout when J+(t_f) falls short (:func:`impulse_outcome`'s test, the sweep's);
        otherwise the grip is searched for on the dense output."""
        s = self.scene
        if s.g_tangent != 0 or p.t0 != 0:
            return False
        return s.mu * slip_per_impulse(s.mass, s.inertia_factor) * self.jp(self.normal.t_f) < abs(s.slip0)

    def _evaluate(self, p: Phase, t):
        """(v_t [m/s], omega [rad/s], x_t [m]) at t within phase p (floats for one instant)."""
        s = self.scene
        t = float(t) if is_instant(t) else np.asarray(t, dtype=float)
        dt = t - p.t0
        if p.mode == Regime.ROLLING:
            accel = s.g_tangent / (1.0 + s.inertia_factor)
            v = p.v0 + accel * dt
            return v, v / s.radius, p.x0 + p.v0 * dt + 0.5 * accel * dt * dt
        j0 = self.jp(p.t0)
        dk = self.jp.integral(t) - self.jp.integral(p.t0) - j0 * dt
        return from_impulse(s, p, dt, -p.sigma * s.mu * (self.jp(t) - j0), -p.sigma * s.mu * dk)

    def _slip(self, p: Phase, t, j0: float | None = None):
        """Slip velocity v_t - omega R [m/s] at t in sliding phase p (the velocities only: no K+; a float for
        one instant, which is how the root search calls it).  ``j0`` is J+ at the phase's start, if known."""
        s = self.scene
        t = float(t) if is_instant(t) else np.asarray(t, dtype=float)
        j0 = self.jp(p.t0) if j0 is None else j0
        v, omega = from_impulse(s, p, t - p.t0, -p.sigma * s.mu * (self.jp(t) - j0))
        return v - omega * s.radius

    def at(self, t):
        """Tangential centre velocity v_t [m/s], spin omega [rad/s] and displacement x_t [m] at t [s]
        (shape (3, len(t)))."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if t.size > SMALL:
            return by_phase(self.phases, t, self._evaluate, (3,))
        out, starts = np.empty((3, t.size)), [p.t0 for p in self.phases]
        for j, instant in enumerate(t.tolist()):  # a few instants: plain floats, the same phases and values
            which = min(max(bisect.bisect_right(starts, instant) - 1, 0), len(starts) - 1)  # phase_index's
            out[:, j] = self._evaluate(self.phases[which], instant)
        return out

    def force(self, t):
        """Friction force F on the ball along the flat [N] at t [s]: -mu P+ sliding, the holding force rolling."""
        def phase_force(p, instants):
            if p.mode == "sliding":
                return -p.sigma * self.scene.mu * np.maximum(self.normal.force(instants), 0.0)
            return np.full(instants.size, -self._hold)

        return by_phase(self.phases, t, phase_force)

    def friction_impulse(self) -> float:
        """Tangential impulse of friction over the contact [N s] (negative: it opposes slip)."""
        s = self.scene
        v_f = float(self.at(self.normal.t_f)[0, 0])
        return s.mass * (v_f - s.v_tangent - s.g_tangent * self.normal.t_f)


def grip_impulses(rows):
    """The normal impulse J+ [N s] at which the contact point stops slipping, m |s0| / (mu (1 + 1/alpha)), s0 =
    v_t - spin R its first slip: 0 where it rolls from the start, NaN where it never can (mu = 0)."""
    slip0 = rows.v_tangent - rows.spin * rows.radius
    with np.errstate(divide="ignore", invalid="ignore"):
        impulse = np.abs(slip0) / (rows.mu * slip_per_impulse(rows.mass, rows.inertia_factor))
    return np.where(slip0 == 0, 0.0, np.where(rows.mu > 0, impulse, np.nan))


def swept_end(rows, impulse, instants) -> dict:
    """The rigid contact's end state from J+ (:func:`impulse_outcome`), with the grip instant ``instants`` as
    t_roll where the contact grips (see :class:`~sphereimpact.contact.tangential.base.SweptTangential`)."""
    slip0 = rows.v_tangent - rows.spin * rows.radius
    vc_t, omega, _, slides = impulse_outcome(rows.v_tangent, rows.spin, impulse, rows.mass, rows.radius,
                                             rows.inertia_factor, rows.mu)
    return {"vc_t": vc_t, "omega_f": omega, "t_roll": np.where(slides, np.nan, instants),
            "switches": np.where(~slides & (slip0 != 0), 1, 0),
            "regime": np.where(slides, "sliding", "rolling").astype(object)}


RIGID = TANGENTIALS.register(TangentialModel(
    "rigid", doc="the chapter's: slips or rolls", stiffness="", parameters=(), spring=None,
    motion=lambda normal, options: TangentialMotion(normal), swept=SweptTangential(grip_impulses, swept_end)))
