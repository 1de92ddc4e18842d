"""The microslip contact's compiled kernel: the element row of the method of dimensionality reduction, marched.

One implementation of the row's step (:func:`row_weights`, :func:`hold`) serves the march with inertia
(:func:`march`, then the ball's motion from it, :func:`motion`) and the quasi-static drive (:func:`quasi_static`);
the physics and the discretisation are described in :mod:`.microslip`.  The functions are compiled by numba (the JIT
compiler of numerical Python: the march is a loop over time steps and cells that numpy can vectorise only within a
step, where one step's numpy calls cost more than the step's arithmetic) and cached on disk: by numba's default in
the ``__pycache__`` folder beside this file, or in ``NUMBA_CACHE_DIR`` when it is set.  A fresh machine compiles them
once, on first use (``results/bench.csv`` times it); numba is imported only then, so a command that never marches a
microslip contact does not pay for it.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types

from ..laws.kernels import SIGNATURE
from ..normal_kernel import ARRAY, NORMAL, normal_state
from .rigid_kernel import positive_impulse, positive_impulse_inside
from ...kernel_cache import refresh

refresh()  # before any kernel is defined: numba's cache of them true to every source they compile

#: Compile on first use, cache the machine code on disk, and keep IEEE semantics (no fast-math reassociation:
#: the march's sums are the same numbers every run).
_COMPILE = {"cache": True, "nogil": True, "error_model": "numpy"}


@numba.njit(**_COMPILE)
def cell_weight(a0, a1, left, width):
    """One element-row cell whose contact radius goes linearly from ``a0`` to ``a1`` over a step.

    Parameters
    ----------
    a0, a1 : float
        Contact radius at the step's start and end, over a_max [-].
    left, width : float
        The cell's left edge and width [a_max].

    Returns
    -------
    mean_length : float
        The cell's covered length clip(a - left, 0, width), averaged over the step exactly [a_max]: a cell that
        enters or leaves the contact part-way through is credited with the mean, where the ends' mean would
        credit a cell entering at the step's end with half its length.
    share : float
        The cell's share at the step's end of the integral of w = (a^2 - x^2) / R over the contact [-]: the
        shares of a row add up to 1 where a1 > 0, else 0.
    """
    length0 = min(max(a0 - left, 0.0), width)
    length = min(max(a1 - left, 0.0), width)
    right = left + length
    load = a1 * a1 * length - (right * right * right - left * left * left) / 3.0  # int of a^2 - x^2, covered part
    total = 2.0 * a1 * a1 * a1 / 3.0
    share = load / total if total > 0.0 else 0.0
    change = a1 - a0
    if min(a0, a1) < left + width and max(a0, a1) > left and abs(change) > 1e-9 * width:
        # the covered length changes slope within the step: its exact mean
        return (_covered_integral(a1, left, width) - _covered_integral(a0, left, width)) / change, share
    return 0.5 * (length0 + length), share


@numba.njit(**_COMPILE)
def _covered_integral(a, left, width):
    """The integral over the contact radius, from 0 to ``a``, of a cell's covered length clip(a - left, 0, width)."""
    inside = min(max(a - left, 0.0), width)
    return 0.5 * inside * inside + width * max(a - left - width, 0.0)


@numba.njit(**_COMPILE)
def cell_moments(elements):
    """c_i, the integral of x^2 over each of ``elements`` cells of width 1 / elements on [0, 1] [a_max^3]."""
    width = 1.0 / elements
    c = np.empty(elements)
    for i in range(elements):
        left = i * width
        c[i] = ((left + width) ** 3.0 - left ** 3.0) / 3.0
    return c


