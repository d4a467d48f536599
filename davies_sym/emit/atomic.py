"""Atomic file output: write to a temporary file beside the target, then rename."""

from __future__ import annotations

import os
import stat
import tempfile


def same_file(a: str | os.PathLike[str], b: str | os.PathLike[str]) -> bool:
    """Whether the paths ``a`` and ``b`` name one file however they are written (relative,
    ``..``, a symbolic link, or a hard link to an existing file)."""
    if os.path.realpath(a) == os.path.realpath(b):
        return True
    return os.path.exists(a) and os.path.exists(b) and os.path.samefile(a, b)


def _mode_for(path: str) -> int:
    """The permissions a new file gets (0666 less the umask, like ``open``), or those of
    the file it replaces."""
    if os.path.exists(path):
        return stat.S_IMODE(os.stat(path).st_mode)
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def write_atomic(path: str, text: str | bytes) -> None:
    """Write ``text`` (or bytes) to ``path`` so that readers see the old or the new file, never half; an
    `OSError` names ``path``.  A device or pipe (``-o /dev/null``) is written to as it is:
    renaming a file over it would replace the device."""
    if os.path.exists(path) and not os.path.isfile(path) and not os.path.isdir(path):
        try:
            with open(path, "wb") as stream:
                stream.write(text if isinstance(text, bytes) else text.encode("utf-8"))
        except OSError as exc:
            raise _about(exc, path) from None
        return
    directory = os.path.dirname(os.path.abspath(path))
    try:
        fd, tmp = tempfile.mkstemp(prefix=".", suffix=".tmp", dir=directory)
    except OSError as exc:
        raise _about(exc, path) from None
    try:
        # mkstemp creates the file readable by its owner only.
        os.chmod(tmp, _mode_for(path))
        if isinstance(text, bytes):
            with os.fdopen(fd, "wb") as binary:
                binary.write(text)
        else:
            with os.fdopen(fd, "w", encoding="utf-8") as handle:
                handle.write(text)
        os.replace(tmp, path)
    except BaseException as exc:
        if os.path.exists(tmp):
            os.unlink(tmp)
        if isinstance(exc, OSError):
            raise _about(exc, path) from None
        raise


def _about(exc: OSError, path: str) -> OSError:
    """``exc`` naming the file the caller wrote to, not the temporary file beside it (of the
    same class: ``PermissionError`` stays one)."""
    return OSError(exc.errno, exc.strerror, path) if exc.errno is not None else OSError(f"{exc} ({path})")
