"""The kelvin-voigt closed form: against textbook limits and against the integrator, in all damping regimes."""

import math

import numpy as np
import pytest

from conftest import TIGHT, assert_outputs_close
from sphereimpact import ImpactError, Scene, SolverOptions, simulate
from sphereimpact.integrators.closed_form import ClosedFormNormal

CRITICAL_B = 2.0 * math.sqrt(60000.0 * 0.145)  # b at zeta = 1 for the chapter's k and m


@pytest.mark.parametrize("method", ["closed", "DOP853", "Radau"])
@pytest.mark.parametrize("angle", [0.0, 60.0])
def test_undamped_limits(method, angle):
    """b = 0: COR = 1, t_f = pi sqrt(m/k), delta_m = v_n sqrt(m/k), t_m = t_f / 2."""
    scene = Scene(model="kelvin-voigt", b=0.0, angle=angle, separation="penetration")
    out = simulate(scene, SolverOptions(method=method, rtol=1e-12, atol=1e-14))
    period = math.sqrt(scene.mass / scene.k)
    assert out.cor == pytest.approx(1.0, rel=1e-10)
    assert out.t_f == pytest.approx(math.pi * period, rel=1e-10)
    assert out.delta_m == pytest.approx(scene.v_normal * period, rel=1e-10)
    assert out.t_m == pytest.approx(0.5 * out.t_f, rel=1e-10)


def test_underdamped_textbook_values():
    """Free damped oscillator from rest position: t_f = pi/omega_d, COR = exp(-zeta pi / sqrt(1 - zeta^2))."""
    scene = Scene(model="kelvin-voigt", separation="penetration")
    out = simulate(scene, SolverOptions(method="closed"))
    z, w = scene.zeta, scene.omega_n
    wd = w * math.sqrt(1 - z * z)
    assert out.t_f == pytest.approx(math.pi / wd, rel=1e-13)
    assert out.cor == pytest.approx(math.exp(-z * math.pi / math.sqrt(1 - z * z)), rel=1e-13)
    assert out.t_m == pytest.approx(math.atan2(wd, z * w) / wd, rel=1e-13)


SCENES = {
    "under-penetration": dict(separation="penetration"),
    "under-force": dict(separation="force"),
    "under-gravity-30deg": dict(separation="penetration", angle=30.0, gravity=9.81),
    "critical-force": dict(b=CRITICAL_B, separation="force"),
    "over-force": dict(b=5 * CRITICAL_B, separation="force", angle=45.0),
    "over-force-gravity": dict(b=1.5 * CRITICAL_B, separation="force", gravity=9.81, angle=20.0),
}


@pytest.mark.parametrize("name", SCENES)
def test_integrated_matches_closed_form(name):
    """Numerical kelvin-voigt vs the closed form: every output within 1e-9."""
    scene = Scene(model="kelvin-voigt", **SCENES[name])
    exact = simulate(scene, SolverOptions(method="closed"))
    numeric = simulate(scene, TIGHT)
    assert_outputs_close(numeric, exact, rtol=1e-9)


def test_closed_form_continuous_across_critical_damping():
    """The under- and over-damped formulas meet the critical one: no cancellation near zeta = 1."""
    t = np.linspace(0.0, 3e-3, 7)
    states = [ClosedFormNormal(Scene(model="kelvin-voigt", b=CRITICAL_B * f, separation="force")).state(t)
              for f in (1 - 1e-9, 1.0, 1 + 1e-9)]
    for other in (states[0], states[2]):
        np.testing.assert_allclose(other[0], states[1][0], rtol=1e-7, atol=1e-15)
        np.testing.assert_allclose(other[1], states[1][1], rtol=1e-7, atol=1e-12)


