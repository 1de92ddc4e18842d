"""Exact elastic microslip: the Cattaneo-Mindlin-Jäger contact for any loading history, by the method of
dimensionality reduction.

Sources: Maw, Barber & Fawcett (1976), Wear 38:101-114 (oblique impact with microslip: new contact area is
laid down free of tangential stress); Popov & Heß, *Method of Dimensionality Reduction in Contact Mechanics
and Friction* (Springer 2015) and Facta Universitatis 12:1-14 (2014); Willert & Popov (2016), ZAMM
96:1089-1095 (the oblique impact of a sphere with friction).

The method of dimensionality reduction (MDR) replaces the axisymmetric Hertz contact by a row of independent
springs at x in [-a, a] on the profile g(x) = x^2 / R.  Spring x is compressed w(x) = delta - x^2 / R
(normal stiffness E* dx) and carries a tangential displacement u(x) (tangential stiffness G* dx), so

    P = E* int w dx = (4/3) E* sqrt(R) delta^(3/2),   Q = G* int u dx,   a = sqrt(R delta).

Each spring sticks, following the rigid tangential displacement of the bodies, while |u| stays below its
own Coulomb limit mu (E*/G*) w, and slides at that limit otherwise; a spring enters contact free of
tangential displacement and leaves it with none.  For axisymmetric contacts this is exact: it reproduces
the Cattaneo-Mindlin curve, the Mindlin-Deresiewicz loops and Jäger's superposition for any history of the
normal and tangential loading.  G* = kappa E*, kappa = k_t / k_n = 4 G_eff / E* (Mindlin's 8 G_eff a
against the normal 2 E* a).  With a damped normal law (Hunt-Crossley) each spring's limit is its share of
mu P+, in proportion to w: the damping scales the pressure without changing its shape, and the limits add
up to mu P+.  The normal motion does not depend on friction: it is solved first.

Discretisation (the model's settings ``elements`` and ``time_steps``, given in ``SolverOptions.settings``,
``--elements`` and ``--time-steps``; defaults from the measured convergence study,
``results/microslip_resolution.csv``):

- N cells of equal width on [0, a_max] (the row is symmetric), each one spring weighted by the length of
  the cell in contact and limited by the cell's exact share of the normal load, so the row's stiffness is
  2 G* a and its limits add up to mu P+ at every instant;
- M equal time steps on [0, t_f], the slip advanced by velocity Verlet; the tangential impulse of a step is
  the mean of the friction fraction F / (mu P+) at its ends times the exact normal impulse mu dJ+, so a
  contact that slides throughout gives the rigid model's impulse exactly.  A spring entering during a step
  takes the part of the step's displacement after it entered.

The march is the compiled kernel of :mod:`.microslip_march` (numba, imported on the first microslip impact).
"""

from __future__ import annotations

import math

import numpy as np

from ..laws.base import Spring, hertz_modulus
from ..parameters import Setting
from .base import KAPPA, POISSON, SHEAR_MODULUS, TANGENTIALS, Regime, TangentialModel, slip_per_impulse
from .rigid import PositiveImpulse, push_terms, pushing_throughout

#: Default resolution: cells of the element row and time steps per contact (the convergence study's choice).
ELEMENTS = 128
TIME_STEPS = 384
#: Fewest time steps per period of the tangential oscillation at full contact (a stiff tangential spring,
#: large kappa, gets more steps than TIME_STEPS; velocity Verlet is stable below 2 / pi steps per period).
STEPS_PER_PERIOD = 64
#: The settings that override them (ranges: fewer cells or steps resolve nothing; more exhaust the memory
#: and the patience of one impact).
ELEMENTS_SETTING = Setting("elements", "microslip's cells of the element row", 8, 100_000,
                           default="the convergence study's")
TIME_STEPS_SETTING = Setting("time_steps", "microslip's time steps over the contact", 16, 10_000_000,
                             default="the convergence study's")
#: Most cells x time steps one impact may take: the march costs about this many cell updates, so the bound
#: keeps one impact to minutes where the settings' own maxima together would take days.
MAX_CELL_STEPS = 10**10
#: A contact counts as sticking in part while its tangential force is below mu P+ by more than this fraction
#: (a friction force within it of mu P+ is gross slip to the row's resolution: at the slide-throughout
#: threshold the discrete row flickers between the two with deficits of 1e-7 to 1e-4).
STICK_TOLERANCE = 1e-3
#: Regimes of a microslip contact: it slid throughout, or part of it stuck at some time.
SLIDING, MICROSLIP = Regime.SLIDING, Regime.MICROSLIP


def hertz_moduli(scene) -> tuple[float, float]:
    """(E*, G*) [Pa] of the scene's Hertz spring k delta^(3/2), k = (4/3) E* sqrt(R), and G* = kappa E*
    (the MDR's tangential modulus, 4 G_eff)."""
    e_star = hertz_modulus(scene)
    return e_star, scene.kappa * e_star


