"""Watching the script and its local modules, debounced.

Layers (as in watchfiles): a *notifier* reports raw paths that changed (watchdog
on the files' folders, or watchdog's polling observer where the file system
sends no events); a :class:`FileWatcher` keeps the paths it cares about and
calls back once things have been quiet for ``debounce`` seconds. Whether the
content really changed is the caller's business (the session hashes it).

Folders rather than files are watched because editors save by renaming (a
watch on the old inode would die) and because a file may vanish and come back.
"""

from __future__ import annotations

import contextlib
import logging
import os
import stat
import threading
import time
from collections.abc import Callable, Iterable
from typing import Protocol

_LOG = logging.getLogger("livemod.watch")
PathCallback = Callable[[str], None]
_WRITE_EVENTS = frozenset({"modified", "moved", "created", "closed"})
_FOLDER_EVENTS = frozenset({"created", "deleted", "moved"})


class Notifier(Protocol):
    """Reports paths that may have changed, from any thread."""

    def start(self, callback: PathCallback) -> None:
        """Begin reporting: ``callback(path)`` for every path that may have
        changed, called from the notifier's own thread."""

    def watch(self, folders: set[str]) -> None:
        """Watch exactly ``folders`` from now on (non-recursively)."""

    def stop(self) -> None:
        """Stop reporting; no callback is made after this returns."""


