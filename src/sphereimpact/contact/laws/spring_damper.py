"""Eq. 4.1's exact solution, the closed form a law declares (``ContactLaw.closed_form``).

Inside contact m delta'' + b delta' + k delta = m g_n is linear.  With the static offset d_s = m g_n / k,
x = delta - d_s, sigma = zeta omega_n, the solution from x(0) = x0, x'(0) = v0 is

    x(t)  = E(t) [x0 C(t) + (v0 + sigma x0) S(t)]
    x'(t) = E(t) [v0 C(t) - (omega_n^2 x0 + sigma v0) S(t)]

with, for zeta <= 1 (under- and critically damped, omega_d = omega_n sqrt(1 - zeta^2)),
E = exp(-sigma t), C = cos(omega_d t), S = sin(omega_d t) / omega_d (= t at zeta = 1);
and for zeta > 1 (q = omega_n sqrt(zeta^2 - 1), r1 = -omega_n / (zeta + sqrt(zeta^2 - 1)) the slow
root), E = exp(r1 t), C = (1 + exp(-2 q t)) / 2, S = -expm1(-2 q t) / (2 q).  These forms never subtract
nearly equal numbers (x'(t) over-damped is written with C - sigma S = (r1 - r2 exp(-2 q t)) / (2 q), see
:func:`spring_damper_state`), so they are accurate to a few ulp in every regime, including zeta -> 1
from either side and zeta in the thousands.

Two forms of the one solution live here: :class:`SpringDamperMotion`, one scene in SI units (the ``closed``
integrator wraps it, :mod:`sphereimpact.integrators.closed_form`; compiled code reads it through
:func:`spring_damper_state`, the kind :data:`KERNEL_KIND` of :mod:`sphereimpact.contact.normal_kernel`), and
:func:`events`, the weightless motion's dimensionless events for many damping ratios at once (the sweep's ``closed``
path).
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import ImpactError
from ...ode.dense import is_instant
from ..separation import Separation
from .closed_form import ClosedForm

#: The kind of compiled normal motion (``KernelState.kind``, beside ``ode.dense.TAYLOR`` and ``DOP853``) that is this
#: closed form: :func:`spring_damper_state` of :attr:`SpringDamperMotion.constants`.
KERNEL_KIND = 2


class SpringDamperMotion:
    """Eq. 4.1's exact motion delta(t) of one scene from first touch, in SI units.

    Parameters
    ----------
    scene
        Anything with ``omega_n`` [rad/s], ``zeta`` [-], ``mass`` [kg], ``g_normal`` [m/s^2], ``k`` [N/m],
        ``b`` [N s/m], ``v_normal`` [m/s] and ``separation`` (a :class:`sphereimpact.Scene`).

    Attributes
    ----------
    weightless : bool
        No gravity along the normal: :meth:`events` gives t_m and t_f as formulas.
    constants : tuple of float
        What :func:`spring_damper_state` reads.
    per_instant : bool
        Every read is :func:`spring_damper_state` instant by instant (weightless), so compiled code may read the
        motion from ``constants``.
    scan_end : float
        [s] A time past any separation of a contact that ends, for root searches with gravity.

    Raises
    ------
    ImpactError
        When the over-damped contact's slow rate omega_n / (2 zeta) underflows double precision.
    """

    def __init__(self, scene):
        self.scene = scene
        w, zeta = scene.omega_n, scene.zeta
        self._w2, self._sigma = w * w, zeta * w
        self._offset = scene.mass * scene.g_normal / scene.k
        self._x0, self._v0 = -self._offset, scene.v_normal
        self.weightless = self._offset == 0.0
        if zeta <= 1.0:
            self._under, self._freq = True, w * math.sqrt(max(0.0, 1.0 - zeta * zeta))
            self.scan_end = min(2 * math.pi / self._freq if self._freq > 0 else math.inf,
                                60.0 / self._sigma if self._sigma > 0 else math.inf)
        else:
            root = math.sqrt(zeta * zeta - 1.0)
            self._under, self._freq = False, w * root
            self._slow = -w / (zeta + root)
            if not self._slow < 0.0:  # w / (2 zeta) underflowed
                raise ImpactError(f"the over-damped contact's slow rate omega_n / (2 zeta) underflows double "
                                  f"precision (zeta = {zeta:.3g}): outside what the model computes")
            self.scan_end = 60.0 / -self._slow
        #: What :func:`spring_damper_state` reads: the regime, sigma, omega_d or q, omega_n^2, x0, v0, offset, r1.
        self.constants = (1.0 if self._under else 0.0, self._sigma, self._freq, self._w2, self._x0, self._v0,
                          self._offset, self._slow if not self._under else 0.0)
        #: Every read of the motion is :func:`spring_damper_state` instant by instant, so compiled code reading it
        #: from :attr:`constants` gives the same bits (the weightless motion's; see :meth:`state`).
        self.per_instant = self.weightless

    def events(self) -> tuple[float, float | None]:
        """t_m and t_f [s] in closed form, for a contact without gravity (x0 = 0); t_f None when the
        criterion never ends contact (penetration, critically or over-damped: delta never returns to 0).

        Under-damped, with theta = omega_d t: delta = E v0 sin(theta) / omega_d and delta_dot = E v0
        (cos(theta) - sigma sin(theta) / omega_d), so maximum compression is at theta = atan2(omega_d,
        sigma); delta returns to 0 at theta = pi; P = k delta + b delta_dot = E v0 (A sin(theta) + b
        cos(theta)), A = (k - b sigma) / omega_d, falls to 0 at theta = pi - atan2(b, A), before pi (P
        starts at b v0 > 0).  Critically and over-damped, with the roots r1 (slow) and r2 of m r^2 + b r
        + k = 0: delta = v0 (e^(r1 t) - e^(r2 t)) / (r1 - r2) > 0 for every t > 0, maximum compression at
        t_m = ln(r2 / r1) / (r1 - r2) = acosh(zeta) / q, and since k + b r = -m r^2, P = 0 at
        e^((r1 - r2) t) = (r2 / r1)^2: t_f = 2 t_m (1 / omega_n and 2 / omega_n at zeta = 1).  No root
        search, so no cancellation (a search on P = k delta + b delta_dot, two terms 1e6 times their
        difference at zeta = 5361, would miss t_f by 1 %).
        """
        s, w, zeta = self.scene, self.scene.omega_n, self.scene.zeta
        if self._under and self._freq > 0.0:
            wd = self._freq
            t_m = math.atan2(wd, self._sigma) / wd
            if s.separation.pulls:
                return t_m, math.pi / wd
            return t_m, (math.pi - math.atan2(s.b, (s.k - s.b * self._sigma) / wd)) / wd
        root = math.sqrt((zeta - 1.0) * (zeta + 1.0))  # no cancellation as zeta -> 1
        t_m = 1.0 / w if root == 0.0 else math.acosh(zeta) / (w * root)
        return t_m, None if s.separation.pulls else 2.0 * t_m

    def state(self, t):
        """Compression delta [m] and its rate delta_dot [m/s] at time(s) t [s]: :func:`spring_damper_state` at each
        instant, in plain floats, so that an instant read alone or among many has the same bits (compiled code
        evaluates the very function: :attr:`per_instant`).  With gravity, whose events are roots on a scan of
        thousands of instants, many instants at once are numpy's (:meth:`_basis`: the same formulas, a few ulp
        apart, vectorised where instant by instant costs the scan most of the impact)."""
        if is_instant(t):
            return spring_damper_state(self.constants, float(t))
        t = np.asarray(t, dtype=float)
        if not self.per_instant:
            e, c, s, damped = self._basis(t)
            x0, v0 = self._x0, self._v0
            x = e * (x0 * c + (v0 + self._sigma * x0) * s)
            xd = e * (v0 * damped - self._w2 * x0 * s)
            return x + self._offset, xd
        if not t.size:
            return np.empty(t.shape), np.empty(t.shape)
        delta, delta_dot = zip(*[spring_damper_state(self.constants, instant) for instant in t.ravel().tolist()])
        return np.array(delta).reshape(t.shape), np.array(delta_dot).reshape(t.shape)

    def _basis(self, t):
        """(E, C, S, C - sigma S) at the instants t [s] (an array), numpy's (see :func:`spring_damper_state`)."""
        if self._under:
            e, c, s = np.exp(-self._sigma * t), np.cos(self._freq * t), t * np.sinc(self._freq * t / math.pi)
            return e, c, s, c - self._sigma * s
        q, q2t = self._freq, 2.0 * self._freq * t  # q > 0 for zeta > 1; expm1 keeps S exact as q t -> 0
        d = np.exp(-q2t)
        return (np.exp(self._slow * t), 0.5 * (1.0 + d), -np.expm1(-q2t) / (2.0 * q),
                (self._slow + (self._sigma + q) * d) / (2.0 * q))


