"""``livemod batch --cluster`` benchmarks (plain python; prints medians).

    python bench/bench_batch.py [--quick] [--only overhead|speedup|memory]

1. Overhead per variant: 1,000 variants of a 10 ms script (each writes its cube
   to -o) on a Dask LocalCluster of 2 worker processes, against the local
   process pool of 2 (``-j 2``). Each sweep runs in a fresh client process, the
   two kinds alternated; the time is the sweep's alone (the cluster is started
   beforehand, as ``--cluster ADDRESS`` finds it). Target: at most 2 ms more
   per variant.
2. 32 variants of a 1 s script on a LocalCluster of 2 workers against one of 1.
   Target: at least 1.8x.
3. Peak memory of the client during a sweep of 200 variants of 393,216 faces
   each (a cube subdivided 8 times, written as .ply) on 2 workers: the growth of
   its resident memory (sampled every 5 ms) over its size just before the sweep,
   against one variant's output file and its mesh in memory. Target: under 4x
   one variant's mesh.

The variants spin for their CPU time rather than sleep, so they cost what real
work does, however loaded the machine.
The machine is shared: the load average is printed with each figure.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import threading

BUSY = """\
import time
n = param("n", 0)
end = time.thread_time() + {seconds}
while time.thread_time() < end:  # CPU time: the same work however loaded the machine
    pass
load("cube")
"""

LARGE = """\
n = param("n", 0)
load("cube")
for _ in range(8):
    subdivide("catmull-clark")
translate(n, 0, 0)
"""

CHILD = """
import json, resource, sys, time
from livemod.runner.batch import ProcessPoolVariantExecutor, make_variants, run_batch
mode, script, count, out, address = sys.argv[1:6]
variants = make_variants(script, [{"n": i} for i in range(int(count))], out)
if mode == "pool":
    executor, client = ProcessPoolVariantExecutor(2), None
else:
    from distributed import Client
    from livemod.runner.cluster import DaskVariantExecutor, silence_dask_logs
    silence_dask_logs()
    client = Client(address)
    executor = DaskVariantExecutor(client)
sys.path.insert(0, sys.argv[6])
from bench_batch import ResidentPeak
# the sampling thread only where memory is measured: with a second thread alive the
# pool would start its workers from a forkserver, not by fork as `livemod batch` does
peak = ResidentPeak(enabled=sys.argv[7] == "memory")
started = time.perf_counter()
with peak:
    results = run_batch(variants, executor, quiet=True)
took = time.perf_counter() - started
assert all(r.status == "ok" for r in results), [r.error for r in results if r.error][:3]
if client is not None:
    client.close()
cpu = sum(getattr(resource.getrusage(who), field) for who in
          (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN) for field in ("ru_utime", "ru_stime"))
