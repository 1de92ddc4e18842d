"""Which bounces to measure (sphereimpact plan): the expected errors against a fit's own and against the spread of
fits of synthetic bounces, the best plan against brute force, what a plan cannot identify, and each door."""

from __future__ import annotations

import itertools
import json

import numpy as np
import pandas as pd
import pytest

from sphereimpact.fit import fit, read_measured
from sphereimpact.fit.plan import (Noise, _design, expected_errors, parse_noise, plan, read_candidates,
                                   realised_spread)
from sphereimpact.impact.ball import Ball, Measurement, calibrated_ball
from sphereimpact.impact.scene import Scene

NOISE = "e_t=0.02,abs_omega_f=5%"


def rigid_ball():
    """Kharaz's alumina sphere (elastic Hertz), the chapter's rigid tangential contact."""
    return Ball(Scene(model="hertz", modulus=6.3e10, mass=2.618e-4, diameter=0.005, mu=0.092, speed=3.9,
                      incidence=20.0))


def microslip_ball():
    return calibrated_ball(Measurement(cor=0.98, speed=3.9), model="hunt-crossley", modulus=6.3e10, mass=2.618e-4,
                           diameter=0.005, mu=0.092, tangential="microslip", kappa=0.86, speed=3.9, incidence=20.0)


def candidates(*angles):
    return pd.DataFrame({"incidence": np.array(angles, float)})


def test_noise_reads_absolute_and_relative_and_refuses_in_one_line():
    noise = parse_noise(NOISE)
    assert noise == {"e_t": Noise(0.02), "abs_omega_f": Noise(0.05, relative=True)}
    assert parse_noise({"cor": 0.01, "omega_f": "10%"})["omega_f"] == Noise(0.1, relative=True)
    for bad, match in (("bogus=1", "not a measurable output"), ("e_t=-1", "finite number > 0"),
                       ("e_t=abc", "finite number > 0"), ("e_t", "not OUTPUT=SIGMA"), ("e_t=1,e_t=2", "twice"),
                       ("", "name at least one output")):
        with pytest.raises(ValueError, match=match):
            parse_noise(bad)


