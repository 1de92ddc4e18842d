"""Vectorised closed form of the kelvin-voigt normal problem without gravity (dimensionless, one lane per scene).

From x(0) = 0, y(0) = 1:  x = E S,  y = E (C - zeta S),  P_hat = x + 2 zeta y = E (2 zeta C + (1 - 2 zeta^2) S),
with E, C, S as in :mod:`sphereimpact.integrators.closed_form`.  The events are explicit:

- maximum compression (y = 0): tau_m = atan(w / zeta) / w (zeta < 1, w = sqrt(1 - zeta^2)),
  atanh(q / zeta) / q (zeta > 1, q = sqrt(zeta^2 - 1)), 1 at zeta = 1;
- delta = 0: tau = pi / w (zeta < 1; never for zeta >= 1);
- P_hat = 0: tau = (pi - atan2(2 zeta w, 1 - 2 zeta^2)) / w (zeta < 1),
  atanh(2 zeta q / (2 zeta^2 - 1)) / q (zeta > 1), 2 at zeta = 1.
"""

from __future__ import annotations

import numpy as np

from ..errors import ImpactError

#: The ODE these formulas solve (``ContactLaw.closed_form``): the linear spring-damper with the family's zeta.
CLOSED_FORM = "kelvin-voigt"


def _state(zeta, tau):
    """(x, y) at tau, stable in every regime."""
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


def events(zeta, separation: str) -> dict:
    """Dimensionless outputs ``tau_m``, ``x_m``, ``tau_f``, ``y_f``, ``y_p`` for each lane (see module docstring).

    Raises
    ------
    ImpactError
        For lanes with zeta >= 1 under the ``penetration`` criterion (delta never returns to 0).
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
    if separation == "penetration":
        if not under.all():
            raise ImpactError(f"no separation: delta never returns to 0 under the 'penetration' criterion for "
                              f"{int((~under).sum())} scene(s) with zeta >= 1 (first: zeta = {zeta[~under][0]:.3g})")
        tau_f = np.pi / w
    else:
        tau_f = tau_force
    x_m = _state(zeta, tau_m)[0]
    y_f = _state(zeta, tau_f)[1]
    y_p = _state(zeta, np.minimum(tau_force, tau_f))[1]
    return {"tau_m": tau_m, "x_m": x_m, "tau_f": tau_f, "y_f": y_f, "y_p": y_p}
