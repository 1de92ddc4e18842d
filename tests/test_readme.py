"""The README's generated blocks: the replication block is exactly what the pipeline writes, and the check
that CI runs after the pipeline tells agreement, run-to-run timing noise and real disagreement apart."""

import re
from pathlib import Path

import pandas as pd
import pytest
import yaml

from sphereimpact.study.readme import (BLOCKS, TIMING_CHARTS, TIMING_RANGE, blocks, check, differences, main,
                                     replication_block, runtime_block, update)
from sphereimpact.study.workflow import job_seconds
from sphereimpact.study.replication import write_report
from sphereimpact.study.runs import run_case

ROOT = Path(__file__).resolve().parents[1]
CONFIG = yaml.safe_load((ROOT / "config/config.yaml").read_text())

TABLE = """Intro line.

| scene | simulate [ms] | error, simulate |
|---|---|---|
| normal | 5.16 | 2.1e-10 |
"""


def test_readme_replication_block_is_what_the_pipeline_writes(tmp_path):
    """Recomputed from the config exactly as the rules `simulate` and `replicate` do: no number in the
    README's replication table or findings can drift from the results."""
    jsons = []
    for case in CONFIG["cases"]:
        for model in CONFIG["models"]:
            jsons.append(tmp_path / f"{case}_{model}.json")
            run_case(CONFIG, case, model, str(tmp_path / f"{case}_{model}.csv"), str(jsons[-1]))
    write_report(CONFIG, str(ROOT / "config/published.yaml"), jsons, str(tmp_path / "replication.csv"),
                 str(tmp_path / "replication.md"), str(tmp_path / "findings.md"))
    fresh = replication_block(CONFIG, str(tmp_path / "replication.csv"), str(tmp_path / "findings.md"))
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    start, end = blocks(text)["replication"]
    assert text[start:end] == fresh, "README is stale: run the pipeline, then python -m sphereimpact.study.readme --update"


def test_readme_opens_with_the_two_commands():
    head = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()[:12]
    assert any("pip install -r environment.txt && snakemake --cores 2" in line for line in head)
    assert any("pip install -r environment.txt && pytest" in line for line in head)


def test_identical_blocks_agree():
    assert differences(TABLE, TABLE) == []


@pytest.mark.parametrize("timed, agrees", [("5.16", True), (f"{5.16 * TIMING_RANGE * 0.99:.3g}", True),
                                          (f"{5.16 / TIMING_RANGE * 1.01:.3g}", True),
                                          (f"{5.16 * TIMING_RANGE * 1.05:.3g}", False), ("0.5", False)])
def test_timed_cells_agree_within_the_stated_range(timed, agrees):
    fresh = TABLE.replace("| 5.16 |", f"| {timed} |")
    assert (differences(TABLE, fresh) == []) is agrees


def test_a_changed_untimed_cell_or_line_disagrees():
    assert differences(TABLE, TABLE.replace("2.1e-10", "2.2e-10"))  # an error is not a timing
    assert differences(TABLE, TABLE.replace("Intro line.", "Other line."))
    assert differences(TABLE, TABLE + "| extra | 1 | 1 |\n")


