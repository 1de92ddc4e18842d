"""The reduced model: the normal motion delta(t) of the ball during contact.

With a rigid flat and no tangential compliance the normal motion does not
depend on friction, so this is the only differential equation the reduced
model integrates:

    m delta'' = -P(delta, delta') + m g cos(beta),  delta(0) = 0,  delta'(0) = v cos(beta).

It is solved in dimensionless form, tau = t / T, x = delta / (v_n T), y = delta' / v_n with T the law's
natural contact time (1 / omega_n for a linear spring, see :class:`sphereimpact.contact.laws.ContactLaw`), so one
absolute tolerance suits every law, ball and speed.
Maximum compression and separation are located on the dense output by Brent's method
(:func:`sphereimpact.ode.roots.brent`, a few ulp).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..ode import series
from ..ode.dense import DOP853, SMALL, TAYLOR, StackedDOP853, fast_solution, is_instant
from ..contact.motion import KernelState, NormalMotion
from ..errors import ImpactError
from . import compiled as rule  # the rule of when this process integrates compiled (numba is not imported by it)
from .base import DEFAULT_INTEGRATOR, INTEGRATORS
from .event_kinds import EventKind

if TYPE_CHECKING:
    from ..impact.scene import Scene, SolverOptions

#: Samples per solver step used when scanning event functions on the dense output.
SUBSTEPS = 8
#: Ramp band of eq. 4.2: once in restitution with u = (c/R) delta below BAND_RESTART, the integration
#: restarts with steps of at most BAND_STEP / (lam max(|y|, BAND_SPEED)) in tau, since a step sized for the
#: slow motion can cross the whole switch of 1 - exp(-u) unseen by the error estimate.  Values from the
#: accuracy grid of tests/test_accuracy.py (lam 3-150, zeta 0.01-3, both criteria).
BAND_RESTART = 30.0
BAND_STEP = 4.0
BAND_SPEED = 0.25

#: Landing on t_f: at most LANDINGS steps ending there (Newton corrections in between); the root is
#: delta = 0 when |x(t_f)| < LANDING_DELTA x_m and the force does not pull at delta = 0 (it stays positive down to
#: there and jumps), else P = 0 inside contact (a lightly damped law's root lies within LANDING_DELTA of delta = 0:
#: kelvin-voigt at zeta 5e-8 ended 3.4e-8 of t_f late when it landed on delta = 0).
LANDINGS = 4
LANDING_DELTA = 1e-6
#: Most right-hand-side evaluations one normal motion may take: a bound on any input's cost, far above what
#: the accepted domain needs (an over-damped contact held until delta = 0 needs about zeta^2).
MAX_NFEV = 1_000_000


class _Budget(Exception):
    """The right-hand side was called more than MAX_NFEV times."""


def substep_grid(steps: np.ndarray) -> np.ndarray:
    """Each step of ``steps`` (its boundaries, ascending) split into SUBSTEPS equal parts: sample times fine
    enough to bracket every event, the last boundary left out."""
    return (steps[:-1, None] + (steps[1:] - steps[:-1])[:, None] * _FRACTIONS).ravel()


def contact_grid(steps: np.ndarray, t_f: float) -> np.ndarray:
    """A motion's ``grid`` [s]: the substeps of ``steps`` [s] (:func:`substep_grid`) before t_f, then t_f."""
    grid = substep_grid(steps)
    return np.concatenate((grid[grid < t_f], (t_f,)))


#: The substeps' fractions of a step (:func:`substep_grid`), made once.
_FRACTIONS = np.linspace(0.0, 1.0, SUBSTEPS, endpoint=False)


def separation_function(scene: Scene):
    """The function of (delta, delta_dot) whose fall through zero ends contact.

    ``penetration``: delta.  ``force``: the first of P = 0 and delta = 0, as P inside contact and -1 outside.
    P alone would not do: it is exactly 0 for every delta <= 0, so a root search could stop anywhere past
    separation.  Nor would delta outside: where P pulls before delta returns to 0, P ~ delta (k + c b
    delta_dot / R) -> 0- and delta -> 0-, so the function would touch zero at delta = 0 without crossing,
    and when one step held both points Brent's search could stop on that touch instead of the crossing of
    P (at 2.345 m/s it did, and t_f flipped by 0.7 % on a 1-ulp change of speed).  Strictly negative
    outside, the function crosses zero once: at P = 0, or at delta = 0 by a jump when P stays positive.
    """
    if scene.separation.pulls:
        return lambda delta, delta_dot: delta
    return lambda delta, delta_dot: np.where(np.asarray(delta) > 0, scene.force(delta, delta_dot), -1.0)


