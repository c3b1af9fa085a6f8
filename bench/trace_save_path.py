"""Trace the path of a save: every livemod file and function called, on every
thread, from the write of the script to the first frame that shows its result
(plain python; prints the files crossed, the calls across layers, the thread hops).

    python bench/trace_save_path.py [--tree DIR] [--backend glfw|headless]
                                    [--levels N] [--functions] [--check-doc]

It opens the window as ``livemod view script.py`` does (``create_viewer`` and the
``run_frames`` main loop; a real glfw window, run under ``xvfb-run`` when there is
no display), waits until the first run is on screen and the window is idle, then
records with ``threading.setprofile`` and ``sys.setprofile`` while it saves a change
to the script, and stops after the first frame that put the new mesh on the screen
whole (uploaded, not drawing in slices, presented). The script is a cube built with
``from_polygons`` and subdivided ``--levels`` times (2 by default) by the
``subdivide`` command (a modeling command: each is a step of the run, and with
two the window draws its timeline); the save changes its size. ``--levels 7`` makes
a mesh of 393k corners, which the window prepares on a worker thread and uploads a
slice a frame; ``--levels 8`` one of 1.6M, which it also measures off the thread.
``--check-doc`` checks that docs/architecture.md's "The path of a save" and
"Threads" name what the trace crossed.

``--tree DIR`` traces the livemod package of another tree (``git archive REV | tar
-x -C DIR``): it is put first on ``sys.path``. Trees before the window's
composition have no ``viewer.frames``/``viewer.display``; :class:`WindowShim` reads
the same facts from their attributes.

What it prints:

* the files of the path, in the order of their first call, with the thread of that
  call and the count of calls: every other thread's calls, and the main thread's
  from the frame that took the result on (the frames before only waited for it,
  polling the session); a ``*`` marks the files that a frame drawn again with no new
  result (``B``) and the idle frames after it call too, so the others are the
  save's own. Then the files only the waiting frames called, and the count of all;
* the window's calls of its session's methods and properties, by call site
  (``file:line``), each said to be a member of the typed protocols of
  ``livemod/viewer/session.py`` or not;
* the calls from one layer into another (viewer -> runner, dlfl -> runner, ...),
  with the callee's class; a call up a layer is a callback;
* the hops between threads: a queue put and get, a condition notified and waited
  for, an event waited for, an event flag set by one thread and cleared by the one
  that takes what it flagged (``NewestJob.take``), a thread started; each named by
  the nearest livemod function on either side. A hand-over that uses none of these
  (a value left in an attribute that another thread reads) is not seen.

The tracing slows every call in the process: timings are not measured here.
"""

from __future__ import annotations

import argparse
import io
import os
import queue
import re
import shutil
import sys
import tempfile
import threading
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from types import FrameType, ModuleType
from typing import Any

ROOT = Path(__file__).resolve().parents[1]

SCRIPT = """\
from livemod.dlfl import current_scene, from_polygons
P = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
     (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
F = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (7, 6, 5, 4)]
current_scene().add(from_polygons([(x * {scale}, y, z) for x, y, z in P], F))
for _ in range({levels}):
    subdivide("catmull-clark")
"""
LAYERS = ("viewer", "runner", "dlfl")  # from the top; a call up a layer is a callback


# -- the tree traced ---------------------------------------------------------------------


def use_tree(tree: Path) -> Path:
    """Import livemod from ``tree`` (first on ``sys.path``); its package folder."""
    sys.path.insert(0, str(tree))
    import livemod

    package = Path(livemod.__file__).resolve().parent
    if package.parent != tree.resolve():
        raise SystemExit(f"livemod came from {package}, not from {tree}")
    return package


def run_under_xvfb() -> None:
    """Without a display, run this script again under ``xvfb-run`` (a real glfw
    window on a virtual X server); returns only when there is a display."""
    if os.environ.get("DISPLAY"):
        return
    if os.environ.get("LIVEMOD_TRACE_XVFB") or not shutil.which("xvfb-run"):
        raise SystemExit("no display, and no xvfb-run to make one: install xvfb, or use "
                         "--backend headless")
    os.environ["LIVEMOD_TRACE_XVFB"] = "1"
    os.execvp("xvfb-run", ["xvfb-run", "-a", "-s", "-screen 0 1024x768x24 -nolisten tcp",
                           sys.executable, *sys.argv])


