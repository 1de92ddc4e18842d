"""The pipeline, run for real in a temporary copy on the small test config (config/test.yaml): outputs,
idempotence, determinism, what reruns when what changes, config errors, logs, lint, report, figures.

The full studies (every method, tolerance and benchmark size) run once, in `.ci/run`.
"""

import hashlib
import os
import re
import shutil
import time
from pathlib import Path

import pytest
from matplotlib.testing.compare import compare_images

from conftest import finish, project_copy, snakemake, start_snakemake

pytestmark = pytest.mark.pipeline

ROOT = Path(__file__).resolve().parents[1]
FIGURES = [f"fig4_{i}" for i in range(2, 9)]
OUTPUTS = ["results/summary.csv", "results/summary.md", "results/replication.csv", "results/replication.md",
           "results/replication_findings.md", "results/config.yaml", "results/readme/replication.md",
           "results/readme/speed.md", "results/readme/validation.md", "results/readme/consistency.md",
           "results/readme/runtime.md", "results/readme/fit.md", "results/fit_kharaz/fit.json",
           "results/fit_kharaz/ball.json", "results/fit_kharaz/residuals.csv", "results/fit_kharaz/fit.png",
           "results/consistency.csv", "results/readme/chung_ooi.md", "results/chung_ooi/test1.csv",
           "results/chung_ooi/test5.csv", "paper_figures/chung_ooi_test5.png", "results/chung_ooi/deviations.csv",
           "results/chung_ooi/departure.csv", "paper_figures/dem_departure.png", "results/readme/dem_departure.md",
           "results/validation.csv", "results/validation_summary.csv", "results/compliance_map.csv",
           "paper_figures/validation_kharaz.png", "paper_figures/validation_maw.png", "paper_figures/compliance_map.png",
           "paper_figures/README.md",
           "results/notebooks/numerics.html",
           "results/work_precision.csv", "results/bench.csv", "results/stability.csv", "results/ablation.csv",
           "results/figures/work_precision.png", "paper_figures/stability.png",
           "results/microslip_resolution.csv", "results/figures/microslip_resolution.png",
           "results/sweep/angle_speed.csv", "results/sweep/speed.csv", "results/bench_sweep.csv",
           "results/sweep_paths.csv", "results/figures/sweep_paths.png",
           "paper_figures/spin_map.png", "paper_figures/cor_speed.png", "paper_figures/contact_speed.png",
           *[f"paper_figures/{f}.{ext}" for f in FIGURES for ext in ("png", "pdf")],
           *[f"results/runs/{c}_{m}.{ext}" for c in ("normal", "oblique60") for m in ("kelvin-voigt", "modified")
             for ext in ("csv", "json")]]
#: Pixel tolerance (RMS on 0-255) for the committed figures: fonts and anti-aliasing only.
FIGURE_TOLERANCE = 2.0
#: Rules whose jobs are timed and so run alone (``threads: workflow.cores``): the test's small run lets them
#: share the machine, since its timings are not read.
TIMED_RULES = ("work_precision", "stability_study", "bench", "bench_sweep", "microslip_resolution", "sweep_paths")
#: Rules whose jobs are benchmarks or heavy studies.
HEAVY = ("work_precision", "numerics_references", "stability_study", "stability", "bench", "bench_sweep", "ablation",
         "sweep_shard", "microslip_resolution", "sweep_paths")


def planned(run) -> dict:
    """Rule -> job count from a dry run's job table."""
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\w+)\s+(\d+)$", run.stdout + run.stderr, re.M)}


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    work = project_copy(tmp_path_factory.mktemp("pipeline"))
    run = snakemake(work, "--set-threads", *[f"{rule}=1" for rule in TIMED_RULES])
    assert run.returncode == 0, run.stderr[-3000:]
    return work


def scratch_copy(workdir: Path, copy: Path) -> Path:
    """A copy of the finished pipeline that a test may break."""
    shutil.copytree(workdir, copy, ignore=shutil.ignore_patterns(".snakemake"))
    shutil.copytree(workdir / ".snakemake", copy / ".snakemake", ignore=shutil.ignore_patterns("conda", "log"))
    return copy


def files(root: Path) -> dict:
    """Relative path -> digest of every file under ``root`` but snakemake's metadata and bytecode."""
    return {p.relative_to(root).as_posix(): digest(p) for p in root.rglob("*")
            if p.is_file() and ".snakemake" not in p.parts and "__pycache__" not in p.parts}


