"""Exact elastic microslip (method of dimensionality reduction) against the closed forms of the theory.

Quasi-static checks drive the element row with a prescribed history (:func:`quasi_static`): the
Cattaneo-Mindlin curve, its initial stiffness 8 G_eff a, the Mindlin-Deresiewicz loop and its dissipated
energy, and a growing contact loaded at Q/P = c < mu that never slips.  Dynamic checks: Maw, Barber &
Fawcett's gross-slip result psi_2 = psi_1 - 4 chi for psi_1 >= 4 chi - 1, the rigid model's answer when the
contact slides throughout, energy never gained, the rigid limit kappa -> infinity, and the compiled row's edge
band against every cell weighed alone.
"""

import math

import numpy as np
import pandas as pd
import pytest

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.impact.solve import simulate_many
from sphereimpact.sweep.engine import sweep
from sphereimpact.contact.tangential import microslip_march
from sphereimpact.integrators.compiled import load_compiled
from sphereimpact.contact.tangential.microslip import ELEMENTS, TIME_STEPS, quasi_static

#: Kharaz et al.'s alumina sphere (see test_compliance.ALUMINA), exact tangential contact.
ALUMINA = dict(mass=4000.0 * math.pi * 0.005 ** 3 / 6.0, diameter=0.005, speed=3.9, mu=0.092, model="hunt-crossley",
               modulus=62.951576984e9, chi=0.0083527, tangential="microslip", shear_modulus=13.521110724e9)
#: An elastic Hertz ball for Maw's theory (kappa and alpha give Maw's chi = kappa (1 + 1/alpha) / 2 = 1.4).
ELASTIC = dict(model="hertz", k=1e9, mu=0.3, tangential="microslip", kappa=0.8, inertia_factor=0.4)


def cattaneo_mindlin(z):
    """Q / (mu P) after a monotone tangential displacement z = U / U_s from a fresh contact (Mindlin 1949)."""
    return 1.0 - (1.0 - np.minimum(z, 1.0)) ** 1.5


# --- quasi-static: the element row against the closed forms (stiffness 2 G* a_max = 1, mu P = 1) -------------
def test_cattaneo_mindlin_curve_at_constant_normal_force():
    elements, u_s = 4096, 1.5  # U_s = 3 mu P / (2 k) = 3 mu P / (16 G_eff a)
    u = np.linspace(0.0, 1.2 * u_s, 241)
    q = quasi_static(np.ones_like(u), np.ones_like(u), u, elements=elements)
    assert np.max(np.abs(q - cattaneo_mindlin(u / u_s))) < 1e-6


def test_initial_stiffness_is_8_g_eff_a():
    for radius in (1.0, 0.5, 0.3):  # contact radius over a_max: the stiffness is 2 G* a = 8 G_eff a
        u = np.array([0.0, 1e-9])
        q = quasi_static(np.full(2, radius), np.ones(2), u, elements=96)
        assert q[1] / u[1] == pytest.approx(radius, rel=1e-12)


def test_mindlin_deresiewicz_loop_and_its_dissipated_energy():
    elements, u_s, z = 4096, 1.5, 0.6
    u_star = z * u_s
    path = np.concatenate([np.linspace(0.0, u_star, 301), np.linspace(u_star, -u_star, 601)[1:],
                           np.linspace(-u_star, u_star, 601)[1:]])
    q = quasi_static(np.ones_like(path), np.ones_like(path), path, elements=elements)
    g = cattaneo_mindlin
    q_star = g(z)
    unload, reload = slice(301, 901), slice(901, None)
    assert np.max(np.abs(q[:301] - g(path[:301] / u_s))) < 1e-6
    assert np.max(np.abs(q[unload] - (q_star - 2.0 * g((u_star - path[unload]) / (2.0 * u_s))))) < 1e-6
    assert np.max(np.abs(q[reload] - (-q_star + 2.0 * g((path[reload] + u_star) / (2.0 * u_s))))) < 1e-6
    assert q[-1] == pytest.approx(q_star, abs=1e-6)  # the loop closes (Masing)
    cycle = slice(300, None)
    area = np.trapezoid(q[cycle], path[cycle])  # the closed integral of Q dU: the work dissipated per cycle
    exact = u_s * (8 * z - 3.2 * (1 - (1 - z) ** 2.5) - 4 * z * (1 - (1 - z) ** 1.5))  # mu P U_s [...]
    assert area == pytest.approx(exact, rel=1e-4)


