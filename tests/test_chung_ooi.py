"""Chung & Ooi's benchmark tests: each reference against an independent closed form, and the DEM-code comparison
through the API and the command line."""

import functools
import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from sphereimpact import simulate
from sphereimpact.cli import run
from sphereimpact.study import chung_ooi
from sphereimpact.study.chung_ooi import (HERTZ_TIME, OUTPUTS, deviations, read_table, scenes_of_test, solve,
                                          write_table)
from sphereimpact.study.chung_ooi_definition import load_tests

#: Each test's reference, solved once for the module (the tests read them, never change them).
reference = functools.lru_cache(maxsize=None)(chung_ooi.reference)


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
    """The project's own `mindlin` outputs, laid out as a DEM code's, through the API: the deviations reported are the
    differences from the reference, computed here row by row, and the verdict follows the tolerance."""
    from sphereimpact.study.dem_compare import compare

    mine, theirs = tmp_path / "reference", tmp_path / "theirs"
    mine.mkdir()
    theirs.mkdir()
    exact = reference(5)
    write_table(exact, mine / "test5.csv")
    rules = solve(scenes_of_test(5, "mindlin"))  # the one rule judged here
    mindlin = rules[rules["rule"] == "mindlin"].reset_index(drop=True)
    write_table(mindlin, theirs / "test5.csv")
    verdict = compare(mine, theirs)
    report = verdict.table.set_index("quantity")
    written = read_table(mine / "test5.csv")
    for quantity in ("omega_f", "vc_t", "e_t"):
        diff = np.abs(mindlin[quantity].to_numpy() - written[quantity].to_numpy())
        assert report.loc[quantity, "max_abs"] == pytest.approx(diff.max(), rel=1e-9)
        assert report.loc[quantity, "max_rel"] == pytest.approx(diff.max() / np.abs(written[quantity]).max(), rel=1e-9)
    assert report.loc["omega_f", "max_rel"] == pytest.approx(
        deviations(rules, exact).set_index(["rule", "quantity"]).loc[("mindlin", "omega_f"), "max_rel"], rel=1e-9)
    assert report.loc["t_f", "max_abs"] < 1e-15  # the normal motion is the same
    worst = report["max_rel"].max()
    assert verdict.passed == (worst <= 0.02) and compare(mine, theirs, {"*": 1.01 * worst}).passed
    assert not compare(mine, theirs, {"*": 0.99 * worst}).passed


def test_command_line_writes_and_compares(tmp_path, capsys):
    """benchmark compare as a CI gate: the reference and a shuffled copy pass (exit 0); a deviation beyond the
    tolerance, a hole and a wrong input fail or are refused; a unit is converted when known, refused otherwise; a
    file with nothing to compare is refused; --json carries the same verdicts."""
    out = tmp_path / "ref"
    assert run(["benchmark", "chung-ooi", "--out", str(out), "--tests", "2,7"]) == 0
    table = pd.read_csv(out / "test7.csv")
    assert "omega_f [rad/s]" in table.columns and len(table) == 30
    capsys.readouterr()
    theirs = tmp_path / "theirs"
    theirs.mkdir()

    def judged(frame, *extra):
        frame.to_csv(theirs / "test7.csv", index=False)
        status = run(["benchmark", "compare", str(out), str(theirs), *extra])
        return status, capsys.readouterr()

    assert judged(table)[0] == 0
    status, said = judged(table.sample(frac=1.0, random_state=1), "--json")  # any order
    assert status == 0 and json.loads(said.out)["passed"] is True
    off = table.assign(**{"omega_f [rad/s]": table["omega_f [rad/s]"] * (1 + 1e-3)})
    assert judged(off)[0] == 0  # within the default 2 %
    status, said = judged(off, "--tolerance", "omega_f=1e-4")
    assert status == 1 and "overall: FAIL (worst: test 7 omega_f" in said.out
    status, said = judged(off, "--json", "--tolerance", "1e-4")
    verdict = json.loads(said.out)
    assert status == 1 and verdict["passed"] is False and verdict["tests"][0]["passed"] is False
    holed = table.copy()
    holed.loc[3, "vc_t [m/s]"] = float("nan")
    status, said = judged(holed)
    assert status == 1 and "FAIL" in said.out
    rpm = table.rename(columns={"omega_f [rad/s]": "omega_f [rpm]"}).assign(
        **{"omega_f [rpm]": table["omega_f [rad/s]"] * 60 / (2 * np.pi)})
    assert judged(rpm)[0] == 0  # converted
    status, said = judged(table.rename(columns={"omega_f [rad/s]": "omega_f [furlong/s]"}))
    assert status == 2 and "unit 'furlong/s' is not 'rad/s'" in said.err
    status, said = judged(table[[c for c in table.columns if c.split(" [")[0] not in OUTPUTS]])
    assert status == 2 and "has no output of the reference's to compare" in said.err
    status, said = judged(table.assign(**{"mu [-]": 0.3}))
    assert status == 2 and "mu 0.3 is not the reference's 0.4" in said.err
    status, said = judged(table.iloc[1:])
    assert status == 2 and "lacks the reference's row 0" in said.err
    status, said = judged(pd.concat([table, table.iloc[:1]]))
    assert status == 2 and "are the same reference row" in said.err
    assert run(["benchmark", "chung-ooi", "--out", str(out), "--tests", "2"]) == 2
    assert "exists; pass --force" in capsys.readouterr().err


