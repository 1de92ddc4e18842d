"""Sweeps of sphere-sphere impacts: each row with a partner solved as its reduced sphere on the flat.

A table whose rows name a partner sphere (the ``partner_*`` columns of :data:`~sphereimpact.impact.pair.PARTNER_FIELDS`)
is swept as the table of each row's reduced sphere (:func:`~sphereimpact.impact.pair.reduced_body`: the row's
mass, diameter, inertia factor and spin replaced by m*, 2 R*, alpha* and w*), through every path of the sweep,
and each body's velocities then follow from the impulses (:func:`~sphereimpact.impact.pair.pair_velocities`),
as :func:`sphereimpact.simulate` derives them.  The table written keeps the rows' own columns.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd

from ..errors import UnitWarning
from ..impact.inputs import check_columns, density_problem
from ..impact.outcome import SCALAR_OUTPUTS
from ..impact.pair import (PARTNER_FIELDS, PARTNER_OUTPUTS, missing_partner, pair_velocities, partner_gravity,
                           reduced_body, stray_partner)
from ..impact.scene import Scene
from .scenes import approach_speeds, given_table

#: The ball's columns the reduction replaces, with the Scene's defaults.
BODY = {name: Scene.__dataclass_fields__[name].default for name in ("mass", "diameter", "inertia_factor", "spin")}
#: The pair's outputs the reduced sphere's give (the ball's are its velocities' and spin's after the impact).
MAPPED = ("vc_t", "vc_n", "omega_f")


def has_partner(scenes) -> bool:
    """True when a table (DataFrame, or a dict of values or lists) names a partner sphere's column."""
    return any(name in PARTNER_FIELDS for name in (scenes.columns if isinstance(scenes, pd.DataFrame) else scenes))


def partner_columns(frame: pd.DataFrame) -> dict:
    """The rows' partner fields as float arrays, checked (NaN where a row has no partner; its inertia factor and
    spin defaulted): ValueError names the parameter and the first bad row."""
    n = len(frame)
    raw = {name: frame[name].to_numpy() if name in frame else np.full(n, np.nan) for name in PARTNER_FIELDS}
    check_columns({name: values for name, values in raw.items() if name in frame})
    columns = {name: np.asarray(values, dtype=float) for name, values in raw.items()}
    mass, diameter = columns["partner_mass"], columns["partner_diameter"]
    pair = ~np.isnan(mass)
    for name, other in (("partner_mass", diameter), ("partner_diameter", mass)):
        lacking = np.isnan(columns[name]) & ~np.isnan(other)
        if lacking.any():
            raise ValueError(f"{missing_partner(name)} (row {int(np.flatnonzero(lacking)[0])})")
    for name in PARTNER_FIELDS[2:]:
        default = Scene.__dataclass_fields__[name].default
        stray = ~pair & ~np.isnan(columns[name]) & (columns[name] != default)
        if stray.any():
            raise ValueError(f"{stray_partner(name)} (row {int(np.flatnonzero(stray)[0])})")
        columns[name] = np.where(np.isnan(columns[name]), default, columns[name])
    if "gravity" in frame:
        gravity = np.asarray(frame["gravity"], dtype=float)
        pulled = pair & ~np.isnan(gravity) & (gravity != 0)  # an empty cell is the default, 0
        if pulled.any():
            i = int(np.flatnonzero(pulled)[0])
            raise ValueError(f"{partner_gravity(frame['gravity'].iloc[i])} (row {i})")
    return columns


def _body(frame: pd.DataFrame) -> dict:
    """The ball's mass, diameter, inertia factor and spin per row, checked (ValueError naming the parameter and
    the row), defaulted where not given."""
    n = len(frame)
    given = {name: frame[name].to_numpy() for name in BODY if name in frame}
    out = {}
    for name, default in BODY.items():
        values = given[name] if name in given else np.full(n, default)
        filled = np.where(pd.isna(values), default, values)  # an empty cell is the default; every given one checked
        check_columns({name: filled})  # before the reduction, which can turn a negative mass positive
        out[name] = np.asarray(filled, dtype=float)
    return out