# -- the recording -------------------------------------------------------------------------


@dataclass(frozen=True)
class Call:
    """One call of a livemod function, in the order the calls happened."""

    thread: str
    file: str          # relative to the livemod package: "runner/watch.py"
    function: str      # its qualified name
    caller: str        # the calling frame's file (relative) when it is livemod's, else ""
    line: int          # the calling frame's line
    frame: int         # the main loop's frame at the time (see Tracer.frame)
    self_type: str     # the class of ``self`` of a call across layers, else ""
    on_session: bool   # ``self`` is the window's session


@dataclass(frozen=True)
class Hop:
    """Work handed from one thread to another."""

    via: str           # "queue", "event", "event flag", "condition", "thread start",
                       # "SimpleQueue"
    source: str        # thread
    source_at: str     # the nearest livemod function on the handing side (see _where)
    target: str
    target_at: str     # the same on the taking side


def _codes(*functions: Callable[..., Any]) -> set[Any]:
    return {f.__code__ for f in functions}


QUEUE_PUT = _codes(queue.Queue.put)
QUEUE_GET = _codes(queue.Queue.get)
NOTIFY = _codes(threading.Condition.notify)
WAIT = _codes(threading.Condition.wait)
THREAD_START = _codes(threading.Thread.start)
EVENT = _codes(threading.Event.set, threading.Event.wait)
EVENT_SET = _codes(threading.Event.set)
EVENT_CLEAR = _codes(threading.Event.clear)
STDLIB_QUEUE = queue.__file__
PLUMBING = {queue.__file__, threading.__file__}


