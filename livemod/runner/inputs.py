"""The inputs of a live session's next run, and the files whose saves ask for one.

:class:`RunInputs` holds what a run of a :class:`~livemod.runner.session.LiveSession`
starts from: the script's path and text, the ``--mesh`` base scene, the script
parameters with the declarations they must fit, and the selection. It also
keeps a digest of every watched file, so that a save re-runs the script only
when some content changed (an editor's save that writes the same bytes, or
one that truncates the script before writing it, runs nothing).
"""

from __future__ import annotations

import hashlib
import logging
import threading
from collections.abc import Callable

from livemod.dlfl.errors import DLFLError
from livemod.dlfl.params import ParamSpec
from livemod.dlfl.run_context import RunContext
from livemod.dlfl.scene import Scene, Selection

from .declarations import check_values, fitting_values, literal_declarations
from .instrument import decode_script
from .watch import FileWatcher

_LOG = logging.getLogger("livemod.session")


class RunInputs:
    """What the next run of a live session gets, and when a save asks for a run.

    Every attribute is guarded by the session's lock: read or write them only
    while holding it. The methods take the lock themselves, except those that
    say the caller holds it.

    Args:
        lock: the session's lock.
        script: absolute path of the user script.
        mesh_file: absolute path of the ``--mesh`` file every run starts from,
            or None.
        base: a scene every run starts from (copied per run), instead of
            ``mesh_file``.
        parameters: initial script parameters, by name.
        output: absolute path the session saves each result to (never watched:
            it changes because a run ended), or None.
        watcher: the watcher of the script and the files its runs read.

    Attributes:
        script: absolute path of the open script.
        source: its text as last run (None until a run read it): what a replay
            or a parameter change runs.
        parameters: the values the next run gets, by name.
        declarations: ``name -> ParamSpec`` of the script as last run.
        selection: what ``faces(True)`` and friends return, or None.
        empty_script: the script's path while a save left it empty, else None.
    """

    def __init__(self, lock: threading.RLock, script: str, *, mesh_file: str | None,
                 base: Scene | None, parameters: dict | None, output: str | None,
                 watcher: FileWatcher) -> None:
        self._lock = lock
        self.script = script
        self.source: str | None = None
        self.parameters = dict(parameters or {})
        self.declarations: dict[str, ParamSpec] = {}  # of the newest script text
        self.selection: Selection | None = None
        self.empty_script: str | None = None
        self._seen: dict[str, bytes] = {}  # path -> digest of the content runs read
        self._mesh_file = mesh_file
        self._base: Scene | None = base.copy() if base is not None else None
        self._base_version = 0  # counts changes of the --mesh file (see base_scene)
        self._output = output
        self._watcher = watcher

    # -- the script and its files ---------------------------------------------------

    def start_watching(self) -> None:
        """Start the watcher on the script and the ``--mesh`` file."""
        self._watcher.start()
        self._watcher.set_files(self._own_files())

    def stop_watching(self) -> None:
        """Stop the watcher (the session winds down)."""
        self._watcher.close()

    def switch(self, script: str) -> None:
        """Open ``script`` instead: the old script's text, declarations, parameter
        values and digests are dropped (caller holds the lock)."""
        self.script = script
        self._seen = {}
        # a replay asked before the first run reads the new script from disk
        self.source, self.declarations, self.parameters = None, {}, {}
        self.empty_script = None
        self._watcher.set_files(self._own_files())

    def text(self, script: str, source: str | None) -> str:
        """The text a run of ``script`` runs: ``source``, or else the script read
        now (its digest remembered). It becomes :attr:`source`.

        Raises:
            OSError: the script cannot be read.
            SyntaxError: its bytes are not text.
        """
        if source is None:
            source, digest = _read_script(script)
            with self._lock:
                self._seen[script] = digest
        with self._lock:
            self.source = source
        return source

    def base_scene(self, load: Callable[[str], Scene]) -> Scene | None:
        """The base scene: the one given, or the ``--mesh`` file loaded with
        ``load`` (in the worker, never on the caller's thread) once, and again
        after the file changed; None for an empty scene. Raises what ``load``
        raises."""
        mesh_file = self._mesh_file
        with self._lock:
            base, version = self._base, self._base_version
            if mesh_file is None or base is not None:
                return base
            digest = _digest(mesh_file)  # first: a file that fails to load is watched too
            if digest is not None:
                self._seen[mesh_file] = digest
        base = load(mesh_file)
        with self._lock:
            # a change seen while loading may have come too late for this load: keep
            # nothing, so that the run the change asked for loads the file again
            if version == self._base_version:
                self._base = base
        return base

    @property
    def mesh_file(self) -> str | None:
        """Absolute path of the ``--mesh`` file, or None."""
        return self._mesh_file

    def watch_files(self, script: str, paths: tuple[str, ...]) -> None:
        """Watch the local modules and mesh files a run of ``script`` read,
        remembering their content now (the session's ``output`` is never
        watched: it changes because a run ended)."""
        paths = tuple(p for p in paths if p != self._output)
        with self._lock:
            if script != self.script:
                return
            for path in paths:
                digest = _digest(path)
                if path not in self._seen and digest is not None:
                    self._seen[path] = digest
            try:
                self._watcher.set_files(self._watcher.files | set(paths))
            except OSError as exc:  # e.g. inotify's watch limit: the run's result still counts
                _LOG.warning("cannot watch the folders of %s: %s; saves there will not "
                             "re-run the script", ", ".join(paths), exc)

    def files_changed(self) -> bool:
        """Watcher callback: whether a watched file's content changed (or the
        script appeared), so that the script must run again. A script left empty
        asks for nothing (see :attr:`empty_script`)."""
        with self._lock:
            files, script = sorted(self._watcher.files), self.script
        source = _read_bytes(script)  # read once: for its digest and for emptiness
        if source is None:
            return False  # the script vanished (or is being replaced): wait for it to return
        digests = {path: _digest(path) for path in files if path != script}
        digests[script] = _hash(source)
        emptied = _is_blank(source)
        with self._lock:
            if script == self.script:
                # an editor truncated it and has not written it yet, or the user
                # emptied it: keep the last result, and say why (empty_script)
                self.empty_script = script if emptied else None
        if emptied:
            return False
        with self._lock:
            changed = [p for p, d in digests.items() if p in self._seen and self._seen[p] != d]
            # no run has read the script yet (it did not exist): its first save runs it
            appeared = script not in self._seen
            self._seen.update({p: d for p, d in digests.items() if d is not None})
            if self._mesh_file in changed:
                self._base = None  # the next run reads the new --mesh
                self._base_version += 1
        return bool(changed or appeared)

    def _own_files(self) -> list[str]:
        """The files watched from the start: the script and the ``--mesh`` file."""
        mesh_file = self._mesh_file
        return [self.script] if mesh_file is None else [self.script, mesh_file]

    # -- parameters and their declarations ---------------------------------------------

    def update_parameters(self, values: dict) -> None:
        """Keep ``values`` for the next runs, once checked against the script's
        declarations when they are known.

        Raises:
            DLFLError: a name the script does not declare or a value that does
                not fit (nothing is changed).
        """
        with self._lock:
            if self.declarations:
                values = check_values(self.declarations, values)
            self.parameters.update(values)

    def forget_parameters(self, names: list[str] | None) -> None:
        """Forget the values of ``names`` (all when None): the defaults apply."""
        with self._lock:
            for name in list(self.parameters) if names is None else names:
                self.parameters.pop(name, None)

    def fit_parameters(self, script: str, source: str, parameters: dict) -> dict:
        """The values that still fit the declarations of ``source`` (caller holds the
        lock); the ones that no longer fit are forgotten for good."""
        try:
            specs = literal_declarations(source, script)
        except DLFLError:
            specs = None  # the run reports the syntax or declaration error
        if specs is None:
            return parameters
        kept = fitting_values(specs, parameters, self.declarations)
        for name in set(parameters) - set(kept):
            if self.parameters.get(name) == parameters[name]:
                del self.parameters[name]
        self.declarations = specs
        return kept

    def ran(self, script: str, declarations: dict[str, ParamSpec]) -> None:
        """A run of ``script`` ended well: its declarations, as the run computed them
        (a ``param()`` may compute its arguments), become the script's, unless
        another script is open now (caller holds the lock)."""
        if script == self.script:
            self.declarations = declarations

    def specs(self, context: RunContext) -> tuple[ParamSpec, ...]:
        """The declarations to show with a result: the script's, as known in full
        (a failed or paused run may not have reached every ``param()``)."""
        with self._lock:
            known = tuple(self.declarations.values())
        return known or tuple(context.declarations.values())


def _read_script(path: str) -> tuple[str, bytes]:
    """The script's text and the digest of its bytes (what a watched save is
    compared with). Raises OSError, or SyntaxError for bytes that are not text."""
    with open(path, "rb") as handle:
        data = handle.read()
    return decode_script(data, path), _hash(data)


def _hash(data: bytes) -> bytes:
    return hashlib.blake2b(data, digest_size=16).digest()


def _is_blank(data: bytes) -> bool:
    """True when a script's bytes are nothing but whitespace (and a UTF-8 BOM):
    an editor between truncating and writing, or a user who emptied it."""
    return not data.removeprefix(b"\xef\xbb\xbf").strip()


def _read_bytes(path: str) -> bytes | None:
    """The file's bytes, None when it cannot be read (e.g. mid-rename)."""
    try:
        with open(path, "rb") as handle:
            return handle.read()
    except OSError:
        return None


def _digest(path: str) -> bytes | None:
    """Hash of the file's bytes, None when it cannot be read (e.g. mid-rename)."""
    data = _read_bytes(path)
    return None if data is None else _hash(data)
