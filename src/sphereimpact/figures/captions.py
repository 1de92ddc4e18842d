"""Every figure's caption, in one place: the index of ``paper_figures/`` (``paper_figures/README.md``, which a
reader browsing the folder sees), the report and the notebooks read them; the chapter figures' captions end with
facts read from their run files (:func:`chapter_facts`).  No matplotlib here."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..contact.separation import Separation
from .catalog import CRITERIA, EQUATIONS, FIGURES

#: Figure (file stem in ``paper_figures/``) -> (section, caption).  The chapter's figures first, in its order.
CAPTIONS = {
    "fig4_2": ("The chapter's figures",
               "Fig. 4.2 redrawn: the centre's normal and tangential displacement against time, normal impact "
               "(modified law, eq. 4.2), drawn to the end of contact under the replication table's criterion (grey "
               "line; the dotted grey line is where the other criterion ends it). Red: the chapter's printed maximum "
               "compression and its t_m and t_f."),
    "fig4_3": ("The chapter's figures", "Fig. 4.3 redrawn: the same for the 60° impact."),
    "fig4_4": ("The chapter's figures",
               "Fig. 4.4 redrawn: the centre's and the contact point's velocities against time, normal impact, under "
               "the table's criterion; each printed end velocity marked with its own red symbol."),
    "fig4_5": ("The chapter's figures",
               "Fig. 4.5 redrawn: the velocities of the 60° impact; the printed normal and tangential contact-point "
               "velocities at t_f marked with different red symbols."),
    "fig4_6": ("The chapter's figures", "Fig. 4.6 redrawn: the spin against time, 60° impact, under the table's "
                                        "criterion, with the printed ω_f."),
    "fig4_7": ("The chapter's figures",
               "Fig. 4.7 redrawn: normal force against deflection, normal impact, eq. 4.1 (dashed) and eq. 4.2 "
               "(solid) under the table's criterion; thin lines continue a law to δ = 0 (the other criterion) "
               "where that differs."),
    "fig4_8": ("The chapter's figures", "Fig. 4.8 redrawn: the same for the 60° impact."),
    "spin_map": ("Sweeps",
                 "Spin (top) and contact-point slip (bottom) after impact against the flat's inclination at the chapter's "
                 "speed, rigid contact (line) and a compliant one with rubber's κ (points: its stick-slip switches change "
                 "with the angle, so it is not a smooth curve), with the grip/slide boundary and the chapter's values."),
    "cor_speed": ("Sweeps", "COR against normal approach speed for both laws, with the chapter's printed CORs at their "
                            "normal speeds: constant for eq. 4.1, falling with speed for eq. 4.2."),
    "contact_speed": ("Sweeps",
                      "Contact time and peak force against normal approach speed for both laws. The dotted line marks "
                      "where eq. 4.2's contact starts to end at P = 0 before δ = 0 (its damping would pull): the kink "
                      "in its contact time."),
    "laws_cor_speed": ("Contact laws",
                       "The field's contact laws, each calibrated to the chapter ball's COR and contact time at one "
                       "speed (dotted line; elastic Hertz to the contact time only, COR 1), against impact speed: COR, "
                       "contact time and peak force. Grey: compression beyond the radius, outside the model."),
    "laws_force": ("Contact laws", "Force against deflection over one impact at the calibration speed, each law, under "
                                   "the penetration criterion: loading and unloading loops, jumps at first touch, "
                                   "tension before δ returns to 0."),
    "validation_kharaz": ("Validation",
                          "A 5 mm alumina sphere on glass at 3.9 m/s (Kharaz, Gorham & Salman 2001): tangential COR, "
                          "spin and rebound angle against incidence, measured (points) and each tangential model "
                          "(lines); the title says how many of the five targets each meets. Shaded: incidences "
                          "below the data's reliable range."),
    "validation_maw": ("Validation", "The same data and models in Maw's normalised variables ψ1 (incidence) and ψ2 "
                                     "(the contact point's rebound): the rigid contact is a broken line, negative ψ2 a "
                                     "reversed contact point."),
    "plan_kharaz": ("Validation",
                    "Which bounces to measure for the Kharaz ball (exact microslip; mu and kappa free): each "
                    "parameter's standard error from one bounce alone against incidence (a gap where a bounce does "
                    "not inform it), the D-optimal plan's bounces circled, and the expected errors of the plan, of "
                    "as many bounces evenly spread and of every candidate (sphereimpact plan; results/plan/kharaz/)."),
    "compliance_map": ("Validation",
                       "Where the rigid tangential contact is enough for the chapter's ball: the signed spin difference "
                       "of each compliant contact from the rigid one over angle and κ (left; the tangential spring "
                       "rings, so it changes sign) and its envelope over neighbouring κ against the configured "
                       "tolerance (right)."),
    "work_precision": ("Numerics",
                       "Timings differ from run to run: this copy is from the run whose timings docs/numerics.md "
                       "shows; each run writes its own to results/figures/. Work-precision: worst relative error "
                       "against median wall time per impact (top) and against right-hand-side evaluations (bottom), "
                       "one colour per method, solid the reduced body, dashed the planar one, dotted the 1e-9 "
                       "target; one column per scene. A line ends at its first impact slower than the config's "
                       "numerics.cost_cap."),
    "stability": ("Numerics", "Where methods fail, one panel per failure mode: stiffness, the force jump at first "
                              "touch, friction at grip, locating separation, and the modified law past separation; "
                              "the naive formulation beside the package's."),
    "microslip_resolution": ("Numerics",
                             "Timings: recorded as work_precision's. The microslip contact's error against its "
                             "cost over its resolution (cells x time steps; left) and each scene's error against "
                             "the time steps at the chosen cell count (right): the default is the cheapest setting "
                             "meeting the target."),
    "sweep_paths": ("Numerics", "Timings: recorded as work_precision's. The sweep's paths on the scenes several of "
                                "them solve: time per scene (top) and worst error (bottom) against the sweep's size, "
                                "one colour per path (named under the figure), solid the force criterion, dashed the "
                                "penetration criterion."),
    "dem_departure": ("Benchmarks: Chung & Ooi",
                      "What a DEM code's tangential rule costs: each rule's largest departure from the exact elastic "
                      "microslip contact, relative to the exact quantity's largest magnitude, in the ball's spin "
                      "(left) and the contact point's rebound angle (right), one bar per scene set: Chung & Ooi's "
                      "oblique tests on a plane and the Kharaz ball over the validation's incidences. '+dashpot': "
                      "Kratos' tangential dashpot set from the scenes' normal COR."),
    **{f"chung_ooi_test{n}": ("Benchmarks: Chung & Ooi", text) for n, text in (
        (1, "Test 1, two identical spheres, elastic, normal: contact time, compression and peak force against "
            "Hertz's closed forms (on the diagonal when they agree)."),
        (2, "Test 2, a sphere on a rigid plane, elastic, normal: the same against Hertz's closed forms."),
        (3, "Test 3, a sphere on a rigid plane, normal, damped: the computed COR against the requested one, each law."),
        (4, "Test 4, oblique at constant speed over incidence: the ball's v_t', spin and contact-point rebound angle, "
            "one column per material, the exact contact (black) and each DEM tangential rule; Kharaz's measurements "
            "(dots) and the paper's own curve (diamonds, Kratos' digitisation) where there are."),
        (5, "Test 5, oblique at constant normal speed over the tangential speed: as test 4."),
        (6, "Test 6 (Kratos' Benchmark6), constant normal speed, the spin alone varied: as test 4."),
        (7, "Test 7, two identical spheres with opposite angular velocities: as test 4 (they do not slip)."),
        (8, "Test 8, two spheres of different sizes: as test 4."))},
}


def contact_ends(history: pd.DataFrame) -> dict:
    """Each criterion's end of contact in a run file's histories: criterion -> its last row."""
    return {criterion: part.iloc[-1] for criterion, part in history.groupby("separation", sort=False)}


def _g(value: float, digits: int = 4) -> str:
    text = f"{value:.{digits}g}"
    return text.replace("-", "−")


def chapter_facts(name: str, histories: list, separation: str) -> str:
    """What chapter figure ``name`` shows, read from its run files' histories (``histories``: one frame per law
    of :data:`~sphereimpact.figures.catalog.FIGURES`, every criterion; SI): the end of contact under
    ``separation`` (the table's criterion) and under the other, and the figure's own numbers (the peak compression,
    the end velocities or spin, or the force at first touch, at the end and held to δ = 0)."""
    spec = FIGURES[name]
    if spec.kind == "force_deflection":
        facts = []
        for model, history in zip(spec.models, histories):
            drawn = criterion_history(history, separation)
            scale = max(drawn["force"].abs().max(), 1e-300)
            first, last = drawn["force"].iloc[0], drawn.iloc[-1]
            text = f"{EQUATIONS[model]} starts " + (f"with a jump to {_g(first)} N" if first > 1e-9 * scale
                                                     else "from 0 N")
            text += (f" and ends at P = 0 with δ = {_g(last['delta'] * 1e3)} mm" if last["delta"] > 1e-9 * drawn["delta"].max()
                     else " and ends at δ = 0")
            lowest = drawn["force"].min()
            text += f", its least force {_g(lowest)} N" if lowest < -1e-9 * scale else ", never pulling"
            for other, end in contact_ends(history).items():
                if Separation(other).pulls and end["t"] - last["t"] > 1e-12:  # held on to delta = 0
                    held = criterion_history(history, other)["force"].min()
                    text += (f"; held to δ = 0 ({other} criterion) it would pull to {_g(held)} N"
                             if held < -1e-9 * scale else f"; held to δ = 0 ({other} criterion) it would not pull")
            facts.append(text)
        return f"Under the {separation} criterion (the table's): " + "; ".join(facts) + "."
    history = histories[0]
    drawn, ends = criterion_history(history, separation), contact_ends(history)
    last = drawn.iloc[-1]
    text = (f"Approach {_g(float(np.hypot(drawn['vc_t'].iloc[0], drawn['vc_n'].iloc[0])))} m/s. Drawn under the "
            f"{separation} criterion (the table's): the contact ends at {_g(last['t'] * 1e3)} ms")
    for other, end in ends.items():
        if other != separation:
            text += (f", as under the {other} criterion" if abs(end["t"] - last["t"]) <= 1e-12
                     else f"; under the {other} criterion ({CRITERIA[other].split(' (')[0]}) at {_g(end['t'] * 1e3)} ms")
    if spec.kind == "displacement":
        peak = drawn.loc[drawn["delta"].idxmax()]
        text += f". Largest compression {_g(peak['delta'] * 1e3)} mm at {_g(peak['t'] * 1e3)} ms (nearest sample)"
    elif spec.kind == "velocity":
        text += (f". At the end the contact point moves at v_E,t = {_g(last['ve_t'])} m/s, "
                 f"v_E,n = {_g(last['ve_n'])} m/s")
    else:
        text += f". Spin at the end {_g(last['omega'])} rad/s"
    return text + "."


def criterion_history(history: pd.DataFrame, separation: str) -> pd.DataFrame:
    """The rows of a run file's histories under ``separation``; refused in one line when it has none."""
    drawn = history[history["separation"] == separation]
    if drawn.empty:
        raise ValueError(f"separation {separation!r}: the run file has no history under it; add it to "
                         f"`separations` (one of {sorted(CRITERIA)}) or choose another `primary.separation`")
    return drawn


def figure_index(facts: dict | None = None) -> str:
    """``paper_figures/README.md``: every figure, grouped by section, with its caption; ``facts`` (figure ->
    :func:`chapter_facts`) follow the chapter figures' captions."""
    facts = facts or {}
    lines = ["# Figures", "",
             "Written by `snakemake --cores 2`, each with its caption; the numbers in the chapter figures' captions "
             "are read from their run files. The notebooks (`results/notebooks/`) discuss them.", ""]
    section = None
    for name, (where, caption) in CAPTIONS.items():
        if where != section:
            lines += [f"## {where}", ""]
            section = where
        fact = f" {facts[name]}" if name in facts else ""
        lines += [f"**{name}.png**: {caption}{fact}", "", f"![{name}]({name}.png)", ""]
    return "\n".join(lines)


def write_figure_index(path: str, run_csvs: dict, separation: str) -> None:
    """Write :func:`figure_index` to ``path``, with the chapter figures' facts read from ``run_csvs`` (figure ->
    its run CSVs, in :data:`~sphereimpact.figures.catalog.FIGURES`' order) under ``separation``."""
    from ..files import write_text

    facts = {name: chapter_facts(name, [pd.read_csv(csv) for csv in csvs], separation)
             for name, csvs in run_csvs.items()}
    write_text(path, figure_index(facts))
