"""Incoming spin and the approach described by the ball's path.

References: the rigid contact's closed forms (sliding throughout: the tangential impulse is sigma mu J+; grip:
the angular momentum about the contact point is kept, v_f = (v_t + alpha R omega_0) / (1 + alpha)), the full
planar body (1e-9), the energy balance, and the chapter's description of the same approach.
"""

import math

import numpy as np
import pytest

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.cli import run
from sphereimpact.sweep.engine import grid, sweep

OUTPUTS = ("t_m", "delta_m", "t_f", "vc_t", "vc_n", "ve_t", "ve_n", "omega_f", "cor")
TIGHT = SolverOptions(rtol=1e-12, atol=1e-12)


def test_spin_that_cancels_the_slip_starts_in_grip():
    base = Scene(angle=30.0)
    out = simulate(base.with_(spin=base.v_tangent / base.radius))
    assert out.t_roll == 0.0 and out.regime == "rolling" and out.switches == 0
    assert out.vc_t == pytest.approx(base.v_tangent, rel=1e-14) and out.ve_t == 0.0
    assert out.omega_f == pytest.approx(base.v_tangent / base.radius, rel=1e-14)
    assert out.work_t == pytest.approx(0.0, abs=1e-12 * base.mass * base.speed ** 2)


@pytest.mark.parametrize("spin", [-400.0, -50.0, 150.0, 600.0])
def test_the_rigid_contact_against_its_closed_forms(spin):
    """Sliding throughout the friction impulse is sigma mu J+; a ball that grips leaves rolling with its
    angular momentum about the contact point."""
    scene = Scene(angle=30.0, spin=spin)
    out = simulate(scene, TIGHT)
    alpha, radius = scene.inertia_factor, scene.radius
    impulse = scene.mass * scene.v_normal * (1.0 + out.cor)  # J+: eq. 4.2 does not pull at these speeds
    sigma = math.copysign(1.0, scene.slip0)
    if scene.mu * (1.0 + 1.0 / alpha) * impulse / scene.mass < abs(scene.slip0):
        assert out.regime == "sliding" and out.t_roll is None
        assert out.vc_t == pytest.approx(scene.v_tangent - sigma * scene.mu * impulse / scene.mass, rel=1e-9)
        assert out.omega_f == pytest.approx(spin + sigma * scene.mu * impulse / (alpha * scene.mass * radius),
                                            rel=1e-9)
    else:
        rolling = (scene.v_tangent + alpha * radius * spin) / (1.0 + alpha)
        assert out.regime == "rolling" and out.ve_t == 0.0
        assert out.vc_t == pytest.approx(rolling, rel=1e-9) and out.omega_f == pytest.approx(rolling / radius,
                                                                                            rel=1e-9)
    assert out.work_t <= 1e-12 * scene.mass * scene.speed ** 2  # friction never gives energy


@pytest.mark.parametrize("changes", [dict(angle=30.0, spin=-300.0), dict(angle=30.0, spin=400.0),
                                     dict(angle=0.0, spin=200.0), dict(angle=20.0, spin=250.0, gravity=9.81),
                                     dict(angle_to_surface=20.0, spin=-200.0, gravity=9.81)],
                         ids=["backspin", "topspin-reverses-slip", "normal-with-spin", "slope-gravity", "path-gravity"])
def test_the_planar_body_agrees_with_the_reduced_one(changes):
    scene = Scene(**changes)
    reduced, planar = simulate(scene, TIGHT), simulate(scene, TIGHT, body="planar")
    for key in OUTPUTS:
        assert getattr(planar, key) == pytest.approx(getattr(reduced, key), rel=1e-9, abs=1e-9), key
    assert planar.regime == reduced.regime


@pytest.mark.parametrize("tangential", ["rigid", "linear", "microslip"])
def test_energy_is_never_gained_with_spin(tangential):
    for spin in (-600.0, -100.0, 100.0, 600.0):
        scene = Scene(angle=25.0, spin=spin)
        if tangential == "linear":
            scene = scene.with_(tangential="linear", poisson=0.5)
        elif tangential == "microslip":
            scene = scene.with_(model="hunt-crossley", k=8.8e5, chi=0.05, tangential="microslip", poisson=0.5)
        out = simulate(scene)
        assert out.work_t <= 1e-9 * 0.5 * scene.mass * scene.speed ** 2, (spin, out.work_t)


