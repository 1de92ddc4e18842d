"""Sphere-sphere impacts: the reduction to one sphere on the flat checked against conservation laws, Hertz's
closed forms for two spheres, the flat as a huge partner, and the exchange of velocities; through the API,
the sweep and the command line."""

import json
import math

import numpy as np
import pandas as pd
import pytest

from sphereimpact import Scene, simulate
from sphereimpact.cli import run
from sphereimpact.contact.materials import effective_moduli
from sphereimpact.impact.solve import simulate_many
from sphereimpact.sweep import sweep

#: Pairs of every kind of contact: (fields of the contact, of the approach and bodies).
CONTACTS = {
    "modified-rigid": dict(model="modified"),
    "hertz-mindlin": dict(model="hertz", modulus=2e7, tangential="mindlin", kappa=0.8),
    "hunt-crossley-microslip": dict(model="hunt-crossley", modulus=2e7, chi=0.05, tangential="microslip", kappa=0.8),
    "kelvin-voigt-linear": dict(model="kelvin-voigt", tangential="linear", kappa=0.7),
}
BODIES = dict(angle=35.0, speed=2.5, spin=-20.0, mass=0.145, diameter=0.063, partner_mass=0.4,
              partner_diameter=0.09, partner_inertia_factor=0.3, partner_spin=12.0, mu=0.3)


def _momenta(scene: Scene, vc_t, vc_n, omega, partner_vc_t, partner_vc_n, partner_omega):
    """Linear momentum along t and n [N s], and angular momentum about the first contact point [kg m^2/s] (each
    body's lever arm its radius, as the model's rigid-body rotation has it), of the pair."""
    r1, r2 = scene.radius, 0.5 * scene.partner_diameter
    i1 = scene.inertia_factor * scene.mass * r1 ** 2
    i2 = scene.partner_inertia_factor * scene.partner_mass * r2 ** 2
    p_t = scene.mass * vc_t + scene.partner_mass * partner_vc_t
    p_n = scene.mass * vc_n + scene.partner_mass * partner_vc_n
    angular = i1 * omega + scene.mass * r1 * vc_t + i2 * partner_omega - scene.partner_mass * r2 * partner_vc_t
    return np.array([p_t, p_n, angular])


@pytest.mark.parametrize("name", CONTACTS)
def test_momentum_conserved_and_energy_not_gained(name):
    scene = Scene(**BODIES, **CONTACTS[name])
    out = simulate(scene)
    before = _momenta(scene, scene.v_tangent, -scene.v_normal, scene.spin, 0.0, 0.0, scene.partner_spin)
    after = _momenta(scene, out.vc_t, out.vc_n, out.omega_f, out.partner_vc_t, out.partner_vc_n, out.partner_omega_f)
    scale = scene.mass * scene.speed * np.array([1.0, 1.0, scene.radius])  # [N s], [N s], [N s m]
    assert np.abs(after - before) / scale == pytest.approx(np.zeros(3), abs=1e-14)  # round-off
    r1, r2 = scene.radius, 0.5 * scene.partner_diameter
    energy = lambda v_t, v_n, w, pv_t, pv_n, pw: (  # noqa: E731
        0.5 * scene.mass * (v_t ** 2 + v_n ** 2) + 0.5 * scene.inertia_factor * scene.mass * r1 ** 2 * w ** 2
        + 0.5 * scene.partner_mass * (pv_t ** 2 + pv_n ** 2)
        + 0.5 * scene.partner_inertia_factor * scene.partner_mass * r2 ** 2 * pw ** 2)
    e0 = energy(scene.v_tangent, -scene.v_normal, scene.spin, 0.0, 0.0, scene.partner_spin)
    e1 = energy(out.vc_t, out.vc_n, out.omega_f, out.partner_vc_t, out.partner_vc_n, out.partner_omega_f)
    assert e1 <= e0 * (1 + 1e-12)
    assert not out.energy_gained


