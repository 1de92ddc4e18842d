"""The default path meets its accuracy contract (1e-9 relative on every output) across the input domain,
not only at the chapter's two scenes: a grid over the two dimensionless numbers that fix the modified law's
normal motion, lam = c v_n / (omega_n R) and zeta = b / (2 sqrt(k m)) (k, m, D and speed enter only through
them), both separation criteria, gravity on and off.

Reference: DOP853 at rtol 1e-13 with steps capped at 1/2000 of the undamped half period, so the ramp band
is resolved whatever the error estimate says (tests/test_numerics.py holds this solver to the mpmath Taylor
reference, too slow for a grid here).

Known misses are strict xfails with their measured errors: a fix turns them into failures to remove.
"""

import math

import pytest

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.numerics.reference import relative_errors

#: The grid covers the numerics' whole domain, compressions beyond the radius included (lam 150 at low zeta).
pytestmark = pytest.mark.filterwarnings("ignore::sphereimpact.BeyondRadiusWarning")
TARGET = 1e-9
BASE = Scene()


def scene_for(lam, zeta, **changes):
    """A modified-law normal impact of the chapter's ball with the given lam and zeta (speed and b set)."""
    speed = lam * BASE.omega_n * BASE.radius / BASE.ramp
    return BASE.with_(speed=speed, b=zeta * 2 * math.sqrt(BASE.k * BASE.mass), **changes)


def capped(scene):
    """The reference: DOP853 at rtol 1e-13 with a step cap, in plain floats (scipy's steps bit for bit,
    tests/test_dop853.py; within 1e-12 of scipy's own on this grid); the default path here is the Taylor
    method."""
    return simulate(scene, SolverOptions(method="DOP853-scalar", rtol=1e-13, atol=1e-13,
                                         max_step=math.pi / scene.omega_n / 2000))


#: (lam, zeta, separation) -> why the default path still misses 1e-9 there (measured).
KNOWN = {
    # none today: over-damped, the force criterion's t_f carries 4 zeta^2 x the state's error, and the
    # tolerances are divided by that (sphereimpact.integrators.normal.conditioned_tolerances: zeta = 3 missed by 2e-9
    # to 7e-9 before); where they reach their floor, steps are bounded too (conditioned_step: zeta 30-100
    # missed t_f by up to 2.2e-8 before, with the root on the interpolant), and the root is corrected on
    # the landed state; lam = 20, zeta = 0.01 missed the COR by 2.2e-9 until the restitution restarts with
    # bounded steps also when maximum compression is inside the ramp band.
}


def _case(lam, zeta, separation, gravity):
    why = KNOWN.get((lam, zeta, separation))
    marks = [pytest.mark.xfail(strict=True, reason=why)] if why and gravity == 0 else []
    return pytest.param(lam, zeta, separation, gravity, marks=marks)


#: lam over the accepted k and speed (1e3-1e9 N/m, 0.1-30 m/s) and zeta up to 100, the contract's edge
#: (the force criterion's t_f is the ill-conditioned output there);
#: over-damped under the penetration criterion at zeta 3 up to lam 150 (a creep whose capped reference
#: costs seconds beyond; zeta 1.5-10 and lam 3-1150 measured at 5.7e-10 at worst).
GRID = [_case(lam, zeta, separation, gravity)
        for lam in (0.004, 3.0, 20.0, 75.0, 150.0, 1150.0)  # the chapter ball's k 1e9 at 0.1 m/s .. 1e3 at 30
        for zeta in (0.01, 0.5, 3.0, 10.0, 30.0, 100.0)
        for separation in ("force", "penetration")
        if not (separation == "penetration" and (zeta > 3 or (zeta == 3 and lam > 150)))
        for gravity in (0.0,)] + [_case(75.0, 0.056, separation, 9.80665) for separation in ("force", "penetration")]


@pytest.mark.parametrize("lam, zeta, separation, gravity", GRID)
def test_default_meets_the_contract_across_lam_and_zeta(lam, zeta, separation, gravity):
    scene = scene_for(lam, zeta, separation=separation, gravity=gravity)
    ref = capped(scene)
    got = simulate(scene)
    errors = relative_errors(got.to_dict(), ref.to_dict(), scene)
    assert max(errors.values()) <= TARGET, errors


