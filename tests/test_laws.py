"""Contact laws: eq. 4.1 and 4.2 with delta >= 0 as compression, the Hertz family, no force and no overflow outside
contact, parameters declared by each law."""

import numpy as np
import pytest

from sphereimpact import LAWS, Scene


def law_scene(name, **changes):
    """A scene of law ``name`` (a Hertz law needs its stiffness: E* = 10 MPa, a soft rubber)."""
    return Scene(model=name, **({"modulus": 1e7} if LAWS[name].spring == "hertz" else {}), **changes)


def test_kelvin_voigt_jumps_at_contact():
    s = Scene(model="kelvin-voigt")
    assert float(s.force(1e-15, 3.0)) == pytest.approx(s.b * 3.0, rel=1e-9)
    assert float(s.force(1e-3, -1.0)) == pytest.approx(s.k * 1e-3 - s.b, rel=1e-15)


def test_modified_starts_from_zero_and_matches_eq_4_2():
    s = Scene(model="modified")
    assert float(s.force(0.0, 3.0)) == 0.0
    delta, rate = 2e-3, -1.5
    expected = s.k * delta + s.b * rate * (1 - np.exp(-100 * delta / s.radius))
    assert float(s.force(delta, rate)) == pytest.approx(expected, rel=1e-14)
    # slope at first touch: dP/ddelta = k + b v c / R
    h = 1e-12
    assert float(s.force(h, 3.0)) / h == pytest.approx(s.k + s.b * 3.0 * 100 / s.radius, rel=1e-6)


@pytest.mark.parametrize("name", list(LAWS))
def test_no_force_and_no_overflow_outside_contact(name):
    s = law_scene(name)
    with np.errstate(all="raise"):
        p = s.force(np.array([-1e3, -1.0, -1e-9]), np.array([-1e3, 5.0, -2.0]))
    assert np.array_equal(p, np.zeros(3))


def test_registry_declares_the_closed_form_only_where_it_exists():
    assert LAWS["kelvin-voigt"].closed_form == "kelvin-voigt"
    assert all(law.closed_form is None for name, law in LAWS.items() if name != "kelvin-voigt")


def test_ramp_continuation_is_smooth_and_bounded():
    """Past delta = 0 the ramp is its Taylor polynomial: equal to 1 - exp(-u) to 1e-16 for the overshoot of
    one step, bounded far beyond it, and no exponential is evaluated (no overflow warning)."""
    from sphereimpact.laws import ramp_continued

    u = -np.logspace(-8, -2, 25)
    np.testing.assert_allclose(ramp_continued(u), -np.expm1(-u), rtol=1e-15, atol=1e-18)
    with np.errstate(all="raise"):
        far = ramp_continued(np.array([-1e6, -1e300]))
    assert np.all(np.isfinite(far)) and np.all(far == far[0])
    assert float(ramp_continued(0.3)) == -np.expm1(-0.3)


def test_force_during_contact_is_the_one_sided_limit():
    """kelvin-voigt starts at b v_n (the chapter's jump), whatever side of zero round-off puts delta."""
    from sphereimpact import SolverOptions, simulate

    out = simulate(Scene(model="kelvin-voigt", separation="penetration"), SolverOptions(method="closed"))
    scene = out.scene
    assert float(out.motion.force(0.0)) == pytest.approx(scene.b * scene.v_normal, rel=1e-15)
    assert out.force_min == pytest.approx(-scene.b * out.vc_n, rel=1e-12)
