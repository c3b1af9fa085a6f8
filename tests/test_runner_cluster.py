"""``livemod batch --cluster`` (livemod.runner.cluster) on real Dask clusters: a
LocalCluster of worker processes, and a scheduler and workers started as
separate ``dask`` commands in folders of their own, which cannot see the
client's files: each worker runs in a mount namespace of its own (``unshare
-m``, as root on Linux) where a tmpfs hides the folder every test's files are
in. One cluster of each kind serves the whole module."""

from __future__ import annotations

import contextlib
import gc
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import warnings
from collections.abc import Iterator
from pathlib import Path

import pytest
from distributed import Client, LocalCluster

from livemod.dlfl import load
from livemod.dlfl.io import read_obj, save_mesh
from livemod.dlfl.scene import Scene, use_scene
from livemod.runner import cli

from .runner_scripts.support import wait_until

pytestmark = [
    # a cluster starts in seconds, but in a minute on a loaded machine
    pytest.mark.timeout(300),
    # tornado leaves the socket of a refused connection (to a killed worker) to the
    # garbage collector; each fixture collects them as it ends
    pytest.mark.filterwarnings("ignore::ResourceWarning"),
    # with `pytest --dist loadgroup`, one xdist worker runs them all (one cluster
    # of each kind instead of one per worker)
    pytest.mark.xdist_group("dask"),
]
SLOW = 180.0  # seconds a cluster may take to start or a sweep to get going, at worst
DASK_TIMEOUTS = {"DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT": "120s"}

# the script of every sweep here: a local module, a file named by an f-string
# (parts/*.obj travel with it), the --mesh; n >= hold waits for the file
# RELEASE in the folder `marks` names (absolute: the workers see it)
SWEEP = """\
import os, pathlib, time
from helper import offset
n = param("n", 0)
kind = param("kind", "tetra")
marks = param("marks", "")
hold = param("hold", 99)
if marks:
    pathlib.Path(marks, f"{n}-{os.getpid()}").touch()
    deadline = time.monotonic() + 60
    while n >= hold and not pathlib.Path(marks, "RELEASE").exists() and time.monotonic() < deadline:
        time.sleep(0.01)
load(f"parts/{kind}.obj")
translate(offset(n), 0, 0)
subdivide("loop")
"""


def _project(root: Path) -> tuple[Path, Path]:
    """A script folder (helper module, parts/) and a --mesh outside it."""
    folder = root / "project"
    (folder / "parts").mkdir(parents=True)
    (folder / "sweep.py").write_text(SWEEP)
    (folder / "helper.py").write_text("def offset(n):\n    return 0.25 * n\n")
    scene = Scene()
    with use_scene(scene):
        load("tetrahedron")
        save_mesh(scene.objects[scene.current].mesh, folder / "parts" / "tetra.obj")
        load("cube")
        mesh = root / "meshes" / "base.obj"
        mesh.parent.mkdir()
        save_mesh(scene.objects[scene.current].mesh, mesh)
    return folder / "sweep.py", mesh


def _single_run(script: Path, mesh: Path, values: dict, out: Path) -> bytes:
    """The bytes ``livemod run --set ... --mesh ... --all-objects -o`` writes."""
    sets = [arg for name, value in values.items() for arg in ("--set", f"{name}={value}")]
    assert cli.main(["run", str(script), *sets, "--mesh", str(mesh), "--all-objects",
                     "-o", str(out)]) == 0
    return out.read_bytes()


# -- the clusters ----------------------------------------------------------------

@pytest.fixture(scope="module", autouse=True)
def _patient_dask() -> Iterator[None]:
    """Dask's timeouts for a loaded machine, here and in the processes started;
    at the end, the sockets Dask left are collected (see ``pytestmark``)."""
    import dask

    with pytest.MonkeyPatch.context() as patch, dask.config.set(
            {"distributed.comm.timeouts.connect": "120s"}):
        for name, value in DASK_TIMEOUTS.items():
            patch.setenv(name, value)
        yield
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ResourceWarning)
        gc.collect()


