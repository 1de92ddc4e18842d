"""What a DEM code's tangential rule costs, as a figure: each rule's largest departure from the exact contact."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.ticker import NullFormatter

from .style import RC, save

#: The panels: (quantity, axis label).
PANELS = (("omega_f", "ball's spin ω_f"), ("rebound_angle_contact", "contact point's rebound angle"))


def departure_figure(departure_csv, outputs) -> None:
    """Horizontal bars, one group per DEM rule, one bar per scene set (Chung & Ooi's tests, the Kharaz ball), the
    largest departure from the exact elastic microslip contact relative to the exact quantity's largest magnitude
    (:func:`sphereimpact.study.departure.departures`), on a log scale; one panel per quantity of :data:`PANELS`."""
    table = pd.read_csv(departure_csv)
    scenes = list(dict.fromkeys(table["scenes"]))
    rules = list(dict.fromkeys(table["rule"]))
    height = 0.8 / max(len(scenes), 1)
    with plt.rc_context(RC | {"figure.figsize": (7.2, 1.2 + 0.55 * len(rules))}):
        fig, axes = plt.subplots(1, len(PANELS), sharey=True, layout="constrained")
        for ax, (quantity, label) in zip(axes, PANELS):
            mine = table[table["quantity"] == quantity]
            for i, name in enumerate(scenes):
                values = mine[mine["scenes"] == name].set_index("rule")["max_rel"].reindex(rules)
                y = np.arange(len(rules)) + (i - (len(scenes) - 1) / 2) * height
                shown = values.to_numpy(dtype=float)
                ax.barh(y, np.where(shown > 0, shown, np.nan), height=height, color=f"C{i}", label=name)
            ax.set(xscale="log", xlabel="largest relative departure")
            shown_all = mine["max_rel"].to_numpy(dtype=float)
            shown_all = shown_all[shown_all > 0]
            if shown_all.size:  # whole decades, so that the axis has labelled ticks and no crowded minor labels
                ax.set_xlim(10.0 ** np.floor(np.log10(shown_all.min())), 10.0 ** np.ceil(np.log10(shown_all.max())))
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_title(label, fontsize=8)
            ax.grid(axis="x", which="both", lw=0.3)
        axes[0].set_yticks(np.arange(len(rules)), rules)
        axes[0].invert_yaxis()
        handles, labels = axes[0].get_legend_handles_labels()
        fig.legend(handles, labels, fontsize=7, ncol=len(scenes), loc="outside lower center")
        fig.suptitle("DEM tangential rules against the exact elastic microslip contact", fontsize=9)
        save(fig, outputs)
        plt.close(fig)
