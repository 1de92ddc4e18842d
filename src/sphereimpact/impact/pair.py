"""Two spheres as one: the exact reduction of a sphere-sphere impact to one sphere on a rigid flat, and back.

The ball (m1, R1, alpha1, spin w1) strikes a partner sphere (m2, R2, alpha2, spin w2) at rest.  Along the
line of centres the overlap obeys m* d2(delta)/dt2 = -P with m* = m1 m2 / (m1 + m2), and a Hertz contact of
two spheres has the radius R* = R1 R2 / (R1 + R2).  Along the contact's tangent a force F slows the contact
points' relative slip s = v_t - w1 R1 - w2 R2 at ds/dt = F (1/m* + R1^2/I1 + R2^2/I2): one sphere of mass
m*, radius R* and inertia factor alpha* with 1/(alpha* m*) = 1/(alpha1 m1) + 1/(alpha2 m2), spinning at
w* = (R1 w1 + R2 w2) / R*, slips alike.  So the relative motion of the two is exactly that sphere's on the
flat, for every contact law and tangential model, and each body's velocities and spin follow from the
impulses (J_n, J_t) it exchanged.  Exact, that is, with the line of centres held fixed during the contact: the
centres' relative tangential motion turns it by about max(|v_t|, |v_t'|) t_f / (R1 + R2) radians, which the
reduction neglects (an error of that order in the tangential outputs; Chung & Ooi's reference files give the
angle per row, ``line_turn``).  The planar two-body model (:mod:`.planar_pair`, ``simulate(..., body='planar')``,
the rigid tangential contact and the springs) frees both centres and measures what that costs (the files'
``reduction_gap`` and ``reduction_gap_spring``); the cost falls with the contact time, first order in the turn.
Momentum is conserved to round-off either way.  Spins are in one rotational sense, the ball's (positive: topspin of
the ball), so two spheres turning the same way rub at the contact.
Functions take floats or arrays.
"""

from __future__ import annotations

from .declarations import PARTNER_OUTPUTS, PARTNER_UNITS  # noqa: F401 (re-exported: declared once there)

#: The partner body's Scene fields, in order: mass [kg], diameter [m], inertia factor [-], spin [rad/s].
PARTNER_FIELDS = ("partner_mass", "partner_diameter", "partner_inertia_factor", "partner_spin")


def missing_partner(name: str) -> str:
    """The refusal of a partner sphere given without ``name`` (its mass or its diameter)."""
    return (f"{name} is required with a partner sphere (give both partner_mass [kg] and partner_diameter [m], or "
            "neither for the rigid flat)")


def stray_partner(name: str) -> str:
    """The refusal of the partner's ``name`` (inertia factor or spin) given without a partner sphere."""
    return f"{name} describes a partner sphere: give partner_mass and partner_diameter too"


def partner_gravity(value) -> str:
    """The refusal of gravity ``value`` with a partner sphere."""
    return (f"gravity must be 0 with a partner sphere (two free bodies: gravity does not press the contact); got "
            f"{value!r}")


def reduced_body(mass, radius, inertia_factor, spin, partner_mass, partner_radius, partner_inertia_factor,
                 partner_spin):
    """The one sphere whose impact on a flat is the pair's relative motion: (m* [kg], R* [m], alpha* [-],
    w* [rad/s]).  alpha* lies between the two bodies' factors, so within (0, 2/3] when theirs are."""
    m_star = mass * partner_mass / (mass + partner_mass)
    r_star = radius * partner_radius / (radius + partner_radius)
    alpha_star = 1.0 / (m_star * (1.0 / (inertia_factor * mass) + 1.0 / (partner_inertia_factor * partner_mass)))
    return m_star, r_star, alpha_star, (radius * spin + partner_radius * partner_spin) / r_star


def pair_velocities(relative: dict, mass, radius, inertia_factor, spin, partner_mass, partner_radius,
                    partner_inertia_factor, partner_spin, v_normal, v_tangent) -> dict:
    """Each body's velocities after the impact from the reduced sphere's end (``relative``: its ``vc_t``,
    ``vc_n`` [m/s], the ball's relative velocity, and ``omega_f``, w*): the ball's ``vc_t``, ``vc_n``,
    ``omega_f`` and the partner's :data:`PARTNER_OUTPUTS` (the partner at rest before, the ball approaching at
    ``v_normal`` along -n and ``v_tangent`` along t, both [m/s]).

    The impulses on the ball are J_n = m* (vc_n + v_n) and J_t = m* (vc_t - v_t) [N s]; the partner receives
    their opposite, and each spin changes by -J_t R / I.
    """
    m_star = mass * partner_mass / (mass + partner_mass)
    j_n = m_star * (relative["vc_n"] + v_normal)
    j_t = m_star * (relative["vc_t"] - v_tangent)
    return {"vc_t": v_tangent + j_t / mass, "vc_n": -v_normal + j_n / mass,
            "omega_f": spin - j_t / (inertia_factor * mass * radius),
            "partner_vc_t": 0.0 - j_t / partner_mass, "partner_vc_n": 0.0 - j_n / partner_mass,
            "partner_omega_f": partner_spin - j_t / (partner_inertia_factor * partner_mass * partner_radius)}