def scalar_separation_function(scene: Scene):
    """:func:`separation_function` for one state in Python floats: by the law's scalar formula (``ContactLaw.scalar``,
    on the reduced sphere as ``Scene.stage_force`` takes it) where it declares one, else :func:`separation_function`
    itself."""
    if scene.law.scalar is None:
        return separation_function(scene)
    if scene.separation.pulls:
        return lambda delta, delta_dot: delta
    law, reduced = scene.law.scalar, scene.reduced
    return lambda delta, delta_dot: law(delta, delta_dot, reduced) if delta > 0 else -1.0


def _step_end(dense) -> float:
    """Where the last step of a dense output would have ended (a terminal event cuts ``ts`` at its root)."""
    if isinstance(dense, StackedDOP853):
        return float(dense.t_old[-1] + dense.h[-1])
    return float(dense.interpolants[-1].t)


def _join(first, later):
    """One dense output: ``first`` up to ``later``'s start, then ``later`` (stacked or OdeSolution)."""
    if isinstance(first, StackedDOP853) and isinstance(later, StackedDOP853):
        return first.join(later)
    from scipy.integrate import OdeSolution  # imported on use (see integrators.runge_kutta._scipy)

    keep = int(np.searchsorted(first.ts, later.ts[0], side="left"))
    return OdeSolution(np.concatenate([first.ts[:keep], later.ts]), first.interpolants[:keep] + later.interpolants)


def no_separation_message(scene: Scene, t_end: float) -> str:
    """One line explaining a contact that never ends under the chosen criterion."""
    what = f"{scene.separation.end_quantity} never returns to 0"
    hint = " (try --separation force)" if scene.separation.pulls else ""
    when = (f"within {t_end:.3g} s" if np.isfinite(t_end)
            else "(an over-damped contact: it decays to 0 only asymptotically)")
    return (f"no separation: {what} {when} under the '{scene.separation}' criterion "
            f"({describe_family(scene)}gravity {scene.gravity:g} m/s^2){hint}")


def describe_family(scene: Scene) -> str:
    """The scene's dimensionless numbers as ``"zeta = 0.0567, lam = 16.3, "`` for messages."""
    return "".join(f"{name} = {value:.3g}, " for name, value in scene.family.items())


def check_rebound(scene: Scene, options: SolverOptions, rate: float) -> None:
    """Reject a numerical separation whose rebound is at the integrator's noise level.

    A ball that comes to rest in contact (e.g. critically damped under the
    ``penetration`` criterion, where delta -> 0 only asymptotically) can cross
    zero numerically once delta is below the tolerance: that is not a rebound.
    The threshold is 10 atol on the dimensionless rebound speed (rtol does not
    set it: at rtol 1e-2 a real rebound of 0.81 must still count).

    Parameters
    ----------
    rate : float
        delta_dot at the detected separation [m/s].
    """
    noise = 10.0 * options.atol  # the state is O(1) dimensionless: atol is its absolute noise level
    if -rate / scene.v_normal <= noise:
        raise ImpactError(
            f"no separation: the rebound found ({-rate / scene.v_normal:.2g} of the approach speed) is below "
            f"what the tolerances resolve ({noise:.2g}): either the ball comes to rest in contact under the "
            f"'{scene.separation}' criterion, or that criterion is ill-conditioned at this damping "
            f"({describe_family(scene).rstrip(', ')}); tighten rtol and atol to tell")


#: Tightest tolerances the conditioning scale may reach (SolverOptions' own floor for rtol).
RTOL_FLOOR, ATOL_FLOOR = 1e-13, 1e-16
#: Largest damping ratio whose tolerances are tightened: the accuracy contract's domain (zeta <= 100).
#: Far beyond it the contact stops within a stiff transient and the tightened integration only turns
#: round-off into a spurious rebound (b = 1e300: COR 1.1e-9 at rtol 1e-13, refused as noise at 1e-10).
CONDITIONED_ZETA_MAX = 100.0