def spring_damper_state(constants, t: float) -> tuple[float, float]:
    """(delta [m], delta_dot [m/s]) of eq. 4.1's exact motion at one instant t [s], in plain floats, from
    :attr:`SpringDamperMotion.constants` (regime: 1 under- or critically damped, 0 over-damped; sigma [1/s];
    omega_d or q [1/s]; omega_n^2 [1/s^2]; x0 [m]; v0 [m/s]; the static offset [m]; r1 [1/s]).  Plain arithmetic
    and :mod:`math`, so that numba compiles this very function for the compiled reads of the motion.

    Under-damped: E = exp(-sigma t), C = cos(omega_d t), S = sin(omega_d t) / omega_d (t at omega_d t = 0).
    Over-damped, with D = exp(-2 q t): E = exp(r1 t), C = (1 + D) / 2, S = -expm1(-2 q t) / (2 q) (exact as q t ->
    0), and C - sigma S = (r1 + (sigma + q) D) / (2 q): 1 - sigma / q is computed as r1 itself, where the direct
    form subtracts nearly equal numbers (at zeta = 5361 it would lose 9 digits of delta_dot)."""
    under, sigma, freq, w2 = constants[0], constants[1], constants[2], constants[3]
    x0, v0, offset, slow = constants[4], constants[5], constants[6], constants[7]
    if under != 0.0:
        e, c = math.exp(-sigma * t), math.cos(freq * t)
        s = math.sin(freq * t) / freq if freq * t != 0.0 else t
        damped = c - sigma * s
    else:
        q2t = 2.0 * freq * t
        d = math.exp(-q2t)
        e, c, s = math.exp(slow * t), 0.5 * (1.0 + d), -math.expm1(-q2t) / (2.0 * freq)
        damped = (slow + (sigma + freq) * d) / (2.0 * freq)
    x = e * (x0 * c + (v0 + sigma * x0) * s)
    xd = e * (v0 * damped - w2 * x0 * s)
    return x + offset, xd


