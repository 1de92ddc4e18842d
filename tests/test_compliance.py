"""Tangential compliance (linear and Hertz-Mindlin springs capped by Coulomb friction).

References: an independent fixed-step scheme (the way DEM codes update a tangential spring: increment,
rescale on unloading, truncate at mu P) on the same normal motion, Richardson-extrapolated; the rigid
model's closed forms in the limits; the energy balance computed two ways; Maw's start criterion.
"""

import math

import numpy as np
import pytest

from conftest import cli
from sphereimpact import ImpactError, Scene, simulate
from sphereimpact.contact.laws import spring_stiffness
from sphereimpact.sweep import rows, sweep

#: Kharaz, Gorham & Salman (2001): 5 mm alumina on glass (data/kharaz2001.README.md).  E* and G* of the pair
#: from E = 380 / 70 GPa, nu = 0.23 / 0.25; chi gives e_n = 0.98 at 3.9 m/s (calibrated in the pipeline).
ALUMINA = dict(mass=4000.0 * math.pi * 0.005 ** 3 / 6.0, diameter=0.005, speed=3.9, mu=0.092, model="hunt-crossley",
               modulus=62.951576984e9, chi=0.0083527, tangential="mindlin", shear_modulus=13.521110724e9)


def stepped(out, steps: int):
    """v_t and omega at t_f by the fixed-step spring update, driven by the solved normal motion."""
    s, normal = out.scene, out.motion.normal
    t = np.linspace(0.0, out.t_f, steps + 1)
    dt, mid = t[1] - t[0], 0.5 * (t[:-1] + t[1:])
    cap = s.mu * np.maximum(normal.force(mid), 0.0)
    k_mid = s.kappa * spring_stiffness(s.law, normal.state(mid)[0], s)
    k_end = s.kappa * spring_stiffness(s.law, normal.state(t)[0], s)
    v, omega, force = s.v_tangent, 0.0, 0.0
    for i in range(steps):
        if s.tangential == "mindlin" and 0 < k_end[i + 1] < k_end[i]:
            force *= k_end[i + 1] / k_end[i]  # the contact shrinks: the force scales with the stiffness
        force -= k_mid[i] * (v - omega * s.radius) * dt
        force = max(-cap[i], min(cap[i], force))
        v += force / s.mass * dt
        omega -= force * s.radius / s.inertia * dt
    return v, omega


@pytest.mark.parametrize("scene", [
    Scene(angle=20, tangential="linear", poisson=0.5),
    Scene(angle=45, model="kelvin-voigt", tangential="linear", kappa=1.0),
    Scene(angle=10, **ALUMINA), Scene(angle=20, **ALUMINA), Scene(angle=5, **ALUMINA),
], ids=["modified-20", "kv-45", "alumina-10", "alumina-20", "alumina-5"])
def test_event_driven_stick_slip_matches_a_fixed_step_scheme(scene):
    out = simulate(scene)
    coarse, fine = np.array(stepped(out, 4000)), np.array(stepped(out, 8000))
    extrapolated = 2.0 * fine - coarse  # the scheme is first order
    scale = np.array([scene.v_tangent, scene.v_tangent / scene.radius])
    assert np.all(np.abs(extrapolated - [out.vc_t, out.omega_f]) / scale < 2e-5), (extrapolated, out.vc_t,
                                                                                    out.omega_f)
    assert out.switches >= 1


def test_stiff_spring_converges_to_the_rigid_contact():
    rigid = simulate(Scene(angle=20))
    errors = [abs(simulate(Scene(angle=20, tangential="linear", kappa=kappa)).vc_t / rigid.vc_t - 1)
              for kappa in (1e2, 1e3, 1e4)]
    assert errors[0] > errors[1] > errors[2] and errors[2] < 2e-5, errors


def test_normal_impact_has_no_tangential_state():
    rigid = simulate(Scene(angle=0))
    for scene in (Scene(angle=0, tangential="linear", kappa=0.5), Scene(**ALUMINA)):
        out = simulate(scene)
        assert out.regime == "none" and out.switches == 0 and out.vc_t == 0 and out.omega_f == 0
        assert out.work_t == 0.0 and out.motion.tangential is None
    assert simulate(Scene(angle=0, tangential="linear", kappa=0.5)).to_dict().keys() == rigid.to_dict().keys()


def test_gross_slip_throughout_gives_the_rigid_answer_exactly():
    for base in (Scene(angle=60), Scene(angle=60, **{**ALUMINA, "tangential": "rigid", "shear_modulus": None})):
        rigid = simulate(base)
        compliant = simulate(base.with_(tangential="linear", kappa=2 / 3) if base.model == "modified"
                             else base.with_(tangential="mindlin", poisson=0.23))
        assert compliant.switches == 0 and compliant.regime == "sliding" and compliant.t_roll is None
        assert compliant.vc_t == pytest.approx(rigid.vc_t, rel=1e-14)
        assert compliant.omega_f == pytest.approx(rigid.omega_f, rel=1e-14)


@pytest.mark.parametrize("angle", [3, 8, 15, 25, 35])
def test_energy_never_increases_and_the_work_balances(angle):
    for scene in (Scene(angle=angle, tangential="linear", kappa=2 / 3), Scene(angle=angle, **ALUMINA)):
        out = simulate(scene)
        history = out.history(40001)
        power = history["force_t"] * history["ve_t"]  # power of the tangential force on the ball
        assert out.work_t < 0
        assert np.trapezoid(power, history["t"]) == pytest.approx(out.work_t, rel=2e-3)
        # the tangential force never exceeds the cap mu P+
        cap = scene.mu * np.maximum(history["force"], 0.0)
        assert np.all(np.abs(history["force_t"]) <= cap * (1 + 1e-9) + 1e-12 * cap.max())


