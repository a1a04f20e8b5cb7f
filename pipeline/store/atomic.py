"""Atomic writes: the one way the pipeline puts a file in place.

A file at the target path is always complete: data goes to a temporary file in
the same directory, is flushed to disk and then ``os.replace``-d onto the
target.  A crash, Ctrl-C or ``kill -9`` mid-write leaves the previous target
(or none), never a truncated one (a killed process can leave its hidden
temporary ``.<name>.tmp-<pid>-<random><suffix>`` behind; harmless).

``atomic_write`` is the primitive; ``save_figure`` (a matplotlib figure, which
it then closes), ``save_image`` (an RGB(A) array as PNG) and ``save_text`` are
the writers the stages, validation and benchmarks use.  ``postprocess/`` draws
figures and renders images but writes nothing: the caller saves them here.
"""
from __future__ import annotations

import contextlib
import os
import secrets
import signal
from pathlib import Path
from typing import Iterator
import sys

__all__ = ["atomic_write", "save_figure", "save_image", "save_text"]


# --------------------------------------------------------------------------
# Atomic writing
# --------------------------------------------------------------------------


def _fsync_path(path: Path) -> None:
    """Flush a file's data to stable storage."""
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _fsync_dir(directory: Path) -> None:
    """Persist a rename by fsyncing the directory (best effort; not on all OSes)."""
    try:
        fd = os.open(directory, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


_SIGINT = {"seen": False}


def watch_interrupts() -> None:
    """Ctrl-C raises KeyboardInterrupt as ever, and is remembered: a library that swallows the exception
    (FFCx's JIT, loading a compiled form, takes it for an ImportError of another process's compile and
    retries) cannot let a stage go on writing as if nothing happened (``interrupted``; the command line
    installs it)."""
    def handler(signum, frame):
        _SIGINT["seen"] = True
        raise KeyboardInterrupt
    signal.signal(signal.SIGINT, handler)


def interrupted() -> bool:
    """Whether Ctrl-C came since ``watch_interrupts`` (even if the exception was swallowed)."""
    return _SIGINT["seen"]


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike) -> Iterator[Path]:
    """Context manager yielding a temporary path that replaces ``path`` on success.

    ::

        with atomic_write("build/modes/r920.msh") as tmp:
            gmsh.write(str(tmp))

    The temporary file ``.<name>.tmp-<pid>-<random><suffix>`` lives in the
    target's directory (so the final ``os.replace`` is an atomic rename on
    the same file system) and keeps the target's suffix, so libraries that
    choose the format from the extension (numpy ``.npz``, gmsh ``.msh``)
    behave as for the target.  It is created empty before the body runs;
    the body may overwrite or truncate it.

    On normal exit the file is fsync-ed and renamed onto ``path``.  If the
    body raises (anything, including ``KeyboardInterrupt``), or a Ctrl-C came
    and was swallowed (``interrupted``), the temporary file is deleted and the
    exception propagates; the target is untouched.
    Parent directories are created as needed.
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    # O_EXCL guarantees that the name is ours; mode 0o666 lets the umask
    # decide the final permissions, as for a normally created file.
    while True:
        tmp = target.with_name(
            f".{target.name}.tmp-{os.getpid()}-{secrets.token_hex(4)}{target.suffix}"
        )
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:  # astronomically unlikely; just pick another name
            continue
        os.close(fd)
        break
    try:
        yield tmp
        if interrupted():                # a Ctrl-C swallowed on the way: nothing more is put in place
            raise KeyboardInterrupt
        if not tmp.exists():
            raise FileNotFoundError(
                f"atomic_write: temporary file {tmp} disappeared before it could "
                f"replace {target} (did the writer rename or delete it?)"
            )
        _fsync_path(tmp)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise
    _fsync_dir(target.parent)


def save_figure(fig, path: str | os.PathLike, **savefig_kw) -> Path:
    """Write a matplotlib figure atomically (``fig.savefig(tmp, **savefig_kw)``),
    then close it (pyplot figures are released; a figure made without pyplot needs nothing, and
    pyplot is not imported for it).  Returns the path."""
    try:
        with atomic_write(path) as tmp:
            fig.savefig(tmp, **savefig_kw)
    finally:
        if "matplotlib.pyplot" in sys.modules:
            sys.modules["matplotlib.pyplot"].close(fig)
    return Path(path)


def save_image(image, path: str | os.PathLike) -> Path:
    """Write an (H, W, 3 or 4) uint8 image array as PNG atomically (PIL, the
    writer pyvista's screenshots use).  Returns the path."""
    from PIL import Image  # lazy: brings in PIL

    with atomic_write(path) as tmp:
        Image.fromarray(image).save(tmp, format="PNG")
    return Path(path)


def save_text(text: str, path: str | os.PathLike) -> Path:
    """Write UTF-8 text atomically (Markdown fragments, reports).  Returns the path."""
    with atomic_write(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)