@dataclass
class Tracer:
    """The profile function of every thread; records while :attr:`recording`.

    Attributes:
        package: the livemod package folder traced.
        calls: livemod calls in order.
        hops: hand-overs between threads, in order (repeats kept).
        frame: the main loop's frame number (the caller counts it).
        session: the window's session (its methods' calls are marked).
    """

    package: Path
    recording: bool = False
    session: object = None
    calls: list[Call] = field(default_factory=list)
    hops: list[Hop] = field(default_factory=list)
    frame: int = 0
    _files: dict[str, str] = field(default_factory=dict)
    _threads: dict[int, str] = field(default_factory=dict)
    _handed: dict[tuple[str, int], tuple[str, str]] = field(default_factory=dict)
    _started: dict[int, tuple[str, str]] = field(default_factory=dict)

    def install(self) -> None:
        """Profile the calling thread and every thread started from now on."""
        threading.setprofile(self.profile)
        sys.setprofile(self.profile)

    def remove(self) -> None:
        threading.setprofile(None)  # type: ignore[arg-type]  # (typeshed wants a function)
        sys.setprofile(None)

    def relative(self, filename: str) -> str:
        """``filename`` relative to the package ("" when it is not livemod's)."""
        rel = self._files.get(filename)
        if rel is None:
            path = Path(filename)
            rel = path.relative_to(self.package).as_posix() \
                if path.is_relative_to(self.package) else ""
            self._files[filename] = rel
        return rel

    def thread(self, frame: FrameType | None = None) -> str:
        """The calling thread's name (a thread started while recording: the hop from
        the thread that started it, to ``frame``, its first call seen)."""
        ident = threading.get_ident()
        name = self._threads.get(ident)
        if name is None:
            current = threading.current_thread()
            # watchdog's threads keep the default names: say their class
            name = current.name if not current.name.startswith("Thread-") \
                else type(current).__name__
            self._threads[ident] = name
            started = self._started.pop(id(current), None)
            if started is not None:
                self.hops.append(Hop("thread start", *started, name, self._where(frame)))
        return name

    def profile(self, frame: FrameType, event: str, arg: Any) -> None:
        if not self.recording:
            return
        if event == "call":
            self._call(frame)
        elif event == "return":
            self._return(frame, arg)
        elif event in ("c_call", "c_return"):
            self._simple_queue(frame, event, arg)

    def _call(self, frame: FrameType) -> None:
        code = frame.f_code
        rel = self.relative(code.co_filename)
        if rel:
            self._livemod_call(frame, rel)
        elif code in QUEUE_PUT:  # (matched to its get by the item: puts may pile up)
            self._handed[("queue", id(frame.f_locals["item"]))] = self._here(frame)
        elif code in NOTIFY and frame.f_back is not None \
                and frame.f_back.f_code.co_filename != STDLIB_QUEUE:
            self._handed[("condition", id(frame.f_locals["self"]))] = self._here(frame)
        elif code in THREAD_START:
            self._started[id(frame.f_locals["self"])] = self._here(frame)
        elif code in EVENT_SET:
            self._handed[("event flag", id(frame.f_locals["self"]))] = self._here(frame)
        elif code in EVENT_CLEAR and frame.f_locals["self"].is_set():
            # a flag set by one thread and cleared by another that took what it flagged
            # (a slot polled each frame, as NewestJob.take)
            self._hop("event flag", id(frame.f_locals["self"]), frame)

    def _livemod_call(self, frame: FrameType, rel: str) -> None:
        back = frame.f_back
        caller = self.relative(back.f_code.co_filename) if back is not None else ""
        line = back.f_lineno if back is not None else 0
        owner = None
        if caller and caller.split("/")[0] != rel.split("/")[0]:
            owner = frame.f_locals.get("self")
        self_type = "" if owner is None else type(owner).__qualname__
        self.calls.append(Call(self.thread(frame), rel, frame.f_code.co_qualname, caller, line,
                               self.frame, self_type, owner is not None and owner is self.session))

    def _return(self, frame: FrameType, value: Any) -> None:
        code = frame.f_code
        if code in QUEUE_GET and value is not None:
            self._hop("queue", id(value), frame)
        elif code in WAIT and value is True and frame.f_back is not None \
                and frame.f_back.f_code.co_filename != STDLIB_QUEUE:
            via = "event" if frame.f_back.f_code in EVENT else "condition"
            self._hop(via, id(frame.f_locals["self"]), frame, key="condition")

    def _simple_queue(self, frame: FrameType, event: str, function: Any) -> None:
        owner = getattr(function, "__self__", None)
        if not isinstance(owner, queue.SimpleQueue):
            return
        name = function.__name__
        if event == "c_call" and name.startswith("put"):
            self._handed[("SimpleQueue", id(owner))] = self._here(frame)
        elif event == "c_return" and name.startswith("get"):
            self._hop("SimpleQueue", id(owner), frame)

    def _hop(self, via: str, owner: int, frame: FrameType, key: str = "") -> None:
        handed = self._handed.pop((key or via, owner), None)
        thread = self.thread(frame)
        if handed is not None and handed[0] != thread:
            self.hops.append(Hop(via, handed[0], handed[1], thread, self._where(frame)))

    def _here(self, frame: FrameType) -> tuple[str, str]:
        return self.thread(frame), self._where(frame)

    def _where(self, frame: FrameType | None) -> str:
        """The nearest livemod function up the stack from ``frame`` ("file:function"),
        else the nearest one outside the standard library's threading and queue."""
        outside = ""
        while frame is not None:
            code = frame.f_code
            rel = self.relative(code.co_filename)
            if rel:
                return f"{rel}:{code.co_qualname}"
            if not outside and code.co_filename not in PLUMBING:
                outside = "/".join(Path(code.co_filename).parts[-2:]) + ":" + code.co_qualname
            frame = frame.f_back
        return outside


# -- the window ------------------------------------------------------------------------------


class WindowShim:
    """The facts the trace reads of a window, in the trees before and after the
    window's composition (``viewer.frames``, ``viewer.display`` and
    ``renderer.unfinished`` are the composition's; the older window kept
    ``presented`` itself and uploaded in the frame that took the result)."""

    def __init__(self, viewer: Any) -> None:
        self.viewer = viewer

    def result_id(self) -> int:
        result = self.viewer.result
        return 0 if result is None else int(result.run_id)

    def shows_result(self) -> bool:
        """The last frame put the result's mesh on the screen, whole."""
        viewer = self.viewer
        display = getattr(viewer, "display", None)
        presented = getattr(viewer, "frames", viewer).presented
        return (viewer.result is not None and not viewer.waiting
                and viewer.renderer.arrays is viewer.result.arrays
                and not getattr(display, "pending", False)
                and not getattr(viewer.renderer, "unfinished", False) and presented)