def conditioned_tolerances(scene: Scene, options: SolverOptions, floor: float = RTOL_FLOOR,
                           power: int = 1) -> tuple[float, float]:
    """(rtol, atol) for the integration: the options', tightened where the outputs are ill-conditioned.

    Over-damped (zeta > 1) under the force criterion, contact ends where P = k delta + b delta_dot r falls
    to zero while its two terms are about 4 zeta^2 times larger than their difference (on the slow mode,
    P / (k delta) ~ (r1 / omega_n)^2 ~ 1 / (4 zeta^2)), so t_f carries about 4 zeta^2 times the state's
    error (measured: 2e-9 to 7e-9 at zeta = 3 and rtol 1e-10).  There the tolerances are divided by 4
    zeta^2 (to the ``power``: the Taylor method needs 2, see :class:`TaylorNormal`), down to ``floor``
    (1e-13, what DOP853 honours; the Taylor method goes down to 1e-16), up to zeta =
    :data:`CONDITIONED_ZETA_MAX`: only such scenes pay, by about (4 zeta^2)^(1/8) in steps (1.6x at zeta = 3).
    The outcome reports the tolerances asked for.
    """
    zeta = scene.family.get("zeta")
    if not scene.separation.on_force or zeta is None or not 1.0 < zeta <= CONDITIONED_ZETA_MAX:
        return options.rtol, options.atol
    scale = (4.0 * zeta * zeta) ** -power
    return max(options.rtol * scale, floor), max(options.atol * scale, ATOL_FLOOR)


def conditioned_step(scene: Scene) -> float:
    """Largest dimensionless step where :func:`conditioned_tolerances` tightens the tolerances, else inf.

    Once those reach their floor (zeta above about 16), t_f still erred by up to 1.4e-9 (zeta 100, lam 150,
    against the 30-digit Taylor reference): steps across the fast mode's decay, time scale 1 / (2 zeta),
    kept too little of the state's accuracy.  Steps of at most 1 / (4 zeta) bring it to 1.5e-11, for 6 %
    more evaluations there (1 / (2 zeta): 1.1e-9; measured at zeta 10-100, lam 75-150).
    """
    zeta = scene.family.get("zeta")
    if not scene.separation.on_force or zeta is None or not 1.0 < zeta <= CONDITIONED_ZETA_MAX:
        return math.inf
    return 1.0 / (4.0 * zeta)


def horizon(scene: Scene) -> float:
    """Longest contact [s] searched for a separation before giving up: the law's dimensionless horizon times T.

    Far beyond any contact that ends: for a linear spring 100 undamped half-periods, stretched by the
    damping ratio for over-damped scenes (their slow mode decays at about omega_n / (2 zeta)).
    """
    return float(scene.law.horizon(scene)) / scene.frequency


#: The dense outputs read at one instant in plain floats, and by the compiled kernels (DOP853's and the Taylor method's).
_PLAIN_FLOAT_DENSE = (StackedDOP853, series.TaylorDense)


class CompiledReads:
    """What a normal motion that compiled code can read adds to :class:`~sphereimpact.contact.motion.NormalMotion`: its
    :class:`~sphereimpact.contact.motion.KernelState`, built once (kept) in a process that integrates compiled
    (:func:`.compiled.compiled_now`), and its evaluations in Python floats counted towards loading the compiled code.
    A subclass says whether compiled code can read it (``_has_kernel_state``) and builds the arrays
    (``_kernel_state``)."""

    def _has_kernel_state(self) -> bool:
        raise NotImplementedError

    def _kernel_state(self) -> KernelState:
        raise NotImplementedError

    def kernel_state(self):
        if not self._has_kernel_state():
            return None
        return self.kept("kernel state", self._kernel_state) if rule.compiled_now() else None

    def spend_in_floats(self, evaluations: int) -> None:
        if self._has_kernel_state():
            rule.spend_in_floats(evaluations)

    def _compiled_states(self, t):
        """(delta [m], delta_dot [m/s]) at the instants of the 1-d array t [s] by compiled code
        (:func:`~sphereimpact.contact.normal_kernel.normal_states`, the Python evaluation's values to the bit), or None
        where :meth:`kernel_state` has no compiled form of the motion."""
        kernel = self.kernel_state()
        if kernel is None:
            return None
        from ..contact.normal_kernel import normal_states

        return normal_states(kernel.arrays(), np.ascontiguousarray(t, dtype=float))


