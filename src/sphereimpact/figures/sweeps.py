"""Maps from sweep tables: spin and slip against angle, COR against speed, contact time and peak force."""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from ..contact.tangential import kappa_from_poisson
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


def printed(published_path: str, config: dict, quantity: str) -> list[dict]:
    """The chapter's printed values of ``quantity`` for the configured cases, each with its case's angle
    [deg] and normal approach speed v_n [m/s] (from the config: the chapter's speed and the case's angle)."""
    cases = config["cases"]
    out = []
    for entry in load_published(published_path):
        if entry["quantity"] == quantity and entry["case"] in cases:
            angle = float(cases[entry["case"]]["angle"])
            out.append(entry | {"angle": angle, "v_n": config["speed"] * math.cos(math.radians(angle))})
    return out


def spin_map(angle_speed_csv: str, published_path: str, config: dict, outputs, compliance_csv: str | None = None) -> None:
    """Spin and rebound contact-point slip against impact angle at ``config['sweep']['map_speed']``, with
    the grip/slide boundary; the chapter's printed values are marked when that is the chapter's speed.

    With ``compliance_csv`` (``results/compliance_map.csv``, solved at the chapter's speed) and the map at
    that speed, the compliant tangential contact (rubber's kappa) is drawn beside the rigid one."""
    speed = config["sweep"]["map_speed"]
    table = pd.read_csv(angle_speed_csv)
    table = table[np.isclose(table["speed"], speed)].sort_values("angle")
    if table.empty:
        raise ValueError(f"sweep.map_speed = {speed:g} m/s is not on the sweep's speed grid: the spin map "
                         "would be empty")
    same_speed = math.isclose(speed, config["speed"])
    boundary = grip_boundary(table)
    with plt.rc_context(RC | {"figure.figsize": (10.0, 6.4)}):
        fig, (top, bottom) = plt.subplots(2, 1, sharex=True)
        top.plot(table["angle"], table["omega_f"], label="spin after impact $\\omega_f$ (rigid contact)")
        bottom.plot(table["angle"], table["ve_t"], color="tab:orange", label="contact-point slip $v_{E,t}$ (rigid contact)")
        if compliance_csv is not None and same_speed:
            compliant = pd.read_csv(compliance_csv)
            kappa = kappa_from_poisson(config["compliance"]["poisson"])
            compliant = compliant[np.isclose(compliant["kappa"], kappa)].sort_values("angle")
            label = f"compliant contact, κ = {kappa:.3g} (points: its stick-slip switches change with the angle)"
            for ax, key, color in ((top, "omega_f", "tab:blue"), (bottom, "ve_t", "tab:orange")):
                ax.plot(compliant["angle"], compliant[key], color=color, ls="none", marker=".", ms=3, label=label)
        for ax, key in ((top, "omega_f"), (bottom, "ve_t")):
            if boundary is not None:
                ax.axvline(boundary, color="gray", linestyle="--",
                           label=f"grip/slide boundary {boundary:.1f}°: tan β = (1 + 1/α) μ (1 + e)")
            for entry in printed(published_path, config, key) if same_speed else []:
                ax.plot([entry["angle"]], [entry["value"]], label=f"chapter, {entry['angle']:g}°: {_math(entry['printed'])}",
                        **PUBLISHED_STYLE)
            ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
        top.set(ylabel="spin [rad/s]", title=f"Spin and slip against impact angle at {speed:g} m/s")
        bottom.set(xlabel="inclination of the flat β [deg]", ylabel="slip [m/s]")
        fig.tight_layout()
        save(fig, outputs)


def cor_speed(speed_csv: str, published_path: str, config: dict, outputs) -> None:
    """COR against normal impact speed for both force laws, with the chapter's printed CORs at their v_n."""
    table = pd.read_csv(speed_csv)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        for model, part in table.groupby("model", sort=True):
            ax.plot(part["speed"], part["cor"], "--" if model == "kelvin-voigt" else "-", label=model)
        for entry, color in zip(printed(published_path, config, "cor"), ("crimson", "purple", "teal", "olive")):
            ax.plot([entry["v_n"]], [entry["value"]], **(PUBLISHED_STYLE | {"color": color}),
                    label=f"chapter, {entry['angle']:g}°: {entry['value']:g} at v_n = {entry['v_n']:.3g} m/s")
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
            if "delta_f" in part and (part["delta_f"] > 0).any() and (part["delta_f"] == 0).any():
                onset = float(part["speed"][part["delta_f"] > 0].min())  # the end switches from delta = 0 to P = 0
                for ax in (top, bottom):
                    ax.axvline(onset, color="0.5", linestyle=":", linewidth=1.0,
                               label=f"{model}: from {onset:.3g} m/s the contact ends at P = 0 before δ = 0"
                               if ax is top else None)
        top.set(ylabel="contact time $t_f$ [ms]", title="Contact time and peak force against speed (normal impact)")
        bottom.set(xscale="log", yscale="log", xlabel="normal approach speed $v_n$ [m/s]", ylabel="peak force [N]")
        top.legend(fontsize=7)
        fig.tight_layout()
        save(fig, outputs)


def _math(text: str) -> str:
    """The chapter's printed quantities typeset as the figures' own labels (``ω_f`` -> $\\omega_f$)."""
    for plain, math_text in (("ω_f", "$\\omega_f$"), ("v_E(t_f)", "$v_E(t_f)$")):
        text = text.replace(plain, math_text)
    return text


#: Each sweep map: what it draws from (angle-speed table, speed table, published values, config, compliance).
MAPS = {
    "spin_map": lambda a, s, p, c, o, m: spin_map(a, p, c, o, m),
    "cor_speed": lambda a, s, p, c, o, m: cor_speed(s, p, c, o),
    "contact_speed": lambda a, s, p, c, o, m: contact_speed(s, o),
}


def draw_map(name: str, angle_speed_csv: str, speed_csv: str, published_path: str, config: dict, outputs,
             compliance_csv: str | None = None) -> None:
    """Draw sweep map ``name`` (a key of :data:`MAPS`) to ``outputs``."""
    if name not in MAPS:
        raise ValueError(f"no sweep map named {name!r}; the maps: {', '.join(MAPS)}")
    MAPS[name](angle_speed_csv, speed_csv, published_path, config, outputs, compliance_csv)