@pytest.mark.parametrize("angle, speed", [(45.0, 20.0), (0.0, 15.0), (60.0, 30.0)])
def test_scenes_that_missed_before_the_ramp_band_restart(angle, speed):
    """These missed 1e-9 by up to 21x at the default tolerance (the ramp switched off inside one step)."""
    scene = Scene(angle=angle, speed=speed)
    errors = relative_errors(simulate(scene).to_dict(), capped(scene).to_dict(), scene)
    assert max(errors.values()) <= TARGET, errors


def test_error_falls_with_the_tolerance():
    """Convergence is monotone again (before: 6.4e-10 at rtol 1e-9, 2.1e-8 at 1e-10, 2e-12 at 1e-11)."""
    scene = Scene(angle=45.0, speed=20.0)
    ref = capped(scene).to_dict()
    worst = [max(relative_errors(simulate(scene, SolverOptions(rtol=r, atol=r)).to_dict(), ref, scene).values())
             for r in (1e-9, 1e-10, 1e-11)]
    assert worst[0] > worst[1] > worst[2]


@pytest.mark.parametrize("speeds", [(2.3449999999999998, 2.345, 2.3450000000000002),
                                    (2.5256666666666665, 2.525666666666667),
                                    (2.6436666666666664, 2.643666666666667)])
def test_end_of_contact_does_not_flip_on_one_ulp(speeds):
    """Under the force criterion the contact ends where P first returns to 0. The separation function used
    to touch zero again at delta = 0; when one step held both points, a 1-ulp change of speed moved t_f by
    0.7 % (4.856 -> 4.891 ms at 2.345 m/s) and left the force pulling (-0.115 N) before the end."""
    outs = [simulate(Scene(speed=v)) for v in speeds]
    for out in outs:
        assert out.force_min >= -1e-9 * out.force_max  # P never pulls under the force criterion
        assert out.t_f == pytest.approx(outs[0].t_f, rel=1e-9)
        assert out.cor == pytest.approx(outs[0].cor, rel=1e-9)


def test_maximum_compression_found_by_the_band_event_alone():
    """Regression: when maximum compression lies inside the ramp band, the band event (delta_dot there) and
    the maximum-compression event share a root; at 6.6 m/s on the laws study's calibrated eq. 4.2 the band
    event's root came first, stopped the integration, and t_m was reported missing."""
    scene = Scene(speed=6.6, b=10.630341729066144, k=59919.7991439172)
    out = simulate(scene)
    ref = simulate(scene, SolverOptions(method="DOP853", rtol=1e-13, atol=1e-13))
    assert out.t_m == pytest.approx(ref.t_m, rel=1e-9)
    assert abs(out.motion.normal.state(out.t_m)[1]) < 1e-12 * scene.v_normal
    assert max(relative_errors(out.to_dict(), ref.to_dict(), scene).values()) < TARGET


def test_the_rebound_speed_comes_from_a_step_not_from_the_interpolant():
    """Linear Hunt-Crossley is smooth through separation, yet the COR read off the crossing step's
    interpolant erred by 7.4e-10 at the default tolerance, 15x the error on t_f (the interpolant is one order
    lower and its error is not controlled).  The last step is now integrated again to end on t_f: 1.9e-11."""
    scene = Scene(model="linear-hunt-crossley", k=6.0e4, chi=0.05, angle=30.0)
    errors = relative_errors(simulate(scene).to_dict(), capped_law(scene).to_dict(), scene)
    assert errors["cor"] <= 2e-10, errors
    assert max(errors.values()) <= 1e-10, errors


def capped_law(scene):
    """As :func:`capped`, with the cap from the law's own time scale (a law without omega_n)."""
    return simulate(scene, SolverOptions(method="DOP853", rtol=1e-13, atol=1e-13,
                                         max_step=math.pi * scene.time_scale / 2000))
