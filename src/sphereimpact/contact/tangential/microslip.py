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
"""

from __future__ import annotations

import math

import numpy as np

from ..laws.base import hertz_modulus
from ..parameters import Setting
from .base import KAPPA, POISSON, SHEAR_MODULUS, TANGENTIALS, TangentialModel, slip_per_impulse
from .rigid import PositiveImpulse

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
#: Time steps advanced per block of precomputed element weights (bounds the working memory).
BLOCK = 64
#: A contact counts as sticking in part while its tangential force is below mu P+ by more than this fraction
#: (a friction force within it of mu P+ is gross slip to the row's resolution: at the slide-throughout
#: threshold the discrete row flickers between the two with deficits of 1e-7 to 1e-4).
STICK_TOLERANCE = 1e-3
#: Regimes of a microslip contact: it slid throughout, or part of it stuck at some time.
SLIDING, MICROSLIP = "sliding", "microslip"


def hertz_moduli(scene) -> tuple[float, float]:
    """(E*, G*) [Pa] of the scene's Hertz spring k delta^(3/2), k = (4/3) E* sqrt(R), and G* = kappa E*
    (the MDR's tangential modulus, 4 G_eff)."""
    e_star = hertz_modulus(scene)
    return e_star, scene.kappa * e_star


def cell_weights(a0, a1, left, width):
    """Weights of element-row cells whose contact radius goes linearly in time from ``a0`` to ``a1`` over a step.

    Parameters
    ----------
    a0, a1 : arrays
        Contact radius at the step's start and end, over a_max [-] (broadcast with ``left``).
    left : array
        Left edges of the cells [a_max].
    width : float
        Width of a cell [a_max].

    Returns
    -------
    mean_length : array
        Each cell's covered length clip(a - left, 0, width), averaged over the step exactly [a_max]: a cell
        that enters or leaves the contact part-way through is credited with the mean, where the ends' mean
        would credit a cell entering at the step's end with half its length.
    share : array
        The cell's share at the step's end of the integral of w = (a^2 - x^2) / R over the contact [-]: the
        shares of a row add up to 1 where a1 > 0, else 0.
    """
    length0 = np.clip(a0 - left, 0.0, width)
    length = np.clip(a1 - left, 0.0, width)
    right = left + length
    load = a1 * a1 * length - (right * right * right - left * left * left) / 3.0  # int of a^2 - x^2, covered part
    total = 2.0 * a1 * a1 * a1 / 3.0
    change = a1 - a0
    crossing = ((np.minimum(a0, a1) < left + width) & (np.maximum(a0, a1) > left)
                & (np.abs(change) > 1e-9 * width))  # the covered length changes slope within the step
    with np.errstate(invalid="ignore", divide="ignore"):
        share = np.where(total > 0, load / total, 0.0)
        exact = (_covered_integral(a1, left, width) - _covered_integral(a0, left, width)) / change
    return np.where(crossing, exact, 0.5 * (length0 + length)), share


def _covered_integral(a, left, width):
    """The integral over the contact radius, from 0 to ``a``, of a cell's covered length clip(a - left, 0, width)."""
    inside = np.clip(a - left, 0.0, width)
    return 0.5 * inside * inside + width * np.maximum(a - left - width, 0.0)


class _Block:
    """The element row's weights for a block of steps of one contact (``xi_a`` of shape (S,)) or B at once
    ((S, B)): each cell's limit, its share of the Coulomb cap over the row's stiffness, as an array (S, [B,] N);
    and the few cells whose covered length is not the full width all through a step (the band at the contact's
    edge), with their exact mean covered lengths.

    A cell covered all through a step has mean length ``width`` and limit cap / stiffness times
    (a^2 width - c_i) / (2 a^3 / 3), with c_i the integral of x^2 over the cell; a cell beyond the contact at
    the step's end has limit 0 (that formula is negative there), which clears what it held.  Only the band is
    weighed cell by cell (:func:`cell_weights`), so a step costs a few passes over the row."""

    def __init__(self, xi_a, cap, stiffness, elements, xi_before):
        width = 1.0 / elements
        left = np.arange(elements) * width
        a1 = np.asarray(xi_a, dtype=float)
        a0 = np.concatenate([np.asarray(xi_before, dtype=float)[None], a1[:-1]])
        with np.errstate(invalid="ignore", divide="ignore"):
            scale = np.where(a1 > 0, cap / (np.asarray(stiffness) * (2.0 / 3.0) * a1 * a1 * a1), 0.0)
        c = ((left + width) ** 3 - left ** 3) / 3.0
        limit = np.maximum(scale[..., None] * ((a1 * a1 * width)[..., None] - c), 0.0)
        low = np.clip(np.floor(np.minimum(a0, a1) * elements), 0, elements).astype(np.int64)
        high = np.clip(np.ceil(a1 * elements), 0, elements).astype(np.int64)
        counts = np.maximum(high - low, 0).ravel()
        lanes = np.repeat(np.arange(counts.size), counts)  # flat (step, lane) of each band cell
        cells = low.ravel()[lanes] + np.arange(lanes.size) - np.repeat(np.cumsum(counts) - counts, counts)
        mean, share = cell_weights(a0.ravel()[lanes], a1.ravel()[lanes], cells * width, width)
        flat = limit.reshape(-1, elements)
        flat[lanes, cells] = (np.broadcast_to(cap / np.asarray(stiffness), a1.shape).ravel()[lanes] * share)
        per_step = a1[0].size if a1.ndim > 1 else 1
        bounds = np.searchsorted(lanes, np.arange(0, a1.shape[0] + 1) * per_step)
        self.limit, self.width = limit, width
        self.band = [(lanes[i:j] % per_step, cells[i:j], mean[i:j]) for i, j in zip(bounds[:-1], bounds[1:])]

    def hold(self, j, held, d_u):
        """Step ``j`` of the block: each cell's held displacement (the integral of u over its part in contact)
        grows by its mean covered length times the rigid displacement ``d_u`` (float, or (B, 1)) while it
        sticks, and is held to its limit when it slides."""
        lanes, cells, mean = self.band[j]
        grown = held + self.width * d_u
        if held.ndim == 1:
            grown[cells] = held[cells] + mean * d_u
        else:
            grown[lanes, cells] = held[lanes, cells] + mean * d_u[lanes, 0]
        limit = self.limit[j]
        return np.minimum(np.maximum(grown, -limit), limit)


def quasi_static(xi_a, cap, displacement, stiffness=1.0, elements=ELEMENTS):
    """The tangential force of the contact under a prescribed history, without inertia.

    Parameters
    ----------
    xi_a, cap, displacement : arrays (K,)
        Contact radius over a_max [-], Coulomb cap mu P+ [N] and the rigid tangential displacement of the
        bodies U [m] at K instants, starting from a fresh contact at the first.
    stiffness : float
        2 G* a_max [N/m].
    elements : int
        Cells of the element row.

    Returns
    -------
    array (K,)
        The tangential force Q = 2 G* int u dx [N] on the moving body, positive along U (the force that
        holds it; the force on the ball in :class:`MicroslipTangential` is its opposite).
    """
    xi_a, cap, displacement = (np.asarray(v, dtype=float) for v in (xi_a, cap, displacement))
    block = _Block(xi_a[1:], cap[1:], stiffness, elements, xi_a[0])
    held, force = np.zeros(elements), np.zeros(xi_a.shape)
    for n, d_u in enumerate(np.diff(displacement)):
        held = block.hold(n, held, float(d_u))
        force[n + 1] = stiffness * held.sum()
    return force


def march(xi_a, cap, impulse, dt, stiffness, inverse_mass, g_t, slip0, held):
    """Advance the element row and the slip through the contact: one contact (numbers) or B at once (arrays).

    Each cell's state is the integral of u over its part in contact [m a_max].  While the cell sticks it grows
    by the covered length times the rigid displacement dU (the material entering the contact brings none),
    and it is held to the cell's share of mu P+ / (2 G* a_max).

    Parameters
    ----------
    xi_a : array (M + 1,) or (M + 1, B)
        Contact radius over a_max at the step ends [-].
    cap : array like ``xi_a``
        Coulomb cap mu P+ at the step ends [N]; zero at the first.
    impulse : array (M,) or (M, B)
        mu times the normal impulse of P+ over each step [N s].
    dt, stiffness, inverse_mass, g_t, slip0 : float or array (B,)
        Step [s]; 2 G* a_max, the row's tangential force per unit of held displacement [N/m];
        (1 + 1/alpha) / m, the slip's acceleration per unit tangential force [1/kg]; gravity along the flat
        [m/s^2]; the slip velocity v_t - omega R at the start [m/s].
    held : array (N,) or (B, N)
        The cells' integrals of u at the start [m a_max] (zero: a fresh contact).

    Returns
    -------
    force, tangential_impulse : arrays like ``xi_a``
        Tangential force on the ball [N] and the tangential impulse on it since the start [N s], at the
        step ends.
    held : array like ``held``
        The cells' integrals of u at the end.
    """
    points, elements = xi_a.shape[0], held.shape[-1]
    one = xi_a.ndim == 1  # one contact: its numbers are plain floats (numpy's per-call cost is most of a step)
    force, j_t = np.zeros(xi_a.shape), np.zeros(xi_a.shape)
    with np.errstate(divide="ignore"):
        per_cap = np.where(cap > 0, 1.0 / cap, 0.0)  # F / cap is the friction fraction phi
    no_cap = (cap <= 0).astype(float)  # the contact's ends: phi is 0 / 0 there and takes its neighbour's value
    if one:
        per_cap, no_cap, impulse = per_cap.tolist(), no_cap.tolist(), impulse.tolist()
        dt, stiffness, inverse_mass, g_t, slip0 = (float(v) for v in (dt, stiffness, inverse_mass, g_t, slip0))
    slip, f_now, phi_now, j_now = slip0, 0.0 * slip0, 0.0 * slip0, 0.0 * slip0
    half_dt2 = 0.5 * dt * dt
    for start in range(0, points - 1, BLOCK):  # the row's weights for a block of steps at once
        stop = min(start + BLOCK, points - 1)
        block = _Block(xi_a[start + 1:stop + 1], cap[start + 1:stop + 1], stiffness, elements, xi_a[start])
        forces, impulses = [], []
        for j, n in enumerate(range(start, stop)):
            d_u = dt * slip + half_dt2 * (f_now * inverse_mass + g_t)
            held = block.hold(j, held, d_u if one else d_u[:, None])
            f_next = -stiffness * (float(held.sum()) if one else held.sum(axis=-1))
            phi_next = f_next * per_cap[n + 1] + no_cap[n + 1] * phi_now
            step_impulse = 0.5 * ((phi_now if n else phi_next) + phi_next) * impulse[n]
            j_now = j_now + step_impulse
            slip = slip + step_impulse * inverse_mass + g_t * dt
            forces.append(f_next)
            impulses.append(j_now)
            f_now, phi_now = f_next, phi_next
        force[start + 1:stop + 1], j_t[start + 1:stop + 1] = forces, impulses
    return force, j_t, held


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
    step [N s], and a_max^2 / R = delta_m [m]."""
    t = np.linspace(0.0, normal.t_f, time_steps + 1)
    delta = np.maximum(normal.state(t)[0], 0.0)
    delta_m = max(normal.delta_m, float(delta.max()))
    load = np.maximum(normal.force(t), 0.0)
    load[0] = load[-1] = 0.0
    return t, np.sqrt(delta / delta_m), load, np.diff(PositiveImpulse(normal)(t)), delta_m


def _inputs(normal, time_steps: int):
    """The step ends t [s] and the arguments of :func:`march` but the held displacements, for one contact (the
    normal motion's samples kept with it: a normal motion shared by scenes of other friction is sampled once)."""
    s = normal.scene
    t, xi_a, load, step_impulse, delta_m = normal.kept(("microslip", time_steps), lambda: _samples(normal, time_steps))
    stiffness = 2.0 * hertz_moduli(s)[1] * math.sqrt(s.radius * delta_m)
    inverse_mass = slip_per_impulse(s.mass, s.inertia_factor)
    return t, (xi_a, s.mu * load, s.mu * step_impulse, float(t[1] - t[0]), stiffness, inverse_mass, s.g_tangent,
               s.slip0)


def _fill_ends(values):
    """``values`` with NaN at its ends replaced by the nearest finite value (0 if there is none)."""
    finite = np.flatnonzero(np.isfinite(values))
    if not finite.size:
        return np.zeros_like(values)
    out = values.copy()
    out[:finite[0]], out[finite[-1] + 1:] = values[finite[0]], values[finite[-1]]
    return np.where(np.isfinite(out), out, 0.0)


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
        self.elements, self.time_steps = resolution(normal.scene, normal, options)
        t, inputs = _inputs(normal, self.time_steps)
        force, j_t, _ = march(*inputs, np.zeros(self.elements))
        self._settle(normal, t, inputs[1], force, j_t)

    @classmethod
    def many(cls, normals, options) -> list:
        """The motions over several solved normal motions: those of one resolution share a march of the batched
        kernel, so each is the motion :class:`MicroslipTangential` gives it alone (a march at a finer resolution
        than its own would differ from that by the resolution's error, 1e-5 of e_t)."""
        sizes = [resolution(n.scene, n, options) for n in normals]
        motions = [None] * len(normals)
        for size in dict.fromkeys(sizes):
            members = [i for i, own in enumerate(sizes) if own == size]
            sampled = [_inputs(normals[i], size[1]) for i in members]
            stacked = [np.stack(parts, axis=-1) for parts in zip(*(inputs for _, inputs in sampled))]
            force, j_t, _ = march(*stacked, np.zeros((len(members), size[0])))
            for b, (i, (t, inputs)) in enumerate(zip(members, sampled)):
                motion = motions[i] = cls.__new__(cls)
                motion.elements, motion.time_steps = size
                motion._settle(normals[i], t, inputs[1], force[:, b], j_t[:, b])
        return motions

    def _settle(self, normal, t, cap, force, j_t):
        """The motion from the march's tangential force and impulse at the step ends ``t`` (cap: mu P+ there)."""
        s = self.scene = normal.scene
        self.normal, self.t, self._force, self._j = normal, t, force, j_t
        with np.errstate(invalid="ignore", divide="ignore"):
            fraction = np.where(cap > 0, force / cap, np.nan)
        self._fraction = _fill_ends(fraction)  # F / (mu P+): at the ends, where the cap is 0, the neighbours'
        self.stuck = (cap > 0) & (np.abs(fraction) < 1.0 - STICK_TOLERANCE)
        self.v = s.v_tangent + s.g_tangent * t + self._j / s.mass
        self.omega = s.spin - self._j / (s.inertia_factor * s.mass * s.radius)
        accel = self._force / s.mass + s.g_tangent
        dt = t[1] - t[0]
        self.x = np.concatenate([[0.0], np.cumsum(0.5 * dt * (self.v[1:] + self.v[:-1])
                                                  + dt * dt / 12.0 * (accel[:-1] - accel[1:]))])
        flips = np.flatnonzero(np.diff(self.stuck[1:-1].astype(np.int8)))  # the ends have no contact
        self.t_roll = float(t[np.argmax(self.stuck)]) if self.stuck.any() else None
        self.regime = MICROSLIP if self.stuck.any() else SLIDING
        self.switches = int(flips.size)

    def at(self, t):
        """Tangential centre velocity v_t [m/s], spin omega [rad/s] and displacement x_t [m] at t [s]
        (shape (3, len(t))); exact at the step ends, cubic Hermite between them."""
        s = self.scene
        t = np.atleast_1d(np.asarray(t, dtype=float))
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
    spring="hertz", motion=MicroslipTangential, many=MicroslipTangential.many,
    settings=(ELEMENTS_SETTING, TIME_STEPS_SETTING), scale_free=True))