def test_the_papers_curves_stand_beside_the_exact_answers():
    """The shipped digitisation of the paper's curves (data/chung_ooi_paper/): test 7's omega' = omega is the exact
    reference to round-off; test 4's alumina curves agree with the exact contact within 3 % from 20 degrees on (the
    digitisation's and the FEM's own accuracy), and the figures' points are the same curves converted."""
    from sphereimpact.study.chung_ooi import published_deviations, published_points, read_curves

    curves = read_curves("data/chung_ooi_paper/curves.csv")
    assert set(curves["test"]) == {4, 5, 6, 7, 8} and (curves["sign"].abs() == 1).all()
    seven = published_deviations(curves, {7: reference(7)})
    assert len(seven) == 2 and seven["max_abs"].max() < 1e-9
    four = solve(scenes_of_test(4).query("case == 'al-oxide'"))  # the curves' material
    steep = published_deviations(curves[(curves["test"] == 4) & (curves["x"] >= 20)], {4: four})
    assert set(steep["quantity"]) == {"e_t", "omega_f", "rebound_angle_contact"} and steep["max_rel"].max() < 0.03
    points = published_points(curves, 4, four)
    spin = points[(points["column"] == "omega_f") & (points["case"] == "al-oxide")]
    assert (spin["y"] > 0).all()  # the paper's negative spins in this project's sense


def test_tests_6_and_8_have_the_papers_beta_curves_on_kratos_axes():
    """Tests 6 and 8's published curves (issue 41 item 4: Kratos' benchmark8_graph1.dat, beta against friction_ratio =
    3.5 mu (1 + e) v_n / v_st): in gross slip (friction_ratio < 1) the paper's curve is Maw's line beta =
    friction_ratio - 1, which the exact reference meets; each of test 8's two curves stands beside both materials of
    its shear case, and the figures read friction_ratio as the ball's spin."""
    from sphereimpact.study.chung_ooi import published_deviations, published_points, read_curves

    curves = read_curves("data/chung_ooi_paper/curves.csv")
    six = solve(scenes_of_test(6))  # reference(6) but its spring's reduction gaps, which this test does not read
    sliding = curves[(curves["test"] == 6) & (curves["x"] < 1.0)]
    assert len(sliding) == 5 and np.allclose(sliding["y"], sliding["x"] - 1.0, atol=0.016)  # the digitisation
    rows = six[six["friction_ratio"] < 0.9]  # sliding throughout (nearer 1 the contact's edge sticks at the end)
    assert len(rows) == 8 and np.allclose(
        rows["beta"], rows["friction_ratio"] * (1 + rows["cor"]) / (1 + rows["cor_target"]) - 1, rtol=1e-12, atol=1e-14)
    gross = published_deviations(curves[curves["x"] < 1.0], {6: six})
    assert set(gross["case"]) == {"al-alloy", "nylon"} and gross["max_abs"].max() < 0.016
    eight = solve(scenes_of_test(8))
    cases = published_deviations(curves, {8: eight}).groupby("case")["points"].sum()
    assert dict(cases) == {"al-alloy, case A": 16, "al-alloy, case B": 16, "nylon, case A": 16, "nylon, case B": 16}
    points = published_points(curves, 6, six)
    at = points[points["case"] == "al-alloy"]
    slip = np.abs(at["x"]) * 0.1  # |omega| R
    assert np.allclose(3.5 * 0.4 * 1.5 * 0.2 / slip, curves[curves["test"] == 6]["x"], rtol=1e-12)
    assert (np.sign(at["x"]) == np.sign(six["spin"].iloc[0])).all() and set(at["column"]) == {"beta"}


