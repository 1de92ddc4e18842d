"""Numerical studies: references, the default's accuracy, and one regression test per failure mode."""

import math
import os

import numpy as np
import pandas as pd
import pytest

from sphereimpact import Scene, SolverOptions, simulate
from sphereimpact.numerics.ablation import ablation
from sphereimpact.numerics.bench import speedups
from sphereimpact.numerics.reference import (reference, relative_errors, stored_references, worst_error,
                                             write_references)
from sphereimpact.numerics.workprecision import METHODS, TARGET, choose_default, work_precision

CHAPTER = {f"{a}deg-{m}": Scene(angle=a, model=m) for a in (0.0, 60.0) for m in ("modified", "kelvin-voigt")}


@pytest.fixture(scope="module")
def references():
    return {name: reference(scene) for name, scene in CHAPTER.items()}


def test_taylor_reference_agrees_with_an_independent_method(references):
    """Two ways: the Taylor reference (24 digits) and DOP853 at rtol 1e-13 (float64) agree to 1e-12."""
    for name, scene in CHAPTER.items():
        ref = references[name]
        assert ref.bound <= 1e-15
        tight = simulate(scene, SolverOptions(rtol=1e-13, atol=1e-13)).to_dict()
        assert worst_error(tight, ref.outputs, scene) < 1e-12, name


def test_taylor_reference_reproduces_the_closed_form():
    """The Taylor machinery itself, checked where an exact answer exists: ramp -> infinity is kelvin-voigt."""
    from sphereimpact.numerics.reference import taylor_normal

    scene = Scene(angle=0.0, model="modified", ramp=1e9, separation="penetration")
    t_m, delta_m, t_f, rate = taylor_normal(scene, 25)
    exact = simulate(scene.with_(model="kelvin-voigt"), SolverOptions(method="closed"))
    assert t_f == pytest.approx(exact.t_f, rel=1e-6) and -rate / scene.v_normal == pytest.approx(exact.cor, rel=1e-6)


def test_the_taylor_references_digits_do_not_depend_on_mpmaths_integers():
    """environment.txt installs gmpy2, which mpmath then uses for its integers: the reference's numbers are the
    ones mpmath's pure-Python integers give (a process told not to use gmpy2), to the bit."""
    import subprocess
    import sys

    import mpmath

    from sphereimpact.numerics.reference import COARSE_DIGITS, taylor_normal

    assert mpmath.libmp.BACKEND == "gmpy"
    script = ("import mpmath; from sphereimpact import Scene; from sphereimpact.numerics.reference import taylor_normal;"
              f"assert mpmath.libmp.BACKEND == 'python'; print(repr(taylor_normal(Scene(angle=60.0), {COARSE_DIGITS})))")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True,
                         env=os.environ | {"MPMATH_NOGMPY": "1"})
    assert run.stdout.strip() == repr(taylor_normal(Scene(angle=60.0), COARSE_DIGITS))


def test_default_meets_the_target_on_every_output(references):
    """The package default (chosen from the work-precision chart) meets 1e-9 in all four chapter scenes."""
    for name, scene in CHAPTER.items():
        out = simulate(scene).to_dict()
        errors = relative_errors(out, references[name].outputs, scene)
        assert max(errors.values()) <= TARGET, (name, errors)


def test_choose_default_picks_the_cheapest_setting_meeting_the_target():
    rows = [("a", "X", 1e-6, 1e-7, 1.0), ("b", "X", 1e-6, 2e-9, 1.0), ("a", "X", 1e-9, 1e-10, 3.0),
            ("b", "X", 1e-9, 1e-10, 3.0), ("a", "Y", 1e-8, 5e-10, 2.0), ("b", "Y", 1e-8, 8e-10, 2.0)]
    frame = pd.DataFrame(rows, columns=["case", "method", "rtol", "error", "time"]).assign(body="reduced",
                                                                                          status="ok")
    choice = choose_default(frame, 1e-9)
    assert (choice["method"], choice["rtol"], choice["time"]) == ("Y", 1e-8, 4.0)


