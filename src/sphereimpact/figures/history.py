"""One impact's time history in one figure: the motion along the normal and the flat, the velocities, the
spin, and the normal force against the compression (read from a history table, SI units)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import pandas as pd

from .catalog import CRITERIA
from .style import RC, save


#: Units of time and length a history is drawn in, from the largest that keeps the numbers at 0.1 or more.
TIME_UNITS = ((1.0, "s"), (1e-3, "ms"), (1e-6, "µs"), (1e-9, "ns"))
LENGTH_UNITS = ((1.0, "m"), (1e-3, "mm"), (1e-6, "µm"), (1e-9, "nm"))


def unit_for(largest: float, units) -> tuple[float, str]:
    """(scale, name) of the unit in ``units`` (size, name; largest first) in which ``largest`` reads 0.1 or more."""
    for size, name in units:
        if largest >= 0.1 * size:
            return size, name
    return units[-1]


def history_figure(history: pd.DataFrame, title: str, separation: str, outputs) -> None:
    """Four panels of :meth:`sphereimpact.Outcome.history`'s table, in the units its contact's time and
    compression read best in (a steel ball's microseconds, a tennis ball's milliseconds), the separation criterion
    that ended the contact (``separation``) named under the title; ``outputs`` the files to write."""
    t_size, t_unit = unit_for(float(history["t"].max()), TIME_UNITS)
    d_size, d_unit = unit_for(float(max(history["delta"].abs().max(), history["u_t"].abs().max())), LENGTH_UNITS)
    t = history["t"] / t_size
    with plt.rc_context(RC | {"figure.figsize": (10.0, 7.0)}):
        fig, ((motion, velocity), (spin, force)) = plt.subplots(2, 2)
        motion.plot(t, history["u_n"] / d_size, label="$u_n$, along the normal (−δ)")
        motion.plot(t, history["u_t"] / d_size, label="$u_t$, along the flat")
        motion.set(xlabel=f"t [{t_unit}]", ylabel=f"centre's displacement [{d_unit}]",
                   title="displacement (contact frame)")
        for key, label, style in (("vc_n", "centre, normal", "-"), ("vc_t", "centre, along the flat", "-"),
                                  ("ve_t", "contact point, along the flat", "--")):
            velocity.plot(t, history[key], style, label=label)
        velocity.set(xlabel=f"t [{t_unit}]", ylabel="velocity [m/s]", title="velocities")
        spin.plot(t, history["omega"])
        spin.set(xlabel=f"t [{t_unit}]", ylabel="ω [rad/s] (+: topspin)", title="spin")
        force.plot(history["delta"] / d_size, history["force"], label="normal P")
        if history["force_t"].abs().max() > 0:
            force.plot(history["delta"] / d_size, history["force_t"], "--", label="tangential F")
        force.axhline(0.0, color="0.5", lw=0.6)
        force.set(xlabel=f"compression δ [{d_unit}]", ylabel="force [N]", title="force against compression")
        for ax in (motion, velocity, force):
            ax.legend(fontsize=7)
        fig.suptitle(f"{title}\ncontact ends when {CRITERIA[separation]}", fontsize=9)
        fig.tight_layout()
        save(fig, outputs)
