"""Measured bounces, as a fit reads them: each bounce's approach and what was measured of its outcome.

Two layouts are read.  A *wide* table has one bounce per row: columns named like the scene's approach
(``speed`` [m/s], ``incidence`` or ``angle_to_surface`` or ``angle`` [deg], ``spin`` [rad/s]) and measured
outputs named like ``simulate``'s (``vc_t``, ``vc_n``, ``omega_f``, ``cor``, ``rebound_angle``, ...; SI, contact
frame) or the derived :data:`DERIVED` ones, any subset, each with an optional uncertainty column
``sigma_<output>`` (one standard deviation, same units).  The *long* layout of the shipped Kharaz et al. (2001)
data has columns ``quantity, incidence_deg, value`` (and optionally ``sigma``, ``speed``, ``spin``); its quantities
are mapped by :data:`LONG_QUANTITIES`.
An approach column a table does not give takes the fitted ball's value.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..impact.ball import APPROACH
from ..sweep.scenes import approach_speeds
from .names import MEASURABLE

#: The long layout's quantities (Kharaz's digitised curves) -> the quantity they measure.
LONG_QUANTITIES = {"e_t": "e_t", "omega_rad_s": "abs_omega_f", "rebound_angle_deg": "rebound_angle"}
#: The long layout's columns, and those it may add: each value's standard uncertainty (its quantity's unit) and
#: the bounce's approach speed [m/s] and spin [rad/s].
LONG_COLUMNS = ("quantity", "incidence_deg", "value")
LONG_OPTIONAL = ("sigma", "speed", "spin")


@dataclass(frozen=True)
class Measured:
    """Measured bounces.

    Attributes
    ----------
    bounces : DataFrame
        One row per bounce: its approach (the columns of :data:`APPROACH` it gives).
    values : DataFrame
        One row per measured value: ``bounce`` (row of ``bounces``), ``quantity`` (a name of
        :data:`MEASURABLE`), ``value`` and ``sigma`` (its standard uncertainty, NaN when not given).
    source : str
        Where the data come from (the file's name), for the fitted ball's record.
    """

    bounces: pd.DataFrame
    values: pd.DataFrame
    source: str = ""


def read_measured(data, source: str = "") -> Measured:
    """Measured bounces from a CSV file's path or a DataFrame, in either layout (module docstring).

    Parameters
    ----------
    data : str, path or DataFrame
        The table (a CSV file's ``#`` lines are comments).
    source : str
        Where the data come from (default: the file's path).

    Raises
    ------
    ValueError
        An unreadable file, a column that is neither an approach nor a measurable quantity, a value that is
        not a finite number, a negative uncertainty, or a table with nothing measured.
    """
    if isinstance(data, pd.DataFrame):
        frame, source = data.reset_index(drop=True), source or "a DataFrame"
    else:
        try:
            frame = pd.read_csv(data, comment="#")
        except (OSError, pd.errors.ParserError, UnicodeDecodeError) as err:
            raise ValueError(f"measured: cannot read {str(data)!r} ({getattr(err, 'strerror', None) or err})") from None
        source = source or str(data)
    if {"quantity", "incidence_deg", "value"} <= set(frame.columns):
        frame = _wide_from_long(frame, source)
    measured = _checked(frame, source)
    bounces = frame[[c for c in APPROACH if c in frame.columns]].copy()
    values = [pd.DataFrame({"bounce": np.flatnonzero(frame[q].notna().to_numpy()), "quantity": q,
                            "value": frame[q].dropna().to_numpy(float),
                            "sigma": (frame[f"sigma_{q}"] if f"sigma_{q}" in frame else pd.Series(np.nan, frame.index))
                            [frame[q].notna()].to_numpy(float)}) for q in measured]
    return Measured(bounces.reset_index(drop=True), pd.concat(values, ignore_index=True), source)


def _wide_from_long(frame: pd.DataFrame, source: str) -> pd.DataFrame:
    """The long layout (quantity, incidence_deg, value; optionally sigma, speed, spin) as a wide table: one bounce
    per measured value.  Every cell is read or refused, as in the wide layout: a column of neither kind, a value
    or an incidence that is not a finite number (an empty cell included)."""
    unknown = [c for c in frame.columns if c not in (*LONG_COLUMNS, *LONG_OPTIONAL)]
    if unknown:
        raise ValueError(f"measured: {source}: column {unknown[0]!r} is not one of the long layout's "
                         f"({', '.join((*LONG_COLUMNS, *LONG_OPTIONAL))})")
    names = frame["quantity"]
    strange = [q for q in dict.fromkeys(names) if q not in LONG_QUANTITIES]
    if strange:
        raise ValueError(f"measured: {source}: unknown quantity {strange[0]!r} in the long layout; expected "
                         f"{', '.join(LONG_QUANTITIES)}")
    numbers = {}
    for column in (c for c in frame.columns if c != "quantity"):
        values = pd.to_numeric(frame[column], errors="coerce")
        bad = ~np.isfinite(values) & (frame[column].notna() if column == "sigma" else True)
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            cell = frame[column].iloc[row]
            shown = "an empty cell" if pd.isna(cell) else f"{cell!r} is not a finite number"
            raise ValueError(f"measured: {source}: column {column!r} row {row}: {shown}"
                             + ("" if column == "sigma" else " (every measured value needs it)"))
        numbers[column] = values
    wide = pd.DataFrame({"incidence": numbers["incidence_deg"]})
    for column in ("speed", "spin"):
        if column in numbers:
            wide[column] = numbers[column]
    for name, quantity in LONG_QUANTITIES.items():
        rows = names == name
        if rows.any():
            wide[quantity] = np.where(rows, numbers["value"], np.nan)
            if "sigma" in numbers:
                wide[f"sigma_{quantity}"] = np.where(rows, numbers["sigma"], np.nan)
    return wide


def _checked(frame: pd.DataFrame, source: str) -> list[str]:
    """The measured quantities of a wide table, each column checked."""
    sigmas = {f"sigma_{q}" for q in MEASURABLE}
    unknown = [c for c in frame.columns if c not in APPROACH and c not in MEASURABLE and c not in sigmas]
    if unknown:
        raise ValueError(f"measured: {source}: column {unknown[0]!r} is neither an approach ({', '.join(APPROACH)}) "
                         f"nor a measurable quantity ({', '.join(MEASURABLE)}) nor its sigma_<quantity>")
    for column in frame.columns:
        numbers = pd.to_numeric(frame[column], errors="coerce")
        bad = frame[column].notna() & ~np.isfinite(numbers)
        if bad.any():
            raise ValueError(f"measured: {source}: column {column!r} row {int(np.flatnonzero(bad)[0])}: "
                             f"{frame[column][bad].iloc[0]!r} is not a finite number")
        if column.startswith("sigma_") and (numbers <= 0).any():
            raise ValueError(f"measured: {source}: {column} must be > 0 (a standard uncertainty)")
        if column in APPROACH and numbers.isna().any():
            raise ValueError(f"measured: {source}: column {column!r} has an empty cell: every bounce needs its "
                             "approach")
        frame[column] = numbers
    measured = [q for q in MEASURABLE if q in frame.columns and frame[q].notna().any()]
    if not measured:
        raise ValueError(f"measured: {source}: nothing measured; give some of {', '.join(MEASURABLE)}")
    return measured


#: The sweep output each derived quantity is computed from.
SOURCES = {"e_t": "vc_t", "abs_omega_f": "omega_f"}


def quantity(name: str, outputs: pd.DataFrame) -> np.ndarray:
    """The model's value of a measured quantity at each bounce, from a sweep's ``outputs`` of the bounces (its
    rows carry each scene's approach)."""
    if name == "e_t":
        return outputs["vc_t"].to_numpy() / approach_speeds(outputs)[1]
    if name == "abs_omega_f":
        return np.abs(outputs["omega_f"].to_numpy())
    return outputs[name].to_numpy(dtype=float)
