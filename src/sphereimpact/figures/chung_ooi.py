"""One figure per Chung & Ooi benchmark test: the exact reference, the DEM rules beside it, the data where there are."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from .style import RC, save

#: The oblique tests' panels: (column, axis label).
PANELS = (("vc_t", "ball's v_t' [m/s]"), ("omega_f", "ball's ω_f [rad/s]"),
          ("rebound_angle_contact", "contact-point rebound [deg]"))
#: Line styles of the tangential rules: the exact contact solid.
STYLES = {"microslip": "-", "mindlin": "--", "mindlin-displacement": ":", "linear": (0, (5, 1, 1, 1, 1, 1)),
          "rigid": "-."}


def test_figure(number: int, title: str, exact: pd.DataFrame, rules: pd.DataFrame, varied, data=None,
                outputs=(), published=None) -> None:
    """Test ``number``'s figure: the normal tests (1-3) as each computed value against its independent reference
    (Hertz's closed forms, the requested COR; on the diagonal when they agree), the oblique ones as the ball's
    v_t', omega_f and contact-point rebound angle against the varied input (``varied``: column, label), the exact
    contact solid and each DEM rule (``rules``) in its own style, per material; ``data`` (columns ``quantity``,
    ``incidence_deg``, ``value``: Kharaz's e_t and |omega|) as points on the first material's curves; ``published``
    (:func:`~sphereimpact.study.chung_ooi.published_points`) the paper's own curves as open diamonds."""
    with plt.rc_context(RC | {"figure.figsize": (6.4, 7.2 if number >= 4 else 3.6)}):
        if number < 4:
            fig, ax = plt.subplots()
            if number == 3:
                for i, (law, part) in enumerate(exact.groupby("model", sort=False)):
                    ax.plot(part["cor_target"], part["cor"], "os^v"[i % 4], mfc="none", label=law)
                ax.set(xlabel="requested COR [-]", ylabel="computed COR [-]")
            else:
                for i, name in enumerate(("t_f", "delta_m", "force_max")):
                    ax.plot(exact[f"hertz_{name}"] / exact[f"hertz_{name}"], exact[name] / exact[f"hertz_{name}"],
                            "os^"[i], mfc="none", label=f"{name} / Hertz's closed form")
                ax.set(xlabel="closed form (normalised) [-]", ylabel="computed / closed form [-]")
                ax.ticklabel_format(useOffset=False)
            lo, hi = ax.get_xlim()
            ax.plot([lo, hi], [lo, hi], "k-", lw=0.5, label="agreement")
            ax.legend(fontsize=7)
        else:
            fig, axes = plt.subplots(len(PANELS), 1, sharex=True)
            column, label = varied
            for ax, (quantity, ylabel) in zip(axes, PANELS):
                for colour, case in zip(("C0", "C3", "C2"), dict.fromkeys(exact["case"])):
                    for rule, part in pd.concat([exact, rules]).groupby("tangential", sort=False):
                        rows = part[part["case"] == case].sort_values(column)
                        ax.plot(rows[column], rows[quantity], ls=STYLES.get(rule, "-"), color=colour, lw=1.2,
                                label=f"{case}, {rule}" + (" (exact)" if rule == "microslip" else ""))
                ax.set_ylabel(ylabel)
            if data is not None:
                first = exact[exact["case"] == exact["case"].iloc[0]].sort_values(column)
                e_t = data[data["quantity"] == "e_t"]
                v_t = np.interp(e_t["incidence_deg"], first["incidence"],
                                first["speed"] * np.sin(np.radians(first["incidence"])))
                axes[0].plot(e_t["incidence_deg"], e_t["value"] * v_t, "k.", ms=4, label="Kharaz et al. (2001)")
                spin = data[data["quantity"] == "omega_rad_s"]
                axes[1].plot(spin["incidence_deg"], spin["value"], "k.", ms=4)
            if published is not None and len(published):
                panel = {quantity: ax for ax, (quantity, _) in zip(axes, PANELS)}
                named = set()
                for (material, column), part in published.groupby(["material", "column"], sort=False):
                    if column in panel:
                        first = part[part["case"] == part["case"].iloc[0]]  # a curve of every case: once
                        tag = None if material in named else ("the paper's curve" + (f" ({material})" if material else "")
                                                               + ", Kratos' digitisation")
                        named.add(material)
                        panel[column].plot(first["x"], first["y"], "D", mfc="none", ms=4, color="k", label=tag)
            axes[-1].set_xlabel(label)
            legend = {}  # every panel's labelled lines and points, once each
            for ax in axes:
                for handle, text in zip(*ax.get_legend_handles_labels()):
                    legend.setdefault(text, handle)
            fig.legend(list(legend.values()), list(legend), fontsize=6, ncol=2, loc="lower center")
            fig.subplots_adjust(left=0.17, bottom=0.24, hspace=0.3)
        fig.suptitle(f"Chung & Ooi test {number}: {title}", fontsize=9)
        save(fig, outputs)
        plt.close(fig)


def test_figures(folder, data_csv: str, outputs, curves_csv=None) -> None:
    """Every test's figure from the study's tables in ``folder`` (rule ``chung_ooi``): ``outputs`` one path per
    test, ``test<N>.png``; test 4 with the Kharaz data of ``data_csv``; with ``curves_csv``, the paper's own
    curves."""
    from pathlib import Path

    from ..study.chung_ooi import VARIED, load_tests, published_points, read_curves, read_table

    _, tests = load_tests()
    rules = read_table(Path(folder) / "dem_rules.csv")
    data = pd.read_csv(data_csv, comment="#")
    curves = None if curves_csv is None else read_curves(curves_csv)
    for path in outputs:
        number = int(Path(path).stem.removeprefix("test"))
        exact = read_table(Path(folder) / f"test{number}.csv")
        points = None if curves is None or number not in VARIED else published_points(curves, number, exact)
        test_figure(number, tests[number]["title"], exact, rules[rules["test"] == number], VARIED.get(number),
                    data if number == 4 else None, [path], points)