@pytest.mark.parametrize("name", CONTACTS)
def test_relative_motion_is_the_reduced_spheres(name):
    """The two bodies' velocities, taken relative to each other, are the reduced sphere's on the flat."""
    scene = Scene(**BODIES, **CONTACTS[name])
    pair, alone = simulate(scene), simulate(scene.reduced)
    r1, r2 = scene.radius, 0.5 * scene.partner_diameter
    assert pair.vc_n - pair.partner_vc_n == pytest.approx(alone.vc_n, rel=1e-13)
    assert pair.vc_t - pair.partner_vc_t == pytest.approx(alone.vc_t, rel=1e-13, abs=1e-15)
    slip = (pair.vc_t - pair.omega_f * r1) - (pair.partner_vc_t + pair.partner_omega_f * r2)
    assert slip == pytest.approx(alone.ve_t, rel=1e-11, abs=1e-13)
    assert (pair.cor, pair.ve_t, pair.t_f) == (alone.cor, alone.ve_t, alone.t_f)
    # the reduced body: m*, R*, alpha* with 1/(alpha* m*) = sum 1/(alpha_i m_i)
    reduced = scene.reduced
    assert reduced.mass == pytest.approx(0.145 * 0.4 / 0.545, rel=1e-15)
    assert reduced.radius == pytest.approx(0.0315 * 0.045 / 0.0765, rel=1e-15)
    assert 1 / (reduced.inertia_factor * reduced.mass) == pytest.approx(1 / (0.4 * 0.145) + 1 / (0.3 * 0.4), rel=1e-14)


def test_hertz_closed_forms_of_two_spheres():
    """Two elastic spheres of different materials, head on: Hertz's maximum overlap, peak force and contact time
    (Johnson, Contact Mechanics, 1985, sec. 11.4) with m*, R* and E* of the pair."""
    e_star, _ = effective_moduli(70e9, 0.30, 40e9, 0.35)
    m1, m2, r1, r2, v = 2699 * 4 / 3 * math.pi * 0.1 ** 3, 1800 * 4 / 3 * math.pi * 0.05 ** 3, 0.1, 0.05, 0.2
    scene = Scene(model="hertz", modulus=e_star, mass=m1, diameter=2 * r1, partner_mass=m2, partner_diameter=2 * r2,
                  speed=v, mu=0.0)
    out = simulate(scene)
    m_star, r_star = m1 * m2 / (m1 + m2), r1 * r2 / (r1 + r2)
    delta_m = (15 * m_star * v ** 2 / (16 * e_star * math.sqrt(r_star))) ** 0.4
    assert out.delta_m == pytest.approx(delta_m, rel=1e-9)
    assert out.force_max == pytest.approx(4 / 3 * e_star * math.sqrt(r_star) * delta_m ** 1.5, rel=1e-9)
    assert out.t_f == pytest.approx(2.868265699 * (m_star ** 2 / (r_star * e_star ** 2 * v)) ** 0.2, rel=1e-8)
    assert out.cor == pytest.approx(1.0, abs=1e-9)
    # momentum of an elastic head-on impact: v1' = (m1 - m2) v / (m1 + m2), v2' = 2 m1 v / (m1 + m2), along -n
    assert out.vc_n == pytest.approx(-(m1 - m2) * v / (m1 + m2), rel=1e-9)
    assert out.partner_vc_n == pytest.approx(-2 * m1 * v / (m1 + m2), rel=1e-9)


def test_identical_elastic_spheres_exchange_velocities():
    scene = Scene(model="hertz", modulus=1e8, speed=3.0, partner_mass=0.145, partner_diameter=0.063)
    out = simulate(scene)
    assert out.vc_n == pytest.approx(0.0, abs=3e-9 * 3.0)
    assert out.partner_vc_n == pytest.approx(-3.0, rel=3e-9)
    assert (out.vc_t, out.omega_f, out.partner_vc_t, out.partner_omega_f) == (0.0, 0.0, 0.0, 0.0)


@pytest.mark.parametrize("name", CONTACTS)
def test_a_huge_partner_is_the_flat(name):
    flat = {key: value for key, value in BODIES.items() if not key.startswith("partner")}
    huge = simulate(Scene(**flat, **CONTACTS[name], partner_mass=1e12, partner_diameter=1e6, partner_spin=0.0))
    alone = simulate(Scene(**flat, **CONTACTS[name]))
    for key in ("t_f", "delta_m", "vc_t", "vc_n", "omega_f", "cor", "ve_t"):
        assert getattr(huge, key) == pytest.approx(getattr(alone, key), rel=1e-6, abs=1e-9), key
    assert abs(huge.partner_vc_n) < 1e-11 and abs(huge.partner_omega_f) < 1e-11


