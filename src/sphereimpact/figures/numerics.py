"""Figures of the numerical studies: work-precision and where methods fail (read from their CSV files)."""

from __future__ import annotations

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
import numpy as np
import pandas as pd

from ..contact.separation import Separation
from .style import RC, save

COLORS = {"taylor": "tab:pink", "DOP853-scalar": "tab:olive", "RK23": "tab:blue", "RK45": "tab:orange",
          "DOP853": "tab:green", "Radau": "tab:red", "BDF": "tab:purple", "LSODA": "tab:brown", "closed": "black"}
BODY_STYLE = {"reduced": "-", "planar": "--"}


def work_precision_figure(csv_path: str, outputs, model: str = "modified", target: float = 1e-9) -> None:
    """Error against median wall time (top) and nfev (bottom), one column per case, one line per method x body."""
    frame = pd.read_csv(csv_path)
    frame = frame[(frame["model"] == model) & (frame["status"] == "ok")]
    cases = list(dict.fromkeys(frame["case"]))
    with plt.rc_context(RC | {"figure.figsize": (5.2 * len(cases), 8.0)}):
        fig, axes = plt.subplots(2, len(cases), squeeze=False, sharey=True)
        for col, case in enumerate(cases):
            data = frame[frame["case"] == case]
            for (method, body), line in data.groupby(["method", "body"], sort=False):
                style = dict(color=COLORS[method], marker="*" if body == "closed" else "o", markersize=4,
                             linestyle="none" if body == "closed" else BODY_STYLE[body])
                label = f"{method} ({body})"
                for row, x in enumerate(("time", "nfev")):
                    if body == "closed" and x == "nfev":
                        continue
                    axes[row, col].loglog(line[x] * (1e3 if x == "time" else 1), line["error"], label=label, **style)
            labels = ("median wall time per impact [ms]",
                      "right-hand-side evaluations (nfev; taylor: series coefficients)")
            for row, x in enumerate(labels):
                ax = axes[row, col]
                ax.axhline(target, color="gray", linewidth=0.8, linestyle=":")
                ax.set(xlabel=x, ylabel="worst relative error", title=f"{case}, {model} law")
        methods = list(dict.fromkeys(frame["method"]))
        handles = [Line2D([], [], color=COLORS[m], marker="o", markersize=5, linestyle="-", label=m) for m in methods]
        handles += [Line2D([], [], color="black", linestyle=BODY_STYLE[body], label=f"{body} body")
                    for body in BODY_STYLE if body in set(frame["body"])]
        handles.append(Line2D([], [], color="gray", linewidth=0.8, linestyle=":", label=f"target {target:g}"))
        fig.suptitle("Work-precision: colour = method, line = body (solid: reduced, dashed: full planar)")
        # fixed margins in inches (tight_layout's, measured once): tight_layout on these log axes took half the
        # drawing time, and save's layout check still refuses a figure whose texts overlap or leave the page
        width, height = fig.get_size_inches()
        fig.subplots_adjust(left=0.84 / width, right=1 - 0.15 / width, bottom=1.17 / height, top=1 - 0.68 / height,
                            wspace=0.1, hspace=0.31)
        fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=9, frameon=False)
        save(fig, outputs)


def _lines(ax, data, x, y, by="method", style="-o", label_suffix=""):
    for key, line in data.groupby(by, sort=False):
        ax.plot(line[x], line[y], style, color=COLORS.get(key), markersize=3, label=f"{key}{label_suffix}")