def test_the_files_give_the_dem_codes_frames_and_normalised_quantities():
    """Test 1 in its lab frame (each sphere at 10 m/s, as the paper sets it up) exchanges the two velocities (elastic,
    identical spheres); test 5's approach is given as v_n and v_t (5 m/s and the listed tangential speeds), and its
    sliding rows lie on Maw's gross-slip line in Kratos' normalised quantities: beta = -1 + 3.5 mu (1 + e) v_n / v_st,
    R omega' / (mu v_n) = 2.5 (1 + e)."""
    one = reference(1)
    assert np.allclose(one["lab_ball_v_n"], -10.0) and np.allclose(one["lab_partner_v_n"], 10.0)
    assert np.allclose(one["lab_ball_vc_n"], 10.0, rtol=1e-8) and np.allclose(one["lab_partner_vc_n"], -10.0, rtol=1e-8)
    from sphereimpact.study.chung_ooi import EXACT, scenes_of_test, solve

    five = scenes_of_test(5, EXACT)
    _, tests = load_tests()
    assert np.allclose(five["v_n"], 5.0) and np.allclose(sorted(set(five["v_t"].round(9))), tests[5]["tangential_speed"])
    sliding = solve(five[five["v_t"] >= 50.0])  # the last rows: sliding throughout
    line = -1.0 + 3.5 * sliding["mu"] * (1 + sliding["cor"]) * sliding["v_n"] / sliding["slip"]
    assert np.allclose(sliding["beta"], line, rtol=1e-6) and np.allclose(sliding["spin_ratio"], 5.0, rtol=1e-6)


def test_test_8_has_both_shear_cases_of_its_source():
    """Test 8 as PySPH sets it up (issue 41 item 1): case A with each sphere's shear modulus 1000 times E / (2 (1 +
    nu)), case B with it, per material.  Before, the file held case B alone under the test's name.  Case A's contact is
    1000 times stiffer tangentially, so at a slow spin it nears the rigid contact's answer (the limit of infinite
    stiffness), where case B's compliance turns the spin well away from it."""
    _, tests = load_tests()
    assert tests[8]["shear_cases"] == {"A": 1000.0, "B": 1.0}
    table = scenes_of_test(8)
    cases = table.drop_duplicates("case").set_index("case")["kappa"]
    assert list(cases.index) == ["al-alloy, case A", "al-alloy, case B", "nylon, case A", "nylon, case B"]
    for material, nu in (("al-alloy", 0.33), ("nylon", 0.40)):
        b = cases[f"{material}, case B"]
        assert b == pytest.approx(2 * (1 - nu) / (2 - nu), rel=1e-12)  # 4 G*/E* of like spheres
        assert cases[f"{material}, case A"] == pytest.approx(1000.0 * b, rel=1e-12)
    slow = table[table["spin"] == table["spin"].min()].reset_index(drop=True)
    exact, rigid = solve(slow), solve(scenes_of_test(8, "rigid").iloc[[0]])
    gap = np.abs(exact["omega_f"] - rigid["omega_f"].iloc[0]).to_numpy()
    assert gap[[0, 2]].max() < 2e-3 * rigid["omega_f"].iloc[0] and gap[[1, 3]].min() > 0.05 * rigid["omega_f"].iloc[0]