def test_scene_refuses_an_incomplete_or_pulled_partner():
    with pytest.raises(ValueError, match="partner_diameter is required"):
        Scene(partner_mass=0.1)
    with pytest.raises(ValueError, match="partner_spin describes a partner sphere"):
        Scene(partner_spin=3.0)
    with pytest.raises(ValueError, match="gravity must be 0 with a partner"):
        Scene(partner_mass=0.1, partner_diameter=0.05, gravity=9.81)
    with pytest.raises(ValueError, match=r"partner_mass must be a finite number > 0 kg; got -1"):
        Scene(partner_mass=-1, partner_diameter=0.05)
    with pytest.raises(ValueError, match=r"partner_inertia_factor must be a finite number in \(0, 2/3\]"):
        Scene(partner_mass=1, partner_diameter=0.05, partner_inertia_factor=0.9)
    scene = Scene(partner_mass=0.1, partner_diameter=0.05)
    assert Scene(**scene.as_dict()) == scene and "partner_mass" not in Scene().as_dict()


def test_sweep_and_simulate_many_give_simulate_on_a_mixed_table():
    """Random rows, some on the flat and some on partners, of several laws and tangential models: the sweep and the
    batched simulate equal simulate row by row (the sweep within its target)."""
    rng = np.random.default_rng(34)
    n = 24
    names = list(CONTACTS)
    contact = [CONTACTS[names[i % len(names)]] for i in range(n)]
    has = rng.random(n) < 0.7
    table = pd.DataFrame({
        "angle": rng.uniform(0, 80, n).round(3), "speed": rng.uniform(0.5, 5, n).round(3),
        "spin": np.where(rng.random(n) < 0.5, 0.0, rng.uniform(-40, 40, n)).round(3), "mu": 0.25,
        "partner_mass": np.where(has, rng.uniform(0.05, 2, n), np.nan),
        "partner_diameter": np.where(has, rng.uniform(0.02, 0.2, n), np.nan),
        "partner_spin": np.where(has, rng.uniform(-30, 30, n), np.nan),
        "model": [c["model"] for c in contact], "modulus": [c.get("modulus", np.nan) for c in contact],
        "chi": [c.get("chi", np.nan) for c in contact], "tangential": [c.get("tangential", "rigid") for c in contact],
        "kappa": [c.get("kappa", np.nan) for c in contact]})
    swept = sweep(table, target=1e-8, chapter_ball=True)
    scenes = [Scene(**{k: v for k, v in row.items() if not (isinstance(v, float) and math.isnan(v))})
              for row in table.to_dict("records")]
    batched = simulate_many(scenes)
    for i, scene in enumerate(scenes):
        one = simulate(scene).to_dict()
        for key in ("vc_t", "vc_n", "omega_f", "cor", "t_f", "partner_vc_t", "partner_vc_n", "partner_omega_f"):
            expected = one.get(key) if scene.has_partner else one.get(key, 0.0)
            scale = scene.speed / scene.radius if "omega" in key else scene.speed
            assert swept[key].iloc[i] == pytest.approx(expected, rel=1e-7, abs=1e-8 * scale), (i, key)
            assert batched[i].to_dict().get(key, 0.0) == pytest.approx(expected if expected is not None else 0.0,
                                                                       rel=1e-9, abs=1e-10 * scale), (i, key)
    assert swept["mass"].tolist() == [0.145] * n and swept["partner_mass"].isna().tolist() == (~has).tolist()


def test_sweep_refuses_a_partner_row_with_gravity():
    with pytest.raises(ValueError, match=r"gravity must be 0 with a partner sphere.*\(row 1\)"):
        sweep(pd.DataFrame({"partner_mass": [np.nan, 0.2], "partner_diameter": [np.nan, 0.05], "gravity": [9.8, 9.8]}),
              chapter_ball=True)
    with pytest.raises(ValueError, match=r"mass must be a finite number > 0 kg; got -1.0 \(row 1\)"):
        sweep(pd.DataFrame({"mass": [0.1, -1.0], "partner_mass": [0.2, 0.2], "partner_diameter": [0.05, 0.05]}),
              chapter_ball=True)
    with pytest.raises(ValueError, match=r"partner_diameter is required with a partner sphere.*\(row 0\)"):
        sweep(pd.DataFrame({"partner_mass": [0.2]}), chapter_ball=True)


