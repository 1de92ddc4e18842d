"""The batched Taylor lanes (eq. 4.2 without gravity): against the Runge-Kutta lanes at a tight target (a
second method), the ``continued`` end, batch independence and the failure modes found while building them."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from sphereimpact import ImpactError
from sphereimpact.contact.separation import Separation
from sphereimpact.sweep import batch, plane, series_lanes
from sphereimpact.sweep.outputs import NORMAL_OUTPUTS as OUTPUTS
from sphereimpact.sweep.series_lanes import End
from sphereimpact.sweep.similarity import _errors

RNG = np.random.default_rng(3)
ZETA = 10 ** RNG.uniform(-2.5, 0.0, 400)  # 0.003 to 1: the plane's domain
LAM = 10 ** RNG.uniform(-2.0, 4.0, 400)


def reference(zeta, lam, separation):
    return batch.integrate(zeta, lam, np.zeros(zeta.size), np.ones(zeta.size, bool), separation, 1e-12)


@pytest.fixture(scope="module", params=list(Separation))
def separation_and_reference(request):
    return request.param, reference(ZETA, LAM, request.param)


@pytest.mark.parametrize("target", [1e-6, 1e-8, 1e-10])
def test_lanes_meet_their_target_against_the_runge_kutta_lanes(separation_and_reference, target):
    """Measured worst errors at 1e-8: 2.8e-9 (penetration tau_f near zeta = 1), 2.4e-10 elsewhere."""
    separation, ref = separation_and_reference
    got = series_lanes.integrate(ZETA, LAM, separation, target)
    assert _errors(got, ref, OUTPUTS) <= max(target, 1e-11)


def test_continued_end_is_the_force_criterion_where_the_force_pulls_and_smooth_across_the_onset():
    """On the plane's tension piece, from its edge (below the onset) up: v = log(2 zeta lam) in
    [edge, edge + 0.5] at zeta = 0.2, the onset at v* = 0.40."""
    zeta = np.full(200, 0.2)
    lam = np.exp(np.linspace(0.0, 0.5, 200) + float(plane.onset_edge(0.2))) / 0.4
    force, continued = (series_lanes.integrate(zeta, lam, end, 1e-10) for end in (Separation.FORCE, End.CONTINUED))
    pen = series_lanes.integrate(zeta, lam, Separation.PENETRATION, 1e-10)
    pulls = 1 + 2 * zeta * lam * pen["y_f"] < 0
    assert 20 < pulls.sum() < 180  # the onset lies inside the range
    for key in ("tau_f", "y_f"):
        assert np.allclose(continued[key][pulls], force[key][pulls], rtol=0, atol=1e-12)  # other root brackets
    # past delta = 0 where the force does not pull: later than the penetration end, and as smooth through the
    # onset as beyond it, where the force criterion's t_f has its kink (second differences 200x larger)
    assert np.all(continued["tau_f"][~pulls] > pen["tau_f"][~pulls])
    smooth, kinked = np.abs(np.diff(continued["tau_f"], 2)), np.abs(np.diff(force["tau_f"], 2))
    assert smooth.max() < 2 * smooth[pulls[1:-1]].max()
    assert kinked.max() > 100 * smooth.max()


def test_a_lane_does_not_depend_on_the_lanes_beside_it():
    """The order comes from the target (not from the batch's most damped lane), so a scene's outputs are bit
    for bit the same alone and in any batch: the plane's fallback integrates whatever subset a shard holds."""
    whole = series_lanes.integrate(ZETA[:50], LAM[:50], Separation.FORCE, 1e-8)
    for i in (0, 17, 49):
        alone = series_lanes.integrate(ZETA[i:i + 1], LAM[i:i + 1], Separation.FORCE, 1e-8)
        assert all(alone[k][0] == whole[k][i] for k in OUTPUTS)


@pytest.mark.parametrize("separation", list(Separation))
@pytest.mark.parametrize("partial", [True, False])
def test_one_lane_serves_many_levels_as_a_lane_per_level_does_to_the_bit(separation, partial):
    """A lane given L levels (the grip tables' nodes) stops once it has them all; each level's instant is the one a
    lane of that level alone gives, to the bit: levels 0, beyond j's largest value (the instant it is largest),
    NaN (none) and levels across the impulse, at three damping ratios."""
    rng = np.random.default_rng(11)
    for zeta0 in (0.05, 0.3, 0.9):
        zeta, lam = np.full(12, zeta0), 10 ** rng.uniform(-1.5, 3.5, 12)
        j_p = series_lanes.integrate(zeta, lam, separation, 1e-8)["j_p"]
        fractions = np.concatenate([[0.0, 1.0, 1.2, np.nan], rng.uniform(0.0, 1.0, 12)])
        levels = j_p[:, None] * fractions[None, :]
        many = series_lanes.integrate(zeta, lam, separation, 1e-8, levels=levels, partial=partial)["tau_g"]
        width = fractions.size
        alone = series_lanes.integrate(np.repeat(zeta, width), np.repeat(lam, width), separation, 1e-8,
                                       levels=levels.ravel(), partial=partial)["tau_g"]
        assert many.shape == levels.shape
        np.testing.assert_array_equal(many.ravel(), alone)
        assert np.isnan(many[:, 3]).all() and (many[:, 0] == 0).all() and (np.diff(many[:, 4:], axis=1) != 0).any()


@pytest.mark.parametrize("separation", list(Separation))
def test_kept_steps_give_the_instants_of_later_levels_as_partial_lanes_do(separation):
    """Lanes integrated to their end with their steps kept answer levels asked afterwards (the grip tables' rounds)
    with the instants lanes stopping at those levels give, to the bit: the replayed crossings and stops are theirs.
    Levels 0, j's largest value and beyond it, NaN, and across the impulse, of j_p and of 1 - y_f, five damping
    ratios up to critical."""
    rng = np.random.default_rng(5)
    for zeta0 in (0.01, 0.05, 0.3, 0.9, 1.0):
        zeta, lam = np.full(20, zeta0), 10 ** rng.uniform(-2.0, 4.0, 20)
        full = series_lanes.integrate(zeta, lam, separation, 1e-8, extremes=True, keep_steps=True)
        for reference in (full["j_p"], 1.0 - full["y_f"]):
            fractions = np.concatenate([[0.0, 1.0, 1.2, np.nan], rng.uniform(0.0, 1.0, 30)])
            levels = reference[:, None] * fractions[None, :]
            stopping = series_lanes.integrate(zeta, lam, separation, 1e-8, levels=levels, partial=True)["tau_g"]
            np.testing.assert_array_equal(full["steps"].instants(levels), stopping)


@pytest.mark.parametrize("order", [16, 18, 20, 24])
def test_high_orders_land_on_the_band_edge_after_maximum_compression(monkeypatch, order):
    """lam 38-70 puts x_m just outside the ramp band: a step that started there still compressing crossed the
    maximum and half the band at once (COR off by 1e-9 at order 16, 3e-4 at 18)."""
    zeta, lam = RNG.uniform(0.005, 0.4, 60), RNG.uniform(38.0, 70.0, 60)
    monkeypatch.setattr(series_lanes, "order_for", lambda tol: order)
    got = series_lanes.integrate(zeta, lam, Separation.FORCE, 1e-9)
    assert _errors(got, reference(zeta, lam, Separation.FORCE), OUTPUTS) < 2e-10


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # scipy's trial steps past the event overflow exp(lam |x|)
@pytest.mark.parametrize("separation", list(Separation))
def test_lanes_against_scipy_where_the_ramp_is_sharp(separation):
    """lam 1e4-1e6 (the ramp switches on within 1e-6 of the deflection scale): scipy's DOP853 at rtol 1e-13
    with steps capped at 2e-4, as a second method (the Runge-Kutta lanes lose up to 6e-5 in y_f here)."""
    for zeta, lam in [(0.002, 1e6), (0.01, 1e6), (0.0005, 3e5), (0.2, 1e4)]:
        got = series_lanes.integrate(np.array([zeta]), np.array([lam]), separation, 1e-11)

        def end(t, z):  # the criterion's end after maximum compression: x = 0, or P / x = 0
            return z[0] if separation.pulls else float(series_lanes.ratio(z[0], z[1], 2 * zeta, lam))

        end.terminal, end.direction = True, -1
        ref = solve_ivp(rhs(zeta, lam), [1.0, 4.0], list(peak(zeta, lam)), method="DOP853", rtol=1e-13, atol=1e-16,
                        events=end, max_step=1e-3)
        assert abs(ref.y_events[0][-1][1] - got["y_f"][0]) < 1e-11
        assert abs(ref.t_events[0][-1] - got["tau_f"][0]) < 1e-11


def rhs(zeta, lam):
    def f(t, z):
        return [z[1], -(z[0] + 2 * zeta * z[1] * -np.expm1(-lam * z[0]))]
    return f


def peak(zeta, lam):
    """The state at tau = 1 (before maximum compression, where neither end can fire), by scipy."""
    sol = solve_ivp(rhs(zeta, lam), [0.0, 1.0], [0.0, 1.0], method="DOP853", rtol=1e-13, atol=1e-16, max_step=1e-3,
                    first_step=1e-9)
    return sol.y[:, -1]


def test_bad_separation_is_refused_and_no_lanes_give_empty_outputs():
    with pytest.raises(ValueError, match="end must be a Separation"):
        series_lanes.integrate(ZETA[:3], LAM[:3], "sideways", 1e-8)
    assert all(v.size == 0 for v in series_lanes.integrate(ZETA[:0], LAM[:0], Separation.FORCE, 1e-8).values())


def test_a_lane_that_never_separates_is_an_error():
    """Critically damped and beyond under the penetration criterion x creeps towards 0: zeta = 5 with a huge
    lam does not return within the horizon."""
    with pytest.raises(ImpactError, match="horizon|steps"):
        series_lanes.integrate(np.array([0.1, 40.0]), np.array([1.0, 1e5]), Separation.PENETRATION, 1e-8)
