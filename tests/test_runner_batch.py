"""livemod.runner.batch: what a stopped batch leaves (SIGTERM, Ctrl-C), the files
of a format that writes companions (a coloured OBJ's .mtl, a .gltf's .bin), the
index kept current as results come in, and what ``batch`` says without ``-o``."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl.colors import MODELLING_COLOR
from livemod.dlfl.io import read_obj
from livemod.dlfl.validate import validate
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


# faces 0 and 1 in a colour of the variant's own; the others in none
COLOURED = ("n = param('n', 0)\n"
            "load('cube')\n"
            "setFaceColor([0, 1], (1, 0, 0.25 * n))\n")


def _coloured_script(folder: Path) -> str:
    script = folder / "coloured.py"
    script.write_text(COLOURED)
    return str(script)


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


@pytest.mark.parametrize("output", ["ring.obj", "coloured.obj", "ring.gltf"])
def test_a_mesh_written_but_not_reported_before_ctrl_c_is_not_left(tmp_path, monkeypatch,
                                                                   output):
    """Issue 30: the index listed 1,380 variants and 1,384 outputs were on disk;
    nor is a companion left (the .mtl of a coloured OBJ, the .bin of a .gltf)."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "batch.pid").write_text(str(os.getpid()))
    monkeypatch.setattr(batch, "run_variant", _written_then_interrupted)
    script, values = RING, {"count": 3, "radius": 1.0}
    if output.startswith("coloured"):
        script, values = _coloured_script(tmp_path), {"n": 1}
    variants = make_variants(script, [values], str(out / output))
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


def _face_colours(path: Path, n: int) -> None:
    """The OBJ ``path`` of variant ``n`` of :data:`COLOURED` reads back, by
    livemod and by trimesh, with its colours."""
    import trimesh

    mesh = read_obj(path)
    validate(mesh)
    own, modelling = np.float32([1, 0, 0.25 * n]), np.float32(MODELLING_COLOR)
    np.testing.assert_array_equal(mesh.face_colors(), [own, own, *[modelling] * 4])
    peer = trimesh.load(path, process=False, group_material=False)
    diffuse = sorted(tuple(g.visual.material.diffuse[:3].tolist())
                     for g in peer.geometry.values())
    assert diffuse == sorted([(255, 0, round(63.75 * n)), (255, 151, 92)])


def test_a_coloured_sweep_writes_each_obj_with_its_library_under_final_names(tmp_path):
    script, out = _coloured_script(tmp_path), tmp_path / "out"
    assert cli.main(["batch", script, "--param", "n=0:2:3", "-o", str(out / "v_{index}.obj"),
                     "-j", "2"]) == 0
    assert sorted(os.listdir(out)) == [
        "index.json", "v_0.mtl", "v_0.obj", "v_1.mtl", "v_1.obj", "v_2.mtl", "v_2.obj"]
    for n in range(3):
        assert (out / f"v_{n}.obj").read_text().splitlines()[1] == f"mtllib v_{n}.mtl"
        _face_colours(out / f"v_{n}.obj", n)


def test_a_dlfl_and_a_gltf_sweep_write_their_companions_beside_each_file(tmp_path):
    import trimesh

    script = _coloured_script(tmp_path)
    assert cli.main(["batch", script, "--param", "n=0:1:2", "-o",
                     str(tmp_path / "d" / "{n}.dlfl"), "-j", "1"]) == 0
    assert sorted(os.listdir(tmp_path / "d")) == [
        "0.dlfl", "0.mtl", "1.dlfl", "1.mtl", "index.json"]
    assert (tmp_path / "d" / "1.dlfl").read_text().splitlines()[1] == "mtllib 1.mtl"
    assert cli.main(["batch", script, "--param", "n=0:1:2", "-o",
                     str(tmp_path / "g" / "{n}.gltf"), "-j", "2"]) == 0
    assert sorted(os.listdir(tmp_path / "g")) == [
        "0.bin", "0.gltf", "1.bin", "1.gltf", "index.json"]
    document = json.loads((tmp_path / "g" / "1.gltf").read_text())
    assert document["buffers"][0]["uri"] == "1.bin"
    peer = trimesh.load(tmp_path / "g" / "1.gltf", force="mesh", process=False)
    assert len(peer.faces) == 12  # the cube's quads as triangles


def test_a_variant_whose_output_cannot_be_put_in_place_leaves_no_companion(tmp_path):
    script, out = _coloured_script(tmp_path), tmp_path / "out"
    variants = make_variants(script, [{"n": 0}, {"n": 1}], str(out / "{n}.obj"))
    (out / "1.obj").mkdir(parents=True)  # a folder where variant 1's OBJ should go
    (out / "1.obj" / "keep").write_text("")
    done = run_batch(variants, SerialExecutor(), quiet=True)
    assert [r.status for r in done] == ["ok", "error"]
    assert f"cannot write {out / '1.obj'}" in str(done[1].error)
    assert sorted(os.listdir(out)) == ["0.mtl", "0.obj", "1.obj"]  # no 1.mtl, no staging


def test_outputs_that_would_share_a_companion_are_refused():
    with pytest.raises(ValueError, match="names one file, out/v.mtl, for variants 0"):
        make_variants(RING, [{"f": "obj"}, {"f": "dlfl"}], "out/v.{f}")


def test_run_o_of_a_coloured_script_writes_the_obj_and_its_library(tmp_path):
    script = _coloured_script(tmp_path)
    assert cli.main(["run", script, "--set", "n=2", "-o", str(tmp_path / "x" / "x.obj")]) == 0
    assert sorted(os.listdir(tmp_path / "x")) == ["x.mtl", "x.obj"]
    _face_colours(tmp_path / "x" / "x.obj", 2)
