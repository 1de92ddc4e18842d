"""Friction from the normal impulse: sliding ratio, grip, and agreement with the full planar model."""

import math

import numpy as np
import pytest

from conftest import TIGHT, assert_outputs_close
from sphereimpact import Scene, SolverOptions, simulate


@pytest.mark.parametrize("model", ["modified", "kelvin-voigt"])
def test_sliding_impulse_ratio_is_mu(model):
    """While sliding throughout, tangential impulse / normal impulse = mu (g = 0, force criterion: P >= 0)."""
    scene = Scene(angle=60.0, model=model)
    out = simulate(scene, TIGHT)
    assert out.regime == "sliding" and out.t_roll is None
    normal_impulse = scene.mass * (scene.v_normal + out.vc_n)
    tangential_impulse = scene.mass * (scene.v_tangent - out.vc_t)
    assert tangential_impulse / normal_impulse == pytest.approx(scene.mu, rel=1e-12)
    # the same impulse spins the ball: I omega = R * tangential impulse
    assert scene.inertia * out.omega_f == pytest.approx(scene.radius * tangential_impulse, rel=1e-12)


@pytest.mark.parametrize("alpha", [0.4, 2.0 / 3.0])
def test_grip_final_velocity(alpha):
    """Grip: ve_t = 0, and the centre keeps vt0 / (1 + alpha) (it loses vt0 / (1 + 1/alpha))."""
    scene = Scene(angle=30.0, inertia_factor=alpha)
    out = simulate(scene, TIGHT)
    vt0 = scene.v_tangent
    assert out.regime == "rolling"
    assert 0 < out.t_roll < out.t_f
    assert out.vc_t == pytest.approx(vt0 / (1 + alpha), rel=1e-13)
    assert vt0 - out.vc_t == pytest.approx(vt0 / (1 + 1 / alpha), rel=1e-13)
    assert abs(out.ve_t) <= 1e-13 * vt0
    assert out.omega_f * scene.radius == pytest.approx(out.vc_t, rel=1e-13)


def test_grip_instant_from_impulse():
    """Grip happens when mu (1 + 1/alpha) J(t) / m = vt0: J(t_roll) from the momentum balance."""
    scene = Scene(angle=30.0)
    out = simulate(scene, TIGHT)
    rate = out.motion.normal.state(out.t_roll)[1]
    impulse = scene.mass * (scene.v_normal - rate)
    assert scene.mu * (1 + 1 / scene.inertia_factor) * impulse / scene.mass == pytest.approx(scene.v_tangent,
                                                                                              rel=1e-12)


def test_grip_slide_boundary():
    """Analytic boundary: the ball grips iff tan(beta) < (1 + 1/alpha) mu (1 + e)."""
    for angle in (40.0, 50.0):
        scene = Scene(angle=angle)
        out = simulate(scene)
        limit = (1 + 1 / scene.inertia_factor) * scene.mu * (1 + out.cor)
        assert (out.regime == "rolling") == (math.tan(scene.beta) < limit)


def test_normal_impact_has_no_tangential_state():
    out = simulate(Scene(angle=0.0))
    assert out.regime == "none" and out.t_roll is None
    assert (out.vc_t, out.ve_t, out.omega_f) == (0.0, 0.0, 0.0)


def test_frictionless_keeps_tangential_velocity():
    scene = Scene(angle=45.0, mu=0.0)
    out = simulate(scene)
    assert out.vc_t == scene.v_tangent and out.omega_f == 0.0 and out.regime == "sliding"


PLANAR_SCENES = {
    "chapter-60deg-sliding": dict(angle=60.0),
    "30deg-grip": dict(angle=30.0),
    "shell-15deg-grip": dict(angle=15.0, inertia_factor=2 / 3, mu=0.4),
    "gravity-grip-then-slip": dict(angle=30.0, gravity=9.81),
    "kv-penetration-tension": dict(angle=60.0, model="kelvin-voigt", separation="penetration"),
    "kv-penetration-grip": dict(angle=20.0, model="kelvin-voigt", separation="penetration"),
    "normal-gravity": dict(angle=0.0, gravity=9.81, separation="penetration"),
}


