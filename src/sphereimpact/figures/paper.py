"""The chapter's Figs 4.2-4.8, redrawn from the run files, with the printed values marked.

Each figure function takes the run CSVs it needs (time histories, SI, every separation criterion), the
published values and the criterion the replication table uses, and returns a matplotlib Figure: the
histories under that criterion, the end of contact under each criterion named on the figure.  Plotted in
ms, mm, m/s, rad/s and N.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import pandas as pd

from ..study.replication import load_published
from .captions import criterion_history, contact_ends
from ..contact.separation import Separation
from .catalog import CRITERIA, EQUATIONS, FIGURES
from .style import RC, save

PUBLISHED_STYLE = dict(color="crimson", marker="x", markersize=9, mew=2, linestyle="none")
#: Symbols of the printed values when a figure marks several: each its own, never two alike in one legend.
PUBLISHED_MARKERS = ("x", "D", "s", "^")


#: The chapter figures' size [in]: the axes of the chapter's proportions, the legend beside them (never on a curve).
WIDE = (9.0, 4.2)


def _legend(ax, fig) -> None:
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    fig.tight_layout()


def _published(published: list[dict], case: str) -> dict:
    return {e["quantity"]: e["value"] for e in published if e["case"] == case}


def _mark_times(ax, pub: dict) -> None:
    """Dotted lines at the printed t_m and t_f."""
    for key, style, label in (("t_m", ":", "published $t_m$"), ("t_f", "-.", "published $t_f$")):
        if key in pub:
            ax.axvline(pub[key] * 1e3, color="crimson", linestyle=style, linewidth=1.2, label=label)


def _time_history(run_csv, published, case, separation, title, curves, markers, ylabel):
    """A figure against time [ms].

    ``curves``: (column, scale, style, label), drawn when not identically zero (``style`` None: always drawn).
    ``markers``: (published quantity, quantity giving its time, scale, label) for the printed values.
    """
    runs = pd.read_csv(run_csv)
    h, pub = criterion_history(runs, separation), _published(published, case)
    with plt.rc_context(RC | {"figure.figsize": WIDE}):
        fig, ax = plt.subplots()
        for column, scale, style, label in curves:
            if style is None or h[column].abs().max() > 0:
                ax.plot(h["t"] * 1e3, h[column] * scale, style or "-", label=label)
        _mark_times(ax, pub)
        end = h["t"].iloc[-1] * 1e3  # the history ends where this model's contact does
        ax.axvline(end, color="0.45", linestyle="-", linewidth=0.8,
                   label=f"contact ends: {CRITERIA[separation]}, {end:.3f} ms")
        for other, row in contact_ends(runs).items():
            if other != separation:
                ax.axvline(row["t"] * 1e3, color="0.45", linestyle=":", linewidth=0.8,
                           label=f"{CRITERIA[other]}: {row['t'] * 1e3:.3f} ms")
        for (key, at, scale, label), marker in zip([m for m in markers if m[0] in pub], PUBLISHED_MARKERS):
            style = PUBLISHED_STYLE | ({"marker": marker} if marker == "x" else {"marker": marker, "mfc": "none",
                                                                                   "markersize": 7, "mew": 1.6})
            ax.plot([pub.get(at, h["t"].iloc[-1]) * 1e3], [pub[key] * scale], label=label, **style)
        ax.set(xlabel="time $t$ [ms]", ylabel=ylabel, title=title)
        _legend(ax, fig)
    return fig


def displacement(run_csv: str, published: list[dict], case: str, separation: str, title: str):
    """Figs 4.2 / 4.3: normal and tangential displacement of the centre against time."""
    return _time_history(run_csv, published, case, separation, title,
                         [("u_n", 1e3, None, "normal $u_n$ (modified model)"),
                          ("u_t", 1e3, None, "tangential $u_t$ (modified model)")],
                         [("delta_m", "t_m", 1e3, "published $\\delta_m$ at $t_m$")],
                         "displacement of the centre [mm]")


def velocity(run_csv: str, published: list[dict], case: str, separation: str, title: str):
    """Figs 4.4 / 4.5: normal and tangential velocity of the centre (and contact point) against time."""
    return _time_history(run_csv, published, case, separation, title,
                         [("vc_n", 1.0, None, "centre, normal $v_{C,n}$"),
                          ("vc_t", 1.0, None, "centre, tangential $v_{C,t}$"),
                          ("ve_t", 1.0, "--", "contact point, tangential $v_{E,t}$")],
                         [("ve_n", "t_f", 1.0, "published $v_{E,n}(t_f)$"),
                          ("ve_t", "t_f", 1.0, "published $v_{E,t}(t_f)$")],
                         "velocity [m/s]")


def spin(run_csv: str, published: list[dict], case: str, separation: str, title: str):
    """Fig 4.6: angular velocity against time."""
    return _time_history(run_csv, published, case, separation, title,
                         [("omega", 1.0, None, "angular velocity $\\omega$ (modified model)")],
                         [("omega_f", "t_f", 1.0, "published $\\omega_f$")],
                         "angular velocity [rad/s]")


def force_deflection(previous_csv: str, modified_csv: str, published: list[dict], case: str, separation: str,
                     title: str):
    """Figs 4.7 / 4.8: normal force against deflection, previous model dashed, modified solid, under
    ``separation``; a thin line of the same colour continues a law to δ = 0 (the other criterion) where its
    contact ends elsewhere, with the least force it would reach."""
    pub = _published(published, case)
    with plt.rc_context(RC | {"figure.figsize": WIDE}):
        fig, ax = plt.subplots()
        for path, style, model, colour in ((previous_csv, "--", "kelvin-voigt", "C0"),
                                           (modified_csv, "-", "modified", "C1")):
            runs = pd.read_csv(path)
            h = criterion_history(runs, separation)
            ax.plot(h["delta"] * 1e3, h["force"], style, color=colour,
                    label=f"{EQUATIONS[model]} ({'previous' if model == 'kelvin-voigt' else 'modified'}), "
                          f"{separation} criterion")
            for other, end in contact_ends(runs).items():
                if Separation(other).pulls and end["t"] - h["t"].iloc[-1] > 1e-12:  # held on to delta = 0
                    held = criterion_history(runs, other)
                    ax.plot(held["delta"] * 1e3, held["force"], style, color=colour, linewidth=0.7,
                            label=f"{EQUATIONS[model]} held to δ = 0 ({other} criterion): least P "
                                  f"{held['force'].min():.3g} N")
        ax.axhline(0.0, color="black", linewidth=0.8)
        if "delta_m" in pub:
            ax.axvline(-pub["delta_m"] * 1e3, color="crimson", linestyle=":", linewidth=1.2,
                       label="published $|\\delta_m|$")
        ax.set(xlabel="deflection $\\delta$ [mm]", ylabel="normal contact force $P$ [N]", title=title)
        _legend(ax, fig)
    return fig


#: Drawing function of each figure kind in :data:`sphereimpact.figures.catalog.FIGURES`.
DRAW = {"displacement": displacement, "velocity": velocity, "spin": spin, "force_deflection": force_deflection}


def make_figure(name: str, run_csvs, published_path: str, separation: str, outputs) -> None:
    """Draw chapter figure ``name`` from its run CSVs and save it to every path in ``outputs``."""
    spec = FIGURES[name]
    fig = DRAW[spec.kind](*run_csvs, load_published(published_path), spec.case, separation, spec.title)
    save(fig, outputs)