def test_maw_start_criterion_psi1():
    """psi_1 = kappa tan(theta) / (mu (1 + chi v_n)) decides: sticking below 1, sliding above (Hertz laws)."""
    base = Scene(model="hertz", k=1e9, mu=0.3, tangential="mindlin", kappa=0.8)
    for psi, mode in ((0.95, "sticking"), (1.05, "sliding")):
        angle = math.degrees(math.atan(psi * base.mu / base.kappa))
        assert simulate(base.with_(angle=angle)).motion.tangential.phases[0].mode == mode


def test_contact_point_velocity_reverses_near_grip():
    """The rigid model cannot reverse the contact point's tangential velocity; the compliant one does."""
    rigid = simulate(Scene(angle=20, **{**ALUMINA, "tangential": "rigid", "shear_modulus": None}))
    out = simulate(Scene(angle=20, **ALUMINA))
    assert rigid.ve_t == 0.0 and rigid.rebound_angle_contact == 0.0
    assert out.ve_t < 0 and out.rebound_angle_contact < 0
    assert out.rebound_angle == pytest.approx(math.degrees(math.atan2(out.vc_t, out.vc_n)), rel=1e-15)


def test_kappa_from_poisson_and_shear_modulus():
    assert Scene(angle=10, tangential="linear", poisson=0.5).kappa == pytest.approx(2 / 3, rel=1e-15)
    scene = Scene(angle=10, **ALUMINA)
    e_star = 0.75 * scene.k / math.sqrt(scene.radius)
    assert scene.kappa == pytest.approx(4 * 13.521110724e9 / e_star, rel=1e-12)
    assert scene.kappa == pytest.approx(0.8591436, rel=1e-6)
    assert scene.with_(diameter=0.01).kappa == pytest.approx(scene.kappa, rel=1e-12)  # G*/E*: no size
    assert scene.with_(tangential="rigid").kappa is None


@pytest.mark.parametrize("kwargs, message", [
    (dict(kappa=1.0), "kappa is a parameter of the compliant tangential models"),
    (dict(tangential="linear"), "kappa is required by tangential 'linear'"),
    (dict(tangential="linear", kappa=0.0), "kappa must be a finite number > 0"),
    (dict(tangential="linear", poisson=0.6), "poisson must be a finite number in (-1, 0.5]"),
    (dict(tangential="linear", kappa=1.0, poisson=0.5), "give kappa or poisson, not both"),
    (dict(tangential="mindlin", kappa=1.0), "tangential 'mindlin' (k_t = 8 G* a) needs a Hertz spring"),
    (dict(tangential="linear", model="hertz", k=1e9, kappa=1.0), "tangential 'linear' (k_t = kappa k, constant)"),
    (dict(tangential="linear", shear_modulus=1e9), "shear_modulus sets kappa of tangential 'mindlin'"),
    (dict(tangential="mindlin", model="hunt-crossley", k=1e9, exponent=1.2, kappa=1.0), "exponent 1.2"),
    (dict(tangential="soft"), "tangential must be one of rigid, linear, mindlin"),
])
def test_bad_tangential_input_is_refused_naming_it(kwargs, message):
    with pytest.raises(ValueError) as err:
        Scene(angle=20, **kwargs)
    assert message in str(err.value)


def test_planar_body_refuses_compliance():
    with pytest.raises(ValueError, match="body 'planar' has the rigid tangential contact only"):
        simulate(Scene(angle=20, tangential="linear", kappa=1.0), body="planar")


def test_switch_bound_is_an_error_not_a_hang():
    with pytest.raises(ImpactError, match="stick-slip switches"):
        from sphereimpact.contact.tangential import springs

        original = springs.MAX_PHASES
        springs.MAX_PHASES = -10**6  # a bound below any contact
        try:
            simulate(Scene(angle=20, tangential="linear", kappa=1.0))
        finally:
            springs.MAX_PHASES = original


def test_sweep_solves_compliant_scenes_as_simulate_does():
    table = sweep({"angle": [0.0, 20.0, 60.0], "tangential": "linear", "poisson": 0.5}, chapter_ball=True)
    assert list(table["kappa"]) == pytest.approx([2 / 3] * 3, rel=1e-15)
    for _, row in table.iterrows():
        one = simulate(Scene(angle=row["angle"], tangential="linear", poisson=0.5))
        for key in ("vc_t", "omega_f", "ve_t", "cor"):
            assert row[key] == pytest.approx(getattr(one, key), rel=1e-8, abs=1e-12), key
        assert row["regime"] == one.regime
    with pytest.raises(ValueError, match=r"needs a Hertz spring .* \(row 1\)"):
        sweep(rows(angle=[0.0, 20.0], tangential=["rigid", "mindlin"], kappa=[np.nan, 1.0]), chapter_ball=True)


def test_cli_tangential_flags():
    run = ["simulate", "--angle", "30", "--json"]
    out = cli(*run, "--tangential", "linear", "--poisson", "0.5")
    assert out.returncode == 0, out.stderr
    direct = simulate(Scene(angle=30, tangential="linear", poisson=0.5))
    import json

    data = json.loads(out.stdout)
    assert data["vc_t"] == direct.vc_t and data["switches"] == direct.switches
    bad = cli(*run, "--kappa", "1")
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "kappa is a parameter" in bad.stderr
