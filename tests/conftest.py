"""Shared helpers for the tests."""

import math

import pytest

from sphereimpact import Scene, SolverOptions

#: Tight options for comparisons at the 1e-9 level.
TIGHT = SolverOptions(method="DOP853", rtol=1e-12, atol=1e-14)


def output_scales(scene: Scene, reference) -> dict:
    """Natural size of each numeric output, so that an output that is exactly zero in one
    model (a rolling ball's ve_t, a normal impact's spin) is compared on the scale of the impact."""
    v = scene.speed
    return {"t_m": reference.t_f, "t_f": reference.t_f, "t_roll": reference.t_f,
            "delta_m": reference.delta_m, "vc_t": v, "vc_n": v, "ve_t": v, "ve_n": v, "cor": 1.0,
            "omega_f": v / scene.radius,
            "force_min": reference.force_max, "force_max": reference.force_max}


def assert_outputs_close(got, ref, rtol: float) -> None:
    """Every physical output of ``got`` within ``rtol`` of ``ref`` (relative to the output's scale)."""
    scales = output_scales(ref.scene, ref)
    assert got.regime == ref.regime
    assert (got.t_roll is None) == (ref.t_roll is None)
    for key, scale in scales.items():
        a, b = getattr(got, key), getattr(ref, key)
        if a is None:
            continue
        assert math.isfinite(a), key
        assert abs(a - b) <= rtol * max(abs(b), scale), f"{key}: {a!r} vs {b!r}"


@pytest.fixture
def tight():
    return TIGHT
