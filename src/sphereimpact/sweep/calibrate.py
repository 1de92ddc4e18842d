"""Calibrate the balls of a table of scenes: each distinct ball's damping (and stiffness) set once from the
COR (and contact time) measured at one speed, then kept across the table's angles, speeds and spins."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd

from ..errors import ExtrapolationWarning
from ..impact.ball import FAR, Measurement, calibrated_ball
from ..impact.scene import Scene
from .scenes import approach_speeds, first_rows, given_fields

#: Columns of a sweep's table that describe the approach or the tangential contact, not the ball and its normal
#: law: a ball's calibration does not depend on them.
APPROACH_COLUMNS = ("angle", "speed", "spin", "incidence", "angle_to_surface", "mu", "inertia_factor", "tangential",
                    "kappa", "poisson", "shear_modulus")


#: A table's approach columns with the Scene's defaults, for one it leaves out (NaN: no path given).
APPROACH_DEFAULTS = {"speed": Scene.__dataclass_fields__["speed"].default, "angle": 0.0, "incidence": np.nan,
                     "angle_to_surface": np.nan}


def normal_speeds(table) -> np.ndarray:
    """Each scene's normal approach speed v cos(theta) [m/s], the approach columns a table leaves out taking the
    Scene's defaults (NaN where a cell is not a number: the sweep refuses it, with its row)."""
    frame = pd.DataFrame(table)
    approach = pd.DataFrame({name: pd.to_numeric(frame[name], errors="coerce") if name in frame else default
                             for name, default in APPROACH_DEFAULTS.items()}, index=frame.index)
    return approach_speeds(approach)[0]


def warn_if_extrapolating(table, measurement: Measurement) -> None:
    """An :class:`~sphereimpact.errors.ExtrapolationWarning` when some of ``table``'s scenes have a normal speed
    more than :data:`~sphereimpact.impact.ball.FAR` times from the measurement's, either way: there the law
    calibrated to it extrapolates."""
    speeds = normal_speeds(table)
    far = int(np.count_nonzero(measurement.extrapolates(speeds)))
    if far:
        factor = speeds / measurement.speed
        warnings.warn(f"{far} of {len(speeds)} scenes have a normal speed more than {FAR:g} times from the "
                      f"{measurement.speed:.3g} m/s at which the COR {measurement.cor:g} was measured "
                      f"({factor.min():.3g} to {factor.max():.3g} times): the calibrated law extrapolates there",
                      ExtrapolationWarning, stacklevel=2)


def calibrate_table(table, measurement: Measurement):
    """A table of scenes with each distinct ball calibrated once: its law's damping (and, with a contact time,
    k) set from ``measurement`` as :func:`~sphereimpact.impact.ball.calibrated_ball` sets it, in a normal impact
    at the measurement's speed, then kept at every angle, speed and spin of the table; warns where the table's
    normal speeds are far from the measurement's (:func:`warn_if_extrapolating`).

    Parameters
    ----------
    table : DataFrame
        Scenes, one per row (as :func:`sphereimpact.sweep.sweep` takes them); every row of one law.
    measurement : Measurement
        The COR (and contact time) and the normal speed they were measured at.

    Returns
    -------
    DataFrame
        ``table`` with the damping column (and ``k``) filled in; ``modulus`` dropped where ``k`` was fitted.
    """
    frame = pd.DataFrame(table).reset_index(drop=True)  # checked row by row as the calibration builds each ball
    warn_if_extrapolating(frame, measurement)
    if "model" in frame and frame["model"].nunique() > 1:
        raise ValueError(f"cor: calibrate one law at a time; the table holds {', '.join(map(str, frame['model'].unique()))}")
    out = frame.copy()
    balls = [name for name in frame.columns if name not in APPROACH_COLUMNS]
    if balls:  # each ball once, in the order of its first row (rows alike as the scene checks group them)
        group, firsts = first_rows({name: frame[name].to_numpy() for name in balls})
        groups = [np.flatnonzero(group == g) for g in range(firsts.size)]
    else:
        groups = [np.arange(len(frame))]
    for rows in groups:
        fields = given_fields(frame.loc[rows[0]].to_dict())
        ball = calibrated_ball(measurement, **{k: v for k, v in fields.items() if k not in APPROACH_COLUMNS})
        for name, value in ball.fitted.items():
            out.loc[rows, name] = value
        if measurement.contact_time is not None and "modulus" in out:
            out.loc[rows, "modulus"] = float("nan")
    return out
