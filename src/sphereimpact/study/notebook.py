"""Execute a jupytext percent-format notebook and render it to HTML."""

from __future__ import annotations

import os

import jupytext
import nbformat
from nbclient import NotebookClient
from nbconvert import HTMLExporter


def execute_to_html(source: str, html_path: str, cwd: str = ".", timeout: int = 600) -> None:
    """Run every cell of ``source`` (a ``.py`` percent notebook) in ``cwd`` and write HTML.

    A cell that raises stops the run with that error (nbclient's CellExecutionError).
    """
    notebook = jupytext.read(source)
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    NotebookClient(notebook, timeout=timeout, kernel_name="python3",
                   resources={"metadata": {"path": os.path.abspath(cwd)}}).execute()
    body, _ = HTMLExporter().from_notebook_node(nbformat.from_dict(notebook))
    os.makedirs(os.path.dirname(os.path.abspath(html_path)), exist_ok=True)
    with open(html_path, "w", encoding="utf-8") as handle:
        handle.write(body)
