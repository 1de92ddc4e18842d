"""Where methods fail: five measured failure modes, each beside the package's default path.

Every study returns rows with the same columns: ``study``, ``variant`` (the
formulation), ``method``, ``x_name``/``x`` (the swept parameter), ``error``
(relative, against an exact value), ``nfev``, ``time`` [s] and ``status``
(``ok`` or why it failed).  Only the stiffness study, which picks the cheapest method per setting, is timed
(the median of repeated runs, :func:`~.timing.median_time`); the others compare formulations by error and
evaluations, run once, their ``time`` empty.  The naive formulations live here only, as
counter-examples; the package never uses them.

1. ``stiffness``: damping ratio up to 100 and stiffness k from 1e3 to 1e9 N/m.
2. ``onset``: the previous model's force jump P(0) = b v_n, integrated through
   contact from free flight (discontinuous right-hand side) vs from contact.
3. ``grip``: Coulomb friction as sign(slip), as tanh(slip/eps), and as the
   exact event switch.
4. ``separation``: separation located at step ends only vs by root finding
   on the dense output, at loose tolerances.
5. ``past-separation``: the modified law without its contact guard,
   integrated over a fixed window past separation (overflow, NaN).
"""

from __future__ import annotations

import logging

import math
import warnings

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from ..errors import BeyondRadiusWarning, ImpactError
from ..integrators import INTEGRATORS
from ..integrators.normal import scalar_separation_function
from ..impact.scene import Scene, SolverOptions
from ..integrators import ivp_method
from ..impact.solve import simulate
from .reference import reference, worst_error
from .timing import median_time, steady_state
from .workprecision import METHODS

log = logging.getLogger(__name__)


#: Right-hand-side evaluations after which a naive formulation is declared stuck: over twice what the dearest
#: naive run that succeeds takes (``results/stability.csv``); a chattering run spends all of it, so a larger
#: budget buys only time.
BUDGET = 100_000


class _OverBudget(Exception):
    pass


def _row(study, variant, method, x_name, x, error=None, nfev=None, time=None, status="ok"):
    return {"study": study, "variant": variant, "method": method, "x_name": x_name, "x": x,
            "error": error, "nfev": nfev, "time": time, "status": status}


def _package_point(study, scene, ref, method, x_name, x, rtol=1e-8, variant="package default path", timed=False):
    """``simulate``'s point of a study, timed (median of repeated runs) where the study reads its time."""
    options = SolverOptions(method=method, rtol=rtol, atol=rtol)
    try:
        seconds, out = median_time(lambda: simulate(scene, options)) if timed else (None, simulate(scene, options))
    except ImpactError as err:
        return _row(study, variant, method, x_name, x, status=f"failed: {err}")
    return _row(study, variant, method, x_name, x, worst_error(out.to_dict(), ref, scene), out.nfev, seconds)


def stiffness_scenes(base: Scene) -> list[tuple]:
    """The stiffness study's points: (x_name, x, scene) with the damping ratio varied (b) and the stiffness k (b
    fixed), ``base``'s law."""
    sweeps = [("zeta", z, base.with_(b=z * 2 * math.sqrt(base.k * base.mass))) for z in (0.05, 0.5, 1, 5, 20, 100)]
    return sweeps + [("k [N/m]", k, base.with_(k=k)) for k in (1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9)]


def stiffness(base: Scene, methods=METHODS) -> list[dict]:
    """Cost against damping ratio (b varied) and against stiffness k (b fixed), ``base``'s law, force criterion
    (:func:`stiffness_scenes`)."""
    rows = []
    for x_name, x, scene in stiffness_scenes(base):
        ref = reference(scene).outputs
        for method in methods:
            rows.append(_package_point("stiffness", scene, ref, method, x_name, x, timed=True))
    return rows


def _budgeted(rhs):
    count = [0]

    def wrapped(t, z):
        count[0] += 1
        if count[0] > BUDGET:
            raise _OverBudget
        return rhs(t, z)

    return wrapped


def _separation_event(scene: Scene):
    """Terminal solve_ivp event ending contact under the scene's criterion, on an SI state (delta, delta_dot, ...): in
    Python floats where the law has its scalar formula (``integrators.normal.scalar_separation_function``)."""
    sep = scalar_separation_function(scene)

    def separation(t, z):
        return float(sep(float(z[0]), float(z[1])))

    separation.terminal, separation.direction = True, -1
    return separation