def test_a_growing_contact_loaded_below_mu_never_slips():
    """Q = c P with c < mu while the contact grows: no slip (Mindlin & Deresiewicz), so Q is linear in c."""
    elements, steps = 1024, 2000
    xi = np.linspace(0.0, 1.0, steps + 1)
    cap = xi ** 3  # mu P, P ~ a^3
    forces = {}
    for c in (0.3, 0.9):  # c / mu
        displacement = c * 1.5 * xi ** 2  # U = (c / mu) U_s(a), U_s ~ delta ~ a^2
        forces[c] = quasi_static(xi, cap, displacement, elements=elements)
        assert np.max(np.abs(forces[c] - c * cap)) < 2e-4 * c
    np.testing.assert_allclose(forces[0.3] / 0.3, forces[0.9] / 0.9, rtol=1e-12, atol=1e-15)
    slipping = quasi_static(xi, cap, 1.2 * 1.5 * xi ** 2, elements=elements)  # c > mu: held at mu P
    assert np.max(np.abs(slipping[1:] - cap[1:])) < 1e-10


# --- dynamic: one impact ------------------------------------------------------------------------------------
def _maw_angle(psi1: float) -> float:
    return math.degrees(math.atan(psi1 * ELASTIC["mu"] / ELASTIC["kappa"]))


@pytest.mark.parametrize("psi1", [4.65, 5.5, 8.0])
def test_maw_gross_slip_beyond_4chi_minus_1(psi1):
    """Maw, Barber & Fawcett (1976): for psi_1 >= 4 chi - 1 the contact slides throughout and
    psi_2 = psi_1 - 4 chi (chi = kappa (1 + 1/alpha) / 2 = 1.4 here, so the threshold is 4.6)."""
    scene = Scene(angle=_maw_angle(psi1), **ELASTIC)
    out = simulate(scene)
    chi = scene.kappa * (1.0 + 1.0 / scene.inertia_factor) / 2.0
    psi2 = scene.kappa * (out.ve_t / out.vc_n) / scene.mu
    assert out.regime == "sliding" and out.switches == 0 and out.t_roll is None
    assert psi2 == pytest.approx(psi1 - 4.0 * chi, abs=1e-8)


def test_below_maw_threshold_part_of_the_contact_sticks():
    out = simulate(Scene(angle=_maw_angle(3.0), **ELASTIC))
    chi = 1.4
    psi2 = ELASTIC["kappa"] * (out.ve_t / out.vc_n) / ELASTIC["mu"]
    assert out.regime == "microslip" and out.t_roll is not None
    assert psi2 > 3.0 - 4.0 * chi + 0.1  # stick recovers part of the rigid model's reversal


@pytest.mark.parametrize("angle", [45.0, 60.0])
def test_a_contact_that_slides_throughout_gives_the_rigid_answer(angle):
    scene = Scene(angle=angle, **ALUMINA)
    out, rigid = simulate(scene), simulate(scene.with_(tangential="rigid"))
    assert out.regime == "sliding" and out.switches == 0
    assert out.vc_t == pytest.approx(rigid.vc_t, rel=1e-13)
    assert out.omega_f == pytest.approx(rigid.omega_f, rel=1e-13)


