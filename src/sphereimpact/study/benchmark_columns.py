"""The columns of Chung & Ooi's reference files and their units: what the references write
(:mod:`.chung_ooi`) and what a DEM code's files are judged by (:mod:`.dem_compare`)."""

#: Columns of a reference file and their units: the inputs, then the outputs.
INPUTS = {"test": "-", "case": "", "model": "", "tangential": "", "speed": "m/s", "incidence": "deg",
          "spin": "rad/s", "mass": "kg", "diameter": "m", "partner_mass": "kg", "partner_diameter": "m",
          "partner_spin": "rad/s", "modulus": "Pa", "kappa": "-", "mu": "-", "cor_target": "-", "dundurs_beta": "-"}
OUTPUTS = {"t_f": "s", "delta_m": "m", "force_max": "N", "vc_t": "m/s", "vc_n": "m/s", "omega_f": "rad/s",
           "ve_t": "m/s", "cor": "-", "e_t": "-", "rebound_angle_contact": "deg", "partner_vc_t": "m/s",
           "partner_vc_n": "m/s", "partner_omega_f": "rad/s"}
#: Hertz's closed forms of the elastic normal tests, beside the computed t_f, delta_m and force_max.
CLOSED_FORMS = {"hertz_t_f": "s", "hertz_delta_m": "m", "hertz_force_max": "N"}
#: What each row says of its own exactness: for two spheres, the angle the line of centres would turn during the
#: contact, max(|v_t|, |v_t'|) t_f / (R1 + R2), which the reduction to one sphere holds fixed (its error is of that
#: order; :mod:`sphereimpact.impact.pair`); empty on a plane.
STATEMENTS = {"line_turn": "rad"}
