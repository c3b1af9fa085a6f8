"""``livemod batch --cluster``: the variants of a sweep on a Dask cluster that
sees nothing of the client's disk.

The client packs what the script needs (:mod:`.bundle`) and sends it once; each
variant travels as a small :class:`~.batch.Variant` naming the client's paths,
runs on a worker in a private copy of the script's folder, and comes back with
the bytes of its output file and of the companions its format writes beside it
(a ``.mtl``, a ``.bin``), which the batch writes (:func:`~.batch.commit`). At
most a window of tasks is submitted at a time (twice the cluster's threads),
so neither the client nor the cluster ever holds the whole sweep's meshes; a
task holds one variant, or, once variants are seen to be short and small,
enough of them to take about 0.2 s.

Dask (``distributed``) is an optional extra: ``pip install "livemod[cluster]"``.
A worker that dies mid-variant costs only time: the scheduler runs the variant
again elsewhere, and its output is written once, when its result arrives.
"""

from __future__ import annotations

import atexit
import collections
import contextlib
import dataclasses
import logging
import os
import shutil
import sys
import tempfile
import threading
import time
import uuid
import warnings
from collections.abc import Callable, Iterator
from typing import Any

from livemod.dlfl.io.atomic import write_unsynced

from .batch import ExecutorLost, Variant, VariantResult, failed_result
from .bundle import Bundle, Unpacked, bundle_of, unpack

INSTALL = 'pip install "livemod[cluster]"'
LOCAL = "local"  # ``--cluster local``: a LocalCluster on this machine
_THREADS_REFRESH = 5.0  # seconds between two looks at the cluster's size


class DaskMissing(ImportError):
    """``distributed`` is not installed (the message says how to install it)."""


def require_dask() -> None:
    """Raises DaskMissing when Dask's ``distributed`` cannot be imported."""
    try:
        import distributed  # noqa: F401
    except ImportError as exc:
        raise DaskMissing(f"--cluster runs variants on Dask, which is not installed: "
                          f"{INSTALL}") from exc


@contextlib.contextmanager
def connect(address: str, workers: int) -> Iterator[Any]:
    """A ``distributed.Client`` of the scheduler at ``address`` (``tcp://host:port``,
    or a scheduler file written by ``dask scheduler --scheduler-file``), or, for
    ``"local"``, of a new ``LocalCluster`` of ``workers`` one-thread processes on
    127.0.0.1; closed (and the local cluster stopped) when the block ends.

    Raises:
        DaskMissing: Dask is not installed.
        OSError: the scheduler cannot be reached (Dask's connect timeout, 30 s
            by default).
    """
    require_dask()
    from distributed import Client, LocalCluster

    if address == LOCAL:
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          host="127.0.0.1", dashboard_address="127.0.0.1:8787",
                          silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
            yield client
        return
    where = {"scheduler_file": address} if os.path.isfile(address) else {"address": address}
    try:
        client = Client(**where)
    except (OSError, TimeoutError) as exc:
        raise OSError(f"cannot reach the Dask scheduler at {address}: {exc}") from None
    with client:
        yield client


def silence_dask_logs() -> None:
    """Keep Dask's log lines (a client reconnecting, connections closing, also
    as the process exits) off the terminal from now on: ``livemod batch``
    reports what matters. Dask gives several of its loggers levels of their own,
    so each is set."""
    names = [name for name in logging.root.manager.loggerDict
             if name == "distributed" or name.startswith("distributed.")]
    for name in ["distributed", *names]:
        logging.getLogger(name).setLevel(logging.CRITICAL)


def describe_cluster(client: Any) -> str:
    """``4 workers, 4 threads at tcp://..., dashboard http://...``."""
    threads = client.nthreads()
    workers, total = len(threads), sum(threads.values())
    dashboard = f", dashboard {client.dashboard_link}" if _has_dashboard(client) else ""
    return (f"{workers} worker{'s' * (workers != 1)}, {total} thread{'s' * (total != 1)} "
            f"at {client.scheduler.address}{dashboard}")


def _has_dashboard(client: Any) -> bool:
    try:
        return "dashboard" in client.scheduler_info().get("services", {})
    except Exception:  # an old or odd scheduler: no link, no failure
        return False