def test_work_precision_charts_the_closed_form_exactly_where_the_law_has_one():
    """The chart gets a ``closed`` point for every case whose law declares an exact solution (asked of the
    law, not of its name), and that point meets the 24-digit reference to round-off."""
    cases = {"kv": Scene(model="kelvin-voigt", angle=30.0), "hertz": Scene(model="hertz", k=8.8e5, angle=30.0)}
    frame = work_precision(cases, tolerances=(1e-6,), methods=("DOP853-scalar",))
    closed = frame[frame["body"] == "closed"]
    assert list(closed["case"]) == [name for name, scene in cases.items() if scene.law.closed_form is not None]
    assert list(closed["case"]) == ["kv"] and (closed["error"] < 1e-13).all()
    reduced = frame[frame["body"] == "reduced"]
    assert set(reduced["case"]) == set(cases) and (reduced["error"].between(1e-9, 1e-4)).all()


def test_a_work_precision_line_stops_after_its_first_point_over_the_cost_cap():
    """Points are run from the loosest tolerance on; once one impact takes more than the cap, the line's tighter
    tolerances are rows saying why they were not run (any time is over a cap of 1e-12 s; none is over 1e9 s)."""
    scene = {"kv": Scene(model="kelvin-voigt", angle=30.0)}
    capped = work_precision(scene, tolerances=(1e-8, 1e-4, 1e-6), methods=("RK45",), cost_cap=1e-12)
    capped = capped[capped["body"] == "reduced"]
    assert list(capped["rtol"]) == [1e-4, 1e-6, 1e-8]
    assert capped["status"].tolist()[0] == "ok" and capped["error"].notna().tolist() == [True, False, False]
    assert all(status.startswith("not run: rtol 0.0001 took ") and status.endswith("over the cost cap")
               for status in capped["status"].tolist()[1:])
    free = work_precision(scene, tolerances=(1e-4, 1e-6), methods=("RK45",), cost_cap=1e9)
    assert (free["status"] == "ok").all()


def test_speedups_at_equal_accuracy():
    frame = pd.DataFrame([
        ("c", "kv", "reduced", "A", 1e-10, 1e-11, 2.0), ("c", "kv", "planar", "A", 1e-10, 1e-10, 6.0),
        ("c", "kv", "planar", "B", 1e-8, 1e-8, 1.0), ("c", "kv", "closed", "closed", 1e-13, 1e-16, 0.5),
    ], columns=["case", "model", "body", "method", "rtol", "error", "time"]).assign(status="ok", nfev=1)
    table = speedups(frame, 1e-9).set_index("body")
    assert table.loc["reduced", "speedup_over_planar"] == 3.0  # the 1e-8 planar point does not count
    assert table.loc["reduced", "closed_speedup"] == 4.0


# --- one regression test per failure mode: the default path does not fail on it -------------------------


def test_a_round_over_the_budget_is_not_repeated():
    """The benchmarks' protocol: every contender once per round, in turn; ``repeats`` rounds unless the rounds
    take more than the budget on average (counted calls, not timings: any call takes some time)."""
    import time

    from sphereimpact.numerics.timing import interleaved_runs, interleaved_seconds

    calls = {"a": [], "b": []}
    contenders = {name: (lambda got=got: (got.append(1), time.sleep(1e-4))) for name, got in calls.items()}
    seconds, rounds = interleaved_runs(contenders, 3, budget=math.inf)
    assert rounds == 3 and [len(c) for c in calls.values()] == [3, 3] and min(seconds.values()) >= 1e-4
    seconds, rounds = interleaved_runs(contenders, 3, budget=0.0)
    assert rounds == 1 and [len(c) for c in calls.values()] == [4, 4]
    assert set(interleaved_seconds(contenders, 2)) == {"a", "b"} and [len(c) for c in calls.values()] == [6, 6]


def test_strongly_overdamped_contact_completes_with_every_method():
    """1. Stiffness (zeta = 100, modified law as in the study): every method finishes; delta_m and COR agree
    with Radau at rtol 1e-12 to 1e-6. t_m is ill-conditioned there (delta_dot crosses zero with slope
    ~ 1/zeta), so it is held to 1e-4."""
    base = Scene()
    scene = base.with_(b=100 * 2 * math.sqrt(base.k * base.mass))
    ref = simulate(scene, SolverOptions(method="Radau", rtol=1e-12, atol=1e-12)).to_dict()
    for method in METHODS:
        out = simulate(scene, SolverOptions(method=method, rtol=1e-8, atol=1e-8)).to_dict()
        errors = relative_errors(out, ref, scene, keys=("t_m", "delta_m", "cor"))
        assert errors["delta_m"] < 1e-6 and errors["cor"] < 1e-6 and errors["t_m"] < 1e-4, (method, errors)


