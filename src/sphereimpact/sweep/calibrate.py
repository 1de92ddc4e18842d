"""Calibrate the balls of a table of scenes: each distinct ball's damping (and stiffness) set once from the
COR (and contact time) measured at one speed, then kept across the table's angles, speeds and spins."""

from __future__ import annotations

from ..impact.calibrate import calibrate
from .scenes import scene_of, scene_table

#: Columns of a sweep's table that describe the approach or the tangential contact, not the ball and its normal
#: law: a ball's calibration does not depend on them.
APPROACH_COLUMNS = ("angle", "speed", "spin", "incidence", "angle_to_surface", "mu", "inertia_factor", "tangential",
                    "kappa", "poisson", "shear_modulus")


def calibrate_table(table, cor, speed: float, relation: str = "exact", contact_time=None):
    """A table of scenes with each distinct ball calibrated once: its law's damping (and, with
    ``contact_time``, k) set so that a normal impact at ``speed`` [m/s] has the COR ``cor`` (and that contact
    time), then kept at every angle, speed and spin of the table.

    Parameters
    ----------
    table : DataFrame
        Scenes, one per row (as :func:`sphereimpact.sweep.sweep` takes them); every row of one law.
    cor, relation, contact_time
        As :func:`calibrate`.
    speed : float
        The normal impact speed at which the COR (and contact time) was measured [m/s].

    Returns
    -------
    DataFrame
        ``table`` with the damping column (and ``k``) filled in; ``modulus`` dropped where ``k`` was fitted.
    """
    frame = scene_table(table)
    models = frame["model"].unique()
    if len(models) != 1:
        raise ValueError(f"cor: calibrate one law at a time; the table holds {', '.join(map(str, models))}")
    out = frame.copy()
    balls = [name for name in frame.columns if name not in APPROACH_COLUMNS]
    for _, rows in frame.groupby(balls, dropna=False, sort=False).groups.items():
        first = frame.loc[rows[0]].to_dict()
        base = scene_of({**first, "angle": 0.0, "speed": speed, "spin": 0.0, "incidence": float("nan"),
                         "angle_to_surface": float("nan"), "tangential": "rigid", "kappa": float("nan"),
                         "poisson": float("nan"), "shear_modulus": float("nan")})
        fitted = calibrate(base, cor, relation, contact_time).scene
        for name in (fitted.law.damping, "k") if contact_time is not None else (fitted.law.damping,):
            out.loc[rows, name] = getattr(fitted, name)
        if contact_time is not None:
            out.loc[rows, "modulus"] = float("nan")
    return out
