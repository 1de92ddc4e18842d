"""One impact's time history in one figure: the motion along the normal and the flat, the velocities, the
spin, and the normal force against the compression (read from a history table, SI units)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import pandas as pd

from .style import RC, save


def history_figure(history: pd.DataFrame, title: str, outputs) -> None:
    """Four panels of :meth:`sphereimpact.Outcome.history`'s table; ``outputs`` the files to write."""
    t = history["t"] * 1e3
    with plt.rc_context(RC | {"figure.figsize": (10.0, 7.0)}):
        fig, ((motion, velocity), (spin, force)) = plt.subplots(2, 2)
        motion.plot(t, history["u_n"] * 1e3, label="u_n, along the normal (-δ)")
        motion.plot(t, history["u_t"] * 1e3, label="u_t, along the flat")
        motion.set(xlabel="t [ms]", ylabel="centre's displacement [mm]", title="displacement (contact frame)")
        for key, label, style in (("vc_n", "centre, normal", "-"), ("vc_t", "centre, along the flat", "-"),
                                  ("ve_t", "contact point, along the flat", "--")):
            velocity.plot(t, history[key], style, label=label)
        velocity.set(xlabel="t [ms]", ylabel="velocity [m/s]", title="velocities")
        spin.plot(t, history["omega"])
        spin.set(xlabel="t [ms]", ylabel="ω [rad/s] (+: topspin)", title="spin")
        force.plot(history["delta"] * 1e3, history["force"], label="normal P")
        if history["force_t"].abs().max() > 0:
            force.plot(history["delta"] * 1e3, history["force_t"], "--", label="tangential F")
        force.axhline(0.0, color="0.5", lw=0.6)
        force.set(xlabel="compression δ [mm]", ylabel="force [N]", title="force against compression")
        for ax in (motion, velocity, force):
            ax.legend(fontsize=7)
        fig.suptitle(title, fontsize=9)
        fig.tight_layout()
        save(fig, outputs)