class _Run:
    """A snakemake run on its own copy of the finished pipeline, started before the tests that read it."""

    def __init__(self, copy: Path, process, before=None):
        self.copy, self._process, self.before, self._result = copy, process, before, None

    @property
    def result(self):
        if self._result is None:
            self._result = finish(self._process)
        return self._result


@pytest.fixture(scope="module", autouse=True)
def overlapping(workdir, tmp_path_factory) -> dict:
    """The runs on copies of the finished pipeline (a broken input, an edited module, the report, an own
    study), all started at once after the pipeline, so that they overlap the tests run in ``workdir`` itself
    (one snakemake process at a time, whatever the cores)."""
    runs = {}

    def start(name, prepare, *args, snapshot=False, configfiles=()):
        copy = scratch_copy(workdir, tmp_path_factory.mktemp(name) / "copy")
        prepare(copy)
        before = files(copy) if snapshot else None
        runs[name] = _Run(copy, start_snakemake(copy, *args, configfiles=configfiles), before)

    def corrupt(copy):
        (copy / "results/runs/normal_modified.csv").write_text("not,a,run\n1,2,3\n")  # a corrupted input

    small = tmp_path_factory.mktemp("own") / "small.yaml"
    bounces = synthetic_tennis_bounces(small.parent / "bounces.csv")
    small.write_text("ranges: {speeds: '5:25:10', map_speeds: '10:30:10', map_angles: '20:80:30'}\n"
                     f"fit: {{data: {bounces}, free: [mu]}}\n")
    start("own", lambda copy: None, snapshot=True, configfiles=["config/examples/tennis.yaml", str(small)])
    start("drawing", lambda copy: edit(copy / "src/sphereimpact/figures/style.py"), "-n")
    start("physics", lambda copy: edit(copy / "src/sphereimpact/integrators/normal.py"), "-n")
    start("failing", corrupt, "paper_figures/fig4_2.png", "--forcerun", "figure")
    start("report", lambda copy: None, "--report", "results/report.html")
    yield runs
    for run in runs.values():
        run.result  # noqa: B018  (no process outlives the module)


#: The friction of the synthetic measured tennis bounces that the own study's fit must find.
TENNIS_MU = 0.55


def synthetic_tennis_bounces(path: Path) -> Path:
    """Twelve bounces of the shipped tennis ball on a court of friction TENNIS_MU, their rebound velocity and
    spin with Gaussian noise (0.05 m/s, 2 rad/s, stated), written as `sphereimpact fit`'s table."""
    import numpy as np
    import pandas as pd
    import yaml

    from sphereimpact.impact.ball import ball_columns
    from sphereimpact.study.config import with_defaults
    from sphereimpact.study.own import study_ball
    from sphereimpact.sweep import sweep

    schema = yaml.safe_load((ROOT / "config/schema.yaml").read_text())
    ball = study_ball(with_defaults(schema, yaml.safe_load((ROOT / "config/examples/tennis.yaml").read_text())))
    rng = np.random.default_rng(0)
    table = pd.DataFrame({"speed": 20.0, "angle_to_surface": rng.uniform(10, 40, 12), "spin": 0.0})
    out = sweep(table.assign(**(ball_columns(ball) | {"mu": TENNIS_MU})), outputs=["vc_t", "omega_f"])
    table.assign(vc_t=out["vc_t"] + rng.normal(0, 0.05, 12), sigma_vc_t=0.05,
                 omega_f=out["omega_f"] + rng.normal(0, 2.0, 12), sigma_omega_f=2.0).to_csv(path, index=False)
    return path


def edit(path: Path) -> None:
    """Change a source file's content (a comment) and make it newer than every output."""
    path.write_text(path.read_text() + "\n# edited by the test\n")
    stat = path.stat()
    os.utime(path, ns=(stat.st_atime_ns, time.time_ns() + 10**12))


def digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_every_output_exists_and_is_not_empty(workdir):
    for name in OUTPUTS:
        path = workdir / name
        assert path.is_file() and path.stat().st_size > 0, name


def test_sweep_shards_are_temporary(workdir):
    assert not list((workdir / "results/sweep/shards").glob("*.csv"))


def test_second_run_does_nothing(workdir):
    run = snakemake(workdir, "-n")
    assert run.returncode == 0 and "Nothing to be done" in run.stdout + run.stderr