@numba.njit(**_COMPILE)
def row_weights(a0, a1, cap, stiffness, c, limit, mean):
    """Each cell's limit and mean covered length over one step, into ``limit`` and ``mean`` (arrays (N,)); ``c`` is
    :func:`cell_moments`.

    A cell's limit is its share of the Coulomb cap ``cap`` = mu P+ [N] at the step's end over the row's
    ``stiffness`` 2 G* a_max [N/m].  A cell covered all through the step has mean length ``width`` and limit
    cap / stiffness (a^2 width - c_i) / (2 a^3 / 3), with c_i the integral of x^2 over the cell; a cell beyond the
    contact at the step's end has limit 0 (that formula is negative there), which clears what it held.  Only the
    band the contact's edge crosses is weighed cell by cell (:func:`cell_weight`).
    """
    elements = limit.size
    width = 1.0 / elements
    scale = cap / (stiffness * (2.0 / 3.0) * a1 * a1 * a1) if a1 > 0.0 else 0.0
    for i in range(elements):
        limit[i] = max(scale * (a1 * a1 * width - c[i]), 0.0)
        mean[i] = width
    low = min(max(math.floor(min(a0, a1) * elements), 0), elements)
    high = min(max(math.ceil(a1 * elements), 0), elements)
    for i in range(low, high):
        mean[i], share = cell_weight(a0, a1, i * width, width)
        limit[i] = cap / stiffness * share


@numba.njit(**_COMPILE)
def hold(held, limit, mean, d_u):
    """One step of the row, in place: each cell's held displacement (the integral of u over its part in contact
    [m a_max]) grows by its mean covered length times the rigid displacement ``d_u`` [m] while it sticks, and is
    held to its limit when it slides.  Returns the row's sum [m a_max]."""
    total = 0.0
    for i in range(held.size):
        value = min(max(held[i] + mean[i] * d_u, -limit[i]), limit[i])
        held[i] = value
        total += value
    return total


@numba.njit(**_COMPILE)
def march(xi_a, cap, impulse, dt, stiffness, inverse_mass, g_t, slip0, held):
    """Advance the element row and the slip through one contact, by velocity Verlet.

    Parameters
    ----------
    xi_a : array (M + 1,)
        Contact radius over a_max at the step ends [-].
    cap : array (M + 1,)
        Coulomb cap mu P+ at the step ends [N]; zero at the first.
    impulse : array (M,)
        mu times the normal impulse of P+ over each step [N s].
    dt, stiffness, inverse_mass, g_t, slip0 : float
        Step [s]; 2 G* a_max, the row's tangential force per unit of held displacement [N/m]; (1 + 1/alpha) / m,
        the slip's acceleration per unit tangential force [1/kg]; gravity along the flat [m/s^2]; the slip
        velocity v_t - omega R at the start [m/s].
    held : array (N,)
        The cells' integrals of u at the start [m a_max] (zero: a fresh contact); advanced in place.

    Returns
    -------
    force, tangential_impulse : arrays (M + 1,)
        Tangential force on the ball [N] and the tangential impulse on it since the start [N s], at the step
        ends.  The tangential impulse of a step is the mean of the friction fraction F / (mu P+) at its ends
        times mu dJ+; at the contact's ends, where the cap is 0, the fraction keeps its neighbour's value.
    """
    points = xi_a.size
    force, j_t = np.zeros(points), np.zeros(points)
    limit, mean, c = np.empty(held.size), np.empty(held.size), cell_moments(held.size)
    slip, f_now, phi_now, j_now = slip0, 0.0, 0.0, 0.0
    half_dt2 = 0.5 * dt * dt
    for n in range(points - 1):
        row_weights(xi_a[n], xi_a[n + 1], cap[n + 1], stiffness, c, limit, mean)
        d_u = dt * slip + half_dt2 * (f_now * inverse_mass + g_t)
        f_next = -stiffness * hold(held, limit, mean, d_u)
        phi_next = f_next * (1.0 / cap[n + 1]) if cap[n + 1] > 0.0 else phi_now
        step_impulse = 0.5 * ((phi_now if n else phi_next) + phi_next) * impulse[n]
        j_now += step_impulse
        slip = slip + step_impulse * inverse_mass + g_t * dt
        force[n + 1], j_t[n + 1] = f_next, j_now
        f_now, phi_now = f_next, phi_next
    return force, j_t


