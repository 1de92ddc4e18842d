"""Normal motions shared by the scenes of one normal problem (:func:`reusing_normal_motions`, what a fit of mu and
kappa runs in): what the normal motion does not read leaves it unchanged, every outcome inside the block is bit
for bit the one solved afresh, each normal problem is solved once, and nothing is kept outside the block."""

import numpy as np

from sphereimpact.contact.tangential import TANGENTIAL_PARAMETERS
import pandas as pd
import pytest

from sphereimpact import Scene, simulate
from sphereimpact import integrators
from sphereimpact.impact import solve
from sphereimpact.impact.ball import ball_columns
from sphereimpact.impact.outcome import SOLVER_KEYS
from sphereimpact.impact.scene import TANGENTIAL_ONLY
from sphereimpact.impact.solve import reusing_normal_motions, simulate_many
from sphereimpact.integrators import normal_motion
from sphereimpact.sweep import sweep

#: Normal problems of every kind of law and integrator (closed form, Taylor, DOP853; gravity on a slope, a partner
#: sphere) -> the tangential models their scenes take in turn.
PROBLEMS = {
    "modified": (dict(model="modified", angle=30.0), ("rigid", "linear")),
    "kelvin-voigt": (dict(model="kelvin-voigt", angle=50.0, gravity=9.81), ("rigid", "linear")),
    "hertz": (dict(model="hertz", modulus=2e7, angle=20.0), ("mindlin", "microslip", "mindlin-displacement")),
    "hunt-crossley": (dict(model="hunt-crossley", modulus=2e7, chi=0.05, speed=4.0, incidence=15.0),
                      ("microslip", "rigid", "mindlin")),
    "pair": (dict(model="hunt-crossley", modulus=2e7, chi=0.05, angle=35.0, partner_mass=0.4,
                  partner_diameter=0.09), ("microslip", "rigid")),
}


def _scenes(seed: int = 0, per_problem: int = 4) -> list[Scene]:
    """Scenes of :data:`PROBLEMS`, ``per_problem`` each, differing only in friction, tangential model, stiffness and
    spin, shuffled."""
    rng = np.random.default_rng(seed)
    scenes = []
    for fields, tangentials in PROBLEMS.values():
        for i in range(per_problem):
            tangential = tangentials[i % len(tangentials)]
            stiffness = {} if tangential == "rigid" else {"kappa": float(rng.uniform(0.5, 1.5))}
            scenes.append(Scene(**fields, tangential=tangential, mu=float(rng.uniform(0.05, 0.6)),
                                spin=float(rng.uniform(-30.0, 30.0)), **stiffness))
    return [scenes[i] for i in rng.permutation(len(scenes))]


def _outputs(outcome) -> dict:
    return {key: value for key, value in outcome.to_dict().items() if key not in SOLVER_KEYS}


def test_the_normal_motion_does_not_read_what_the_normal_problem_leaves_out():
    """Each field :attr:`Scene.normal_problem` leaves out, changed alone: the normal motion solved afresh is the same
    to the last bit on a fine grid, and so is the normal problem."""
    base = Scene(model="hertz", modulus=2e7, angle=20.0, tangential="mindlin", kappa=0.8)
    changes = {"mu": 0.7, "tangential": "microslip", "kappa": 1.3, "poisson": 0.3, "shear_modulus": 5e6, "spin": 40.0}
    assert set(changes) - set(TANGENTIAL_PARAMETERS) | {"parameters"} == set(TANGENTIAL_ONLY)  # and the model's own
    reference = normal_motion(base, solve.SolverOptions())
    t = np.linspace(0.0, reference.t_f, 501)
    for name, value in changes.items():
        extra = {"kappa": None} if name in ("poisson", "shear_modulus") else {}
        other = base.with_(**{name: value}, **extra)
        assert other.normal_problem == base.normal_problem, name
        motion = normal_motion(other, solve.SolverOptions())
        assert motion.t_f == reference.t_f and np.array_equal(motion.state(t), reference.state(t)), name
    assert base.with_(chi=None, model="hunt-crossley", modulus=2e7).normal_problem != base.normal_problem


def test_outcomes_inside_the_block_are_those_solved_afresh():
    """simulate and simulate_many inside the block, against simulate outside it, on the mixed scenes: every output
    equal, bit for bit."""
    scenes = _scenes()
    fresh = [_outputs(simulate(scene)) for scene in scenes]
    with reusing_normal_motions():
        alone = [_outputs(simulate(scene)) for scene in scenes]
        batched = [_outputs(outcome) for outcome in simulate_many(scenes)]
        again = [_outputs(simulate(scene)) for scene in scenes]  # the shared motions read a second time
    outside = [_outputs(outcome) for outcome in simulate_many(scenes)]
    assert alone == fresh and again == fresh and batched == outside


