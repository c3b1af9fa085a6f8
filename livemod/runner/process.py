"""What a script may change in the interpreter, and giving it back.

A run executes the user's code in livemod's own process, so whatever the script
changes process-wide would outlive it: a ``os.chdir`` would move the next
``-o`` file, ``warnings.simplefilter("error")`` would fail the next run's mesh
repair, a replaced ``sys.stdout`` would hide every later report. A
:class:`ProcessState` is a picture of those parts;
:meth:`ProcessState.restore` puts back whatever differs from it (and touches
nothing that does not, so that it costs little when a script changed nothing).

What it covers: the working directory; ``os.environ``; ``sys.path`` and
``sys.meta_path`` (the list objects and their contents); ``sys.stdin``,
``sys.stdout`` and ``sys.stderr`` (a stream the script closed is opened again
on its descriptor) and the descriptors 0, 1 and 2 themselves (closed or
redirected by the script); the warnings filters, ``warnings.showwarning`` and
``formatwarning``; ``sys.excepthook``, ``sys.unraisablehook``,
``threading.excepthook`` and ``os._exit``; the recursion limit, the switch
interval, the int-to-text digit limit, the garbage collector's state and
thresholds; the SIGINT and SIGTERM handlers (from the main thread only);
``builtins`` and livemod's library (``livemod`` and every module of
``livemod.dlfl``): their ``sys.modules`` entries, the names each module binds,
and the attributes of the classes they define. What a script changes inside
an object (an item of a module's dict or list) is not seen, nor anything of
other packages; docs/guide.md lists what cannot be given back.
"""

from __future__ import annotations

import builtins
import gc
import importlib
import logging
import os
import pkgutil
import signal
import sys
import threading
import warnings
from collections.abc import Callable
from types import ModuleType
from typing import Any, TextIO

_LOG = logging.getLogger("livemod.runner")
_MISSING = object()

# (object, attribute) pairs put back by identity
_ATTRIBUTES: tuple[tuple[Any, str], ...] = (
    (sys, "path"), (sys, "meta_path"), (sys, "stdin"), (sys, "stdout"), (sys, "stderr"),
    (sys, "excepthook"), (sys, "unraisablehook"), (threading, "excepthook"),
    (warnings, "filters"), (warnings, "showwarning"), (warnings, "formatwarning"),
    (os, "_exit"),
)
# lists whose contents are put back too (they are shared with the interpreter)
_LISTS: tuple[tuple[Any, str], ...] = ((sys, "path"), (sys, "meta_path"), (warnings, "filters"))
_STREAMS = ("stdin", "stdout", "stderr")
_SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM") if hasattr(signal, name))


def _set_gc(enabled: bool) -> None:
    (gc.enable if enabled else gc.disable)()


def _set_gc_threshold(threshold: tuple[int, ...]) -> None:
    gc.set_threshold(*threshold)


# (read, write) pairs of process-wide settings
_SETTINGS: tuple[tuple[Callable[[], Any], Callable[[Any], Any]], ...] = (
    (sys.getrecursionlimit, sys.setrecursionlimit),
    (sys.getswitchinterval, sys.setswitchinterval),
    (sys.get_int_max_str_digits, sys.set_int_max_str_digits),
    (gc.isenabled, _set_gc),
    (gc.get_threshold, _set_gc_threshold),
)


class ProcessState:
    """The parts of the process a script may change, as they are now.

    Two pictures: of the process's settings (:class:`_Settings`: directory,
    environment, streams, hooks, limits), which :meth:`retake` takes again, so
    that changes the host makes between runs stand; and of livemod's library
    (:class:`_Modules`), taken once: the library the first run saw is the one
    every run gets. Taking it imports every module of ``livemod.dlfl`` first
    (once per process), so that all of the library is in the picture. Call
    :meth:`close` when done with it: it holds duplicates of the standard
    descriptors.
    """

    def __init__(self) -> None:
        self.settings = _Settings()
        self.modules = _Modules()
        self._local: dict[str, dict[str, ModuleType]] = {}  # see local_modules
        # runs abandoned while they held it (or were about to) that may still change
        # it, and whether one of them ended since the last restore: then a run
        # restores it as it starts, instead of retaking it (see RunLease)
        self.abandoned = 0
        self.dirty = False

    def local_modules(self, folder: str, find: Callable[[], dict[str, ModuleType]],
                      ) -> dict[str, ModuleType]:
        """The modules of a script's ``folder`` the host had imported, as the
        first run from that folder saw them (``find()`` looks them up then)."""
        if folder not in self._local:
            self._local[folder] = find()
        return self._local[folder]

    def retake(self) -> None:
        """Picture the process's settings again, as the host has them now."""
        settings, self.settings = self.settings, _Settings(self.settings.streams)
        settings.streams.close(keep=self.settings.streams)

    def restore(self) -> None:
        """Put back every part that differs from the pictures; safe from any
        thread (signal handlers are put back from the main thread only)."""
        self.settings.restore()
        self.modules.restore()

    def close(self) -> None:
        """Release the duplicated descriptors (restore() cannot mend them after)."""
        self.settings.streams.close()


