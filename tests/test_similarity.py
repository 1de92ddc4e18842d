"""The one-ball interpolant in lam and the family interpolant of kernel-less laws: tension onset, accuracy
between nodes, fallback, shards."""

import numpy as np
import pandas as pd
import pytest

from sphereimpact import Scene
from sphereimpact.contact.separation import Separation
from sphereimpact.sweep import batch, similarity
from sphereimpact.sweep.engine import grid, sweep

ZETA = Scene().zeta
LAM_MIN, LAM_MAX = 0.05, 150.0  # the chapter's ball from 0.01 to 30 m/s normal speed


def solve(lam, separation=Separation.FORCE, target=1e-12):
    lam = np.atleast_1d(np.asarray(lam, float))
    return batch.integrate(np.full(lam.size, ZETA), lam, np.zeros(lam.size), np.ones(lam.size, bool), separation,
                           target)


@pytest.fixture(scope="module")
def interpolant():
    return similarity.LambdaInterpolant(ZETA, LAM_MIN, LAM_MAX, Separation.FORCE, 1e-8)


def test_tension_onset_is_where_the_exit_force_ratio_vanishes(interpolant):
    """At u*, G = 1 + 2 zeta lam y_f = 0 (solved directly); just below it the force criterion ends at
    delta = 0 like the penetration criterion, just above it at P = 0, before delta = 0."""
    (cut,) = interpolant.cuts
    lam_star = np.exp(cut)
    y_f = solve(lam_star, Separation.PENETRATION)["y_f"][0]
    assert abs(1 + 2 * ZETA * lam_star * y_f) < 1e-9
    below, above = solve(lam_star * (1 - 1e-4)), solve(lam_star * (1 + 1e-4))
    pen_below = solve(lam_star * (1 - 1e-4), Separation.PENETRATION)
    pen_above = solve(lam_star * (1 + 1e-4), Separation.PENETRATION)
    assert below["tau_f"][0] == pytest.approx(pen_below["tau_f"][0], abs=1e-12)
    assert above["tau_f"][0] < pen_above["tau_f"][0] - 1e-9


@pytest.mark.parametrize("separation", list(Separation))
@pytest.mark.parametrize("lam_range, cuts", [((LAM_MIN, LAM_MAX), 1), ((LAM_MIN, 5.0), 0), ((20.0, LAM_MAX), 0)],
                         ids=["across the onset", "no tension", "tension throughout"])
def test_interpolant_matches_direct_solves_between_nodes(separation, lam_range, cuts):
    interp = similarity.LambdaInterpolant(ZETA, *lam_range, separation, 1e-8)
    assert interp.cuts.size == cuts
    lam = np.exp(np.random.default_rng(5).uniform(*np.log(lam_range), 40))
    got, ref = interp(lam), solve(lam, separation)
    assert similarity._errors(got, ref, similarity.NORMAL_OUTPUTS) < 1e-9


def test_failed_check_falls_back_to_integration(monkeypatch):
    """With too few nodes allowed the interpolant refuses, and the engine integrates each scene instead."""
    scenes = grid(angle=np.arange(0, 90, 3.0), speed=np.arange(0.5, 30.01, 0.5))
    monkeypatch.setattr(similarity, "FIRST_NODES", 3)
    monkeypatch.setattr(similarity, "MAX_NODES", 5)
    with pytest.raises(similarity.InterpolationError, match="did not reach"):
        similarity.LambdaInterpolant(ZETA, LAM_MIN, LAM_MAX, Separation.FORCE, 1e-8)
    monkeypatch.setattr("sphereimpact.sweep.paths.SIMILARITY_MIN", 100)
    fallback = sweep(scenes, outputs=["cor"], chapter_ball=True)
    monkeypatch.undo()
    direct = sweep(scenes, outputs=["cor"], chapter_ball=True)  # 1800 scenes: below SIMILARITY_MIN, integrated directly
    assert np.array_equal(fallback["cor"].to_numpy(), direct["cor"].to_numpy())


LAW_BALLS = {"linear-hunt-crossley": Scene(model="linear-hunt-crossley", k=6.0e4, chi=0.05),
             "hunt-crossley": Scene(model="hunt-crossley", k=8.8e5, chi=0.05)}


