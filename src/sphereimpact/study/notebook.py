"""Execute a jupytext percent-format notebook and render it to HTML."""

from __future__ import annotations

import os
import tempfile

import jupytext
import nbformat
from jupyter_client import KernelManager
from nbclient import NotebookClient
from nbconvert import HTMLExporter


def execute_to_html(source: str, html_path: str, cwd: str = ".", timeout: int = 600) -> None:
    """Run every cell of ``source`` (a ``.py`` percent notebook) in ``cwd`` and write HTML.

    A cell that raises stops the run with that error (nbclient's CellExecutionError).
    """
    notebook = jupytext.read(source)
    notebook.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    # the kernel talks over local sockets (IPC), not TCP: no network port, and no warning that TCP is unencrypted
    with tempfile.TemporaryDirectory() as sockets:
        manager = KernelManager(kernel_name="python3", transport="ipc", ip=os.path.join(sockets, "kernel"))
        try:
            NotebookClient(notebook, km=manager, timeout=timeout, kernel_name="python3",
                           resources={"metadata": {"path": os.path.abspath(cwd)}}).execute()
        finally:  # a kernel manager given to the client is the caller's to shut down
            if manager.has_kernel:
                manager.shutdown_kernel(now=True)
    body, _ = HTMLExporter().from_notebook_node(nbformat.from_dict(notebook))
    os.makedirs(os.path.dirname(os.path.abspath(html_path)), exist_ok=True)
    with open(html_path, "w", encoding="utf-8") as handle:
        handle.write(body)
