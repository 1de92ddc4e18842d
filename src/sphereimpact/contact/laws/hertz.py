"""Laws with a Hertz spring k delta^n: elastic Hertz, and Hunt-Crossley damping on it.

k is the constant of the spring term in N/m^n (n = 3/2 for Hertz: k = (4/3) E* sqrt(R), which
``modulus`` = E* [Pa] gives instead).  There is no omega_n: the time scale is the elastic contact's,
T = delta_s / v_n with delta_s = ((n + 1) m v_n^2 / (2 k))^(1/(n+1)) the elastic maximum compression,
and in tau = t / T, x = delta / (v_n T), y = delta_dot / v_n the weightless motion is y' = -P_hat,

    P_hat = (n + 1) / 2 x^n (1 + chi v_n y)      (family: n and chi v_n).

Elastic Hertz (chi = 0) has the closed form t_f = (2 / (n + 1)) B(1 / (n + 1), 1/2) T, delta_m = v_n T.
"""

from __future__ import annotations

import numpy as np

from ..parameters import Parameter
from .base import LAWS, ContactLaw, Kernel, Spring
from .linear import CHI, hunt_crossley_relations

K = Parameter("k", "N/m^n", "constant of the spring term k delta^n (Hertz: (4/3) E* sqrt(R))",
              "a finite number > 0", lambda x: x > 0)
EXPONENT = Parameter("exponent", "-", "exponent n of the spring term k delta^n (3/2 for Hertz)",
                     "a finite number in [1, 3]", lambda x: (x >= 1) & (x <= 3), 1.5)
HERTZ = 1.5


def hertz_frequency(p, n=HERTZ):
    """1 / T = v_n / delta_s [1/s], delta_s = ((n + 1) m v_n^2 / (2 k))^(1/(n+1)) (elastic maximum compression)."""
    return p.v_normal / ((n + 1.0) * p.mass * p.v_normal ** 2 / (2.0 * p.k)) ** (1.0 / (n + 1.0))


def _power(delta, n):
    """sign(delta) |delta|^n: k delta^n continued as an odd function (C^1 at 0 for n >= 1)."""
    return np.sign(delta) * np.abs(delta) ** n


def hertz_continued(delta, delta_dot, p):
    """k sign(delta) |delta|^(3/2)."""
    return p.k * _power(np.asarray(delta, dtype=float), HERTZ)


def hunt_crossley_continued(delta, delta_dot, p):
    """k sign(delta) |delta|^n (1 + chi delta_dot)."""
    delta, delta_dot = np.asarray(delta, dtype=float), np.asarray(delta_dot, dtype=float)
    return p.k * _power(delta, p.exponent) * (1.0 + p.chi * delta_dot)


def _power_scalar(delta: float, n: float) -> float:
    """sign(delta) |delta|^n for one Python float."""
    return abs(delta) ** n if delta >= 0.0 else -(abs(delta) ** n)


def hertz_scalar(delta: float, delta_dot: float, p) -> float:
    """k sign(delta) |delta|^(3/2) for Python floats."""
    return p.k * _power_scalar(delta, HERTZ)


def hunt_crossley_scalar(delta: float, delta_dot: float, p) -> float:
    """k sign(delta) |delta|^n (1 + chi delta_dot) for Python floats."""
    return p.k * _power_scalar(delta, p.exponent) * (1.0 + p.chi * delta_dot)


def hunt_crossley_scaled(x, y, numbers):
    """Dimensionless form P_hat = (n + 1) / 2 sign(x) |x|^n (1 + q y), q = chi v_n; elastic Hertz is q = 0,
    n = 3/2 (see :attr:`~sphereimpact.contact.laws.ContactLaw.scaled`)."""
    n = numbers.get("exponent", HERTZ)
    return 0.5 * (n + 1.0) * _power(np.asarray(x, dtype=float), n) * (1.0 + numbers.get("chi_v", 0.0) * y)


def hertz_rate(delta, delta_dot, delta_ddot, p):
    """dP/dt = (3/2) k delta^(1/2) delta_dot [N/s]."""
    return HERTZ * p.k * np.sqrt(np.maximum(delta, 0.0)) * np.asarray(delta_dot, dtype=float)


def hunt_crossley_rate(delta, delta_dot, delta_ddot, p):
    """dP/dt = n k delta^(n-1) delta_dot (1 + chi delta_dot) + k delta^n chi delta_ddot [N/s]."""
    delta, delta_dot = np.maximum(np.asarray(delta, dtype=float), 0.0), np.asarray(delta_dot, dtype=float)
    return p.k * (p.exponent * delta ** (p.exponent - 1.0) * delta_dot * (1.0 + p.chi * delta_dot)
                  + delta ** p.exponent * p.chi * np.asarray(delta_ddot, dtype=float))


LAWS.register(ContactLaw(
    "hertz", "elastic Hertz contact, P = k delta^(3/2), k = (4/3) E* sqrt(R)",
    (K,), hertz_continued, hertz_frequency,
    family=lambda p: {}, horizon=lambda p: np.full(np.shape(p.mass), 100.0 * np.pi), spring=Spring.HERTZ,
    scaled=hunt_crossley_scaled, scalar=hertz_scalar, rate=hertz_rate, passive=True,
    kernel=Kernel("hertz", lambda p: (p.k,))))

LAWS.register(ContactLaw(
    "hunt-crossley", "Hertz spring with Hunt-Crossley damping, P = k delta^n (1 + chi delta_dot), n = 3/2 by default",
    (K, CHI, EXPONENT), hunt_crossley_continued, lambda p: hertz_frequency(p, p.exponent),
    family=lambda p: {"exponent": p.exponent, "chi_v": p.chi * p.v_normal},
    horizon=lambda p: 100.0 * np.pi * (1.0 + p.chi * p.v_normal),
    spring=Spring.HERTZ, damping="chi", cor_relations=hunt_crossley_relations(), scaled=hunt_crossley_scaled,
    scalar=hunt_crossley_scalar, rate=hunt_crossley_rate, passive=True,
    kernel=Kernel("hunt_crossley", lambda p: (p.k, p.exponent, p.chi))))
