"""The chapter figures say what they show: drawn under the replication table's separation criterion, the other
criterion's end named, and captions whose numbers are read from the run files and agree with closed forms."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest
import yaml

from sphereimpact.figures.captions import chapter_facts, criterion_history
from sphereimpact.figures.catalog import FIGURES
from sphereimpact.study.config import with_defaults
from sphereimpact.study.runs import run_case


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The chapter's four run files (both laws, both cases, both criteria), as the pipeline writes them."""
    root = Path(__file__).resolve().parents[1]
    config = with_defaults(yaml.safe_load((root / "config/schema.yaml").read_text()),
                           yaml.safe_load((root / "config/config.yaml").read_text()))
    folder = tmp_path_factory.mktemp("runs")
    out = {}
    for case in ("normal", "oblique60"):
        for model in ("kelvin-voigt", "modified"):
            csv = folder / f"{case}_{model}.csv"
            run_case(config, case, model, str(csv), str(folder / f"{case}_{model}.json"))
            out[case, model] = pd.read_csv(csv)
    return out, config


def _facts(runs, name, separation="force"):
    frames, _ = runs
    spec = FIGURES[name]
    return chapter_facts(name, [frames[spec.case, m] for m in spec.models], separation)


def test_force_caption_states_the_jump_and_the_pull_from_the_data(runs):
    """Fig 4.7: eq. 4.1's force at first touch is b v (closed form, 10.5 N s/m x 3 m/s); under the force
    criterion neither law pulls; held to δ = 0 both do (the README's finding for eq. 4.2's −1.3 N), each least
    force equal to the penetration history's own minimum."""
    frames, config = runs
    text = _facts(runs, "fig4_7")
    jump = config["damping"] * config["speed"]
    assert f"eq. 4.1 starts with a jump to {jump:.4g} N" in text
    assert "eq. 4.2 starts from 0 N" in text
    assert text.count("never pulling") == 2
    for model in ("kelvin-voigt", "modified"):
        least = criterion_history(frames["normal", model], "penetration")["force"].min()
        assert least < -1.0
        assert f"pull to {least:.4g} N".replace("-", "−") in text


def test_oblique_force_caption_says_eq_4_2_does_not_pull(runs):
    text = _facts(runs, "fig4_8")
    assert "eq. 4.2 starts from 0 N and ends at δ = 0, never pulling" in text
    assert "eq. 4.1 starts with a jump to 15.75 N" in text  # b v_n at 60°: 10.5 x 3 cos 60°


def test_history_captions_name_both_criteria_and_the_table_times(runs):
    """Fig 4.2 under the table's criterion ends where the table's t_f does; the penetration end is named too;
    the 60° impact, whose two criteria end together, says so."""
    frames, _ = runs
    normal = _facts(runs, "fig4_2")
    t_force = criterion_history(frames["normal", "modified"], "force")["t"].iloc[-1]
    t_pen = criterion_history(frames["normal", "modified"], "penetration")["t"].iloc[-1]
    assert f"the contact ends at {t_force * 1e3:.4g} ms" in normal
    assert f"under the penetration criterion (δ returns to 0) at {t_pen * 1e3:.4g} ms" in normal
    assert "as under the penetration criterion" in _facts(runs, "fig4_3")
    penetration = _facts(runs, "fig4_2", "penetration")
    assert f"the contact ends at {t_pen * 1e3:.4g} ms" in penetration


def test_a_criterion_the_runs_lack_is_refused_in_one_line(runs):
    frames, _ = runs
    only_force = frames["normal", "modified"].query("separation == 'force'")
    with pytest.raises(ValueError, match="separation 'penetration': the run file has no history under it"):
        chapter_facts("fig4_2", [only_force], "penetration")


def test_figure_legend_names_the_criteria(runs, tmp_path):
    """The drawn figure carries the same words: its legend names the table's criterion and the other's end."""
    import matplotlib

    matplotlib.use("Agg")
    from sphereimpact.figures.paper import force_deflection, spin

    frames, _ = runs
    paths = {}
    for model in ("kelvin-voigt", "modified"):
        paths[model] = tmp_path / f"{model}.csv"
        frames["normal", model].to_csv(paths[model], index=False)
    fig = force_deflection(str(paths["kelvin-voigt"]), str(paths["modified"]), [], "normal", "force", "t")
    labels = [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
    assert "eq. 4.2 (modified), force criterion" in labels
    assert any(label.startswith("eq. 4.1 held to δ = 0 (penetration criterion): least P -26.4") for label in labels)
    fig = spin(str(paths["modified"]), [], "normal", "force", "t")
    labels = [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
    assert any(label.startswith("contact ends: P returns to 0 (force criterion), 4.799") for label in labels)
    assert any(label.startswith("δ returns to 0 (penetration criterion): 4.891") for label in labels)


def test_drawn_under_the_penetration_criterion_the_pull_is_the_curve_itself(runs):
    """With primary.separation = penetration the curves reach δ = 0 themselves: their least force is the pull,
    and nothing is "held" further."""
    frames, _ = runs
    text = _facts(runs, "fig4_7", "penetration")
    least = criterion_history(frames["normal", "modified"], "penetration")["force"].min()
    assert f"its least force {least:.4g} N".replace("-", "−") in text
    assert "held to δ = 0" not in text