#: The arrays of a KernelState that its kind does not use, empty (shared: nothing can be written into them).
_NONE, _NO_COEFFICIENTS, _NO_ROWS, _NO_STATES = np.empty(0), np.empty((0, 0)), np.empty((0, 7, 2)), np.empty((0, 2))


class _DimensionlessNormal(CompiledReads, NormalMotion):
    """A normal motion held as a dense solution of the dimensionless state (tau = omega t, x = delta / d_scale,
    y = delta_dot / v): subclasses set ``_sol``, ``_w`` (omega [1/s]), ``_d_scale`` [m] and ``_v`` [m/s]."""

    def _has_kernel_state(self) -> bool:
        """Whether compiled code can read this motion: its law has a kernel and the scalar formula it compiles, and
        its dense output is one the kernels evaluate."""
        law = self.scene.law
        return law.kernel is not None and law.scalar is not None and isinstance(self._sol, _PLAIN_FLOAT_DENSE)

    def _kernel_state(self) -> KernelState:
        """Its dense output's arrays and its law's checked kernel."""
        sol, scene, none = self._sol, self.scene, _NONE
        if isinstance(sol, StackedDOP853):
            kind, knots, starts, sizes = DOP853, sol.ts, sol.t_old, sol.h
            cx = cy = _NO_COEFFICIENTS
            f, y_old = np.ascontiguousarray(sol.f[:, ::-1]), np.ascontiguousarray(sol.y_old)
        else:
            (starts, knots, cx, cy), kind, sizes = sol.pieces(), TAYLOR, none
            f, y_old = _NO_ROWS, _NO_STATES
        return KernelState(kind, np.ascontiguousarray(knots, dtype=float), np.ascontiguousarray(starts, dtype=float),
                           np.ascontiguousarray(sizes, dtype=float), cx, cy, f, y_old, float(self._w),
                           float(self._d_scale), float(self._v), rule.checked_kernel(scene, (self._d_scale, self._v)),
                           np.array(scene.law.kernel.parameters(scene), dtype=float))

    def state(self, t):
        if isinstance(self._sol, _PLAIN_FLOAT_DENSE):
            if is_instant(t):  # in plain floats
                t = float(t)
                known = self.kept("states", dict)  # t = 0, t_m and t_f are read many times: each state kept (see kept)
                if t not in known:
                    x, y = self._sol.single(t * self._w)
                    known[t] = (x * self._d_scale, y * self._v)
                return known[t]
            # a few instants (t_m and t_f): each one's kept state, what the dense output's few-instant path computes
            if np.ndim(t) == 1 and 0 < len(t) <= SMALL:
                delta, delta_dot = zip(*[self.state(instant) for instant in np.asarray(t, dtype=float).tolist()])
                return np.array(delta), np.array(delta_dot)
            compiled = self._compiled_states(t) if np.ndim(t) == 1 else None
            if compiled is not None:  # many instants (a microslip march's steps): compiled, the same values to the bit
                return compiled
        z = self._sol(np.asarray(t, dtype=float) * self._w)
        return z[0] * self._d_scale, z[1] * self._v