@pytest.mark.parametrize("separation", list(Separation))
@pytest.mark.parametrize("model", LAW_BALLS)
def test_family_interpolant_matches_direct_solves_between_nodes(model, separation):
    """A law without a batched kernel, interpolated in chi v_n over the chapter ball's 0.5-30 m/s: against
    the single-impact integrator at random chi v_n, in the sweep's error measure."""
    from sphereimpact import SolverOptions

    ball = LAW_BALLS[model]
    lo, hi = 0.05 * 0.5, 0.05 * 30.0
    interp = similarity.FamilyInterpolant(ball, lo, hi, separation, 1e-8)
    q = np.exp(np.random.default_rng(8).uniform(np.log(lo), np.log(hi), 12))
    tight = SolverOptions(rtol=1e-12, atol=1e-12)
    rows = [similarity.dimensionless_motion(ball.with_(speed=ball.speed * x / ball.family["chi_v"],
                                                       separation=separation), tight) for x in q]
    ref = {k: np.array([row[k] for row in rows]) for k in similarity.NORMAL_OUTPUTS}
    assert similarity._errors(interp(q), ref, similarity.NORMAL_OUTPUTS) < 1e-9
    assert interp.nodes <= 129


def test_family_interpolant_needs_a_number_proportional_to_the_speed():
    """kelvin-voigt's family (zeta) does not move with the speed: no interpolant, the sweep solves per family."""
    with pytest.raises(similarity.InterpolationError, match="not proportional to the approach speed"):
        similarity.FamilyInterpolant(Scene(model="kelvin-voigt"), 0.01, 0.1, Separation.FORCE, 1e-8)


@pytest.mark.filterwarnings("ignore::sphereimpact.BeyondRadiusWarning")  # 30 m/s compresses past R here
def test_family_interpolated_sweep_keeps_shards_equal_and_meets_the_contract(monkeypatch):
    from sphereimpact import SolverOptions, simulate
    from sphereimpact.numerics.reference import relative_errors
    from sphereimpact.sweep import engine, paths

    scenes = grid(angle=np.arange(0, 90, 3.0), speed=np.arange(0.5, 30.01, 2.0)).assign(
        model="linear-hunt-crossley", k=6.0e4, chi=0.05)
    built = []
    monkeypatch.setattr(paths, "FamilyInterpolant", lambda *a, **k: built.append(a) or similarity.FamilyInterpolant(*a, **k))
    whole = sweep(scenes, chapter_ball=True)
    assert len(built) == 1  # 450 distinct chi v_n >= FAMILY_MIN: one interpolant
    shards = [sweep(scenes.iloc[i], span=scenes, chapter_ball=True) for i in np.array_split(np.arange(len(scenes)), 3)]
    assert pd.concat(shards, ignore_index=True).equals(whole)
    keys = ["t_m", "delta_m", "t_f", "cor", "omega_f", "ve_t"]
    for row in whole.iloc[::37].to_dict("records"):
        scene = engine.scene_of({k: row[k] for k in engine.SCENE_COLUMNS})
        ref = simulate(scene, SolverOptions(rtol=1e-12, atol=1e-12)).to_dict()
        assert max(relative_errors(row, ref, scene, keys).values()) <= 1e-8


@pytest.mark.filterwarnings("ignore::sphereimpact.BeyondRadiusWarning")
@pytest.mark.parametrize("model", LAW_BALLS)
def test_random_balls_of_a_kernel_less_law_meet_the_contract(model, monkeypatch):
    """k, m, chi, speed and angle drawn per scene: chi v_n is the law's one varying number, so 500 random
    balls share one interpolant per criterion (checked to be built), and a sample meets 1e-8 against
    simulate."""
    from sphereimpact import SolverOptions, simulate
    from sphereimpact.numerics.reference import relative_errors
    from sphereimpact.sweep import engine, paths

    rng = np.random.default_rng(11)
    n = 500
    k = rng.uniform(2e4, 2e5, n) if model == "linear-hunt-crossley" else rng.uniform(2e5, 2e6, n)
    scenes = pd.DataFrame({"model": model, "k": k, "chi": rng.uniform(0.01, 0.2, n),
                           "mass": rng.uniform(0.05, 0.5, n), "speed": rng.uniform(0.5, 20, n),
                           "angle": rng.uniform(0, 85, n), "separation": rng.choice(["force", "penetration"], n)})
    built = []
    monkeypatch.setattr(paths, "FamilyInterpolant", lambda *a, **k: built.append(a) or similarity.FamilyInterpolant(*a, **k))
    table = sweep(scenes, chapter_ball=True)
    assert len(built) == 2
    keys = ["t_m", "delta_m", "t_f", "cor", "omega_f", "ve_t"]
    for row in table.iloc[::25].to_dict("records"):
        scene = engine.scene_of({c: row[c] for c in engine.SCENE_COLUMNS})
        ref = simulate(scene, SolverOptions(rtol=1e-12, atol=1e-12)).to_dict()
        assert max(relative_errors(row, ref, scene, keys).values()) <= 1e-8, row