@pytest.mark.parametrize("angle", [1.0, 4.0, 10.0, 20.0, 30.0])
def test_energy_is_never_gained_and_the_work_balances(angle):
    for scene in (Scene(angle=angle, **ALUMINA), Scene(angle=angle, **ELASTIC)):
        out = simulate(scene)
        assert out.work_t < 0
        history = out.history(20001)
        power = history["force_t"] * history["ve_t"]  # the tangential force's power on the ball
        assert np.trapezoid(power, history["t"]) == pytest.approx(out.work_t, rel=2e-3)
        cap = scene.mu * np.maximum(history["force"], 0.0)
        assert np.all(np.abs(history["force_t"]) <= cap * (1 + 1e-9) + 1e-12 * cap.max())


def test_a_stiff_tangential_contact_approaches_the_rigid_one():
    base = Scene(angle=10.0, **{**ALUMINA, "shear_modulus": None, "kappa": 1.0})
    rigid = simulate(base.with_(tangential="rigid"))
    errors = [abs(simulate(base.with_(kappa=kappa)).vc_t / rigid.vc_t - 1.0) for kappa in (1.0, 10.0, 100.0, 1000.0)]
    assert all(a > b for a, b in zip(errors, errors[1:])) and errors[-1] < 0.01, errors


def test_low_incidence_is_not_the_rigid_answer():
    """Below 8 deg the data's e_t is 0.75-0.79; the rigid contact grips (5/7) and a no-slip spring rebounds
    e_t ~ 1; the exact theory lands between."""
    e_t = simulate(Scene(angle=3.0, **ALUMINA)).vc_t / Scene(angle=3.0, **ALUMINA).v_tangent
    assert 0.74 < e_t < 0.80


def test_the_edge_band_weighs_every_cell_as_the_dense_row_does():
    """A step of the row weighs only the cells the contact's edge crosses (``row_weights``); every other cell's
    limit comes from the affine formula.  Against every cell weighed by ``cell_weight``, on contact radii that jump
    several cells a step, shrink, stall, land on cell edges and reach 0: the limits and one step of the row agree
    to round-off."""
    rng = np.random.default_rng(3)
    elements, steps = 16, 40
    xi = rng.uniform(0.0, 1.0, steps)
    xi[5] = xi[4]  # a stalled step
    xi[7], xi[8], xi[-1] = 5.0 / elements, 0.0, 0.0  # a cell's edge, then no contact, then the end
    a0 = np.concatenate([[0.3], xi[:-1]])
    cap, stiffness, width = rng.uniform(0.5, 2.0, steps), 2.0, 1.0 / elements
    moments = microslip_march.cell_moments(elements)
    limit, mean = np.empty(elements), np.empty(elements)
    held = rng.uniform(-0.05, 0.05, elements)
    for j in range(steps):
        microslip_march.row_weights(a0[j], xi[j], cap[j], stiffness, moments, limit, mean)
        dense = np.array([microslip_march.cell_weight(a0[j], xi[j], i * width, width) for i in range(elements)])
        np.testing.assert_allclose(limit, cap[j] / stiffness * dense[:, 1], rtol=1e-12, atol=1e-15)
        expected = np.clip(held + dense[:, 0] * 0.01, -limit, limit)
        total = microslip_march.hold(held, limit, mean, 0.01)
        np.testing.assert_allclose(held, expected, rtol=1e-12, atol=1e-15)
        assert total == pytest.approx(expected.sum(), rel=1e-12, abs=1e-15)


def test_contacts_of_several_resolutions_are_each_marched_at_their_own():
    """A stiff tangential contact needs more time steps than the default (kappa 100: 769); solved with a soft one
    (simulate_many, a sweep), each is marched at its own resolution, so both are what simulate gives them alone (one
    march at the finer resolution moved the soft one's e_t by 9e-6)."""
    soft, stiff = (Scene(angle=20.0, **{**ALUMINA, "shear_modulus": None, "kappa": k}) for k in (0.8, 100.0))
    batched = simulate_many([soft, stiff, soft.with_(angle=35.0)])
    for outcome in batched:
        alone = simulate(outcome.scene)
        assert outcome.motion.tangential.time_steps == alone.motion.tangential.time_steps
        assert outcome.vc_t == pytest.approx(alone.vc_t, rel=1e-13) and outcome.omega_f == pytest.approx(alone.omega_f, rel=1e-13)
    assert batched[1].motion.tangential.time_steps > TIME_STEPS == batched[0].motion.tangential.time_steps
    swept = sweep(pd.DataFrame([outcome.scene.as_dict() for outcome in batched]).dropna(axis=1, how="all"))
    np.testing.assert_allclose(swept["vc_t"], [outcome.vc_t for outcome in batched], rtol=1e-8)  # the sweep's target


