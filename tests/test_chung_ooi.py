"""Chung & Ooi's benchmark tests: each reference against an independent closed form, and the DEM-code comparison
through the API and the command line."""

import json
import math

import numpy as np
import pandas as pd
import pytest

from sphereimpact.cli import run
from sphereimpact.study.chung_ooi import (HERTZ_TIME, compare, dem_rules, deviations, load_tests, read_table,
                                          reference, write_table)


def test_hertz_time_constant_is_johnsons():
    """2.868 (Johnson, Contact Mechanics, 1985, eq. 11.24, to four digits), from 2.94 delta_m / v."""
    assert HERTZ_TIME == pytest.approx(2.868, abs=5e-4)
    x = (np.arange(2_000_000) + 0.5) / 2_000_000
    integral = float(np.mean((1 - x ** 2.5) ** -0.5))
    assert HERTZ_TIME == pytest.approx(2 * integral * (15 / 16) ** 0.4, rel=2e-4)  # midpoint rule, singular end


def test_elastic_plane_test_against_hertz_from_the_materials():
    """Test 2 from the materials alone: E* = E / (1 - nu^2) against a rigid plane, m = rho 4/3 pi R^3."""
    materials, tests = load_tests()
    exact = reference(2)
    for _, row in exact.iterrows():
        material = materials[row["case"]]
        e_star = material["E"] / (1 - material["nu"] ** 2)
        radius, v = tests[2]["radius"], tests[2]["normal_speed"]
        mass = material["rho"] * 4 / 3 * math.pi * radius ** 3
        delta_m = (15 * mass * v ** 2 / (16 * e_star * math.sqrt(radius))) ** 0.4
        assert row["delta_m"] == pytest.approx(delta_m, rel=1e-8)
        assert row["force_max"] == pytest.approx(4 / 3 * e_star * math.sqrt(radius) * delta_m ** 1.5, rel=1e-8)
        assert row["t_f"] == pytest.approx(2.868265699 * (mass ** 2 / (radius * e_star ** 2 * v)) ** 0.2, rel=1e-8)
        assert row["cor"] == pytest.approx(1.0, abs=1e-8) and row["dundurs_beta"] == pytest.approx(
            (1 - 2 * material["nu"]) / (2 * (1 - material["nu"])), rel=1e-15)


def test_every_damped_law_returns_the_requested_cor():
    exact = reference(3)
    assert set(exact["model"]) == {"hunt-crossley", "linear-hunt-crossley", "kelvin-voigt", "modified", "hertz"}
    assert np.abs(exact["cor"] - exact["cor_target"]).max() < 1e-8


def test_sliding_rows_follow_the_gross_slip_line():
    """Test 5's fastest tangential speeds slide throughout: vc_t = v_t - mu (1 + e) v_n, R omega_f = mu (1 + e) v_n / alpha."""
    exact = reference(5)
    fast = exact[exact["speed"] > 30]
    v_n = fast["speed"] * np.cos(np.radians(fast["incidence"]))
    v_t = fast["speed"] * np.sin(np.radians(fast["incidence"]))
    np.testing.assert_allclose(fast["vc_t"], v_t - 0.3 * 2 * v_n, rtol=1e-9)
    np.testing.assert_allclose(fast["omega_f"] * 0.5 * fast["diameter"], 0.3 * 2 * v_n / 0.4, rtol=1e-8)


def test_compare_reports_the_deviation_of_a_dem_rule(tmp_path):
    """The project's own `mindlin` outputs, laid out as a DEM code's, through the API and the command line: the
    deviations reported are the differences from the reference, computed here row by row."""
    mine, theirs = tmp_path / "reference", tmp_path / "theirs"
    mine.mkdir()
    theirs.mkdir()
    exact = reference(5)
    write_table(exact, mine / "test5.csv")
    rules = dem_rules(5)
    mindlin = rules[rules["tangential"] == "mindlin"].reset_index(drop=True)
    write_table(mindlin, theirs / "test5.csv")
    report = compare(mine, theirs).set_index("quantity")
    written = read_table(mine / "test5.csv")
    for quantity in ("omega_f", "vc_t", "e_t"):
        diff = np.abs(mindlin[quantity].to_numpy() - written[quantity].to_numpy())
        assert report.loc[quantity, "max_abs"] == pytest.approx(diff.max(), rel=1e-9)
        assert report.loc[quantity, "max_rel"] == pytest.approx(diff.max() / np.abs(written[quantity]).max(), rel=1e-9)
    assert report.loc["omega_f", "max_rel"] == pytest.approx(
        deviations(rules, exact).set_index(["tangential", "quantity"]).loc[("mindlin", "omega_f"), "max_rel"], rel=1e-9)
    assert report.loc["t_f", "max_abs"] < 1e-15  # the normal motion is the same


def test_command_line_writes_and_compares(tmp_path, capsys):
    out = tmp_path / "ref"
    assert run(["benchmark", "chung-ooi", "--out", str(out), "--tests", "2"]) == 0
    table = pd.read_csv(out / "test2.csv")
    assert "force_max [N]" in table.columns and len(table) == 2
    capsys.readouterr()
    theirs = tmp_path / "theirs"
    theirs.mkdir()
    table.assign(**{"force_max [N]": table["force_max [N]"] * 1.01}).to_csv(theirs / "test2.csv", index=False)
    assert run(["benchmark", "compare", str(out), str(theirs), "--json"]) == 0
    rows = {row["quantity"]: row for row in json.loads(capsys.readouterr().out)}
    assert rows["force_max"]["max_rel"] == pytest.approx(0.01, rel=1e-6) and rows["t_f"]["max_abs"] == 0
    table.iloc[:1].to_csv(theirs / "test2.csv", index=False)
    assert run(["benchmark", "compare", str(out), str(theirs)]) == 2
    assert "has 1 rows; the reference has 2" in capsys.readouterr().err
    assert run(["benchmark", "chung-ooi", "--out", str(out), "--tests", "2"]) == 2
    assert "exists; pass --force" in capsys.readouterr().err