def test_unresolvable_separation_is_an_error_not_a_number():
    """kelvin-voigt at zeta = 300 under the force criterion: the rebound (closed form: COR 2.78e-6) is below
    what rtol = atol = 1e-6 resolves (10 atol), so the separation found cannot be told from a false P = 0 on
    the slow manifold, where P = k delta + b delta_dot is a tiny difference of two large terms. The package
    refuses it with a clear error; a tighter tolerance resolves it. (RK45 at zeta = 100 and rtol 1e-8 finds
    such a false separation, rebound 3.9e-13, after 2e5 steps: the stability study records it.)"""
    from sphereimpact import ImpactError

    base = Scene(model="kelvin-voigt")
    scene = base.with_(b=300 * 2 * math.sqrt(base.k * base.mass))
    exact = simulate(scene, SolverOptions(method="closed")).cor
    assert exact == pytest.approx(2.7778e-6, rel=1e-4)
    with pytest.raises(ImpactError, match="below what the tolerances resolve"):
        simulate(scene, SolverOptions(method="DOP853", rtol=1e-6, atol=1e-6))
    assert simulate(scene, SolverOptions(method="DOP853", rtol=1e-8, atol=1e-8)).cor == pytest.approx(exact, rel=1e-4)


def test_stiffness_k_does_not_change_the_cost():
    """1. In dimensionless form k enters only through zeta: the same zeta at k = 1e3 and 1e9 costs the same."""
    nfev = []
    for k in (1e3, 1e9):
        base = Scene(k=k, model="kelvin-voigt")
        scene = base.with_(b=0.3 * 2 * math.sqrt(k * base.mass))
        nfev.append(simulate(scene).nfev)
    assert nfev[0] == nfev[1]


def test_force_jump_at_onset_is_never_inside_a_step():
    """2. The default path starts at contact: kelvin-voigt (P(0) = b v_n) meets rtol-level accuracy."""
    scene = Scene(model="kelvin-voigt")
    exact = simulate(scene, SolverOptions(method="closed")).to_dict()
    for rtol in (1e-6, 1e-9):
        assert worst_error(simulate(scene, SolverOptions(rtol=rtol, atol=rtol)).to_dict(), exact, scene) < 10 * rtol


@pytest.mark.parametrize("method", METHODS)
def test_grip_is_exact_and_cheap(method):
    """3. Late grip at 50 deg: the exact event switch gives vt0/(1 + alpha) to round-off, in few evaluations."""
    scene = Scene(angle=50.0)
    out = simulate(scene, SolverOptions(method=method, rtol=1e-8, atol=1e-8))
    assert out.regime == "rolling"
    assert out.vc_t == pytest.approx(scene.v_tangent / (1 + scene.inertia_factor), rel=1e-14)
    assert out.nfev < 5000


@pytest.mark.parametrize("method", METHODS)
def test_separation_found_at_loose_tolerance(method):
    """4. rtol 1e-3: separation is never missed and t_f errs by about the tolerance, not a whole step."""
    scene = Scene(angle=0.0)
    exact = simulate(scene, SolverOptions(rtol=1e-12, atol=1e-12)).t_f
    out = simulate(scene, SolverOptions(method=method, rtol=1e-3, atol=1e-3))
    assert abs(out.t_f / exact - 1) < 1e-3


@pytest.mark.parametrize("method", METHODS)
def test_no_overflow_past_separation(method):
    """5. A steep ramp and a loose tolerance: no overflow, no NaN, a finite outcome."""
    with np.errstate(over="raise", invalid="raise", divide="raise"):
        out = simulate(Scene(angle=0.0, ramp=1e4), SolverOptions(method=method, rtol=1e-3, atol=1e-3))
    assert all(math.isfinite(v) for v in (out.t_f, out.cor, out.force_min, out.force_max))


