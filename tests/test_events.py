"""Event location helpers against scipy: the plain-float Brent minimiser takes scipy's steps, and the Brent root
finder finds scipy's roots in as many evaluations."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from sphereimpact.ode.events import extremum, minimise

FUNCTIONS = {
    "smooth": (lambda t: -math.sin(t), 1.2, 1.9),
    "quartic": (lambda t: (t - 0.3) ** 4 + 0.1 * t, -1.0, 2.0),
    "edge": (lambda t: t * t, 0.5, 3.0),  # minimum at the left end
    "kink": (lambda t: abs(t - 0.77), 0.0, 1.0),
    "flat": (lambda t: 1.0, 0.0, 1.0),
    "force-like": (lambda t: -(math.exp(-3 * t) * math.sin(7 * t)), 0.0, 0.5),
}


@pytest.mark.parametrize("name", FUNCTIONS)
@pytest.mark.parametrize("xatol", [1e-5, 1e-14])
def test_minimise_takes_scipys_steps(name, xatol):
    f, a, b = FUNCTIONS[name]
    ours, theirs = [], []
    x, fx = minimise(lambda t, _: ours.append(t) or f(t), None, a, b, xatol)
    res = minimize_scalar(lambda t: theirs.append(float(t)) or f(t), bounds=(a, b), method="bounded",
                          options={"xatol": xatol})
    assert ours == theirs and x == float(res.x) and fx == float(res.fun)


def test_minimise_stops_after_maxfun_evaluations_as_scipy_does():
    ours, theirs = [], []
    minimise(lambda t, _: ours.append(t) or math.sin(1 / (t + 1e-3)), None, 0.0, 1.0, 1e-300, maxfun=5)
    minimize_scalar(lambda t: theirs.append(float(t)) or math.sin(1 / (t + 1e-3)), bounds=(0.0, 1.0),
                    method="bounded", options={"xatol": 1e-300, "maxiter": 5})
    assert len(ours) == 5 and ours == theirs


def test_extremum_refines_the_peak_of_a_sampled_function():
    """A peak between grid points is found to the function's round-off (value) and ~1e-8 in t."""
    grid = np.linspace(0.0, 1.0, 11)
    t, value = extremum(lambda t: np.sin(3 * np.asarray(t)), grid, "max")
    assert value == pytest.approx(1.0, abs=1e-15) and t == pytest.approx(math.pi / 6, abs=1e-7)
    t, value = extremum(lambda t: np.sin(3 * np.asarray(t)), grid, "min")
    assert (t, value) == (0.0, 0.0)  # the end point


def test_an_extremum_inside_an_end_interval_is_found():
    """f = (1 - t)(20 (1 - t) - 1) dips to -1/80 at t = 0.975, inside the last interval of the grid, with its
    best sample at the end point (f = 0): the end interval is refined because f just inside it is below both
    of its samples (before, the end point's 0 was returned, as simulate's force_min was for a brief pull
    just before delta returns to 0)."""
    from sphereimpact.ode.events import extremum

    def f(t):
        return (1.0 - t) * (20.0 * (1.0 - t) - 1.0)

    grid = [0.0, 0.5, 1.0]
    t, value = extremum(f, grid, "min")
    assert t == pytest.approx(0.975, abs=1e-7) and value == pytest.approx(-1.0 / 80.0, rel=1e-12)
    t, value = extremum(lambda x: -f(1.0 - x), grid, "max")  # mirrored: a peak inside the first interval
    assert t == pytest.approx(0.025, abs=1e-7) and value == pytest.approx(1.0 / 80.0, rel=1e-12)
    calls = []
    extremum(lambda x: calls.append(x) or x * x, [0.0, 0.5, 1.0], "max")  # monotone into its end: no search
    assert len(calls) <= 5


def test_a_root_inside_the_last_interval_is_found():
    """f = (1 - t)(20 (1 - t) - 1) crosses 0 at t = 0.95 and returns to 0 at the end, both inside the last
    grid interval, whose samples are positive and zero: the root at 0.95 is found from f just inside the end
    (before, none was, and a force's brief pull just before delta returns to 0 counted as pushing: simulate's
    friction impulse J+ 1e-6 off, found by the sweep's differential test)."""
    from sphereimpact.ode.events import roots

    def f(t):
        return (1.0 - np.asarray(t, dtype=float)) * (20.0 * (1.0 - np.asarray(t, dtype=float)) - 1.0)

    found = roots(f, [0.0, 0.5, 1.0])
    assert found[0] == pytest.approx(0.95, rel=1e-14) and found[-1] == 1.0
    assert roots(f, [0.0, 0.5, 1.0], direction=-1)[0] == pytest.approx(0.95, rel=1e-14)  # the downward one
    assert roots(lambda t: 1.0 - np.asarray(t, dtype=float), [0.0, 0.5, 1.0]) == [1.0]  # no dip: the end