def test_resolution_options_and_refusals():
    scene = Scene(angle=20.0, **ALUMINA)
    out = simulate(scene)
    assert (out.motion.tangential.elements, out.motion.tangential.time_steps) == (ELEMENTS, TIME_STEPS)
    fine = simulate(scene, SolverOptions(settings={"elements": 2 * ELEMENTS, "time_steps": 2 * TIME_STEPS}))
    assert fine.motion.tangential.time_steps == 2 * TIME_STEPS
    assert fine.vc_t == pytest.approx(out.vc_t, rel=1e-3)
    for bad in (dict(elements=4), dict(time_steps=10**8), dict(elements=2.5), dict(time_steps=True)):
        with pytest.raises(ValueError, match=f"{next(iter(bad))} must be an integer in"):
            SolverOptions(settings=bad)
    with pytest.raises(ValueError, match="tangential 'microslip' .* needs a Hertz spring"):
        Scene(angle=20.0, tangential="microslip", kappa=1.0)
    with pytest.raises(ValueError, match="body 'planar' has the rigid tangential contact only"):
        simulate(scene, body="planar")


def test_sweep_solves_microslip_scenes_as_simulate_does():
    angles = [0.0, 4.0, 20.0, 60.0]
    table = sweep({"angle": angles, **ALUMINA})
    for row in table.to_dict("records"):
        one = simulate(Scene(**{**ALUMINA, "angle": row["angle"]}))
        for key in ("vc_t", "omega_f", "ve_t", "cor"):
            assert row[key] == pytest.approx(getattr(one, key), rel=1e-8, abs=1e-12), key
        assert row["regime"] == one.regime


@pytest.mark.parametrize("compiled", [True, False], ids=["compiled", "python"])
@pytest.mark.parametrize("separation", ["force", "penetration"])
def test_the_march_samples_read_once_are_the_motions_own_values_to_the_bit(separation, compiled, monkeypatch):
    """The march's inputs evaluate the normal motion once and read the force and J+ off that state: the values of
    normal.force(t) and PositiveImpulse(normal)(t) on numpy's linspace to the bit, under both criteria (the
    penetration criterion's force pulls before delta returns to 0: J+ stops growing there), by the compiled sampler
    and by Python floats (a motion without a kernel state)."""
    from sphereimpact.contact.tangential.microslip import _samples
    from sphereimpact.contact.tangential.rigid import PositiveImpulse
    from sphereimpact.integrators import normal_motion

    load_compiled()
    scene = Scene(model="hunt-crossley", modulus=1e8, chi=2.0, angle=30.0, tangential="microslip", kappa=0.8,
                  separation=separation)
    normal = normal_motion(scene, SolverOptions())
    assert normal.kernel_state() is not None
    if not compiled:
        monkeypatch.setattr(type(normal), "kernel_state", lambda self: None)
    t, xi_a, load, step_impulse, delta_m = _samples(normal, 384)
    force = np.maximum(normal.force(t), 0.0)
    force[0] = force[-1] = 0.0
    positive = PositiveImpulse(normal)
    assert np.array_equal(t, np.linspace(0.0, normal.t_f, 385))
    assert np.array_equal(load, force) and np.array_equal(step_impulse, np.diff(positive(t)))
    delta = np.maximum(normal.state(t)[0], 0.0)
    assert delta_m == max(normal.delta_m, delta.max()) and np.array_equal(xi_a, np.sqrt(delta / delta_m))
    if separation == "penetration":
        assert len(positive.intervals) == 1 and positive.intervals[0][1] < normal.t_f  # a gap: J+ held


