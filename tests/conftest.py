"""Shared helpers for the tests."""

import math
import os
import runpy
import shutil
import subprocess
import sys
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# The tests compare the pipeline's files with computations of their own byte for byte, so they compute with the
# arithmetic the pipeline's jobs do (sphereimpact.arithmetic), set before numpy is imported: the module is run from
# its file, as importing it would import the package, and numpy with it.
if "numpy" in sys.modules:
    warnings.warn("numpy was imported before tests/conftest.py (by a pytest plugin?): the tests compute with this "
                  "processor's own arithmetic, and on one with AVX-512 a byte comparison with the pipeline's files "
                  "can fail at the last bit", stacklevel=1)
runpy.run_path(str(ROOT / "src/sphereimpact/arithmetic.py"))["pin_arithmetic"]()

from sphereimpact import SolverOptions  # noqa: E402
from sphereimpact.integrators.compiled import GROUPS  # noqa: E402
from sphereimpact.numerics.reference import output_scales  # noqa: E402

#: The small configuration the pipeline tests run on.
TEST_CONFIG = "config/test.yaml"
#: numba's disk cache of a module's compiled kernels: an index and machine code in the module's __pycache__, valid
#: while the module's text is the same (a copy keeps it); and the record of the sources the kernels compile
#: (:mod:`sphereimpact.kernel_cache`), which the copy's kernels then find unchanged.
KERNEL_CACHE = (".nbi", ".nbc", ".stamps")
#: Compiles one group of the built-in kernels of the project's own tree (``group``), or loads it from the disk
#: cache: what a test process, or a process of a copy's pipeline, would otherwise compile on first use.
COMPILE_KERNELS = "from sphereimpact.integrators.compiled import compile_all; compile_all({group!r})"
#: Tight options for comparisons at the 1e-9 level.
TIGHT = SolverOptions(method="DOP853", rtol=1e-12, atol=1e-14)


def assert_outputs_close(got, ref, rtol: float) -> None:
    """Every physical output of ``got`` within ``rtol`` of ``ref`` (relative to the output's scale)."""
    scales = output_scales(ref.scene, ref.t_f, ref.delta_m, ref.force_max)
    assert got.regime == ref.regime
    assert (got.t_roll is None) == (ref.t_roll is None)
    for key, scale in scales.items():
        a, b = getattr(got, key), getattr(ref, key)
        if a is None:
            continue
        assert math.isfinite(a), key
        assert abs(a - b) <= rtol * max(abs(b), scale), f"{key}: {a!r} vs {b!r}"



def pytest_configure(config):
    """Compile the project's kernels before any test runs, in two processes at once (a fresh clone's numba cache
    is empty): the test processes then load them, none compiling what another compiles beside it.  Once, in the
    process that starts the others (xdist's controller)."""
    if hasattr(config, "workerinput"):
        return
    runs = [subprocess.Popen([sys.executable, "-c", COMPILE_KERNELS.format(group=group)], cwd=ROOT,
                             env=os.environ | {"PYTHONPATH": str(ROOT / "src")}) for group in GROUPS]
    if any([run.wait() for run in runs]):  # both waited for, whichever fails
        raise RuntimeError("compiling the project's kernels failed (see the output above)")


def pytest_collection_modifyitems(items):
    """The test pipeline's file first, then the other files with pipeline tests (each runs Snakemake), then the
    rest: run in parallel by file in this order (pyproject's ``-n 2 --dist loadfile --no-loadscope-reorder``; xdist
    otherwise takes the files with the most tests first), the long module fixture of test_workflow.py (the test
    pipeline) overlaps the unit tests on the other worker, and the suite does not end on a file of Snakemake runs."""
    running = {item.path.name for item in items if item.get_closest_marker("pipeline")}
    items.sort(key=lambda item: 0 if item.path.name == "test_workflow.py" else 1 if item.path.name in running else 2)


def _left_out(directory: str, names: list) -> list:
    """What a project copy leaves out: bytecode (its own is compiled once by its jobs) and build metadata; numba's
    cache of the kernels is kept."""
    if Path(directory).name == "__pycache__":
        return [name for name in names if not name.endswith(KERNEL_CACHE)]
    return [name for name in names if name.endswith(".egg-info")]


def project_copy(work: Path) -> Path:
    """A copy of what the pipeline needs (Snakefile, workflow, config, notebooks, src, data) in ``work``, with the
    disk cache of the project's kernels (compiled before any test, :func:`pytest_configure`): its jobs load them.
    The kernels' code and answers are the same; only who compiles them changes."""
    for item in ("Snakefile", "workflow", "config", "notebooks", "src", "data"):
        src = ROOT / item
        (shutil.copytree if src.is_dir() else shutil.copy)(src, work / item,
                                                            **({"ignore": _left_out} if src.is_dir() else {}))
    return work


def start_snakemake(cwd, *args, configfiles=(), path=()) -> subprocess.Popen:
    """Start snakemake in ``cwd`` on the test config (plus ``configfiles``), importing the package from the
    copy in ``cwd/src`` (so a test can edit it) with ``path`` first on the module path; :func:`finish` waits."""
    env = os.environ | {"PYTHONPATH": os.pathsep.join([*map(str, path), str(Path(cwd) / "src")])}
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # the copy's bytecode, compiled once, serves its ~50 job processes
    return subprocess.Popen(["snakemake", "--cores", "2", *args, "--configfile", TEST_CONFIG, *configfiles], cwd=cwd,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)


def finish(process: subprocess.Popen) -> subprocess.CompletedProcess:
    """Wait for a :func:`start_snakemake` run; its exit code and output."""
    out, err = process.communicate()
    return subprocess.CompletedProcess(process.args, process.returncode, out, err)


def snakemake(cwd, *args, configfiles=(), path=()) -> subprocess.CompletedProcess:
    """Run snakemake in ``cwd`` (see :func:`start_snakemake`) and wait for it."""
    return finish(start_snakemake(cwd, *args, configfiles=configfiles, path=path))


def cli(*args: str) -> subprocess.CompletedProcess:
    """``sphereimpact ARGS`` in this process (the command line's own entry, :func:`sphereimpact.cli.run`), its exit
    status and what it wrote, as a finished subprocess: the door without a new interpreter's start-up per call."""
    import contextlib
    import io

    from sphereimpact.cli import run

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = run(list(args))
    return subprocess.CompletedProcess(["sphereimpact", *args], status, out.getvalue(), err.getvalue())
