"""The user's terms, not ours (issue 42): nothing of the user's description is substituted, a data file runs no
code, a failed write keeps the old file, and the answers that broke the model's own bounds stay inside them.
Each test failed before its fix."""

import json
import re
import sys
import textwrap

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from sphereimpact import Scene, load_ball, save_ball, simulate
from sphereimpact.cli import run
from sphereimpact.impact.ball import Ball

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def trap(tmp_path, monkeypatch):
    """A module that leaves a marker file when imported, on the module path, and a ball file that names it."""
    marker = tmp_path / "imported"
    (tmp_path / "trap_module.py").write_text(f"open({str(marker)!r}, 'w').write('ran')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "trap_module", raising=False)
    path = tmp_path / "ball.json"
    save_ball(Ball(Scene(), plugins=("trap_module",)), path)
    return path, marker


def test_a_ball_file_never_imports_code(trap, capsys):
    path, marker = trap
    with pytest.raises(ValueError, match="uses the plug-in 'trap_module', which is not loaded"):
        load_ball(path)
    assert run(["simulate", "--ball", str(path), "--json"]) == 2
    assert "never imports code" in capsys.readouterr().err
    assert not marker.exists()


def test_a_ball_file_loads_with_the_plugins_the_user_names(trap):
    path, marker = trap
    ball = load_ball(path, plugins=["trap_module"])
    assert marker.exists() and ball.plugins == ("trap_module",)


def test_the_study_config_check_does_not_import_a_ball_files_plugins(trap, tmp_path):
    from sphereimpact.study.config_check import config_errors

    path, marker = trap
    config = yaml_config(tmp_path, f"study: mine\nball_file: {path}\n")
    errors = config_errors(config, "config/schema.yaml")
    assert any("never imports code" in line for line in errors) and not marker.exists()


def yaml_config(tmp_path, text: str) -> dict:
    import yaml

    return yaml.safe_load(textwrap.dedent(text))


def test_a_ball_file_saved_from_the_chapters_defaults_says_so_at_every_door(tmp_path, capsys):
    """Before: ``simulate --save-ball`` without a ball wrote the chapter's 145 g, 63 mm ball as plain numbers, and every
    door that read the file (sweep, fit, a study's ball_file) took it as the user's, without a word (issue 42 item
    1).  Now the file lists the parts it took (``chapter``); they read back marked, and each door refuses or notes
    them as it does the options' silence."""
    from sphereimpact.fit import fit, read_measured
    from sphereimpact.study.config_check import config_errors

    path = tmp_path / "ball.json"
    assert run(["simulate", "--json", "--mass", "0.05", "--save-ball", str(path)]) == 0
    assert json.loads(path.read_text())["chapter"] == ["diameter", "k", "b"]  # no approach in a ball file
    ball = load_ball(path)
    assert ball.scene.chapter_ball == ("diameter", "k", "b") and ball.scene.mass == 0.05
    assert ball.scene.diameter == 0.063 and ball.scene.k == 60000.0
    capsys.readouterr()
    assert run(["simulate", "--json", "--ball", str(path), "--speed", "2"]) == 0
    assert (f"the ball file {str(path)!r} holds the chapter's ball where its maker was silent (diameter 0.063 m, "
            "k 60000 N/m, b 10.5 N s/m)") in capsys.readouterr().err
    out = tmp_path / "sweep.csv"
    assert run(["sweep", "--ball", str(path), "--speed", "2", "--angle", "30:60:30", "--out", str(out)]) == 2
    assert "its diameter, k, b are the chapter's defaults" in capsys.readouterr().err and not out.exists()
    assert run(["sweep", "--ball", str(path), "--speed", "2", "--angle", "30:60:30", "--out", str(out),
                "--chapter-ball"]) == 0
    assert len(pd.read_csv(out)) == 2
    bounces = read_measured(pd.DataFrame({"speed": 2.0, "incidence": [10.0, 30.0], "e_t": [0.7, 0.6]}))
    with pytest.raises(ValueError, match="fit: describe the ball: its diameter, k, b are the chapter's"):
        fit(bounces, ball, ["mu"])
    errors = config_errors(yaml_config(tmp_path, f"study: mine\nball_file: {path}\n"), "config/schema.yaml")
    assert any("takes the chapter's diameter, k, b" in line for line in errors)
    described = tmp_path / "mine.json"  # a described ball keeps no list
    assert run(["simulate", "--json", "--mass", "0.05", "--diameter", "0.04", "--k", "1e4", "--b", "1",
                "--speed", "2", "--save-ball", str(described)]) == 0
    assert "chapter" not in json.loads(described.read_text()) and load_ball(described).scene.chapter_ball == ()


def test_plugins_in_a_ball_file_must_be_a_list_of_names(tmp_path):
    path = tmp_path / "ball.json"
    save_ball(Ball(Scene()), path)
    record = json.loads(path.read_text())
    path.write_text(json.dumps(record | {"plugins": "trap_module"}))
    with pytest.raises(ValueError, match="plugins must be a list of module names"):
        load_ball(path)


KHARAZ = "data/kharaz2001.csv"
#: Kharaz's alumina ball, as the data file's header states it (5 mm, 4000 kg/m^3, E 380 GPa on glass) at 3.9 m/s.
ALUMINA = ["--mass", "2.618e-4", "--diameter", "0.005", "--model", "hertz", "--modulus", "1.5e11"]


def test_fit_refuses_a_ball_it_was_not_given(capsys):
    """Before: the Kharaz data were fitted as the chapter's 145 g, 63 mm ball at 3 m/s, exit 0, no word."""
    assert run(["fit", KHARAZ, "--free", "mu"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "give --mass, --diameter, --k or --contact-time, --b or --cor (or --ball FILE" in err
    assert run(["fit", KHARAZ, "--free", "mu", *ALUMINA]) == 2  # the ball, but not the bounces' speed
    assert "has no speed column: give the bounces' approach speed along the path with --speed" in capsys.readouterr().err
    assert run(["fit", KHARAZ, "--free", "mu", *ALUMINA, "--speed", "3.9", "--json"]) == 0


def test_plan_refuses_candidates_without_their_speed(tmp_path, capsys):
    """Before: plan of candidates without a speed column ran them at the ball file's own speed (the 34.6 m/s its COR
    was calibrated at), exit 0, no word; fit refused the same bounces.  Now plan refuses them as fit does."""
    ball, candidates = tmp_path / "golf.json", tmp_path / "candidates.csv"
    assert run(["simulate", "--mass", "0.0459", "--diameter", "0.0427", "--model", "hunt-crossley", "--modulus", "1e8",
                "--cor", "0.8", "--speed", "40", "--save-ball", str(ball)]) == 0
    candidates.write_text("incidence\n10\n20\n30\n40\n")
    capsys.readouterr()
    assert run(["plan", str(candidates), "--ball", str(ball), "--free", "mu", "--noise", "e_t=0.02"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "has no speed column: give the bounces' approach speed along the path" in err
    assert run(["plan", str(candidates), "--ball", str(ball), "--free", "mu", "--noise", "e_t=0.02", "--speed", "30"]) == 0


def test_fit_out_must_name_a_folder(tmp_path, monkeypatch, capsys):
    """Before: --out "" wrote ball.json, fit.json, residuals.csv and fit.png into the current folder."""
    monkeypatch.chdir(tmp_path)
    assert run(["fit", str(ROOT / KHARAZ), "--free", "mu", *ALUMINA, "--speed", "3.9", "--out", ""]) == 2
    assert "out: give a folder's name" in capsys.readouterr().err and not list(tmp_path.iterdir())


def test_simulate_says_when_it_runs_the_chapters_ball(capsys):
    assert run(["simulate", "--json"]) == 0
    assert ("note: the chapter's ball where the options are silent (mass 0.145 kg, diameter 0.063 m, k 60000 N/m, "
            "b 10.5 N s/m)") in capsys.readouterr().err
    ball = ["--mass", "0.05", "--diameter", "0.04", "--model", "hunt-crossley", "--modulus", "1e7"]
    assert run(["simulate", "--json", *ball, "--speed", "3"]) == 0
    assert "note" not in capsys.readouterr().err
    # before: a described ball without --speed ran at the chapter's 3 m/s without a word
    assert run(["simulate", "--json", *ball]) == 0
    err = capsys.readouterr().err
    assert "note: the chapter's approach speed 3 m/s where --speed is silent" in err and "chapter's ball" not in err


def test_the_api_says_which_parts_of_the_ball_are_the_chapters(capsys):
    """Before: Scene() took the chapter's ball and nothing in the API said so (the command line alone noted it).  Now
    every scene and outcome names the parts it took (issue 42 item 1), through copies, calibration and a partner; the
    command line's note is built from what the API says."""
    from sphereimpact import simulate
    from sphereimpact.impact.ball import chapter_parts
    from sphereimpact.impact.calibrate import calibrate

    chapter = ("mass", "diameter", "k", "b")
    assert Scene().chapter_ball == chapter and simulate(Scene(angle=60)).chapter_ball == chapter
    assert Scene(mass=0.145, diameter=0.063, k=60000.0, b=10.5).chapter_ball == ()  # the same numbers, given
    assert Scene(mass=0.145, diameter=0.063, k=60000.0, b=10.5) == Scene()
    assert Scene().with_(speed=5.0, angle=30.0).chapter_ball == chapter
    assert Scene(**Scene().as_dict()).chapter_ball == chapter
    assert calibrate(Scene(), 0.6).scene.chapter_ball == ("mass", "diameter", "k")  # b is set by the COR
    assert Scene(model="hunt-crossley", modulus=1e7).chapter_ball == ("mass", "diameter")
    assert Scene(mass=0.05, diameter=0.04, model="hertz", modulus=1e7).chapter_ball == ()
    pair = simulate(Scene(partner_mass=1.0, partner_diameter=0.1, mass=0.2, diameter=0.07, angle=0.0))
    assert pair.chapter_ball == ("k", "b")
    assert chapter_parts(Scene(mass=0.2)) == ["diameter", "k or contact_time", "b or cor"]
    # the approach speed alike: the API says when it is the chapter's, and the command line's note reads it
    assert Scene().chapter_approach == ("speed",) and Scene(speed=3.0).chapter_approach == ()
    assert simulate(Scene(angle=60.0)).scene.chapter_approach == ("speed",)
    assert Scene(**Scene().as_dict()).chapter_approach == ("speed",) and Scene().with_(speed=5.0).chapter_approach == ()
    assert run(["simulate", "--json", "--mass", "0.2", "--cor", "0.7"]) == 0
    said = capsys.readouterr().err
    assert "(diameter 0.063 m, k 60000 N/m); describe yours with --diameter, --k or --contact-time" in said


def test_the_api_sweep_refuses_a_ball_it_was_not_given():
    """Before: sweep() of a table without mass or diameter swept the chapter's 145 g, 63 mm ball without a word, where
    the command line's sweep refused it, and a table without speed took the chapter's 3 m/s (issue 42 item 1).  Now
    the API refuses, naming the first row and what it lacks, and takes the chapter's ball and speed only when asked;
    the answer asked for is the described ball's."""
    from sphereimpact.sweep import sweep

    chapter = {"mass": 0.145, "diameter": 0.063, "k": 6e4, "b": 10.5}
    with pytest.raises(ValueError, match=r"row 0 lacks mass, diameter, k, b, speed \("):
        sweep({"angle": [30.0]})
    with pytest.raises(ValueError, match=r"row 0 lacks b \("):
        sweep({"angle": [30.0], "speed": 3.0, **{n: v for n, v in chapter.items() if n != "b"}})
    with pytest.raises(ValueError, match=r"row 0 lacks speed \("):  # the approach is the user's too
        sweep({"angle": [30.0], **chapter})
    table = pd.DataFrame({"angle": [30.0, 40.0, 50.0], "mass": [0.145, 0.145, np.nan], "diameter": 0.063, "speed": 3.0})
    with pytest.raises(ValueError, match=r"row 2 lacks mass"):  # an empty cell: that row is silent
        sweep(table.assign(k=6e4, b=10.5))
    with pytest.raises(ValueError, match=r"row 1 lacks k \("):  # per row, per law
        sweep(table.iloc[:2].assign(model=["hertz", "modified"], k=[1e7, np.nan], b=10.5))
    hertz = sweep({"angle": [30.0], "speed": 3.0, "mass": 0.1, "diameter": 0.05, "model": "hertz", "modulus": 1e8})
    assert hertz["mass"].iloc[0] == 0.1  # a law without the chapter's defaults needs only the ball
    described = sweep({"angle": [30.0], "speed": 3.0, **chapter})
    asked = sweep({"angle": [30.0]}, chapter_ball=True)
    assert described.equals(asked)
    assert asked["vc_t"].iloc[0] == pytest.approx(simulate(Scene(angle=30.0)).vc_t, rel=1e-8)
    with pytest.raises(ValueError, match="chapter_ball must be True or False"):
        sweep({"angle": [30.0]}, chapter_ball="yes")


def test_the_api_fit_and_plan_refuse_a_ball_they_were_not_given():
    """Before: fit(measured, Ball(Scene()), ["mu"]) fitted the bounces as the chapter's 145 g, 63 mm ball, exit
    without a word, where the command line refuses it (issue 42 item 1); plan likewise.  Now both name the parts the
    ball took from the chapter and take them only when asked."""
    from sphereimpact.fit import fit, read_measured
    from sphereimpact.fit.plan import plan

    bounces = pd.DataFrame({"speed": 3.0, "incidence": [10.0, 20.0, 30.0, 40.0], "e_t": [0.7, 0.6, 0.65, 0.7]})
    with pytest.raises(ValueError, match=r"fit: describe the ball: its mass, diameter, k, b are the chapter's"):
        fit(read_measured(bounces), Ball(Scene()), ["mu"])
    with pytest.raises(ValueError, match=r"plan: describe the ball: its mass, diameter are the chapter's"):
        plan(bounces[["speed", "incidence"]], Ball(Scene(model="hertz", modulus=1e8)), ["mu"], "e_t=0.02")
    described = Ball(Scene(mass=0.145, diameter=0.063, k=6e4, b=10.5))
    asked = fit(read_measured(bounces), Ball(Scene()), ["mu"], chapter_ball=True)
    assert asked.parameters["mu"].value == fit(read_measured(bounces), described, ["mu"]).parameters["mu"].value


def long_table(tmp_path, rows, columns="quantity,incidence_deg,value"):
    path = tmp_path / "long.csv"
    path.write_text(columns + "\n" + "\n".join(rows) + "\n")
    return path


def test_the_long_layout_reads_every_column_or_refuses_it(tmp_path):
    """Before: a speed or sigma column was read as if absent, and a typo'd or empty value dropped ("fitted to 23
    measured values of 24"), while the wide layout refused the same typo."""
    from sphereimpact.fit import read_measured

    read = read_measured(long_table(tmp_path, ["e_t,30,0.6,0.02,3.9", "omega_rad_s,30,150,5,3.5"],
                                   "quantity,incidence_deg,value,sigma,speed"))
    assert read.bounces["speed"].tolist() == [3.9, 3.5]
    assert read.values[["quantity", "value", "sigma"]].values.tolist() == [["e_t", 0.6, 0.02], ["abs_omega_f", 150.0, 5.0]]
    for rows, message in ((["e_t,30,0.6", "e_t,40,O.7"], "column 'value' row 1: 'O.7' is not a finite number"),
                          (["e_t,30,0.6", "e_t,40,"], "column 'value' row 1: an empty cell"),
                          (["e_t,30,0.6", "e_t,,0.7"], "column 'incidence_deg' row 1"),
                          (["spin_rate,30,0.6"], "unknown quantity 'spin_rate'")):
        with pytest.raises(ValueError, match=message):
            read_measured(long_table(tmp_path, rows))
    with pytest.raises(ValueError, match="column 'mass' is not one of the long layout's"):
        read_measured(long_table(tmp_path, ["e_t,30,0.6,0.1"], "quantity,incidence_deg,value,mass"))


def test_the_long_layouts_speed_reaches_the_fit(tmp_path):
    """The same bounces at another speed fit to another mu: the speed column is the bounces', not the options'."""
    from sphereimpact.fit import fit, read_measured
    from sphereimpact.impact.ball import Ball

    ball = Ball(Scene(model="hertz", modulus=1.5e11, mass=2.618e-4, diameter=0.005, mu=0.1))
    rows = ["e_t,50,0.85,,{v}", "e_t,60,0.9,,{v}", "e_t,70,0.93,,{v}"]
    fits = [fit(read_measured(long_table(tmp_path, [r.format(v=v) for r in rows],
                                         "quantity,incidence_deg,value,sigma,speed")), ball, ["mu"])
            for v in (2.0, 3.9)]
    assert fits[0].residuals["speed"].tolist() == [2.0] * 3 and fits[1].residuals["speed"].tolist() == [3.9] * 3


def test_one_gravity_default_at_every_door():
    """Before: a study's surface defaulted to 9.80665 m/s^2, simulate, fit and Scene to 0: the same bounces fitted
    to mu 0.5426 in a study and 0.5444 on the command line."""
    import yaml

    from sphereimpact.cli import _parser
    from sphereimpact.study.config import with_defaults
    from sphereimpact.study.own import study_ball

    schema = yaml.safe_load((ROOT / "config/schema.yaml").read_text())
    config = with_defaults(schema, {"study": "mine", "ball": {"mass": 0.05, "diameter": 0.04},
                                    "contact": {"modulus": 1e7}, "bounces": {"drop": {"speed": 5.0}}})
    cli = {name: _parser().parse_args([name, *extra]).gravity
           for name, extra in (("simulate", []), ("fit", ["x.csv", "--free", "mu"]))}
    assert study_ball(config).scene.gravity == Scene().gravity == cli["simulate"] == cli["fit"] == 0.0


ELASTIC = [("modified", {"b": 0.0}), ("linear-hunt-crossley", {"chi": 0.0}), ("kelvin-voigt", {"b": 0.0}),
           ("hertz", {"k": 1e7}), ("hunt-crossley", {"k": 1e7, "chi": 0.0})]


@pytest.mark.parametrize("model, parameters", ELASTIC, ids=[m for m, _ in ELASTIC])
def test_an_elastic_contact_never_rebounds_faster_than_it_came(model, parameters):
    """Before: COR 1 + 1e-12 ... 1 + 1e-10 (modified, linear-hunt-crossley: Taylor, DOP853-scalar, Radau).  A
    passive law's COR is at most 1 on every method, and still 1 to each method's accuracy."""
    from sphereimpact import SolverOptions, simulate
    from sphereimpact.integrators import method_names

    scene = Scene(model=model, **parameters)
    assert scene.law.passive
    for method in method_names():
        try:
            out = simulate(scene, SolverOptions(method=method))
        except ValueError:  # closed and taylor serve the laws that have them
            continue
        assert 1.0 - 1e-8 <= out.cor <= 1.0, method


@pytest.mark.parametrize("b", [1e-5, 3e-5, 1e-4])
def test_a_lightly_damped_contact_ends_where_its_force_does(b):
    """Before: kelvin-voigt at zeta 5e-8 ... 2e-7 ended at delta = 0, not P = 0, 3.4e-8 ... 1e-7 of t_f late with
    every step-by-step method.  Held against the law's closed form."""
    from sphereimpact import SolverOptions, simulate

    scene = Scene(model="kelvin-voigt", b=b)
    exact = simulate(scene, SolverOptions(method="closed"))
    for method in ("taylor", "DOP853-scalar", "DOP853", "Radau", "RK45"):
        out = simulate(scene, SolverOptions(method=method))
        assert out.t_f == pytest.approx(exact.t_f, rel=1e-10), method
        assert out.cor == pytest.approx(exact.cor, rel=1e-9), method


def test_a_contact_time_calibration_of_a_nearly_elastic_ball_meets_its_contact_time():
    """The calibration inherited the late end: at COR 0.9999999 its contact time missed by the same 1e-7."""
    from sphereimpact import Measurement, SolverOptions, calibrated_ball, simulate

    ball = calibrated_ball(Measurement(0.9999999, 3.0, contact_time=5e-3), model="kelvin-voigt",
                           mass=0.145, diameter=0.063)
    out = simulate(ball.scene, SolverOptions(method="closed"))
    assert out.t_f == pytest.approx(5e-3, rel=1e-9) and out.cor == pytest.approx(0.9999999, rel=1e-9)


def test_sweep_refuses_a_ball_it_was_not_given(tmp_path, capsys):
    """Before: a sweep without a ball swept the chapter's, silently.  --chapter-ball asks for it; simulate says it."""
    out = tmp_path / "s.csv"
    assert run(["sweep", "--angle", "30", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and ("sweep: describe your ball and its speed: give --mass, --diameter, --k or "
                                      "--contact-time, --b or --cor, --speed (or --ball FILE") in err
    assert not out.exists()
    hertz = ["sweep", "--angle", "30", "--model", "hunt-crossley", "--modulus", "1e7", "--out", str(out)]
    assert run([*hertz, "--speed", "3"]) == 2
    assert "give --mass, --diameter (or --ball FILE" in capsys.readouterr().err
    # the approach is the user's too: before, a sweep of a described ball took the chapter's 3 m/s unasked
    assert run([*hertz, "--mass", "0.1", "--diameter", "0.05"]) == 2
    assert "sweep: give --speed, the approach speed [m/s]" in capsys.readouterr().err and not out.exists()
    assert run(["sweep", "--chapter-ball", "--angle", "30", "--out", str(out)]) == 0 and out.exists()
    assert run(["simulate", "--chapter-ball", "--angle", "30", "--json"]) == 0
    assert "note" not in capsys.readouterr().err
    ball = tmp_path / "ball.json"
    save_ball(Ball(Scene()), ball)
    assert run(["simulate", "--ball", str(ball), "--chapter-ball", "--json"]) == 0  # the file's chapter parts, asked for
    assert "note" not in capsys.readouterr().err


def test_a_failed_ball_write_keeps_the_old_ball(tmp_path, monkeypatch):
    """Before: save_ball wrote in place, so --save-ball --force that failed left a truncated ball."""
    path = tmp_path / "ball.json"
    save_ball(Ball(Scene(mass=0.05)), path)
    old = path.read_text()

    def full_disk(self, text, encoding=None):
        Path.open(self, "w").write(text[:20])  # part of it, then the disk is full
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Path, "write_text", full_disk)
    with pytest.raises(OSError):
        save_ball(Ball(Scene(mass=0.07)), path)
    monkeypatch.undo()
    assert path.read_text() == old and [p.name for p in tmp_path.iterdir()] == ["ball.json"]


def test_a_failed_fit_keeps_the_old_fit_folder_whole(tmp_path, monkeypatch):
    """Before: fit --out DIR --force replaced ball.json and fit.json, then failed on the figure: a folder whose ball
    came from one fit and whose residuals and figure from another."""
    import sphereimpact.study.fitting as fitting
    from sphereimpact.fit import FIT_FILES, fit, read_measured
    from sphereimpact.impact.ball import Ball as BallFile

    ball = BallFile(Scene(model="hertz", modulus=1.5e11, mass=2.618e-4, diameter=0.005, speed=3.9, mu=0.1))
    result = fit(read_measured(ROOT / KHARAZ), ball, ["mu"])
    folder = tmp_path / "fitted"
    fitting.write_fit(result, folder)
    before = {name: (folder / name).read_bytes() for name in FIT_FILES}

    def broken(*args, **kwargs):
        raise RuntimeError("the figure failed")

    monkeypatch.setattr(fitting, "fit_figure", broken)
    with pytest.raises(RuntimeError):
        fitting.write_fit(fit(read_measured(ROOT / KHARAZ), ball.__class__(ball.scene.with_(mu=0.3)), ["mu"]), folder)
    assert {name: (folder / name).read_bytes() for name in FIT_FILES} == before
    assert sorted(p.name for p in folder.iterdir()) == sorted(FIT_FILES)


def test_a_failed_reference_write_keeps_the_old_file(tmp_path, monkeypatch):
    import pandas as pd

    from sphereimpact.study.chung_ooi import write_table

    path = tmp_path / "test1.csv"
    path.write_text("old\n")

    def killed(self, where, **kwargs):
        Path(where).write_text("par")
        raise KeyboardInterrupt

    monkeypatch.setattr(pd.DataFrame, "to_csv", killed)
    with pytest.raises(KeyboardInterrupt):
        write_table(pd.DataFrame({"mu": [0.1]}), path)
    assert path.read_text() == "old\n" and [p.name for p in tmp_path.iterdir()] == ["test1.csv"]


def test_a_partner_rows_ball_is_checked_as_given_whatever_the_other_rows_leave_empty():
    """Before: with an empty cell elsewhere in the column, the pair sweep checked the reduced sphere's value: a ball
    of -0.5 kg on a 0.3 kg partner reduces to +0.75 kg and was answered; an inertia factor 5 was named as 1.05."""
    import numpy as np
    import pandas as pd

    from sphereimpact.sweep import sweep

    pair = dict(angle=30.0, speed=3.0, partner_mass=0.3, partner_diameter=0.1)
    for name, bad, shown in (("mass", -0.5, "got -0.5 (row 0)"), ("diameter", -0.063, "got -0.063 (row 0)"),
                             ("inertia_factor", 5.0, "got 5.0 (row 0)")):
        with pytest.raises(ValueError, match=rf"{name} must be .*{re.escape(shown)}"):
            sweep(pd.DataFrame([pair | {name: bad}, pair | {name: np.nan}]), outputs=["cor"], chapter_ball=True)


def test_an_empty_gravity_cell_on_a_partner_row_is_the_default():
    """Before: refused as if given ("gravity must be 0 with a partner sphere; got nan").  Each row is simulate's."""
    import numpy as np
    import pandas as pd

    from sphereimpact import simulate
    from sphereimpact.sweep import sweep

    rows = [dict(angle=30.0, speed=3.0, gravity=9.80665, partner_mass=np.nan, partner_diameter=np.nan),
            dict(angle=30.0, speed=3.0, gravity=np.nan, partner_mass=0.3, partner_diameter=0.1)]
    table = sweep(pd.DataFrame(rows), outputs=["cor", "vc_t", "omega_f", "partner_vc_n"], chapter_ball=True)
    flat = simulate(Scene(angle=30.0, gravity=9.80665))
    partner = simulate(Scene(angle=30.0, partner_mass=0.3, partner_diameter=0.1))
    for row, out in ((0, flat), (1, partner)):
        for key in ("cor", "vc_t", "omega_f"):
            assert table[key].iloc[row] == pytest.approx(getattr(out, key), rel=1e-7, abs=1e-9), (row, key)
    assert table["partner_vc_n"].iloc[1] == pytest.approx(partner.partner_vc_n, rel=1e-7)


def test_a_ball_no_ball_resembles_is_flagged_with_its_likely_unit_slip(capsys):
    """Before: --mass 45.9 --diameter 42.7 (grams and millimetres typed as SI) ran silently, a 0.585 m compression."""
    import pandas as pd

    from sphereimpact.errors import UnitWarning
    from sphereimpact.sweep import sweep

    with pytest.warns(UnitWarning, match=r"density is 0.00113 kg/m\^3 .*: is the diameter in millimetres\?") as said:
        Scene(mass=45.9, diameter=42.7)
    with pytest.warns(UnitWarning, match=r"density is 1.13e\+06 kg/m\^3 .*: is the mass in grams\?"):
        Scene(mass=45.9, diameter=0.0427)
    with pytest.warns(UnitWarning, match="partner sphere's mean density"):
        Scene(partner_mass=300.0, partner_diameter=0.1)
    with pytest.warns(UnitWarning, match=r"\(2 of 3 rows, the first row 1\)") as swept:
        sweep(pd.DataFrame({"mass": [0.0459, 45.9, 45.9], "diameter": [0.0427, 42.7, 42.7]}), outputs=["cor"], chapter_ball=True)
    assert len([w for w in swept if w.category is UnitWarning]) == 1  # once for the table, not once per row
    assert run(["simulate", "--mass", "45.9", "--diameter", "42.7", "--model", "hertz", "--modulus", "1e8"]) == 0
    assert f"sphereimpact: warning: {said[0].message}" in capsys.readouterr().err  # the API's words, one line


def test_the_api_warns_where_the_command_line_does(tmp_path, capsys):
    """Before: a calibrated law used at 0.25 x its measurement's speed, and a sweep whose tangential model made
    energy, were said by the command line alone."""
    import pandas as pd

    from sphereimpact import Measurement, ball_scene, calibrated_ball
    from sphereimpact.errors import EnergyGainWarning, ExtrapolationWarning
    from sphereimpact.sweep import sweep
    from sphereimpact.sweep.calibrate import calibrate_table

    golf = calibrated_ball(Measurement(0.78, 40.0), model="hunt-crossley", modulus=1e8, mass=0.0459, diameter=0.0427)
    with pytest.warns(ExtrapolationWarning, match="is 0.25 times the 40 m/s at which the COR 0.78 was measured") as said:
        ball_scene(golf, speed=10.0)
    path = tmp_path / "golf.json"
    save_ball(golf, path)
    assert run(["simulate", "--ball", str(path), "--speed", "10"]) == 0
    assert f"sphereimpact: warning: {said[0].message}" in capsys.readouterr().err
    table = pd.DataFrame({"speed": [10.0, 40.0], "model": "hunt-crossley", "modulus": 1e8, "mass": 0.0459,
                          "diameter": 0.0427})
    with pytest.warns(ExtrapolationWarning, match="1 of 2 scenes have a normal speed more than 2 times"):
        calibrate_table(table, Measurement(0.78, 40.0))
    energetic = {"incidence": [20.0, 40.0], "speed": 5.0, "model": "hertz", "modulus": 1e7,  # test_f14's scene
                 "tangential": "mindlin-displacement", "kappa": 0.99, "mu": 0.65}
    with pytest.warns(EnergyGainWarning, match=r"in 1 of 2 scenes the tangential model made energy") as gained:
        sweep(energetic, chapter_ball=True)
    out = tmp_path / "e.csv"
    args = ["sweep", "--chapter-ball", "--incidence", "20:40:20", "--speed", "5", "--model", "hertz", "--modulus", "1e7",
            "--tangential", "mindlin-displacement", "--kappa", "0.99", "--mu", "0.65", "--out", str(out)]
    assert run(args) == 0 and f"sphereimpact: warning: {gained[0].message}" in capsys.readouterr().err


CHATTER = [dict(angle=2.0, mu=mu, kappa=kappa, spin=spin) for mu, kappa, spin in
           ((0.2, 0.3, -50.0), (0.2, 0.3, 50.0), (0.5, 0.8, 50.0), (0.2, 0.3, 0.0), (0.5, 0.8, 0.0))]


@pytest.mark.parametrize("spec", CHATTER, ids=[f"mu{s['mu']}-kappa{s['kappa']}-spin{s['spin']}" for s in CHATTER])
def test_a_linear_spring_at_a_force_that_closes_at_separation_does_not_chatter(spec):
    """Before: eq. 4.2 (b 40) under the penetration criterion, whose force closes to zero at separation, found a stick
    root 3 ulp before t_f and alternated zero-length phases there: simulate refused ('more than 54 stick-slip
    switches') at one rtol and answered at the next, with a regime that flipped; the sweep refused the table."""
    from sphereimpact import SolverOptions, simulate
    from sphereimpact.sweep import sweep

    scene = Scene(model="modified", b=40.0, separation="penetration", tangential="linear", **spec)
    outs = [simulate(scene, SolverOptions(rtol=rtol, atol=rtol)) for rtol in (1e-8, 1e-10, 1e-12)]
    assert len({(out.regime, out.switches) for out in outs}) == 1
    for out in outs[:2]:
        assert out.vc_t == pytest.approx(outs[2].vc_t, rel=1e-6) and out.omega_f == pytest.approx(outs[2].omega_f, rel=1e-6)
    row = sweep({key: [value] for key, value in spec.items()} | dict(model="modified", b=40.0, separation="penetration",
                                                                     tangential="linear"), chapter_ball=True)
    one = simulate(scene)
    assert row["regime"][0] == one.regime and row["vc_t"][0] == pytest.approx(one.vc_t, rel=1e-7)


def test_the_single_path_keeps_one_chunk_of_outcomes_at_a_time(monkeypatch):
    """Before: the single path (gravity on a slope, compliant contacts) kept every row's Outcome, its motion and dense
    output, until the table was done: about 40 kB a scene against the size check's 0.6 kB, so 520k scenes needed 25 GB
    and were accepted.  Now a chunk's outcomes are gone before the next chunk is solved, and the rows still agree
    with simulate."""
    import gc
    import weakref

    import numpy as np
    import pandas as pd

    import sphereimpact.sweep.paths as paths
    from sphereimpact import simulate
    from sphereimpact.sweep import sweep

    alive, seen = [], []
    solve = paths.simulate_many

    def counting(scenes, options):
        gc.collect()
        seen.append(sum(ref() is not None for ref in alive))
        outs = solve(scenes, options)
        alive.extend(weakref.ref(out) for out in outs)
        return outs

    monkeypatch.setattr(paths, "simulate_many", counting)
    table = pd.DataFrame({"angle": np.linspace(5.0, 60.0, 2 * paths.SINGLES_CHUNK + 10), "gravity": 9.80665})
    out = sweep(table, outputs=["vc_t", "omega_f"], chapter_ball=True)
    assert set(out["path"]) == {"single"} and len(seen) == 3 and seen == [0, 0, 0]
    for i in (0, len(table) - 1):
        one = simulate(Scene(angle=float(table["angle"][i]), gravity=9.80665))
        assert out["vc_t"][i] == pytest.approx(one.vc_t, rel=1e-7) and out["omega_f"][i] == pytest.approx(one.omega_f, rel=1e-7)


def alumina(mu: float) -> Ball:
    """Kharaz's alumina ball on glass at 3.9 m/s (as the data file's header states it)."""
    return Ball(Scene(model="hertz", modulus=1.5e11, mass=2.618e-4, diameter=0.005, speed=3.9, mu=mu))


def test_a_fit_started_where_every_bounce_grips_finds_friction_from_another_start():
    """Before: started at mu 1, where every Kharaz bounce grips and no output depends on mu, the fit stopped there and
    called mu 'not identifiable ... the measured values do not depend on it'."""
    from sphereimpact.fit import fit, read_measured

    data = read_measured(ROOT / KHARAZ)
    good, flat = fit(data, alumina(0.1), ["mu"]), fit(data, alumina(1.0), ["mu"])
    assert flat.parameters["mu"].identifiable
    assert flat.parameters["mu"].value == pytest.approx(good.parameters["mu"].value, rel=1e-6)
    assert flat.statistics["start"] == {"mu": 1.0}
    assert any(note.startswith("the data did not depend on every parameter at the start (mu = 1); also started from")
               for note in flat.notes)
    assert not any("started from" in note for note in good.notes)  # a good start costs nothing more


def test_a_fit_says_what_its_chi2_means_and_flags_data_no_ball_gives(tmp_path, capsys):
    """Before: COR 2 (no passive contact gives it) fitted to chi2/dof 1, printed as a quality; with sigmas from the
    scatter chi2/dof is 1 by construction."""
    import pandas as pd

    from sphereimpact.fit import fit, read_measured

    impossible = pd.DataFrame({"speed": 3.0, "incidence": 0.0, "cor": [2.0, 2.1, 1.9, 2.0]})
    result = fit(read_measured(impossible), Ball(Scene(model="kelvin-voigt", k=6e4, b=10.5)), ["b"],
                 chapter_ball=True)
    assert result.statistics["weights"] == "scatter"
    assert any(note.startswith("4 of 4 measured cor lie outside what the model can give ([0, 1] for a passive contact")
               for note in result.notes)
    path = tmp_path / "impossible.csv"
    impossible.to_csv(path, index=False)
    assert run(["fit", str(path), "--free", "b", "--chapter-ball", "--model", "kelvin-voigt"]) == 0
    out = capsys.readouterr().out
    assert "near 1 by construction" in out and "no parameter reaches them" in out
    stated = pd.DataFrame({"speed": 3.0, "incidence": 0.0, "cor": [0.9, 0.91, 0.89, 0.9], "sigma_cor": 0.001})
    misfit = fit(read_measured(stated), Ball(Scene(model="linear-hunt-crossley", k=6e4, chi=0.05)), ["chi"],
                 chapter_ball=True)
    assert misfit.statistics["weights"] == "given"
    assert any(note.startswith("the model misses the data beyond their stated uncertainties: chi2/dof 66.7")
               for note in misfit.notes)


PAIR = ["--model", "hunt-crossley", "--modulus", "1e8", "--mass", "0.05", "--diameter", "0.04",
        "--partner-mass", "0.1", "--partner-diameter", "0.05"]


def test_sweep_calibrates_a_pair_as_simulate_does(tmp_path, capsys):
    """Before: sweep --cor with a partner was refused ('partner_mass is not a parameter of model ...') where simulate
    answered; and the sweep's default cor_speed was the path's speed where simulate's is the normal one."""
    import json

    import pandas as pd

    out = tmp_path / "pair.csv"
    assert run(["sweep", "--speed", "3", "--angle", "30", *PAIR, "--cor", "0.8", "--out", str(out)]) == 0
    row = pd.read_csv(out).iloc[0]
    assert run(["simulate", "--speed", "3", "--angle", "30", *PAIR, "--cor", "0.8", "--json"]) == 0
    one = json.loads(capsys.readouterr().out)
    for key in ("vc_t", "vc_n", "omega_f", "partner_vc_n", "cor"):
        assert row[key] == pytest.approx(one[key], rel=1e-7), key
    assert row["cor"] == pytest.approx(0.8, rel=1e-7)
    assert run(["sweep", "--speed", "3", "--angle", "0:30:30", *PAIR, "--cor", "0.8", "--out", str(out), "--force"]) == 2
    assert "cor_speed is required when the sweep's scenes have several normal speeds" in capsys.readouterr().err


def test_a_fit_takes_what_was_measured_of_the_partner(tmp_path, capsys):
    """Before: a measured partner_vc_t was refused ('neither an approach ... nor a measurable quantity')."""
    import pandas as pd

    from sphereimpact import simulate
    from sphereimpact.fit import fit, read_measured

    pair = dict(model="hunt-crossley", modulus=1e8, chi=0.1, mass=0.05, diameter=0.04, partner_mass=0.1,
                partner_diameter=0.05)
    rows = []
    for incidence in (20.0, 40.0, 60.0):
        out = simulate(Scene(incidence=incidence, mu=0.15, **pair))
        rows.append({"speed": 3.0, "incidence": incidence, "partner_vc_t": out.partner_vc_t,
                     "partner_omega_f": out.partner_omega_f})
    path = tmp_path / "pair.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    result = fit(read_measured(path), Ball(Scene(mu=0.4, **pair)), ["mu"])
    assert result.parameters["mu"].value == pytest.approx(0.15, rel=1e-6)
    flat = {key: value for key, value in pair.items() if not key.startswith("partner")}
    with pytest.raises(ValueError, match="partner_omega_f is the partner sphere's, and the ball strikes the flat"):
        fit(read_measured(path), Ball(Scene(mu=0.4, **flat)), ["mu"])
    assert run(["fit", str(path), "--free", "mu", "--mu", "0.4", "--chi", "0.1", *PAIR, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["parameters"]["mu"]["value"] == pytest.approx(0.15, rel=1e-6)


def test_every_output_is_declared_once_with_a_scale_its_unit_gives():
    """Before: outputs were described in seven tables and nothing tested that a new dimensional output is scaled by
    the similar path.  Each is one declaration; its scale follows from its unit, and a unit without one fails here."""
    from sphereimpact import simulate
    from sphereimpact.impact.declarations import OUTPUTS, PARTNER, SCALE_OF_UNIT, SCALES, Kind
    from sphereimpact.impact.outcome import NUMERIC_OUTPUTS, OUTPUT_KEYS, OUTPUT_UNITS

    names = [o.name for o in (*OUTPUTS, *PARTNER)]
    assert len(names) == len(set(names))
    assert all(o.unit in SCALE_OF_UNIT for o in (*OUTPUTS, *PARTNER)), "declare the scale of a new unit"
    out = simulate(Scene(angle=30.0))
    assert tuple(out.to_dict()) == OUTPUT_KEYS and tuple(OUTPUT_UNITS) == OUTPUT_KEYS
    dimensional = {o.name for o in OUTPUTS if o.kind is Kind.NUMBER and o.unit not in ("-", "deg")}
    assert set(SCALES) == dimensional and set(SCALES) <= set(NUMERIC_OUTPUTS)


def test_the_similar_path_scales_every_numeric_output_as_simulate_gives_it():
    """Two scenes of one dimensionless problem (an elastic Hertz ball with microslip at one incidence, two speeds):
    the second is the first's outputs scaled, and every numeric output, dimensional or not, is simulate's."""
    import math

    from sphereimpact import simulate
    from sphereimpact.impact.outcome import NUMERIC_OUTPUTS
    from sphereimpact.sweep import sweep

    ball = dict(model="hertz", k=1e7, tangential="microslip", kappa=0.8, mu=0.3, incidence=30.0)
    import pandas as pd

    table = sweep(pd.DataFrame({"speed": [3.0, 6.0]} | {key: [value] * 2 for key, value in ball.items()}), chapter_ball=True)
    assert table["path"].tolist() == ["similar", "similar"]
    for row in (0, 1):
        one = simulate(Scene(speed=float(table["speed"][row]), **ball))
        for key in NUMERIC_OUTPUTS:
            expected = getattr(one, key)
            got = table[key][row]
            if expected is None:
                assert math.isnan(got), key
            else:
                assert got == pytest.approx(expected, rel=1e-7, abs=1e-12), (row, key)


def test_a_pair_sweep_judges_each_body_not_their_reduced_sphere():
    """The pair sweep solves each pair as its reduced sphere (m*, R*), which is no body: before, only that sphere's
    density was judged, and a 500 kg partner of 5 cm (whose reduced sphere looks like a ball) passed unsaid.  Now each
    body is judged as given, and a real pair raises nothing."""
    import warnings

    import pandas as pd

    from sphereimpact.errors import UnitWarning
    from sphereimpact.sweep import sweep

    real = dict(angle=30.0, mass=0.145, diameter=0.063)  # 1107 kg/m^3: a ball; the partner a steel ball
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitWarning)
        sweep(pd.DataFrame([real | dict(partner_mass=0.5, partner_diameter=0.0496)]), outputs=["cor"], chapter_ball=True)
    with pytest.warns(UnitWarning, match="the partner sphere.s mean density is 7.83e\\+06"):
        sweep(pd.DataFrame([real | dict(partner_mass=500.0, partner_diameter=0.0496)]), outputs=["cor"], chapter_ball=True)