def reduced_table(frame: pd.DataFrame) -> tuple[pd.DataFrame, dict, dict]:
    """The table of each row's reduced sphere: the partner's columns dropped and, in the rows with a partner, the
    ball's mass, diameter, inertia factor and spin replaced by m*, 2 R*, alpha* and w*; with the rows' partner
    (:func:`partner_columns`) and ball (:func:`_body`) columns it was reduced from."""
    partner, body = partner_columns(frame), _body(frame)
    pair = ~np.isnan(partner["partner_mass"])
    m, r, alpha, spin = reduced_body(body["mass"], 0.5 * body["diameter"], body["inertia_factor"], body["spin"],
                                     partner["partner_mass"], 0.5 * partner["partner_diameter"],
                                     partner["partner_inertia_factor"], partner["partner_spin"])
    reduced = frame.drop(columns=[name for name in PARTNER_FIELDS if name in frame])
    for name, value in (("mass", m), ("diameter", 2.0 * r), ("inertia_factor", alpha), ("spin", spin)):
        reduced[name] = np.where(pair, value, body[name])
    return reduced, partner, body


def pair_sweep(sweep, scenes, span=None, outputs=None, **options) -> pd.DataFrame:
    """``sweep(scenes, ...)`` for a table with partner spheres: the reduced table swept by ``sweep`` (the engine's
    function), then, in the rows with a partner, the ball's velocities and spin and the partner's
    (:data:`~sphereimpact.impact.pair.PARTNER_OUTPUTS`; 0 in rows on the flat, which does not move) from the
    impulses.  The scene columns are the rows' own, the partner's after them; ``k`` is the contact's."""
    reduced, partner, body = reduced_table(given_table(scenes).reset_index(drop=True))
    wanted = None if outputs is None else [outputs] if isinstance(outputs, str) else list(outputs)
    solved_for = None if wanted is None else [name for name in dict.fromkeys([*wanted, *MAPPED, "cor"])
                                              if name not in PARTNER_OUTPUTS]
    reduced_span = None if span is None else reduced_table(given_table(span).reset_index(drop=True))[0]
    pair = ~np.isnan(partner["partner_mass"])
    for slip in (density_problem(body["mass"], body["diameter"]),
                 density_problem(partner["partner_mass"][pair], partner["partner_diameter"][pair], "partner sphere")):
        if slip:  # each body as given, once for the table
            warnings.warn(slip, UnitWarning, stacklevel=3)
    with warnings.catch_warnings():  # the reduced sphere (m*, R*) is no body: its density says nothing
        warnings.simplefilter("ignore", UnitWarning)
        result = sweep(reduced, span=reduced_span, outputs=solved_for, **options)
    v_n, v_t = approach_speeds(result)
    velocities = pair_velocities({name: result[name].to_numpy() for name in MAPPED}, body["mass"],
                                 0.5 * body["diameter"], body["inertia_factor"], body["spin"],
                                 partner["partner_mass"], 0.5 * partner["partner_diameter"],
                                 partner["partner_inertia_factor"], partner["partner_spin"], v_n, v_t)
    for name in (*MAPPED, *PARTNER_OUTPUTS):
        flat = result[name].to_numpy() if name in MAPPED else np.zeros(len(result))
        result[name] = np.where(pair, velocities[name], flat)
    for name, values in body.items():
        result[name] = values
    result = pd.concat([result, pd.DataFrame(partner)], axis=1)
    scene_columns = [name for name in result.columns if name not in SCALAR_OUTPUTS
                     and name not in (*PARTNER_FIELDS, *PARTNER_OUTPUTS, "path")]
    shown = [name for name in SCALAR_OUTPUTS if name in result and (wanted is None or name in wanted)]
    partner_shown = [name for name in PARTNER_OUTPUTS if wanted is None or name in wanted]
    return result[[*scene_columns, *PARTNER_FIELDS, *shown, *partner_shown, "path"]]