class _RightHandSide:
    """x' = y, y' = -P / (m omega v) + gamma at (tau, [x, y]), under the evaluation budget (:data:`MAX_NFEV`).

    A compiled stepper does not call it: it reads the scene (its law's kernel) and ``scales`` (d = v_n T [m],
    v_n [m/s], m v_n / T [N], gamma) and integrates the same equation, and reports its evaluations to
    :meth:`spend`."""

    def __init__(self, scene: Scene, d_scale: float, v: float, p_scale: float, gamma: float, law, scalar):
        self.scene, self.scales = scene, (d_scale, v, p_scale, gamma)
        self._law, self._scalar = law, scalar
        self.calls = 0

    def __call__(self, tau, z):
        self.spend(1)
        d_scale, v, p_scale, gamma = self.scales
        x, y = float(z[0]), float(z[1])
        scalar = self._scalar
        force = scalar(x * d_scale, y * v, self.scene) if scalar is not None else self._law(x * d_scale, y * v)
        return [y, -force / p_scale + gamma]

    def spend(self, calls: int) -> None:
        """Count ``calls`` evaluations; :class:`_Budget` past :data:`MAX_NFEV`."""
        self.calls += calls
        if self.calls > MAX_NFEV:
            raise _Budget

    @property
    def left(self) -> int:
        """Evaluations left in the budget."""
        return MAX_NFEV - self.calls


class _Run:
    """The dimensionless normal ODE x' = y, y' = -P / (m omega v) + gamma as one integrator runs it: the
    right-hand side under the evaluation budget (:data:`MAX_NFEV`), the events, the conditioned tolerances and
    the integrator's stepper (``Integrator.stepper``; a plain-float one runs as its ``ivp`` method for a law
    without a scalar formula)."""

    def __init__(self, scene: Scene, options: SolverOptions):
        self.scene = scene
        self.w, self.v = w, v = scene.frequency, scene.v_normal
        self.d_scale = d_scale = v / w
        gamma, p_scale = scene.g_normal / (w * v), scene.mass * w * v
        law = scene.stage_force  # smooth past separation: the crossing step stays accurate
        scalar = scene.law.scalar  # the same law without numpy's per-call cost, when the law has one
        integrator = INTEGRATORS.named(DEFAULT_INTEGRATOR if options.method == "auto" else options.method)
        if integrator.stepper is None:
            raise ValueError(f"method {integrator.name!r} is not a step-by-step integrator")
        if integrator.floats and scalar is None:  # the same algorithm in numpy
            integrator = INTEGRATORS.named(integrator.ivp)
        self.method, self.stepper, self.multistep = integrator.name, integrator.stepper, integrator.multistep
        self.drive = integrator.drive
        sep = scalar_separation_function(scene)
        rhs = _RightHandSide(scene, d_scale, v, p_scale, gamma, law, scalar)

        def force(z):  # the law, continued past separation, at a dimensionless state [N]
            x, y = float(z[0]), float(z[1])
            return float(scalar(x * d_scale, y * v, scene) if scalar is not None else law(x * d_scale, y * v))

        def max_compression(tau, z):
            return z[1]

        def separation(tau, z):
            return sep(z[0] * d_scale, z[1] * v)

        max_compression.direction, max_compression.kind = -1, EventKind.MAX_COMPRESSION
        separation.direction = -1
        separation.kind = EventKind.PENETRATION if scene.separation.pulls else EventKind.FORCE
        separation.terminal = True
        self.rhs, self.force, self.max_compression, self.separation = rhs, force, max_compression, separation
        self.end = horizon(scene) * w
        self.rtol, self.atol = conditioned_tolerances(scene, options)
        self.max_step = min(options.max_step * w, conditioned_step(scene))

    def integrate(self, span, z0, max_step, events, first_step=None):
        """One solver run over ``span`` (tau) from ``z0``; ImpactError past the budget or on overflow."""
        try:
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                sol = self.stepper(self.rhs, span, z0, self.rtol, self.atol, max_step, events, first_step)
        except OverflowError:  # float arithmetic (x ** n) raises where numpy returns inf
            raise ImpactError(f"the contact force overflows ({describe_family(self.scene)}method {self.method}): "
                              "the scene lies outside what the solver resolves") from None
        except _Budget:
            scene = self.scene
            raise ImpactError(
                f"no separation within {MAX_NFEV:.0e} right-hand-side evaluations (method {self.method}; "
                f"{describe_family(scene)}criterion '{scene.separation}'): the contact is too stiff or too slow to "
                "end" + (": an over-damped contact returns to delta = 0 slowly if ever, try --separation force"
                         if scene.separation.pulls else "")) from None
        if sol.status == -1:
            raise ImpactError(f"solver {self.method} failed: {sol.message}")
        return sol


