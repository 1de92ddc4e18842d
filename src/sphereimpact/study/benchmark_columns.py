"""The columns of Chung & Ooi's reference files and their units: what the references write
(:mod:`.chung_ooi`) and what a DEM code's files are judged by (:mod:`.dem_compare`)."""

#: Columns of a reference file and their units: the inputs, then the outputs.
INPUTS = {"test": "-", "case": "", "model": "", "tangential": "", "rule": "", "dashpot_cor": "-", "speed": "m/s",
          "incidence": "deg", "spin": "rad/s", "mass": "kg", "diameter": "m", "partner_mass": "kg", "partner_diameter": "m",
          "partner_spin": "rad/s", "modulus": "Pa", "kappa": "-", "mu": "-", "cor_target": "-", "dundurs_beta": "-"}
OUTCOME_OUTPUTS = {"t_f": "s", "delta_m": "m", "force_max": "N", "vc_t": "m/s", "vc_n": "m/s", "omega_f": "rad/s",
                   "ve_t": "m/s", "cor": "-", "e_t": "-", "rebound_angle_contact": "deg", "partner_vc_t": "m/s",
                   "partner_vc_n": "m/s", "partner_omega_f": "rad/s"}
#: Columns that name the model that solved a file (its normal law, tangential model, rule and the COR its dashpot is
#: set from), not the test's inputs: a code's file may say its own, never checked against the reference's.
MODEL_COLUMNS = ("model", "tangential", "rule", "dashpot_cor")
#: The approach as the DEM codes set it up (inputs): the normal and tangential approach speeds and the contact
#: point's initial slip v_t - w R (- w2 R2 with a partner) [m/s]; for two spheres set up symmetrically (``lab:
#: symmetric``, tests 1 and 7: each at half the relative speed, as Chung & Ooi's test 1 and Kratos' benchmarks do),
#: each body's normal velocity before in that lab frame (n from the partner towards the ball).
FRAME_INPUTS = {"v_n": "m/s", "v_t": "m/s", "slip": "m/s", "lab_ball_v_n": "m/s", "lab_partner_v_n": "m/s"}
#: The same frame after the impact, and the normalised quantities of Kratos' benchmarks 5, 6 and 8
#: (``DEM_benchmarks_class.py``): on a plane slip_ratio = slip / (mu v_n) and spin_ratio = R omega' / (mu v_n); beta =
#: -ve_t' / slip, the contact point's tangential velocity after over before, negated (for two spheres, their contact
#: points' relative one), against friction_ratio = 3.5 mu (1 + e) v_n / |slip| with e the test's COR (``cor_target``),
#: the abscissa of the paper's tests 6 and 8 as Kratos computes it (3.5 = 1 + 1/alpha of a solid sphere, kept for
#: two spheres: the digitised curves of both tests share one graph); in gross slip beta = friction_ratio - 1 at the
#: COR reached.  Both empty where the slip is 0.
FRAME_OUTPUTS = {"slip_ratio": "-", "spin_ratio": "-", "beta": "-", "friction_ratio": "-", "lab_ball_vc_n": "m/s",
                 "lab_partner_vc_n": "m/s"}
INPUTS |= FRAME_INPUTS
OUTPUTS = OUTCOME_OUTPUTS | FRAME_OUTPUTS
#: Hertz's closed forms of the elastic normal tests, beside the computed t_f, delta_m and force_max.
CLOSED_FORMS = {"hertz_t_f": "s", "hertz_delta_m": "m", "hertz_force_max": "N"}
#: What each row says of its own exactness: for two spheres, the angle the line of centres would turn during the
#: contact, max(|v_t|, |v_t'|) t_f / (R1 + R2), which the reduction to one sphere holds fixed (its error is of that
#: order; :mod:`sphereimpact.impact.pair`), and ``reduction_gap``, what holding it fixed costs, measured: the largest
#: difference of either body's velocities (spins times their radii) between the reduction and the planar two-body
#: model with both centres free (:mod:`sphereimpact.impact.planar_pair`), both with the rigid tangential contact, and
#: ``reduction_gap_spring`` (the reference files) the same with the row's own tangential spring where the two-body
#: model has it (the damped Mindlin variant's), else Mindlin's undamped spring at the row's kappa (the contact nearest
#: the exact microslip one, which it has not); empty on a plane (the spring's also where the row's contact is rigid).
STATEMENTS = {"line_turn": "rad", "reduction_gap": "m/s", "reduction_gap_spring": "m/s"}
