"""One figure per Chung & Ooi benchmark test: the exact reference, the DEM rules beside it, the data where there are."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from .style import RC, save

#: The oblique tests' panels: (column, axis label).
PANELS = (("vc_t", "ball's v_t' [m/s]"), ("omega_f", "ball's ω_f [rad/s]"),
          ("rebound_angle_contact", "contact-point rebound [deg]"))
#: The panel added where the paper's curve is of beta (tests 6 and 8).
BETA_PANEL = ("beta", "β = −v′_st / v_st [-]")
#: Line styles of the tangential rules: the exact contact solid.
STYLES = {"microslip": "-", "mindlin": "--", "mindlin+dashpot": (0, (1, 1)), "mindlin-displacement": ":",
          "linear": (0, (5, 1, 1, 1, 1, 1)), "linear+dashpot": (0, (3, 1, 1, 1)), "rigid": "-."}
#: Colours of the tangential rules, so that curves lying close apart stay told apart: the exact contact black.
COLOURS = {"microslip": "k", "mindlin": "C0", "mindlin+dashpot": "C4", "mindlin-displacement": "C2", "linear": "C1",
           "linear+dashpot": "C6", "rigid": "C3"}


def test_figure(number: int, title: str, exact: pd.DataFrame, rules: pd.DataFrame, varied, data=None,
                outputs=(), published=None) -> None:
    """Test ``number``'s figure: the normal tests (1-3) as each computed value against its independent reference
    (Hertz's closed forms, the requested COR; on the diagonal when they agree), the oblique ones as the ball's
    v_t', omega_f and contact-point rebound angle against the varied input (``varied``: column, label), one column
    of panels per material (two materials' curves nearly coincide: drawn in one panel, one would hide the other),
    the exact contact solid and each DEM rule (``rules``) in its own style; ``data`` (columns ``quantity``,
    ``incidence_deg``, ``value``: Kharaz's e_t and |omega|) as points in the first material's column;
    ``published`` (:func:`~sphereimpact.study.chung_ooi.published_points`) the paper's own curves as open
    diamonds in their material's column, in a fourth panel of beta where the paper's curve is of it."""
    cases = list(dict.fromkeys(exact["case"]))
    panels = PANELS + ((BETA_PANEL,) if published is not None and (published["column"] == "beta").any() else ())
    size = (3.6 + 3.0 * len(cases), 7.6 + 2.5 * (len(panels) - len(PANELS))) if number >= 4 else (6.4, 4.0)
    with plt.rc_context(RC | {"figure.figsize": size}):
        if number < 4:
            fig, ax = plt.subplots(layout="constrained")
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
            fig, grid = plt.subplots(len(panels), len(cases), sharex=True, squeeze=False, layout="constrained")
            column, label = varied
            both = pd.concat([exact, rules])
            for col, case in enumerate(cases):
                axes = grid[:, col]
                for ax, (quantity, ylabel) in zip(axes, panels):
                    for rule, part in both[both["case"] == case].groupby("rule", sort=False):
                        rows = part.sort_values(column)
                        ax.plot(rows[column], rows[quantity], ls=STYLES.get(rule, "-"), color=COLOURS.get(rule, "C5"),
                                lw=1.2,
                                label=rule + (" (exact)" if rule == "microslip" else ""))
                    if col == 0:
                        ax.set_ylabel(ylabel)
                axes[0].set_title(case, fontsize=9)
                axes[-1].set_xlabel(label)
                if data is not None and col == 0:
                    first = exact[exact["case"] == case].sort_values(column)
                    e_t = data[data["quantity"] == "e_t"]
                    v_t = np.interp(e_t["incidence_deg"], first["incidence"],
                                    first["speed"] * np.sin(np.radians(first["incidence"])))
                    axes[0].plot(e_t["incidence_deg"], e_t["value"] * v_t, "k.", ms=4, label="Kharaz et al. (2001)")
                    spin = data[data["quantity"] == "omega_rad_s"]
                    axes[1].plot(spin["incidence_deg"], spin["value"], "k.", ms=4)
                if published is not None and len(published):
                    panel = {quantity: ax for ax, (quantity, _) in zip(axes, panels)}
                    for quantity, part in published[published["case"] == case].groupby("column", sort=False):
                        if quantity in panel:
                            panel[quantity].plot(part["x"], part["y"], "D", mfc="none", ms=4, color="C5",
                                                 label="the paper's curve, Kratos' digitisation")
            legend = {}  # every panel's labelled lines and points, once each
            for ax in grid.flat:
                for handle, text in zip(*ax.get_legend_handles_labels()):
                    legend.setdefault(text, handle)
            fig.legend(list(legend.values()), list(legend), fontsize=7, ncol=3, loc="outside lower center")
        fig.suptitle(f"Chung & Ooi test {number}: {title}", fontsize=9)
        save(fig, outputs)
        plt.close(fig)


def test_figures(folder, data_csv: str, outputs, curves_csv=None) -> None:
    """Every test's figure from the study's tables in ``folder`` (rule ``chung_ooi``): ``outputs`` one path per
    test, ``chung_ooi_test<N>.png``; test 4 with the Kharaz data of ``data_csv``; with ``curves_csv``, the paper's own
    curves."""
    from pathlib import Path

    from ..study.chung_ooi import VARIED, published_points, read_curves, read_table
    from ..study.chung_ooi_definition import load_tests

    _, tests = load_tests()
    rules = read_table(Path(folder) / "dem_rules.csv")
    data = pd.read_csv(data_csv, comment="#")
    curves = None if curves_csv is None else read_curves(curves_csv)
    for path in outputs:
        number = int(Path(path).stem.removeprefix("chung_ooi_test"))
        exact = read_table(Path(folder) / f"test{number}.csv")
        points = None if curves is None or number not in VARIED else published_points(curves, number, exact)
        test_figure(number, tests[number]["title"], exact, rules[rules["test"] == number], VARIED.get(number),
                    data if number == 4 else None, [path], points)
