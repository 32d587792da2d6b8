"""Writing a file so that no reader ever sees half of it: the one atomic write of the course.

Used by the progress record (gm_core.checks.store), the grader's results
(gm_grader.report) and the workspace sync (tools/sync_workspace.py).
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path

__all__ = ["atomic_write"]


def atomic_write(path: str | os.PathLike[str], data: bytes | str) -> None:
    """Write ``data`` (``str`` is written as UTF-8) to ``path`` atomically.

    The bytes go to a temporary file in the same folder, are flushed to disk, and the file is then
    renamed over ``path``: a reader sees the old file or the new one, never a mixture. On any
    failure the temporary file is removed and the error is raised unchanged.
    """
    path = Path(path)
    if isinstance(data, str):
        data = data.encode("utf-8")
    if not isinstance(data, bytes):
        raise TypeError(f"data must be bytes or str, not {type(data).__name__}")
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise
