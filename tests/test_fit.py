"""Fitting a ball to measured bounces: synthetic bounces from known parameters come back within their stated
errors at the nominal rate, unidentifiable parameters are said to be, bad data and bad requests are refused
in one line, and the fitted ball is reused by the command line."""

import json
import math

import numpy as np
import pandas as pd
import pytest

from conftest import cli
from sphereimpact import Ball, Measurement, Scene, calibrated_ball, load_ball, simulate
from sphereimpact.fit import fit, read_measured, with_values
from sphereimpact.impact.ball import ball_columns
from sphereimpact.impact.calibrate import normal_cor
from sphereimpact.sweep import sweep

#: The ball of the synthetic bounces: the chapter's eq. 4.1, rigid tangential contact.
TRUTH = Scene(model="kelvin-voigt", mu=0.25)
SIGMA_V, SIGMA_W = 0.02, 1.0  # m/s, rad/s


def bounces(seed: int, n: int = 20, truth: Ball = Ball(TRUTH), incidences=(30.0, 80.0), sigma=True) -> pd.DataFrame:
    """``n`` bounces of ``truth`` at random incidences and spins, vc_t and omega_f with Gaussian noise (at the
    default incidences most of them slide, so that each one tells mu)."""
    rng = np.random.default_rng(seed)
    table = pd.DataFrame({"speed": 3.0, "incidence": rng.uniform(*incidences, n), "spin": rng.uniform(-20, 20, n)})
    out = sweep(table.assign(**ball_columns(truth)), outputs=["vc_t", "omega_f"])
    data = table.assign(vc_t=out["vc_t"] + rng.normal(0, SIGMA_V, n), omega_f=out["omega_f"] + rng.normal(0, SIGMA_W, n))
    return data.assign(sigma_vc_t=SIGMA_V, sigma_omega_f=SIGMA_W) if sigma else data


@pytest.mark.parametrize("sigma", [True, False], ids=["sigma given", "sigma from the residuals"])
def test_mu_comes_back_within_its_standard_error_at_the_nominal_rate(sigma):
    """Over 30 seeds, |mu - 0.25| < stderr about 68 % of the time and < 2 stderr about 95 % (binomial 95 %
    bounds at 30 draws: [0.47, 0.87] and >= 0.83); a stderr a factor 2 too large fails the first (0.95 expected)
    and one a factor 2 too small fails it nine times in ten (0.38 expected)."""
    z = []
    for seed in range(30):
        result = fit(read_measured(bounces(seed, sigma=sigma)), Ball(TRUTH.with_(mu=0.1)), ["mu"], chapter_ball=True)
        p = result.parameters["mu"]
        assert p.identifiable and result.statistics["dof"] == 39
        z.append(abs(p.value - 0.25) / p.stderr)
    z = np.array(z)
    assert 0.47 <= np.mean(z < 1) <= 0.87 and np.mean(z < 2) >= 0.83, np.round(z, 2)


def test_two_parameters_of_a_compliant_contact_come_back():
    """mu and kappa of a linear tangential spring come back from 10 bounces within 3 standard errors, weakly
    correlated, and the fitted ball carries them."""
    truth = Ball(TRUTH.with_(tangential="linear", kappa=0.6, mu=0.3))
    data = read_measured(bounces(7, n=10, truth=truth, incidences=(5.0, 45.0)))
    start = Ball(truth.scene.with_(mu=0.2, kappa=1.0))
    result = fit(data, start, ["mu", "kappa"], chapter_ball=True)
    for name, value in (("mu", 0.3), ("kappa", 0.6)):
        p = result.parameters[name]
        assert p.identifiable and abs(p.value - value) < 3 * p.stderr, (name, p)
    assert result.ball.scene.kappa == pytest.approx(result.parameters["kappa"].value, rel=1e-12)
    assert abs(result.correlation.loc["mu", "kappa"]) < 1


def test_the_exact_microslip_contact_gives_back_its_friction_and_stiffness():
    """The fit serves the exact contact too (a Hertz ball, tangential microslip): mu and kappa of 10 bounces
    come back within 3 standard errors."""
    truth = Ball(Scene(model="hertz", modulus=1e7, mu=0.3, tangential="microslip", kappa=0.8, speed=3.0))
    data = read_measured(bounces(0, n=10, truth=truth, incidences=(5.0, 50.0)))
    result = fit(data, Ball(truth.scene.with_(mu=0.2, kappa=1.2)), ["mu", "kappa"], chapter_ball=True)
    for name, value in (("mu", 0.3), ("kappa", 0.8)):
        p = result.parameters[name]
        assert p.identifiable and abs(p.value - value) < 3 * p.stderr, (name, p)


