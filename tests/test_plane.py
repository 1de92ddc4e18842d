"""The (zeta, lam) plane: eq. 4.2's normal outputs for sweeps of many balls, against direct solves (the
Runge-Kutta lanes at 1e-12), its refusals and fallbacks, batch independence, and the engine's use of it."""

import numpy as np
import pandas as pd
import pytest

from sphereimpact import SolverOptions, simulate
from sphereimpact.contact.separation import Separation
from sphereimpact.impact.outcome import NUMERIC_OUTPUTS
from sphereimpact.numerics.reference import relative_errors
from sphereimpact.sweep import batch, chebyshev, engine, paths, plane, series_lanes, similarity
from sphereimpact.sweep.engine import sweep
from sphereimpact.sweep.outputs import NORMAL_OUTPUTS as OUTPUTS
from sphereimpact.sweep.similarity import InterpolationError, _errors

KEYS = [k for k in engine.SWEEP_OUTPUTS if k in NUMERIC_OUTPUTS]
#: The random-ball benchmark's rectangle (k 2e4-2e5 N/m, b 2-30 N s/m, m 0.05-0.5 kg, 0.5-30 m/s, 0-89 deg).
BALLS = (0.00335, 0.3707, 0.0791, 383.3)


def direct(zeta, lam, separation):
    return batch.integrate(zeta, lam, np.zeros(zeta.size), np.ones(zeta.size, bool), separation, 1e-12)


def inside(rectangle, n, seed):
    rng = np.random.default_rng(seed)
    zeta_lo, zeta_hi, lam_lo, lam_hi = rectangle
    return rng.uniform(zeta_lo, zeta_hi, n), np.exp(rng.uniform(np.log(lam_lo), np.log(lam_hi), n))


@pytest.mark.parametrize("separation", list(Separation))
@pytest.mark.parametrize("rectangle", [BALLS, (0.05, 0.06, 1.0, 10.0), (0.01, 0.5, 1e-3, 1e4), (1e-4, 0.01, 10.0, 1e6)],
                         ids=["random balls", "narrow, across the onset", "up to its largest zeta", "light damping"])
def test_plane_meets_the_target_between_its_nodes(separation, rectangle):
    """Against the Runge-Kutta lanes where they hold (lam <= 1e4), else the Taylor lanes at 1e-12 (checked
    against scipy's DOP853 up to lam = 1e6 in test_series_lanes.py)."""
    interpolant = plane.PlaneInterpolant(*rectangle, separation, 1e-8)
    zeta, lam = inside(rectangle, 400, seed=1)
    ref = direct(zeta, lam, separation) if rectangle[3] <= 1e4 else series_lanes.integrate(zeta, lam, separation, 1e-12)
    assert _errors(interpolant(zeta, lam), ref, OUTPUTS) < 1e-8


@pytest.mark.parametrize("zeta", [0.005, 0.05, 0.2, 0.5, 0.9])
def test_the_onset_estimate_is_within_five_percent_and_the_edge_below_the_onset(zeta):
    """v* = log(2 zeta lam*) where the force first pulls before delta = 0, as the one-ball interpolant locates
    it (G = 1 + 2 zeta lam y_f = 0 on its penetration series)."""
    lam_star = 1.0 / (2 * zeta)  # v* >= 0: the onset lies above lam = 1 / (2 zeta)
    (cut,) = similarity.LambdaInterpolant(zeta, lam_star, 10 * lam_star, Separation.FORCE, 1e-8).cuts
    v_star = cut + np.log(2 * zeta)
    estimate = plane.onset_edge(zeta) / plane.ONSET_MARGIN
    assert abs(estimate / v_star - 1) < 0.05
    assert plane.onset_edge(zeta) < v_star


def test_points_pulling_below_the_tension_piece_are_integrated(monkeypatch):
    """With the piece's edge put above the onset (margin 1.6 instead of 0.8) the scenes that pull below it
    are solved by the lanes, and every output still meets the target."""
    monkeypatch.setattr(plane, "ONSET_MARGIN", 1.6)
    interpolant = plane.PlaneInterpolant(0.05, 0.3, 1.0, 50.0, Separation.FORCE, 1e-8)
    zeta, lam = inside((0.05, 0.3, 1.0, 50.0), 300, seed=2)
    pen = direct(zeta, lam, Separation.PENETRATION)
    v, v_star = np.log(2 * zeta * lam), -np.log(-pen["y_f"])
    below = (v > v_star) & (v < plane.onset_edge(zeta))
    assert below.sum() > 10
    assert _errors(interpolant(zeta, lam), direct(zeta, lam, Separation.FORCE), OUTPUTS) < 1e-8