class _RampBand:
    """Eq. 4.2's ramp band as a step policy (see :data:`BAND_RESTART`): a terminal event where restitution
    enters the band, and the bounded steps the integration restarts with there.

    ``lam`` is the ramp's rate in the dimensionless compression, u = lam x.
    """

    def __init__(self, lam: float):
        self.lam = lam

        def band_exit(tau, z):  # falls through 0 once in restitution inside the band
            return max(lam * z[0] - BAND_RESTART, z[1])

        band_exit.direction, band_exit.terminal = -1, True  # at the edge, or at t_m inside the band
        band_exit.kind, band_exit.lam, band_exit.edge = EventKind.BAND, lam, BAND_RESTART
        self.event = band_exit

    @classmethod
    def of(cls, scene: Scene, d_scale: float):
        """The band of ``scene``'s law, or None when it has no ramp (or its rate underflowed to 0: an elastic
        contact)."""
        rate = scene.law.ramp_rate
        lam = None if rate is None else rate(scene) * d_scale
        return None if lam is None or lam == 0.0 else cls(lam)

    def step(self, max_step: float, z0) -> float:
        """The largest step [tau] inside the band from state ``z0``."""
        return min(max_step, BAND_STEP / (self.lam * max(abs(z0[1]), BAND_SPEED)))

    def restitution(self, run: _Run, sol):
        """The restitution from the band event on, integrated with bounded steps (None when the first run
        separated before reaching it); returns (that solution, its step bound)."""
        if not len(sol.t_events[2]) or len(sol.t_events[1]):
            return None, run.max_step
        start, z0 = float(sol.t_events[2][0]), sol.y_events[2][0]
        step = self.step(run.max_step, z0)
        # go on with the step the first part had reached, not scipy's estimate from a standing start
        first = min(step, float(sol.t[-2] - sol.t[-3])) if len(sol.t) >= 3 else None
        return run.integrate((start, run.end), z0, step, (run.separation,), first), step

    def max_compression(self, sol, t_m):
        """t_m's event times: where the band event fired at maximum compression (its function is delta_dot
        there) and its root came first, that root."""
        if not len(t_m) and self.lam * sol.y_events[2][0][0] < BAND_RESTART:
            return sol.t_events[2]
        return t_m


def _land(run: _Run, dense, tau_f: float, cap: float, on_delta: bool):
    """The step that ends exactly at separation, and t_f corrected on it (a step policy).

    The state at separation comes from a step that ends at t_f, not from the crossing step's interpolant,
    which is one order lower and not error-controlled (on a Hertz spring's continuation it erred by 1.4e-7 in
    the COR).  The root itself was found on that interpolant; where the separation function is a small
    difference of large terms (over-damped under the force criterion) Newton's method on the landed state
    corrects it, landing again while a correction exceeds the tolerance (at most :data:`LANDINGS` times; not
    for a multistep integrator, ``Integrator.multistep``).  Returns (last run, tau_f, its evaluations).
    """
    tau_k, crossing, tau_end = float(dense.ts[-2]), dense, _step_end(dense)
    nfev = 0

    def ending(z):  # the separation function, smooth through its root: delta, or the continued force
        return float(z[0]) if on_delta else run.force(z)

    for attempt in range(LANDINGS):
        tail = run.integrate((tau_k, tau_f), dense(tau_k), cap, (), first_step=tau_f - tau_k if tau_f > tau_k else None)
        nfev += tail.nfev
        h = 1e-6 * (tau_end - tau_k)
        slope = (ending(crossing(min(tau_f + h, tau_end))) - ending(crossing(max(tau_f - h, tau_k)))) / (
            min(tau_f + h, tau_end) - max(tau_f - h, tau_k))
        correction = -ending(tail.y[:, -1]) / slope if slope != 0 else 0.0
        if not abs(correction) > run.rtol * tau_f or attempt == LANDINGS - 1 or run.multistep:
            break
        corrected = min(tau_f + correction, tau_end)
        if not corrected > tau_k:  # the correction leaves the crossing step: keep the landing made
            break
        tau_f = corrected
    return tail, tau_f, nfev


