"""Resolution of the exact microslip contact: accuracy against cost over its cells x time steps, and the
default resolution that the measurement supports (a benchmark: timings are written to files, never
asserted).

Each setting is run on every scene and compared with a fine reference run of the same model; its error is
the larger of the tangential COR's absolute error and the rebound spin's relative error.  The default is
the setting with the fewest time steps, then the fewest cells, whose worst error over the scenes meets the
target: a step costs about the same whatever the cell count at these sizes, so that order is the cost's.
"""

from __future__ import annotations

import logging

import pandas as pd

from ..impact.scene import Scene, SolverOptions
from ..impact.solve import simulate
from ..contact.tangential.microslip import ELEMENTS, TIME_STEPS
from .timing import median_seconds

log = logging.getLogger(__name__)

#: Accuracy the default resolution must reach on every scene: e_t (absolute) and spin (relative), 30 times
#: below the digitisation scatter of the measurements it is validated on (0.003 in e_t).
TARGET = 1e-4


def _outputs(scene: Scene, elements: int, time_steps: int) -> tuple[float, float]:
    out = simulate(scene, SolverOptions(settings={"elements": elements, "time_steps": time_steps}))
    return out.e_t, out.omega_f


def resolution_study(scenes: dict[str, Scene], elements, time_steps, reference: tuple[int, int],
                     repeats: int = 3, target: float = TARGET) -> pd.DataFrame:
    """Every (cells, time steps) setting on every scene against the reference resolution.

    Returns
    -------
    DataFrame
        One row per scene and setting: ``scene``, ``angle``, ``kappa``, ``elements``, ``time_steps``,
        ``e_t``, ``omega_f`` [rad/s], ``error_e_t`` (absolute), ``error_spin`` (relative), ``error`` (the
        larger), ``time`` [s per impact, median of ``repeats``], ``worst_error`` (the setting's worst over
        the scenes), ``meets_target``, ``chosen`` (the default the study supports) and ``package_default``
        (the package's :data:`~sphereimpact.contact.tangential.microslip.ELEMENTS` and ``TIME_STEPS``).
    """
    rows = []
    for name, scene in scenes.items():
        log.info("microslip resolution: scene %s", name)
        e_ref, w_ref = _outputs(scene, *reference)
        for n in elements:
            for m in time_steps:
                e_t, omega = _outputs(scene, n, m)
                rows.append({"scene": name, "angle": scene.angle, "kappa": scene.kappa, "elements": n,
                             "time_steps": m, "e_t": e_t, "omega_f": omega, "error_e_t": abs(e_t - e_ref),
                             "error_spin": abs(omega / w_ref - 1.0),
                             "time": median_seconds(lambda: _outputs(scene, n, m), repeats)})
    table = pd.DataFrame(rows)
    table["error"] = table[["error_e_t", "error_spin"]].max(axis=1)
    table["worst_error"] = table.groupby(["elements", "time_steps"])["error"].transform("max")
    table["meets_target"] = table["worst_error"] <= target
    met = table[table["meets_target"]].sort_values(["time_steps", "elements"])
    chosen = (int(met["elements"].iloc[0]), int(met["time_steps"].iloc[0])) if len(met) else None
    table["chosen"] = [(n, m) == chosen for n, m in zip(table["elements"], table["time_steps"])]
    table["package_default"] = (table["elements"] == ELEMENTS) & (table["time_steps"] == TIME_STEPS)
    return table