def test_command_line_simulates_and_sweeps_a_pair(tmp_path, capsys):
    argv = ["--angle", "30", "--spin", "5", "--partner-mass", "0.3", "--partner-diameter", "0.1",
            "--partner-spin", "-2", "--model", "hertz", "--modulus", "2e7", "--tangential", "mindlin", "--kappa", "0.8"]
    assert run(["simulate", *argv, "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    expected = simulate(Scene(angle=30, spin=5, partner_mass=0.3, partner_diameter=0.1, partner_spin=-2,
                              model="hertz", modulus=2e7, tangential="mindlin", kappa=0.8)).to_dict()
    for key in ("vc_t", "vc_n", "omega_f", "partner_vc_t", "partner_vc_n", "partner_omega_f", "cor"):
        assert printed[key] == pytest.approx(expected[key], rel=1e-14), key
    out = tmp_path / "pairs.csv"
    assert run(["sweep", "--chapter-ball", *argv, "--angle", "10:30:20", "--out", str(out)]) == 0
    table = pd.read_csv(out)
    assert table["angle"].tolist() == [10.0, 30.0]
    assert table["partner_omega_f"].iloc[1] == pytest.approx(expected["partner_omega_f"], rel=1e-7)
    assert run(["simulate", "--partner-mass", "0.3"]) == 2
    assert "partner_diameter is required" in capsys.readouterr().err


def test_own_study_surface_takes_a_partner():
    from pathlib import Path

    import yaml

    from sphereimpact.study.config import with_defaults
    from sphereimpact.study.own import study_ball

    schema = yaml.safe_load((Path(__file__).parents[1] / "config/schema.yaml").read_text())
    config = with_defaults(schema, {"study": "pairs", "ball": {"mass": 0.145, "diameter": 0.063},
                                    "surface": {"mu": 0.2, "gravity": 0.0,
                                                      "partner": {"mass": 0.2, "diameter": 0.05, "spin": 3.0}},
                        "contact": {"model": "hertz", "modulus": 1e8}})
    scene = study_ball(config).scene
    assert (scene.partner_mass, scene.partner_diameter, scene.partner_inertia_factor, scene.partner_spin) == \
        (0.2, 0.05, 0.4, 3.0)