def test_the_grip_resolution_solves_the_fits_first_nodes_once_and_profiles_its_three(monkeypatch):
    """With batched lanes the grip tables' resolution solves the first nodes of the fit that follows, which the fit then
    finds solved (no lane is integrated twice), and profiles only its end and middle nodes (the others' levels NaN):
    their grip instants are those of every node profiled, to the bit."""
    from sphereimpact.sweep import series_lanes

    calls = []
    integrate = series_lanes.integrate
    monkeypatch.setattr(series_lanes, "integrate", lambda lam_zeta, lam, *a, **k: calls.append(
        (np.asarray(lam).tobytes(), bool(k.get("partial")))) or integrate(lam_zeta, lam, *a, **k))
    interp = similarity.LambdaInterpolant(ZETA, LAM_MIN, LAM_MAX, Separation.FORCE, 1e-8, extremes=True, grips=True)
    whole = [np.frombuffer(lam) for lam, partial in calls if not partial]
    nodes = set(np.exp(np.concatenate([piece.series.nodes for piece in interp.pieces])).tolist())
    assert len(whole) >= 2 and all(set(lam.tolist()) <= nodes for lam in whole)  # the fits' nodes alone
    assert len({lam.tobytes() for lam in whole}) == len(whole)  # each solve once (a piece's, at its criterion)
    stretch, n = interp.pieces[0].tables[0][0], 17
    u = similarity.lobatto(np.log(LAM_MIN), np.log(LAM_MAX), 33)
    lam = np.exp(u)
    steps = integrate(np.full(u.size, ZETA), lam, Separation.PENETRATION, 1e-10, extremes=True, keep_steps=True)
    levels = (1.0 - steps["y_f"])[:, None] * stretch.nodes(n)[None, :]
    every = steps["steps"].instants(levels)
    some = levels.copy()
    some[1:-1] = np.nan
    some[16] = levels[16]
    three = steps["steps"].instants(some)
    assert np.array_equal(three[[0, 16, 32]], every[[0, 16, 32]]) and np.isnan(three[1]).all()


def test_the_runge_kutta_lanes_profile_only_the_resolutions_three_nodes(monkeypatch):
    """Where the Taylor lanes do not reach (zeta 2 up to lam 150), the grip profiles are Runge-Kutta lanes stopping at
    each level: the resolution's rounds solve its three profiled nodes' lanes alone, none for a node left out (a NaN
    level), and the tables are built all the same."""
    from sphereimpact.sweep import series_lanes

    assert not series_lanes.covers(2.0, 150.0)
    calls = []
    integrate = batch.integrate

    def spy(zeta, lam, *args, **kwargs):
        if kwargs.get("levels") is not None:  # a grip profile's lanes, each stopping at its level
            calls.append((np.unique(lam).size, np.asarray(kwargs["levels"], dtype=float)))
        return integrate(zeta, lam, *args, **kwargs)

    monkeypatch.setattr(batch, "integrate", spy)
    interp = similarity.LambdaInterpolant(2.0, 0.05, 150.0, Separation.FORCE, 1e-8, extremes=True, grips=True)
    assert all(piece.tables for piece in interp.pieces)
    assert calls and all(np.isfinite(levels).all() for _, levels in calls)
    assert any(nodes == 3 for nodes, _ in calls)