def test_the_compiled_sampler_is_the_python_one_to_the_bit_on_random_scenes(monkeypatch):
    """``microslip_march.samples`` against the Python sampler (a motion without a kernel state) on the consistency
    test's random microslip scenes, Hertz and Hunt-Crossley, at several step counts (odd ones too): every array and
    delta_m to the bit."""
    from sphereimpact.contact.tangential.microslip import _samples
    from sphereimpact.integrators import normal_motion
    from sphereimpact.integrators.normal import _DimensionlessNormal
    from sphereimpact.numerics.consistency import random_scenes
    from sphereimpact.sweep.scenes import scene_of, scene_table

    load_compiled()
    rows = [row for row in scene_table(random_scenes(4000, seed=11)).to_dict("records") if row["tangential"] == "microslip"]
    scenes = [scene_of(row) for model in ("hertz", "hunt-crossley") for row in rows if row["model"] == model][:12]
    scenes += [scene_of(row) for row in rows if row["model"] == "hunt-crossley"][:12]
    assert sum(scene.model == "hunt-crossley" for scene in scenes) >= 8
    for i, scene in enumerate(scenes):
        normal, steps = normal_motion(scene, SolverOptions()), (17, 384, 1001)[i % 3]
        assert normal.kernel_state() is not None
        compiled = _samples(normal, steps)
        with monkeypatch.context() as patch:
            patch.setattr(_DimensionlessNormal, "kernel_state", lambda self: None)
            python = _samples(normal, steps)
        for mine, theirs in zip(compiled, python):
            assert np.array_equal(mine, theirs), scene


@pytest.mark.parametrize("scene", [Scene(angle=_maw_angle(3.0), **ELASTIC),
                                   Scene(angle=20.0, spin=-30.0, gravity=9.81, **ALUMINA)], ids=["sticks", "spin-and-gravity"])
def test_the_motion_kernel_is_the_momentum_balance_on_the_marched_force(scene):
    """``microslip_march.motion`` against numpy's element-wise arithmetic on the march's own force and impulse, to the
    bit: v = v_t + g_t t + J_t / m, omega = spin - J_t / (alpha m R), x by the trapezoidal rule with its end correction
    dt^2 / 12 times the change of acceleration, the friction fraction F / (mu P+) held at its nearest values where
    the cap is 0, the stuck step ends, their switches over the interior and the first one (t_roll)."""
    motion = simulate(scene).motion.tangential
    t, force, j_t = motion.t, motion._force, motion._j
    cap = scene.mu * np.maximum(motion.normal.force(t), 0.0)
    cap[0] = cap[-1] = 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = np.where(cap > 0, force / cap, np.nan)
    stuck = (cap > 0) & (np.abs(fraction) < 1.0 - 1e-3)
    inside = np.flatnonzero(np.isfinite(fraction))
    filled = fraction.copy()
    filled[:inside[0]], filled[inside[-1] + 1:] = fraction[inside[0]], fraction[inside[-1]]
    v = scene.v_tangent + scene.g_tangent * t + j_t / scene.mass
    omega = scene.spin - j_t / (scene.inertia_factor * scene.mass * scene.radius)
    accel = force / scene.mass + scene.g_tangent
    dt = t[1] - t[0]
    x = np.concatenate([[0.0], np.cumsum(0.5 * dt * (v[1:] + v[:-1]) + dt * dt / 12.0 * (accel[:-1] - accel[1:]))])
    for mine, theirs in ((motion._fraction, filled), (motion.stuck, stuck), (motion.v, v), (motion.omega, omega),
                         (motion.x, x)):
        assert np.array_equal(mine, theirs)
    assert motion.switches == np.count_nonzero(np.diff(stuck[1:-1].astype(int)))
    assert motion.t_roll == (t[np.argmax(stuck)] if stuck.any() else None)
    assert stuck.any() == (motion.regime == "microslip")
