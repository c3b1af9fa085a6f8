"""Parameter sweeps: independent variants of one script in a pool of processes.

The pool hides behind :class:`VariantExecutor` (one method, ``map_unordered``),
so a Dask cluster (:mod:`livemod.runner.cluster`) replaces the local process
pool without touching the rest: variants and their results are small picklable
dataclasses.

Only the batch itself (the process that called :func:`run_batch`) puts outputs
in place, each as its result comes in and is recorded: a local worker writes its
mesh, under the output's name, into the batch's temporary folder beside the
output (``Variant.staging``), with the companions its format writes beside it
(the ``.mtl`` of a coloured OBJ or ``.dlfl``, the ``.bin`` of a ``.gltf``,
see :func:`~livemod.dlfl.io.companion_paths`), which name one another by their
final names; the batch renames the companions into place, then the file. A cluster worker sends the bytes of every file back. So
whatever stops the batch (Ctrl-C, SIGTERM, a lost cluster), the outputs on
disk, companions included, are exactly the variants the index lists.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import dataclasses
import itertools
import multiprocessing
import os
import signal
import threading
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import Any, Protocol, TextIO

import numpy as np

from livemod.commandline import describe
from livemod.dlfl.errors import DLFLError, InvalidArgumentError
from livemod.dlfl.params import ParamSpec
from livemod.dlfl.scene import Selection
from livemod.progress import ProgressBar

from .declarations import undeclared


@dataclass(frozen=True)
class Variant:
    """One run of a sweep: the script, its parameters and where its mesh goes.

    ``staging`` is where a worker writes the mesh for the batch to move to
    ``output``: a file of the output's own name in the batch's temporary folder
    beside it (see :func:`~livemod.dlfl.io.atomic.temporary_path`), with the
    format's companion files beside it; None writes ``output`` itself.
    """

    index: int
    script: str
    parameters: tuple[tuple[str, Any], ...]
    output: str | None = None
    mesh_path: str | None = None
    seed: int | None = 0
    selection: Selection | None = None
    all_objects: bool = False
    staging: str | None = None


@dataclass(frozen=True)
class VariantResult:
    """What a variant reports back: its counts, or its error; the mesh is in the
    file ``staged`` (to be moved to ``output``, the companion files beside it
    to the output's folder), in ``data`` (from a cluster: the bytes of the
    output, under its file name, and of each companion, under theirs), or was
    written to ``output`` already (both None)."""

    index: int
    parameters: tuple[tuple[str, Any], ...]
    status: str
    counts: tuple[int, int, int] | None
    error: str | None
    output: str | None
    elapsed: float
    genus: int | None = None
    staged: str | None = None
    data: dict[str, bytes] | None = None


def parse_param(text: str) -> tuple[str, list[Any]]:
    """``"name=start:stop:count"`` (inclusive, evenly spaced) or ``"name=value"``.

    Values are ints when start and stop are ints and the spacing is whole,
    floats otherwise.

    Raises:
        ValueError: the text does not have that form, or count < 1.
    """
    name, sep, spec = text.partition("=")
    if not sep or not name.isidentifier():
        raise ValueError(f"--param expects name=start:stop:count, got {text!r}")
    parts = spec.split(":")
    if len(parts) == 1:
        return name, [_number(parts[0], text)]
    if len(parts) != 3:
        raise ValueError(f"--param expects name=start:stop:count, got {text!r}")
    start, stop, count = _number(parts[0], text), _number(parts[1], text), parts[2]
    if not count.isdigit() or int(count) < 1:
        raise ValueError(f"--param count must be a positive integer, got {text!r}")
    return name, _spaced(start, stop, int(count))


def declared_sweep(text: str, specs: dict[str, ParamSpec]) -> tuple[str, list[Any]]:
    """A ``--param`` of ``livemod batch`` parsed and checked against the declarations.

    Forms: ``name=value``, ``name=start:stop:count`` (numbers; an int parameter
    gets whole values, repeats removed) and ``name=a,b,c`` (any kind, e.g. a
    choice or ``true,false``). Every value is converted and range-checked.

    Raises:
        ValueError: a malformed text.
        InvalidArgumentError: a name the script does not declare, or a value that
            does not fit.
    """
    name, sep, body = text.partition("=")
    if not sep or not name.isidentifier():
        raise ValueError(f"--param expects name=start:stop:count or name=a,b,..., got {text!r}")
    problem = undeclared(specs, {name: None})
    if problem is not None:
        raise InvalidArgumentError(problem)
    spec = specs[name]
    if spec.kind in ("int", "float") and body.count(":") == 2:
        _, values = parse_param(text)
        if spec.kind == "int":
            values = list(dict.fromkeys(int(round(v)) for v in values))
    else:
        values = body.split(",") if spec.kind != "str" or "," in body else [body]
    return name, [spec.check(value) for value in values]


def _number(text: str, whole: str) -> int | float:
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"--param value {text!r} is not a number in {whole!r}") from None


def _spaced(start: float, stop: float, count: int) -> list[Any]:
    values = np.linspace(start, stop, count)
    whole = isinstance(start, int) and isinstance(stop, int)
    if whole and np.allclose(values, np.round(values)):
        return [int(v) for v in np.round(values)]
    return [float(v) for v in values]


def sweep(ranges: Iterable[tuple[str, list[Any]]]) -> list[dict[str, Any]]:
    """Every combination of the ranges (the last one varying fastest).

    Raises:
        ValueError: a name given twice (the first range would be dropped).
    """
    ranges = list(ranges)
    names = [name for name, _ in ranges]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise ValueError(f"--param {', '.join(twice)} given more than once; give one range "
                         "or list per parameter (e.g. n=1,2,5)")
    return [dict(zip(names, combo, strict=True))
            for combo in itertools.product(*(values for _, values in ranges))]


def output_name(pattern: str, parameters: dict[str, Any], index: int) -> str:
    """``pattern`` formatted with the parameters and ``index`` (e.g. ``out/{r:.2f}.obj``).

    Raises:
        ValueError: the pattern names a field that is neither a parameter nor ``index``,
            a format spec does not fit its value, or a parameter is named ``index``.
    """
    if "index" in parameters:
        raise ValueError("a parameter named 'index' clashes with the output pattern's "
                         "{index}, the variant's number; rename the parameter")
    try:
        return pattern.format(index=index, **parameters)
    except (KeyError, IndexError) as exc:
        raise ValueError(f"output pattern {pattern!r} names an unknown field {exc}") from None
    except ValueError as exc:  # a format spec that does not fit the value, e.g. {name:.2f}
        raise ValueError(f"output pattern {pattern!r} cannot format {parameters}: {exc}") from None


def run_variant(variant: Variant) -> VariantResult:
    """Run one variant in this process and write its mesh (a top-level function,
    so process pools can pickle it). Never raises for the script's or a file's
    failure: the result says it."""
    from livemod.dlfl.analysis import genus
    from livemod.dlfl.io import scene_objects

    from .headless import run_outcome
    from .results import result_mesh

    started = time.perf_counter()
    try:
        outcome = run_outcome(variant.script, mesh_path=variant.mesh_path,
                              seed=variant.seed, parameters=dict(variant.parameters),
                              selection=variant.selection)
    except OSError as exc:
        return failed_result(variant, describe(exc), started)
    except DLFLError as exc:  # a --mesh that does not parse: this variant fails, the batch goes on
        return failed_result(variant, str(exc), started)
    if outcome.error is not None:
        return failed_result(variant, str(outcome.error), started)
    mesh = result_mesh(outcome.scene, variant.all_objects)
    if variant.output is not None:
        problem = _written(scene_objects(outcome.scene, variant.all_objects), variant)
        if problem is not None:
            return failed_result(variant, problem, started)
    counts = mesh.counts() if mesh is not None else (0, 0, 0)
    return VariantResult(variant.index, variant.parameters, "ok", counts, None,
                         variant.output, time.perf_counter() - started,
                         genus(mesh) if mesh is not None else None, variant.staging)


def _written(objects: Sequence[tuple[str, Any]], variant: Variant) -> str | None:
    """Write the variant's ``(name, mesh)`` objects to its ``staging`` file (in the
    format of its output's suffix), or to ``output`` without one; None, or what
    went wrong, said of ``output``. A bug in a writer is the variant's failure
    too: a worker must not die of it."""
    from .results import save_problem

    output = str(variant.output)
    try:
        if variant.staging is None or not objects:
            return save_problem(objects, output)
        return _staged(objects, variant.staging, output)
    except Exception as exc:
        return f"cannot write {output}: {type(exc).__name__}: {exc}"


def _staged(objects: Sequence[tuple[str, Any]], staging: str, output: str) -> str | None:
    """Write ``objects`` to ``staging`` in ``output``'s format (its folders made if
    missing); None, or the failure said of ``output`` (and a companion's of its
    final name)."""
    from livemod.dlfl.io import companion_paths

    from .results import save_result

    for companion in companion_paths(staging):  # of an earlier try of this variant
        with contextlib.suppress(OSError):
            os.unlink(companion)
    try:
        save_result(objects, staging, format=os.path.splitext(output)[1][1:].lower())
    except OSError as exc:
        return _said_of_output(describe(exc), staging, output)
    except DLFLError as exc:  # a writer's refusal
        return _said_of_output(f"cannot write {output}: {exc}", staging, output)
    return None


def _said_of_output(text: str, staging: str, output: str) -> str:
    """``text`` naming the output and its folder where it names ``staging`` and
    the staging folder."""
    folder = os.path.dirname(output) or os.curdir
    return text.replace(staging, output).replace(os.path.dirname(staging), folder)


def failed_result(variant: Variant, message: str, started: float) -> VariantResult:
    """``variant`` failed with ``message``, ``started`` (a ``perf_counter`` time) ago."""
    return VariantResult(variant.index, variant.parameters, "error", None, message,
                         variant.output, time.perf_counter() - started)


class VariantExecutor(Protocol):
    """Where variants run. A Dask or Ray client fits behind the same method."""

    def map_unordered(self, fn: Callable[[Variant], VariantResult],
                      variants: list[Variant]) -> Iterator[VariantResult]:
        """Results of ``fn`` over ``variants``, in the order they finish."""
        ...


class SerialExecutor:
    """Runs variants one after another in this process (``-j 1``)."""

    def map_unordered(self, fn: Callable[[Variant], VariantResult],
                      variants: list[Variant]) -> Iterator[VariantResult]:
        """``fn`` of each variant, lazily and in order (the pool's contract allows
        any order)."""
        return (fn(v) for v in variants)


class FuturesVariantExecutor:
    """Any ``concurrent.futures.Executor``: a local pool, or a cluster's, e.g. Dask's
    ``Client(...).get_executor()``. The executor is not shut down here."""

    def __init__(self, executor: concurrent.futures.Executor) -> None:
        self.executor = executor

    def map_unordered(self, fn: Callable[[Variant], VariantResult],
                      variants: list[Variant]) -> Iterator[VariantResult]:
        """As :meth:`VariantExecutor.map_unordered`; a variant whose future failed
        (its worker died, or the cluster lost it) comes back as a failed result."""
        started = time.perf_counter()
        for variant, outcome in _finished(self.executor, fn, variants):
            yield outcome if isinstance(outcome, VariantResult) else failed_result(
                variant, _lost(outcome), started)


def _finished(executor: concurrent.futures.Executor, fn: Callable[[Variant], VariantResult],
              variants: list[Variant],
              ) -> Iterator[tuple[Variant, VariantResult | Exception]]:
    """``(variant, its result or the exception its future raised)``, as they finish."""
    futures = {executor.submit(fn, v): v for v in variants}
    for future in concurrent.futures.as_completed(futures):
        try:
            yield futures[future], future.result()
        except Exception as exc:
            yield futures[future], exc


def _lost(exc: Exception) -> str:
    """What to say of a variant whose run never reported back."""
    if isinstance(exc, BrokenProcessPool):
        return ("its worker process died (the script crashed the interpreter, was "
                "killed, or ran out of memory)")
    return f"{type(exc).__name__}: {exc}"


class ProcessPoolVariantExecutor:
    """A local pool of ``jobs`` processes.

    Workers are forked directly when this process runs a single thread (the
    ``livemod batch`` case: no start-up cost). With other threads alive (a
    watching session, say) plain ``fork`` could copy a lock in a held state, so
    the workers come from a forkserver that has imported ``livemod.dlfl`` instead.
    """

    def __init__(self, jobs: int) -> None:
        self.jobs = max(1, jobs)

    def map_unordered(self, fn: Callable[[Variant], VariantResult],
                      variants: list[Variant]) -> Iterator[VariantResult]:
        """As :meth:`VariantExecutor.map_unordered`. A worker that dies breaks the
        whole pool, so the variants it took down are run again, each in a pool of
        its own: only one that kills its own worker is reported failed. When the
        caller stops reading (or Ctrl-C comes), no variant runs on."""
        context, started = _process_context(), time.perf_counter()
        lost = []
        with _stoppable_pool(self.jobs, context) as pool:
            for variant, outcome in _finished(pool, fn, variants):
                if isinstance(outcome, BrokenProcessPool):
                    lost.append(variant)
                elif isinstance(outcome, VariantResult):
                    yield outcome
                else:
                    # its own start is unknown: the map's bounds it, as in the futures pool
                    yield failed_result(variant, _lost(outcome), started)
        for variant in lost:
            with _stoppable_pool(1, context) as alone:
                yield from FuturesVariantExecutor(alone).map_unordered(fn, [variant])


@contextlib.contextmanager
def _stoppable_pool(jobs: int, context: multiprocessing.context.BaseContext,
                    ) -> Iterator[concurrent.futures.ProcessPoolExecutor]:
    """A process pool whose workers are ended when the block ends. When it ends in
    an exception (Ctrl-C, or the caller stopped reading: GeneratorExit) the
    variants not started are dropped and the running ones ended at once (their
    workers remove the temporary file of a mesh being written, see
    :func:`_killed`)."""
    workers = _Workers(context)
    pool = concurrent.futures.ProcessPoolExecutor(
        jobs, mp_context=context, initializer=_worker_started,
        initargs=(workers.started, workers.stopping))
    try:
        yield pool
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        workers.terminate()
        raise
    else:
        # every result is in: end the workers rather than wait for them, since a
        # thread a script left running would keep its worker from ever exiting
        pool.shutdown(wait=False)
        workers.terminate()
    finally:
        workers.close()


class _Workers:
    """The worker processes of one pool, as each reports its process id from the
    pool's initializer. ProcessPoolExecutor offers no public way to end its
    workers before Python 3.14's ``terminate_workers()``; shutting it down waits
    for the running variants, which may take minutes.

    A worker still in its initializer when the pool is ended has not reported
    yet, so it cannot be signalled; :attr:`stopping` covers it: a worker checks
    it after reporting and exits before taking a variant when it is set.
    """

    def __init__(self, context: multiprocessing.context.BaseContext) -> None:
        self.started = context.SimpleQueue()
        self.stopping = context.Event()
        self._ids: set[int] = set()

    def terminate(self) -> None:
        """End every worker: those reported are signalled and waited for (at most
        5 s each); any that reports later finds :attr:`stopping` set and exits.
        Only live children of this process are signalled, so an id reused since
        its worker exited is never signalled."""
        # set before reading: a report the read misses comes after it, and the
        # worker then sees the flag (it checks only after reporting)
        self.stopping.set()
        self._read()
        running = [p for p in multiprocessing.active_children() if p.pid in self._ids]
        for worker in running:
            worker.terminate()
        for worker in running:
            worker.join(timeout=5)

    def close(self) -> None:
        """Close this process's end of the queue (the pool is done with)."""
        self.started.close()

    def _read(self) -> None:
        """Take in the process ids reported so far."""
        while not self.started.empty():
            self._ids.add(self.started.get())