def test_tables_are_byte_identical_when_rebuilt(workdir):
    tables = ["results/summary.csv", "results/summary.md", "results/replication.csv", "results/replication.md",
              "results/replication_findings.md"]
    before = {t: digest(workdir / t) for t in tables}
    run = snakemake(workdir, "--forcerun", "simulate", "--until", "tabulate", "replicate")
    assert run.returncode == 0, run.stderr[-2000:]
    assert {t: digest(workdir / t) for t in tables} == before


def test_changing_one_case_reruns_only_its_jobs(workdir, tmp_path):
    other = tmp_path / "other.yaml"
    other.write_text("cases:\n  normal: {angle: 0.0}\n  oblique60: {angle: 45.0}\n")
    run = snakemake(workdir, "-n", configfiles=[str(other)])
    jobs = planned(run)
    assert run.returncode == 0
    assert jobs.get("simulate") == 2  # the two oblique60 runs, not the normal ones
    assert jobs.get("figure") == 4  # figs 4.3, 4.5, 4.6, 4.8 only
    assert "stability" not in jobs and "bench_sweep" not in jobs and "sweep_shard" not in jobs
    assert "wildcards: case=normal" not in run.stdout + run.stderr


def test_samples_rerun_the_histories_not_the_benchmarks(workdir):
    run = snakemake(workdir, "-n", "--config", "samples=201")
    jobs = planned(run)
    assert run.returncode == 0
    assert jobs.get("simulate") == 4 and jobs.get("figure") == 7
    assert not set(HEAVY) & set(jobs), jobs


def test_editing_a_drawing_module_redraws_without_recomputing(overlapping):
    jobs = planned(overlapping["drawing"].result)
    assert jobs.get("figure") == 7 and jobs.get("numerics_figure") == 1 and jobs.get("timing_chart") == 3
    assert jobs.get("sweep_map") == 3
    assert not {"simulate", *HEAVY} & set(jobs), jobs


def test_editing_the_physics_reruns_what_uses_it(overlapping):
    jobs = planned(overlapping["physics"].result)
    assert jobs.get("simulate") == 4
    assert {"work_precision", "stability", "bench", "sweep_shard", "speed_table", "bench_sweep"} <= set(jobs)


def test_a_failing_job_writes_its_traceback_to_its_log(overlapping):
    failing = overlapping["failing"]  # the run of fig 4.2 on a corrupted run table
    assert failing.result.returncode != 0
    log = (failing.copy / "logs/figures/fig4_2.log").read_text()
    assert "Traceback (most recent call last)" in log and "KeyError: 'separation'" in log


def test_html_report_has_every_figure_and_table(overlapping):
    report = overlapping["report"]
    assert report.result.returncode == 0, report.result.stderr[-2000:]
    html = (report.copy / "results/report.html").read_text(errors="replace")
    for name in ["fig4_7.png", "work_precision.png", "spin_map.png", "replication.csv", "bench_sweep.csv", "config.yaml"]:
        assert name in html, name
    # every figure's caption comes from sphereimpact.figures.captions, the one place they are written
    for phrase in ["thin lines continue a law", "one panel per failure mode", "over the tangential speed"]:
        assert phrase in html, phrase


@pytest.mark.parametrize("name", FIGURES)
def test_committed_figure_is_current(workdir, name):
    """A stale committed figure fails: regenerate with `snakemake --cores 2` and commit paper_figures/*.png."""
    committed = ROOT / "paper_figures" / f"{name}.png"
    assert committed.is_file(), f"{committed} is not committed"
    assert compare_images(str(committed), str(workdir / "paper_figures" / f"{name}.png"),
                          tol=FIGURE_TOLERANCE) is None


def test_merged_sweep_equals_the_sweep_run_at_once(workdir, tmp_path):
    """The sharded angle x speed sweep, merged, is byte-identical to the same sweep run in one piece."""
    import yaml

    from sphereimpact.study.sweeps import angle_speed_scenes
    from sphereimpact.sweep.engine import sweep
    from sphereimpact.sweep.io import write_table

    config = yaml.safe_load((workdir / "results" / "config.yaml").read_text())
    assert config["sweep"]["shards"] >= 2
    whole = tmp_path / "whole.csv"
    write_table(sweep(angle_speed_scenes(config), target=config["sweep"]["target"]), str(whole))
    assert (workdir / "results/sweep/angle_speed.csv").read_bytes() == whole.read_bytes()