class IntegratedNormal(_DimensionlessNormal):
    """Normal motion integrated step by step by an integrator's stepper (DOP853 in plain floats, scipy's
    :func:`~scipy.integrate.solve_ivp` methods): one run to separation (:class:`_Run`), restarted with bounded
    steps in the ramp band (:class:`_RampBand`), then landed on t_f (:func:`_land`).

    Parameters
    ----------
    scene : Scene
    options : SolverOptions
        ``method`` names an integrator with a ``stepper`` (``auto``: the default one).
    drive : bool
        Let the integrator's ``drive`` do the whole work where it can (the same answer to the bit); False: run
        by run here (the reference its tests hold it to).

    Raises
    ------
    ValueError
        For an integrator without a stepper (``closed``, ``taylor``).
    ImpactError
        When the solver fails, or maximum compression or separation is not found.
    """

    def __init__(self, scene: Scene, options: SolverOptions, drive: bool = True):
        self.scene = scene
        run = _Run(scene, options)
        band = _RampBand.of(scene, run.d_scale)
        driven = run.drive(run, band) if drive and run.drive is not None else None
        self._landed(run, options, *(driven if driven is not None else self._driven(run, band, options)))

    def _driven(self, run: _Run, band: _RampBand | None, options: SolverOptions):
        """The motion driven run by run: to separation, through the ramp band, landed on t_f.  Returns the dense
        output, the step ends, tau_m, tau_f, y at t_f and the evaluations."""
        scene = self.scene
        events = [run.max_compression, run.separation] + ([band.event] if band is not None else [])
        # overflow in an absurd scene (b = 1e300) is reported by the checks below, not as a warning
        sol = run.integrate((0.0, run.end), [0.0, 1.0], run.max_step, events)
        rest, cap = (None, run.max_step) if band is None else band.restitution(run, sol)
        final, at = (sol, 1) if rest is None else (rest, 0)  # where the separation event is
        t_m, t_f = sol.t_events[0], final.t_events[at]
        if rest is not None:
            t_m = band.max_compression(sol, t_m)
        if final.status == 0 or len(t_f) == 0:
            raise ImpactError(no_separation_message(scene, horizon(scene)))
        if len(t_m) == 0:
            raise ImpactError(f"separation found before maximum compression ({describe_family(scene)}method "
                              f"{run.method}, rtol {options.rtol:g}): an event was missed (tighten the tolerance), "
                              "or the damping stops the ball within round-off of first touch (beyond what the "
                              "solver resolves)")
        nfev, dense, steps = sol.nfev, fast_solution(sol.sol), sol.t
        if rest is not None:  # one dense output over both parts
            nfev += rest.nfev
            dense = _join(dense, fast_solution(rest.sol))
            steps = np.concatenate([sol.t[:-1], rest.t])
        tau_f = float(t_f[0])
        x_m = float(sol.y_events[0][0][0]) if len(sol.y_events[0]) else 1.0
        z_f = dense(tau_f)
        on_delta = scene.separation.pulls or (abs(float(z_f[0])) <= LANDING_DELTA * x_m
                                              and not run.force(np.array([0.0, float(z_f[1])])) < 0)
        tail, tau_f, landing = _land(run, dense, tau_f, cap, on_delta)
        dense = _join(dense, fast_solution(tail.sol))
        steps = np.concatenate([steps[:-1], tail.t[1:]])
        return dense, steps, float(t_m[0]), tau_f, float(tail.y[1, -1]), nfev + landing

    def _landed(self, run: _Run, options: SolverOptions, dense, steps, tau_m: float, tau_f: float, rate_f: float,
                nfev: int) -> None:
        """The motion from its dense output and step ends (tau), maximum compression and separation [tau] and y at
        t_f: its rebound checked, its times in seconds, its grid."""
        check_rebound(self.scene, options, rate_f * run.v)
        self._sol, self._w, self._d_scale, self._v = dense, run.w, run.d_scale, run.v
        self.t_m = tau_m / run.w
        self.t_f = tau_f / run.w
        self.grid = contact_grid(steps / run.w, self.t_f)
        self.stats = {"method": run.method, "rtol": options.rtol, "atol": options.atol, "nfev": int(nfev)}