def _through_contact(scene: Scene, method: str, rtol: float, lead: float):
    """Free flight and contact in one ODE with the physical (discontinuous) law, from ``lead`` seconds before."""
    m = scene.mass

    def rhs(t, z):
        return [z[1], -float(scene.force(z[0], z[1])) / m]

    def max_compression(t, z):
        return z[1]

    max_compression.direction = -1
    separation = _separation_event(scene)
    v = scene.v_normal
    sol = solve_ivp(_budgeted(rhs), (-lead, 1.0), [-v * lead, v], method=ivp_method(method), rtol=rtol,
                    atol=rtol * 1e-3, events=(max_compression, separation))
    if sol.status != 1:
        raise ImpactError(f"no separation ({sol.message})")
    out = {"t_m": sol.t_events[0][0], "delta_m": sol.y_events[0][0][0], "t_f": sol.t_events[1][0],
           "cor": -sol.y_events[1][0][1] / v, "omega_f": 0.0, "ve_t": 0.0}
    return out, sol.nfev


def onset(base: Scene, methods=METHODS) -> list[dict]:
    """The kelvin-voigt force jump at first touch: through-contact integration vs starting at contact."""
    scene = base.with_(model="kelvin-voigt", angle=0.0)
    ref = reference(scene).outputs
    rows = []
    for method in methods:
        for rtol in (1e-4, 1e-6, 1e-8, 1e-10):
            rows.append(_package_point("onset", scene, ref, method, "rtol", rtol, rtol=rtol,
                                       variant="start at contact (package)"))
            try:
                out, nfev = _through_contact(scene, method, rtol, 0.5e-3)
                rows.append(_row("onset", "through contact from free flight", method, "rtol", rtol,
                                 worst_error(out, ref, scene), nfev))
            except (ImpactError, _OverBudget) as err:
                rows.append(_row("onset", "through contact from free flight", method, "rtol", rtol,
                                 status=f"failed: {err or 'over budget'}"))
    return rows


def _friction_ode(scene: Scene, law, method: str, rtol: float):
    """Normal and tangential state together, friction -mu P+ law(slip): the formulation the package avoids."""
    m, radius, inertia, mu = scene.mass, scene.radius, scene.inertia, scene.mu
    force = scene.law.in_floats(scene.reduced)  # the law's scalar formula: the runs evaluate it up to BUDGET times

    def rhs(t, z):
        p = max(force(float(z[0]), float(z[1])), 0.0)
        f = -mu * p * law(z[2] - z[3] * radius)
        return [z[1], -p / m, f / m, -f * radius / inertia]

    sol = solve_ivp(_budgeted(rhs), (0.0, 1.0), [0.0, scene.v_normal, scene.v_tangent, 0.0], method=ivp_method(method),
                    rtol=rtol, atol=rtol * 1e-3, events=_separation_event(scene))
    if sol.status != 1:
        raise ImpactError(f"no separation ({sol.message})")
    return sol.y_events[0][0][2], sol.nfev


def grip(base: Scene, methods=("RK45", "DOP853", "Radau", "LSODA"), angle: float = 50.0) -> list[dict]:
    """Coulomb friction at grip: error in the final v_t against vt0 / (1 + alpha), and cost."""
    scene = base.with_(angle=angle)
    exact = scene.v_tangent / (1 + scene.inertia_factor)
    laws = [("sign(slip)", None, np.sign)]
    laws += [("tanh(slip/eps)", eps, (lambda e: lambda s: math.tanh(s / e))(eps)) for eps in 10.0 ** -np.arange(1, 7)]
    rows = []
    for method in methods:
        for variant, eps, law in laws:
            try:
                v_t, nfev = _friction_ode(scene, law, method, 1e-8)
                rows.append(_row("grip", variant, method, "eps [m/s]", eps, abs(v_t / exact - 1), nfev))
            except _OverBudget:
                rows.append(_row("grip", variant, method, "eps [m/s]", eps,
                                 status=f"failed: over {BUDGET} evaluations (chattering / step-size collapse)"))
            except ImpactError as err:
                rows.append(_row("grip", variant, method, "eps [m/s]", eps, status=f"failed: {err}"))
        out = simulate(scene, SolverOptions(method=method, rtol=1e-8, atol=1e-8))
        rows.append(_row("grip", "exact event switch (package)", method, "eps [m/s]", 0.0,
                         abs(out.vc_t / exact - 1), out.nfev))
    return rows