@numba.njit(**_COMPILE)
def motion(t, force, j_t, cap, v_t, g_t, mass, spin, spin_arm, stick_below):
    """The ball's tangential motion from a march (:func:`march`'s force and impulse at the step ends t [s]), written
    into arrays allocated once, in the order of numpy's element-wise and running-sum arithmetic (so the same bits).

    Parameters
    ----------
    t, force, j_t, cap : arrays (M + 1,)
        Step ends [s], the tangential force [N], its impulse since the start [N s] and the cap mu P+ [N] there.
    v_t, g_t, mass, spin : float
        Incoming tangential velocity [m/s], gravity along the flat [m/s^2], mass [kg], incoming spin [rad/s].
    spin_arm : float
        alpha m R, the impulse per change of spin [kg m].
    stick_below : float
        A step end sticks where |F| / (mu P+) is below it (1 - the stick tolerance).

    Returns
    -------
    fraction : array (M + 1,)
        F / (mu P+), at the contact's ends (cap 0) the nearest value where it is defined (0 if none is).
    stuck : bool array (M + 1,)
        Whether part of the contact sticks.
    v, omega, x : arrays (M + 1,)
        Centre velocity [m/s], spin [rad/s] and displacement [m] along the flat: x by the trapezoidal rule with
        its end correction, dt^2 / 12 times the change of acceleration.
    switches : int
        Changes between sliding and sticking over the interior step ends.
    first_stuck : int
        Index of the first step end that sticks, -1 if none does.
    """
    points = t.size
    fraction, stuck = np.empty(points), np.empty(points, dtype=np.bool_)
    v, omega, x, accel = np.empty(points), np.empty(points), np.empty(points), np.empty(points)
    first_finite, last_finite, first_stuck = -1, -1, -1
    for k in range(points):
        ratio = force[k] / cap[k] if cap[k] > 0.0 else np.nan
        fraction[k] = ratio
        if math.isfinite(ratio):
            last_finite = k
            if first_finite < 0:
                first_finite = k
        stuck[k] = cap[k] > 0.0 and abs(ratio) < stick_below
        if stuck[k] and first_stuck < 0:
            first_stuck = k
        v[k] = v_t + g_t * t[k] + j_t[k] / mass
        omega[k] = spin - j_t[k] / spin_arm
        accel[k] = force[k] / mass + g_t
    for k in range(points):  # the ends, where the cap is 0: the nearest defined fraction
        if first_finite < 0:
            fraction[k] = 0.0
        elif k < first_finite:
            fraction[k] = fraction[first_finite]
        elif k > last_finite:
            fraction[k] = fraction[last_finite]
        elif not math.isfinite(fraction[k]):
            fraction[k] = 0.0
    dt = t[1] - t[0]
    half_dt, end_term = 0.5 * dt, dt * dt / 12.0
    x[0] = 0.0
    for k in range(points - 1):
        piece = half_dt * (v[k + 1] + v[k]) + end_term * (accel[k] - accel[k + 1])
        x[k + 1] = piece if k == 0 else x[k] + piece
    switches = 0
    for k in range(1, points - 2):  # the ends have no contact
        if stuck[k + 1] != stuck[k]:
            switches += 1
    return fraction, stuck, v, omega, x, switches, first_stuck


@numba.njit(types.Tuple((ARRAY, ARRAY, ARRAY, ARRAY, types.float64))(
    NORMAL, types.FunctionType(SIGNATURE), ARRAY, ARRAY, types.float64, types.float64, types.int64), **_COMPILE)
