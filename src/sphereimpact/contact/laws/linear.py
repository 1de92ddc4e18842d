"""Laws with a linear spring k delta: the chapter's eq. 4.1 and eq. 4.2, and Hunt-Crossley damping on it.

Time scale 1 / omega_n, omega_n = sqrt(k / m); in tau = omega_n t, x = delta omega_n / v_n, y = delta_dot / v_n the
weightless normal motion is y' = -P_hat with

- kelvin-voigt: P_hat = x + 2 zeta y                     (family: zeta = b / (2 sqrt(k m)))
- modified:     P_hat = x + 2 zeta y (1 - exp(-lam x))   (family: zeta, lam = c v_n / (omega_n R))
- linear-hunt-crossley: P_hat = x (1 + chi v_n y)        (family: chi v_n)

The chapter prints eq. 4.1 as P = k delta - b delta_dot and eq. 4.2 with exp(+100 delta / R) because its
delta is the (negative) displacement of the centre; with delta as compression both read as below.
"""

from __future__ import annotations

import math
from operator import mul

import numpy as np

from ..parameters import Parameter
from .base import LAWS, ContactLaw, Kernel
from .spring_damper import SPRING_DAMPER

K = Parameter("k", "N/m", "contact stiffness", "a finite number > 0", lambda x: x > 0, 60000.0)
B = Parameter("b", "N s/m", "contact damping", "a finite number >= 0", lambda x: x >= 0, 10.5)
RAMP = Parameter("ramp", "-", "constant c of the damping ramp 1 - exp(-c delta / R)", "a finite number > 0",
                 lambda x: x > 0, 100.0)
CHI = Parameter("chi", "s/m", "Hunt-Crossley damping factor in P = k delta^n (1 + chi delta_dot)",
                "a finite number >= 0", lambda x: x >= 0, 0.0)


def _arrays(delta, delta_dot):
    return np.asarray(delta, dtype=float), np.asarray(delta_dot, dtype=float)


def natural_frequency(p):
    """omega_n = sqrt(k / m) [rad/s]."""
    return np.sqrt(p.k / p.mass)


def damping_ratio(p):
    """zeta = b / (2 sqrt(k m)) [-]."""
    return p.b / (2.0 * np.sqrt(p.k * p.mass))


# --- eq. 4.1 ------------------------------------------------------------------------------------------
def kelvin_voigt_continued(delta, delta_dot, p):
    """k delta + b delta_dot for every delta (the linear law's own continuation)."""
    delta, delta_dot = _arrays(delta, delta_dot)
    return p.k * delta + p.b * delta_dot


def kelvin_voigt_scalar(delta: float, delta_dot: float, p) -> float:
    """k delta + b delta_dot for Python floats."""
    return p.k * delta + p.b * delta_dot


def kelvin_voigt_scaled(x, y, numbers):
    """Dimensionless eq. 4.1, P_hat = x + 2 zeta y (see :attr:`~sphereimpact.contact.laws.ContactLaw.scaled`)."""
    return x + 2.0 * numbers["zeta"] * y


def kelvin_voigt_rate(delta, delta_dot, delta_ddot, p):
    """dP/dt = k delta_dot + b delta_ddot [N/s]."""
    return p.k * np.asarray(delta_dot, dtype=float) + p.b * np.asarray(delta_ddot, dtype=float)


def kelvin_voigt_series(x: float, y: float, numbers: dict, gamma: float, order: int) -> tuple[list, list]:
    """Taylor coefficients of x and y (orders 0..order) at (x, y) of y' = -(x + 2 zeta y) + gamma, the
    dimensionless eq. 4.1 (see :attr:`~sphereimpact.contact.laws.ContactLaw.series`)."""
    two_zeta = 2.0 * float(numbers["zeta"])
    xs, ys = [x], [y]
    for k in range(order):
        xs.append(ys[k] / (k + 1))
        ys.append(((gamma if k == 0 else 0.0) - xs[k] - two_zeta * ys[k]) / (k + 1))
    return xs, ys


# --- eq. 4.2 ------------------------------------------------------------------------------------------
#: 1/n! for the Taylor continuation of the ramp.
_INVERSE_FACTORIALS = tuple(1.0 / math.factorial(n) for n in range(1, 9))