class _Settings:
    """The process's settings a script may change (all but the library's code).

    Args:
        streams: the previous picture's standard descriptors, whose duplicates
            are kept for those still open on the same file.
    """

    def __init__(self, streams: _Streams | None = None) -> None:
        self.cwd = os.getcwd()
        self.environ = _raw_environ()
        self.attributes = [(owner, name, getattr(owner, name)) for owner, name in _ATTRIBUTES]
        self.lists = [(getattr(owner, name), list(getattr(owner, name))) for owner, name in _LISTS]
        self.values = [(read, write, read()) for read, write in _SETTINGS]
        self.signals = {number: signal.getsignal(number) for number in _SIGNALS}
        self.streams = _Streams(streams)

    def restore(self) -> None:
        self._restore_cwd()
        _restore_environ(self.environ)
        if self._restore_attributes():  # maybe the warnings filters: forget what
            warnings._filters_mutated()  # type: ignore[attr-defined]  # registries say
        for read, write, value in self.values:
            if read() != value:
                write(value)
        self._restore_signals()
        self.streams.restore()

    def _restore_attributes(self) -> bool:
        """Put back the attributes and the lists' contents; True if one differed."""
        changed = False
        for owner, name, value in self.attributes:
            if getattr(owner, name, _MISSING) is not value:
                setattr(owner, name, value)
                changed = True
        for target, contents in self.lists:
            if target != contents:
                target[:] = contents
                changed = True
        return changed

    def _restore_cwd(self) -> None:
        try:
            if os.getcwd() == self.cwd:
                return
        except OSError:  # the folder the script went to was removed
            pass
        try:
            os.chdir(self.cwd)
        except OSError as exc:
            _LOG.warning("cannot go back to the folder %s after the run: %s", self.cwd, exc)

    def _restore_signals(self) -> None:
        if threading.current_thread() is not threading.main_thread():
            return  # a script outside the main thread cannot have changed them
        for number, handler in self.signals.items():
            if signal.getsignal(number) is not handler and handler is not None:
                signal.signal(number, handler)


def _raw_environ() -> dict:
    """``os.environ``'s items as it keeps them (encoded): a copy compares in one
    dict comparison in C, where the mapping itself decodes item by item."""
    return dict(os.environ._data)  # type: ignore[attr-defined]


def _restore_environ(raw: dict) -> None:
    """Give ``os.environ`` the items of ``raw`` (see :func:`_raw_environ`) back,
    one key at a time (it is never empty on the way)."""
    if os.environ._data == raw:  # type: ignore[attr-defined]
        return
    saved = {os.environ.decodekey(k): os.environ.decodevalue(v) for k, v in raw.items()}
    for key in [key for key in os.environ if key not in saved]:
        del os.environ[key]
    for key, value in saved.items():
        if os.environ.get(key) != value:
            os.environ[key] = value


class _Streams:
    """The standard streams' descriptors: their identity and a duplicate of
    each, to put back one the script closed or pointed elsewhere; and the fd of
    each ``sys`` stream, to open one the script closed again.

    Args:
        previous: an earlier picture, whose duplicates are taken over for the
            descriptors still open on the same file (see :meth:`close`).
    """

    def __init__(self, previous: _Streams | None = None) -> None:
        self.saved: dict[int, tuple[tuple[int, int], int]] = {}
        for fd in (0, 1, 2):
            identity = _identity(fd)
            if identity is None:
                continue
            if previous is not None and previous.saved.get(fd, (None,))[0] == identity:
                self.saved[fd] = previous.saved[fd]
            else:
                self.saved[fd] = (identity, os.dup(fd))
        self.numbers = {name: _fileno(getattr(sys, name)) for name in _STREAMS}

    def restore(self) -> None:
        for fd, (identity, copy) in self.saved.items():
            if _identity(fd) != identity:
                os.dup2(copy, fd)
        for name in _STREAMS:
            stream, number = getattr(sys, name), self.numbers[name]
            if getattr(stream, "closed", False) and number is not None:
                setattr(sys, name, _reopened(stream, number))

    def close(self, keep: _Streams | None = None) -> None:
        """Close the duplicates, but those ``keep`` took over."""
        kept = {copy for _, copy in keep.saved.values()} if keep is not None else set()
        for _, copy in self.saved.values():
            if copy not in kept:
                os.close(copy)
        self.saved = {}