print(json.dumps({"seconds": took, "grown": peak.grown, "cpu": cpu}))
"""


class ResidentPeak:
    """The largest growth of this process's resident memory over its size when
    the block began, sampled every 5 ms by a thread while the block runs."""

    def __init__(self, enabled: bool = True) -> None:
        self.grown = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._sample, daemon=True) if enabled else None

    def __enter__(self) -> ResidentPeak:
        self._start = _resident()
        if self._thread is not None:
            self._thread.start()
        return self

    def __exit__(self, *exc_info: object) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join()

    def _sample(self) -> None:
        while not self._stop.wait(0.005):
            self.grown = max(self.grown, _resident() - self._start)


def _resident() -> int:
    with open("/proc/self/statm") as handle:
        return int(handle.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def _load() -> str:
    with open("/proc/loadavg") as handle:
        return " ".join(handle.read().split()[:3])


def _sweep(mode: str, script: str, count: int, out: str, address: str = "",
           memory: bool = False) -> dict:
    """One sweep in a fresh client process: its seconds, the client's growth and
    the CPU seconds of the client (with its pool's workers) and, for Dask, of this
    process (where a LocalCluster's scheduler runs) and its workers."""
    import json

    cluster_before = _cluster_cpu()
    done = subprocess.run([sys.executable, "-c", CHILD, mode, script, str(count), out,
                           address, os.path.dirname(os.path.abspath(__file__)),
                           "memory" if memory else "time"],
                          check=True, capture_output=True, text=True)
    measured = json.loads(done.stdout.strip().splitlines()[-1])
    if mode == "dask":
        measured["cpu"] += _cluster_cpu() - cluster_before
    return measured


def _cluster_cpu() -> float:
    """CPU seconds of this process and its children's children (a LocalCluster's
    scheduler and nanny threads, its worker processes)."""
    import psutil

    me = psutil.Process()
    total = 0.0
    for process in [me, *me.children(recursive=True)]:
        try:
            times = process.cpu_times()
        except psutil.Error:  # ended meanwhile
            continue
        total += times.user + times.system
    return total


def _cluster(workers: int):  # noqa: ANN202
    from distributed import LocalCluster

    return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                        host="127.0.0.1", dashboard_address="127.0.0.1:0", silence_logs=50)


def _script(folder: str, name: str, text: str) -> str:
    path = os.path.join(folder, name)
    with open(path, "w") as handle:
        handle.write(text)
    return path


def bench_overhead(folder: str, count: int, repeats: int) -> None:
    script = _script(folder, "busy10ms.py", BUSY.format(seconds=0.010))
    out = os.path.join(folder, "overhead", "{n}.obj")
    times: dict[str, list[float]] = {"pool": [], "dask": []}
    cpus: dict[str, list[float]] = {"pool": [], "dask": []}
    loads = []
    with _cluster(2) as cluster:
        for _ in range(repeats):
            for mode in times:  # alternated, so changes of load hit both alike
                loads.append(_load())
                measured = _sweep(mode, script, count, out, cluster.scheduler_address)
                times[mode].append(measured["seconds"])
                cpus[mode].append(measured["cpu"])
    pool, dask = statistics.median(times["pool"]), statistics.median(times["dask"])
    pool_cpu, dask_cpu = statistics.median(cpus["pool"]), statistics.median(cpus["dask"])
    print(f"  CPU per variant, all processes: pool {pool_cpu / count * 1e3:.1f} ms, Dask "
          f"{dask_cpu / count * 1e3:.1f} ms ({(dask_cpu - pool_cpu) / count * 1e3:+.1f} ms; the "
          f"pool's includes starting its processes, Dask's cluster was up)")
    print(f"{count:,} variants of 10 ms, 2 workers: process pool {pool:.2f} s "
          f"({pool / count * 1e3:.2f} ms each), Dask {dask:.2f} s "
          f"({dask / count * 1e3:.2f} ms each): {(dask - pool) / count * 1e3:+.2f} ms per "
          f"variant (target <= +2 ms; medians of {repeats}; all: pool "
          f"{[round(t, 2) for t in times['pool']]}, dask {[round(t, 2) for t in times['dask']]}; "
          f"load {loads[0]} .. {loads[-1]})")


def bench_speedup(folder: str, count: int) -> None:
    script = _script(folder, "busy1s.py", BUSY.format(seconds=1.0))
    out = os.path.join(folder, "speedup", "{n}.obj")
    took = {}
    loads = []
    for workers in (1, 2):
        with _cluster(workers) as cluster:
            loads.append(_load())
            took[workers] = _sweep("dask", script, count, out,
                                   cluster.scheduler_address)["seconds"]
    print(f"{count} variants of 1 s on Dask: 1 worker {took[1]:.1f} s, 2 workers "
          f"{took[2]:.1f} s: {took[1] / took[2]:.2f}x (target >= 1.8x; load {' / '.join(loads)})")


def bench_memory(folder: str, count: int) -> None:
    from livemod.dlfl.io import load_mesh

    script = _script(folder, "large.py", LARGE)
    out = os.path.join(folder, "memory", "{n}.ply")
    with _cluster(2) as cluster:
        load_before = _load()
        measured = _sweep("dask", script, count, out, cluster.scheduler_address, memory=True)
    one_file = os.path.getsize(out.format(n=0))
    mesh = load_mesh(out.format(n=0))
    in_memory = _array_bytes(mesh)
    grown = measured["grown"]
    print(f"{count} variants of {mesh.num_faces:,} faces on 2 workers ({measured['seconds']:.0f} s): "
          f"client grew by at most {grown / 1e6:.1f} MB = {grown / one_file:.2f}x one "
          f"variant's .ply ({one_file / 1e6:.1f} MB), {grown / in_memory:.2f}x its mesh's "
          f"arrays ({in_memory / 1e6:.1f} MB) (target < 4x; load {load_before} at the start, "
          f"{_load()} at the end)")


def _array_bytes(mesh) -> int:  # noqa: ANN001
    """Bytes of a mesh's arrays (``mesh_arrays``: positions, faces, corners, edges),
    what the viewer and a snapshot hold of it."""
    import dataclasses

    import numpy as np

    from livemod.dlfl import mesh_arrays

    arrays = mesh_arrays(mesh)
    return sum(value.nbytes for field in dataclasses.fields(arrays)
               if isinstance(value := getattr(arrays, field.name), np.ndarray))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller sweeps")
    parser.add_argument("--only", choices=("overhead", "speedup", "memory"))
    parser.add_argument("--repeats", type=int, default=3,
                        help="alternated pairs of overhead sweeps (default 3)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-batch-") as folder:
        if args.only in (None, "overhead"):
            bench_overhead(folder, 200 if args.quick else 1000, args.repeats)
        if args.only in (None, "speedup"):
            bench_speedup(folder, 8 if args.quick else 32)
        if args.only in (None, "memory"):
            bench_memory(folder, 10 if args.quick else 200)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
