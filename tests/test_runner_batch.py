"""livemod.runner.batch: what a stopped batch leaves (SIGTERM, Ctrl-C), the index
kept current as results come in, and what ``batch`` says without ``-o``."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

from livemod.runner import batch, cli
from livemod.runner.batch import (
    BatchInterrupted,
    LiveIndex,
    ProcessPoolVariantExecutor,
    SerialExecutor,
    make_variants,
    run_batch,
)

from .runner_scripts.support import script_path

RING = script_path("ring.py")

# variants 0 and 1 finish; the others report their process and run until ended
STUCK_FROM_2 = (
    "import os, pathlib, time\n"
    "n = param('n', 0)\n"
    "load('cube')\n"
    "if n >= 2:\n"
    "    pathlib.Path(__file__).with_name(f'{n}.{os.getpid()}.pid').touch()\n"
    "    while True:\n"
    "        time.sleep(0.01)\n")


def _gone(pid: int) -> bool:
    """No such process, or only its exit status is left (a zombie)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as handle:
            return handle.read().rsplit(b")", 1)[1].split()[0] == b"Z"
    except FileNotFoundError:
        return True


def test_sigterm_ends_the_workers_and_writes_the_index_as_ctrl_c_does(tmp_path):
    script = tmp_path / "stuck.py"
    script.write_text(STUCK_FROM_2)
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "livemod.runner.cli", "batch", str(script),
                             "--param", "n=0:5:6", "-o", str(out / "{n}.obj"), "-j", "2"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stderr is not None
    progress = [proc.stderr.readline() for _ in range(2)]  # one line per result off a tty
    assert " 2/6" in progress[1], progress
    from .runner_scripts.support import wait_until

    workers = wait_until(lambda: [int(p.name.split(".")[1]) for p in tmp_path.glob("*.pid")])
    proc.terminate()  # `kill PID`: the batch alone, not its process group
    printed, error = proc.communicate(timeout=60)
    assert proc.returncode == 128 + signal.SIGTERM
    assert "Traceback" not in error and "(interrupted)" in error
    assert printed == (f"interrupted: 2/6 variants finished, 2 ok\n"
                       f"wrote {out / 'index.json'}\n")
    index = json.loads((out / "index.json").read_text())
    assert (index["interrupted"], index["reason"], index["running"]) == (True, "SIGTERM", False)
    assert [v["index"] for v in index["variants"]] == [0, 1]
    assert all(_gone(pid) for pid in workers), workers
    assert sorted(os.listdir(out)) == ["0.obj", "1.obj", "index.json"]


_REAL_RUN_VARIANT = batch.run_variant


def _written_then_interrupted(variant: batch.Variant) -> batch.VariantResult:
    """A variant that writes its mesh, then has Ctrl-C sent to the batch before it
    reports back (the batch's pid is in ``batch.pid`` beside the output); waits to
    be ended."""
    result = _REAL_RUN_VARIANT(variant)
    batch_pid = int((Path(str(variant.output)).parent / "batch.pid").read_text())
    os.kill(batch_pid, signal.SIGINT)
    signal.pause()  # the batch ends this worker
    return result


def test_a_mesh_written_but_not_reported_before_ctrl_c_is_not_left(tmp_path, monkeypatch):
    """Issue 30: the index listed 1,380 variants and 1,384 outputs were on disk."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "batch.pid").write_text(str(os.getpid()))
    monkeypatch.setattr(batch, "run_variant", _written_then_interrupted)
    variants = make_variants(RING, [{"count": 3, "radius": 1.0}], str(out / "ring.obj"))
    try:
        run_batch(variants, ProcessPoolVariantExecutor(2), quiet=True)
    except BatchInterrupted as stop:
        assert stop.results == [] and stop.signum == signal.SIGINT
    else:
        raise AssertionError("the batch was not interrupted")
    assert sorted(os.listdir(out)) == ["batch.pid"]  # no mesh the index would not list


def test_the_index_is_kept_current_as_results_come_in(tmp_path):
    variants = make_variants(RING, [{"count": n, "radius": 1.0} for n in (3, 4, 5)],
                             str(tmp_path / "ring_{count}.obj"))
    index = str(tmp_path / "index.json")
    live = LiveIndex(index, RING, {}, planned=3, interval=0.0)
    seen = []

    def record(results: list) -> None:
        live(results)
        document = json.loads(Path(index).read_text())
        listed = [v["output"] for v in document["variants"]]
        seen.append((document["running"], listed))
        assert all(os.path.exists(path) for path in listed)  # on disk before it is listed

    run_batch(variants, SerialExecutor(), quiet=True, on_result=record)
    assert [len(listed) for _, listed in seen] == [1, 2, 3]
    assert all(running for running, _ in seen)


def test_batch_without_output_says_it_wrote_nothing_and_how_to(capsys):
    code = cli.main(["batch", RING, "--param", "count=3:4:2", "--param", "radius=1", "-j", "1"])
    assert code == 0
    assert capsys.readouterr().out == (
        "2/2 variants ok\n"
        "ran and checked 2 variants but wrote no mesh: give -o with a pattern, e.g. "
        "-o 'out/{count}_{radius}.obj', to write each one\n")


def test_a_thread_a_script_leaves_running_does_not_hold_the_batch(tmp_path):
    script = tmp_path / "threads.py"
    script.write_text("import threading, time\n"
                      "n = param('n', 0)\n"
                      "threading.Thread(target=time.sleep, args=(10**6,)).start()\n"
                      "load('cube')\n")
    out = tmp_path / "out"
    # the timeout is a deadline for a hang, not a measure: the thread sleeps for days
    done = subprocess.run([sys.executable, "-m", "livemod.runner.cli", "batch", str(script),
                           "--param", "n=0:1:2", "-o", str(out / "{n}.obj"), "-j", "2"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in out.glob("*.obj")) == ["0.obj", "1.obj"]