def test_closed_form_satisfies_ode():
    """Residual of m delta'' + b delta' + k delta = m g_n by central differences of the exact delta'."""
    scene = Scene(model="kelvin-voigt", angle=20.0, gravity=9.81, b=1.5 * CRITICAL_B)
    sol = ClosedFormNormal(scene)
    t, h = np.linspace(1e-4, 0.8 * sol.t_f, 9), 1e-8
    delta, rate = sol.state(t)
    accel = (sol.state(t + h)[1] - sol.state(t - h)[1]) / (2 * h)
    residual = scene.mass * accel + scene.b * rate + scene.k * delta - scene.mass * scene.g_normal
    assert np.max(np.abs(residual)) < 1e-6 * scene.k * sol.delta_m


@pytest.mark.parametrize("method, body", [("closed", "reduced"), ("DOP853", "reduced"), ("RK45", "reduced"),
                                          ("LSODA", "reduced"), ("DOP853", "planar"), ("LSODA", "planar")])
@pytest.mark.parametrize("factor", [1.0, 5.0])
def test_overdamped_penetration_never_separates(factor, method, body):
    """delta -> 0 only asymptotically: no separation, never a spurious one at the tolerance level."""
    scene = Scene(model="kelvin-voigt", b=factor * CRITICAL_B, separation="penetration", angle=30.0)
    with pytest.raises(ImpactError, match="no separation"):
        simulate(scene, SolverOptions(method=method), body=body)


def test_ball_held_by_gravity_never_separates():
    """Strongly over-damped with gravity: P settles at m g cos(beta) > 0, so even the force criterion never ends."""
    scene = Scene(model="kelvin-voigt", b=3 * CRITICAL_B, separation="force", gravity=9.81, angle=20.0)
    for method in ("closed", "DOP853-scalar"):
        with pytest.raises(ImpactError, match="P never returns to 0"):
            simulate(scene, SolverOptions(method=method))


@pytest.mark.parametrize("b, separation", [(5.0, "force"), (5.0, "penetration"), (150.0, "force"),
                                           (CRITICAL_B, "force"), (400.0, "force"), (1e4, "force"), (1e6, "force")])
def test_event_formulas_are_the_roots_of_the_solution(b, separation):
    """Without gravity t_m and t_f come from formulas (no root search); each is a root of the solution's own
    delta_dot and of the separation function, found here by Brent's method on the closed form."""
    from scipy.optimize import brentq

    scene = Scene(model="kelvin-voigt", b=b, separation=separation)
    motion = ClosedFormNormal(scene)
    rate = motion.state(motion.t_m)[1]
    assert abs(rate) < 1e-14 * scene.v_normal
    delta_f, rate_f = motion.state(motion.t_f)
    if separation == "force":  # P = k delta + b delta_dot: zero to round-off in its two terms
        assert abs(float(motion.force(motion.t_f))) < 1e-13 * (scene.k * abs(delta_f) + scene.b * abs(rate_f))
        assert float(motion.force(0.999 * motion.t_f)) > 0.0  # the first root, not a later one
        root = brentq(lambda t: float(scene.k * motion.state(t)[0] + scene.b * motion.state(t)[1]),
                      0.5 * motion.t_f, 1.5 * motion.t_f, xtol=1e-300, rtol=8.9e-16)
    else:
        root = brentq(lambda t: float(motion.state(t)[0]), 0.5 * motion.t_f, 1.5 * motion.t_f, xtol=1e-300,
                      rtol=8.9e-16)
    assert motion.t_f == pytest.approx(root, rel=1e-12)


def test_heavily_overdamped_contact_time_is_exact():
    """zeta = 5361 (b = 1e6): t_f = 2 acosh(zeta) / (omega_n sqrt(zeta^2 - 1)) = 5.382 us.  A root search on
    P = k delta + b delta_dot (two large terms) missed it by 1 %, and the integrator by 17 %."""
    scene = Scene(model="kelvin-voigt", b=1e6)
    z, w = scene.zeta, scene.omega_n
    out = simulate(scene)
    assert out.method == "closed"
    assert out.t_f == pytest.approx(2.0 * math.acosh(z) / (w * math.sqrt(z * z - 1.0)), rel=1e-14)
    assert out.t_f == pytest.approx(5.382e-6, rel=1e-3)
    assert out.t_m == pytest.approx(0.5 * out.t_f, rel=1e-14)
