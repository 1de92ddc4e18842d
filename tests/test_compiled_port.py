"""The microslip contact's speed baseline, the compiled port (sphereimpact.numerics.compiled_port), against
``simulate``: a second method for the normal motion the march reads (fixed-step RK4 on the march's own steps,
against the package's adaptive DOP853 and its samples), so agreement checks the package's sampling as much as the
port; and its row in the bench table."""

import math

import pytest

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.numerics.bench import microslip_bench
from sphereimpact.numerics.compiled_port import compiled_port, port_numbers

from test_microslip import ALUMINA, ELASTIC

#: RK4's error on 384 steps and the adaptive integrator's at rtol 1e-10, in e_t (over v_t) and in spin (relative):
#: measured up to 9e-7 (spin, at 1 degree, where the spin is smallest).
AGREEMENT = 2e-6


def _port(scene: Scene):
    out = simulate(scene)
    row = out.motion.tangential
    v_t, omega, _ = compiled_port(*port_numbers(scene, row.elements, row.time_steps))
    return out, v_t, omega


@pytest.mark.parametrize("ball", [ALUMINA, ELASTIC], ids=["hunt-crossley", "hertz"])
@pytest.mark.parametrize("angle", [1.0, 8.0, 30.0, 85.0])
@pytest.mark.parametrize("speed", [1.0, 7.0])
def test_the_port_gives_simulates_microslip_answer_across_the_domain(ball, angle, speed):
    scene = Scene(angle=angle, **{**ball, "speed": speed})
    out, v_t, omega = _port(scene)
    assert abs(v_t - out.vc_t) / scene.v_tangent < AGREEMENT
    assert abs(omega - out.omega_f) / abs(out.omega_f) < AGREEMENT


def test_the_port_refuses_what_it_does_not_solve():
    with pytest.raises(ValueError, match="law hunt-crossley or hertz on the flat; got law 'modified', "
                                         "tangential 'rigid', gravity 0 m/s\\^2"):
        port_numbers(Scene(angle=30.0), 128, 384)
    with pytest.raises(ValueError, match="gravity 9.81 m/s\\^2"):
        port_numbers(Scene(angle=30.0, gravity=9.81, **ALUMINA), 128, 384)


def test_the_bench_times_the_port_beside_the_impact_with_both_errors():
    scene = Scene(angle=10.0, **ALUMINA)
    table = microslip_bench(scene, (256, 1536), repeats=1).set_index("contender")
    impact, port = table.loc["simulate"], table.loc["compiled port (numba: RK4 normal motion, the same march)"]
    ref = simulate(scene, SolverOptions(settings={"elements": 256, "time_steps": 1536}))
    out = simulate(scene)
    assert impact["error"] == max(abs(out.vc_t - ref.vc_t) / scene.v_tangent, abs(out.omega_f / ref.omega_f - 1.0))
    assert abs(port["error"] - impact["error"]) < AGREEMENT and port["error"] > 10 * AGREEMENT  # the resolution's
    assert port["time_ratio"] == pytest.approx(port["time"] / impact["time"], rel=1e-12)
    assert port["method"] == "RK4" and math.isnan(port["rtol"]) and port["nfev"] > 4 * 384