class DaskVariantExecutor:
    """Runs variants on a Dask cluster through ``client`` (a ``distributed.Client``),
    shipping each script's :class:`~.bundle.Bundle`; see the module's docstring.

    Args:
        client: a connected client; not closed here.
        window: variants submitted at once; by default twice the cluster's
            threads (looked at again every few seconds, as workers come and go).
        announce: called once per bundle with its summary (what travels).
    """

    def __init__(self, client: Any, window: int | None = None,
                 announce: Callable[[str], None] | None = None) -> None:
        self.client = client
        self._fixed_window = window
        self._announce = announce
        self._window, self._window_at = 2, -_THREADS_REFRESH

    def map_unordered(self, fn: Callable[[Variant], VariantResult],
                      variants: list[Variant]) -> Iterator[VariantResult]:
        """Results of ``fn`` (a top-level function: it is pickled by name) over
        ``variants``, as they finish. A variant whose worker died three times
        (Dask's ``allowed-failures``) comes back failed. When the caller stops
        reading (or Ctrl-C comes), the sweep's futures are cancelled.

        Raises:
            ExecutorLost: the connection to the scheduler was lost.
        """
        bundles = {key: bundle_of(*key)
                   for key in dict.fromkeys((v.script, v.mesh_path) for v in variants)}
        from distributed import as_completed
        from distributed.client import ClosedClientError

        # said when the connection is lost, when the client no longer knows it
        lost = _lost(self.client.scheduler.address)
        run, fetch = _Submitter(self.client, fn), _Fetcher(self.client, lost)
        queue, running = collections.deque(variants), dict[Any, tuple[list[Variant], float]]()
        # done futures come through it (a cancelled one too: Dask cancels them all
        # when the connection to the scheduler is lost, so waiting never hangs)
        completed = as_completed(loop=self.client.loop)
        try:
            self._ship(run, bundles)
            self._fill(run, queue, running, completed, 1)
            while running:
                done = {future: running.pop(future) for future in completed.next_batch()}
                # keep the workers busy first
                chunk = fetch.chunk(len(queue), self._current_window())
                self._fill(run, queue, running, completed, chunk)
                yield from fetch.results(done)
        except (OSError, ClosedClientError):  # the connection closed on the way
            raise ExecutorLost(lost) from None
        finally:
            run.cancel(list(running))

    def _ship(self, run: _Submitter, bundles: dict[tuple[str, str | None], Bundle]) -> None:
        """Send each bundle to every worker as a worker plugin (which Dask also
        gives to workers that join or restart later), named in ``run``."""
        for key, bundle in bundles.items():
            if self._announce is not None:
                self._announce(f"sending {bundle.summary()} to the cluster")
            name = f"livemod-bundle-{bundle.digest}-{uuid.uuid4().hex[:8]}"
            with warnings.catch_warnings():  # a large --mesh makes a "large graph"
                warnings.simplefilter("ignore")
                self.client.register_plugin(BundlePlugin(bundle, name), name=name)
            run.bundles[key] = name

    def _fill(self, run: _Submitter, queue: collections.deque[Variant],
              running: dict[Any, tuple[list[Variant], float]], completed: Any,
              chunk: int) -> None:
        """Submit tasks of ``chunk`` variants from ``queue`` until the window is
        full, each future added to ``running`` and to the ``as_completed``
        ``completed``."""
        while queue and len(running) < self._current_window():
            variants = [queue.popleft() for _ in range(min(chunk, len(queue)))]
            future = run.submit(variants)
            running[future] = (variants, time.perf_counter())
            completed.add(future)

    def _current_window(self) -> int:
        if self._fixed_window is not None:
            return self._fixed_window
        now = time.monotonic()
        if now - self._window_at >= _THREADS_REFRESH:
            self._window_at = now
            with contextlib.suppress(Exception):  # keep the last size if it cannot tell
                self._window = max(2, 2 * sum(self.client.nthreads().values()))
        return self._window

class _Submitter:
    """Submits one sweep's variants, a task of one or more naming its bundle's
    plugin, under keys unique to the sweep (``livemod-variants-FIRST-SWEEP``, as
    the dashboard shows them). The bundle is no dependency of the task: Dask
    would then send every variant to the worker holding it. The earlier variant
    has the higher priority (a worker runs those it holds in order)."""

    def __init__(self, client: Any, fn: Callable[[Variant], VariantResult]) -> None:
        self.client, self.fn = client, fn
        self.bundles: dict[tuple[str, str | None], str] = {}  # plugin names, by script and mesh
        self.sweep = uuid.uuid4().hex[:8]

    def submit(self, variants: list[Variant]) -> Any:
        """A future of ``run_shipped(fn, variants, their bundle's plugin name)``
        (variants of one script and mesh: those of a sweep)."""
        first = variants[0]
        bundle = self.bundles[first.script, first.mesh_path]
        return self.client.submit(run_shipped, self.fn, variants, bundle, pure=False,
                                  key=f"livemod-variants-{first.index}-{self.sweep}",
                                  priority=-first.index)

    def cancel(self, futures: list[Any]) -> None:
        """Cancel ``futures`` and take the bundles off the workers (nothing is
        asked of a scheduler already gone)."""
        if self.client.status == "running":
            with contextlib.suppress(Exception):
                if futures:
                    self.client.cancel(futures)
                for name in self.bundles.values():
                    self.client.unregister_worker_plugin(name)
        self.bundles.clear()


