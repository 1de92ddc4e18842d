"""Shared helpers for the tests."""

import math

from sphereimpact import SolverOptions
from sphereimpact.numerics.reference import output_scales

#: Tight options for comparisons at the 1e-9 level.
TIGHT = SolverOptions(method="DOP853", rtol=1e-12, atol=1e-14)


def assert_outputs_close(got, ref, rtol: float) -> None:
    """Every physical output of ``got`` within ``rtol`` of ``ref`` (relative to the output's scale)."""
    scales = output_scales(ref.scene, ref.t_f, ref.delta_m, ref.force_max)
    assert got.regime == ref.regime
    assert (got.t_roll is None) == (ref.t_roll is None)
    for key, scale in scales.items():
        a, b = getattr(got, key), getattr(ref, key)
        if a is None:
            continue
        assert math.isfinite(a), key
        assert abs(a - b) <= rtol * max(abs(b), scale), f"{key}: {a!r} vs {b!r}"



def pytest_collection_modifyitems(items):
    """The pipeline tests first: run in parallel by file (pyproject's ``-n 2 --dist loadfile``), their
    long module fixture (the test pipeline) then overlaps the unit tests on the other worker."""
    items.sort(key=lambda item: item.path.name != "test_workflow.py")