def test_damped_mindlin_variant_is_the_dem_codes_contact(tmp_path, capsys):
    """The reference's second variant (issue 41): the DEM codes' Mindlin spring with Kratos's tangential dashpot set
    from the test's COR.  Test 7's spheres do not slip, so the dashpot is idle and the paper's V'ct = 0, omega' =
    omega hold in it too; test 6's answer depends on the tangential damping: the damped spring departs from the
    exact elastic contact by more than the default tolerance.  Written by the command line, named in its rows,
    refused for a test without it."""
    out = tmp_path / "damped"
    assert run(["benchmark", "chung-ooi", "--out", str(out), "--tests", "4,5", "--variant", "damped-mindlin"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["test4.csv"]  # test 5 is elastic: one reference
    four = read_table(out / "test4.csv")
    assert set(four["rule"]) == {"mindlin+dashpot"} and set(four["tangential"]) == {"mindlin"}
    chung_ooi.run_study(tmp_path / "study", [4])  # the pipeline's study writes the variant from the DEM rules' table
    assert (tmp_path / "study/damped-mindlin/test4.csv").read_bytes() == (out / "test4.csv").read_bytes()
    assert np.allclose(four["dashpot_cor"], 0.98)
    seven = solve(scenes_of_test(7, "mindlin+dashpot").iloc[[0, 7, 14]])  # slow, middle and fast spins
    assert np.max(np.abs(seven["vc_t"])) < 1e-9 * np.max(seven["spin"] * 0.05)
    assert np.allclose(seven["omega_f"], seven["spin"], rtol=1e-9)
    capsys.readouterr()
    assert run(["benchmark", "chung-ooi", "--out", str(tmp_path / "none"), "--tests", "5",
                "--variant", "damped-mindlin"]) == 2
    assert "none of 5 has a 'damped-mindlin' reference" in capsys.readouterr().err
    rows = [2, 8, 14]  # of test 6's al-alloy spins: slow, middle, fast (the full table is the pipeline's)
    exact, damped = (solve(scenes_of_test(6, rule).iloc[rows].reset_index(drop=True))
                     for rule in ("microslip", "mindlin+dashpot"))
    assert set(exact["rule"]) == {"microslip"} and np.isnan(exact["dashpot_cor"]).all()
    assert pd.testing.assert_series_equal(exact["t_f"], damped["t_f"]) is None  # one normal motion
    departure = np.max(np.abs(damped["vc_t"] - exact["vc_t"])) / np.max(np.abs(exact["vc_t"]))
    assert departure > 0.1  # the tangential damping decides the answer at e = 0.5 (the whole test: the docs block)
    with pytest.raises(ValueError, match="test 5 has no 'damped-mindlin' reference"):
        chung_ooi.reference(5, variant="damped-mindlin")


def test_departure_of_the_dem_rules_on_the_kharaz_ball():
    """The departure study's API (issue 41 item 6): the Kharaz ball's rules each against the exact contact at the same
    incidences, the damped rule with the measured e_n; Chung & Ooi's rows taken from the study's deviations."""
    import yaml

    from sphereimpact.study.departure import departures, kharaz_table

    config = Path(__file__).resolve().parents[1] / "config" / "config.yaml"
    section = yaml.safe_load(config.read_text(encoding="utf-8"))["validation"]
    table = kharaz_table(section, [10.0, 30.0], rules=("mindlin", "mindlin+dashpot"))
    assert list(dict.fromkeys(table["rule"])) == ["microslip", "mindlin", "mindlin+dashpot"]
    chung = pd.DataFrame({"test": [5, 2], "rule": ["mindlin", "mindlin"], "quantity": ["omega_f", "omega_f"],
                          "max_abs": [1.0, 1.0], "max_rel": [0.057, 0.5]})
    found = departures(chung, table).set_index(["scenes", "rule", "quantity"])["max_rel"]
    assert found[("Chung & Ooi test 5", "mindlin", "omega_f")] == 0.057
    assert not any(s == "Chung & Ooi test 2" for s, _, _ in found.index)  # a normal test has no departure shown
    exact, damped = (table[table["rule"] == r].reset_index(drop=True) for r in ("microslip", "mindlin+dashpot"))
    expected = np.max(np.abs(damped["e_t"] - exact["e_t"])) / np.max(np.abs(exact["e_t"]))
    assert found[("Kharaz ball", "mindlin+dashpot", "e_t")] == pytest.approx(expected, rel=1e-12)
    undamped = table[table["rule"] == "mindlin"].reset_index(drop=True)
    assert not np.allclose(undamped["omega_f"], damped["omega_f"], rtol=1e-6)  # the dashpot is there (e_n 0.98)


def test_the_departure_study_refuses_what_it_cannot_run(tmp_path, capsys):
    """The departure study's command line (issue 41 item 6's third door) refuses in one line, before any work: a
    test that is not an oblique one on a plane, and a config without the Kharaz ball; and writes nothing."""
    from sphereimpact.cli import run

    out = tmp_path / "out"
    assert run(["benchmark", "departure", "--tests", "7", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "tests must be some of 4, 5, 6 (the oblique tests on a plane); got 7" in err
    config = tmp_path / "config.yaml"
    config.write_text("validation:\n  sphere: {modulus: 3.8e+11, poisson: 0.23, density: 4000.0}\n  speed: 3.9\n")
    assert run(["benchmark", "departure", "--config", str(config), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "lacks validation.sphere.diameter, validation.anvil.modulus" in err
    # a value the schema refuses is named as the user wrote it (it was reported as E* = -5.28 Pa, a number of ours)
    config.write_text("validation:\n  sphere: {modulus: -5.0, poisson: 0.23, density: 4000.0, diameter: 0.005}\n"
                      "  anvil: {modulus: 7.0e+10, poisson: 0.25}\n  speed: 3.9\n  mu: 0.09\n  cor: 0.98\n"
                      "  model: hunt-crossley\n  angles: '10:20:10'\n")
    assert run(["benchmark", "departure", "--config", str(config), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "config key validation.sphere.modulus: -5.0 is less than or equal to the minimum" in err
    assert not out.exists()


def test_the_reduction_gap_with_a_spring_is_of_the_line_turns_order():
    """Issue 41 item 7: test 8's pairs measured against the planar two-body model with a tangential spring, as with
    the rigid contact: the exact microslip contact's rows with Mindlin's undamped spring at their kappa, the damped
    Mindlin variant's and a linear DEM rule's with their own.  A first-order effect of the turn, so below the turn
    times the speed and of its order; empty on a plane and for a rigid contact's spring."""
    from sphereimpact.study.chung_ooi import _line_turn, reduction_gap

    for rule in ("microslip", "mindlin+dashpot", "linear+dashpot"):
        table = scenes_of_test(8, rule)
        for scene in table["scene"].iloc[[4, 16, 22]]:  # kappa 802 (case A) and 0.8 (case B), spins 0.7 to 2 rad/s
            turn = _line_turn(scene, simulate(scene)) * scene.speed
            spring, rigid = reduction_gap(scene, "spring"), reduction_gap(scene)
            assert 0.05 * turn < spring < turn and 0.5 < spring / rigid < 2.0, (rule, spring, rigid, turn)
    plane = scenes_of_test(5)["scene"].iloc[3]
    assert math.isnan(reduction_gap(plane, "spring")) and math.isnan(reduction_gap(plane))
    assert math.isnan(reduction_gap(table["scene"].iloc[4].with_(tangential="rigid"), "spring"))
    with pytest.raises(ValueError, match="tangential must be 'rigid' or 'spring'; got 'linear'"):
        reduction_gap(table["scene"].iloc[4], "linear")