@pytest.fixture(scope="module")
def local_cluster(_patient_dask) -> Iterator[Client]:
    """A LocalCluster of two one-thread worker processes, and a client of it. A
    variant whose worker dies is not run again (Dask's allowed-failures is 0 here,
    3 by default), so that one that kills its worker fails at once."""
    import dask

    with dask.config.set({"distributed.scheduler.allowed-failures": 0}), \
            LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                         dashboard_address="127.0.0.1:0", silence_logs=50) as cluster, \
            Client(cluster) as client:
        yield client


class SeparateCluster:
    """``dask scheduler`` and two ``dask worker`` processes, each started in a
    folder of its own under ``home``; the workers' view of ``hidden`` is an empty
    tmpfs. ``marks`` is a folder both sides see."""

    def __init__(self, hidden: Path) -> None:
        self.home = Path(tempfile.mkdtemp(prefix="livemod-dask-"))
        self.hidden = hidden
        self.marks = self.home / "marks"
        self.marks.mkdir()
        self.scheduler_file = self.home / "scheduler.json"
        self.processes: list[subprocess.Popen] = []

    def start(self) -> Client:
        self.scheduler = self._start("scheduler", [
            "scheduler", "--host", "127.0.0.1", "--port", "0", "--dashboard-address", "127.0.0.1:0",
            "--scheduler-file", str(self.scheduler_file)])
        wait_until(self.scheduler_file.exists, timeout=SLOW)
        for index in range(2):
            hide = f"mount -t tmpfs tmpfs {self.hidden} && exec \"$@\""
            self._start(f"worker{index}", [
                "worker", "--scheduler-file", str(self.scheduler_file), "--nthreads", "1",
                "--host", "127.0.0.1", "--dashboard-address", "127.0.0.1:0"], ["unshare", "-m", "sh", "-c", hide, "-"])
        client = Client(scheduler_file=str(self.scheduler_file), timeout=SLOW)
        client.wait_for_workers(2, timeout=SLOW)
        return client

    def _start(self, name: str, arguments: list[str], prefix: list[str] = ()) -> subprocess.Popen:
        folder = self.home / name
        folder.mkdir()
        with open(folder / "log", "wb") as log:
            process = subprocess.Popen([*prefix, sys.executable, "-m", "dask", *arguments],
                                       cwd=folder, stdout=log, stderr=subprocess.STDOUT)
        self.processes.append(process)
        return process

    def stop(self) -> None:
        for process in reversed(self.processes):
            process.terminate()
        for process in self.processes:
            try:
                process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait(timeout=30)
        shutil.rmtree(self.home, ignore_errors=True)


@pytest.fixture(scope="module")
def separate_cluster(tmp_path_factory, _patient_dask) -> Iterator[tuple[SeparateCluster, Client]]:
    cluster = SeparateCluster(tmp_path_factory.getbasetemp())
    try:
        client = cluster.start()
        with client:
            yield cluster, client
    finally:
        cluster.stop()


# -- tests -------------------------------------------------------------------------

def test_the_separate_workers_cannot_see_the_clients_files(separate_cluster, tmp_path):
    _, client = separate_cluster
    script, mesh = _project(tmp_path)
    assert script.exists() and mesh.exists()
    seen = client.run(lambda paths: [os.path.exists(p) for p in paths], [script, mesh, tmp_path])
    assert list(seen.values()) == [[False, False, False]] * 2