def test_each_normal_problem_is_solved_once_inside_the_block_and_every_time_outside(monkeypatch):
    calls = []

    def counted(scene, options):
        calls.append(scene)
        return normal_motion(scene, options)

    monkeypatch.setattr(solve, "normal_motion", counted)
    scenes = _scenes(per_problem=3)
    with reusing_normal_motions():
        for scene in scenes:
            simulate(scene)
        simulate_many(scenes)
        with reusing_normal_motions():  # a nested block shares the outer one's
            simulate(scenes[0])
        simulate(scenes[0].with_(speed=scenes[0].speed * (1 + 1e-12)))  # a normal problem of its own
    assert len(calls) == len(PROBLEMS) + 1
    calls.clear()
    for scene in scenes:
        simulate(scene)
    assert len(calls) == len(scenes)


def test_a_sweep_inside_the_block_is_the_sweep_outside():
    """A table mixing the problems' scenes (the sweep's single-impact path, microslip batched) twice inside the
    block, the second time on shared motions: the same table as outside."""
    table = pd.DataFrame([scene.as_dict() for scene in _scenes(seed=1, per_problem=6)])
    table = table.drop(columns=[c for c in table if table[c].isna().all()])
    outside = sweep(table, chapter_ball=True)
    with reusing_normal_motions():
        first, second = sweep(table, chapter_ball=True), sweep(table, chapter_ball=True)
    pd.testing.assert_frame_equal(first, outside)
    pd.testing.assert_frame_equal(second, outside)


def test_a_fit_solves_its_bounces_normal_motions_once(monkeypatch):
    """A fit of what the normal motion does not depend on evaluates its model tens of times but solves each
    bounce's normal motion once."""
    from sphereimpact.fit import fit, read_measured
    from sphereimpact.impact.ball import Ball

    truth = Scene(model="hunt-crossley", modulus=2e7, chi=0.05, tangential="microslip", kappa=0.8, mu=0.3)
    bounces = pd.DataFrame({"speed": 3.0, "incidence": [10.0, 25.0, 40.0, 55.0]})
    bounces["vc_t"] = [simulate(truth.with_(incidence=theta)).vc_t for theta in bounces["incidence"]]
    calls = []
    monkeypatch.setattr(solve, "normal_motion", lambda scene, options: calls.append(scene) or normal_motion(scene, options))
    result = fit(read_measured(bounces), Ball(truth.with_(mu=0.2, kappa=1.1)), ["mu", "kappa"], chapter_ball=True)
    assert result.statistics["evaluations"] > 10 and len(calls) == len(bounces)
    assert result.parameters["mu"].value == pytest.approx(0.3, rel=1e-6)


def test_a_fit_of_a_rigid_contact_solves_its_bounces_normal_motions_once(monkeypatch):
    """The sweep's per-family path (a Hertz law without batched lanes, rigid tangential contact) shares the block's
    motions too.  Before, it solved every bounce's normal motion at every evaluation of the model (the pipeline's fit
    of the Kharaz data: 576 solves for 24 bounces), though the fit ran inside the block; its result is bit for bit
    the same either way."""
    from sphereimpact.fit import fit, read_measured
    from sphereimpact.impact.ball import Ball

    truth = Scene(model="hunt-crossley", modulus=2e7, chi=0.05, mu=0.3)
    bounces = pd.DataFrame({"speed": 3.0, "incidence": [20.0, 35.0, 50.0, 65.0]})
    bounces["vc_t"] = [simulate(truth.with_(incidence=theta)).vc_t for theta in bounces["incidence"]]
    start = Ball(truth.with_(mu=0.2))
    calls, choose = [], integrators.choose  # counted where every normal solve passes, whoever imported it
    monkeypatch.setattr(integrators, "choose", lambda scene, options: calls.append(scene) or choose(scene, options))
    result = fit(read_measured(bounces), start, ["mu"], chapter_ball=True)
    assert result.statistics["evaluations"] > 5 and len(calls) == len(bounces)
    assert sweep(bounces[["speed", "incidence"]].assign(**ball_columns(start)))["path"].eq("per-family").all()
    assert result.parameters["mu"].value == pytest.approx(0.3, rel=1e-6)


def test_a_sweep_over_spin_solves_each_normal_problem_once(monkeypatch):
    """A compliant damped ball's spin x incidence map (the single path): one normal solve per incidence, every
    row bit for bit simulate's at the sweep's options."""
    from sphereimpact.sweep.paths import single_options

    calls = []
    monkeypatch.setattr(solve, "normal_motion", lambda scene, options: calls.append(scene) or normal_motion(scene, options))
    table = pd.DataFrame({"incidence": np.repeat([10.0, 30.0, 60.0], 5), "spin": np.tile(np.linspace(-200, 200, 5), 3)})
    table = table.assign(speed=3.0, model="hunt-crossley", modulus=2e7, chi=0.05, tangential="microslip", kappa=0.8)
    swept = sweep(table, chapter_ball=True)
    assert set(swept["path"]) == {"single"} and len(calls) == 3
    options = single_options(1e-8)
    for row, (_, scene) in zip(swept.itertuples(), table.iterrows()):
        alone = simulate(Scene(**scene.to_dict()), options)
        assert (row.vc_t, row.omega_f, row.t_f) == (alone.vc_t, alone.omega_f, alone.t_f)