def test_candidates_are_approaches_or_refused(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text("incidence,speed\n10,3.9\n20,3.9\n")
    assert read_candidates(path).shape == (2, 2)
    for text, match in (("incidence,vc_t\n10,1\n", "column 'vc_t' is not an approach"),
                        ("incidence\n", "no candidate bounces"), ("incidence\n10\nx\n", "row 1")):
        path.write_text(text)
        with pytest.raises(ValueError, match=match):
            read_candidates(path)


def test_the_plans_errors_are_the_fits_own_at_the_truth():
    """Fitting the plan's noise-free model values with the planned sigmas given, the fit reports from its Jacobian
    at the solution (the truth) the standard errors the plan predicted from the same Jacobian."""
    ball = microslip_ball()
    result = plan(candidates(3, 8, 25, 30, 40), ball, ["mu", "kappa"], NOISE)
    table = result.table()
    rows = result.candidates
    for name in result.noise:
        table[name] = rows[name].to_numpy()
    fitted = fit(read_measured(table), ball, ["mu", "kappa"])
    for name in ("mu", "kappa"):
        assert fitted.parameters[name].stderr == pytest.approx(result.stderr["chosen"][name], rel=2e-3)


def test_predicted_errors_match_the_spread_of_fits_of_synthetic_bounces():
    """Rigid contact, mu free: over 20 seeds the realised spread is within three of its Monte Carlo errors of the
    prediction (the pipeline checks the microslip and damped balls, results/plan/checks.csv)."""
    ball = rigid_ball()
    result = plan(candidates(*range(5, 80, 5)), ball, ["mu"], NOISE, size=5)
    spread = realised_spread(result, ball, 20)
    row = spread.iloc[0]
    assert abs(row["realised"] - row["predicted"]) < 3 * row["mc_error"], spread
    assert abs(row["mean"] - 0.092) < 3 * row["predicted"] / np.sqrt(20)


def test_the_exchange_finds_the_d_optimal_plan_of_brute_force():
    ball = microslip_ball()
    table = candidates(2, 5, 9, 14, 20, 27, 33, 45)
    result = plan(table, ball, ["mu", "kappa"], NOISE, size=3)
    design = _design(read_candidates(table), ball, ["mu", "kappa"], parse_noise(NOISE), 1e-8)
    info = np.einsum("iop,ioq->ipq", design.weighted, design.weighted)
    best = max(itertools.combinations(range(len(table)), 3),
               key=lambda rows: np.linalg.slogdet(info[list(rows)].sum(axis=0))[1])
    assert result.chosen == tuple(best)
    assert result.stderr["chosen"]["kappa"] <= result.stderr["even"]["kappa"]


def test_a_plan_whose_bounces_all_slide_cannot_identify_kappa_and_says_why():
    """Bounces that all slide do not depend on the tangential stiffness: kappa unbounded, the reason named, and
    that no candidate would identify it."""
    result = plan(candidates(45, 55, 65, 75), microslip_ball(), ["mu", "kappa"], NOISE)
    assert result.stderr["chosen"]["kappa"] == np.inf
    assert any(note.startswith("kappa is not identifiable from the plan: no planned output depends on it")
               and "no candidate identifies it" in note for note in result.notes), result.notes
    assert np.isfinite(result.stderr["chosen"]["mu"])


def test_expected_errors_of_measured_values_add_their_information():
    """Values measured at the same bounces, one quantity each, carry together what a plan measuring both gives."""
    ball = rigid_ball()
    both = plan(candidates(10, 30, 50), ball, ["mu"], NOISE)
    values = pd.DataFrame({"incidence": [10.0, 30.0, 50.0] * 2, "quantity": ["e_t"] * 3 + ["abs_omega_f"] * 3})
    assert expected_errors(values, ball, ["mu"], NOISE)["mu"] == pytest.approx(both.stderr["all"]["mu"], rel=1e-12)


def test_size_and_criterion_are_checked():
    for size in (0, 4, 2.5):
        with pytest.raises(ValueError, match="size must be an integer in"):
            plan(candidates(10, 20, 30), rigid_ball(), ["mu"], NOISE, size=size)
    with pytest.raises(ValueError, match="criterion must be one of D, A"):
        plan(candidates(10, 20), rigid_ball(), ["mu"], NOISE, criterion="E")
    a_plan = plan(candidates(*range(5, 80, 10)), rigid_ball(), ["mu"], NOISE, size=2, criterion="A")
    assert len(a_plan.chosen) == 2


def test_command_line_door(tmp_path, capsys):
    """`sphereimpact plan` with the ball described as for fit: JSON, the folder, and the plan read back by fit once
    its outputs are filled in."""
    from sphereimpact.cli import run

    path = tmp_path / "candidates.csv"
    candidates(*range(5, 80, 5)).to_csv(path, index=False)
    ball = ["--model", "hertz", "--modulus", "6.3e10", "--mass", "2.618e-4", "--diameter", "0.005", "--mu", "0.092",
            "--speed", "3.9"]
    assert run(["plan", str(path), "--free", "mu", "--noise", NOISE, "--size", "4", *ball, "--json",
                "--out", str(tmp_path / "plan")]) == 0
    record = json.loads(capsys.readouterr().out)
    api = plan(path, rigid_ball(), ["mu"], NOISE, size=4)
    assert record["stderr"]["chosen"]["mu"] == pytest.approx(api.stderr["chosen"]["mu"], rel=1e-12)
    table = pd.read_csv(tmp_path / "plan" / "plan.csv")
    assert list(table.columns) == ["incidence", "e_t", "sigma_e_t", "abs_omega_f", "sigma_abs_omega_f"]
    table["e_t"], table["abs_omega_f"] = api.candidates.loc[api.candidates.chosen, ["e_t", "abs_omega_f"]].to_numpy().T
    table.to_csv(tmp_path / "measured.csv", index=False)
    assert run(["fit", str(tmp_path / "measured.csv"), "--free", "mu", *ball]) == 0
    assert run(["plan", str(path), "--free", "mu", "--noise", NOISE]) == 2  # the ball undescribed
    assert "plan: describe the ball you will measure" in capsys.readouterr().err


def test_study_config_door_is_checked_before_any_job(tmp_path):
    """A study's plan section: its candidates, noise, free parameters and size checked with the config."""
    import yaml

    from sphereimpact.study.config_check import config_errors

    config = yaml.safe_load(open("config/examples/tennis.yaml", encoding="utf-8"))
    assert config_errors(config, "config/schema.yaml") == []
    for change, key in (({"noise": {"e_t": -1}}, "plan.noise"), ({"free": ["bogus"]}, "plan.free"),
                        ({"size": 1000}, "plan.size"), ({"candidates": str(tmp_path / "none.csv")}, "plan.candidates")):
        errors = config_errors(config | {"plan": config["plan"] | change}, "config/schema.yaml")
        assert len(errors) == 1 and errors[0].startswith(f"config key {key}:"), errors