def test_an_own_study_writes_only_its_own_files(overlapping):
    """The shipped tennis example (its ranges made small) after the chapter's pipeline: every output of the
    study under results/studies/tennis/, and not one byte of the chapter's files changed, nor a chapter rule
    run."""
    own = overlapping["own"]
    run, scratch, before = own.result, own.copy, own.before
    assert run.returncode == 0, run.stderr[-3000:]
    assert set(planned(run)) <= {"own_fit", "own_ball", "own_bounces", "own_speed", "own_maps", "own_bounce_figure",
                                  "own_figures", "own_plan", "own_page", "all", "total"}, planned(run)
    after = files(scratch)
    changed = {p for p in before if after.get(p) != before[p]}
    added = set(after) - set(before)
    assert not changed, sorted(changed)
    assert all(p.startswith(("results/studies/tennis/", "logs/studies/tennis/")) for p in added), sorted(added)
    study = scratch / "results/studies/tennis"
    for name in ("index.html", "index.md", "ball.json", "outcomes.csv", "speed.csv", "maps.csv",
                 "histories/topspin-drive.csv", "figures/topspin-drive.png", "figures/speed.png",
                 "figures/spin_map.png", "figures/rebound_map.png", "plan/plan.csv", "plan/plan.json",
                 "plan/candidates.csv", "plan/plan.png"):
        assert (study / name).stat().st_size > 0, name
    took = sorted(p.name for p in (study / "benchmarks").iterdir())  # 7 jobs and a figure per bounce
    assert len(took) == 7 + 5 and "jobs took" in (study / "index.md").read_text(), took
    assert "Which bounces to measure" in (study / "index.md").read_text()  # the config's plan section
    import json

    import pandas as pd

    from sphereimpact import load_ball, simulate

    from sphereimpact.study.own_outputs import read_history

    ball = load_ball(study / "ball.json").scene
    outcomes = read_history(study / "outcomes.csv").set_index("bounce")  # units in its header
    assert pd.read_csv(study / "outcomes.csv").columns[1] == "speed [m/s]"
    fitted = json.loads((study / "fit/fit.json").read_text())["parameters"]["mu"]  # the config's fit section
    assert abs(fitted["value"] - TENNIS_MU) < 3 * fitted["stderr"] and fitted["identifiable"]
    assert ball.mu == pytest.approx(fitted["value"], rel=1e-12)  # the study uses the fitted ball
    assert "Fitted to measured bounces" in (study / "index.md").read_text()
    drop = outcomes.loc["drop-test"]
    assert drop["cor"] == pytest.approx(0.745, abs=1e-8)  # the measured COR, recovered
    assert drop["t_f"] == pytest.approx(4.5e-3, rel=1e-8)  # and the contact time
    serve = simulate(ball.with_(speed=30.0, angle_to_surface=12.0, spin=150.0))  # the fitted mu
    assert outcomes.loc["flat-serve", "omega_f"] == pytest.approx(serve.omega_f, rel=1e-9)


def test_the_pipeline_fits_the_kharaz_data_as_the_api_does(workdir):
    """The pipeline's door of the fit: rule kharaz_fit's parameters are the API's on the same ball and data, and
    its ball file is the fitted ball."""
    import json

    import yaml

    from sphereimpact import load_ball
    from sphereimpact.fit import fit, read_measured, with_values
    from sphereimpact.impact.ball import Ball
    from sphereimpact.study.validation import experiment

    config = yaml.safe_load((workdir / "results/config.yaml").read_text())
    spec = config["kharaz_fit"]
    record = json.loads((workdir / "results/fit_kharaz/fit.json").read_text())
    ball = with_values(Ball(experiment(config["validation"]).with_tangential(spec["tangential"])),
                       {n: v for n, v in spec["start"].items() if n in spec["free"]})
    api = fit(read_measured(ROOT / config["validation"]["data"]), ball, spec["free"])
    for name in spec["free"]:
        assert record["parameters"][name]["value"] == pytest.approx(api.parameters[name].value, rel=1e-12)
        assert record["parameters"][name]["stderr"] == pytest.approx(api.parameters[name].stderr, rel=1e-9)
    assert record["reference"]["mu"] == config["validation"]["mu"]
    assert load_ball(workdir / "results/fit_kharaz/ball.json").scene.mu == pytest.approx(api.ball.scene.mu, rel=1e-12)


