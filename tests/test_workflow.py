"""The pipeline, run for real in a temporary copy: outputs, idempotence, determinism, config errors, lint, figures."""

import hashlib
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from matplotlib.testing.compare import compare_images

ROOT = Path(__file__).resolve().parents[1]
FIGURES = [f"fig4_{i}" for i in range(2, 9)]
OUTPUTS = ["results/summary.csv", "results/summary.md", "results/replication.csv", "results/replication.md",
           "results/notebooks/replication.html", "results/notebooks/numerics.html",
           "results/work_precision.csv", "results/bench.csv", "results/stability.csv", "results/ablation.csv",
           "paper_figures/work_precision.png", "paper_figures/stability.png",
           "results/sweep/angle_speed.csv", "results/sweep/speed.csv", "results/bench_sweep.csv",
           "paper_figures/spin_map.png", "paper_figures/cor_speed.png", "paper_figures/contact_speed.png",
           "results/notebooks/sweeps.html",
           *[f"paper_figures/{f}.{ext}" for f in FIGURES for ext in ("png", "pdf")],
           *[f"results/runs/{c}_{m}.{ext}" for c in ("normal", "oblique60") for m in ("kelvin-voigt", "modified")
             for ext in ("csv", "json")]]
#: Pixel tolerance (RMS on 0-255) for the committed figures: fonts and anti-aliasing only.
FIGURE_TOLERANCE = 2.0


def snakemake(cwd, *args):
    return subprocess.run(["snakemake", "--cores", "2", *args], cwd=cwd, capture_output=True, text=True)


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    work = tmp_path_factory.mktemp("pipeline")
    for item in ("Snakefile", "workflow", "config", "notebooks"):
        src = ROOT / item
        (shutil.copytree if src.is_dir() else shutil.copy)(src, work / item)
    run = snakemake(work)
    assert run.returncode == 0, run.stderr[-3000:]
    return work


def digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_every_output_exists_and_is_not_empty(workdir):
    for name in OUTPUTS:
        path = workdir / name
        assert path.is_file() and path.stat().st_size > 0, name


def test_second_run_does_nothing(workdir):
    run = snakemake(workdir, "-n")
    assert run.returncode == 0 and "Nothing to be done" in run.stdout + run.stderr


def test_tables_are_byte_identical_when_rebuilt(workdir):
    tables = ["results/summary.csv", "results/summary.md", "results/replication.csv", "results/replication.md"]
    before = {t: digest(workdir / t) for t in tables}
    run = snakemake(workdir, "--forcerun", "simulate", "--until", "tabulate", "replicate")
    assert run.returncode == 0, run.stderr[-2000:]
    assert {t: digest(workdir / t) for t in tables} == before


def test_changing_one_case_reruns_only_its_jobs(workdir, tmp_path):
    other = tmp_path / "other.yaml"
    other.write_text("cases:\n  normal: {angle: 0.0}\n  oblique60: {angle: 45.0}\n")
    run = snakemake(workdir, "-n", "--configfile", str(other))
    text = run.stdout + run.stderr
    assert run.returncode == 0
    assert re.search(r"^simulate\s+2$", text, re.M)  # the two oblique60 runs, not the normal ones
    assert re.search(r"^figure\s+4$", text, re.M)  # figs 4.3, 4.5, 4.6, 4.8 only
    assert not re.search(r"^stability\s", text, re.M)  # the stability study uses the normal case only
    assert "wildcards: case=normal" not in text


@pytest.mark.parametrize("args, message", [
    (["--config", "mass=-1"], "config key mass: -1 is less than or equal to the minimum of 0"),
    (["--config", "colour=red"], "'colour' was unexpected"),
    (["--config", "method=Euler"], "config key method: 'Euler' is not one of"),
])
def test_bad_config_stops_before_any_job(workdir, args, message):
    run = snakemake(workdir, "-n", *args)
    assert run.returncode != 0
    assert message in run.stdout + run.stderr


def test_lint_is_clean(workdir):
    run = subprocess.run(["snakemake", "--lint"], cwd=workdir, capture_output=True, text=True)
    assert run.returncode == 0 and "Congratulations" in run.stdout + run.stderr, run.stdout + run.stderr


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

    config = yaml.safe_load((workdir / "config" / "config.yaml").read_text())
    assert config["sweep"]["shards"] >= 2
    whole = tmp_path / "whole.csv"
    write_table(sweep(angle_speed_scenes(config), target=config["sweep"]["target"]), str(whole))
    assert (workdir / "results/sweep/angle_speed.csv").read_bytes() == whole.read_bytes()


def test_slurm_profile_dry_run(workdir):
    """The cluster profile plans every job (where the SLURM executor plugin is installed)."""
    pytest.importorskip("snakemake_executor_plugin_slurm")
    run = subprocess.run(["snakemake", "-n", "--forceall", "--profile", "workflow/profiles/slurm"], cwd=workdir,
                         capture_output=True, text=True)
    text = run.stdout + run.stderr
    assert run.returncode == 0, text[-2000:]
    assert re.search(r"^sweep_shard\s+2$", text, re.M)
