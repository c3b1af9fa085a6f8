"""Atomic file replacement: a failed save never leaves a truncated file.

Every writer in :mod:`livemod.dlfl.io` writes through :func:`atomic_write`: the
bytes go to a temporary file in the target's folder, which is flushed, synced
to disk and then renamed over the target with :func:`os.replace` (atomic on
POSIX and Windows). If anything raises before the rename, the temporary file is
removed and the old target, if any, is untouched. Saving through a symbolic
link replaces the file it points to and keeps the link. Files written into a
folder named to :func:`write_unsynced` (a cluster worker's scratch outputs,
read back at once) are replaced atomically too, but not synced.

A process killed mid-save (SIGKILL, a power cut) cannot remove its temporary
file, so each name says who wrote it: ``.NAME.HOST-PID-START-RANDOM.tmp``, with
a hash of the host name, the writer's process id and a token of that process's
start (its start time on Linux, so that a reused process id is told apart).
The first save into a folder (and again once a minute) removes the temporary
files there whose writer, on this host, is gone (and temporary folders of such
names: a batch stages a file with its companions in one); a live writer's,
another host's and names of any other form are left alone.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import os
import re
import secrets
import shutil
import socket
import threading
import time
from collections.abc import Iterable, Iterator
from typing import BinaryIO


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike[str], *, sync_folder: bool = True,
                 ) -> Iterator[BinaryIO]:
    """Open a binary file that replaces ``path`` only when the block succeeds.

    Args:
        path: the file to create or replace; its folder must exist. A symbolic
            link is followed: the file it points to is replaced and the link
            kept, as editors save through links (a dangling link's target is
            created).
        sync_folder: make the rename durable at once (syncing the folder); a
            caller that saves many files in a row passes False and calls
            :func:`sync_folders` once before it records them as saved.

    Yields:
        A binary file object open for writing (a temporary file beside ``path``).

    Raises:
        OSError: the folder cannot hold the temporary file, or the rename fails.
            Whatever the block raises is re-raised after the temporary file is
            removed.
    """
    # the temporary file must sit beside the file finally replaced, for the rename
    target = os.path.realpath(os.path.abspath(os.fspath(path)))
    folder = os.path.dirname(target)
    remove_abandoned(folder)
    old_mode = _old_mode(target)
    # created with the old file's mode (a private file's new text is never readable
    # by others), or 0o666 less the umask for a new file, as any other new file
    fd, tmp_path = _temporary_beside(target, 0o666 if old_mode is None else old_mode)
    durable = folder not in _unsynced
    try:
        with os.fdopen(fd, "wb") as handle:
            yield handle
            handle.flush()
            if durable:
                os.fsync(handle.fileno())
        if old_mode is not None:  # the umask may have cleared some of its bits
            os.chmod(tmp_path, old_mode)
        try:
            os.replace(tmp_path, target)
        except OSError as exc:  # the target may be a folder, say
            raise _about(target, exc) from None
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp_path)
        raise
    finally:
        _in_progress.discard(tmp_path)
    if sync_folder and durable:
        _sync_folder(folder)


# temporary files of the writes under way in this process
_in_progress: set[str] = set()
# folders whose files are read back at once and thrown away (see write_unsynced)
_unsynced: set[str] = set()


def write_unsynced(folder: str) -> None:
    """From now on, files written into ``folder`` (an absolute, real path; not
    its subfolders) are still replaced atomically but not synced to disk, nor
    the folder: for a scratch folder whose files are read back at once and
    thrown away (a cluster worker's outputs, which the client writes durably).
    Syncing would make the disk write each file, to be discarded after."""
    _unsynced.add(folder)


def _temporary_beside(target: str, mode: int) -> tuple[int, str]:
    """A new file of :func:`temporary_path` beside ``target``, open for writing
    (``mode`` less the umask), and its path, listed in ``_in_progress`` *before* it exists: a
    worker killed between the two (SIGTERM, see :func:`remove_unfinished`) must
    not leave it behind.

    Raises:
        OSError: the folder cannot hold it (the message names ``target``).
    """
    for _ in range(100):
        tmp_path = temporary_path(target)
        _in_progress.add(tmp_path)
        try:
            return os.open(tmp_path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, mode), tmp_path
        except FileExistsError:
            _in_progress.discard(tmp_path)
        except OSError as exc:
            _in_progress.discard(tmp_path)
            raise _about(target, exc) from None
    raise FileExistsError(errno.EEXIST, f"cannot write {target}: no free temporary name")


def temporary_path(target: str) -> str:
    """A fresh name ``.NAME.HOST-PID-START-RANDOM.tmp`` beside ``target`` (an
    absolute path) that says this process wrote it (see the module's docstring);
    nothing is created. The name may be given to a file or to a folder (the
    sweep of abandoned ones removes either)."""
    folder, name = os.path.split(target)
    return os.path.join(folder, f".{name}.{writer_token()}-{secrets.token_hex(4)}.tmp")


def writer_token() -> str:
    """``HOST-PID-START`` of the calling process (worked out once per process: a
    forked child gets its own)."""
    pid = os.getpid()
    if _token[0] != pid:
        _token[:] = [pid, f"{_host_hash()}-{pid}-{_start_token(pid) or 0}"]
    return str(_token[1])


_token: list = [None, ""]  # [pid it is for, its token]


def _host_hash() -> str:
    return hashlib.blake2b(socket.gethostname().encode(), digest_size=4).hexdigest()


def _start_token(pid: int) -> int | None:
    """When process ``pid`` started, in clock ticks since boot (Linux's
    ``/proc/PID/stat``); None where that cannot be read (no such process, or no
    ``/proc``)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as handle:
            stat = handle.read()
    except OSError:
        return None
    # the fields after the command name, which is in parentheses and may hold any byte
    fields = stat[stat.rfind(b")") + 2:].split()
    return int(fields[19]) if len(fields) > 19 else None


_TEMPORARY = re.compile(r"\.(?P<name>.+)\.(?P<host>[0-9a-f]{8})-(?P<pid>\d+)-(?P<start>\d+)"
                        r"-[0-9a-f]{8}\.tmp")
_SWEEP_INTERVAL = 60.0  # seconds between two sweeps of one folder by one process
_swept: dict[str, float] = {}  # folder -> when this process last swept it
_swept_lock = threading.Lock()


def remove_abandoned(folder: str) -> list[str]:
    """Remove the temporary files in ``folder`` whose writer is gone (a killed
    save's), unless this process swept ``folder`` less than a minute ago; the
    names removed. Files whose writer lives, runs on another host or cannot be
    told (names of another form) are kept; nothing here raises."""
    if _TEMPORARY.fullmatch(os.path.basename(folder)):
        return []  # a staging folder (see temporary_path): its writer's alone, and new
    now = time.monotonic()
    with _swept_lock:
        if now - _swept.get(folder, -_SWEEP_INTERVAL) < _SWEEP_INTERVAL:
            return []
        _swept[folder] = now
    try:
        names = [entry.name for entry in os.scandir(folder)
                 if entry.name.endswith(".tmp") and entry.name.startswith(".")]
    except OSError:
        return []
    removed = []
    for name in names:
        found = _TEMPORARY.fullmatch(name)
        if found is not None and _writer_gone(found["host"], int(found["pid"]),
                                              int(found["start"])):
            with contextlib.suppress(OSError):
                remove_temporary(os.path.join(folder, name))
                removed.append(name)
    return removed


def remove_temporary(path: str) -> None:
    """Remove the temporary file ``path``, or the temporary folder of that name
    with what it holds (a batch stages a file and its companions in one, see
    :func:`temporary_path`); a symbolic link is removed, never followed.

    Raises:
        OSError: it cannot be removed (FileNotFoundError: there is none).
    """
    if os.path.isdir(path) and not os.path.islink(path):
        shutil.rmtree(path)
    else:
        os.unlink(path)


def _writer_gone(host: str, pid: int, start: int) -> bool:
    """True when the process that named a temporary file ``host``, ``pid``,
    ``start`` has surely exited: it ran on this host, and no process ``pid``
    runs now, or (where start times can be read) the one that does started at
    another time. Unsure means alive."""
    if host != _host_hash() or pid == os.getpid():
        return False
    now_start = _start_token(pid)
    if now_start is not None:
        return start != 0 and now_start != start
    if os.path.isdir("/proc/self"):  # /proc is there, so no process has that id
        return True
    if os.name == "nt":  # os.kill would end the process there, not probe it
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except OSError:  # it exists (another user's, say), or this platform cannot tell
        return False
    return False


def _about(target: str, exc: OSError) -> OSError:
    """``exc`` said of ``target``, not of a temporary name the caller never saw."""
    return type(exc)(exc.errno, f"cannot write {target}: {exc.strerror}")


def remove_unfinished() -> None:
    """Remove the temporary files of the writes still under way in this process.

    For a process that is being killed (a batch worker on SIGTERM): the writes
    will never finish, and their targets are untouched.
    """
    for tmp_path in list(_in_progress):
        with contextlib.suppress(OSError):
            os.unlink(tmp_path)


def move_into_place(staged: str, path: str | os.PathLike[str], *,
                    sync_folder: bool = True) -> None:
    """Replace ``path`` with the finished file ``staged`` (one of
    :func:`temporary_path` beside it, which another process may have written), as
    :func:`atomic_write` ends: with the old file's permission bits, durably
    (``sync_folder``, as there), and through a symbolic link to the file it
    points to.

    Raises:
        OSError: the rename fails (the message names ``path``); ``staged`` is left.
    """
    target = os.path.realpath(os.path.abspath(os.fspath(path)))
    old_mode = _old_mode(target)
    try:
        if old_mode is not None:
            os.chmod(staged, old_mode)
        os.replace(staged, target)
    except OSError as exc:
        raise _about(target, exc) from None
    if sync_folder:
        _sync_folder(os.path.dirname(target))


def sync_folders(paths: Iterable[str | os.PathLike[str]]) -> None:
    """Make the renames into the folders of ``paths`` durable (see
    ``sync_folder`` of :func:`atomic_write`): each folder once."""
    folders = {os.path.dirname(os.path.realpath(os.path.abspath(os.fspath(p)))) for p in paths}
    for folder in sorted(folders):
        _sync_folder(folder)


def write_atomically(path: str | os.PathLike[str], data: bytes | Iterable[bytes | memoryview], *,
                     sync_folder: bool = True) -> None:
    """Replace ``path`` with ``data`` through :func:`atomic_write`.

    Args:
        path: the file to create or replace.
        data: the contents, or an iterable of pieces written one after another
            (so a large file never has to exist whole in memory).
        sync_folder: as for :func:`atomic_write`.

    Raises:
        OSError: the file cannot be written; an existing file is left intact.
            Whatever iterating ``data`` raises is re-raised, the file likewise
            left intact.
    """
    with atomic_write(path, sync_folder=sync_folder) as handle:
        if isinstance(data, bytes | bytearray | memoryview):
            handle.write(data)
            return
        for piece in data:
            handle.write(piece)


def _old_mode(target: str) -> int | None:
    """The permission bits of the file being replaced, or None when there is none.

    A new file gets ``0o666`` less the umask through ``os.open``, which applies
    the umask itself (reading the umask would mean setting it, which is not
    thread-safe, and scripts save from a worker thread).
    """
    try:
        return os.stat(target).st_mode & 0o777
    except OSError:
        return None


def _sync_folder(folder: str) -> None:
    """Make the rename itself durable where the platform allows syncing a folder."""
    if not hasattr(os, "O_DIRECTORY"):
        return
    with contextlib.suppress(OSError):
        fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)
