"""A fit's files: the fitted ball, its residual table, its parameters and statistics, and its figure; and the
pipeline's fit of the shipped Kharaz et al. (2001) data."""

from __future__ import annotations

import json
import math
from contextlib import ExitStack
from pathlib import Path

from ..fit import FIT_FILES, fit, read_measured, with_values
from ..figures.fit import fit_figure
from ..files import replacing
from ..impact.ball import Ball, save_ball
from ..sweep.io import write_table

#: Units of the residual table's columns (a measured quantity's own unit is in its ``quantity``).
RESIDUAL_UNITS = {"speed": "m/s", "incidence": "deg", "angle_to_surface": "deg", "angle": "deg", "spin": "rad/s"}


def finite(value):
    """A JSON value: an infinite or undefined number as null (a standard error the data do not bound)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(v) for v in value]
    return value


def write_fit(result, folder, extra: dict | None = None) -> None:
    """Write a :class:`~sphereimpact.fit.FitResult` into ``folder`` (made if missing): its files
    (:data:`~sphereimpact.fit.FIT_FILES`) are the fitted ball, the parameters and statistics (JSON, with the
    keys of ``extra`` besides), the residual table and the figure of data against model."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    stats = result.statistics
    title = (", ".join(f"{n} = {p.value:.4g} ± {p.stderr:.2g}" for n, p in result.parameters.items())
             + f"\n{stats['values']} measured values, χ²/dof = {stats['reduced_chi2']:.3g}")
    with ExitStack() as stack:  # all four written beside, then renamed together: one fit's files or the old ones
        ball, summary, residuals, figure = (stack.enter_context(replacing(folder / name)) for name in FIT_FILES)
        save_ball(result.ball, ball)
        Path(summary).write_text(json.dumps(finite(result.as_dict() | (extra or {})), indent=2) + "\n",
                                 encoding="utf-8")
        write_table(result.residuals, residuals, units=RESIDUAL_UNITS)
        fit_figure(result.residuals, title, [figure])


def kharaz_fit(config: dict, data_csv: str, folder: str) -> None:
    """Fit the shipped Kharaz data: the experiment's ball (``validation``: its e_n given, the normal damping
    calibrated to it) with ``kharaz_fit``'s tangential model, its free parameters started from ``start``; the
    fit's files in ``folder``, ``fit.json`` also holding the values the paper and the materials give
    (``reference``: the measured mu and kappa = 4 G*/E*)."""
    from .validation import experiment

    spec, exp = config["kharaz_fit"], experiment(config["validation"])
    start = {name: value for name, value in spec["start"].items() if name in spec["free"]}
    ball = with_values(Ball(exp.with_tangential(spec["tangential"]), source="Kharaz et al. (2001)"), start)
    result = fit(read_measured(data_csv, source=Path(data_csv).name), ball, spec["free"])
    write_fit(result, folder, {"reference": {
        "mu": config["validation"]["mu"], "kappa": exp.kappa, "tangential": spec["tangential"],
        "source": "mu measured by Kharaz et al. (2001); kappa = 4 G*/E* of alumina on glass"}})


def study_fit(config: dict, folder: str) -> None:
    """An own study's ``fit`` section: its ball (as the other sections describe it) fitted to the measured
    bounces, the fit's files in ``folder`` (its ``ball.json`` is then the study's ball)."""
    from .own import study_ball

    section = config["fit"]
    result = fit(read_measured(section["data"]), study_ball(config), section["free"], section["bootstrap"],
                 section["seed"])
    write_fit(result, folder)
