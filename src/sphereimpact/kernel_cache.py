"""numba's disk cache of the package's kernels, kept true to every source they compile.

numba keeps a compiled kernel on disk (its module's ``__pycache__``, or under ``NUMBA_CACHE_DIR``) and compiles it
anew when that module's text changes, but not when a function it compiles from another module changes (``ode.events``'
searches, :func:`~sphereimpact.contact.normal_kernel.normal_state` inside the stick and grip kernels), nor a constant it
reads from one.  A checkout updated in place (a pull, an edit) would then run the machine code of the old sources:
seen here, the grip kernel read a new kind of normal motion as DOP853's and returned inf.  So the first kernel module a
process imports calls :func:`refresh` before it defines its kernels: where the text of a file of :data:`SOURCES`
differs from the record made at the last refresh, it deletes the cached kernels of every module of :data:`KERNELS`,
which numba then compiles on first use, as on a fresh machine.  A plug-in law's kernel module is the plug-in's:
numba's own rule holds for it.
"""

from __future__ import annotations

import hashlib
import types
from pathlib import Path

#: The package's modules that keep compiled kernels on disk (numba's ``cache`` option), relative to the package.
KERNELS = ("contact/laws/kernels.py", "contact/normal_kernel.py", "contact/tangential/microslip_march.py",
           "contact/tangential/rigid_kernel.py", "contact/tangential/stick_kernel.py", "integrators/dop853_kernel.py",
           "integrators/taylor_kernel.py")
#: Every package module the kernels may compile code or constants from: the kernel modules and the modules they
#: import, directly or not (tests/test_kernels.py holds this list to their imports).
SOURCES = (*KERNELS, "choice.py", "contact/laws/closed_form.py", "contact/laws/spring_damper.py",
           "contact/separation.py", "errors.py", "integrators/event_kinds.py", "ode/dense.py", "ode/dop853.py",
           "ode/dop853_tableau.py", "ode/events.py", "ode/roots.py", "ode/series.py")
#: The package's folder, and the record of its sources' texts at the last refresh.
ROOT = Path(__file__).resolve().parent
RECORD = ROOT / "__pycache__" / "kernel_sources.stamps"
_refreshed = False


def digests(root: Path = ROOT, sources=SOURCES) -> str:
    """Each of ``sources``' name under ``root`` and the SHA-256 of its text, a line each."""
    return "".join(f"{name} {hashlib.sha256((root / name).read_bytes()).hexdigest()}\n" for name in sources)


def cache_folder(source: Path) -> Path | None:
    """The folder where numba caches the kernels of the module file ``source``: its own choice, in its order
    (``NUMBA_CACHE_DIR``, the module's ``__pycache__``, the user's cache folder); None where it caches nowhere."""
    from numba.core import caching

    for locator in (caching.UserProvidedCacheLocator, caching.InTreeCacheLocator, caching.UserWideCacheLocator):
        found = locator.from_function(cache_folder, str(source))
        if found is not None:
            return Path(found.get_cache_path())
    return None


def refresh(root: Path = ROOT, record: Path = RECORD, kernels=KERNELS, sources=SOURCES) -> int:
    """Delete the cached kernels of ``kernels`` where a text of ``sources`` differs from the record (or none was made),
    then record them; once per process.  Returns the files deleted.  A process that cannot write beside the package
    (an installation made read-only, whose files never change in place) leaves numba's own rule alone."""
    global _refreshed
    if root == ROOT:
        if _refreshed:
            return 0
        _refreshed = True
    try:
        import fcntl  # one process at a time checks and deletes (two processes compile a fresh clone's kernels at once)
    except ImportError:  # not POSIX: unlocked
        fcntl = None
    try:
        record.parent.mkdir(exist_ok=True)
        with open(record.with_suffix(".lock"), "a") as lock:
            if fcntl is not None:
                fcntl.flock(lock, fcntl.LOCK_EX)
            now = digests(root, sources)
            if record.is_file() and record.read_text() == now:
                return 0
            deleted = 0
            for name in kernels:
                folder = cache_folder(root / name)
                for cached in (folder.glob(f"{Path(name).stem}.*.nb[ic]") if folder is not None else ()):
                    cached.unlink(missing_ok=True)
                    deleted += 1
            written = record.with_suffix(".new")
            written.write_text(now)
            written.replace(record)
            return deleted
    except OSError:
        return 0


def owned(function, owner: str):
    """A copy of the plain function ``function`` for the kernel module ``owner`` to compile, with its own numba cache
    files.  numba names a kernel's cache files after the function's module and qualified name, so modules compiling the
    same helper (``ode.dense.grown`` in three) shared one index and its numbered entries: compiled at once in parallel
    processes (a fresh clone's :func:`~sphereimpact.integrators.compiled.compile_all` groups), one process's machine
    code could land in the entry another had indexed for another signature, and a clean clone's compile then failed
    typing ``grown``.  The copy runs the same code (its code object, globals and defaults), only named for its owner."""
    copy = types.FunctionType(function.__code__, function.__globals__, function.__name__, function.__defaults__,
                              function.__closure__)
    copy.__qualname__ = f"{function.__qualname__}_{owner}"
    copy.__doc__ = function.__doc__
    return copy