def _state(zeta, tau):
    """Dimensionless (x, y) at tau from x(0) = 0, y(0) = 1 (tau = omega_n t, x = delta omega_n / v_n,
    y = delta_dot / v_n): x = E S, y = E (C - zeta S) with E, C, S above, stable in every regime."""
    under = zeta <= 1
    w = np.sqrt(np.abs(1.0 - zeta * zeta))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        e_under, c_under, s_under = np.exp(-zeta * tau), np.cos(w * tau), tau * np.sinc(w * tau / np.pi)
        slow = -1.0 / (zeta + w)  # r1 = -(zeta - q), computed without cancellation
        q2t = 2.0 * w * tau
        e_over, c_over = np.exp(slow * tau), 0.5 * (1.0 + np.exp(-q2t))
        s_over = np.where(w > 0, -np.expm1(-q2t) / np.where(w > 0, 2.0 * w, 1.0), tau)
    e, c, s = (np.where(under, a, b) for a, b in ((e_under, e_over), (c_under, c_over), (s_under, s_over)))
    return e * s, e * (c - zeta * s)


def jet(numbers, tau):
    """The weightless motion at tau with its force: (x, y, P_hat, P_hat', P_hat''), P_hat = x + 2 zeta y, y' =
    -P_hat, so P_hat' = y - 2 zeta P_hat and P_hat'' = -P_hat - 2 zeta P_hat'."""
    zeta = np.asarray(numbers["zeta"], dtype=float)
    x, y = _state(zeta, tau)
    p = x + 2.0 * zeta * y
    dp = y - 2.0 * zeta * p
    return x, y, p, dp, -p - 2.0 * zeta * dp