def test_compliant_models_start_from_the_spun_slip():
    """A spring contact with the slip cancelled by spin sticks from the start; backspin slides it."""
    base = Scene(model="hertz", k=1e9, mu=0.3, tangential="mindlin", kappa=0.8, angle=30.0)
    assert simulate(base.with_(spin=base.v_tangent / base.radius)).motion.tangential.phases[0].mode == "sticking"
    assert simulate(base.with_(spin=-2000.0)).motion.tangential.phases[0].mode == "sliding"


def test_zero_spin_is_bit_identical_to_no_spin():
    for changes in (dict(angle=30.0), dict(angle=60.0, gravity=9.81), dict(angle=20.0, tangential="linear", kappa=1.0)):
        a, b = simulate(Scene(**changes)), simulate(Scene(**changes, spin=0.0))
        assert a.to_dict() | {"wall_time": 0} == b.to_dict() | {"wall_time": 0}


def test_the_path_description_is_the_chapters_approach_on_a_level_flat():
    """Without gravity the flat's tilt does not matter: incidence theta and angle to the surface 90 - theta give
    the chapter's vertical drop on a flat tilted by theta; with gravity they differ by its direction only."""
    chapter = simulate(Scene(angle=35.0))
    for path in (dict(incidence=35.0), dict(angle_to_surface=55.0)):
        out = simulate(Scene(**path))
        assert out.to_dict() | {"wall_time": 0} == chapter.to_dict() | {"wall_time": 0}
    level = Scene(incidence=35.0, gravity=9.81)
    assert level.g_tangent == 0.0 and level.g_normal == 9.81 and level.v_normal == pytest.approx(3.0 * math.cos(
        math.radians(35.0)), rel=1e-15)


@pytest.mark.parametrize("kwargs, message", [
    (dict(angle=10.0, incidence=20.0), "give the flat's tilt (angle, the ball arriving vertically) or the ball's path"),
    (dict(incidence=20.0, angle_to_surface=70.0), "give incidence or angle_to_surface, not both"),
    (dict(incidence=90.0), "incidence must be a finite number in [0, 90)"),
    (dict(angle_to_surface=0.0), "angle_to_surface must be a finite number in (0, 90]"),
    (dict(spin=math.inf), "spin must be a finite number rad/s"),
])
def test_bad_approach_is_refused_naming_it(kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)").replace("[", r"\[")):
        Scene(**kwargs)


def test_with_keeps_one_description():
    path = Scene(incidence=20.0)
    assert path.with_(angle=10.0).incidence is None and path.with_(angle_to_surface=30.0).incidence is None
    assert Scene(angle=10.0).with_(incidence=20.0).angle == 0.0


def test_the_sweep_matches_simulate_with_spin_and_paths(capsys):
    table = sweep(grid(angle_to_surface=[10.0, 45.0, 80.0], spin=[-300.0, 0.0, 300.0]), chapter_ball=True)
    for row in table.to_dict("records"):
        one = simulate(Scene(angle_to_surface=row["angle_to_surface"], spin=row["spin"]))
        for key in OUTPUTS:
            assert row[key] == pytest.approx(getattr(one, key), rel=1e-8, abs=1e-12), key
        assert row["regime"] == one.regime
    compliant = sweep(grid(angle=[20.0], spin=[-300.0, 300.0]).assign(tangential="linear", poisson=0.5), chapter_ball=True)
    for row in compliant.to_dict("records"):
        one = simulate(Scene(angle=20.0, spin=row["spin"], tangential="linear", poisson=0.5))
        assert row["omega_f"] == pytest.approx(one.omega_f, rel=1e-8)
    with pytest.raises(ValueError, match=r"not both.*\(row 0\)"):
        sweep({"angle": [10.0], "incidence": [20.0]}, chapter_ball=True)
    assert run(["simulate", "--angle-to-surface", "16", "--speed", "20", "--spin", "300", "--json"]) == 0
    assert run(["simulate", "--angle", "10", "--incidence", "20"]) == 2
    assert "give the flat's tilt" in capsys.readouterr().err
    assert np.all(np.isnan(table["incidence"]))