def _worker_started(started: Any, stopping: Any) -> None:
    """In each pool worker: report this process to the pool's :class:`_Workers`
    (the queue ``started``), and exit at once if the pool is being ended already
    (the event ``stopping``). Ctrl-C is left to the batch (which ends the workers;
    a worker interrupted on its own would print a traceback and take the next
    variant); when the pool kills it (SIGTERM: Ctrl-C, or another worker died),
    remove the temporary file of a mesh it was writing, then exit."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _killed)
    started.put(os.getpid())
    if stopping.is_set():
        os._exit(128 + signal.SIGTERM)  # as if signalled: it never took a variant


def _killed(signum: int, frame: object) -> None:
    from livemod.dlfl.io.atomic import remove_unfinished

    remove_unfinished()
    os._exit(128 + signum)  # not SystemExit: a run would catch it and go on


def _process_context() -> multiprocessing.context.BaseContext:
    methods = multiprocessing.get_all_start_methods()
    if "fork" in methods and threading.active_count() == 1:
        return multiprocessing.get_context("fork")
    if "forkserver" in methods:
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(["livemod.dlfl", "livemod.runner.batch"])
        return context
    return multiprocessing.get_context("spawn")


def make_variants(script: str, parameter_sets: list[dict[str, Any]], pattern: str | None,
                  *, mesh_path: str | None = None, seed: int | None = 0,
                  selection: Selection | None = None,
                  all_objects: bool = False) -> list[Variant]:
    """One :class:`Variant` per parameter set, outputs named from ``pattern``; every
    variant starts with the same ``selection`` (what ``faces(True)`` returns) and
    with ``all_objects`` writes every object of its scene joined.

    Raises:
        ValueError: see :func:`output_name`, or two variants would write one file.
    """
    script = os.path.abspath(script)
    variants = [
        Variant(i, script, tuple(params.items()),
                output_name(pattern, params, i) if pattern else None, mesh_path, seed,
                selection, all_objects)
        for i, params in enumerate(parameter_sets)
    ]
    _check_distinct_outputs(variants, pattern)
    return variants


def _check_distinct_outputs(variants: list[Variant], pattern: str | None) -> None:
    """Raises ValueError when two variants would write the same file (their
    outputs, or companions: ``v.obj`` and ``v.dlfl`` would share ``v.mtl``)."""
    from livemod.dlfl.io import companion_paths

    first: dict[str, Variant] = {}
    for variant in variants:
        if variant.output is None:
            continue
        for path in [variant.output, *companion_paths(variant.output)]:
            seen = first.setdefault(os.path.abspath(path), variant)
            if seen is not variant:
                raise ValueError(
                    f"output pattern {pattern!r} names one file, {path}, for variants "
                    f"{seen.index} {dict(seen.parameters)} and {variant.index} "
                    f"{dict(variant.parameters)}; put {{index}} or the swept parameters in it")


class Stop(KeyboardInterrupt):
    """SIGINT (Ctrl-C) or SIGTERM came while :func:`run_batch` ran (``signum``)."""

    def __init__(self, signum: int) -> None:
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


class BatchInterrupted(KeyboardInterrupt):
    """Ctrl-C or SIGTERM stopped :func:`run_batch`; ``results`` are the variants
    that had finished, sorted by variant index (the others did not run or were
    ended), ``signum`` the signal (SIGINT for a plain KeyboardInterrupt)."""

    def __init__(self, results: list[VariantResult], signum: int = signal.SIGINT) -> None:
        super().__init__(f"interrupted after {len(results)} variants")
        self.results = results
        self.signum = signum


class ExecutorLost(RuntimeError):
    """Where the variants ran went away (a cluster's scheduler): no more results
    will come. Raised by an executor's ``map_unordered``; the message says what."""


class BatchLost(RuntimeError):
    """:func:`run_batch` ended early because its executor was lost (the message
    says why); ``results`` are the variants that had finished, by index."""

    def __init__(self, results: list[VariantResult], why: str) -> None:
        super().__init__(why)
        self.results = results


class _StopSignals:
    """While a batch runs, SIGINT and SIGTERM raise :class:`Stop`: at once, or,
    while :meth:`held` (an output being put in place and recorded), right after,
    so that no output is ever on disk without its record. Installed only in the
    main thread, the one signals reach."""

    SIGNALS = (signal.SIGINT, signal.SIGTERM)

    def __init__(self) -> None:
        self._pending: int | None = None
        self._holding = False
        self._previous: dict[int, Any] = {}

    def __enter__(self) -> _StopSignals:
        if threading.current_thread() is threading.main_thread():
            for signum in self.SIGNALS:
                self._previous[signum] = signal.signal(signum, self._handle)
        return self

    def __exit__(self, *exc_info: object) -> None:
        for signum, handler in self._previous.items():
            signal.signal(signum, handler)

    def _handle(self, signum: int, frame: object) -> None:
        if self._holding:
            self._pending = signum
            return
        raise Stop(signum)

    @contextlib.contextmanager
    def held(self) -> Iterator[None]:
        """A block no signal cuts short; one that came meanwhile is raised after it."""
        self._holding = True
        try:
            yield
        finally:
            self._holding = False
        if self._pending is not None:
            raise Stop(self._pending)


def run_batch(variants: list[Variant], executor: VariantExecutor | None = None, *,
              jobs: int = 1, progress: TextIO | None = None, quiet: bool = False,
              on_result: Callable[[list[VariantResult]], None] | None = None,
              ) -> list[VariantResult]:
    """Run ``variants`` (on ``executor``, default a pool of ``jobs`` processes) with a
    progress bar on ``progress`` (default: the current ``sys.stderr``; none if
    ``quiet``); results come back sorted by variant index.

    Each result's mesh is put in place (:func:`commit`) as it comes in, then
    ``on_result`` is called with the results so far (to keep an index current);
    a signal waits for both. Outputs of variants that did not finish are never
    left, nor their temporary files.

    Raises:
        BatchInterrupted: Ctrl-C (a KeyboardInterrupt) or SIGTERM came; it holds
            the results of the variants that had finished.
        BatchLost: the executor was lost (:class:`ExecutorLost`); likewise.
    """
    bar = None if quiet else ProgressBar("batch", progress)
    if executor is None:
        executor = ProcessPoolVariantExecutor(jobs) if jobs > 1 else SerialExecutor()
    staged = with_staging(variants)
    results: list[VariantResult] = []
    with _StopSignals() as signals, _synced(results):
        try:
            for result in executor.map_unordered(run_variant, staged):
                with signals.held():
                    results.append(commit(result))
                    if on_result is not None:
                        on_result(results)
                if bar is not None:
                    bar(len(results), len(variants), "" if results[-1].status == "ok"
                        else f"variant {result.index} failed")
        except (KeyboardInterrupt, ExecutorLost) as exc:
            if bar is not None:  # a note ends the bar's line: what follows starts afresh
                bar(len(results), len(variants), "interrupted")
            done = sorted(results, key=lambda r: r.index)
            if isinstance(exc, ExecutorLost):
                raise BatchLost(done, str(exc)) from None
            raise BatchInterrupted(done, getattr(exc, "signum", signal.SIGINT)) from None
        finally:
            _remove_staging(staged)
    return sorted(results, key=lambda r: r.index)


@contextlib.contextmanager
def _synced(results: list[VariantResult]) -> Iterator[None]:
    """Make the outputs of ``results`` durable when the block ends, however it
    ends (:func:`commit` leaves their folders unsynced)."""
    try:
        yield
    finally:
        sync_outputs(results)


def sync_outputs(results: list[VariantResult]) -> None:
    """Make the outputs of ``results`` durable: each of their folders synced once
    (see :func:`commit`)."""
    from livemod.dlfl.io.atomic import sync_folders

    sync_folders(r.output for r in results if r.status == "ok" and r.output is not None)


def with_staging(variants: list[Variant]) -> list[Variant]:
    """``variants`` each staged in a temporary folder beside its output, one per
    folder, named by this process (a later save into the folder removes it if
    this process dies before the batch ends), under the name of the file its
    output is (or links to): the companions are named after it and land beside
    it. (Distinct outputs have distinct companions: see :func:`make_variants`.)
    One folder serves many variants because removing a folder costs as much as
    writing a small mesh, on a disk mounted with ``discard``."""
    from livemod.dlfl.io.atomic import temporary_path

    folders: dict[str, str] = {}
    staged = []
    for variant in variants:
        if variant.output is not None and variant.staging is None:
            folder, name = os.path.split(os.path.realpath(os.path.abspath(variant.output)))
            staging = folders.setdefault(folder, temporary_path(os.path.join(folder, "batch")))
            variant = dataclasses.replace(variant, staging=os.path.join(staging, name))
        staged.append(variant)
    return staged


def commit(result: VariantResult) -> VariantResult:
    """Put a finished variant's files in place: its companions beside the output,
    then the output itself (the ``staged`` files renamed, or ``data`` written,
    each atomically, the folder made if missing), so that no file ever names a
    companion not there yet; the result without the files, or failed with what
    went wrong (its companions then removed). The renames are made durable
    later, for many outputs at once (:func:`sync_outputs`): one folder sync per
    output would cost the batch as much again as the output."""
    bare = dataclasses.replace(result, staged=None, data=None)
    if result.status != "ok" or result.output is None:
        return bare
    placed: list[str] = []
    try:
        _put_in_place(result, placed)
    except OSError as exc:
        _remove_all(placed)
        return dataclasses.replace(bare, status="error", counts=None, genus=None,
                                   error=describe(exc))
    return bare


def _put_in_place(result: VariantResult, placed: list[str]) -> None:
    """:func:`commit`'s moves and writes; each companion put in place is added
    to ``placed``.

    Raises:
        OSError: a file cannot be put in place.
    """
    from livemod.dlfl.io import companion_paths
    from livemod.dlfl.io.atomic import move_into_place, write_atomically

    output = str(result.output)
    target = os.path.realpath(os.path.abspath(output))
    folder, name = os.path.split(target)
    if result.data is not None:
        os.makedirs(folder, exist_ok=True)
        for companion in sorted(set(result.data) - {name}):
            placed.append(os.path.join(folder, companion))
            write_atomically(placed[-1], result.data[companion], sync_folder=False)
        write_atomically(output, result.data[name], sync_folder=False)
    elif result.staged is not None:
        for companion in filter(os.path.exists, companion_paths(result.staged)):
            placed.append(os.path.join(folder, os.path.basename(companion)))
            move_into_place(companion, placed[-1], sync_folder=False)
        move_into_place(result.staged, output, sync_folder=False)


def _remove_staging(variants: list[Variant]) -> None:
    """Remove the batch's staging folders, with the files left in them (of
    variants that failed, were ended or not put in place)."""
    _remove_all(list(dict.fromkeys(os.path.dirname(v.staging) for v in variants
                                   if v.staging is not None)))


def _remove_all(paths: list[str]) -> None:
    """Remove each file or staging folder of ``paths`` that is there."""
    from livemod.dlfl.io.atomic import remove_temporary

    for path in paths:
        with contextlib.suppress(OSError):
            remove_temporary(path)


def index_rows(results: list[VariantResult]) -> list[dict[str, Any]]:
    """One JSON-ready record per variant: values, output, status, counts, genus."""
    rows = []
    for r in results:
        v, e, f = r.counts if r.counts is not None else (None, None, None)
        rows.append({"index": r.index, "values": dict(r.parameters), "output": r.output,
                     "status": r.status, "V": v, "E": e, "F": f, "genus": r.genus,
                     "error": r.error, "elapsed": round(r.elapsed, 4)})
    return rows


def index_path(variants: list[Variant], given: str | None) -> str | None:
    """Where the sweep's ``index.json`` goes: ``given``, else next to the first
    output, else nowhere (None)."""
    if given is not None:
        return given
    outputs = [v.output for v in variants if v.output is not None]
    if not outputs:
        return None
    return os.path.join(os.path.dirname(os.path.abspath(outputs[0])), "index.json")


def write_index(path: str, script: str, specs: dict[str, ParamSpec],
                results: list[VariantResult], *, planned: int | None = None,
                interrupted: bool = False, running: bool = False,
                reason: str | None = None) -> None:
    """Write the sweep's index atomically (a reader never sees half of it): the
    script, its declarations, ``planned`` (the number of variants of the sweep,
    default ``len(results)``), ``running`` (true while the sweep goes on),
    ``interrupted`` (true when Ctrl-C, SIGTERM or a lost cluster stopped the
    batch, ``reason`` saying which: ``variants`` then lists only those that
    finished) and one record per variant.

    Raises:
        OSError: the file cannot be written.
    """
    import json

    document = {
        "script": os.path.abspath(script),
        "parameters": [{"name": s.name, "kind": s.kind, "default": s.default, "min": s.min,
                        "max": s.max, "choices": list(s.choices) if s.choices else None,
                        "doc": s.doc} for s in specs.values()],
        "planned": len(results) if planned is None else planned,
        "running": running,
        "interrupted": interrupted,
        "reason": reason,
        "variants": index_rows(results),
    }
    from livemod.dlfl.io.atomic import write_atomically

    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    text = json.dumps(document, indent=2, default=str) + "\n"
    write_atomically(path, text.encode("utf-8"))


class LiveIndex:
    """A sweep's index kept current while it runs (a :func:`run_batch`
    ``on_result``): rewritten as results come in, at most every ``interval``
    seconds (``"running": true``), then once more by :meth:`write` at the end. A
    rewrite that fails mid-sweep is left for the last one to report."""

    def __init__(self, path: str, script: str, specs: dict[str, ParamSpec], planned: int,
                 interval: float = 2.0) -> None:
        self.path, self.script, self.specs = path, script, specs
        self.planned, self.interval = planned, interval
        self._written_at = time.monotonic()
        self._synced = 0  # results whose outputs are durable

    def __call__(self, results: list[VariantResult]) -> None:
        """Rewrite the index if the last write is ``interval`` seconds old (the
        outputs it lists made durable first)."""
        now = time.monotonic()
        if now - self._written_at < self.interval:
            return
        self._written_at = now
        sync_outputs(results[self._synced:])
        self._synced = len(results)
        with contextlib.suppress(OSError):
            self.write(results, running=True)

    def write(self, results: list[VariantResult], *, running: bool = False,
              interrupted: bool = False, reason: str | None = None) -> None:
        """Write the index of ``results`` (see :func:`write_index`).

        Raises:
            OSError: the file cannot be written.
        """
        write_index(self.path, self.script, self.specs,
                    sorted(results, key=lambda r: r.index), planned=self.planned,
                    interrupted=interrupted, running=running, reason=reason)
