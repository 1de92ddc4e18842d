"""Figures of a study of one's own ball, drawn from its tables: each bounce's history, the normal impact's
COR, contact time and peak force against speed, and the spin and rebound-angle maps."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..impact.ball import load_ball
from .history import history_figure
from .style import RC, save


def bounce_figure(history: pd.DataFrame, study: str, bounce: str, separation: str, outputs) -> None:
    """One bounce's history (:func:`sphereimpact.figures.history.history_figure`), titled by its study, its
    contact ended under ``separation``."""
    history_figure(history, f"study {study}: bounce {bounce}", separation, outputs)


def speed_figure(csv_path: str, study: str, outputs, measured_at: float | None = None) -> None:
    """COR, contact time and peak force of normal impacts against speed, with a dotted line at ``measured_at``
    [m/s], the speed of the COR's measurement (the law extrapolates away from it)."""
    table = pd.read_csv(csv_path)
    with plt.rc_context(RC | {"figure.figsize": (12.0, 3.8)}):
        fig, axes = plt.subplots(1, 3)
        for ax, (key, scale, label) in zip(axes, (("cor", 1.0, "COR [-]"), ("t_f", 1e3, "contact time [ms]"),
                                                   ("force_max", 1.0, "peak normal force [N]"))):
            ax.plot(table["speed"], table[key] * scale)
            if measured_at is not None:
                ax.axvline(measured_at, color="0.4", linestyle=":", linewidth=1.0, label="COR measured here")
            ax.set(xlabel="impact speed, normal [m/s]", ylabel=label)
        if measured_at is not None:
            axes[0].legend(loc="best", frameon=False)
        fig.suptitle(f"study {study}: normal impacts against speed", fontsize=9)
        fig.tight_layout()
        save(fig, outputs)


def map_figure(csv_path: str, study: str, key: str, label: str, outputs, centre: float | None = None) -> None:
    """One output over angle to the surface x speed; with ``centre``, a signed quantity on a diverging scale
    symmetric about it (so its sign reads off the colour: the spin's topspin red, backspin blue)."""
    table = pd.read_csv(csv_path)
    angles, speeds = np.unique(table["angle_to_surface"]), np.unique(table["speed"])
    values = table.pivot(index="speed", columns="angle_to_surface", values=key).loc[speeds, angles].to_numpy()
    scale = {"cmap": "viridis"}
    if centre is not None:
        reach = float(np.nanmax(np.abs(values - centre))) or 1.0
        scale = {"cmap": "RdBu_r", "vmin": centre - reach, "vmax": centre + reach}
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        mesh = ax.pcolormesh(angles, speeds, values, shading="nearest", **scale)
        fig.colorbar(mesh, ax=ax, label=label)
        ax.set(xlabel="angle to the surface [deg]", ylabel="speed along the path [m/s]")
        ax.set_title(f"study {study}: {label}, incoming spin {table['spin'].iloc[0]:g} rad/s", fontsize=9)
        fig.tight_layout()
        save(fig, outputs)


def curves_and_maps(speed_csv: str, maps_csv: str, ball_json: str, study: str, outputs: dict, plugins=()) -> None:
    """The study's speed figure and its two maps (``outputs``: speed, spin_map, rebound_map -> path); ``plugins``:
    the study's, which its ball file may name."""
    measured = load_ball(ball_json, plugins).measurement
    speed_figure(speed_csv, study, [outputs["speed"]], None if measured is None else measured.speed)
    map_figure(maps_csv, study, "omega_f", "rebound spin [rad/s], + topspin, - backspin", [outputs["spin_map"]],
               centre=0.0)
    map_figure(maps_csv, study, "rebound_angle_to_surface", "rebound angle of the centre to the surface [deg]",
               [outputs["rebound_map"]])
