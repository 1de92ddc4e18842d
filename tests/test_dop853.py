"""DOP853 in floats (sphereimpact.ode.dop853) against scipy's DOP853, and the stacked dense output against
OdeSolution: the same algorithm, so the same steps and events up to round-off, and the same dense values
bit for bit."""

import math

import numpy as np
import pytest
from scipy.integrate import OdeSolution, solve_ivp

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.ode.dense import StackedDOP853, fast_solution
from sphereimpact.ode.dop853 import solve

OUTPUTS = ("t_m", "delta_m", "t_f", "vc_t", "vc_n", "ve_t", "omega_f", "cor", "force_max")


def modified(t, z):
    """The chapter's eq. 4.2, dimensionless (zeta 0.056, lam 13), ramp continued as 1 - exp(-u)."""
    x, y = float(z[0]), float(z[1])
    return [y, -(x - 0.11 * y * math.expm1(-13.0 * x))]


def damped(t, z):
    """x'' + 0.2 x' + x = 0 with its running integral: three states, a closed form."""
    return [z[1], -z[0] - 0.2 * z[1], z[0]]


def max_compression(t, z):
    return z[1]


def separation(t, z):
    return z[0]


max_compression.direction = -1
separation.direction, separation.terminal = -1, True


@pytest.mark.parametrize("fun, y0, events", [(modified, [0.0, 1.0], (max_compression, separation)),
                                             (damped, [0.0, 1.0, 0.0], (max_compression,))])
@pytest.mark.parametrize("rtol", [1e-4, 1e-8, 1e-11])
def test_same_steps_states_and_events_as_scipy(fun, y0, events, rtol):
    ref = solve_ivp(fun, (0.0, 30.0), y0, method="DOP853", rtol=rtol, atol=rtol, dense_output=True, events=events)
    got = solve(fun, (0.0, 30.0), y0, rtol, rtol, events=events)
    assert got.status == ref.status and got.nfev == ref.nfev and len(got.t) == len(ref.t)
    # the error estimate is a sum of nearly cancelling terms, so its round-off moves step ends by up to
    # ~1e-8 relative; the solution through them is the same to ~1e-14 (measured: at most 1.3e-14)
    np.testing.assert_allclose(got.t, ref.t, rtol=1e-6, atol=0)
    np.testing.assert_allclose(got.y, ref.sol(got.t), rtol=0, atol=1e-12)
    for mine, theirs, states, their_states in zip(got.t_events, ref.t_events, got.y_events, ref.y_events):
        np.testing.assert_allclose(mine, theirs, rtol=1e-12)
        np.testing.assert_allclose(states, their_states, rtol=0, atol=1e-12)
    t = np.linspace(0.0, ref.t[-1], 777)
    np.testing.assert_allclose(got.sol(t), ref.sol(t), rtol=0, atol=1e-12)


def test_accuracy_against_the_closed_form():
    """x(t) = exp(-0.1 t) sin(w t) / w, w = sqrt(0.99): the dense output within the tolerance's reach."""
    w = math.sqrt(0.99)
    got = solve(damped, (0.0, 20.0), [0.0, 1.0, 0.0], 1e-10, 1e-10)
    t = np.linspace(0.0, 20.0, 501)
    exact = np.exp(-0.1 * t) * np.sin(w * t) / w
    assert got.status == 0 and got.t[-1] == 20.0
    assert np.max(np.abs(got.sol(t)[0] - exact)) < 1e-9


def test_max_step_and_first_step_are_honoured():
    got = solve(damped, (0.0, 10.0), [0.0, 1.0, 0.0], 1e-6, 1e-6, max_step=0.25, first_step=0.01)
    assert np.diff(got.t)[0] == pytest.approx(0.01)
    assert np.max(np.diff(got.t)) <= 0.25 * (1 + 1e-15)


def test_a_blow_up_fails_like_scipy():
    """y' = y^2 from y(0) = 1 blows up at t = 1: both stop there with status -1."""
    def fun(t, y):
        return [y[0] * y[0]]

    ref = solve_ivp(fun, (0.0, 2.0), [1.0], method="DOP853", rtol=1e-8, atol=1e-8)
    got = solve(fun, (0.0, 2.0), [1.0], 1e-8, 1e-8)
    assert got.status == ref.status == -1
    assert got.t[-1] == pytest.approx(1.0, abs=1e-6) and ref.t[-1] == pytest.approx(1.0, abs=1e-6)
    assert "step size" in got.message


