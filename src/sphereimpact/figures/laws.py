"""The contact laws compared: COR, contact time and peak force against speed; force against deflection."""

from __future__ import annotations

import matplotlib.pyplot as plt
import pandas as pd

from .style import RC, save

#: One line style per law, in the order the config lists them (the chapter's two first); no plain dotted line,
#: which marks the calibration speed.
_STYLES = ("-", "--", "-.", (0, (5, 1, 1, 1)), (0, (8, 2)), (0, (3, 1, 1, 1, 1, 1)))


def cor_speed(speed_csv: str, fitted_csv: str, outputs) -> None:
    """Three panels against impact speed (log scale): COR, contact time and peak force, one line per law;
    points outside the model (delta_m > R) are drawn thin and grey."""
    table = pd.read_csv(speed_csv)
    fitted = pd.read_csv(fitted_csv)
    with plt.rc_context(RC | {"figure.figsize": (6.4, 8.0)}):
        fig, axes = plt.subplots(3, 1, sharex=True)
        for style, (_, fit) in zip(_STYLES, fitted.iterrows()):
            law = fit["law"]
            rows = table[table["law"] == law].sort_values("speed")
            inside = ~rows["beyond_radius"].to_numpy(bool)
            elastic = "cor" in fit and fit["cor"] >= 1.0
            label = f"{law} (elastic: COR 1, contact time only)" if elastic else law
            for ax, key, scale in zip(axes, ("cor", "t_f", "force_max"), (1.0, 1e3, 1.0)):
                ax.plot(rows["speed"].where(inside), rows[key].where(inside) * scale, linestyle=style, label=label)
                if not inside.all():
                    ax.plot(rows["speed"].where(~inside), rows[key].where(~inside) * scale, color="0.6", lw=0.8)
        speed = float(fitted["speed"].iloc[0])
        for ax in axes:
            ax.axvline(speed, color="0.5", lw=0.8, ls=":", label=f"calibration speed {speed:g} m/s" if ax is axes[0] else None)
        axes[0].set_ylabel("COR [-]")
        axes[1].set_ylabel("contact time $t_f$ [ms]")
        axes[2].set_ylabel("peak force [N]")
        axes[2].set_yscale("log")
        axes[2].set_xscale("log")
        axes[2].set_xlabel("impact speed [m/s]")
        axes[0].legend(loc="lower left", fontsize=7)
        axes[0].set_title("Laws calibrated to one COR and contact time at one speed (elastic Hertz: to the\n"
                          "contact time only); grey: compression beyond the radius, outside the model", fontsize=9)
        fig.tight_layout()
        save(fig, outputs)


def force_deflection(force_csv: str, outputs) -> None:
    """P against delta along one impact per law at the calibration speed (penetration criterion): loading
    and unloading loops, a jump at first touch, and tension (P < 0) before delta returns to 0."""
    table = pd.read_csv(force_csv)
    with plt.rc_context(RC):
        fig, ax = plt.subplots()
        for style, law in zip(_STYLES, dict.fromkeys(table["law"])):
            rows = table[table["law"] == law]
            ax.plot(rows["delta"] * 1e3, rows["force"], linestyle=style, label=law)
        ax.axhline(0.0, color="0.3", lw=0.8)
        ax.set_xlabel("deflection δ [mm]")
        ax.set_ylabel("normal force P [N]")
        ax.set_title("Force against deflection over one impact (penetration criterion)", fontsize=9)
        ax.legend()
        fig.tight_layout()
        save(fig, outputs)
