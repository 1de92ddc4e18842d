"""Every figure is checked at page size before it is written: a label running into another panel, a text
leaving the page, or two materials' curves drawn in one panel is refused."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
import pytest  # noqa: E402

from sphereimpact.figures.style import FigureLayoutError, layout_problems, save  # noqa: E402


def _panels(ylabel: str, layout=None):
    fig, axes = plt.subplots(2, 1, figsize=(4.0, 2.4), layout=layout)
    for ax in axes:
        ax.plot([0, 1], [0, 1e3])
        ax.set(ylabel=ylabel, xlabel="incidence [deg]")
    return fig


def test_a_label_running_into_the_panel_above_is_refused_and_nothing_is_written(tmp_path):
    fig = _panels("a long label of the contact point's rebound [deg]")
    problems = layout_problems(fig)
    assert any("overlaps" in p or "outside the page" in p for p in problems), problems
    with pytest.raises(FigureLayoutError, match="does not read at its size"):
        save(fig, [tmp_path / "bad.png"])
    assert not list(tmp_path.iterdir())


def test_the_same_panels_laid_out_read():
    assert layout_problems(_panels("v [m/s]", layout="constrained")) == []


def test_ticks_outside_the_view_are_not_counted():
    """Matplotlib keeps tick labels beyond the axis limits without drawing them: they are no overlap."""
    fig, ax = plt.subplots(figsize=(4.0, 3.0), layout="constrained")
    ax.plot([0, 1], [-0.95, 0.0])
    ax.set_ylim(-0.99, 0.01)
    assert layout_problems(fig) == []
    plt.close(fig)


def test_chung_ooi_materials_get_a_column_each(tmp_path, monkeypatch):
    """Two materials whose curves coincide are drawn side by side, not one on the other (issue 44's test 4)."""
    from sphereimpact.figures.chung_ooi import test_figure

    incidence = np.linspace(1.0, 85.0, 5)
    rows = [{"case": case, "tangential": "microslip", "rule": "microslip", "incidence": a, "speed": 3.9,
             "vc_t": np.sin(np.radians(a)), "omega_f": 10.0 * a, "rebound_angle_contact": a}
            for case in ("al-oxide", "al-alloy") for a in incidence]
    exact = pd.DataFrame(rows)
    captured = {}
    original = plt.Figure.savefig

    def keep(fig, *args, **kwargs):
        captured["fig"] = fig
        return original(fig, *args, **kwargs)

    monkeypatch.setattr(plt.Figure, "savefig", keep)
    test_figure(4, "oblique", exact, exact.iloc[0:0], ("incidence", "incidence [deg]"), outputs=[tmp_path / "t4.png"])
    fig = captured["fig"]
    assert fig.axes[0].get_gridspec().get_geometry() == (3, 2)
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert titles == ["al-oxide", "al-alloy"]
    assert (tmp_path / "t4.png").stat().st_size > 0
