"""Maps from sweep tables: spin and slip against angle, COR against speed, contact time and peak force."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..study.replication import load_published
from .paper import PUBLISHED_STYLE
from .style import RC, save


def grip_boundary(table: pd.DataFrame) -> float | None:
    """The angle [deg] where tan(beta) = (1 + 1/alpha) mu (1 + e): below it the ball grips."""
    beta = np.radians(table["angle"].to_numpy())
    g = np.tan(beta) - (1 + 1 / table["inertia_factor"]) * table["mu"] * (1 + table["cor"])
    change = np.flatnonzero(np.diff(np.sign(g)) > 0)
    if not change.size:
        return None
    i = change[0]
    return float(np.interp(0.0, g.iloc[i:i + 2], table["angle"].iloc[i:i + 2]))


def spin_map(angle_speed_csv: str, published_path: str, speed: float, outputs) -> None:
    """Spin and rebound contact-point slip against impact angle at one speed, with the grip/slide boundary."""
    table = pd.read_csv(angle_speed_csv)
    table = table[np.isclose(table["speed"], speed)].sort_values("angle")
    pub = {e["quantity"]: e["value"] for e in load_published(published_path) if e["case"] == "oblique60"}
    boundary = grip_boundary(table)
    with plt.rc_context(RC | {"figure.figsize": (6.4, 6.4)}):
        fig, (top, bottom) = plt.subplots(2, 1, sharex=True)
        top.plot(table["angle"], table["omega_f"], label="spin after impact $\\omega_f$")
        bottom.plot(table["angle"], table["ve_t"], color="tab:orange", label="contact-point slip $v_{E,t}$")
        for ax, key, label in ((top, "omega_f", "chapter, 60°: $\\omega_f$"), (bottom, "ve_t", "chapter, 60°: $v_{E,t}$")):
            if boundary is not None:
                ax.axvline(boundary, color="gray", linestyle="--",
                           label=f"grip/slide boundary {boundary:.1f}°: tan β = (1 + 1/α) μ (1 + e)")
            if key in pub:
                ax.plot([60.0], [pub[key]], label=label, **PUBLISHED_STYLE)
            ax.legend(loc="best")
        top.set(ylabel="spin [rad/s]", title=f"Spin and slip against impact angle at {speed:g} m/s")
        bottom.set(xlabel="inclination of the flat β [deg]", ylabel="slip [m/s]")
        fig.tight_layout()
        save(fig, outputs)


def cor_speed(speed_csv: str, outputs) -> None:
    """COR against impact speed for both force laws (normal impact)."""
    table = pd.read_csv(speed_csv)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        for model, part in table.groupby("model", sort=True):
            ax.plot(part["speed"], part["cor"], "--" if model == "kelvin-voigt" else "-", label=model)
        ax.plot([3.0], [0.85], label="chapter, 0°: 0.85 at v_n = 3 m/s", **PUBLISHED_STYLE)
        ax.plot([1.5], [0.86], label="chapter, 60°: 0.86 at v_n = 1.5 m/s", color="purple", marker="x",
                markersize=9, mew=2, linestyle="none")
        ax.set(xscale="log", xlabel="normal approach speed v_n [m/s]", ylabel="coefficient of restitution [-]",
               title="COR against speed: constant for eq. 4.1, not for eq. 4.2")
        ax.legend(loc="best")
        save(fig, outputs)


def contact_speed(speed_csv: str, outputs) -> None:
    """Contact time and peak force against impact speed for both force laws (normal impact)."""
    table = pd.read_csv(speed_csv)
    with plt.rc_context(RC | {"figure.figsize": (6.4, 6.4)}):
        fig, (top, bottom) = plt.subplots(2, 1, sharex=True)
        for model, part in table.groupby("model", sort=True):
            style = "--" if model == "kelvin-voigt" else "-"
            top.plot(part["speed"], part["t_f"] * 1e3, style, label=model)
            bottom.plot(part["speed"], part["force_max"], style, label=model)
        top.set(ylabel="contact time t_f [ms]", title="Contact time and peak force against speed (normal impact)")
        bottom.set(xscale="log", yscale="log", xlabel="normal approach speed v_n [m/s]", ylabel="peak force [N]")
        top.legend()
        fig.tight_layout()
        save(fig, outputs)
