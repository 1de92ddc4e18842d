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
