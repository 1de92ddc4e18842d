"""A fit's data against its model: one panel per measured quantity, the model's uncertainty as a band."""

from __future__ import annotations

import matplotlib.pyplot as plt
import pandas as pd

from ..impact.outcome import OUTPUT_UNITS
from .style import RC, save

#: Axis labels of the derived quantities (the others are named as simulate's outputs, with units).
_LABELS = {"e_t": "e_t = v_t'/v_t [-]", "abs_omega_f": "|ω_f| [rad/s]"}


def fit_figure(residuals: pd.DataFrame, title: str, outputs) -> None:
    """Measured values (with their standard uncertainty where one was given) and the fitted model at each
    bounce, against the bounce's incidence from the normal (or its speed, when every bounce is normal), the
    model's standard error from the parameters' covariance as a band (±2 standard errors); drawn as a curve
    when the bounces differ only along the axis, else at each bounce (a line through bounces of different
    speeds or spins would mean nothing)."""
    quantities = list(dict.fromkeys(residuals["quantity"]))
    x_name = "incidence" if residuals["incidence"].nunique() > 1 else "speed"
    x_label = "incidence from the normal [deg]" if x_name == "incidence" else "approach speed [m/s]"
    with plt.rc_context(RC | {"figure.figsize": (6.4, 2.6 * len(quantities) + 0.8)}):
        fig, axes = plt.subplots(len(quantities), 1, sharex=True, squeeze=False)
        curve = all(residuals[c].nunique() <= 1 for c in ("speed", "spin") if c in residuals and c != x_name)
        for ax, name in zip(axes[:, 0], quantities):
            rows = residuals[residuals["quantity"] == name].sort_values(x_name)
            x, model, band = rows[x_name].to_numpy(), rows["model"].to_numpy(), 2.0 * rows["model_stderr"].to_numpy()
            if curve:
                ax.fill_between(x, model - band, model + band, color="C0", alpha=0.25, lw=0,
                                label="model ± 2 standard errors")
                ax.plot(x, model, "-", color="C0", label="fitted model")
            else:
                ax.errorbar(x, model, yerr=band, fmt="_", color="C0", ms=10, capsize=0,
                            label="fitted model at each bounce ± 2 standard errors")
            given, measured = rows["sigma_given"].to_numpy(bool), rows["measured"].to_numpy()
            if given.any():
                ax.errorbar(x[given], measured[given], yerr=rows["sigma"].to_numpy()[given], fmt="o", color="C3",
                            ms=4, capsize=2, label="measured ± its uncertainty")
            if not given.all():
                ax.plot(x[~given], measured[~given], "o", color="C3", ms=4, mfc="none",
                        label="measured (no uncertainty given)")
            unit = OUTPUT_UNITS.get(name, "")
            ax.set_ylabel(_LABELS.get(name, f"{name} [{unit}]" if unit else name))
        legend = {}  # every kind of mark any panel drew, once
        for ax in axes[:, 0]:
            for handle, label in zip(*ax.get_legend_handles_labels()):
                legend.setdefault(label, handle)
        fig.legend(legend.values(), legend.keys(), loc="lower center", ncol=2, fontsize=8, frameon=False)
        axes[-1, 0].set_xlabel(x_label)
        axes[0, 0].set_title(title, fontsize=8)
        fig.tight_layout(rect=(0, 0.07 if len(quantities) > 1 else 0.12, 1, 1))
        save(fig, outputs)