@dataclass
class Trace:
    """What one traced save gave."""

    package: Path
    backend: str
    calls: list[Call]
    hops: list[Hop]
    take_frame: int       # the frame that took the new result from the session's queue
    last_frame: int       # the first frame that showed it
    redraw: set[str]      # the main thread's files in a frame drawn again and idle ones
    periodic: set[str]    # the other threads that ran livemod code then (no save)


def _frames_until(window_module: ModuleType, viewer: Any, tracer: Tracer,
                  done: Callable[[], bool], timeout: float) -> None:
    """Run the main loop until ``done`` (asked between frames, untraced)."""
    deadline = time.monotonic() + timeout
    finished = []

    def until(_viewer: Any) -> bool:
        sys.setprofile(None)  # (the checks are the trace's, not the window's)
        try:
            time.sleep(0.005)  # the run's threads get a core
            tracer.frame += 1
            if done():
                finished.append(True)
            return bool(finished) or time.monotonic() > deadline
        finally:
            sys.setprofile(tracer.profile)

    window_module.run_frames(viewer, until=until)
    if not finished:
        raise SystemExit("timed out waiting for the window")


def _rest(window_module: ModuleType, viewer: Any, tracer: Tracer, seconds: float) -> None:
    """Run the main loop for ``seconds``."""
    end = time.monotonic() + seconds
    _frames_until(window_module, viewer, tracer, lambda: time.monotonic() > end, seconds + 5)


def _redraw_files(window_module: ModuleType, viewer: Any,
                  tracer: Tracer) -> tuple[set[str], set[str]]:
    """The main thread's files in a frame drawn again with no new result (``B``
    changes the background) and the idle frames of the next 1.2 s (the watcher
    rechecks its folders each second), and the other threads that ran livemod code
    meanwhile; the background is put back after."""
    viewer.handle_key("B")
    tracer.recording = True
    _rest(window_module, viewer, tracer, 1.2)
    tracer.recording = False
    files = {c.file for c in tracer.calls if c.thread == "MainThread"}
    threads = {c.thread for c in tracer.calls} - {"MainThread"}
    viewer.handle_key("B")
    _rest(window_module, viewer, tracer, 0.5)
    tracer.calls.clear()
    tracer.hops.clear()
    return files, threads


def trace_save(package: Path, backend: str, levels: int, folder: Path) -> Trace:
    """Open the window on a script, save a change and trace it to the screen."""
    from livemod.viewer import window as window_module

    script = folder / "model.py"
    script.write_text(SCRIPT.format(scale=1.0, levels=levels))
    tracer = Tracer(package)
    tracer.install()
    viewer = window_module.create_viewer(window_module.ViewOptions(
        str(script), backend=backend, size=(320, 240), samples=0, vsync=False,
        echo=io.StringIO()))
    tracer.session = viewer.session
    shim = WindowShim(viewer)
    try:
        _frames_until(window_module, viewer, tracer,
                      lambda: shim.result_id() >= 1 and shim.shows_result(), 120.0)
        viewer.whole.wait(60.0)  # the first mesh's genus and volume, off the thread if big
        _rest(window_module, viewer, tracer, 0.5)
        redraw, periodic = _redraw_files(window_module, viewer, tracer)
        first, took = shim.result_id(), []

        def shown() -> bool:
            if not took and shim.result_id() > first:
                took.append(tracer.frame - 1)  # the frame just drawn took it
            return bool(took) and shim.shows_result()

        tracer.recording = True
        script.write_text(SCRIPT.format(scale=1.5, levels=levels))
        _frames_until(window_module, viewer, tracer, shown, 120.0)
        tracer.recording = False
    finally:
        tracer.remove()
        window_module.close_viewer(viewer)
    return Trace(package, viewer.wnd.name, tracer.calls, tracer.hops, took[0],
                 tracer.frame - 1, redraw, periodic)


# -- the report ------------------------------------------------------------------------------


def layer(file: str) -> str:
    """``"runner/watch.py"`` -> ``"runner"``; a top-level module -> ``"livemod"``."""
    head = file.split("/")[0]
    return head if head in LAYERS else "livemod"