def test_bootstrap_is_seeded_and_agrees_with_the_jacobian():
    data = read_measured(bounces(3))
    one, two = (fit(data, Ball(TRUTH), ["mu"], bootstrap=20, seed=5, chapter_ball=True) for _ in range(2))
    p = one.parameters["mu"]
    assert p.bootstrap_stderr == two.parameters["mu"].bootstrap_stderr
    assert 0.5 < p.bootstrap_stderr / p.stderr < 2.0


def test_a_parameter_the_bounces_do_not_depend_on_is_not_identifiable():
    """Bounces that all slide throughout leave the centre's tangential velocity v_t - mu (1 + e) v_n free of
    the ball's inertia: with only vc_t measured, inertia_factor is reported as not identifiable, with a note,
    while mu is fitted."""
    data = bounces(11, n=10, incidences=(70.0, 85.0)).drop(columns=["omega_f", "sigma_omega_f"])
    result = fit(read_measured(data), Ball(TRUTH.with_(mu=0.2, inertia_factor=0.5)), ["mu", "inertia_factor"], chapter_ball=True)
    mu = result.parameters["mu"]
    assert mu.identifiable and abs(mu.value - 0.25) < 3 * mu.stderr
    assert not result.parameters["inertia_factor"].identifiable
    assert math.isinf(result.parameters["inertia_factor"].stderr)
    assert any(note.startswith("inertia_factor is not identifiable") for note in result.notes)


def test_a_calibrated_ball_keeps_its_measured_cor_while_its_stiffness_moves():
    ball = calibrated_ball(Measurement(0.8, 5.0), model="hunt-crossley", modulus=1e7)
    moved = with_values(ball, {"k": 3.0 * ball.scene.k})
    assert moved.scene.k == pytest.approx(3.0 * ball.scene.k, rel=1e-12)
    assert normal_cor(moved.scene.with_(speed=5.0)) == pytest.approx(0.8, abs=1e-8)
    assert normal_cor(with_values(ball, {"cor": 0.6}).scene.with_(speed=5.0)) == pytest.approx(0.6, abs=1e-8)


def test_the_kharaz_long_layout_is_read_and_mapped():
    from pathlib import Path

    data = read_measured(Path(__file__).resolve().parents[1] / "data/kharaz2001.csv")
    counts = data.values["quantity"].value_counts().to_dict()
    assert counts == {"e_t": 8, "abs_omega_f": 7, "rebound_angle": 9}
    assert set(data.bounces.columns) == {"incidence"} and len(data.bounces) == 24


@pytest.mark.parametrize("table, message", [
    ({"incidence": [30.0], "vc_t": [1.0], "colour": [1]}, "column 'colour' is neither an approach"),
    ({"incidence": [30.0, 40.0], "vc_t": [1.0, "x"]}, "column 'vc_t' row 1: 'x' is not a finite number"),
    ({"incidence": [30.0], "vc_t": [1.0], "sigma_vc_t": [-1.0]}, "sigma_vc_t must be > 0"),
    ({"incidence": [30.0, 40.0]}, "nothing measured"),
    ({"incidence": [30.0, None], "vc_t": [1.0, 2.0]}, "column 'incidence' has an empty cell"),
])
def test_bad_measured_tables_are_refused_naming_the_column(table, message):
    with pytest.raises(ValueError, match=message):
        read_measured(pd.DataFrame(table))


@pytest.mark.parametrize("free, ball, message", [
    (["spin"], Ball(TRUTH), "'spin' cannot be fitted"),
    (["kappa"], Ball(TRUTH), "'kappa' is not a parameter of the 'rigid' tangential contact"),
    (["mu", "mu"], Ball(TRUTH), "named twice"),
    (["cor"], Ball(TRUTH), "'cor' needs a ball calibrated to a measured COR"),
    (["chi"], calibrated_ball(Measurement(0.8, 3.0), model="hunt-crossley", modulus=1e7),
     "'chi' is set by the measured COR"),
])
def test_bad_requests_are_refused_before_any_work(free, ball, message):
    data = read_measured(bounces(1, n=5))
    with pytest.raises(ValueError, match=message):
        fit(data, ball, free, chapter_ball=True)


def test_more_values_than_free_parameters_and_no_e_t_of_a_normal_impact():
    with pytest.raises(ValueError, match="more than 1 measured values"):
        fit(read_measured(pd.DataFrame({"incidence": [30.0], "vc_t": [1.0]})), Ball(TRUTH), ["mu"], chapter_ball=True)
    with pytest.raises(ValueError, match="e_t of a normal impact"):
        fit(read_measured(pd.DataFrame({"incidence": [0.0, 30.0], "e_t": [0.5, 0.6]})), Ball(TRUTH), ["mu"], chapter_ball=True)


