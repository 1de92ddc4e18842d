"""A sweep's one-at-a-time scenes shared among forked processes (:mod:`sphereimpact.sweep.processes`): the chunks'
results in their order, the workers' warnings and errors raised here, the same table whatever the processes, at
each door (the API's ``jobs``, the command line's ``--jobs``)."""

import os
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from sphereimpact.cli import run
from sphereimpact.sweep import processes
from sphereimpact.sweep.processes import checked_jobs, solved_chunks, workers_for

forks = pytest.mark.skipif(not processes.can_fork(), reason="this system's processes cannot fork")


def _pid_and_square(chunk):
    if chunk == 5:
        warnings.warn(f"chunk {chunk} warns", UserWarning)
    return {"pid": os.getpid(), "square": chunk * chunk}


@forks
def test_chunks_come_back_in_order_from_the_workers_with_their_warnings():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = list(solved_chunks(_pid_and_square, list(range(9)), jobs=2))
    assert [o["square"] for o in out] == [c * c for c in range(9)]
    assert out[0]["pid"] == os.getpid()  # the first chunk here (it loads the kernels the workers share)
    assert {o["pid"] for o in out[1:]} - {os.getpid()} and os.getpid() not in {o["pid"] for o in out[1:]}
    assert [str(w.message) for w in caught] == ["chunk 5 warns"] and caught[0].category is UserWarning


def _fails_at_three(chunk):
    if chunk == 3:
        raise ValueError(f"row {chunk} failed")
    return {"chunk": chunk}


@forks
def test_a_workers_error_is_raised_here_in_its_chunks_turn():
    got = []
    with pytest.raises(ValueError, match=r"^row 3 failed$"):
        for out in solved_chunks(_fails_at_three, list(range(8)), jobs=2):
            got.append(out["chunk"])
    assert got == [0, 1, 2]


def test_few_chunks_or_one_job_stay_in_this_process():
    assert workers_for(processes.PARALLEL_MIN_CHUNKS - 1, 8) == 1 and workers_for(100, 1) == 1
    assert workers_for(100, 2) == (2 if processes.can_fork() else 1)
    assert [o["pid"] for o in solved_chunks(_pid_and_square, [1, 2], jobs=4)] == [os.getpid()] * 2


@pytest.mark.parametrize("jobs", [0, -1, 1.5, True, "2"])
def test_jobs_must_be_a_positive_integer(jobs, monkeypatch):
    monkeypatch.delenv(processes.JOBS_VARIABLE, raising=False)
    with pytest.raises(ValueError, match=r"^jobs must be an integer >= 1 .*got "):
        checked_jobs(jobs)
    assert checked_jobs(None) == processes.available_cpus() >= 1 and checked_jobs(3) == 3


def test_the_environment_sets_the_default_as_the_pipeline_does(monkeypatch, tmp_path, capsys):
    """``SPHEREIMPACT_JOBS`` is the default of ``jobs`` (the pipeline's common.smk sets it to 1); a bad value is
    refused naming it, at the command line in one line."""
    monkeypatch.setenv(processes.JOBS_VARIABLE, "3")
    assert checked_jobs(None) == 3 and checked_jobs(2) == 2
    monkeypatch.setenv(processes.JOBS_VARIABLE, "many")
    with pytest.raises(ValueError, match=r"^SPHEREIMPACT_JOBS must be an integer >= 1 .*got 'many'$"):
        checked_jobs(None)
    assert run(["sweep", "--chapter-ball", "--out", str(tmp_path / "s.csv")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("sphereimpact: error: SPHEREIMPACT_JOBS must be") and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "s.csv").exists()
    common = (Path(__file__).parents[1] / "workflow/rules/common.smk").read_text(encoding="utf-8")
    assert f'os.environ.setdefault("{processes.JOBS_VARIABLE}", "1")' in common


@forks
def test_the_command_lines_jobs_give_the_table_of_one_process(tmp_path, monkeypatch):
    """A damped microslip map (every scene solved alone: no similarity serves it) in chunks of 4: shared among two
    processes, the same file."""
    from sphereimpact.sweep import paths

    monkeypatch.setattr(paths, "SINGLES_CHUNK", 4)
    made = []
    monkeypatch.setattr(processes, "ProcessPoolExecutor",
                        lambda *a, **k: made.append(k["max_workers"]) or _Executor(*a, **k))
    files = {}
    for jobs in (1, 2):
        files[jobs] = tmp_path / f"map{jobs}.csv"
        assert run(["sweep", "--model", "hunt-crossley", "--chi", "0.02", "--modulus", "6.3e10", "--mass", "2.618e-4",
                    "--diameter", "0.005", "--tangential", "microslip", "--kappa", "0.8", "--mu", "0.1",
                    "--incidence", "5:80:15",
                    "--speed", "2:4:1", "--jobs", str(jobs), "--out", str(files[jobs])]) == 0
    assert made == [2]  # two processes once, none for one job
    one = pd.read_csv(files[1])
    assert len(one) == 18 and set(one["path"]) == {"single"} and np.isfinite(one["omega_f"]).all()
    assert files[1].read_bytes() == files[2].read_bytes()


_Executor = processes.ProcessPoolExecutor