def on_path(trace: Trace, call: Call) -> bool:
    """The call is the save's work: another thread's, or the main thread's from the
    frame that took the result (the frames before only waited for it)."""
    return call.thread != "MainThread" or call.frame >= trace.take_frame


@dataclass
class FileRow:
    file: str
    thread: str
    function: str
    calls: int = 0
    threads: set[str] = field(default_factory=set)


def files_in_order(calls: list[Call]) -> list[FileRow]:
    """The files of ``calls`` in the order of their first call."""
    rows: dict[str, FileRow] = {}
    for call in calls:
        row = rows.setdefault(call.file, FileRow(call.file, call.thread, call.function))
        row.calls += 1
        row.threads.add(call.thread)
    return list(rows.values())


def split(files: list[str]) -> str:
    """``"61 (viewer 28, runner 16, dlfl 17)"``."""
    counts = Counter(layer(file) for file in files)
    parts = ", ".join(f"{name} {counts[name]}" for name in (*LAYERS, "livemod") if counts[name])
    return f"{len(files)} ({parts})"


def print_files(title: str, rows: list[FileRow], redraw: set[str]) -> None:
    """``rows``, a ``*`` on the files a frame drawn again (no new result) calls too."""
    print(f"\n{title}: {split([row.file for row in rows])} files")
    for n, row in enumerate(rows, 1):
        others = sorted(row.threads - {row.thread})
        also = f"  (also {', '.join(others)})" if others else ""
        mark = "*" if row.file in redraw else " "
        print(f"  {n:2d}. {mark} {row.file:28s} {row.thread:16s} {row.calls:6d} calls  "
              f"first {row.function}{also}")


def print_crossings(calls: list[Call]) -> None:
    """Calls from one layer's code into another's, by edge."""
    edges: Counter[tuple[str, str, str, str]] = Counter()
    for call in calls:
        if call.caller and layer(call.caller) != layer(call.file):
            edges[(call.caller, call.file, call.function, call.self_type)] += 1
    print("\ncalls across layers (caller file -> callee file:function [self's class]):")
    for pair in sorted({(layer(c), layer(f)) for c, f, _, _ in edges}):
        inside = {e: n for e, n in edges.items() if (layer(e[0]), layer(e[1])) == pair}
        up = set(pair) <= set(LAYERS) and LAYERS.index(pair[1]) < LAYERS.index(pair[0])
        print(f"  {pair[0]} -> {pair[1]}: {sum(inside.values())} calls, {len(inside)} "
              f"distinct{'  (up a layer: a callback)' if up else ''}")
        for (caller, file, function, self_type), n in sorted(inside.items()):
            owner = f" [{self_type}]" if self_type else ""
            print(f"      {n:5d}  {caller} -> {file}:{function}{owner}")


def print_session_calls(calls: list[Call], protocol: set[str]) -> None:
    """The window's calls of its session's methods and properties, and whether each
    is a member of the typed protocol."""
    sites = Counter((f"{c.caller}:{c.line}", c.function) for c in calls
                    if c.on_session and layer(c.caller) == "viewer")
    where = "livemod/viewer/session.py's protocols" if protocol else "no protocol in this tree"
    print(f"\nthe window's calls into its session: {sum(sites.values())} calls, "
          f"{len(sites)} call sites ({where}):")
    for (caller, function), n in sorted(sites.items()):
        member = function.rsplit(".", 1)[-1] in protocol
        print(f"      {n:5d}  {caller} -> {function}  "
              f"{'typed (protocol member)' if member else 'NOT through a protocol'}")


def print_hops(hops: list[Hop]) -> None:
    """Hops between threads, each once, in the order of the first."""
    seen: Counter[Hop] = Counter(hops)
    print(f"\nhops between threads: {len(seen)} distinct ({len(hops)} in all)")
    for hop in dict.fromkeys(hops):
        print(f"  {hop.source} -> {hop.target} ({hop.via}, x{seen[hop]}): "
              f"{hop.source_at or '-'}  =>  {hop.target_at or '-'}")


def protocol_members() -> set[str]:
    """Names of the typed protocols the window drives the session through (empty in
    trees that have none)."""
    try:
        from livemod.viewer import session
    except ImportError:
        return set()
    names: set[str] = set()
    for value in vars(session).values():
        if isinstance(value, type) and getattr(value, "_is_protocol", False):
            names |= {n for n in vars(value) if not n.startswith("_")}
            names |= set(getattr(value, "__annotations__", {}))
    return names