class WatchdogNotifier:
    """watchdog's native observer (inotify on Linux), or its polling observer.

    Every event's ``src_path`` and, for moves, ``dest_path`` are reported, so a
    save by rename (``tmp -> script.py``) and vim's move-away pattern are seen.

    A folder that does not exist (yet, or any more: deleted, or moved away) is
    watched through its nearest existing ancestor until it is back; then it is
    watched again and every file in it is reported once, since files written
    before its new watch began sent no event. The folders are looked at again
    on every folder event and every ``recheck_interval`` seconds, by a thread of
    the notifier's own (never the observer's, whose lock it would take in the
    other order than :meth:`watch` does).

    Args:
        poll: use watchdog's polling observer.
        poll_interval: seconds between the polling observer's scans.
        recheck_interval: seconds between looks at the folders without events.
        observer_factory: makes the observer (tests pass a fake); None: watchdog's.
    """

    def __init__(self, *, poll: bool = False, poll_interval: float = 0.25,
                 recheck_interval: float = 1.0,
                 observer_factory: Callable[[], object] | None = None) -> None:
        self._poll = poll
        self._poll_interval = poll_interval
        self._recheck_interval = recheck_interval
        self._factory = observer_factory
        self._lock = threading.Lock()  # held around every schedule/unschedule
        self._observer: object | None = None
        self._wanted: frozenset[str] = frozenset()
        self._watches: dict[str, tuple[object, tuple[int, int] | None]] = {}
        self._missing: set[str] = set()  # wanted folders watched through an ancestor
        # watched folders whose watch said they were deleted (the handler's lock: it
        # must never wait for the main one, which is held while the observer's is taken)
        self._dead: set[str] = set()
        self._dead_lock = threading.Lock()
        self._callback: PathCallback | None = None
        self._wake = threading.Event()
        self._stopping = threading.Event()
        self._rechecker: threading.Thread | None = None

    def start(self, callback: PathCallback) -> None:
        """Start the observer thread; ``callback`` gets each event's paths."""
        self._callback = callback
        observer = self._make_observer()
        observer.start()  # type: ignore[attr-defined]
        with self._lock:
            self._observer = observer
            self._sync_locked()  # folders asked for before the start
        self._rechecker = threading.Thread(target=self._recheck_loop, daemon=True,
                                           name="livemod-watch-recheck")
        self._rechecker.start()

    def _make_observer(self) -> object:
        if self._factory is not None:
            return self._factory()
        from watchdog.observers import Observer
        from watchdog.observers.polling import PollingObserver

        return PollingObserver(timeout=self._poll_interval) if self._poll else Observer()

    def watch(self, folders: set[str]) -> None:
        """Watch exactly ``folders`` (non-recursively); a missing one is watched
        through its nearest existing ancestor until it exists. After :meth:`stop`
        (also one racing this call) it does nothing."""
        with self._lock:
            self._wanted = frozenset(folders)
            self._missing &= self._wanted
            self._sync_locked()

    @property
    def watched(self) -> dict[str, str]:
        """``wanted folder -> folder watched for it`` (itself, or an ancestor)."""
        with self._lock:
            return {folder: _nearest_folder(folder) if folder in self._missing else folder
                    for folder in self._wanted}

    def recheck(self) -> None:
        """Look at the folders now: watch again each one that came back, or was
        replaced since its watch began, and report the files in it."""
        with self._lock:
            if self._observer is None:
                return  # stopped
            with self._dead_lock:
                dead, self._dead = self._dead, set()
            for path, (_, identity) in list(self._watches.items()):
                # deleted or replaced (a new folder may get the old inode: hence both)
                if path in dead or _identity(path) != identity:
                    self._drop_locked(path)
                    if path in self._wanted:
                        self._missing.add(path)
            armed = self._sync_locked()
        for folder in sorted(armed):
            self._report_folder(folder)

    def stop(self) -> None:
        """Stop the observer thread and wait for it (at most 5 s each)."""
        with self._lock:  # a watch() under way finishes first; later ones do nothing
            observer, self._observer = self._observer, None
        self._stopping.set()
        self._wake.set()
        if self._rechecker is not None and self._rechecker is not threading.current_thread():
            self._rechecker.join(timeout=5)
        if observer is not None:
            observer.stop()  # type: ignore[attr-defined]
            observer.join(timeout=5)  # type: ignore[attr-defined]

    def _sync_locked(self) -> set[str]:
        """Schedule the watches the wanted folders need now and drop the rest
        (caller holds the lock); returns the missing folders that came back."""
        if self._observer is None:
            return set()
        targets = {folder: _nearest_folder(folder) for folder in self._wanted}
        for path in set(self._watches) - set(targets.values()):
            self._drop_locked(path)
        for path in set(targets.values()) - set(self._watches):
            self._schedule_locked(path)
        armed = {f for f in self._missing if targets[f] == f and f in self._watches}
        self._missing = {f for f, target in targets.items()
                         if target != f or f not in self._watches}
        return armed

    def _schedule_locked(self, path: str) -> None:
        identity = _identity(path)
        if identity is None:
            return  # gone between the look and now: the next recheck finds it
        watch = self._observer.schedule(  # type: ignore[union-attr]
            _Handler(path, self._report, self._folder_event), path, recursive=False,
            event_filter=_event_types())
        self._watches[path] = (watch, identity)

    def _drop_locked(self, path: str) -> None:
        watch, _ = self._watches.pop(path)
        with contextlib.suppress(KeyError):  # the observer may have dropped it itself
            self._observer.unschedule(watch)  # type: ignore[union-attr]

    def _recheck_loop(self) -> None:
        """The recheck thread: after a folder event, and now and then, recheck."""
        while not self._stopping.is_set():
            self._wake.wait(self._recheck_interval)
            self._wake.clear()
            if self._stopping.is_set():
                return
            try:
                self.recheck()
            except OSError as exc:  # e.g. inotify's watch limit: try again later
                _LOG.warning("cannot watch %s again: %s", sorted(self._missing), exc)

    def _folder_event(self, folder: str, gone: bool) -> None:
        """Observer thread: a folder event in ``folder`` (``gone``: it was deleted)."""
        if gone:
            with self._dead_lock:
                self._dead.add(folder)
        self._wake.set()

    def _report_folder(self, folder: str) -> None:
        with contextlib.suppress(OSError):  # gone again: the next recheck sees it
            for entry in os.scandir(folder):
                self._report(entry.path)

    def _report(self, path: str) -> None:
        if self._callback is not None:
            self._callback(path)


def _nearest_folder(folder: str) -> str:
    """``folder`` if it is a folder, else its nearest ancestor that is one."""
    while not os.path.isdir(folder):
        parent = os.path.dirname(folder)
        if parent == folder:
            return folder  # no folder at all up to the root: nothing to watch
        folder = parent
    return folder


def _identity(folder: str) -> tuple[int, int] | None:
    """``(device, inode)`` of the folder, None if it is not one now."""
    try:
        info = os.stat(folder)
    except OSError:
        return None
    return (info.st_dev, info.st_ino) if stat.S_ISDIR(info.st_mode) else None


def _event_types() -> list[type]:
    from watchdog.events import (
        DirCreatedEvent,
        DirDeletedEvent,
        DirMovedEvent,
        FileClosedEvent,
        FileCreatedEvent,
        FileModifiedEvent,
        FileMovedEvent,
    )

    return [FileModifiedEvent, FileMovedEvent, FileCreatedEvent, FileClosedEvent,
            DirCreatedEvent, DirDeletedEvent, DirMovedEvent]