def _identity(fd: int) -> tuple[int, int] | None:
    """``(device, inode)`` of what ``fd`` is open on, None if it is not open."""
    try:
        info = os.fstat(fd)
    except OSError:
        return None
    return info.st_dev, info.st_ino


def _fileno(stream: object) -> int | None:
    try:
        return int(stream.fileno())  # type: ignore[attr-defined]
    except (AttributeError, OSError, ValueError):  # io.UnsupportedOperation is both
        return None


def _reopened(stream: Any, fd: int) -> TextIO:
    """A text stream on ``fd`` like the closed ``stream`` (which must not own the
    descriptor: Python's own standard streams do not)."""
    return open(fd, "w" if fd else "r", buffering=1 if stream.line_buffering else -1,  # noqa: SIM115
                encoding=stream.encoding, errors=stream.errors, closefd=False)


class _Modules:
    """``builtins`` and livemod's library: their ``sys.modules`` entries, their
    namespaces and the attributes of the classes they define.

    A namespace is compared with its picture in one dict comparison, which is
    done in C and meets the same objects (equal by identity) when nothing
    changed; only a namespace that differs is gone through name by name. Names
    a script added are removed, except modules: a submodule imported after the
    picture is bound in its package, and must stay.
    """

    def __init__(self) -> None:
        names, classes = library()
        self.modules = {name: sys.modules[name] for name in names}
        self.modules["builtins"] = builtins
        self.namespaces = [(vars(m), dict(vars(m))) for m in self.modules.values()]
        self.classes = [(cls, dict(vars(cls))) for cls in classes]

    def restore(self) -> None:
        for name, module in self.modules.items():
            if sys.modules.get(name) is not module:
                sys.modules[name] = module
        for namespace, saved in self.namespaces:
            if not _same(namespace, saved):
                _put_back_names(namespace, saved)
        for cls, saved in self.classes:
            if not _same(vars(cls), saved):
                _put_back_attributes(cls, saved)


def _same(now: Any, saved: dict) -> bool:
    """True when the namespace ``now`` holds the very objects of ``saved``."""
    try:
        return bool(now == saved)  # objects equal by identity first, in C
    except Exception:  # a replaced value whose __eq__ fails (a numpy array): it differs
        return False


def _put_back_names(namespace: dict, saved: dict) -> None:
    for name, value in saved.items():
        if namespace.get(name, _MISSING) is not value:
            namespace[name] = value
    for name in [n for n in namespace if n not in saved]:
        if not isinstance(namespace[name], ModuleType):
            del namespace[name]


def _put_back_attributes(cls: type, saved: dict) -> None:
    now = vars(cls)
    for name, value in saved.items():
        if now.get(name, _MISSING) is not value:
            setattr(cls, name, value)
    for name in [n for n in now if n not in saved]:
        delattr(cls, name)


_LIBRARY: tuple[tuple[str, ...], tuple[type, ...]] | None = None


def library() -> tuple[tuple[str, ...], tuple[type, ...]]:
    """``(module names, classes)`` of livemod's library: ``livemod`` and every
    module of ``livemod.dlfl`` (imported now, once per process), and the classes
    they define (not those they import)."""
    global _LIBRARY
    if _LIBRARY is None:
        import livemod.dlfl

        names = ["livemod", "livemod.dlfl"]
        for info in pkgutil.walk_packages(livemod.dlfl.__path__, "livemod.dlfl."):
            importlib.import_module(info.name)
            names.append(info.name)
        classes = [value for name in names for value in vars(sys.modules[name]).values()
                   if isinstance(value, type) and value.__module__ == name]
        _LIBRARY = tuple(names), tuple(classes)
    return _LIBRARY