def test_ablation_drops_only_what_a_scene_does_not_need():
    cases = {"normal": Scene(angle=0.0), "oblique60": Scene(angle=60.0)}
    published = [{"case": "oblique60", "quantity": "omega_f", "resolution": 1.0}]
    frame = ablation(cases, published).set_index(["case", "variant", "output"]).sort_index()["change"]
    assert frame.loc["normal", "no friction"].abs().max() == 0.0  # a normal impact needs no friction
    assert frame.loc["normal", "thin shell"].abs().max() == 0.0
    assert frame.loc["oblique60", "full planar model"].abs().max() < 1e-9  # the planar model only adds cost
    base = simulate(Scene(angle=60.0), SolverOptions(rtol=1e-12, atol=1e-12))
    spin_scale = 3.0 / base.scene.radius  # changes are relative to max(|value|, v/R)
    assert frame.loc[("oblique60", "no friction", "omega_f")] == pytest.approx(-base.omega_f / spin_scale, rel=1e-9)
    assert abs(frame.loc[("oblique60", "ramp 10", "cor")]) > 1e-3  # the ramp constant is a real choice


def test_a_commands_start_is_timed_in_fresh_processes_beside_pythons():
    """The bench's start-up rows (issue 43's target for `simulate --json`): each contender run whole in a fresh
    process, the ratio over numpy's start; the command's own run succeeds (its failure would raise).  Timings are
    written by the pipeline, never asserted."""
    from sphereimpact.numerics.bench import STARTUP, STARTUP_SCENE, startup_bench

    table = startup_bench(1)
    assert list(table["contender"]) == list(STARTUP) and table["scene"].eq(STARTUP_SCENE).all()
    assert (table["time"] > 0).all() and table["time_ratio"].iloc[0] == 1.0
    assert table["time_ratio"].iloc[1] == pytest.approx(table["time"].iloc[1] / table["time"].iloc[0], rel=1e-12)


def test_the_stability_studies_one_job_each_merge_into_the_table_of_all_at_once(tmp_path):
    """The pipeline runs each failure-mode study in its own job (the timed one alone) and merges their tables: the
    merged table is, byte for byte, the one all the studies write at once (studies without timings here); a study
    the config does not list is refused by name."""
    import yaml

    from sphereimpact.study.config import with_defaults
    from sphereimpact.study.numerics import merge_stability, write_stability

    schema = yaml.safe_load(open("config/schema.yaml"))
    config = with_defaults(schema, yaml.safe_load(open("config/config.yaml")))
    config["numerics"] |= {"stability": ["past-separation", "onset"], "methods": ["RK45", "LSODA"]}
    parts = []
    for study in config["numerics"]["stability"]:
        parts.append(tmp_path / f"{study}.csv")
        write_stability(config, parts[-1], study)
    merge_stability(parts, tmp_path / "merged.csv")
    write_stability(config, tmp_path / "whole.csv")
    assert (tmp_path / "merged.csv").read_bytes() == (tmp_path / "whole.csv").read_bytes()
    assert pd.read_csv(tmp_path / "whole.csv")["study"].unique().tolist() == ["past-separation", "onset"]
    with pytest.raises(ValueError, match=r"stability study 'grip' is not one of numerics.stability"):
        write_stability(config, tmp_path / "grip.csv", "grip")


def test_a_laws_force_in_floats_is_its_stage_force_to_the_bit():
    """The stability studies' naive runs and the planar bodies evaluate the law in Python floats
    (``ContactLaw.in_floats``: its scalar formula, for speed): at
    states in contact, past separation (the continuation) and pulling, for every built-in law and a ball striking a
    partner (whose reduced sphere the force takes), the same float as ``Scene.stage_force`` and its separation event
    the same as the numpy one's."""
    from sphereimpact.contact.laws import LAWS
    from sphereimpact.numerics.bench import LAW_SCENES
    from sphereimpact.numerics.stability import _separation_event

    scenes = [Scene(model=name, **LAW_SCENES.get(name, {})) for name in LAWS]
    scenes.append(Scene(angle=20.0, partner_mass=0.4, partner_diameter=0.09))
    for scene in scenes:
        force, event = scene.law.in_floats(scene.reduced), _separation_event(scene)
        d, v = 0.1 * scene.radius, scene.v_normal
        for delta, delta_dot in ((d, v), (d, -0.6 * v), (1e-3 * d, -v), (-1e-3 * d, -v), (-0.5 * d, 0.3 * v)):
            assert force(delta, delta_dot) == float(scene.stage_force(delta, delta_dot)), (scene.model, delta)
            expected = float(np.where(delta > 0, scene.force(delta, delta_dot), -1.0))
            if not scene.separation.pulls:
                assert event(0.0, np.array([delta, delta_dot])) == expected, (scene.model, delta)


