"""The built-in laws' compiled force kernels: P(delta, delta_dot, params) [N] as numba functions.

A kernel is the law's ``scalar`` formula compiled for one signature, :data:`SIGNATURE` (delta [m], delta_dot
[m/s] and the parameters the law's :class:`~.base.Kernel` packs, a float64 array), so the compiled integrator of
the normal motion (:mod:`sphereimpact.integrators.dop853_kernel`) calls it through a function pointer: one compiled
integrator serves every law, and numba caches it on disk once for all of them.  Each kernel is the scalar formula's
arithmetic in its order, so the two agree bit for bit (tests/test_kernels.py).

numba is imported when this module is (on the first compiled integration), never by a command that does not
integrate a law this way.  A kernel is written here as a plain function and compiled for :data:`SIGNATURE` when a
law first asks for it (:func:`compiled`), or loaded from the disk cache beside this file: a process pays for the
laws it integrates only.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types
from ...kernel_cache import refresh

refresh()  # before any kernel is defined: numba's cache of them true to every source they compile

#: P = kernel(delta, delta_dot, params): the one signature of every force kernel.
SIGNATURE = types.float64(types.float64, types.float64, types.float64[::1])
#: series(x, y, numbers, gamma, order, xs, ys): the one signature of every series kernel, which writes the Taylor
#: coefficients of orders 0 to ``order`` of x and y into ``xs`` and ``ys`` (the law's ``series``, compiled for
#: the compiled Taylor method, :mod:`sphereimpact.integrators.taylor_kernel`).
SERIES_SIGNATURE = types.none(types.float64, types.float64, types.float64[::1], types.float64, types.int64,
                              types.float64[::1], types.float64[::1])
#: Cache the machine code on disk; IEEE semantics (no fast-math): the scalar formula's numbers, bit for bit.
_COMPILE = {"cache": True, "nogil": True, "error_model": "numpy"}


#: 1/n!, n = 1..8: the ramp's Taylor continuation (linear.py's; not imported from there, which imports this
#: module's importer: the bit-for-bit test holds the two equal).
_INVERSE_FACTORIALS = tuple(1.0 / math.factorial(n) for n in range(1, 9))
_COMPILED: dict = {}


def compiled(function, signature=SIGNATURE):
    """``function`` (a kernel of this module or a plug-in's, a plain Python function) compiled for ``signature``
    (:data:`SIGNATURE`, or :data:`SERIES_SIGNATURE` for a series kernel), once per process."""
    if function not in _COMPILED:
        _COMPILED[function] = numba.njit(signature, **_COMPILE)(function)
    return _COMPILED[function]


@numba.njit(**_COMPILE)
def _power(delta, n):
    """sign(delta) |delta|^n (``hertz._power_scalar``)."""
    return abs(delta) ** n if delta >= 0.0 else -(abs(delta) ** n)


@numba.njit(**_COMPILE)
def _ramp(u):
    """1 - exp(-u) continued past u = 0 by its degree-8 Taylor polynomial (``linear.ramp_scalar``)."""
    if u >= 0.0:
        return -math.expm1(-u)
    w, poly = min(-u, 1.0), 0.0
    for i in range(len(_INVERSE_FACTORIALS) - 1, -1, -1):
        poly = (poly + _INVERSE_FACTORIALS[i]) * w
    return -poly


def kelvin_voigt(delta, delta_dot, p):
    """k delta + b delta_dot; p = (k, b)."""
    return p[0] * delta + p[1] * delta_dot


def modified(delta, delta_dot, p):
    """Eq. 4.2, k delta + b delta_dot (1 - exp(-c delta / R)) with the ramp continued; p = (k, b, c, R)."""
    return p[0] * delta + p[1] * delta_dot * _ramp(p[2] * delta / p[3])


def linear_hunt_crossley(delta, delta_dot, p):
    """k delta (1 + chi delta_dot); p = (k, chi)."""
    return p[0] * delta * (1.0 + p[1] * delta_dot)


def hertz(delta, delta_dot, p):
    """k sign(delta) |delta|^(3/2); p = (k,)."""
    return p[0] * _power(delta, 1.5)


def hunt_crossley(delta, delta_dot, p):
    """k sign(delta) |delta|^n (1 + chi delta_dot); p = (k, n, chi)."""
    return p[0] * _power(delta, p[1]) * (1.0 + p[2] * delta_dot)


# --- series kernels: the laws' ``series`` (contact/laws/linear.py), their arithmetic in its order ---------------
def kelvin_voigt_series(x, y, numbers, gamma, order, xs, ys):
    """``linear.kelvin_voigt_series`` into xs, ys; numbers = (zeta,)."""
    two_zeta = 2.0 * numbers[0]
    xs[0], ys[0] = x, y
    for k in range(order):
        xs[k + 1] = ys[k] / (k + 1)
        ys[k + 1] = ((gamma if k == 0 else 0.0) - xs[k] - two_zeta * ys[k]) / (k + 1)


def modified_series(x, y, numbers, gamma, order, xs, ys):
    """``linear.modified_series`` into xs, ys; numbers = (zeta, lam).  The convolution c_k summed from i = 0 up,
    as Python's ``sum`` adds."""
    two_zeta, lam = 2.0 * numbers[0], numbers[1]
    es = np.empty(order + 1)
    xs[0], ys[0], es[0] = x, y, math.exp(-lam * x)
    ramp = -math.expm1(-lam * x)
    for k in range(order):
        c = 0.0
        for i in range(k + 1):
            c += ys[i] * es[k - i]
        damping = ys[0] * ramp if k == 0 else ys[k] - c
        xs[k + 1] = ys[k] / (k + 1)
        ys[k + 1] = ((gamma if k == 0 else 0.0) - xs[k] - two_zeta * damping) / (k + 1)
        es[k + 1] = -lam * c / (k + 1)


def linear_hunt_crossley_series(x, y, numbers, gamma, order, xs, ys):
    """``linear.linear_hunt_crossley_series`` into xs, ys; numbers = (chi_v,)."""
    q = numbers[0]
    xs[0], ys[0] = x, y
    for k in range(order):
        xy = 0.0
        for i in range(k + 1):
            xy += xs[i] * ys[k - i]
        xs[k + 1] = ys[k] / (k + 1)
        ys[k + 1] = ((gamma if k == 0 else 0.0) - xs[k] - q * xy) / (k + 1)
