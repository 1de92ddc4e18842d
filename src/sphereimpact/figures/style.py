"""Deterministic figure output: the same data give byte-identical PNG, PDF and SVG files."""

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


def save(fig, paths) -> None:
    """Save ``fig`` to every path (format from the extension) without time stamps, then close it; each file is
    written beside and renamed (:func:`~sphereimpact.files.replacing`), so a failed save keeps the old figure."""
    try:
        for path in paths:
            fmt = str(path).rsplit(".", 1)[-1]
            with replacing(path) as partial:
                fig.savefig(partial, format=fmt, metadata=_METADATA.get(fmt, {}), bbox_inches=None)
    finally:
        plt.close(fig)