@pytest.mark.parametrize("name", PLANAR_SCENES)
def test_reduced_matches_planar(name):
    """The reduced model (normal ODE + impulse algebra) agrees with the full planar model to 1e-9."""
    scene = Scene(**PLANAR_SCENES[name])
    assert_outputs_close(simulate(scene, TIGHT), simulate(scene, TIGHT, body="planar"), rtol=1e-9)


def test_gravity_regrip_sequence():
    """With gravity the rolling ball slips again when mu P can no longer hold it; both models agree on when."""
    scene = Scene(angle=30.0, gravity=9.81)
    reduced = simulate(scene, TIGHT)
    phases = [p.mode for p in reduced.motion.tangential.phases]
    assert phases == ["sliding", "rolling", "sliding"]
    reslip = reduced.motion.tangential.phases[2].t0
    hold = scene.mass * scene.g_tangent * scene.inertia_factor / (1 + scene.inertia_factor)
    assert scene.mu * float(reduced.motion.force(reslip)) == pytest.approx(hold, rel=1e-9)
    assert reduced.ve_t > 0


def test_history_frames_consistent():
    """Global and local histories describe the same motion: speeds and the end state agree."""
    out = simulate(Scene(angle=60.0))
    h = out.history(201)
    speed_local = h["vc_t"] ** 2 + h["vc_n"] ** 2
    speed_global = h["VX"] ** 2 + h["VY"] ** 2
    assert max(abs(speed_local - speed_global)) < 1e-12
    assert h["VX"][0] == pytest.approx(0.0, abs=1e-12) and h["VY"][0] == pytest.approx(-3.0, rel=1e-12)
    assert h["vc_n"].iloc[-1] == pytest.approx(out.vc_n, rel=1e-12)
    assert h["ve_t"].iloc[-1] == pytest.approx(out.ve_t, rel=1e-12)
    assert min(h["u_n"]) == pytest.approx(-out.delta_m, rel=1e-4)


@pytest.mark.parametrize("body", ["reduced", "planar"])
def test_tight_tolerance_keeps_converging_through_separation(body):
    """Regression: with the physical law (0 past delta = 0) in the right-hand side, the step that crosses
    separation lost the rebound velocity (COR error 8.9e-11 at rtol 1e-12, worse than at 1e-11).
    Against the closed form, the error now falls with the tolerance."""
    scene = Scene(angle=60.0, model="kelvin-voigt", separation="penetration")
    exact = simulate(scene, SolverOptions(method="closed"))
    errors = [abs(simulate(scene, SolverOptions(method="DOP853-scalar", rtol=r, atol=r), body=body).cor - exact.cor)
              for r in (1e-10, 1e-12)]
    assert errors[1] < 1e-11 and errors[1] < errors[0]


def test_positive_impulse_is_the_quadrature_of_the_positive_force():
    """J+ and K+ against the trapezoid rule on max(P, 0), for a force that pulls before delta returns to 0
    (kelvin-voigt, penetration criterion) and for one that never pulls."""
    from scipy.integrate import cumulative_trapezoid

    from sphereimpact.contact.tangential import PositiveImpulse

    for scene in (Scene(model="kelvin-voigt", separation="penetration", angle=30), Scene(model="hertz", k=1e9)):
        normal = simulate(scene).motion.normal
        impulse = PositiveImpulse(normal)
        t = np.linspace(0.0, normal.t_f, 200001)
        positive = np.maximum(normal.force(t), 0.0)
        j = cumulative_trapezoid(positive, t, initial=0.0)
        k = cumulative_trapezoid(j, t, initial=0.0)
        assert np.max(np.abs(impulse(t) - j)) < 1e-8 * j[-1]
        assert np.max(np.abs(impulse.integral(t) - k)) < 1e-8 * k[-1]
        assert len(impulse.intervals) == 1  # P > 0 on one interval: from first touch to tension or separation



@pytest.mark.parametrize("scene", [Scene(angle=60.0), Scene(angle=30.0, gravity=9.81),
                                   Scene(angle=30.0, model="hunt-crossley", k=8.8e5, chi=0.05),
                                   Scene(angle=30.0, model="kelvin-voigt")],
                         ids=["chapter", "gravity", "hunt-crossley", "kelvin-voigt"])