def samples(normal, force, params, pushing, t_f, delta_m, steps):
    """What the march reads of the normal motion, on ``steps`` equal steps of [0, t_f]: ``microslip._samples``
    compiled, each number that function's to the bit (tests/test_microslip.py), for a force pushing over one interval.

    Parameters
    ----------
    normal, force, params : tuple, kernel, array
        The motion's :meth:`~..motion.KernelState.arrays`, its law's compiled force [N] and the force's parameters.
    pushing : array
        The one pushing interval's numbers (``rigid_kernel.PUSHING``).
    t_f, delta_m : float
        Separation [s] and the motion's maximum compression [m].
    steps : int
        Time steps M.

    Returns
    -------
    t, xi_a, load, step_impulse, delta_m
        The step ends (numpy's ``linspace(0, t_f, M + 1)``) [s], the contact radius over a_max there [-], P+ [N]
        (0 at the ends), the impulse of P+ over each step [N s] (M,), and a_max^2 / R [m], the larger of
        ``delta_m`` and the largest sampled compression.
    """
    points = steps + 1
    t, xi_a, load, step_impulse = np.empty(points), np.empty(points), np.empty(points), np.empty(steps)
    a, b = pushing[0], pushing[1]
    step = t_f / steps  # numpy's linspace: k step + 0, the last one t_f itself
    largest, before = -np.inf, 0.0
    for k in range(points):
        instant = t_f if k == steps else (k * step if step != 0.0 else k / steps * t_f) + 0.0
        compression, rate = normal_state(normal, instant)
        delta = compression if compression >= 0.0 or compression != compression else 0.0  # np.maximum's rule
        if largest == largest and not delta <= largest:  # np.max's: a NaN, once met, is the largest
            largest = delta
        p = force(compression, rate, params)
        load[k] = 0.0 if k == 0 or k == steps else (p if p >= 0.0 or p != p else 0.0)
        if a <= instant <= b:  # J+ (PositiveImpulse.from_impulse): inside the interval, read off this state
            positive = positive_impulse_inside(pushing, instant, rate)
        else:
            positive = positive_impulse(normal, pushing, instant)
        if k:
            step_impulse[k - 1] = positive - before
        t[k], xi_a[k], before = instant, delta, positive
    delta_m = largest if largest > delta_m else delta_m  # Python's max(delta_m, largest)
    for k in range(points):
        xi_a[k] = math.sqrt(xi_a[k] / delta_m)
    return t, xi_a, load, step_impulse, delta_m


@numba.njit(**_COMPILE)
def quasi_static(xi_a, cap, displacement, stiffness, elements):
    """The tangential force of the contact under a prescribed history, without inertia.

    Parameters
    ----------
    xi_a, cap, displacement : arrays (K,)
        Contact radius over a_max [-], Coulomb cap mu P+ [N] and the rigid tangential displacement of the bodies
        U [m] at K instants, starting from a fresh contact at the first.
    stiffness : float
        2 G* a_max [N/m].
    elements : int
        Cells of the element row.

    Returns
    -------
    array (K,)
        The tangential force Q = 2 G* int u dx [N] on the moving body, positive along U (the force that holds
        it; the force on the ball in :class:`~.microslip.MicroslipTangential` is its opposite).
    """
    held, limit, mean, c = np.zeros(elements), np.empty(elements), np.empty(elements), cell_moments(elements)
    force = np.zeros(xi_a.size)
    for n in range(xi_a.size - 1):
        row_weights(xi_a[n], xi_a[n + 1], cap[n + 1], stiffness, c, limit, mean)
        force[n + 1] = stiffness * hold(held, limit, mean, displacement[n + 1] - displacement[n])
    return force


def compile_all() -> None:
    """Compile every kernel of this module (or load them from the disk cache), on small inputs of the types the
    contact passes: what a fresh process pays once, before its first microslip impact (``results/bench.csv``)."""
    xi_a, cap = np.array([0.0, 0.5, 0.0]), np.array([0.0, 1.0, 0.0])
    force, j_t = march(xi_a, cap, np.array([1e-6, 1e-6]), 1e-6, 1.0, 1.0, 0.0, 0.1, np.zeros(8))
    motion(np.array([0.0, 1e-6, 2e-6]), force, j_t, cap, 1.0, 0.0, 1.0, 0.0, 1.0, 0.999)
    quasi_static(xi_a, cap, np.zeros(3), 1.0, 8)