def ramp_continued(u):
    """1 - exp(-u) for u >= 0; for u < 0 its degree-8 Taylor polynomial, with u clipped at -1.

    No exponential is evaluated outside contact, the value is bounded, and the function is smooth to
    8th order across u = 0 (the polynomial's error is below 1e-16 for |u| < 0.01, far more than one step
    overshoots).
    """
    u = np.asarray(u, dtype=float)
    ramp = np.atleast_1d(-np.expm1(-np.maximum(u, 0.0)))
    negative = np.atleast_1d(u < 0)
    if negative.any():  # only the stages past separation pay for the polynomial
        w = np.minimum(-np.atleast_1d(u)[negative], 1.0)  # w = -u in (0, 1]
        poly = np.zeros_like(w)
        for c in reversed(_INVERSE_FACTORIALS):  # sum_{n=1..8} w^n / n!, by Horner
            poly = (poly + c) * w
        ramp[negative] = -poly
    return ramp.reshape(u.shape)


def modified_continued(delta, delta_dot, p):
    """Eq. 4.2 with the ramp continued past delta = 0 by :func:`ramp_continued`."""
    delta, delta_dot = _arrays(delta, delta_dot)
    return p.k * delta + p.b * delta_dot * ramp_continued(p.ramp * delta / p.radius)


def ramp_scalar(u: float) -> float:
    """:func:`ramp_continued` for one Python float (the same formula, evaluated with :mod:`math`)."""
    if u >= 0.0:
        return -math.expm1(-u)
    w, poly = min(-u, 1.0), 0.0
    for c in reversed(_INVERSE_FACTORIALS):
        poly = (poly + c) * w
    return -poly


def modified_scalar(delta: float, delta_dot: float, p) -> float:
    """Eq. 4.2 continued past delta = 0, for Python floats."""
    return p.k * delta + p.b * delta_dot * ramp_scalar(p.ramp * delta / p.radius)


def modified_scaled(x, y, numbers):
    """Dimensionless eq. 4.2, P_hat = x + 2 zeta y (1 - exp(-lam x)), the ramp continued past x = 0 as in
    :func:`modified_continued` (see :attr:`~sphereimpact.contact.laws.ContactLaw.scaled`)."""
    return x + 2.0 * numbers["zeta"] * y * ramp_continued(numbers["lam"] * x)


def ramp_per_x(x, lam):
    """(1 - exp(-lam x)) / x, and lam at x = 0: eq. 4.2's ramp per unit compression, entire in x (no 0 / 0)."""
    u = lam * x
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(u != 0, -np.expm1(-u) / np.where(u != 0, x, 1.0), lam)


def modified_per_compression(x, y, numbers):
    """Q = P_hat / x of eq. 4.2: 1 + 2 zeta y (1 - exp(-lam x)) / x, entire in x.

    P_hat = x Q has a forced zero at x = 0 (the ramp switches the damping off), so the force's sign inside
    the contact is Q's, and Q's first root after maximum compression is where the force falls to 0 (the
    force criterion's end, or tension).  At x = 0 it is G = 1 + 2 zeta lam y: at the rebound rate y_f, the
    force pulls before delta returns to 0 iff G < 0.  (See :attr:`ContactLaw.per_compression`.)
    """
    return 1.0 + 2.0 * numbers["zeta"] * y * ramp_per_x(x, numbers["lam"])


def modified_rate(delta, delta_dot, delta_ddot, p):
    """dP/dt = k delta_dot + b [delta_ddot (1 - exp(-u)) + delta_dot^2 (c/R) exp(-u)], u = c delta / R [N/s]."""
    delta, delta_dot = _arrays(delta, delta_dot)
    u = p.ramp * np.maximum(delta, 0.0) / p.radius
    return p.k * delta_dot + p.b * (np.asarray(delta_ddot, dtype=float) * -np.expm1(-u)
                                     + delta_dot * delta_dot * (p.ramp / p.radius) * np.exp(-u))


