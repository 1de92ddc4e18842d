"""A ball described once by what was measured (COR at a stated speed, contact time), calibrated, saved, and
reused through every door: the API, the command line (simulate and sweep) and the pipeline."""

import json

import pandas as pd
import pytest

from sphereimpact import (Measurement, SolverOptions, ball_scene, calibrated_ball, load_ball, save_ball,
                          simulate)
from sphereimpact.cli import run
from sphereimpact.impact.calibrate import TIGHT

#: The golf ball of issue 33: only what was measured.
GOLF = dict(model="hunt-crossley", mass=0.0459, diameter=0.0427, mu=0.3)
MEASURED = Measurement(cor=0.78, speed=40.0, contact_time=4.5e-4)
GOLF_FLAGS = ["--model", "hunt-crossley", "--mass", "0.0459", "--diameter", "0.0427", "--mu", "0.3", "--cor", "0.78",
              "--cor-speed", "40", "--contact-time", "4.5e-4"]


@pytest.fixture(scope="module")
def golf():
    return calibrated_ball(MEASURED, **GOLF)


def test_a_ball_is_calibrated_from_its_measured_numbers_alone(golf):
    at_measurement = simulate(golf.scene, TIGHT)
    assert golf.scene.v_normal == 40.0 and golf.scene.incidence_deg == 0.0
    assert at_measurement.cor == pytest.approx(0.78, rel=1e-9)
    assert at_measurement.t_f == pytest.approx(4.5e-4, rel=1e-9)
    assert set(golf.fitted) == {"chi", "k"} and golf.fitted["k"] == golf.scene.k
    elsewhere = simulate(ball_scene(golf, speed=30.0, angle_to_surface=45.0))  # the same ball, another bounce
    assert elsewhere.cor != pytest.approx(0.78, abs=0.05)  # the law's COR falls with speed: 0.870 at 21 m/s


def test_what_the_measurement_sets_is_not_given_twice():
    with pytest.raises(ValueError, match=r"give chi or cor, not both \(cor sets chi\)"):
        calibrated_ball(MEASURED, chi=0.01, **GOLF)
    with pytest.raises(ValueError, match=r"give modulus or contact_time, not both \(contact_time fits k\)"):
        calibrated_ball(MEASURED, modulus=1e9, **GOLF)
    with pytest.raises(ValueError, match=r"cor_speed must be a finite number > 0 m/s"):
        Measurement(0.78, -1.0)


def test_a_scene_far_from_the_measurement_is_named_with_its_factor(golf):
    assert golf.far_from_measurement(ball_scene(golf, speed=40.0, angle_to_surface=60.0)) is None  # 0.87 times
    line = golf.far_from_measurement(ball_scene(golf, speed=10.0))
    assert "is 0.25 times the 40 m/s at which the COR 0.78 was measured" in line


def test_a_saved_ball_is_the_same_ball(golf, tmp_path):
    path = tmp_path / "golf.json"
    save_ball(golf, path)
    again = load_ball(path)
    assert again.scene == golf.scene and again.measurement == golf.measurement and again.fitted == golf.fitted
    record = json.loads(path.read_text())
    for bad, message in (("{", "is not JSON"), (json.dumps({"scene": {}}), "is not a ball file"),
                         (json.dumps(record | {"format": "sphereimpact-ball/1"}), "its format is 'sphereimpact-ball/1'"),
                         (json.dumps(record | {"ball": {"mass": -1}}), "mass must be"),
                         (json.dumps(record | {"contact": record["contact"] | {"speed": 40.0}}),
                          "section 'contact': 'speed' is part of the approach, which each bounce gives"),
                         (json.dumps(record | {"surface": {"mass": 1.0}}), "section 'surface': it holds gravity, "),
                         (json.dumps(record | {"ball": [1]}), "section 'ball': it holds mass, diameter")):
        (tmp_path / "bad.json").write_text(bad)
        with pytest.raises(ValueError, match=message):
            load_ball(tmp_path / "bad.json")
    with pytest.raises(ValueError, match="cannot read"):
        load_ball(tmp_path / "missing.json")


def test_a_ball_file_holds_the_ball_its_contact_and_surface_never_an_approach(golf, tmp_path):
    """A ball file (issue 42 item 3) holds the ball, its contact and its surface: no approach, which each bounce gives,
    every other Scene field in one section.  Read back, the ball stands in a normal impact at its measurement's speed;
    without a measurement, at the Scene's default approach, whose speed it says was not given."""
    from sphereimpact.impact.ball import APPROACH, SECTIONS
    from sphereimpact.impact.scene import SCENE_KEYS

    path = tmp_path / "golf.json"
    save_ball(golf.__class__(golf.scene.with_(speed=25.0, angle_to_surface=30.0, spin=50.0), golf.measurement,
                             golf.fitted, golf.relations), path)
    record = json.loads(path.read_text())
    held = [name for section in SECTIONS for name in record[section]]
    assert not set(held) & set(APPROACH) and "scene" not in record
    assert sorted(name for names in SECTIONS.values() for name in names) == sorted(
        name for name in SCENE_KEYS if name not in APPROACH)
    assert record["ball"] == {"mass": 0.0459, "diameter": 0.0427, "inertia_factor": 0.4}
    assert load_ball(path).scene == golf.scene  # at the measurement's 40 m/s, normal
    save_ball(golf.__class__(golf.scene.with_(speed=25.0)), path)  # no measurement
    again = load_ball(path).scene
    assert again.speed == 3.0 and again.chapter_approach == ("speed",) and again.chapter_ball == ()


