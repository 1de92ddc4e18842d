"""The README's quick start runs as printed: each `sphereimpact` line through the command line's own entry point
in a fresh folder, the pipeline's lines by the pipeline test (tests/test_workflow.py runs both configurations)."""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path

from sphereimpact.cli import run

ROOT = Path(__file__).resolve().parents[1]


def quick_start() -> list[list[str]]:
    """The commands of the README's Quick start block, each split as a shell would, comments dropped."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text[text.index("## Quick start"):]
    block = re.search(r"```bash\n(.*?)```", section, re.S).group(1)
    return [shlex.split(line, comments=True) for line in block.splitlines() if line.strip()]


def test_the_quick_start_names_each_task():
    commands = [" ".join(c) for c in quick_start()]
    assert commands[0] == "snakemake --cores 2"
    assert commands[-1] == "snakemake --cores 2 --configfile config/examples/tennis.yaml"
    for task in ("sphereimpact simulate --angle", "sphereimpact simulate --model", "sphereimpact sweep --ball",
                 "sphereimpact fit data/kharaz2001.csv", "sphereimpact benchmark chung-ooi",
                 "sphereimpact benchmark compare"):
        assert any(command.startswith(task) for command in commands), task


def test_every_command_of_the_quick_start_runs(tmp_path, monkeypatch, capsys):
    """In order, as a newcomer types them: the golf ball saved, then mapped; the Kharaz fit; the benchmark's
    references, then compared with a DEM code's results (here a copy of them, which pass). The benchmark is
    written for two of its tests only, to keep the suite short (tests/test_chung_ooi.py writes every test)."""
    monkeypatch.chdir(tmp_path)
    shutil.copytree(ROOT / "data", "data")
    shutil.copytree(ROOT / "config", "config")
    for command in quick_start():
        if command[0] == "snakemake":
            assert command[1:3] == ["--cores", "2"]
            continue
        assert command[0] == "sphereimpact"
        argv = command[1:]
        if argv[:2] == ["benchmark", "chung-ooi"]:
            argv += ["--tests", "2,7"]
        if argv[:2] == ["benchmark", "compare"]:
            shutil.copytree(argv[2], argv[3])
        assert run(argv) == 0, (command, capsys.readouterr().err[-2000:])
    assert Path("golf.json").is_file() and Path("golf.csv").stat().st_size > 0
    assert {p.name for p in Path("kharaz_fit").iterdir()} >= {"ball.json", "fit.json", "residuals.csv", "fit.png"}