class _Handler:
    """The watchdog event handler: forwards paths, and wakes the recheck on a
    folder's event; nothing else (it runs on the observer thread)."""

    def __init__(self, folder: str, report: PathCallback,
                 folder_event: Callable[[str, bool], None]) -> None:
        self._folder = folder
        self._report = report
        self._folder_event = folder_event

    def dispatch(self, event: object) -> None:
        kind = getattr(event, "event_type", "")
        if getattr(event, "is_directory", False):
            if kind in _FOLDER_EVENTS:  # a watched folder, or one awaited, came or went
                where = os.fsdecode(getattr(event, "src_path", ""))
                self._folder_event(self._folder, kind == "deleted" and where == self._folder)
            return
        if kind not in _WRITE_EVENTS:
            return  # our own reads cause "opened"/"closed_no_write" events
        for attr in ("src_path", "dest_path"):
            path = getattr(event, attr, "")
            if path:
                self._report(os.fsdecode(path))


class ManualNotifier:
    """A notifier driven by hand (tests, or a manual "reload" key)."""

    def __init__(self) -> None:
        self.folders: set[str] = set()
        self._callback: PathCallback | None = None

    def start(self, callback: PathCallback) -> None:
        """Keep ``callback`` for :meth:`fire`."""
        self._callback = callback

    def watch(self, folders: set[str]) -> None:
        """Remember ``folders`` in :attr:`folders` (tests read what is watched)."""
        self.folders = set(folders)

    def stop(self) -> None:
        """Forget the callback: later :meth:`fire` calls report nothing."""
        self._callback = None

    def fire(self, path: str) -> None:
        """Report ``path`` as changed."""
        if self._callback is not None:
            self._callback(os.path.abspath(path))


class FileWatcher:
    """Calls ``on_change`` (in its own thread) ``debounce`` s after the last event
    on any of the watched files.

    Args:
        on_change: called with no arguments once the files have been quiet.
        debounce: seconds of quiet required after the last event.
        notifier: the event source (default: watchdog, polling if ``poll``).
        poll: use watchdog's polling observer (WSL, network and Docker mounts).
    """

    def __init__(self, on_change: Callable[[], None], *, debounce: float = 0.15,
                 notifier: Notifier | None = None, poll: bool = False) -> None:
        self._on_change = on_change
        self._debounce = debounce
        self._notifier = notifier if notifier is not None else WatchdogNotifier(poll=poll)
        self._files: frozenset[str] = frozenset()
        self._cond = threading.Condition()
        self._last_event: float | None = None
        self._closed = False
        self._thread = threading.Thread(target=self._loop, name="livemod-watch", daemon=True)

    def start(self) -> None:
        """Start the notifier and the debounce thread."""
        self._notifier.start(self._on_path)
        self._thread.start()

    def set_files(self, files: Iterable[str]) -> None:
        """Watch exactly ``files`` (absolute paths), through their folders."""
        self._files = frozenset(os.path.abspath(f) for f in files)
        self._notifier.watch({os.path.dirname(f) for f in self._files})

    @property
    def files(self) -> frozenset[str]:
        """The absolute paths watched now (the script and what it reads)."""
        return self._files

    def close(self) -> None:
        """Stop watching; no callback runs afterwards."""
        with self._cond:
            self._closed = True
            self._cond.notify_all()
        self._notifier.stop()
        if self._thread.is_alive() and self._thread is not threading.current_thread():
            self._thread.join(timeout=5)

    def _on_path(self, path: str) -> None:
        if os.path.abspath(path) in self._files:
            with self._cond:
                self._last_event = time.monotonic()
                self._cond.notify_all()

    def _loop(self) -> None:
        """The debounce thread: one ``on_change`` per quiet spell until closed."""
        while self._wait_for_quiet():
            try:
                self._on_change()
            except Exception:  # a failing callback must not stop the watching
                _LOG.exception("the change callback failed; watching goes on")

    def _wait_for_quiet(self) -> bool:
        """Block until an event is followed by ``debounce`` s of quiet; False on close."""
        with self._cond:
            while not self._closed:
                if self._last_event is None:
                    self._cond.wait()
                    continue
                left = self._last_event + self._debounce - time.monotonic()
                if left <= 0:
                    self._last_event = None
                    return True
                self._cond.wait(left)
            return False