def test_the_command_line_calibrates_saves_and_reuses_the_ball(golf, tmp_path, capsys):
    path = tmp_path / "golf.json"
    assert run(["simulate", *GOLF_FLAGS, "--speed", "40", "--save-ball", str(path), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["cor"] == pytest.approx(0.78, rel=1e-9)
    assert load_ball(path).scene == golf.scene  # the same calibration as the API's
    assert run(["simulate", *GOLF_FLAGS, "--speed", "40", "--save-ball", str(path)]) == 2  # kept, as --out's
    assert "save-ball: " in capsys.readouterr().err and load_ball(path).scene == golf.scene
    assert run(["simulate", "--ball", str(path), "--speed", "30", "--angle-to-surface", "45", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    api = simulate(ball_scene(golf, speed=30.0, angle_to_surface=45.0))
    assert cli["cor"] == api.cor and cli["omega_f"] == api.omega_f
    assert run(["simulate", "--ball", str(path), "--speed", "10"]) == 0  # normal speed 10 m/s: a quarter
    assert "warning: the normal speed 10 m/s is 0.25 times the 40 m/s" in capsys.readouterr().err
    assert run(["simulate", "--ball", str(path), "--k", "1e6"]) == 2
    assert "--k: the ball file" in capsys.readouterr().err
    out = tmp_path / "golf.csv"
    assert run(["sweep", "--ball", str(path), "--speed", "20:40:20", "--angle-to-surface", "30:60:30", "--mu", "0.5",
                "--out", str(out)]) == 0
    table = pd.read_csv(out)
    for row in table.to_dict("records"):
        one = simulate(ball_scene(golf, speed=row["speed"], angle_to_surface=row["angle_to_surface"]).with_(mu=0.5),
                       SolverOptions(rtol=1e-12, atol=1e-12))
        assert row["omega_f"] == pytest.approx(one.omega_f, rel=1e-8) and row["mu"] == 0.5


def test_the_command_line_sweeps_a_ball_calibrated_from_its_measured_numbers(golf, tmp_path, capsys):
    out = tmp_path / "cal.csv"
    assert run(["sweep", *GOLF_FLAGS, "--speed", "30", "--angle-to-surface", "45", "--out", str(out)]) == 0
    row = pd.read_csv(out).iloc[0]
    assert row["k"] == pytest.approx(golf.scene.k, rel=1e-12) and row["chi"] == pytest.approx(golf.scene.chi, rel=1e-12)
    assert run(["sweep", *GOLF_FLAGS[:-2], "--modulus", "1e9", "--contact-time", "4.5e-4", "--speed", "30", "--out",
                str(tmp_path / "x.csv")]) == 2
    assert "give --modulus or --contact-time, not both" in capsys.readouterr().err


def test_a_calibration_at_the_scenes_own_speed_is_said_to_be(capsys):
    """Without --cor-speed the COR is taken as measured at this scene's normal speed: on an oblique scene that is
    rarely what was measured, and a note says so."""
    measured = [*GOLF_FLAGS[:8], "--cor", "0.78", "--contact-time", "4.5e-4"]
    assert run(["simulate", *measured, "--speed", "30", "--angle-to-surface", "45"]) == 0
    assert "note: --cor calibrated the law at this scene's normal speed 21.2132 m/s" in capsys.readouterr().err
    assert run(["simulate", *measured, "--speed", "30"]) == 0
    assert "note" not in capsys.readouterr().err  # a normal impact: its speed is the measurement's


def test_a_study_reuses_a_saved_ball(golf, tmp_path):
    """The pipeline's door in the process: a study config naming the ball file calibrates nothing and gives the
    API's numbers (the pipeline test runs it through Snakemake)."""
    from sphereimpact.study.own import study_ball

    path = tmp_path / "golf.json"
    save_ball(golf, path)
    assert study_ball({"ball_file": str(path)}).scene == golf.scene


@pytest.mark.pipeline
def test_the_pipeline_reuses_a_saved_ball(golf, tmp_path):
    from conftest import project_copy, snakemake

    work = project_copy(tmp_path)
    save_ball(golf, tmp_path / "golf.json")
    config = tmp_path / "golf.yaml"
    config.write_text(f"study: golf\nball_file: {tmp_path / 'golf.json'}\n"
                      "bounces: {drive: {speed: 30.0, angle_to_surface: 45.0}}\n"
                      "ranges: {speeds: '10:40:10', map_speeds: '20:40:20', map_angles: '30:60:30'}\n")
    done = snakemake(work, "results/studies/golf/outcomes.csv", configfiles=[str(config)])
    assert done.returncode == 0, done.stderr[-3000:]
    assert load_ball(work / "results/studies/golf/ball.json").scene == golf.scene
    from sphereimpact.study.own_outputs import read_history

    bounce = read_history(work / "results/studies/golf/outcomes.csv").iloc[0]
    assert bounce["omega_f"] == pytest.approx(simulate(ball_scene(golf, speed=30.0, angle_to_surface=45.0)).omega_f,
                                              rel=1e-9)  # written to 10 digits