def test_one_pushing_interval_is_the_general_cut_to_the_bit(scene):
    """Under the force criterion the force pushes over all of [0, t_f]: J+'s arrays built for that one interval in
    floats are the general cut's (any number of intervals, numpy) to the bit, so J+ and K+ are the same whichever
    builds them."""
    from sphereimpact.contact.tangential import PositiveImpulse

    normal = simulate(scene).motion.normal
    one = PositiveImpulse(normal)
    cut = object.__new__(PositiveImpulse)
    cut._n = normal
    cut._cut([])
    assert one.intervals == cut.intervals == [(0.0, normal.t_f)]
    for name in ("_a", "_b", "_ja", "_jb", "_ka", "_kb", "_before", "_k_start"):
        assert getattr(one, name).tolist() == getattr(cut, name).tolist(), name

def test_a_flickering_force_costs_no_more_than_a_few_intervals():
    """A slow creep back to delta = 0 (eq. 4.2, zeta = 536, penetration criterion) makes P flicker about 0
    thousands of times; J+ is then evaluated in one vectorised pass (interval by interval, the same scene at
    ten times the damping ran for over ten minutes)."""
    scene = Scene(angle=30, b=1e5, separation="penetration")
    out = simulate(scene)
    assert len(out.motion.tangential.jp.intervals) > 1000
    assert out.vc_t == pytest.approx(scene.v_tangent / (1 + scene.inertia_factor), rel=1e-6)  # it grips and rolls


@pytest.mark.parametrize("scene", [Scene(angle=30.0, gravity=9.81), Scene(angle=60.0),
                                   Scene(model="kelvin-voigt", separation="penetration", angle=30)],
                         ids=["regrip", "sliding", "kv-pulling"])
def test_scalar_paths_give_the_array_paths_values_to_the_bit(scene):
    """The post-processing reads a few instants in plain floats (J+, K+, slip, the motion at t_m and t_f)
    and grids through numpy; both must be the same numbers, or outputs would depend on how they were asked.
    (On an integrated motion, whose dense output is bitwise the same either way; the kelvin-voigt closed
    form's scalar and array formulas agree to round-off only.)"""
    tangential = simulate(scene, SolverOptions(method="DOP853-scalar")).motion.tangential
    t = np.linspace(0.0, tangential.normal.t_f, 41)
    grid = tangential.at(t)  # more than SMALL instants: the array path
    few = np.column_stack([tangential.at(t[i:i + 2]) for i in range(0, t.size - 1, 2)] + [tangential.at(t[-1:])])
    assert np.array_equal(few, grid)
    jp = tangential.jp
    assert [jp(float(x)) for x in t] == jp(t).tolist()
    assert [jp.integral(float(x)) for x in t] == jp.integral(t).tolist()
    p = tangential.phases[0]
    assert [tangential._slip(p, float(x)) for x in t] == tangential._slip(p, t).tolist()


def test_every_built_in_model_reports_a_declared_regime_written_as_a_plain_word(tmp_path):
    """The regimes are one enumeration (contact.tangential.Regime); a table and the JSON hold their words."""
    import json

    from sphereimpact.contact.tangential import TANGENTIALS, Regime
    from sphereimpact.sweep.engine import sweep

    hertz = {"model": "hertz", "modulus": 1e8}
    seen = set()
    for name, model in TANGENTIALS.items():
        law = (hertz if model.spring == "hertz" else {}) | ({"kappa": 0.8} if name != "rigid" else {})
        for angle, mu in ((5.0, 1.0), (20.0, 0.5), (70.0, 0.1)):
            out = simulate(Scene(angle=angle, mu=mu, tangential=name, **law))
            assert out.regime in tuple(Regime), (name, out.regime)
            assert json.loads(json.dumps(out.to_dict()))["regime"] == out.regime.value
            seen.add(out.regime)
    assert simulate(Scene()).regime is Regime.NONE
    assert {Regime.SLIDING, Regime.ROLLING, Regime.MICROSLIP} <= seen  # a spring lets go sliding as its cap falls
    path = tmp_path / "table.csv"
    sweep({"angle": [0.0, 20.0, 70.0], "mu": 0.5}, chapter_ball=True).to_csv(path, index=False)
    assert path.read_text().count(",rolling,") + path.read_text().count(",none,") == 3