def quasi_static(xi_a, cap, displacement, stiffness=1.0, elements=ELEMENTS):
    """The tangential force of the contact under a prescribed history, without inertia: the compiled kernel's
    :func:`~.microslip_march.quasi_static` (arrays (K,) of contact radius over a_max [-], Coulomb cap mu P+ [N]
    and rigid tangential displacement U [m] from a fresh contact; ``stiffness`` 2 G* a_max [N/m]), returning
    the force Q [N] on the moving body, positive along U."""
    from . import microslip_march

    xi_a, cap, displacement = (np.ascontiguousarray(v, dtype=float) for v in (xi_a, cap, displacement))
    return microslip_march.quasi_static(xi_a, cap, displacement, float(stiffness), int(elements))


def march(xi_a, cap, impulse, dt, stiffness, inverse_mass, g_t, slip0, elements):
    """The element row and the slip marched through one contact from a fresh row of ``elements`` cells: the
    compiled kernel's :func:`~.microslip_march.march` (its arguments and results), imported on first use."""
    from . import microslip_march

    return microslip_march.march(np.ascontiguousarray(xi_a, dtype=float), np.ascontiguousarray(cap, dtype=float),
                                 np.ascontiguousarray(impulse, dtype=float), float(dt), float(stiffness),
                                 float(inverse_mass), float(g_t), float(slip0), np.zeros(int(elements)))


def resolution(scene, normal, options) -> tuple[int, int]:
    """(elements, time steps) of one impact: the options' or the defaults, with at least
    :data:`STEPS_PER_PERIOD` steps per period of the tangential oscillation at maximum contact.

    Raises
    ------
    ValueError
        When that needs more steps than the setting allows (a kappa far beyond a material's), or the cells
        times the steps exceed :data:`MAX_CELL_STEPS` (naming the cost, before any of it is spent).
    """
    elements = options.setting("elements") or ELEMENTS
    steps = options.setting("time_steps")
    if steps is None:
        e_star, g_star = hertz_moduli(scene)
        a_max = math.sqrt(scene.radius * max(normal.delta_m, 0.0))
        omega_t = math.sqrt(2.0 * g_star * a_max * slip_per_impulse(scene.mass, scene.inertia_factor))
        needed = STEPS_PER_PERIOD * normal.t_f * omega_t / (2.0 * math.pi)
        if not needed <= TIME_STEPS_SETTING.high:
            raise ValueError(f"microslip: kappa {scene.kappa:g} makes the tangential spring ring {needed / STEPS_PER_PERIOD:.3g} "
                             f"times per contact, which needs {needed:.3g} time steps ({STEPS_PER_PERIOD} a period), "
                             f"more than the {TIME_STEPS_SETTING.high} allowed: kappa = k_t / k_n is "
                             "2 (1 - nu) / (2 - nu), 2/3 to 1 for real materials")
        steps = max(TIME_STEPS, math.ceil(needed))
    if elements * steps > MAX_CELL_STEPS:
        raise ValueError(f"microslip: {elements} cells x {steps} time steps = {elements * steps:.3g} cell-steps, more "
                         f"than the {MAX_CELL_STEPS:.0e} one impact may take (the defaults take "
                         f"{ELEMENTS * TIME_STEPS:.3g}, and results/microslip_resolution.csv shows how fine a "
                         "resolution a target needs): lower elements or time_steps")
    return elements, steps


def _samples(normal, time_steps: int):
    """What the march reads of the normal motion alone, on ``time_steps`` equal steps: the step ends t [s], the
    contact radius over a_max [-], P+ [N] (zero at the ends: no area, no load), the impulse of P+ over each
    step [N s], and a_max^2 / R = delta_m [m].  Compiled (:func:`.microslip_march.samples`, the same numbers to the
    bit) where the motion has a kernel state and its force pushes over one interval, as the force criterion's does
    (read without building J+ where it pushes throughout, :func:`~.rigid.pushing_throughout`)."""
    positive = None
    pushing = pushing_throughout(normal)
    if pushing is None:
        positive = PositiveImpulse(normal)
        pushing = positive.one_interval()
    terms = push_terms(normal, pushing)
    if terms is not None:
        from .microslip_march import samples

        arrays, force, params, pushing = terms
        t, xi_a, load, step_impulse, delta_m = samples(arrays, force, params, pushing, float(normal.t_f),
                                                        float(normal.delta_m), int(time_steps))
        return t, xi_a, load, step_impulse, float(delta_m)
    t = np.linspace(0.0, normal.t_f, time_steps + 1)
    compression, rate = normal.state(t)  # once: the force and the impulse are read off it
    delta = np.maximum(compression, 0.0)
    delta_m = max(normal.delta_m, float(delta.max()))
    load = np.maximum(normal.forces_at(compression, rate), 0.0)  # normal.force(t), as compiled code computes it
    load[0] = load[-1] = 0.0
    impulse = normal.impulse_from(t, rate)  # normal.impulse(t)
    positive = PositiveImpulse(normal) if positive is None else positive
    return t, np.sqrt(delta / delta_m), load, np.diff(positive.from_impulse(t, impulse)), delta_m


