"""A measurement plan's figure: where a bounce informs each parameter, and the bounces chosen."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .style import RC, save


def plan_figure(plan, outputs) -> None:
    """Each free parameter's standard error from one bounce alone (the others known) against the candidates'
    incidence from the normal, log scale (a gap: the bounce does not inform it), the chosen bounces marked, and
    the plan's expected error, as many evenly spread bounces' and every candidate's as lines (``plan``: a
    :class:`~sphereimpact.fit.plan.Plan`)."""
    frame = plan.candidates
    x = frame["incidence_deg"].to_numpy()
    order = np.argsort(x, kind="stable")
    names = list(plan.free)
    with plt.rc_context(RC | {"figure.figsize": (6.4, 2.4 * len(names) + 1.2)}):
        fig, axes = plt.subplots(len(names), 1, sharex=True, squeeze=False, layout="constrained")
        for ax, name in zip(axes[:, 0], names):
            single = frame[f"stderr_{name}"].to_numpy()
            shown = np.where(np.isfinite(single), single, np.nan)
            ax.semilogy(x[order], shown[order], ".-", color="0.5", ms=3, lw=0.8, label="one bounce alone")
            chosen = frame["chosen"].to_numpy()
            ax.semilogy(x[chosen], shown[chosen], "o", color="C3", ms=6, mfc="none", label="chosen")
            levels = [v for v in shown if np.isfinite(v)]
            for label, style, colour in (("chosen", "-", "C3"), ("even", "--", "C0"), ("all", ":", "0.3")):
                error = plan.stderr[label][name]
                if np.isfinite(error):
                    levels.append(error)
                    ax.axhline(error, color=colour, ls=style, lw=1.2,
                               label={"chosen": "the plan", "even": "as many, evenly spread",
                                      "all": "every candidate"}[label])
            if levels:  # axhline does not widen a log axis: every level inside it
                ax.set_ylim(min(levels) / 1.5, max(levels) * 1.5)
            ax.set_ylabel(f"standard error of {name}")
        axes[-1, 0].set_xlabel("incidence from the normal [deg]")
        handles, labels = axes[0, 0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=7)
        fig.suptitle(f"{plan.criterion}-optimal plan of {len(plan.chosen)} bounces of {len(frame)} candidates\n"
                     f"noise {', '.join(f'{k} {v}' for k, v in plan.noise.items())}", fontsize=9)
        save(fig, outputs)
