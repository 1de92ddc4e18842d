"""The chapter's Figs 4.2-4.8, redrawn from the run files, with the printed values marked.

Each figure function takes the run CSVs it needs (time histories, SI), the
published values and the criterion whose histories to draw, and returns a
matplotlib Figure.  Plotted in ms, mm, m/s, rad/s and N.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import pandas as pd

from ..study.replication import load_published
from .style import RC, save

PUBLISHED_STYLE = dict(color="crimson", marker="x", markersize=9, mew=2, linestyle="none")


def _history(path: str, separation: str) -> pd.DataFrame:
    frame = pd.read_csv(path)
    return frame[frame["separation"] == separation]


def _published(published: list[dict], case: str) -> dict:
    return {e["quantity"]: e["value"] for e in published if e["case"] == case}


def _mark_times(ax, pub: dict) -> None:
    """Dotted lines at the printed t_m and t_f."""
    for key, style, label in (("t_m", ":", "published $t_m$"), ("t_f", "-.", "published $t_f$")):
        if key in pub:
            ax.axvline(pub[key] * 1e3, color="crimson", linestyle=style, linewidth=1.2, label=label)


def displacement(run_csv: str, published: list[dict], case: str, separation: str, title: str):
    """Figs 4.2 / 4.3: normal and tangential displacement of the centre against time."""
    h, pub = _history(run_csv, separation), _published(published, case)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        ax.plot(h["t"] * 1e3, h["u_n"] * 1e3, label="normal $u_n$ (modified model)")
        ax.plot(h["t"] * 1e3, h["u_t"] * 1e3, label="tangential $u_t$ (modified model)")
        _mark_times(ax, pub)
        if "delta_m" in pub and "t_m" in pub:
            ax.plot([pub["t_m"] * 1e3], [pub["delta_m"] * 1e3], label="published $\\delta_m$ at $t_m$",
                    **PUBLISHED_STYLE)
        ax.set(xlabel="time $t$ [ms]", ylabel="displacement of the centre [mm]", title=title)
        ax.legend(loc="best")
    return fig


def velocity(run_csv: str, published: list[dict], case: str, separation: str, title: str):
    """Figs 4.4 / 4.5: normal and tangential velocity of the centre (and contact point) against time."""
    h, pub = _history(run_csv, separation), _published(published, case)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        ax.plot(h["t"] * 1e3, h["vc_n"], label="centre, normal $v_{C,n}$")
        ax.plot(h["t"] * 1e3, h["vc_t"], label="centre, tangential $v_{C,t}$")
        if h["ve_t"].abs().max() > 0:
            ax.plot(h["t"] * 1e3, h["ve_t"], "--", label="contact point, tangential $v_{E,t}$")
        _mark_times(ax, pub)
        end = pub.get("t_f", h["t"].iloc[-1]) * 1e3
        for key, label in (("ve_n", "published $v_{E,n}(t_f)$"), ("ve_t", "published $v_{E,t}(t_f)$")):
            if key in pub:
                ax.plot([end], [pub[key]], label=label, **PUBLISHED_STYLE)
        ax.set(xlabel="time $t$ [ms]", ylabel="velocity [m/s]", title=title)
        ax.legend(loc="best")
    return fig


def spin(run_csv: str, published: list[dict], case: str, separation: str, title: str):
    """Fig 4.6: angular velocity against time."""
    h, pub = _history(run_csv, separation), _published(published, case)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        ax.plot(h["t"] * 1e3, h["omega"], label="angular velocity $\\omega$ (modified model)")
        _mark_times(ax, pub)
        if "omega_f" in pub:
            ax.plot([pub.get("t_f", h["t"].iloc[-1]) * 1e3], [pub["omega_f"]], label="published $\\omega_f$",
                    **PUBLISHED_STYLE)
        ax.set(xlabel="time $t$ [ms]", ylabel="angular velocity [rad/s]", title=title)
        ax.legend(loc="best")
    return fig


def force_deflection(previous_csv: str, modified_csv: str, published: list[dict], case: str, separation: str,
                     title: str):
    """Figs 4.7 / 4.8: normal force against deflection, previous model dashed, modified solid."""
    pub = _published(published, case)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        for path, style, label in ((previous_csv, "--", "previous model, eq. 4.1"),
                                   (modified_csv, "-", "modified model, eq. 4.2")):
            h = _history(path, separation)
            ax.plot(h["delta"] * 1e3, h["force"], style, label=label)
        ax.axhline(0.0, color="black", linewidth=0.8)
        if "delta_m" in pub:
            ax.axvline(-pub["delta_m"] * 1e3, color="crimson", linestyle=":", linewidth=1.2,
                       label="published $|\\delta_m|$")
        ax.set(xlabel="deflection $\\delta$ [mm]", ylabel="normal contact force $P$ [N]", title=title)
        ax.legend(loc="best")
    return fig


#: Figure name -> (function, case, runs it reads by model, title).
FIGURES = {
    "fig4_2": (displacement, "normal", ("modified",), "Fig. 4.2: displacement of the centre, normal impact"),
    "fig4_3": (displacement, "oblique60", ("modified",), "Fig. 4.3: displacement of the centre, 60° impact"),
    "fig4_4": (velocity, "normal", ("modified",), "Fig. 4.4: velocities, normal impact"),
    "fig4_5": (velocity, "oblique60", ("modified",), "Fig. 4.5: velocities, 60° impact"),
    "fig4_6": (spin, "oblique60", ("modified",), "Fig. 4.6: angular velocity, 60° impact"),
    "fig4_7": (force_deflection, "normal", ("kelvin-voigt", "modified"), "Fig. 4.7: normal force, normal impact"),
    "fig4_8": (force_deflection, "oblique60", ("kelvin-voigt", "modified"), "Fig. 4.8: normal force, 60° impact"),
}


def make_figure(name: str, run_csvs, published_path: str, separation: str, outputs) -> None:
    """Draw chapter figure ``name`` from its run CSVs and save it to every path in ``outputs``."""
    function, case, _, title = FIGURES[name]
    fig = function(*run_csvs, load_published(published_path), case, separation, title)
    save(fig, outputs)