def stability_figure(csv_path: str, outputs) -> None:
    """Six panels, one picture per failure mode (see sphereimpact.numerics.stability)."""
    frame = pd.read_csv(csv_path)
    ok = frame[frame["status"] == "ok"]
    with plt.rc_context(RC | {"figure.figsize": (15.0, 9.0), "legend.fontsize": 7}):
        fig, ax = plt.subplots(2, 3)
        stiff = ok[ok["study"] == "stiffness"]
        for panel, name in ((ax[0, 0], "zeta"), (ax[0, 1], "k [N/m]")):
            _lines(panel, stiff[stiff["x_name"] == name], "x", "nfev")
            panel.set(xscale="log", yscale="log", xlabel=name, ylabel="nfev per impact (rtol 1e-8)",
                      title=f"1. stiffness: cost against {name.split()[0]}")
        ax[0, 0].legend()
        onset = ok[ok["study"] == "onset"]
        for variant, style in (("start at contact (package)", "-o"), ("through contact from free flight", "--x")):
            _lines(ax[0, 2], onset[onset["variant"] == variant], "x", "error", style=style,
                   label_suffix=" from contact" if "package" in variant else " through contact")
        ax[0, 2].set(xscale="log", yscale="log", xlabel="rtol", ylabel="worst relative error",
                     title="2. force jump at onset (previous model)")
        ax[0, 2].legend(ncol=2)
        grip = ok[(ok["study"] == "grip") & (ok["variant"] == "tanh(slip/eps)")]
        _lines(ax[1, 0], grip, "x", "nfev")
        exact = ok[(ok["study"] == "grip") & (ok["variant"].str.startswith("exact"))]
        for _, row in exact.iterrows():
            ax[1, 0].axhline(row["nfev"], color=COLORS[row["method"]], linestyle=":", linewidth=1,
                             label=f"{row['method']}, exact switch (event)")
        failed = frame[(frame["study"] == "grip") & (frame["status"] != "ok")]
        ax[1, 0].set(xscale="log", yscale="log", xlabel="tanh width eps [m/s]", ylabel="nfev (rtol 1e-8)",
                     title=f"3. friction at grip: tanh(slip/eps); dotted = exact switch\n"
                           f"{len(failed)} sign()/tanh runs over budget (chattering)")
        ax[1, 0].invert_xaxis()
        ax[1, 0].legend()
        sep = ok[ok["study"] == "separation"]
        for variant, style in (("root on dense output (package)", "-o"), ("first step end past separation", "--x")):
            _lines(ax[1, 1], sep[sep["variant"] == variant], "x", "error", style=style)
        ax[1, 1].set(xscale="log", yscale="log", xlabel="rtol", ylabel="relative error of $t_f$",
                     title="4. separation: dense-output root (solid)\nvs first step end (dashed)")
        handles = [Line2D([], [], color=COLORS.get(m), marker="o", markersize=3, label=m)
                   for m in dict.fromkeys(sep["method"])]
        ax[1, 1].legend(handles=handles, ncol=2)
        past = frame[frame["study"] == "past-separation"]
        methods = list(dict.fromkeys(past["method"]))
        xs = np.arange(len(methods))
        for offset, variant, color in ((-0.2, "unguarded law, fixed window", "crimson"),
                                       (0.2, "guarded law, terminal event (package)", "seagreen")):
            part = past[past["variant"] == variant].set_index("method").reindex(methods)
            ax[1, 2].bar(xs + offset, part["nfev"], width=0.4, color=color, label=variant)
        ax[1, 2].set(xticks=xs, yscale="log", ylabel="nfev",
                     title="5. modified law past separation:\nunguarded blows up (every method fails)")
        ax[1, 2].set_xticklabels(methods, rotation=30, ha="right")
        ax[1, 2].legend()
        fig.tight_layout()
        save(fig, outputs)