def march_inputs(normal, time_steps: int):
    """The step ends t [s] and the arguments of :func:`march` but the number of cells, for one contact (the
    normal motion's samples kept with it: a normal motion shared by scenes of other friction is sampled once)."""
    s = normal.scene
    t, xi_a, load, step_impulse, delta_m = normal.kept(("microslip", time_steps), lambda: _samples(normal, time_steps))
    stiffness = 2.0 * hertz_moduli(s)[1] * math.sqrt(s.radius * delta_m)
    inverse_mass = slip_per_impulse(s.mass, s.inertia_factor)
    return t, (xi_a, s.mu * load, s.mu * step_impulse, float(t[1] - t[0]), stiffness, inverse_mass, s.g_tangent,
               s.slip0)


def _hermite(t, nodes, values, slopes):
    """Cubic Hermite interpolation of (values, slopes) given at increasing ``nodes``, at the instants t."""
    i = np.clip(np.searchsorted(nodes, t, side="right") - 1, 0, nodes.size - 2)
    h = nodes[i + 1] - nodes[i]
    s = (t - nodes[i]) / h
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
    return h00 * values[i] + h10 * h * slopes[i] + h01 * values[i + 1] + h11 * h * slopes[i + 1]


class MicroslipTangential:
    """Tangential motion and spin of a ball whose Hertz contact slips partially (see module docstring).

    Parameters
    ----------
    normal : NormalMotion
        The solved normal motion of a Hertz-spring law (exponent 3/2); its scene has an angle > 0.
    options : SolverOptions
        Its settings ``elements`` and ``time_steps`` (not given: :func:`resolution`).

    Attributes
    ----------
    t : array
        The step ends [s], 0 to t_f.
    t_roll : float or None
        First step end at which part of the contact sticks [s], None if it slides throughout.
    regime : str
        ``sliding`` (the contact slid throughout) or ``microslip`` (part of it stuck at some time).
    switches : int
        Changes between gross slip and partial stick over the contact.
    elements, time_steps : int
        The resolution used.
    """

    def __init__(self, normal, options):
        from . import microslip_march

        self.elements, self.time_steps = resolution(normal.scene, normal, options)
        t, inputs = march_inputs(normal, self.time_steps)
        force, j_t = march(*inputs, self.elements)
        s = self.scene = normal.scene
        self.normal, self.t, self._force, self._j = normal, t, force, j_t
        # F / (mu P+) (at the ends, where the cap is 0, the neighbours'), where part sticks, v, omega and x
        self._fraction, self.stuck, self.v, self.omega, self.x, switches, first_stuck = microslip_march.motion(
            t, force, j_t, inputs[1], *(float(q) for q in (s.v_tangent, s.g_tangent, s.mass, s.spin,
                                                            s.inertia_factor * s.mass * s.radius)), 1.0 - STICK_TOLERANCE)
        self.t_roll = float(t[first_stuck]) if first_stuck >= 0 else None
        self.regime = MICROSLIP if first_stuck >= 0 else SLIDING
        self.switches = int(switches)

    def at(self, t):
        """Tangential centre velocity v_t [m/s], spin omega [rad/s] and displacement x_t [m] at t [s]
        (shape (3, len(t))); exact at the step ends, cubic Hermite between them."""
        s = self.scene
        t = np.atleast_1d(np.asarray(t, dtype=float))
        if t.size == 1 and t[0] == self.t[-1]:  # at t_f (an outcome's read): the last step end's values, which the
            return np.array([[self.v[-1]], [self.omega[-1]], [self.x[-1]]])  # interpolation returns there exactly
        accel = self._force / s.mass + s.g_tangent
        spin_rate = -self._force / (s.inertia_factor * s.mass * s.radius)
        return np.array([_hermite(t, self.t, self.v, accel), _hermite(t, self.t, self.omega, spin_rate),
                         _hermite(t, self.t, self.x, self.v)])

    def force(self, t):
        """Tangential contact force on the ball [N] at t [s]: the friction fraction F / (mu P+), linear between
        the step ends, times mu P+(t), so that |F| <= mu P+ between the steps too."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.interp(t, self.t, self._fraction) * self.scene.mu * np.maximum(self.normal.force(t), 0.0)


MICROSLIP_MODEL = TANGENTIALS.register(TangentialModel(
    "microslip", doc="exact elastic microslip of a Hertz contact (method of dimensionality reduction), Hertz laws",
    stiffness="k_t = 2 G* a, resolved across the contact", parameters=(KAPPA, POISSON, SHEAR_MODULUS),
    spring=Spring.HERTZ, motion=MicroslipTangential,
    settings=(ELEMENTS_SETTING, TIME_STEPS_SETTING), scale_free=True))