def _step_end_separation(scene: Scene, method: str, rtol: float) -> tuple[float, int]:
    """Separation taken as the first step end where P <= 0 or delta <= 0 (no root finding)."""
    w, v, stage = scene.omega_n, scene.v_normal, scene.law.in_floats(scene.reduced)
    sol = solve_ivp(lambda t, z: [z[1], -stage(float(z[0]), float(z[1])) / scene.mass], (0.0, 50 / w),
                    [0.0, v], method=ivp_method(method), rtol=rtol, atol=rtol * v / w)
    force = scene.force(sol.y[0], sol.y[1])
    ended = np.flatnonzero((sol.t > 0) & ((sol.y[0] <= 0) | (force <= 0)))
    if not len(ended):
        raise ImpactError("separation missed at every step end")
    return float(sol.t[ended[0]]), sol.nfev


def separation(base: Scene, methods=METHODS) -> list[dict]:
    """t_f error at loose tolerances: step-end detection vs root finding on the dense output."""
    scene = base.with_(angle=0.0)
    exact = reference(scene).outputs["t_f"]
    rows = []
    for method in methods:
        for rtol in (1e-2, 1e-3, 1e-4, 1e-6):
            t_f, nfev = _step_end_separation(scene, method, rtol)
            rows.append(_row("separation", "first step end past separation", method, "rtol", rtol,
                             abs(t_f / exact - 1), nfev))
            out = simulate(scene, SolverOptions(method=method, rtol=rtol, atol=rtol))
            rows.append(_row("separation", "root on dense output (package)", method, "rtol", rtol,
                             abs(out.t_f / exact - 1), out.nfev))
    return rows


def _unguarded_modified(delta, delta_dot, p):
    """Eq. 4.2 evaluated for every delta, as naive code does: exp(+c|delta|/R) past separation."""
    return p.k * delta + p.b * delta_dot * (1.0 - np.exp(-p.ramp * delta / p.radius))


def past_separation(base: Scene, methods=METHODS, window: float = 0.2) -> list[dict]:
    """The unguarded modified law over a fixed window [0, window] s: when does it overflow?"""
    scene = base.with_(angle=0.0)
    rows = []
    for method in methods:
        reached = [0.0]

        def rhs(t, z):
            reached[0] = max(reached[0], t)
            return [z[1], -_unguarded_modified(z[0], z[1], scene) / scene.mass]

        try:
            with np.errstate(over="ignore", invalid="ignore"):
                sol = solve_ivp(_budgeted(rhs), (0.0, window), [0.0, scene.v_normal], method=ivp_method(method),
                                rtol=1e-8, atol=1e-12)
            bad = np.flatnonzero(~np.isfinite(sol.y).all(axis=0))
            status = (f"failed: non-finite state at t = {sol.t[bad[0]]:.3g} s" if len(bad)
                      else f"failed: solver stopped at t = {sol.t[-1]:.3g} s ({sol.message})" if sol.status != 0
                      else f"failed: |delta| reached {np.max(np.abs(sol.y[0])):.3g} m: the ball never leaves")
            nfev = sol.nfev
        except _OverBudget:
            status, nfev = f"failed: over {BUDGET} evaluations, stuck at t = {reached[0]:.3g} s", BUDGET
        rows.append(_row("past-separation", "unguarded law, fixed window", method, "window [s]", window,
                         nfev=nfev, status=status))
        out = simulate(scene, SolverOptions(method=method, rtol=1e-8, atol=1e-8))
        rows.append(_row("past-separation", "guarded law, terminal event (package)", method, "window [s]", window,
                         nfev=out.nfev, status=f"ok: separates at t_f = {out.t_f:.4g} s, COR {out.cor:.4f}"))
    return rows


STUDIES = {"stiffness": stiffness, "onset": onset, "grip": grip, "separation": separation,
           "past-separation": past_separation}


def stability(base: Scene, studies=tuple(STUDIES), methods=METHODS) -> pd.DataFrame:
    """The ``studies`` on the chapter's scene ``base`` (angle and model set per study), for ``methods``
    (the grip study keeps to the explicit and implicit methods among them that it contrasts); the stiffness study
    timed in the steady state (:func:`~.timing.steady_state`; loaded only for it: a fresh machine's compilation is
    seconds the other studies need not pay)."""
    if "stiffness" in studies:
        steady_state()
    rows = []
    with warnings.catch_warnings():  # the stiffness study reaches k = 1e3 N/m, where delta_m exceeds R
        warnings.simplefilter("ignore", BeyondRadiusWarning)
        for name in studies:
            log.info("stability: %s", name)
            chosen = [m for m in methods if m in ("RK45", "DOP853", "Radau", "LSODA")] if name == "grip" else methods
            if name != "stiffness":  # the naive formulations beside the package's path are Runge-Kutta code
                chosen = [m for m in chosen if INTEGRATORS[m].ivp is not None]
            rows += STUDIES[name](base, chosen)
    return pd.DataFrame(rows)
