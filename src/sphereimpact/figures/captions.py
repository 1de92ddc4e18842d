"""Every figure's caption, in one place: the index of ``paper_figures/`` (``paper_figures/README.md``, which a
reader browsing the folder sees) and the notebooks read them.  No matplotlib here."""

from __future__ import annotations

#: Figure (file stem in ``paper_figures/``) -> (section, caption).  The chapter's figures first, in its order.
CAPTIONS = {
    "fig4_2": ("The chapter's figures",
               "Fig. 4.2 redrawn: the centre's normal and tangential displacement against time, normal impact at 3 m/s "
               "(modified law, eq. 4.2). Red: the chapter's printed maximum compression and its t_m and t_f; grey: the "
               "end of this model's contact, after which nothing is drawn."),
    "fig4_3": ("The chapter's figures", "Fig. 4.3 redrawn: the same for the 60° impact."),
    "fig4_4": ("The chapter's figures",
               "Fig. 4.4 redrawn: the centre's and the contact point's velocities against time, normal impact; each "
               "printed end velocity marked with its own red symbol."),
    "fig4_5": ("The chapter's figures",
               "Fig. 4.5 redrawn: the velocities of the 60° impact; the printed normal and tangential contact-point "
               "velocities at t_f marked with different red symbols."),
    "fig4_6": ("The chapter's figures", "Fig. 4.6 redrawn: the spin against time, 60° impact, with the printed ω_f."),
    "fig4_7": ("The chapter's figures",
               "Fig. 4.7 redrawn: normal force against deflection, normal impact, eq. 4.1 (dashed) and eq. 4.2 "
               "(solid): eq. 4.1 jumps at first touch and pulls before δ returns to 0, eq. 4.2 does neither."),
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
    "compliance_map": ("Validation",
                       "Where the rigid tangential contact is enough for the chapter's ball: the signed spin difference "
                       "of each compliant contact from the rigid one over angle and κ (left; the tangential spring "
                       "rings, so it changes sign) and its envelope over neighbouring κ against the configured "
                       "tolerance (right)."),
    "work_precision": ("Numerics",
                       "Work-precision: worst relative error against median wall time per impact (top) and against "
                       "right-hand-side evaluations (bottom), one colour per method, solid the reduced body, dashed "
                       "the planar one, dotted the 1e-9 target; one column per scene."),
    "stability": ("Numerics", "Where methods fail, one panel per failure mode: stiffness, the force jump at first "
                              "touch, friction at grip, locating separation, and the modified law past separation; "
                              "the naive formulation beside the package's."),
    "microslip_resolution": ("Numerics",
                             "The microslip contact's error against its cost over its resolution (cells x time "
                             "steps; left) and each scene's error against the time steps at the chosen cell count "
                             "(right): the default is the cheapest setting meeting the target."),
    "sweep_paths": ("Numerics", "The sweep's paths on the scenes several of them solve: time per scene (top) and worst "
                                "error (bottom) against the sweep's size, one colour per path (named under the "
                                "figure), solid the force criterion, dashed the penetration criterion."),
}


def figure_index() -> str:
    """``paper_figures/README.md``: every figure, grouped by section, with its caption."""
    lines = ["# Figures", "",
             "Written by `snakemake --cores 2` (the chapter's Figs 4.2-4.8 are committed; the others are drawn on "
             "every run). Each figure with its caption; the notebooks (`results/notebooks/`) discuss them.", ""]
    section = None
    for name, (where, caption) in CAPTIONS.items():
        if where != section:
            lines += [f"## {where}", ""]
            section = where
        lines += [f"**{name}.png**: {caption}", "", f"![{name}]({name}.png)", ""]
    return "\n".join(lines)


def write_figure_index(path: str) -> None:
    """Write :func:`figure_index` to ``path``."""
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(figure_index())