def test_a_sweep_on_workers_that_see_no_shared_disk_equals_single_runs(
        separate_cluster, tmp_path, capsys):
    cluster, _ = separate_cluster
    script, mesh = _project(tmp_path)
    code = cli.main(["batch", str(script), "--param", "n=0:3:4", "--mesh", str(mesh),
                     "--all-objects", "-o", str(tmp_path / "out" / "s_{n}.obj"),
                     "--cluster", str(cluster.scheduler_file)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "dask: sending sweep.py, 1 module, 1 file, --mesh base.obj" in captured.err
    assert captured.out.startswith("4/4 variants ok\n")
    for n in range(4):
        single = _single_run(script, mesh, {"n": n}, tmp_path / f"single_{n}.obj")
        assert (tmp_path / "out" / f"s_{n}.obj").read_bytes() == single
    index = json.loads((tmp_path / "out" / "index.json").read_text())
    assert [(v["index"], v["status"], v["F"]) for v in index["variants"]] == [
        (n, "ok", 6 + 16) for n in range(4)]


def test_a_coloured_sweep_brings_each_objs_library_back_from_the_workers(
        separate_cluster, tmp_path, capsys):
    """The workers cannot see the client's disk: the .mtl beside each OBJ came
    back with it; the files equal those of the same sweep in local processes."""
    cluster, _ = separate_cluster
    script = tmp_path / "coloured.py"
    script.write_text("n = param('n', 0)\nload('cube')\nsetFaceColor([0, 1], (1, 0, 0.5 * n))\n")
    sweep = ["batch", str(script), "--param", "n=0:1:2", "-o"]
    assert cli.main([*sweep, str(tmp_path / "local" / "v_{index}.obj"), "-j", "2"]) == 0
    code = cli.main([*sweep, str(tmp_path / "out" / "v_{index}.obj"),
                     "--cluster", str(cluster.scheduler_file)])
    assert code == 0, capsys.readouterr().err
    names = ["v_0.mtl", "v_0.obj", "v_1.mtl", "v_1.obj"]
    assert sorted(os.listdir(tmp_path / "out")) == ["index.json", *names]
    for name in names:
        assert (tmp_path / "out" / name).read_bytes() == (tmp_path / "local" / name).read_bytes()
    assert read_obj(tmp_path / "out" / "v_1.obj").face_color(0) == (1.0, 0.0, 0.5)


def test_a_killed_worker_costs_only_time(separate_cluster, tmp_path, capsys):
    """Variant 2 holds until its worker is killed; Dask runs it again elsewhere,
    and every output is written once and equals its single run."""
    cluster, client = separate_cluster
    script, mesh = _project(tmp_path)
    marks = cluster.marks / "kill"
    marks.mkdir()
    killed: list[int] = []

    def kill_the_worker_of_variant_2() -> None:
        started = wait_until(lambda: list(marks.glob("2-*")), timeout=SLOW)
        pid = int(started[0].name.split("-")[1])
        assert pid in client.run(os.getpid).values()  # a worker process, not the client
        os.kill(pid, signal.SIGKILL)
        killed.append(pid)
        (marks / "RELEASE").touch()  # the run again elsewhere goes through

    killer = threading.Thread(target=kill_the_worker_of_variant_2)
    killer.start()
    code = cli.main(["batch", str(script), "--param", "n=0:5:6", "--param", f"marks={marks}",
                     "--param", "hold=2", "--mesh", str(mesh), "--all-objects",
                     "-o", str(tmp_path / "out" / "{n}.obj"),
                     "--cluster", str(cluster.scheduler_file)])
    killer.join(timeout=60)
    assert code == 0, capsys.readouterr().err
    runs_of_2 = sorted(p.name for p in marks.glob("2-*"))
    assert len(runs_of_2) == 2 and runs_of_2[0] != runs_of_2[1] and killed
    assert sorted(os.listdir(tmp_path / "out")) == sorted(
        [f"{n}.obj" for n in range(6)] + ["index.json"])
    index = json.loads((tmp_path / "out" / "index.json").read_text())
    assert [(v["index"], v["status"]) for v in index["variants"]] == [(n, "ok") for n in range(6)]
    (marks / "RELEASE").touch()
    for n in range(6):
        single = _single_run(script, mesh, {"n": n, "marks": marks, "hold": 2},
                             tmp_path / f"single_{n}.obj")
        assert (tmp_path / "out" / f"{n}.obj").read_bytes() == single


def test_a_failing_variant_is_reported_at_its_line_and_the_sweep_goes_on(
        local_cluster, tmp_path, capsys):
    script = tmp_path / "fails.py"
    script.write_text("n = param('n', 0)\nload('cube')\nif n == 1:\n    extrude('nothing')\n")
    code = cli.main(["batch", str(script), "--param", "n=0:2:3", "-o",
                     str(tmp_path / "out" / "{n}.obj"), "--cluster",
                     local_cluster.scheduler.address])
    captured = capsys.readouterr()
    assert code == 1
    assert f"livemod: error: variant 1 {{'n': 1}}: {script}:4: " in captured.err
    assert captured.out.startswith("2/3 variants ok\n")
    assert sorted(os.listdir(tmp_path / "out")) == ["0.obj", "2.obj", "index.json"]


def test_a_variant_that_kills_its_worker_fails_and_the_sweep_goes_on(
        local_cluster, tmp_path, capsys):
    script = tmp_path / "exits.py"
    script.write_text("import os, signal\nn = param('n', 0)\nload('cube')\nif n == 1:\n"
                      "    os.kill(os.getpid(), signal.SIGKILL)\n")
    # (the last variant: one queued behind it on its worker would be lost with it,
    # as Dask may run that again only where allowed-failures allows)
    code = cli.main(["batch", str(script), "--param", "n=0:1:2", "-o",
                     str(tmp_path / "out" / "{n}.obj"), "--cluster",
                     local_cluster.scheduler.address])
    assert code == 1
    assert ("livemod: error: variant 1 {'n': 1}: its worker died each time it ran it "
            "(killed, out of memory, or the interpreter crashed)") in capsys.readouterr().err
    assert sorted(os.listdir(tmp_path / "out")) == ["0.obj", "index.json"]
    local_cluster.wait_for_workers(2, timeout=SLOW)  # the nanny starts a new one


def test_ctrl_c_cancels_the_sweep_on_the_cluster(local_cluster, tmp_path):
    script, mesh = _project(tmp_path)
    marks = tmp_path / "marks"
    marks.mkdir()
    proc = subprocess.Popen(
        [sys.executable, "-m", "livemod", "batch", str(script), "--param", "n=0:7:8",
         "--param", f"marks={marks}", "--param", "hold=2", "--mesh", str(mesh),
         "-o", str(tmp_path / "out" / "{n}.obj"), "--cluster", local_cluster.scheduler.address],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        wait_until(lambda: all((tmp_path / "out" / f"{n}.obj").exists() for n in (0, 1)),
                   timeout=SLOW)
        wait_until(lambda: list(marks.glob("2-*")), timeout=SLOW)
        os.killpg(proc.pid, signal.SIGINT)
        printed, error = proc.communicate(timeout=60)
        assert proc.returncode == 130, error
        assert printed.startswith("interrupted: 2/8 variants finished, 2 ok\n")
        index = json.loads((tmp_path / "out" / "index.json").read_text())
        assert (index["interrupted"], index["reason"]) == (True, "SIGINT")
        assert [v["index"] for v in index["variants"]] == [0, 1]
        assert sorted(os.listdir(tmp_path / "out")) == ["0.obj", "1.obj", "index.json"]
        wait_until(lambda: not _sweep_tasks(local_cluster), timeout=60)
    finally:
        (marks / "RELEASE").touch()  # the variants still running on the workers end
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate(timeout=60)
    wait_until(lambda: not any(local_cluster.run(_executing).values()), timeout=SLOW)
    assert sorted(os.listdir(tmp_path / "out")) == ["0.obj", "1.obj", "index.json"]


def _executing(dask_worker) -> int:  # noqa: ANN001  (a distributed.Worker)
    return dask_worker.state.executing_count


def _sweep_tasks(client: Client) -> list[str]:
    """The keys of variants the scheduler still knows of."""
    return client.run_on_scheduler(
        lambda dask_scheduler: [str(k) for k in dask_scheduler.tasks
                                if str(k).startswith("livemod-variant")])


def test_the_scheduler_going_away_ends_the_batch_with_a_clear_error(tmp_path, _patient_dask):
    cluster = SeparateCluster(tmp_path / "nothing-hidden")  # a scheduler, no workers
    script, _ = _project(tmp_path)
    try:
        cluster.scheduler = cluster._start("scheduler", [
            "scheduler", "--host", "127.0.0.1", "--port", "0", "--dashboard-address", "127.0.0.1:0",
            "--scheduler-file", str(cluster.scheduler_file)])
        wait_until(cluster.scheduler_file.exists, timeout=SLOW)
        proc = subprocess.Popen(
            [sys.executable, "-m", "livemod", "batch", str(script), "--param", "n=0:3:4",
             "-o", str(tmp_path / "out" / "{n}.obj"), "--cluster", str(cluster.scheduler_file)],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        with Client(scheduler_file=str(cluster.scheduler_file), timeout=SLOW) as client:
            wait_until(lambda: _sweep_tasks(client), timeout=SLOW)  # submitted, never run
        cluster.scheduler.kill()
        printed, error = proc.communicate(timeout=SLOW)
    finally:
        cluster.stop()
    assert proc.returncode == 1
    assert "livemod: error: lost the connection to the Dask scheduler at tcp://127.0.0.1:" in error
    assert "Traceback" not in error
    assert printed.startswith("stopped: 0/4 variants finished, 0 ok\n")
    index = json.loads((tmp_path / "out" / "index.json").read_text())
    assert index["interrupted"] is True and index["variants"] == []
    assert index["reason"].startswith("lost the connection to the Dask scheduler")


def test_cluster_local_starts_a_dask_cluster_of_j_processes(tmp_path):
    script, mesh = _project(tmp_path)
    done = subprocess.run(
        [sys.executable, "-m", "livemod", "batch", str(script), "--param", "n=0:1:2",
         "--mesh", str(mesh), "--all-objects", "-o", str(tmp_path / "out" / "{n}.obj"),
         "--cluster", "local", "-j", "1"], capture_output=True, text=True, timeout=SLOW)
    assert done.returncode == 0, done.stderr
    assert "dask: 1 worker, 1 thread at tcp://127.0.0.1:" in done.stderr
    assert done.stdout.startswith("2/2 variants ok\n")
    single = _single_run(script, mesh, {"n": 1}, tmp_path / "single.obj")
    assert (tmp_path / "out" / "1.obj").read_bytes() == single


def test_without_dask_cluster_says_how_to_install_it(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed fails
    ring = str(Path(__file__).parent / "runner_scripts" / "ring.py")
    assert cli.main(["batch", ring, "--param", "count=3", "--cluster", "local"]) == 2
    assert capsys.readouterr().err == (
        'livemod: error: --cluster runs variants on Dask, which is not installed: '
        'pip install "livemod[cluster]"\n')


def test_an_unreachable_scheduler_is_an_error_naming_it(capsys):
    import dask

    ring = str(Path(__file__).parent / "runner_scripts" / "ring.py")
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
        code = cli.main(["batch", ring, "--param", "count=3", "--cluster", "tcp://127.0.0.1:9"])
    assert code == 1
    assert "cannot reach the Dask scheduler at tcp://127.0.0.1:9" in capsys.readouterr().err


def test_a_workers_variants_share_one_output_folder_left_empty(tmp_path, monkeypatch):
    """run_shipped in this process (as on a worker): each variant's file comes
    back as the bytes of a single run, a failed variant's too is cleared, the
    outputs are never synced to disk, and the scratch holds the bundle's copy
    and one output folder, not a folder per variant."""
    from livemod.dlfl.io import atomic
    from livemod.runner import cluster
    from livemod.runner.batch import make_variants, run_variant, with_staging
    from livemod.runner.bundle import bundle_of

    script, mesh = _project(tmp_path)
    (tmp_path / "scratch").mkdir()
    monkeypatch.setattr(cluster, "_scratch", [str(tmp_path / "scratch")])
    monkeypatch.setattr(cluster, "_unpacked", {})
    monkeypatch.setattr(cluster, "_bundles", {"b": bundle_of(str(script), str(mesh))})
    monkeypatch.setattr(atomic, "_unsynced", set())
    variants = with_staging(make_variants(
        str(script), [{"n": 0}, {"n": 1, "kind": "missing"}, {"n": 2}],
        str(tmp_path / "out" / "v_{n}.obj"), mesh_path=str(mesh), all_objects=True))
    real_fsync, synced = os.fsync, []
    monkeypatch.setattr(os, "fsync", lambda fd: synced.append(fd) or real_fsync(fd))
    results = cluster.run_shipped(run_variant, variants, "b")
    assert [r.status for r in results] == ["ok", "error", "ok"]
    assert synced == []
    # said of the client's files, not of the worker's copy
    assert results[1].error == (f"{script}:12: InvalidArgumentError: no file missing.obj "
                                f"in {script.parent / 'parts'}")
    for n in (0, 2):
        single = _single_run(script, mesh, {"n": n}, tmp_path / f"single_{n}.obj")
        assert results[n].data == {f"v_{n}.obj": single}
        assert results[n].output == str(tmp_path / "out" / f"v_{n}.obj")
    names = sorted(os.listdir(tmp_path / "scratch"))
    assert len(names) == 2 and names[1] == "output" and names[0].startswith("bundle-")
    assert os.listdir(tmp_path / "scratch" / "output") == []