def events(zeta, separation: Separation) -> dict:
    """Dimensionless outputs ``tau_m``, ``x_m``, ``tau_f``, ``y_f`` and ``j_p`` (the impulse of P_hat while
    positive, 1 - y where P_hat first falls to 0) of the weightless motion, one per damping ratio in ``zeta``.

    P_hat = x + 2 zeta y = E (2 zeta C + (1 - 2 zeta^2) S), so the events are explicit: maximum
    compression (y = 0) at tau_m = atan(w / zeta) / w (zeta < 1, w = sqrt(1 - zeta^2)), atanh(q / zeta) / q
    (zeta > 1, q = sqrt(zeta^2 - 1)), 1 at zeta = 1; delta = 0 at tau = pi / w (zeta < 1; never for
    zeta >= 1); P_hat = 0 at (pi - atan2(2 zeta w, 1 - 2 zeta^2)) / w (zeta < 1),
    atanh(2 zeta q / (2 zeta^2 - 1)) / q (zeta > 1), 2 at zeta = 1.

    Raises
    ------
    ImpactError
        For damping ratios >= 1 under the ``penetration`` criterion (delta never returns to 0).
    """
    zeta = np.asarray(zeta, dtype=float)
    w = np.sqrt(np.abs(1.0 - zeta * zeta))
    under, over = zeta < 1, zeta > 1
    with np.errstate(divide="ignore", invalid="ignore"):
        safe_w = np.where(w > 0, w, 1.0)
        tau_m = np.where(under, np.arctan2(w, zeta) / safe_w,
                         np.where(over, np.arctanh(w / zeta) / safe_w, 1.0))
        tau_force = np.where(under, (np.pi - np.arctan2(2 * zeta * w, 1 - 2 * zeta * zeta)) / safe_w,
                             np.where(over, np.arctanh(2 * zeta * w / (2 * zeta * zeta - 1)) / safe_w, 2.0))
    if separation.pulls:
        if not under.all():
            raise ImpactError(f"no separation: delta never returns to 0 under the '{separation}' criterion for "
                              f"{int((~under).sum())} scene(s) with zeta >= 1 (first: zeta = {zeta[~under][0]:.3g})")
        tau_f = np.pi / w
    else:
        tau_f = tau_force
    x_m = _state(zeta, tau_m)[0]
    y_f = _state(zeta, tau_f)[1]
    y_p = _state(zeta, np.minimum(tau_force, tau_f))[1]
    return {"tau_m": tau_m, "x_m": x_m, "tau_f": tau_f, "y_f": y_f, "j_p": 1.0 - y_p}


#: Eq. 4.1's closed form (the kelvin-voigt law's): the linear ODE with the family's zeta.
SPRING_DAMPER = ClosedForm("linear spring-damper", SpringDamperMotion,
                           lambda numbers, separation: events(numbers["zeta"], separation), ("zeta",), jet,
                           kernel_kind=KERNEL_KIND)
