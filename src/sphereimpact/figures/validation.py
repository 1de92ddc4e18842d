"""The model against Kharaz et al. (2001), in physical and in Maw's normalised variables; the chapter-ball map."""

from __future__ import annotations

import matplotlib.pyplot as plt
from matplotlib.colors import SymLogNorm
import numpy as np
import pandas as pd

from ..contact.tangential import TANGENTIALS
from .style import RC, save
_PANELS = (("e_t", "tangential COR $e_t = v_t'/v_t$ [-]"), ("omega_rad_s", "rebound spin |ω| [rad/s]"),
           ("rebound_angle_deg", "rebound angle of the centre [deg]"))


def _styles(models) -> dict:
    """Line style per tangential model: a contact without tangential stiffness (the rigid one) as a grey
    broken line, the compliant ones in colours in the order given."""
    compliant = [m for m in models if TANGENTIALS.model(m).stiffness_parameters]
    return {m: dict(color=f"C{compliant.index(m)}", ls="-") if m in compliant else dict(color="0.45", ls="--")
            for m in models}


def kharaz(curves_csv: str, data_csv: str, summary_csv: str, outputs) -> None:
    """e_t, spin and rebound angle against incidence: measured points, rigid and compliant curves."""
    curves, summary = pd.read_csv(curves_csv), pd.read_csv(summary_csv)
    data = pd.read_csv(data_csv, comment="#")
    low = float(summary["min_incidence"].iloc[0])
    with plt.rc_context(RC | {"figure.figsize": (6.4, 8.4)}):
        fig, axes = plt.subplots(3, 1, sharex=True)
        styles = _styles(curves["tangential"].unique())
        for ax, (key, label) in zip(axes, _PANELS):
            for tangential, rows in curves.groupby("tangential", sort=False):
                ax.plot(rows["incidence_deg"], rows[key], label=f"{tangential} tangential contact",
                        **styles[tangential])
            points = data[data["quantity"] == key]
            ax.plot(points["incidence_deg"], points["value"], "o", color="C3", ms=5, label="Kharaz et al. (2001)")
            ax.axvspan(0, low, color="0.92", zorder=0)
            ax.set_ylabel(label)
        fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=3, fontsize=8, frameon=False)
        axes[-1].set_xlabel("incidence from the normal [deg]")
        axes[-1].set_xlim(0, max(62.0, float(data["incidence_deg"].max()) + 2))
        text = "targets met: " + ", ".join(f"{r.tangential} {r.targets_met}/{r.targets}" for r in summary.itertuples())
        axes[0].set_title(f"5 mm alumina on glass, 3.9 m/s (shaded: below {low:g}°)\n{text}", fontsize=8)
        fig.tight_layout(rect=(0, 0.06, 1, 1))  # the legend below the panels, clear of every curve
        save(fig, outputs)


def maw(curves_csv: str, derived_csv: str, outputs) -> None:
    """Maw's normalised variables: psi_2 of the contact point against psi_1, the models and the data."""
    curves, derived = pd.read_csv(curves_csv), pd.read_csv(derived_csv)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        styles = _styles(curves["tangential"].unique())
        for tangential, rows in curves.groupby("tangential", sort=False):
            ax.plot(rows["psi1"], rows["psi2"], label=f"{tangential} tangential contact", **styles[tangential])
        ax.plot(derived["psi1"], derived["psi2"], "s", color="C3", ms=5,
                label="Kharaz et al., from e_t and spin (derived)")
        ax.axhline(0.0, color="0.3", lw=0.6)
        right = min(12.0, float(curves["psi1"].max()))
        shown = curves[curves["psi1"] <= right]["psi2"]
        ax.set_xlim(0, right)
        ax.set_ylim(min(float(shown.min()), float(derived["psi2"].min()), 0.0) - 0.5, float(shown.max()) + 0.5)
        ax.set_xlabel("ψ1 = κ tan θ / μ (incidence)")
        ax.set_ylabel("ψ2 = κ tan θc / μ (contact point's rebound)")
        ax.set_title("Maw's normalised variables (rigid: a broken line; negative ψ2: reversed contact point)",
                     fontsize=8)
        ax.legend(fontsize=8)
        fig.tight_layout()
        save(fig, outputs)


def compliance_map(map_csv: str, kappa_rubber: float, tolerance: float, outputs) -> None:
    """For each compliant model mapped, over angle x kappa: the signed relative spin difference against the
    rigid contact (left; the tangential spring rings, so it changes sign with kappa) and its envelope over
    neighbouring kappa, the larger of the spin and rebound-velocity differences (right), with the tolerance."""
    table = pd.read_csv(map_csv)
    models = list(dict.fromkeys(table["tangential"]))
    with plt.rc_context(RC | {"figure.figsize": (11.0, 4.2 * len(models))}):
        fig, axes = plt.subplots(len(models), 2, squeeze=False)
        for row, model in zip(axes, models):
            part = table[table["tangential"] == model]
            angles, kappas = np.unique(part["angle"]), np.unique(part["kappa"])
            grid = {key: part.pivot(index="kappa", columns="angle", values=key).loc[kappas, angles].to_numpy()
                    for key in ("spin_difference", "envelope")}
            law = part["model"].iloc[0]
            signed = row[0].pcolormesh(angles, kappas, grid["spin_difference"], shading="nearest", cmap="RdBu_r",
                                       norm=SymLogNorm(linthresh=tolerance / 10, vmin=-1.0, vmax=1.0))
            fig.colorbar(signed, ax=row[0], label="spin, compliant / rigid - 1")
            envelope = row[1].pcolormesh(angles, kappas, np.log10(np.maximum(grid["envelope"], 1e-16)),
                                         shading="nearest", cmap="viridis", vmin=-4, vmax=0)
            row[1].contour(angles, kappas, grid["envelope"], levels=[tolerance], colors="w", linewidths=1.2)
            fig.colorbar(envelope, ax=row[1], label="log10 largest difference (spin, rebound velocity)")
            for ax, title in ((row[0], "signed spin difference"),
                              (row[1], f"envelope over neighbouring κ (white: {100 * tolerance:g} %)")):
                ax.axhline(kappa_rubber, color="C3" if ax is row[1] else "k", lw=1.0, ls="--")
                ax.set_yscale("log")
                ax.set(xlabel="angle of the flat [deg]", ylabel="κ = k_t / k_n", title=f"{model} ({law} law): {title}")
                ax.title.set_fontsize(8)
        fig.suptitle(f"Chapter's ball: compliant against rigid tangential contact (dashed: κ = {kappa_rubber:.3g}, "
                     "rubber)", fontsize=9)
        fig.tight_layout()
        save(fig, outputs)