def test_check_and_update_round_trip(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("# T\n" + "".join(f"<!-- BEGIN GENERATED {name}: x -->\nold\n<!-- END GENERATED {name} -->\n"
                                        for name in BLOCKS))
    snippets = tmp_path / "snippets"
    snippets.mkdir()
    for name in BLOCKS:
        (snippets / f"{name}.md").write_text(TABLE if name == "speed" else f"fresh {name}\n")
    assert check(str(readme), str(snippets))
    readme.write_text(update(str(readme), str(snippets)))
    assert check(str(readme), str(snippets)) == []
    assert "fresh replication\n<!-- END GENERATED replication -->" in readme.read_text()


def test_check_reports_a_missing_block_or_snippet(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("<!-- BEGIN GENERATED speed -->\nx\n<!-- END GENERATED speed -->\n")
    problems = check(str(readme), str(tmp_path))
    assert "no document has the generated block 'replication'" in problems
    assert any("speed.md is missing" in p for p in problems)


def test_blocks_may_stand_in_docs_pages_but_once(tmp_path):
    """A block moved from the README to a docs/ page is checked there; the same block in two documents is a
    problem (which copy would the reader trust?)."""
    snippets = tmp_path / "snippets"
    snippets.mkdir()
    documents = []
    for i, name in enumerate(BLOCKS):
        (snippets / f"{name}.md").write_text(f"{name}\n")
        page = tmp_path / f"page{i % 2}.md"
        with page.open("a") as handle:
            handle.write(f"<!-- BEGIN GENERATED {name} -->\n{name}\n<!-- END GENERATED {name} -->\n")
        documents.append(str(page))
    documents = sorted(set(documents))
    assert check(documents, str(snippets)) == []
    with (tmp_path / "page0.md").open("a") as handle:
        handle.write("<!-- BEGIN GENERATED speed -->\nspeed\n<!-- END GENERATED speed -->\n")
    assert any("block 'speed' stands in" in p for p in check(documents, str(snippets)))


def test_timing_charts_are_recorded_by_update_and_required_by_check(tmp_path, monkeypatch):
    """`--update` copies each run's timing charts into paper_figures/ beside the timings the README shows;
    `--check` fails while one is missing."""
    monkeypatch.chdir(tmp_path)
    snippets, figures, recorded = Path("results/readme"), Path("results/figures"), Path("paper_figures")
    for folder in (snippets, figures, recorded):
        folder.mkdir(parents=True)
    text = "".join(f"<!-- BEGIN GENERATED {n} -->\nold\n<!-- END GENERATED {n} -->\n" for n in BLOCKS)
    Path("README.md").write_text(text)
    for name in BLOCKS:
        (snippets / f"{name}.md").write_text(f"{name}\n")
    png = b"\x89PNG\r\n\x1a\n" + b"chart"
    for name in TIMING_CHARTS:
        (figures / f"{name}.png").write_bytes(png)
    assert main(["--check"]) == 1
    assert main(["--update"]) == 0
    assert main(["--check"]) == 0
    assert all((recorded / f"{name}.png").read_bytes() == png for name in TIMING_CHARTS)
    (recorded / f"{TIMING_CHARTS[0]}.png").unlink()
    assert main(["--check"]) == 1


def test_timed_cells_are_compared_in_their_units():
    """The time column switches from ms to s at one second: 1.48 s against 933 ms is a ratio of 1.6, not 630
    (CI failed on exactly that)."""
    block = "| sweep | time |\n|---|---|\n| big | 1.48 s |\n"
    assert differences(block, block.replace("1.48 s", "933 ms")) == []
    assert differences(block, block.replace("1.48 s", "93.3 ms"))  # 16x: beyond the range


def _benchmark(path: Path, seconds: float) -> str:
    """A benchmark file as Snakemake's ``benchmark:`` directive writes it (its first columns)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(f"s\th:m:s\tmax_rss\n{seconds}\t0:00:01\t50.0\n")
    return str(path)


def test_runtime_block_sums_each_part_and_the_whole(tmp_path):
    """Jobs, rules and summed wall times per part of the pipeline, the parts in the pipeline's order, and a
    fresh run whose times moved within the stated factor still agrees with the block."""
    root = tmp_path / "benchmarks"
    files = [_benchmark(root / "sweep/sweep_shard/0.tsv", 2.0), _benchmark(root / "sweep/sweep_shard/1.tsv", 3.5),
             _benchmark(root / "simulate/simulate/normal_modified.tsv", 0.25),
             _benchmark(root / "sweep/bench_sweep.tsv", 60.0)]
    block = runtime_block(files, str(root))
    rows = [line for line in block.splitlines() if line.startswith("| ") and "---" not in line][1:]
    assert rows == ["| the chapter's runs | `simulate` | 1 | 250 ms |",
                    "| sweeps and their differential test | `bench_sweep`, `sweep_shard` | 3 | 65.5 s |",
                    "| **all** | 3 rules | 4 | 65.8 s |"]
    _benchmark(root / "sweep/bench_sweep.tsv", 150.0)  # the next run: the benchmark took 2.5 times as long
    assert differences(block, runtime_block(files, str(root))) == []
    with pytest.raises(ValueError, match="no benchmark files"):
        runtime_block([], str(root))


def test_job_seconds_refuses_a_file_that_is_not_a_benchmark(tmp_path):
    bad = tmp_path / "x.tsv"
    bad.write_text("time\n3\n")
    with pytest.raises(ValueError, match="not a Snakemake benchmark file"):
        job_seconds(str(bad))


def _documents():
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def test_every_figure_the_documents_name_is_committed():
    """No dangling figure: every `paper_figures/<name>.png` the README or a docs page shows or names is in the
    repository (tracked by git), so a fresh clone has it."""
    import subprocess

    from sphereimpact.figures.captions import CAPTIONS

    tracked = set(subprocess.run(["git", "ls-files", "paper_figures"], cwd=ROOT, capture_output=True, text=True,
                                 check=True).stdout.split())
    named = {f"paper_figures/{name}.png" for name in CAPTIONS}  # the index, paper_figures/README.md, shows each
    for document in _documents():
        text = document.read_text(encoding="utf-8")
        named |= set(re.findall(r"paper_figures/[\w.-]+\.png", text))
        named |= {f"paper_figures/{name}" for name in re.findall(r"`([\w-]+\.png)`", text)
                  if name.removesuffix(".png") in CAPTIONS}
    assert named and named <= tracked, sorted(named - tracked)


def test_links_and_contents_of_the_documents_resolve():
    """Each relative link of the README and docs/ points at a file of the repository, and each of the README's
    contents entries at one of its headings (GitHub's anchors: lower case, punctuation dropped, spaces as -)."""
    for document in _documents():
        text = document.read_text(encoding="utf-8")
        for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", text):
            assert (document.parent / target).exists(), f"{document.name}: {target}"
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    anchors = {re.sub(r"[^\w\- ]", "", h.strip().lower()).replace(" ", "-")
               for h in re.findall(r"^#+ (.+)$", readme, re.M)}
    wanted = set(re.findall(r"\]\(#([\w-]+)\)", readme))
    assert wanted and wanted <= anchors, sorted(wanted - anchors)


def test_the_first_screen_has_the_contents_and_the_quick_start():
    """A newcomer's first screen: what it is, the two commands, the contents, then the quick start."""
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    assert lines.index("## Contents") < 25 and lines.index("## Quick start") < 45


def test_the_speed_blocks_text_does_not_depend_on_the_rounds_a_run_took(tmp_path):
    """A benchmark row that took fewer rounds (its round over the budget) must not change the block's words: the
    README check compares them exactly, so text worded from the rounds run made CI fail on a slow spell."""
    from sphereimpact.study.readme import speed_block

    single = pd.DataFrame([{"scene": "s", "contender": c, "method": "taylor", "time": 1e-3, "time_ratio": 1.0,
                            "error": 1e-11, "rtol": 1e-10, "reached": True, "repeats": 3, "batch": 50}
                           for c in ("simulate", "handwritten")])
    single.to_csv(tmp_path / "bench.csv", index=False)
    texts = []
    for rounds in (1, 3):
        rows = pd.DataFrame([
            {"sweep": "grid", "scenes": 10, "seconds": 0.1, "throughput": 100.0, "worst_error": 1e-12,
             "repeats": rounds, "sample": 5, "seconds_all": 0.2, "all_over_fast": 2.0, "target_speedup": None,
             "speedup_over_handwritten": 9.0, "handwritten_reached": True, "handwritten_error": 1e-12,
             "handwritten_rtol": 1e-12, "speedup_over_simulate": 5.0, "simulate_reached": True,
             "simulate_error": 1e-12, "simulate_rtol": 1e-12, "evaluations": None, "target_seconds": None},
            {"sweep": "fit", "scenes": 20, "seconds": 6.0, "throughput": 50.0, "worst_error": None, "repeats": rounds,
             "evaluations": 30, "target_seconds": 10.0},
            {"sweep": "map", "command": "sphereimpact sweep --chapter-ball", "scenes": 1000, "seconds": 5.0,
             "throughput": 200.0, "repeats": 3, "target_seconds": 10.0}])
        rows.to_csv(tmp_path / "bench_sweep.csv", index=False)
        texts.append(speed_block(str(tmp_path / "bench.csv"), str(tmp_path / "bench_sweep.csv")))
    assert texts[0] == texts[1] and "or of fewer where one round" in texts[0]
    assert "| map | `sphereimpact sweep --chapter-ball` | 1,000 | 5 s | 200 | under 10 s |" in texts[0]
