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

import logging
import os
import threading
import time
from collections.abc import Callable, Iterable
from typing import Protocol

_LOG = logging.getLogger("livemod.watch")
PathCallback = Callable[[str], None]
_WRITE_EVENTS = frozenset({"modified", "moved", "created", "closed"})


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
    """

    def __init__(self, *, poll: bool = False, poll_interval: float = 0.25) -> None:
        self._poll = poll
        self._poll_interval = poll_interval
        self._observer: object | None = None
        self._watches: dict[str, object] = {}
        self._callback: PathCallback | None = None

    def start(self, callback: PathCallback) -> None:
        """Start the observer thread; ``callback`` gets each event's paths."""
        from watchdog.observers import Observer
        from watchdog.observers.polling import PollingObserver

        self._callback = callback
        observer = PollingObserver(timeout=self._poll_interval) if self._poll else Observer()
        observer.start()
        self._observer = observer

    def watch(self, folders: set[str]) -> None:
        """Watch exactly ``folders`` (non-recursively); missing folders are skipped."""
        observer = self._observer
        if observer is None:
            return
        for folder in set(self._watches) - folders:
            observer.unschedule(self._watches.pop(folder))  # type: ignore[attr-defined]
        for folder in folders - set(self._watches):
            if os.path.isdir(folder):
                handler = _Handler(self._report)
                watch = observer.schedule(  # type: ignore[attr-defined]
                    handler, folder, recursive=False, event_filter=_event_types())
                self._watches[folder] = watch

    def stop(self) -> None:
        """Stop the observer thread and wait for it (at most 5 s)."""
        observer, self._observer = self._observer, None
        if observer is not None:
            observer.stop()  # type: ignore[attr-defined]
            observer.join(timeout=5)  # type: ignore[attr-defined]

    def _report(self, path: str) -> None:
        if self._callback is not None:
            self._callback(path)


def _event_types() -> list[type]:
    from watchdog.events import (
        FileClosedEvent,
        FileCreatedEvent,
        FileModifiedEvent,
        FileMovedEvent,
    )

    return [FileModifiedEvent, FileMovedEvent, FileCreatedEvent, FileClosedEvent]


class _Handler:
    """The watchdog event handler: forwards paths and does nothing else (it runs
    on the observer thread)."""

    def __init__(self, report: PathCallback) -> None:
        self._report = report

    def dispatch(self, event: object) -> None:
        if getattr(event, "event_type", "") not in _WRITE_EVENTS:
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
