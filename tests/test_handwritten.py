"""The hand-written baseline of the benchmarks is a correct solver: it meets its tolerance against the
closed form and the package's tight solution, so speed-ups against it are at equal accuracy."""

import pytest

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.numerics.handwritten import handwritten
from sphereimpact.numerics.reference import worst_error


@pytest.mark.parametrize("model", ["kelvin-voigt", "modified"])
@pytest.mark.parametrize("angle, speed", [(0.0, 3.0), (60.0, 3.0), (30.0, 0.5), (10.0, 12.0)])
@pytest.mark.parametrize("rtol", [1e-8, 1e-11])
def test_baseline_meets_its_tolerance(model, angle, speed, rtol):
    scene = Scene(angle=angle, speed=speed, model=model)
    exact = simulate(scene, SolverOptions(method="closed") if model == "kelvin-voigt"
                     else SolverOptions(rtol=1e-13, atol=1e-13))
    assert worst_error(handwritten(scene, rtol), exact.to_dict(), scene) < 30 * rtol


def test_baseline_refuses_what_it_does_not_cover():
    with pytest.raises(ValueError, match="without gravity"):
        handwritten(Scene(gravity=9.81), 1e-8)


@pytest.mark.parametrize("model, params", [("linear-hunt-crossley", {"chi": 0.05}), ("hertz", {"k": 8.8e5}),
                                           ("hunt-crossley", {"k": 8.8e5, "chi": 0.05})])
@pytest.mark.parametrize("angle, speed", [(0.0, 3.0), (60.0, 3.0), (30.0, 20.0)])
def test_baseline_of_the_other_laws_meets_its_tolerance(model, params, angle, speed):
    """For laws beyond the chapter's the baseline types the law's scalar formula; against the package at
    rtol 1e-13, and elastic Hertz against its closed-form contact time."""
    scene = Scene(angle=angle, speed=speed, model=model, **params)
    exact = simulate(scene, SolverOptions(rtol=1e-13, atol=1e-13))
    got = handwritten(scene, 1e-10)
    assert worst_error(got, exact.to_dict(), scene) < 30 * 1e-10
    if model == "hertz":
        from scipy.special import beta

        assert got["t_f"] == pytest.approx(0.8 * beta(0.4, 0.5) / scene.frequency, rel=1e-9)