def modified_series(x: float, y: float, numbers: dict, gamma: float, order: int) -> tuple[list, list]:
    """Taylor coefficients of x and y (orders 0..order) at (x, y) of y' = -(x + 2 zeta y (1 - E)) + gamma,
    E = exp(-lam x), the dimensionless eq. 4.2 (see :attr:`~sphereimpact.contact.laws.ContactLaw.series`).

    E' = -lam y E, so with c_k = sum_i y_i E_(k-i) (the series of y E): E_(k+1) = -lam c_k / (k + 1), and
    the damping term's series is y_0 (1 - E_0) at order 0 (1 - E_0 by expm1: no cancellation near x = 0)
    and y_k - c_k above.  One convolution per order.
    """
    two_zeta, lam = 2.0 * float(numbers["zeta"]), float(numbers["lam"])
    xs, ys, es = [x], [y], [math.exp(-lam * x)]
    ramp = -math.expm1(-lam * x)
    for k in range(order):
        c = sum(map(mul, ys, reversed(es)))
        damping = ys[0] * ramp if k == 0 else ys[k] - c
        xs.append(ys[k] / (k + 1))
        ys.append(((gamma if k == 0 else 0.0) - xs[k] - two_zeta * damping) / (k + 1))
        es.append(-lam * c / (k + 1))
    return xs, ys


def modified_series_batched(x, y, two_zeta, lam, order: int):
    """:func:`modified_series` without gravity for many lanes at once (the sweep's Taylor lanes): x, y,
    two_zeta = 2 zeta and lam are arrays of equal length.  Returns the coefficients of orders 0 to ``order``
    as one array of shape (order + 1, 2, lanes), [:, 0] of x and [:, 1] of y, so one Horner pass evaluates
    both; the same recurrence, with the convolution c_k as one einsum over the lanes."""
    n = x.size
    z, es = np.empty((order + 1, 2, n)), np.empty((order + 1, n))
    xs, ys = z[:, 0], z[:, 1]
    xs[0], ys[0] = x, y
    u = lam * x
    es[0] = np.exp(-u)
    damping = y * -np.expm1(-u)  # y (1 - E) at order 0, without cancellation near x = 0
    for k in range(order):
        if k:
            c = np.einsum("in,in->n", ys[:k + 1], es[k::-1])  # the series of y E at order k
            damping = ys[k] - c
            es[k + 1] = c * (-lam / (k + 1))
        else:
            es[1] = -lam * y * es[0]
        xs[k + 1] = ys[k] * (1.0 / (k + 1))
        np.multiply(two_zeta, damping, out=ys[k + 1])
        ys[k + 1] += xs[k]
        ys[k + 1] *= -1.0 / (k + 1)
    return z


# --- Hunt-Crossley damping on a linear spring ---------------------------------------------------------
def linear_hunt_crossley_continued(delta, delta_dot, p):
    """k delta (1 + chi delta_dot) for every delta (a polynomial: its own continuation)."""
    delta, delta_dot = _arrays(delta, delta_dot)
    return p.k * delta * (1.0 + p.chi * delta_dot)


def linear_hunt_crossley_scalar(delta: float, delta_dot: float, p) -> float:
    """k delta (1 + chi delta_dot) for Python floats."""
    return p.k * delta * (1.0 + p.chi * delta_dot)


def linear_hunt_crossley_scaled(x, y, numbers):
    """Dimensionless form P_hat = x (1 + q y), q = chi v_n
    (see :attr:`~sphereimpact.contact.laws.ContactLaw.scaled`)."""
    return x * (1.0 + numbers["chi_v"] * y)


def linear_hunt_crossley_rate(delta, delta_dot, delta_ddot, p):
    """dP/dt = k delta_dot (1 + chi delta_dot) + k delta chi delta_ddot [N/s]."""
    delta, delta_dot = _arrays(delta, delta_dot)
    return p.k * (delta_dot * (1.0 + p.chi * delta_dot) + delta * p.chi * np.asarray(delta_ddot, dtype=float))