def report(trace: Trace, functions: bool) -> None:
    path = [c for c in trace.calls if on_path(trace, c)]
    path_rows = files_in_order(path)
    own = [row.file for row in path_rows if row.file not in trace.redraw]
    waiting = [r for r in files_in_order([c for c in trace.calls if not on_path(trace, c)])
               if r.file not in {row.file for row in path_rows}]
    print(f"livemod at {trace.package} ({trace.backend} window); frames "
          f"{trace.take_frame}..{trace.last_frame} took the new result and showed it")
    print_files("the path of the save (other threads; the main thread from the take)",
                path_rows, trace.redraw)
    print(f"\n  *: a frame drawn again with no new result calls it too; the save's own: "
          f"{split(own)}")
    print_files("files only the frames waiting for the result called", waiting, trace.redraw)
    print(f"\nall files from the write to the frame: "
          f"{split([r.file for r in files_in_order(trace.calls)])}")
    threads = [t + (" (periodic: also with no save)" if t in trace.periodic else "")
               for t in dict.fromkeys(c.thread for c in path)]
    print(f"\nthreads of the path, in the order they ran livemod code: {', '.join(threads)}")
    print_session_calls(path, protocol_members())
    print_crossings(path)
    print_hops(trace.hops)
    if functions:
        print("\nfunctions, in the order of their first call (thread, calls):")
        counted = Counter((c.thread, c.file, c.function) for c in trace.calls)
        for thread, file, function in counted:
            print(f"  {thread:16s} {file}:{function}  x{counted[(thread, file, function)]}")


def section(doc: str, title: str) -> str:
    """The text of ``doc``'s section ``## title`` (to the next ``## ``)."""
    return doc.split(f"\n## {title}\n", 1)[1].split("\n## ", 1)[0]


def check_doc(trace: Trace, doc: Path) -> bool:
    """Whether ``doc`` (docs/architecture.md) is true to the trace: its "The path of
    a save" names every runner and viewer file the save crossed and no file it did
    not cross (the library's files it names must be crossed too; which of them a
    save crosses depends on the script), and its "Threads" names every thread of
    the path (a run's number as ``N``). Prints what differs."""
    text = doc.read_text(encoding="utf-8")
    named = set(re.findall(r"\b((?:runner|viewer|dlfl)/[\w/]+\.py)\b",
                           section(text, "The path of a save")))
    crossed = {c.file for c in trace.calls if on_path(trace, c)}
    threads = {re.sub(r"-\d+$", "-N", c.thread) for c in trace.calls if on_path(trace, c)}
    problems = {
        "crossed, not named in \"The path of a save\"":
            sorted(f for f in crossed - named if layer(f) != "dlfl"),
        "named in \"The path of a save\", not crossed": sorted(named - crossed),
        "threads not named in \"Threads\"":
            sorted(t for t in threads if f"`{t}`" not in section(text, "Threads")),
    }
    print(f"\n{doc}:")
    for what, names in problems.items():
        print(f"  {what}: {', '.join(names) if names else 'none'}")
    return not any(problems.values())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tree", type=Path, default=ROOT,
                        help="the tree whose livemod package is traced (default: this one)")
    parser.add_argument("--backend", choices=("glfw", "headless"), default="glfw")
    parser.add_argument("--levels", type=int, default=2,
                        help="Catmull-Clark steps of the cube, each a step of the run "
                             "(7: a mesh prepared off the main thread)")
    parser.add_argument("--functions", action="store_true", help="list every function too")
    parser.add_argument("--check-doc", action="store_true",
                        help="check the tree's docs/architecture.md against the trace "
                             "(exit status 1 when it differs)")
    args = parser.parse_args()
    if args.backend == "glfw":
        run_under_xvfb()
    package = use_tree(args.tree)
    with tempfile.TemporaryDirectory() as folder:
        trace = trace_save(package, args.backend, args.levels, Path(folder))
    report(trace, args.functions)
    if args.check_doc and not check_doc(trace, args.tree / "docs" / "architecture.md"):
        sys.exit(1)


if __name__ == "__main__":
    main()