def test_fit_on_the_command_line_writes_a_ball_that_simulate_reuses(tmp_path):
    """The command line door: --json prints value and stderr (the API's numbers), --out writes the fitted ball
    that `simulate --ball` then uses; a bad option is one line and exit 2."""
    csv = tmp_path / "bounces.csv"
    bounces(2).to_csv(csv, index=False)
    truth = ["--mass", "0.145", "--diameter", "0.063", "--k", "60000", "--b", "10.5"]  # TRUTH's ball, described
    run = cli("fit", str(csv), "--free", "mu", "--model", "kelvin-voigt", "--mu", "0.1", *truth, "--json",
               "--out", str(tmp_path / "fitted"))
    assert run.returncode == 0, run.stderr
    printed = json.loads(run.stdout)["parameters"]["mu"]
    api = fit(read_measured(csv), Ball(TRUTH.with_(mu=0.1)), ["mu"], chapter_ball=True).parameters["mu"]
    assert printed["value"] == pytest.approx(api.value, rel=1e-12) and printed["stderr"] == pytest.approx(api.stderr, rel=1e-9)
    ball = load_ball(tmp_path / "fitted/ball.json")
    assert ball.scene.mu == pytest.approx(api.value, rel=1e-12) and "bounces.csv" in ball.source
    for name in ("fit.json", "residuals.csv", "fit.png"):
        assert (tmp_path / "fitted" / name).stat().st_size > 0
    again = cli("simulate", "--ball", str(tmp_path / "fitted/ball.json"), "--incidence", "40", "--json")
    assert json.loads(again.stdout)["omega_f"] == pytest.approx(simulate(ball.scene.with_(incidence=40.0)).omega_f,
                                                                rel=1e-12)
    refused = cli("fit", str(csv), "--free", "mu", "--model", "kelvin-voigt", *truth, "--out", str(tmp_path / "fitted"))
    assert refused.returncode == 2 and "exists; pass --force" in refused.stderr and "Traceback" not in refused.stderr
    bad = cli("fit", str(csv), "--free", "colour", *truth, "--out", str(tmp_path / "never"))
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "'colour' cannot be fitted" in bad.stderr
    assert not (tmp_path / "never").exists()  # the folder is made once the fit succeeds
    assert math.isfinite(printed["value"])


def test_the_fit_benchmark_gives_back_the_parameters_of_its_noise_free_curve():
    """``measure_fit`` (the fit's row of results/bench_sweep.csv) on a small curve: the fitted mu and kappa come back
    to the sweep's accuracy, and the row says how many evaluations the fit took."""
    from sphereimpact.numerics.bench_sweep import FIT_TARGET_SECONDS, measure_fit

    truth = Ball(Scene(model="hunt-crossley", modulus=2e7, chi=0.05, mu=0.3, tangential="microslip", kappa=0.8,
                       speed=3.0))
    row = measure_fit("small curve", truth, {"mu": 0.2, "kappa": 1.1}, np.linspace(5.0, 60.0, 8), repeats=1)
    assert row["worst_error"] < 1e-6 and row["scenes"] == 8 and row["target_seconds"] == FIT_TARGET_SECONDS
    assert row["evaluations"] > 5 and row["throughput"] == pytest.approx(row["evaluations"] * 8 / row["seconds"])


def test_the_data_fit_benchmark_times_the_fit_a_user_runs(monkeypatch):
    """``measure_data_fit`` (the row of results/bench_sweep.csv that fits measured bounces, the COR free too): the
    fit it times is ``fit`` itself on the user's bounces, ball and free parameters, the row reports that fit's
    evaluations, and it names no parameter error (no values made measured bounces)."""
    from sphereimpact.numerics import bench_sweep

    truth = calibrated_ball(Measurement(0.8, 3.0), model="kelvin-voigt", mu=0.25, mass=0.145, diameter=0.063, k=6e4)
    data = read_measured(bounces(5, n=8, truth=truth))
    start = with_values(truth, {"mu": 0.1})
    calls = []

    def spied(*args, **options):  # the package's fit, its call and result recorded
        calls.append((args, options, fit(*args, **options)))
        return calls[-1][2]

    monkeypatch.setattr(bench_sweep, "fit", spied)
    row = bench_sweep.measure_data_fit("eight bounces", data, start, ["mu", "cor"], repeats=1)
    [(args, options, direct)] = calls
    assert args[0] is data and args[1] is start and args[2] == ["mu", "cor"] and options == {}
    assert row["evaluations"] == direct.statistics["evaluations"] > 2 and row["scenes"] == 8
    assert math.isnan(row["worst_error"]) and row["target_seconds"] == bench_sweep.DATA_FIT_TARGET_SECONDS
    assert direct.parameters["mu"].value == pytest.approx(0.25, abs=4 * direct.parameters["mu"].stderr)