def linear_hunt_crossley_series(x: float, y: float, numbers: dict, gamma: float,
                                order: int) -> tuple[list, list]:
    """Taylor coefficients of x and y (orders 0..order) at (x, y) of y' = -x (1 + q y) + gamma, q = chi v_n
    (see :attr:`~sphereimpact.contact.laws.ContactLaw.series`): one convolution (x y) per order."""
    q = float(numbers["chi_v"])
    xs, ys = [x], [y]
    for k in range(order):
        xy = sum(map(mul, xs, reversed(ys)))
        xs.append(ys[k] / (k + 1))
        ys.append(((gamma if k == 0 else 0.0) - xs[k] - q * xy) / (k + 1))
    return xs, ys


def hunt_crossley_relations() -> dict:
    """The published COR -> chi relations for P = k delta^n (1 + chi delta_dot), v = approach speed v_n.

    Derived for the Hertz contact by energy balance, each an approximation whose real COR is measured in
    ``results/cor_relations.csv``:

    - Hunt & Crossley (1975): chi = 3 (1 - e) / (2 v)
    - Lankarani & Nikravesh (1990): chi = 3 (1 - e^2) / (4 v)
    - Flores, Machado, Silva & Martins (2011): chi = 8 (1 - e) / (5 e v)
    - Gonthier, McPhee, Lange & Piedboeuf (2004): chi = (1 - e^2) / (e v)
    """
    return {
        "hunt-crossley": lambda e, p: 1.5 * (1.0 - e) / p.v_normal,
        "lankarani-nikravesh": lambda e, p: 0.75 * (1.0 - e * e) / p.v_normal,
        "flores": lambda e, p: 1.6 * (1.0 - e) / (e * p.v_normal),
        "gonthier": lambda e, p: (1.0 - e * e) / (e * p.v_normal),
    }


LAWS.register(ContactLaw(
    "kelvin-voigt", "eq. 4.1, linear spring-damper P = k delta + b delta_dot (the chapter's 'previous' model)",
    (K, B), kelvin_voigt_continued, natural_frequency,
    family=lambda p: {"zeta": damping_ratio(p)},
    horizon=lambda p: 100.0 * np.pi * (1.0 + 2.0 * damping_ratio(p)),
    damping="b", scaled=kelvin_voigt_scaled, closed_form=SPRING_DAMPER, scalar=kelvin_voigt_scalar,
    rate=kelvin_voigt_rate, series=kelvin_voigt_series, passive=True,
    kernel=Kernel("kelvin_voigt", lambda p: (p.k, p.b)),
    series_kernel=Kernel("kelvin_voigt_series", lambda p: (p.family["zeta"],))))

LAWS.register(ContactLaw(
    "modified", "eq. 4.2, P = k delta + b delta_dot (1 - exp(-c delta/R)) (the chapter's model, c = ramp)",
    (K, B, RAMP), modified_continued, natural_frequency,
    family=lambda p: {"zeta": damping_ratio(p), "lam": p.ramp * p.v_normal / (natural_frequency(p) * p.radius)},
    horizon=lambda p: 100.0 * np.pi * (1.0 + 2.0 * damping_ratio(p)),
    damping="b", scaled=modified_scaled, ramp_rate=lambda p: p.ramp / p.radius, scalar=modified_scalar,
    rate=modified_rate, series=modified_series, per_compression=modified_per_compression, passive=True,
    kernel=Kernel("modified", lambda p: (p.k, p.b, p.ramp, p.radius)),
    series_kernel=Kernel("modified_series", lambda p: (p.family["zeta"], p.family["lam"]))))

LAWS.register(ContactLaw(
    "linear-hunt-crossley", "linear spring with Hunt-Crossley damping, P = k delta (1 + chi delta_dot)",
    (K, CHI), linear_hunt_crossley_continued, natural_frequency,
    family=lambda p: {"chi_v": p.chi * p.v_normal},
    horizon=lambda p: 100.0 * np.pi * (1.0 + p.chi * p.v_normal),
    damping="chi", cor_relations=hunt_crossley_relations(), scaled=linear_hunt_crossley_scaled,
    scalar=linear_hunt_crossley_scalar, rate=linear_hunt_crossley_rate, series=linear_hunt_crossley_series, passive=True,
    kernel=Kernel("linear_hunt_crossley", lambda p: (p.k, p.chi)),
    series_kernel=Kernel("linear_hunt_crossley_series", lambda p: (p.family["chi_v"],))))
