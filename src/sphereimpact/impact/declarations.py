"""Every output of an impact declared once: its name, unit, kind, what it needs and what it is.

The tables the other modules read (the JSON's keys and their order, the units, the numeric outputs a tolerance
applies to, the solver's statistics, the outputs that need the force's history, the partner's, and how each
scales between scenes of one dimensionless problem) are views of :data:`OUTPUTS`; none is written twice.  A
number's scale follows from its unit (:data:`SCALE_OF_UNIT`), so a new dimensional output is scaled by the sweep's
similar-scenes path as soon as it is declared, and a unit without a declared scale fails the completeness test
(``tests/test_user_terms.py``).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..choice import Choice


class Kind(Choice):
    """What an output's value is."""

    NUMBER = "number"  # a float compared to a tolerance
    TEXT = "text"  # a name (the regime)
    FLAG = "flag"  # a bool (outside the model, energy gained)
    SOLVER = "solver"  # the solver's statistics, not the impact's


class Needs(Choice):
    """What an output needs beyond the contact's end state."""

    END = "end"  # the end state alone
    HISTORY = "history"  # the force's history over the contact (its extremes, the instant the contact grips)
    PARTNER = "partner"  # a partner sphere (given only with one)


#: How a number scales between two scenes of one dimensionless problem, by its unit: with the time scale T = 1 / w,
#: the length v_n T, the speed v_n, the spin v_n / R, the force m v_n / T, the energy m v_n^2; None: the same in both
#: (ratios, angles, counts).
SCALE_OF_UNIT = {"s": "time", "m": "length", "m/s": "speed", "rad/s": "spin", "N": "force", "J": "energy",
                 "-": None, "deg": None, "": None}


@dataclass(frozen=True)
class Output:
    """One output of an impact."""

    name: str
    unit: str
    kind: Kind
    doc: str
    needs: Needs = Needs.END

    @property
    def scale(self) -> str | None:
        """How it scales between scenes of one dimensionless problem (:data:`SCALE_OF_UNIT`); None for a number the
        same in both, and for every output that is not a number."""
        return SCALE_OF_UNIT[self.unit] if self.kind is Kind.NUMBER else None


N, T, F, S = Kind.NUMBER, Kind.TEXT, Kind.FLAG, Kind.SOLVER
#: Every output, in the order of the JSON object and of tables.
OUTPUTS = (
    Output("t_m", "s", N, "time of maximum compression"),
    Output("delta_m", "m", N, "maximum compression"),
    Output("t_f", "s", N, "contact time"),
    Output("vc_t", "m/s", N, "centre's velocity along the surface after the impact"),
    Output("vc_n", "m/s", N, "centre's velocity along the normal after the impact"),
    Output("ve_t", "m/s", N, "contact point's velocity along the surface after the impact"),
    Output("ve_n", "m/s", N, "contact point's velocity along the normal after the impact"),
    Output("omega_f", "rad/s", N, "spin after the impact"),
    Output("cor", "-", N, "normal coefficient of restitution"),
    Output("regime", "", T, "the tangential contact's mode at separation (contact.tangential.Regime)"),
    Output("t_roll", "s", N, "first instant the contact point stops slipping", Needs.HISTORY),
    Output("force_min", "N", N, "smallest normal force over the contact", Needs.HISTORY),
    Output("force_max", "N", N, "largest normal force over the contact", Needs.HISTORY),
    Output("beyond_radius", "", F, "the maximum compression exceeds the radius: outside the model"),
    Output("switches", "-", N, "stick-slip switches"),
    Output("rebound_angle", "deg", N, "the centre's rebound direction from the normal"),
    Output("rebound_angle_contact", "deg", N, "the contact point's rebound direction from the normal"),
    Output("rebound_angle_to_surface", "deg", N, "the centre's rebound direction from the surface"),
    Output("work_t", "J", N, "work of the tangential contact force on the ball"),
    Output("energy_gained", "", F, "the tangential model made energy (work_t > 0)"),
    Output("method", "", S, "the integrator"),
    Output("rtol", "-", S, "its relative tolerance"),
    Output("atol", "-", S, "its absolute tolerance"),
    Output("nfev", "-", S, "its right-hand-side evaluations"),
    Output("wall_time", "s", S, "the solve's wall-clock time"),
)
#: The partner sphere's outputs (a scene with one only).
PARTNER = (
    Output("partner_vc_t", "m/s", N, "partner's centre velocity along t after the impact", Needs.PARTNER),
    Output("partner_vc_n", "m/s", N, "partner's centre velocity along n after the impact", Needs.PARTNER),
    Output("partner_omega_f", "rad/s", N, "partner's spin after the impact", Needs.PARTNER),
)
del N, T, F, S

#: The outputs of one impact, in the order of the JSON object and tables.
OUTPUT_KEYS = tuple(o.name for o in OUTPUTS)
#: The solver's statistics among OUTPUT_KEYS; the others are the impact's scalar outputs.
SOLVER_KEYS = tuple(o.name for o in OUTPUTS if o.kind is Kind.SOLVER)
#: The scalar outputs of one impact (OUTPUT_KEYS less the solver's statistics): the columns of a sweep's table too.
SCALAR_OUTPUTS = tuple(o.name for o in OUTPUTS if o.kind is not Kind.SOLVER)
#: The scalar outputs that are numbers (not the regime's name or a flag): what is compared to a tolerance.
NUMERIC_OUTPUTS = tuple(o.name for o in OUTPUTS if o.kind is Kind.NUMBER)
#: Units of the outputs (SI; angles in degrees).
OUTPUT_UNITS = {o.name: o.unit for o in OUTPUTS}
#: The outputs that depend on the force's history, not only on the contact's end.
HISTORY_OUTPUTS = tuple(o.name for o in OUTPUTS if o.needs is Needs.HISTORY)
#: How each dimensional number scales between two scenes of one dimensionless problem.
SCALES = {o.name: o.scale for o in OUTPUTS if o.scale is not None}
#: The partner's outputs and their units.
PARTNER_OUTPUTS = tuple(o.name for o in PARTNER)
PARTNER_UNITS = {o.name: o.unit for o in PARTNER}
