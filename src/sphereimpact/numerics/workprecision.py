"""Work-precision: worst relative error against wall time and nfev for every method, body and tolerance.

Every point is one impact solved by :func:`sphereimpact.simulate`, timed as the
median of repeats in one process so ratios between methods hold.  The error is
the worst relative error over t_m, delta_m, t_f, COR, omega_f and ve_t against
:func:`sphereimpact.numerics.reference.reference`.
"""

from __future__ import annotations

import logging

import pandas as pd

from ..errors import ImpactError
from ..integrators import INTEGRATORS
from ..impact.scene import Scene, SolverOptions
from ..impact.solve import BODIES, simulate
from .reference import reference, worst_error
from .timing import median_time, steady_state

log = logging.getLogger(__name__)

METHODS = ("taylor", "DOP853-scalar", "RK23", "RK45", "DOP853", "Radau", "BDF", "LSODA")
TOLERANCES = tuple(10.0 ** -e for e in range(3, 13))
#: Accuracy every output must meet with the package's default method and tolerance.
TARGET = 1e-9
#: Seconds [s] one impact may take before a method's line stops: its tighter tolerances are not run (each is
#: a row saying so), since a line whose slope is measured only grows dearer from there (RK23's and Radau's at
#: the tightest tolerances).  Which points that stops depends on the machine, as every time of the chart does.
COST_CAP = 0.2


def measure(scene: Scene, ref: dict, method: str, rtol: float, body: str = "reduced") -> dict:
    """One point: error, median time and nfev (``status`` says why a point failed)."""
    options = SolverOptions(method=method, rtol=rtol, atol=rtol)
    try:
        seconds, out = median_time(lambda: simulate(scene, options, body=body))
    except ImpactError as err:
        return _without_result(method, body, rtol, f"failed: {err}")
    return {"method": method, "body": body, "rtol": rtol, "error": worst_error(out.to_dict(), ref, scene),
            "time": seconds, "nfev": out.nfev, "status": "ok"}


def _without_result(method: str, body: str, rtol: float, status: str) -> dict:
    """The row of a point with no result: failed, or not run (``status`` says which and why)."""
    return {"method": method, "body": body, "rtol": rtol, "error": None, "time": None, "nfev": None,
            "status": status}


def work_precision(cases: dict[str, Scene], tolerances=TOLERANCES, methods=METHODS,
                   cost_cap: float = COST_CAP) -> pd.DataFrame:
    """Every method x body x tolerance for each case, plus the closed form where it exists (timed in the steady
    state, :func:`~.timing.steady_state`), from the loosest tolerance to the tightest; a line stops after the first
    point whose impact took more than ``cost_cap`` seconds (its other points are rows saying so)."""
    steady_state()
    tolerances = sorted(tolerances, reverse=True)
    rows = []
    for case, scene in cases.items():
        log.info("work-precision: case %s", case)
        ref = reference(scene)
        base = {"case": case, "model": scene.model, "reference_bound": ref.bound}
        if scene.law.closed_form is not None:
            rows.append(base | measure(scene, ref.outputs, "closed", 1e-13) | {"body": "closed"})
        for body in BODIES:
            for method in methods:
                if body == "planar" and INTEGRATORS[method].ivp != method:  # reduced only, or run as another
                    continue
                over = None
                for rtol in tolerances:
                    point = measure(scene, ref.outputs, method, rtol, body) if over is None else _without_result(
                        method, body, rtol, f"not run: rtol {over['rtol']:g} took {over['time']:.2g} s an impact, "
                        "over the cost cap")
                    rows.append(base | point)
                    if over is None and point["time"] is not None and point["time"] > cost_cap:
                        over = point
    return pd.DataFrame(rows)


def choose_default(frame: pd.DataFrame, target: float = TARGET, body: str = "reduced") -> pd.Series:
    """The cheapest (method, rtol) whose error meets ``target`` in every case (total median time)."""
    ok = frame[(frame["body"] == body) & (frame["status"] == "ok")]
    per_setting = ok.groupby(["method", "rtol"]).agg(worst=("error", "max"), time=("time", "sum"),
                                                     cases=("case", "nunique"))
    eligible = per_setting[(per_setting["worst"] <= target) & (per_setting["cases"] == frame["case"].nunique())]
    if eligible.empty:
        raise ValueError(f"no method meets {target:g} in every case")
    best = eligible["time"].idxmin()
    return pd.Series({"method": best[0], "rtol": best[1], **eligible.loc[best].to_dict()})
