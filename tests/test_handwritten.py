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


def test_time_split_and_profile_tables():
    """The bench's 'where the time goes' tables: every stage of every scene, simulate's share 1, and a
    profile whose top functions include the integrator (what is measured, not how fast: no timing is
    asserted)."""
    from sphereimpact.numerics.bench import profile_call, stages

    scenes = {"oblique/modified": Scene(angle=60.0), "oblique/kelvin-voigt": Scene(angle=60.0, model="kelvin-voigt")}
    table = stages(scenes, repeats=1)
    assert sorted(table.groupby("scene").stage.apply(tuple).apply(sorted).iloc[0]) == sorted(
        ("build", "copy", "normal", "tangential", "outcome", "simulate", "handwritten"))
    assert len(table) == 14 and (table.time > 0).all() and (table.batch >= 10).all()
    assert table[table.stage == "simulate"].share.tolist() == [1.0, 1.0]
    profile = profile_call(Scene(angle=60.0), calls=5, top=8)
    assert len(profile) == 8 and profile.own_us.is_monotonic_decreasing
    assert (profile.share > 0).all() and profile.share.sum() <= 1.0
    # auto integrates eq. 4.2 by its series: in Python floats, or by its compiled loop in a process that has loaded it
    # (a test before this one in the same process may have)
    assert profile.function.str.contains(r"series\.py|taylor_kernel\.py").any()


@pytest.mark.parametrize("seconds, calls", [(2e-3, 10), (1e-4, 100), (3e-4, 34), (0.0, 1000)])
def test_a_timed_run_lasts_at_least_min_run(monkeypatch, seconds, calls):
    """A contender quicker than MIN_RUN for BATCH calls is run in batches that long (at most MAX_BATCH calls): a
    call that advances a fake clock by ``seconds`` gets ``calls`` per run (ceil(10 ms / seconds), at least 10)."""
    from sphereimpact.numerics import timing

    clock = [0.0]
    monkeypatch.setattr(timing.time, "perf_counter", lambda: clock[0])

    def call():
        clock[0] += seconds

    assert (timing.BATCH, timing.MIN_RUN, timing.MAX_BATCH) == (10, 0.01, 1000)
    assert timing.batch_size(call) == calls