def test_a_point_has_the_same_value_however_many_are_evaluated_with_it():
    interpolant = plane.PlaneInterpolant(*BALLS, Separation.FORCE, 1e-8)
    zeta, lam = inside(BALLS, 2 * chebyshev.EVAL_BLOCK + 37, seed=3)
    whole = interpolant(zeta, lam)
    for size in (1, 5, chebyshev.EVAL_BLOCK - 1, chebyshev.EVAL_BLOCK + 1):
        parts = [interpolant(zeta[i:i + size], lam[i:i + size]) for i in range(0, min(zeta.size, 40 * size), size)]
        for key in OUTPUTS:
            got = np.concatenate([part[key] for part in parts])
            assert np.array_equal(got, whole[key][:got.size]), (size, key)


@pytest.mark.parametrize("rectangle", [(0.1, 0.6, 1.0, 10.0), (0.1, 0.2, 1e-4, 10.0), (0.1, 0.2, 1.0, 1e7)])
def test_outside_its_domain_the_plane_refuses(rectangle):
    with pytest.raises(InterpolationError, match="covers zeta"):
        plane.PlaneInterpolant(*rectangle, Separation.FORCE, 1e-8)


def test_a_plane_that_cannot_reach_the_target_refuses_and_the_engine_integrates(monkeypatch):
    monkeypatch.setattr(plane, "MAX_NODES", 200)
    with pytest.raises(InterpolationError, match="did not reach"):
        plane.PlaneInterpolant(*BALLS, Separation.FORCE, 1e-8)
    monkeypatch.setattr(paths, "PLANE_MIN", 50)
    scenes = random_balls(120, seed=4)
    monkeypatch.setattr(plane, "PlaneInterpolant", _refusing)
    integrated = sweep(scenes, chapter_ball=True)
    monkeypatch.setattr(paths, "PLANE_MIN", 10 ** 9)
    assert integrated.equals(sweep(scenes, chapter_ball=True))


def _refusing(*args, **kwargs):
    raise InterpolationError("refused")


def random_balls(n, seed):
    rng = np.random.default_rng(seed)
    return pd.DataFrame({"angle": rng.uniform(0, 89, n), "speed": rng.uniform(0.5, 30, n),
                         "k": rng.uniform(2e4, 2e5, n), "b": rng.uniform(2, 30, n), "mass": rng.uniform(0.05, 0.5, n),
                         "separation": rng.choice(["force", "penetration"], n)})


@pytest.mark.filterwarnings("ignore::sphereimpact.BeyondRadiusWarning")  # random balls: some beyond R
def test_engine_takes_the_plane_for_many_balls_and_shards_equal_the_whole(monkeypatch):
    monkeypatch.setattr(paths, "PLANE_MIN", 100)
    built = []
    original = plane.PlaneInterpolant
    monkeypatch.setattr(plane, "PlaneInterpolant", lambda *a, **k: built.append(a) or original(*a, **k))
    scenes = random_balls(400, seed=5)
    whole = sweep(scenes, chapter_ball=True)
    assert sorted(args[4] for args in built) == [Separation.FORCE, Separation.PENETRATION]
    for row in whole.iloc[::10].to_dict("records"):  # the sweep's contract, against the single-impact path
        scene = engine.scene_of({k: row[k] for k in engine.SCENE_COLUMNS})
        ref = simulate(scene, SolverOptions(rtol=1e-12, atol=1e-12))
        assert max(relative_errors(row, ref.to_dict(), scene, KEYS).values()) < 1e-8
        assert row["regime"] == ref.regime
    shards = [sweep(scenes.iloc[i], span=scenes, chapter_ball=True) for i in np.array_split(np.arange(len(scenes)), 3)]
    assert pd.concat(shards, ignore_index=True).equals(whole)
    assert sweep(scenes, chunk_size=7, chapter_ball=True).equals(whole)
    with pytest.raises(ValueError, match="span does not cover"):
        sweep(scenes.iloc[:5].assign(b=60.0), span=scenes, chapter_ball=True)