def test_the_sweep_path_study_times_with_the_errors_its_own_job_wrote(tmp_path, monkeypatch):
    """The sweep-path study's untimed half (each contender's worst error on its sample), written by its own job (rule
    sweep_paths_accuracy) and read back by the timed one, which computes no reference and reports each comparison's
    errors from the file in its rows; a file written for another sample or another size is refused by name."""
    import json

    from sphereimpact.numerics import sweep_paths

    sweep_paths.write_accuracies(tmp_path / "accuracy.json", sizes=(40,), sample=3)
    known = json.loads((tmp_path / "accuracy.json").read_text())
    assert len(known["errors"]) == 4 and all(0 < e < 1e-6 for row in known["errors"].values() for e in row.values())
    known["errors"]["one ball, 40 scenes, force"]["plane"] = 0.125
    (tmp_path / "told.json").write_text(json.dumps(known))
    monkeypatch.setattr(sweep_paths, "dimensionless_motion", lambda *a: pytest.fail("the timed job solved a reference"))
    monkeypatch.setattr(sweep_paths, "interleaved_seconds", lambda calls, repeats: {name: 1.0 for name in calls})
    told = sweep_paths.run(tmp_path / "told.csv", sizes=(40,), sample=3, repeats=1, accuracy_json=tmp_path / "told.json")
    assert len(told) == 14  # (4 + 3 contenders) x 2 criteria, each with its comparison's error from the file
    assert [known["errors"][f"{r.comparison}, {r.scenes} scenes, {r.separation}"][r.path] for r in told.itertuples()] == \
        told["worst_error"].tolist()
    with pytest.raises(ValueError, match="not at 1e-08 on 4"):
        sweep_paths.run(tmp_path / "other.csv", accuracy_json=tmp_path / "told.json", sizes=(40,), sample=4)
    with pytest.raises(ValueError, match="no errors of the comparison 'one ball, 50 scenes, force'"):
        sweep_paths.run(tmp_path / "other.csv", accuracy_json=tmp_path / "told.json", sizes=(50,), sample=3)


def test_the_sweep_benchmark_times_with_the_accuracy_its_own_job_wrote(tmp_path, monkeypatch):
    """The sweep benchmark's untimed half (each sweep's worst error on its sample, the contenders' tolerances at it),
    written by its own job (rule bench_sweep_accuracy) and read back by the timed one, gives the rows it computes in
    one process: every cell but the timings and the traced memory equal; a file written for another sample size is
    refused by name; each engine run is made once untimed before its rounds."""
    import json

    from sphereimpact.numerics import bench_sweep
    from sphereimpact.sweep.engine import FAST_OUTPUTS, sweep

    small = {"sample": 3, "lanes": 60, "million": False, "laws": ()}
    bench_sweep.write_accuracies(tmp_path / "accuracy.json", **small)
    accuracies = json.loads((tmp_path / "accuracy.json").read_text())
    apart = bench_sweep.run(tmp_path / "apart.csv", repeats=1, accuracies=accuracies, **small)
    whole = bench_sweep.run(tmp_path / "whole.csv", repeats=1, **small)
    timed = ("seconds", "throughput", "speedup", "all_over", "peak_memory")
    kept = [c for c in whole.columns if not c.startswith(timed) and not c.endswith(timed)]
    assert {"worst_error", "simulate_rtol", "handwritten_error", "handwritten_reached"} <= set(kept)
    assert len(apart) == 3 and (apart["worst_error"] > 0).all()
    pd.testing.assert_frame_equal(apart[kept], whole[kept], check_exact=True)
    first = next(iter(accuracies))  # the timed job times what the file says, computing none of it again
    accuracies[first]["worst_error"], accuracies[first]["chosen"]["simulate"]["rtol"] = 0.125, 1e-5
    swept = []
    monkeypatch.setattr(bench_sweep, "sweep", lambda *a, **k: swept.append(k.get("outputs")) or sweep(*a, **k))
    told = bench_sweep.run(tmp_path / "told.csv", repeats=1, accuracies=accuracies, **small)
    assert (told.loc[0, "worst_error"], told.loc[0, "simulate_rtol"]) == (0.125, 1e-5)
    # per row: the fast and the every-output sweep once untimed (first touch), then once each in the one round
    assert swept == [FAST_OUTPUTS, None, FAST_OUTPUTS, None] * 3
    with pytest.raises(ValueError, match=r"no accuracy of the sweep 'k, b, m per scene.*on a sample of 4 scenes"):
        bench_sweep.run(tmp_path / "other.csv", repeats=1, accuracies=accuracies, **(small | {"sample": 4}))


