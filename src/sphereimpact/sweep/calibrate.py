"""Calibrate the balls of a table of scenes: each distinct ball's damping (and stiffness) set once from the
COR (and contact time) measured at one speed, then kept across the table's angles, speeds and spins."""

from __future__ import annotations

import pandas as pd

from ..impact.ball import Measurement, calibrated_ball
from .scenes import given_fields

#: Columns of a sweep's table that describe the approach or the tangential contact, not the ball and its normal
#: law: a ball's calibration does not depend on them.
APPROACH_COLUMNS = ("angle", "speed", "spin", "incidence", "angle_to_surface", "mu", "inertia_factor", "tangential",
                    "kappa", "poisson", "shear_modulus")


def calibrate_table(table, measurement: Measurement):
    """A table of scenes with each distinct ball calibrated once: its law's damping (and, with a contact time,
    k) set from ``measurement`` as :func:`~sphereimpact.impact.ball.calibrated_ball` sets it, in a normal impact
    at the measurement's speed, then kept at every angle, speed and spin of the table.

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
    if "model" in frame and frame["model"].nunique() > 1:
        raise ValueError(f"cor: calibrate one law at a time; the table holds {', '.join(map(str, frame['model'].unique()))}")
    out = frame.copy()
    balls = [name for name in frame.columns if name not in APPROACH_COLUMNS]
    groups = frame.groupby(balls, dropna=False, sort=False).groups.items() if balls else [(None, frame.index)]
    for _, rows in groups:
        fields = given_fields(frame.loc[rows[0]].to_dict())
        ball = calibrated_ball(measurement, **{k: v for k, v in fields.items() if k not in APPROACH_COLUMNS})
        for name, value in ball.fitted.items():
            out.loc[rows, name] = value
        if measurement.contact_time is not None and "modulus" in out:
            out.loc[rows, "modulus"] = float("nan")
    return out