def test_the_pipeline_writes_the_chung_ooi_references_as_the_command_line_does(workdir, tmp_path):
    """The pipeline's door of the benchmark: rule chung_ooi's reference files are the command line's, and each
    reference is within 1e-8 of its closed-form check."""
    import numpy as np
    import pandas as pd

    from sphereimpact.cli import run

    assert run(["benchmark", "chung-ooi", "--out", str(tmp_path), "--tests", "1,5"]) == 0
    for name in ("test1.csv", "test5.csv"):
        assert (workdir / "results/chung_ooi" / name).read_bytes() == (tmp_path / name).read_bytes()
    checks = pd.read_csv(workdir / "results/chung_ooi/checks.csv")
    assert set(checks["test"]) == {1, 5} and checks["max_rel"].max() < 1e-8
    # the planar two-body model's door (issue 41 item 7): test 1 is normal, so the line of centres never turns
    assert "the reduction against the planar two-body model" in " ".join(checks["check"])
    one = pd.read_csv(workdir / "results/chung_ooi/test1.csv")
    assert np.isfinite(one["reduction_gap [m/s]"]).all() and one["reduction_gap [m/s]"].max() < 1e-7
    assert one["reduction_gap_spring [m/s]"].isna().all()  # its contact is rigid: no spring to measure with
    # the gate's pipeline door: each DEM rule judged as `benchmark compare` judges a code's file of it
    from sphereimpact.study.chung_ooi import scenes_of_test, solve, write_table

    verdicts = pd.read_csv(workdir / "results/chung_ooi/verdicts.csv")
    rules = pd.concat([solve(scenes_of_test(5, rule)) for rule in ("mindlin", "rigid")], ignore_index=True)
    for rule in ("mindlin", "rigid"):
        theirs = tmp_path / rule
        theirs.mkdir()
        write_table(rules[rules["rule"] == rule].reset_index(drop=True), theirs / "test5.csv")
        status = run(["benchmark", "compare", str(workdir / "results/chung_ooi"), str(theirs)])
        mine = verdicts[(verdicts["rule"] == rule) & (verdicts["test"] == 5)]
        assert len(mine) > 3 and status == (0 if mine["passed"].all() else 1)
    # the DEM rules' departure (issue 41 item 6): test 5's from its deviations, the Kharaz ball's from its own table
    departure = pd.read_csv(workdir / "results/chung_ooi/departure.csv")
    deviation = pd.read_csv(workdir / "results/chung_ooi/deviations.csv").set_index(["rule", "quantity"])
    five = departure[departure["scenes"] == "Chung & Ooi test 5"].set_index(["rule", "quantity"])["max_rel"]
    assert np.allclose(five, deviation.loc[five.index, "max_rel"], rtol=1e-5)
    kharaz = pd.read_csv(workdir / "results/chung_ooi/departure_kharaz.csv")
    exact = kharaz[kharaz["rule"] == "microslip"].reset_index(drop=True)
    damped = kharaz[kharaz["rule"] == "mindlin+dashpot"].reset_index(drop=True)
    mine = departure[(departure["scenes"] == "Kharaz ball") & (departure["rule"] == "mindlin+dashpot")]
    expected = np.max(np.abs(damped["omega_f"] - exact["omega_f"])) / np.max(np.abs(exact["omega_f"]))
    assert mine.set_index("quantity").loc["omega_f", "max_rel"] == pytest.approx(expected, rel=1e-5)
    assert "`mindlin+dashpot`" in (workdir / "results/readme/dem_departure.md").read_text()
    # the departure study's command-line door: the pipeline's own files, from its used config's Kharaz ball
    out = tmp_path / "departure"
    assert run(["benchmark", "departure", "--tests", "5", "--config", str(workdir / "results/config.yaml"),
                "--out", str(out)]) == 0
    for name in ("departure.csv", "departure_kharaz.csv"):
        assert (out / name).read_bytes() == (workdir / "results/chung_ooi" / name).read_bytes(), name
    assert (out / "departure.png").stat().st_size > 0
    published = pd.read_csv(workdir / "results/chung_ooi/published.csv")  # the paper's curves beside the references
    assert set(published["test"]) == {5} and published["points"].min() > 10
