"""The baseline every benchmark is measured against: the script a competent user writes by hand.

One :func:`scipy.integrate.solve_ivp` call per impact on the dimensionless normal ODE
(x = delta omega_n / v_n, y = delta_dot / v_n, tau = omega_n t; for another law, its own time scale T
for 1 / omega_n), with

- a scalar right-hand side in plain :mod:`math` (no numpy call per evaluation), the law as the chapter
  states it (eq. 4.2's ramp inside contact only); for the other laws, the law's own scalar formula
  (``ContactLaw.scalar``: what a user would type, P = k delta^n (1 + chi delta_dot) and the like),
- the two events it needs (maximum compression; separation, terminal), read from ``y_events``,
- no dense output (nothing here needs the solution between steps),

then the impulse algebra for the tangential outputs (sliding: J_t = mu J_n; grip: v_t = v_t0/(1 + alpha)),
exactly as :func:`sphereimpact.numerics.reference.outputs_from_normal` states it.  Gravity-free scenes
of the chapter's two laws or of a law with a scalar formula, and exact only where the force does not
pull before separation (always under the ``force`` criterion, which the benchmarks use): this is a
baseline, not a second implementation of the package.

Nothing of the package's solver path is used, so a benchmark against it measures the package's own
machinery, and its error against the references is measured like the package's.
"""

from __future__ import annotations

import math

from scipy.integrate import solve_ivp

from ..impact.scene import Scene
from .reference import outputs_from_normal

#: The chapter's laws, written out here as the chapter states them; other laws use their scalar formula.
LAWS = ("kelvin-voigt", "modified")


def handwritten(scene: Scene, rtol: float, atol: float | None = None, method: str = "DOP853") -> dict:
    """Every output of one gravity-free impact by one plain ``solve_ivp`` call (see module docstring).

    Parameters
    ----------
    scene : Scene
        Gravity-free scene of a law in :data:`LAWS` or of a law with a ``scalar`` formula.
    rtol, atol : float
        solve_ivp tolerances on the dimensionless state (``atol`` defaults to ``rtol``).
    method : str
        A solve_ivp method.

    Returns
    -------
    dict
        ``t_m`` [s], ``delta_m`` [m], ``t_f`` [s], ``cor``, ``omega_f`` [rad/s], ``ve_t``, ``vc_t``,
        ``vc_n``, ``ve_n`` [m/s], ``nfev``.

    Raises
    ------
    ValueError
        Gravity on, or a law without a scalar formula.
    RuntimeError
        The solver failed or an event was not found.
    """
    if scene.gravity != 0 or (scene.model not in LAWS and scene.law.scalar is None):
        raise ValueError(f"the hand-written baseline covers {', '.join(LAWS)} and laws with a scalar formula, "
                         "without gravity")
    w, v = scene.frequency, scene.v_normal
    expm1 = math.expm1

    if scene.model == "kelvin-voigt":
        two_zeta = 2.0 * scene.zeta

        def force(x, y):
            return x + two_zeta * y
    elif scene.model == "modified":  # the ramp only inside contact: unguarded, exp(+lam |x|) overflows
        two_zeta, lam = 2.0 * scene.zeta, scene.family["lam"]

        def force(x, y):
            return x - two_zeta * y * expm1(-lam * x) if x > 0 else x
    else:  # the law's own formula, scaled: P / (m w v) at delta = x v / w, delta_dot = y v
        law, d_scale, p_scale = scene.law.scalar, v / w, scene.mass * w * v

        def force(x, y):
            return law(x * d_scale, y * v, scene) / p_scale

    def rhs(tau, z):
        return [z[1], -force(z[0], z[1])]

    def max_compression(tau, z):
        return z[1]

    if scene.separation.pulls:
        def separation(tau, z):
            return z[0]
    else:  # the first of P = 0 and delta = 0
        def separation(tau, z):
            return force(z[0], z[1]) if z[0] > 0 else z[0]

    max_compression.direction = -1
    separation.direction, separation.terminal = -1, True
    horizon = float(scene.law.horizon(scene))
    sol = solve_ivp(rhs, (0.0, horizon), [0.0, 1.0], method=method, rtol=rtol,
                    atol=rtol if atol is None else atol, events=(max_compression, separation))
    if sol.status != 1 or not len(sol.t_events[0]):
        raise RuntimeError(f"hand-written baseline: {sol.message} (events {[len(t) for t in sol.t_events]})")
    tau_m, x_m = sol.t_events[0][0], sol.y_events[0][0][0]
    tau_f, y_f = sol.t_events[1][0], sol.y_events[1][0][1]
    out = outputs_from_normal(scene, tau_m / w, x_m * v / w, tau_f / w, y_f * v)
    return out | {"nfev": int(sol.nfev)}