class TaylorNormal(_DimensionlessNormal):
    """Normal motion integrated by the Taylor-series method (:mod:`sphereimpact.ode.series`), for a law with a
    ``series``: compiled (:mod:`.taylor_kernel`) for a law with a series kernel once the process integrates
    compiled (:func:`.compiled.compiled_now`), the same steps and answer to the bit.

    The local tolerance (each step's truncation bound on the O(1) state) is min(rtol, atol), those
    tightened where the outputs are ill-conditioned (over-damped under the force criterion): by the square
    of :func:`conditioned_tolerances`' factor 1 / (4 zeta^2), down to 1e-16 (with the factor applied once,
    t_f's error grew with zeta far past the tolerance; tests/test_taylor.py checks the linear law's closed
    form up to zeta 30).  Its accuracy against DOP853-scalar's: ``results/work_precision.csv``.

    Raises
    ------
    ValueError
        The law has no series.
    ImpactError
        Maximum compression or separation not found, or more steps than the budget allows.
    series.SeriesOverflowError
        The series or the force leaves double precision (``simulate`` then reports it, or under ``auto``
        integrates with DOP853-scalar instead).
    """

    def __init__(self, scene: Scene, options: SolverOptions):
        law = scene.law
        if law.series is None:
            raise ValueError(f"method 'taylor' needs a law with a series; model {scene.model!r} has none")
        self.scene = scene
        w, v = scene.frequency, scene.v_normal
        d_scale, gamma = v / w, scene.g_normal / (w * v)
        # ill-conditioned t_f: the series' error reaches it more than DOP853's does (see above)
        rtol, atol = conditioned_tolerances(scene, options, floor=ATOL_FLOOR, power=2)
        ramp_rate = law.ramp_rate
        lam = None if ramp_rate is None else ramp_rate(scene) * d_scale
        compiled = law.series_kernel is not None and law.kernel is not None and law.scalar is not None
        try:
            if compiled and rule.compiled_now():  # the same steps and answer, compiled (no numpy arithmetic to warn)
                from .taylor_kernel import solved

                sol = solved(rule.checked_series_kernel(scene), rule.checked_kernel(scene, (d_scale, v)),
                             law.series_kernel.parameters(scene), law.kernel.parameters(scene), gamma,
                             min(rtol, atol), horizon(scene) * w, lam, options.max_step * w, d_scale, v,
                             scene.separation.pulls)
            else:
                sep = scalar_separation_function(scene)

                def separation(x, y):
                    return float(sep(x * d_scale, y * v))

                numbers = {name: float(value) for name, value in scene.family.items()}
                with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                    sol = series.solve(law.series, numbers, gamma, min(rtol, atol),
                                       horizon(scene) * w, separation, lam or None, options.max_step * w)
                if compiled:
                    rule.spend_in_floats(sol["dense"].steps * sol["order"])
        except series.StepBudgetError:
            raise ImpactError(f"no separation within {series.MAX_STEPS} Taylor steps ({describe_family(scene)}"
                              f"criterion '{scene.separation}'): the contact is too stiff or too slow to end") from None
        except (OverflowError, ZeroDivisionError):
            raise series.SeriesOverflowError(f"the contact force overflows ({describe_family(scene)}method "
                                             "taylor)") from None
        if sol["tau_f"] is None:
            if sol["tau_m"] is None:
                raise ImpactError(f"maximum compression not found ({describe_family(scene)}method taylor): the "
                                  "damping stops the ball within round-off of first touch, or an event was missed")
            raise ImpactError(no_separation_message(scene, horizon(scene)))
        check_rebound(scene, options, sol["state_f"][1] * v)
        self._sol, self._w, self._d_scale, self._v = sol["dense"], w, d_scale, v
        self.t_m, self.t_f = sol["tau_m"] / w, sol["tau_f"] / w
        self.grid = contact_grid(sol["dense"].ts / w, self.t_f)
        # nfev: the force's Taylor coefficients computed, one per order and step (each the work of about one
        # right-hand-side call), so the work-precision chart compares like with like
        self.stats = {"method": "taylor", "rtol": options.rtol, "atol": options.atol,
                      "nfev": sol["dense"].steps * sol["order"]}