def test_a_brief_pull_inside_the_last_step_leaves_the_friction_impulse_exact():
    """The scene the differential test found: eq. 4.2 under the penetration criterion, the pull before delta
    returns to 0 inside the last step at rtol 1e-10 and 1e-12 but not at 1e-13; every tolerance now gives the
    same sliding ball, as the planar body does."""
    from sphereimpact import Scene, SolverOptions, simulate

    scene = Scene(mass=0.436573, diameter=0.227728, inertia_factor=0.5969, mu=0.022844, k=37495.384737,
                  b=86.381474, ramp=27.778466, separation="penetration", speed=3.664594, angle=30.934473)
    outs = [simulate(scene, SolverOptions(rtol=tol, atol=tol)) for tol in (1e-10, 1e-12, 1e-13)]
    planar = simulate(scene, SolverOptions(method="DOP853", rtol=1e-12, atol=1e-12), body="planar")
    for out in outs:
        assert out.force_min < 0 and out.ve_t == pytest.approx(planar.ve_t, rel=1e-9)


ROOT_FUNCTIONS = {  # (f, its root, a bracket)
    "linear": (lambda x: 2.0 * x - 1.0, 0.5, (-3.0, 4.0)),
    "steep": (lambda x: math.tanh(40.0 * (x - 0.3)), 0.3, (-1.0, 2.0)),
    "exponential": (lambda x: math.exp(x) - 5.0, math.log(5.0), (0.0, 10.0)),
    "cubic": (lambda x: (x - 1.25) * (1.0 + x * x), 1.25, (2.0, -1.0)),
    "tiny": (lambda x: x - 3e-200, 3e-200, (0.0, 1.0)),
    "cos": (lambda x: math.cos(x), 0.5 * math.pi, (1.0, 2.0)),
}


@pytest.mark.parametrize("name", ROOT_FUNCTIONS)
def test_brent_finds_the_root_to_its_tolerance_in_as_few_evaluations_as_scipy(name):
    """The package's Brent root finder (every scalar root search: events, calibrations) against the closed-form root
    to its tolerance (xtol + rtol |x|, as scipy.optimize.brentq documents it), and against scipy's brentq: the same
    root to that tolerance, in at most two evaluations more."""
    from scipy.optimize import brentq

    from sphereimpact.ode.roots import brent

    f, root, (a, b) = ROOT_FUNCTIONS[name]
    calls = {"ours": 0, "scipy": 0}

    def counted(who):
        def g(x):
            calls[who] += 1
            return f(x)
        return g

    eps = np.finfo(float).eps
    for xtol, rtol in ((1e-300, 4 * eps), (1e-6, 4 * eps), (1e-15, 1e-10)):
        calls.update(ours=0, scipy=0)
        ours = brent(counted("ours"), a, b, xtol=xtol, rtol=rtol)
        theirs = brentq(counted("scipy"), a, b, xtol=xtol, rtol=rtol)
        tol = xtol + rtol * abs(root) + 4 * eps * abs(root)  # and f's own round-off near the root
        assert abs(ours - root) <= tol and abs(ours - theirs) <= 2 * tol, (xtol, rtol, ours, theirs)
        assert calls["ours"] <= calls["scipy"] + 2, (xtol, rtol, calls)


def test_brent_refuses_a_bracket_without_a_sign_change_and_says_when_it_stops_short():
    from sphereimpact.ode.roots import brent

    with pytest.raises(ValueError, match="must be finite and of opposite signs"):
        brent(lambda x: x * x + 1.0, -1.0, 1.0, xtol=1e-12, rtol=1e-12)
    with pytest.raises(ValueError, match="must be finite and of opposite signs"):
        brent(lambda x: math.nan if x > 0 else -1.0, -1.0, 1.0, xtol=1e-12, rtol=1e-12)
    assert brent(lambda x: x, 0.0, 1.0, xtol=1e-12, rtol=1e-12) == 0.0  # an end that is a root
    with pytest.raises(RuntimeError, match="no convergence in 3 iterations"):
        brent(lambda x: (x - 0.123456789) ** 3, 0.0, 1.0, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=3)
    last = brent(lambda x: (x - 0.123456789) ** 3, 0.0, 1.0, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=3,
                 strict=False)
    assert 0.0 < last < 1.0  # the best point so far, as the events' search takes it