try:  # a plugin must be a WorkerPlugin; without Dask, nothing uses this one
    from distributed.diagnostics.plugin import WorkerPlugin as _PluginBase
except ImportError:
    _PluginBase = object  # type: ignore[misc,assignment]


class BundlePlugin(_PluginBase):
    """A bundle carried to each worker process (kept there under ``name`` for
    :func:`run_shipped`), and its copy removed when the plugin goes."""

    def __init__(self, bundle: Bundle, name: str) -> None:
        self.bundle, self.name = bundle, name

    def setup(self, worker: Any) -> None:
        _bundles[self.name] = self.bundle

    def teardown(self, worker: Any) -> None:
        _bundles.pop(self.name, None)
        here = _unpacked.pop(self.name, None)
        if here is not None:
            shutil.rmtree(here.root, ignore_errors=True)


class _Fetcher:
    """Brings finished tasks' results to the client: several in one round trip
    while they are small, one at a time once one was large (so that the client
    holds one mesh at a time); and says how many variants a task should hold
    (:meth:`chunk`)."""

    SMALL = 1 << 20  # bytes of output below which results are fetched together
    TASK_SECONDS = 0.2  # what a task of short variants should take
    MOST = 64  # variants in one task, at most

    def __init__(self, client: Any, lost: str) -> None:
        self.client, self.lost = client, lost
        self.largest = 0  # bytes of the largest output fetched so far
        self.typical: float | None = None  # seconds a variant takes (a running mean)

    def chunk(self, waiting: int, window: int) -> int:
        """Variants for the next task: one until a result was seen and while
        outputs are large; else as many as take about TASK_SECONDS (Dask's own
        work per task, a few milliseconds, is then shared by them), and few
        enough that the ``waiting`` variants still fill the ``window``."""
        if self.typical is None or self.largest >= self.SMALL:
            return 1
        by_time = int(self.TASK_SECONDS / max(self.typical, 1e-4))
        return max(1, min(self.MOST, by_time, waiting // max(window, 1)))

    def results(self, done: dict[Any, tuple[list[Variant], float]]) -> Iterator[VariantResult]:
        """The results of the futures ``done`` (each with its variants and submit
        time), as they are fetched; the futures are released.

        Raises:
            ExecutorLost: a future was cancelled (the scheduler is gone).
        """
        together = [f for f in done if f.status == "finished"] if self.largest < self.SMALL else []
        gathered = self._gathered(together) if len(together) > 1 else []
        for future, results in zip(together, gathered, strict=False):
            future.release()
            yield from map(self._seen, results)
        for future in done:
            if future not in together or not gathered:
                yield from map(self._seen, _outcome(future, *done[future], self.lost))

    def _gathered(self, futures: list[Any]) -> list[list[VariantResult]]:
        """The results of ``futures`` in one round trip, or [] when one of them
        failed or was cancelled meanwhile (then each is fetched on its own)."""
        try:
            return list(self.client.gather(futures))
        except Exception:
            return []

    def _seen(self, result: VariantResult) -> VariantResult:
        self.largest = max(self.largest, sum(map(len, (result.data or {}).values())))
        if result.status == "ok":
            self.typical = result.elapsed if self.typical is None else (
                0.8 * self.typical + 0.2 * result.elapsed)
        return result


def _lost(address: str) -> str:
    """What to say when the connection to the scheduler at ``address`` was lost."""
    return (f"lost the connection to the Dask scheduler at {address}; "
            f"the variants not listed did not finish")


def _outcome(future: Any, variants: list[Variant], submitted: float,
             lost: str) -> list[VariantResult]:
    """The results of a finished task, or its variants failed with why.

    Raises:
        ExecutorLost: the future was cancelled (the scheduler is gone).
    """
    from distributed import KilledWorker

    try:
        return future.result()
    except KilledWorker:
        why = ("its worker died each time it ran it (killed, out of memory, or the "
               "interpreter crashed)")
    except Exception as exc:
        if future.cancelled():  # by Dask, as the connection was lost (ours come not here)
            raise ExecutorLost(lost) from None
        why = f"{type(exc).__name__}: {exc}"
    finally:
        future.release()
    return [failed_result(variant, why, submitted) for variant in variants]


# -- on a worker ----------------------------------------------------------------

_RUN_LOCK = threading.Lock()  # runs change process state (sys.path, seeds): one at a time
_bundles: dict[str, Bundle] = {}  # plugin name -> the bundle it brought
_unpacked: dict[str, Unpacked] = {}  # plugin name -> its bundle's copy in this process
_scratch: list[str] = []  # this process's folder for copies and outputs


def run_shipped(fn: Callable[[Variant], VariantResult], variants: list[Variant],
                bundle: str) -> list[VariantResult]:
    """On a worker: run ``fn`` on each of ``variants`` in this process's copy of
    the bundle the plugin ``bundle`` brought (unpacked at its first variant here);
    their results as the client knows them: the client's paths in them, and the
    bytes of the output file and its companions in ``data``, by file name. One variant at a time per process (a worker
    with several threads runs them in turn).

    Raises:
        RuntimeError: no such bundle reached this process.
    """
    return [_run_one(fn, variant, bundle) for variant in variants]


def _run_one(fn: Callable[[Variant], VariantResult], variant: Variant,
             bundle: str) -> VariantResult:
    """:func:`run_shipped` of one variant."""
    with _RUN_LOCK:
        here = _unpacked.get(bundle)
        if here is None:
            if bundle not in _bundles:
                raise RuntimeError(f"the script's files ({bundle}) did not reach this worker")
            here = _unpacked[bundle] = unpack(
                _bundles[bundle], tempfile.mkdtemp(prefix="bundle-", dir=_scratch_folder()))
        out = _output_folder()
        # named as the client stages it: the companions are named after it
        local = dataclasses.replace(
            variant, script=here.script, mesh_path=here.mesh, staging=None,
            output=None if variant.output is None
            else os.path.join(out, os.path.basename(variant.staging or variant.output)))
        try:
            result = fn(local)
            data = None
            if result.status == "ok" and local.output is not None:
                data = _files_in(out)
        finally:
            _empty(out)
    paths = {here.folder: os.path.dirname(variant.script),
             **({here.mesh: str(variant.mesh_path)} if here.mesh else {}),
             **({local.output: str(variant.output),
                 out: os.path.dirname(str(variant.output)) or os.curdir}
                if local.output else {})}
    return dataclasses.replace(result, output=variant.output, data=data, staged=None,
                               error=_renamed(result.error, paths))


def _files_in(folder: str) -> dict[str, bytes]:
    """The bytes of each file in ``folder``, by name."""
    files = {}
    for name in os.listdir(folder):
        with open(os.path.join(folder, name), "rb") as handle:
            files[name] = handle.read()
    return files


def _empty(folder: str) -> None:
    """Remove everything in ``folder`` (a variant's outputs, sent or failed), so
    that nothing of one variant comes back with the next."""
    for entry in os.scandir(folder):
        with contextlib.suppress(OSError):
            if entry.is_dir(follow_symlinks=False):
                shutil.rmtree(entry.path)
            else:
                os.unlink(entry.path)


def _renamed(text: str | None, paths: dict[str, str]) -> str | None:
    """``text`` with the worker's paths said as the client's."""
    if text is None:
        return None
    for worker_path, client_path in paths.items():
        text = text.replace(worker_path, client_path)
    return text


def _output_folder() -> str:
    """This process's folder for a variant's output and companions: one for
    all its variants, emptied after each (making and removing a folder per
    variant costs as much as a small variant's output, on a disk mounted with
    ``discard``). Its files are not synced to disk: they are read back at once,
    and the client writes them durably."""
    out = os.path.join(_scratch_folder(), "output")
    if not os.path.isdir(out):
        os.mkdir(out)
        write_unsynced(os.path.realpath(out))
    return out


def _scratch_folder() -> str:
    """This process's folder for bundles and outputs: in the Dask worker's own
    folder (which Dask cleans up, also after a killed worker) when there is one,
    removed when the process exits."""
    if not _scratch:
        base = None
        with contextlib.suppress(Exception):
            from distributed import get_worker

            base = get_worker().local_directory
        _scratch.append(tempfile.mkdtemp(prefix="livemod-", dir=base))
        atexit.register(shutil.rmtree, _scratch[0], True)
    return _scratch[0]


def note(text: str) -> None:
    """A line on standard error, as ``livemod batch --cluster`` reports."""
    print(f"dask: {text}", file=sys.stderr, flush=True)
