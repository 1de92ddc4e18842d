"""The pipeline's checks that need no results: the config refused before any job, lint, the cluster
profile's plan.  A copy of the project without running it (tests/test_workflow.py runs it), so these run
beside the pipeline test on the other worker."""

import re
import subprocess

import pytest

from conftest import TEST_CONFIG, project_copy, snakemake

pytestmark = pytest.mark.pipeline


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    return project_copy(tmp_path_factory.mktemp("project"))


def test_bad_config_stops_before_any_job(workdir):
    """Every config check is tabulated, without snakemake, in tests/test_inputs.py; here, that they run, each
    problem named (the schema's, the non-finite numbers that pass every schema bound) and no job planned."""
    run = snakemake(workdir, "-n", "--config", "mass=-1", "colour=red", "ramp=nan", "damping=-inf")
    text = run.stdout + run.stderr
    assert run.returncode != 0 and "config key mass: -1 is less than or equal to the minimum of 0" in text
    assert "'colour' was unexpected" in text and "Job stats" not in text
    assert "config key ramp: nan is not a finite number" in text
    assert "config key damping: -inf is not a finite number" in text


def test_an_off_grid_map_speed_is_refused_before_any_job(workdir, tmp_path):
    import yaml

    sweep = yaml.safe_load((workdir / TEST_CONFIG).read_text())["sweep"]
    off_grid = tmp_path / "off_grid.yaml"  # a config file replaces whole sections: give all of `sweep`
    off_grid.write_text(yaml.safe_dump({"sweep": sweep | {"map_speed": 2.0}}))
    run = snakemake(workdir, "-n", configfiles=[str(off_grid)])
    assert run.returncode != 0
    assert "config key sweep.map_speed: 2.0 is not on the speed grid '1:5:2'" in run.stdout + run.stderr


def test_lint_is_clean(workdir):
    run = subprocess.run(["snakemake", "--lint"], cwd=workdir, capture_output=True, text=True)
    assert run.returncode == 0 and "Congratulations" in run.stdout + run.stderr, run.stdout + run.stderr


def test_slurm_profile_dry_run_parses_without_matplotlib(workdir, tmp_path):
    """The cluster profile plans every job (where the SLURM executor plugin is installed), and planning
    imports no drawing code (a matplotlib that refuses to import is first on the path)."""
    pytest.importorskip("snakemake_executor_plugin_slurm")
    blocker = tmp_path / "blocker" / "matplotlib"
    blocker.mkdir(parents=True)
    (blocker / "__init__.py").write_text("raise ImportError('matplotlib imported while parsing the Snakefile')\n")
    run = snakemake(workdir, "-n", "--forceall", "--profile", "workflow/profiles/slurm", path=[blocker.parent])
    text = run.stdout + run.stderr
    assert run.returncode == 0, text[-2000:]
    assert re.search(r"^sweep_shard\s+2$", text, re.M)