def microslip_resolution_figure(csv_path: str, outputs) -> None:
    """Worst error over the scenes against the time of one impact, one line per cell count (left), and each
    scene's error against the time steps at the chosen cell count (right)."""
    frame = pd.read_csv(csv_path)
    settings = frame.groupby(["elements", "time_steps"], as_index=False).agg(
        worst_error=("worst_error", "first"), time=("time", "median"), chosen=("chosen", "first"),
        package_default=("package_default", "first"))
    with plt.rc_context(RC | {"figure.figsize": (13.0, 4.8)}):
        fig, (left, right) = plt.subplots(1, 2)
        colors = plt.cm.viridis(np.linspace(0.0, 0.9, settings["elements"].nunique()))
        for color, (cells, line) in zip(colors, settings.groupby("elements")):
            left.loglog(line["time"] * 1e3, line["worst_error"], "-o", color=color, markersize=3,
                        label=f"{cells} cells")
        for mask, marker, label in ((settings["chosen"], "*", "chosen (cheapest meeting the target)"),
                                    (settings["package_default"], "s", "package default")):
            if mask.any():
                left.loglog(settings["time"][mask] * 1e3, settings["worst_error"][mask], marker, color="C3",
                            markersize=11, markerfacecolor="none", label=label)
        left.set(xlabel="median time of one impact [ms]",
                 ylabel="worst error over the scenes\n($e_t$ absolute, spin relative)",
                 title="microslip: accuracy against cost")
        left.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
        chosen = frame[frame["chosen"]]
        cells = int(chosen["elements"].iloc[0]) if len(chosen) else int(frame["elements"].max())
        for scene, line in frame[frame["elements"] == cells].groupby("scene", sort=False):
            right.loglog(line["time_steps"], line["error"], "-o", markersize=3, label=scene)
        right.set(xlabel="time steps over the contact",
                  ylabel="error against the reference\n($e_t$ absolute, spin relative)", title=f"each scene, {cells} cells")
        right.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
        fig.tight_layout()
        save(fig, outputs)


PATH_COLORS = {"lambda-interpolant": "tab:blue", "plane": "tab:orange", "taylor-lanes": "tab:pink",
               "runge-kutta-lanes": "tab:green"}
CRITERION_STYLE = {Separation.FORCE: "-", Separation.PENETRATION: "--"}
#: What each path of the sweep-path study is (the figure's key).
PATH_NOTES = {"lambda-interpolant": "a Chebyshev interpolant in lam for one zeta (one ball), from batched lanes",
              "plane": "a Chebyshev interpolant over the (zeta, lam) plane (many balls), from batched lanes",
              "taylor-lanes": "every scene integrated at once by the Taylor method (one lane each)",
              "runge-kutta-lanes": "every scene integrated at once by DOP853 (one lane each)"}


def sweep_paths_figure(csv_path: str, outputs) -> None:
    """Time per scene (top) and worst error (bottom) against the sweep's size, one column per comparison of
    the sweep-path study, one line per path and criterion."""
    frame = pd.read_csv(csv_path)
    comparisons = list(dict.fromkeys(frame["comparison"]))
    with plt.rc_context(RC | {"figure.figsize": (5.2 * len(comparisons), 7.0)}):
        fig, axes = plt.subplots(2, len(comparisons), squeeze=False, sharex=True)
        for col, comparison in enumerate(comparisons):
            data = frame[frame["comparison"] == comparison]
            for (path, criterion), line in data.groupby(["path", "separation"], sort=False):
                style = dict(color=PATH_COLORS.get(path, "black"), linestyle=CRITERION_STYLE[criterion], marker="o",
                             markersize=3, label=f"{path} ({criterion})")
                axes[0, col].loglog(line["scenes"], line["us_per_scene"], **style)
                axes[1, col].loglog(line["scenes"], line["worst_error"], **style)
            axes[1, col].axhline(float(data["target"].iloc[0]), color="gray", linewidth=0.8, linestyle=":")
            axes[0, col].set(ylabel="median time per scene [µs]", title=comparison)
            axes[1, col].set(xlabel="scenes in the sweep", ylabel="worst error (dotted: target)")
        axes[0, 0].legend(fontsize=7)
        fig.suptitle("Sweep paths where several apply: eq. 4.2 without gravity (builds included)")
        fig.tight_layout(rect=(0, 0.1, 1, 1))
        fig.text(0.01, 0.01, "\n".join(f"{name}: {PATH_NOTES[name]}" for name in PATH_COLORS), fontsize=8,
                 va="bottom")
        save(fig, outputs)


#: Study name -> its chart.
CHARTS = {"work_precision": work_precision_figure, "stability": stability_figure,
          "microslip_resolution": microslip_resolution_figure, "sweep_paths": sweep_paths_figure}


def draw_study(study: str, csv_path: str, outputs) -> None:
    """The chart of numerical study ``study`` (one of :data:`CHARTS`)."""
    if study not in CHARTS:
        raise ValueError(f"no chart for study {study!r}; expected one of {', '.join(CHARTS)}")
    CHARTS[study](csv_path, outputs)
