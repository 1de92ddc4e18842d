"""Figure output: deterministic (the same data give byte-identical PNG, PDF and SVG files) and checked at page
size before it is written (no text outside the page, no label running into another panel's or the legend's)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

from ..files import replacing  # noqa: E402

RC = {"figure.figsize": (6.4, 4.2), "figure.dpi": 100, "savefig.dpi": 150, "font.size": 10,
      "axes.grid": True, "grid.alpha": 0.3, "legend.fontsize": 8, "lines.linewidth": 1.6,
      "svg.hashsalt": "sphereimpact", "pdf.compression": 6}

#: Metadata written as None drops the entries (software version, creation date) that change between runs.
_METADATA = {"png": {"Software": None}, "pdf": {"Creator": None, "Producer": None, "CreationDate": None},
             "svg": {"Date": None, "Creator": None}}


class FigureLayoutError(ValueError):
    """A figure whose texts overlap or leave the page: drawn, it would not read at its size."""


#: Pixels of overlap tolerated between two texts' boxes (anti-aliasing and glyph padding, at savefig.dpi).
OVERLAP_PX = 1.0


def _texts(fig):
    """(owner, label, box) of every visible, non-empty text: each axes' title, labels and tick labels, each
    legend's entries and title, the figure's own texts (its title among them) and figure legends."""
    renderer = fig.canvas.get_renderer()
    out = []

    def add(owner, text):
        if text.get_visible() and text.get_text().strip():
            out.append((owner, text.get_text(), text.get_window_extent(renderer)))

    for i, ax in enumerate(fig.axes):
        if not ax.get_visible():
            continue
        owner = f"panel {i + 1}"
        for text in (ax.title, ax.xaxis.label, ax.yaxis.label):
            add(owner, text)
        for axis, (lo, hi) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            lo, hi = min(lo, hi), max(lo, hi)
            slack = 1e-9 * (hi - lo)
            for tick in (*axis.get_major_ticks(), *axis.get_minor_ticks()):
                if lo - slack <= tick.get_loc() <= hi + slack:  # a tick outside the view is not drawn
                    add(owner, tick.label1)
                    add(owner, tick.label2)
        legend = ax.get_legend()
        if legend is not None:
            for text in (*legend.get_texts(), legend.get_title()):
                add(f"{owner}'s legend", text)
    for text in fig.texts:  # the suptitle among them
        add("figure", text)
    for legend in fig.legends:
        for text in (*legend.get_texts(), legend.get_title()):
            add("figure legend", text)
    return out


def layout_problems(fig) -> list[str]:
    """What would not read in ``fig`` at its size: a text reaching outside the page, or two texts of different
    owners (panels, legends, the figure's title) overlapping.  Empty when the figure reads."""
    fig.draw_without_rendering()  # the layout and every text's box, no pixels
    page = fig.bbox
    texts = _texts(fig)
    problems = [f"{owner}: {label!r} reaches outside the page" for owner, label, box in texts
                if box.x0 < page.x0 - OVERLAP_PX or box.y0 < page.y0 - OVERLAP_PX
                or box.x1 > page.x1 + OVERLAP_PX or box.y1 > page.y1 + OVERLAP_PX]
    for i, (owner, label, box) in enumerate(texts):
        for other, other_label, other_box in texts[i + 1:]:
            if owner != other and min(box.x1, other_box.x1) - max(box.x0, other_box.x0) > OVERLAP_PX \
                    and min(box.y1, other_box.y1) - max(box.y0, other_box.y0) > OVERLAP_PX:
                problems.append(f"{owner}'s {label!r} overlaps {other}'s {other_label!r}")
    return problems


def save(fig, paths) -> None:
    """Save ``fig`` to every path (format from the extension) without time stamps, then close it; each file is
    written beside and renamed (:func:`~sphereimpact.files.replacing`), so a failed save keeps the old figure.

    Raises
    ------
    FigureLayoutError
        The figure's texts overlap or leave the page (:func:`layout_problems`); nothing is written.
    """
    try:
        problems = layout_problems(fig)
        if problems:
            raise FigureLayoutError(f"figure {', '.join(map(str, paths))} does not read at its size: "
                                    + "; ".join(problems[:5]) + (f"; and {len(problems) - 5} more"
                                                                 if len(problems) > 5 else ""))
        for path in paths:
            fmt = str(path).rsplit(".", 1)[-1]
            with replacing(path) as partial:
                fig.savefig(partial, format=fmt, metadata=_METADATA.get(fmt, {}), bbox_inches=None)
    finally:
        plt.close(fig)