def test_stored_references_are_the_computed_ones_to_the_bit(tmp_path, monkeypatch):
    """The timed studies' references, computed in a job of their own and read back (rule numerics_references): every
    output, the bound and the method equal reference()'s (wall_time aside); a scene the file lacks is computed."""
    stored = [Scene(angle=60.0), Scene(angle=30.0, model="kelvin-voigt"), Scene(model="hertz", modulus=1e8)]
    path = tmp_path / "references.json"
    write_references(stored, path)
    with stored_references(path):
        read = [reference(scene) for scene in stored]
        import sphereimpact.numerics.reference as module

        monkeypatch.setattr(module, "outputs_from_normal", lambda *args: pytest.fail("recomputed a stored reference"))
        assert reference(stored[0]).outputs == read[0].outputs
        monkeypatch.undo()
        other = reference(Scene(angle=45.0, model="kelvin-voigt"))  # not in the file: computed
    assert other.how == "closed form"
    for scene, got in zip(stored, read):
        want = reference(scene)
        assert (got.bound, got.how) == (want.bound, want.how)
        assert {k: v for k, v in got.outputs.items() if k != "wall_time"} == pytest.approx(
            {k: v for k, v in want.outputs.items() if k != "wall_time"}, rel=0, abs=0, nan_ok=True)


def test_the_kernels_rows_are_written_for_the_bench_table_to_take_in(tmp_path, monkeypatch):
    """Rule bench_kernels' job (beside others) writes the compilation and load rows in the bench table's columns;
    their ratio is the compilation over the load (the seconds themselves stubbed: a fresh compile takes a minute)."""
    from sphereimpact.numerics import bench
    from sphereimpact.study.numerics import write_kernel_bench

    monkeypatch.setattr(bench, "kernel_seconds", lambda repeats: (2.0, 0.5))
    write_kernel_bench({"bench": {"repeats": 2}}, tmp_path / "kernels.csv")
    rows = pd.read_csv(tmp_path / "kernels.csv").set_index("contender")
    assert list(rows.index) == ["compile (fresh disk cache)", "load (from the disk cache)"]
    assert (rows["scene"] == bench.KERNEL_SCENE).all() and (rows["repeats"] == 2).all()
    assert rows.loc["compile (fresh disk cache)", "time_ratio"] == 4.0 and rows["error"].isna().all()


def test_a_commands_benchmark_row_times_the_whole_command_and_counts_its_table():
    """``measure_command`` (the map-as-a-command row of results/bench_sweep.csv) runs the command in a fresh process
    and reads its table back: a 2 x 2 chapter sweep gives 4 scenes; the damped map's arguments hold the ball to the
    bit."""
    from sphereimpact.numerics.bench_sweep import DAMPED_MAP, damped_map_command, measure_command

    row = measure_command("four", ["sweep", "--chapter-ball", "--angle", "0:30:30", "--speed", "1:3:2"], repeats=1)
    assert row["scenes"] == 4 and row["throughput"] == pytest.approx(4 / row["seconds"]) and row["repeats"] == 1
    assert row["command"] == "sphereimpact sweep --chapter-ball --angle 0:30:30 --speed 1:3:2"
    ball = Scene(model="hunt-crossley", modulus=6.3e10 / 3, mass=2.618e-4, diameter=0.005, mu=0.092,
                 tangential="microslip", shear_modulus=1.35e10 / 7)
    flags = damped_map_command(ball)
    assert flags[flags.index("--modulus") + 1] == repr(6.3e10 / 3) and flags[flags.index("--chi") + 1] == "0.02"
    assert flags[flags.index("--shear-modulus") + 1] == repr(1.35e10 / 7) and DAMPED_MAP["incidence"] in flags
