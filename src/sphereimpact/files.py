"""Files written whole or not at all: each is written beside its target and renamed over it at the end.

A run killed, a full disk or a failing figure then leaves the old file as it was (or no file), never a
truncated one: ``os.replace`` within one folder is atomic on POSIX and Windows.
"""

from __future__ import annotations

import os
from contextlib import contextmanager
from pathlib import Path


@contextmanager
def replacing(path):
    """Yield a temporary path beside ``path`` (same folder, so the rename is atomic; hidden, ending in ``path``'s own
    name, so a writer that reads the format off the extension still can) to write to; on success it is renamed
    over ``path``, on any failure removed and the failure raised again."""
    folder, name = os.path.split(os.path.abspath(path))
    partial = os.path.join(folder, f".partial-{os.getpid()}-{name}")
    try:
        yield partial
        os.replace(partial, path)
    except BaseException:
        if os.path.exists(partial):
            os.unlink(partial)
        raise


def copy_file(source, path) -> None:
    """Copy the file ``source`` to ``path``, written whole or not at all (:func:`replacing`)."""
    data = Path(source).read_bytes()
    with replacing(path) as partial:
        Path(partial).write_bytes(data)


def write_text(path, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` whole or not at all (:func:`replacing`)."""
    with replacing(path) as partial:
        Path(partial).write_text(text, encoding="utf-8")


def load_yaml(stream):
    """The data of a YAML text or open file, as ``yaml.safe_load`` reads it, by libyaml's parser where PyYAML was
    built with it (the same objects, about 7x faster: the config schema is read each time a workflow starts)."""
    import yaml

    return yaml.load(stream, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))  # noqa: S506 (a safe loader)