def test_stacked_dense_output_is_scipys_to_the_bit():
    ref = solve_ivp(modified, (0.0, 30.0), [0.0, 1.0], method="DOP853", rtol=1e-9, atol=1e-9, dense_output=True,
                    events=(max_compression, separation))
    stacked = fast_solution(ref.sol)
    assert isinstance(stacked, StackedDOP853)
    t = np.concatenate([np.linspace(-0.5, ref.t[-1] + 0.5, 1001), ref.sol.ts])  # outside, inside, on boundaries
    assert np.array_equal(stacked(t), ref.sol(t))
    for instant in t[::37]:
        assert np.array_equal(stacked(instant), ref.sol(instant))
    for size in range(1, 7):  # a few instants take the float path, more the vectorised one: the same bits
        assert np.array_equal(stacked(t[100:100 + size]), ref.sol(t[100:100 + size]))


def test_join_matches_scipys_concatenation_to_the_bit():
    first = solve_ivp(modified, (0.0, 1.0), [0.0, 1.0], method="DOP853", rtol=1e-9, atol=1e-9, dense_output=True)
    later = solve_ivp(modified, (1.0, 3.0), first.y[:, -1], method="DOP853", rtol=1e-9, atol=1e-9, dense_output=True)
    joined = fast_solution(first.sol).join(fast_solution(later.sol))
    scipy = OdeSolution(np.concatenate([first.sol.ts[:-1], later.sol.ts]),
                        first.sol.interpolants + later.sol.interpolants)
    t = np.linspace(0.0, 3.0, 601)
    assert np.array_equal(joined(t), scipy(t))


def test_other_methods_keep_their_own_dense_output():
    ref = solve_ivp(modified, (0.0, 1.0), [0.0, 1.0], method="RK45", dense_output=True)
    assert fast_solution(ref.sol) is ref.sol


@pytest.mark.parametrize("scene", [
    Scene(angle=0.0), Scene(angle=30.0), Scene(angle=60.0, model="kelvin-voigt"),
    Scene(angle=45.0, speed=20.0), Scene(angle=20.0, gravity=9.81),
    Scene(angle=30.0, model="hunt-crossley", modulus=1e7, chi=0.05),
    Scene(angle=30.0, model="hertz", modulus=1e7, separation="penetration"),
], ids=["0deg", "30deg", "kv-60deg", "45deg-20ms", "gravity", "hunt-crossley", "hertz"])
def test_simulate_gives_scipys_answer(scene):
    """DOP853-scalar (the default integrator) and scipy's DOP853 agree to round-off on every output."""
    fast = simulate(scene, SolverOptions(method="DOP853-scalar"))
    ref = simulate(scene, SolverOptions(method="DOP853"))
    assert fast.method == "DOP853-scalar" and ref.method == "DOP853" and fast.nfev == ref.nfev
    for key in OUTPUTS:  # abs: ve_t = vc_t - omega R cancels two O(1 m/s) terms (rolling: 2.7e-5 m/s left)
        assert getattr(fast, key) == pytest.approx(getattr(ref, key), rel=1e-12, abs=1e-14), key
    assert fast.regime == ref.regime


def test_planar_body_runs_it_as_scipys_dop853():
    out = simulate(Scene(angle=60.0), body="planar")
    assert out.method == "DOP853"
    assert out.cor == pytest.approx(simulate(Scene(angle=60.0)).cor, rel=1e-8)


def test_the_tableau_written_out_is_scipys_to_the_bit():
    """ode.dop853_tableau holds DOP853's coefficients so that no integrator imports scipy.integrate for them."""
    from scipy.integrate import DOP853

    from sphereimpact.ode import dop853_tableau as written

    assert written.N_STAGES == DOP853.n_stages and written.ERROR_ESTIMATOR_ORDER == DOP853.error_estimator_order
    for name in ("A", "C", "B", "E3", "E5", "A_EXTRA", "C_EXTRA", "D"):
        ours, theirs = np.array(getattr(written, name)), getattr(DOP853, name)
        assert ours.shape == theirs.shape and np.array_equal(ours, theirs), name