def test_fit_recovers_friction_from_bounces_on_a_partner(tmp_path, capsys):
    """The fit's doors with a partner: bounces of a ball on a partner sphere that slide throughout, made by simulate
    with mu = 0.1, give mu back through the API and the command line."""
    from sphereimpact.fit import fit, read_measured
    from sphereimpact.impact.ball import Ball

    pair = dict(partner_mass=0.3, partner_diameter=0.1, partner_spin=5.0)
    rows = []
    for incidence in (50.0, 60.0, 70.0):
        out = simulate(Scene(incidence=incidence, mu=0.1, **pair))
        assert out.regime == "sliding"
        rows.append({"speed": 3.0, "incidence": incidence, "vc_t": out.vc_t, "omega_f": out.omega_f})
    path = tmp_path / "bounces.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    result = fit(read_measured(path), Ball(Scene(mu=0.3, **pair)), ["mu"], chapter_ball=True)
    assert result.parameters["mu"].value == pytest.approx(0.1, rel=1e-7)
    assert run(["fit", str(path), "--free", "mu", "--mu", "0.3", "--partner-mass", "0.3", "--partner-diameter", "0.1",
                "--partner-spin", "5", "--mass", "0.145", "--diameter", "0.063", "--k", "60000", "--b", "10.5",
                "--speed", "3", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["parameters"]["mu"]["value"] == pytest.approx(0.1, rel=1e-7)


#: Soft spheres (E* 2 GPa) at 40 degrees: the line of centres turns by a few hundredths of a radian in the contact.
SOFT = dict(model="hertz", modulus=2e9, mass=0.1, diameter=0.05, partner_mass=0.3, partner_diameter=0.08,
            incidence=40.0, speed=5.0, mu=0.2, spin=50.0, partner_spin=-20.0)


def test_two_body_planar_model_conserves_momentum_and_angular_momentum():
    """The planar two-body model (both centres free, the normal turning with the line of centres, issue 41 item 7):
    linear momentum exactly (one force on each body), and angular momentum about a fixed point, m* d x v - I1 w1 -
    I2 w2 (spins in the ball's sense, clockwise), which changes by int delta F dt (the lever arms R1, R2 put the two
    contact points delta apart) and by nothing else only if every lever arm and sign is right.  The tangential
    force's work is its power F s integrated: the energy balance with the normal force's work closes."""
    scene = Scene(**SOFT)
    out = simulate(scene, body="planar")
    m1, m2 = scene.mass, scene.partner_mass
    assert m1 * out.vc_t + m2 * out.partner_vc_t == pytest.approx(m1 * scene.v_tangent, abs=1e-15)
    assert m1 * out.vc_n + m2 * out.partner_vc_n == pytest.approx(-m1 * scene.v_normal, abs=1e-15)
    r1, r2 = scene.radius, 0.5 * scene.partner_diameter
    i1, i2 = 0.4 * m1 * r1 ** 2, 0.4 * m2 * r2 ** 2
    motion, m_star = out.motion, m1 * m2 / (m1 + m2)

    def angular(d, v, w1, w2):
        return m_star * (d[0] * v[1] - d[1] * v[0]) - i1 * w1 - i2 * w2

    before = angular((0.0, r1 + r2), (scene.v_tangent, -scene.v_normal), scene.spin, scene.partner_spin)
    z = motion._state(out.t_f)[:, 0]
    after = angular(z[0:2], z[2:4], out.omega_f, out.partner_omega_f)
    times = np.linspace(0.0, out.t_f, 20001)
    leak = np.trapezoid(motion.kinematics(times)["delta"] * motion.tangential_force(times), times)
    assert abs(leak) > 1e-4 * abs(before)  # the lever arms' share is measurable here
    assert abs(after - before - leak) < 1e-7 * abs(before)  # the quadrature's and the tolerance's error
    assert motion.line_turn > 1e-3  # it did turn
    assert out.work_t < 0 and not out.energy_gained


def test_the_reduction_differs_from_the_two_body_model_to_first_order_in_the_turn():
    """The reduction holds the line of centres fixed: its error falls with the contact time, as t_c ~ E*^(-2/5)
    (100 x stiffer: 100^(2/5) = 6.3 x smaller), and vanishes for a normal impact; frictionless and elastic, the
    two-body model keeps the kinetic energy."""
    gaps = []
    for modulus in (2e9, 2e11):
        scene = Scene(**SOFT | {"modulus": modulus})
        planar, reduced = simulate(scene, body="planar"), simulate(scene)
        gaps.append(abs(planar.vc_t - reduced.vc_t))
    assert gaps[0] / gaps[1] == pytest.approx(100 ** 0.4, rel=0.1) and gaps[0] > 1e-3
    normal = Scene(**SOFT | {"incidence": 0.0, "spin": 0.0, "partner_spin": 0.0})
    assert simulate(normal, body="planar").vc_n == pytest.approx(simulate(normal).vc_n, rel=1e-8)
    smooth = Scene(**SOFT | {"mu": 0.0})
    out = simulate(smooth, body="planar")
    m1, m2 = smooth.mass, smooth.partner_mass
    energy = m1 * (out.vc_t ** 2 + out.vc_n ** 2) + m2 * (out.partner_vc_t ** 2 + out.partner_vc_n ** 2)
    assert energy == pytest.approx(m1 * smooth.speed ** 2, rel=1e-8) and out.work_t == 0.0
    assert out.omega_f == smooth.spin and out.partner_omega_f == smooth.partner_spin


def test_two_body_model_through_the_command_line_and_its_refusals(capsys):
    argv = ["simulate", "--json", "--model", "hertz", "--modulus", "2e9", "--mass", "0.1", "--diameter", "0.05",
            "--partner-mass", "0.3", "--partner-diameter", "0.08", "--incidence", "40", "--speed", "5", "--mu", "0.2",
            "--spin", "50", "--partner-spin", "-20", "--body", "planar"]
    assert run(argv) == 0
    said = json.loads(capsys.readouterr().out)
    api = simulate(Scene(**SOFT), body="planar")
    assert said["partner_vc_t"] == pytest.approx(api.partner_vc_t, rel=1e-12)
    assert said["omega_f"] == pytest.approx(api.omega_f, rel=1e-12)
    spring = argv + ["--tangential", "mindlin", "--kappa", "0.7"]
    assert run(spring) == 0
    said = json.loads(capsys.readouterr().out)
    api = simulate(Scene(**SOFT | {"tangential": "mindlin", "kappa": 0.7}), body="planar")
    assert said["partner_vc_t"] == pytest.approx(api.partner_vc_t, rel=1e-12) and said["regime"] == api.regime
    with pytest.raises(ValueError, match="body 'planar' has the rigid, linear, mindlin, mindlin-displacement tangential "
                                         "contacts for two spheres; tangential 'microslip' is solved by body 'reduced'"):
        simulate(Scene(**SOFT | {"tangential": "microslip", "kappa": 0.7}), body="planar")
    assert run(spring + ["--dashpot-cor", "0.5"]) == 0
    said = json.loads(capsys.readouterr().out)
    api = simulate(Scene(**SOFT | {"tangential": "mindlin", "kappa": 0.7, "dashpot_cor": 0.5}), body="planar")
    assert said["omega_f"] == pytest.approx(api.omega_f, rel=1e-12)


#: The two-body model's tangential springs, each on a law it serves: (fields, the stiffness varied, soft, stiff).
SPRINGS = {
    "mindlin": (dict(model="hertz", tangential="mindlin", kappa=0.8), "modulus", 2e9, 2e11),
    "mindlin-displacement": (dict(model="hertz", tangential="mindlin-displacement", kappa=0.8), "modulus", 2e9, 2e11),
    "linear": (dict(model="kelvin-voigt", b=0.0, tangential="linear", kappa=0.7), "k", 2e5, 2e7),
    "mindlin, dashpot": (dict(model="hertz", tangential="mindlin", kappa=0.8, dashpot_cor=0.5), "modulus", 2e9, 2e11),
    "linear, dashpot": (dict(model="kelvin-voigt", b=0.0, tangential="linear", kappa=0.7, dashpot_cor=0.5), "k", 2e5,
                        2e7),
}


@pytest.mark.parametrize("spring", sorted(SPRINGS))
def test_two_body_spring_model_keeps_the_balances_and_converges_to_the_reduction(spring):
    """The two-body model with a tangential spring, with and without the DEM codes' dashpot (issue 41 item 7), against
    what does not depend on its code: linear momentum exactly; an elastic normal law gives back its work, so the
    kinetic energy of both bodies (centres and spins) changes by the tangential force's work F s integrated alone; the
    reduction's error falls at first order in the line's turn (as the contact time: t_f's ratio), and the stick-slip
    phases are the reduced model's."""
    fields, stiffness, soft, stiff = SPRINGS[spring]
    gaps, times = [], []
    for value in (soft, stiff):
        scene = Scene(**SOFT | {"modulus": None, "chi": None} | fields | {stiffness: value})
        planar, reduced = simulate(scene, body="planar"), simulate(scene)
        assert planar.switches == reduced.switches >= 1 and planar.regime == reduced.regime
        m1, m2 = scene.mass, scene.partner_mass
        assert m1 * planar.vc_t + m2 * planar.partner_vc_t == pytest.approx(m1 * scene.v_tangent, abs=1e-15)
        assert m1 * planar.vc_n + m2 * planar.partner_vc_n == pytest.approx(-m1 * scene.v_normal, abs=1e-15)
        i1 = scene.inertia_factor * m1 * scene.radius ** 2
        i2 = scene.partner_inertia_factor * m2 * (0.5 * scene.partner_diameter) ** 2

        def energy(v1, v2, w1, w2):
            return 0.5 * (m1 * (v1[0] ** 2 + v1[1] ** 2) + m2 * (v2[0] ** 2 + v2[1] ** 2) + i1 * w1 ** 2 + i2 * w2 ** 2)

        before = energy((scene.v_tangent, -scene.v_normal), (0.0, 0.0), scene.spin, scene.partner_spin)
        after = energy((planar.vc_t, planar.vc_n), (planar.partner_vc_t, planar.partner_vc_n), planar.omega_f,
                       planar.partner_omega_f)
        assert planar.work_t < -1e-3 * before
        assert after - before == pytest.approx(planar.work_t, abs=1e-7 * before)
        gaps.append(max(abs(planar.vc_t - reduced.vc_t), abs(planar.vc_n - reduced.vc_n),
                        abs(planar.omega_f - reduced.omega_f) * scene.radius))
        times.append(reduced.t_f)
    assert gaps[0] / gaps[1] == pytest.approx(times[0] / times[1], rel=0.1) and gaps[0] > 1e-3 * SOFT["speed"]


def test_two_body_model_of_a_frictionless_or_normal_impact_never_switches():
    """Before: a frictionless normal impact (Chung & Ooi's test 1) switched between rolling and sliding without end,
    its rolling force and cap both 0.  Now no friction, or no tangential motion, is F = 0 throughout."""
    for changes in ({"mu": 0.0}, {"incidence": 0.0, "spin": 0.0, "partner_spin": 0.0}):
        scene = Scene(**SOFT | changes)
        planar, reduced = simulate(scene, body="planar"), simulate(scene)
        assert planar.switches == 0 and planar.regime == reduced.regime
    assert planar.cor == pytest.approx(reduced.cor, rel=1e-8)  # the normal impact: the line never turns
