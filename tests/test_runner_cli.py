"""``livemod run`` and ``livemod batch`` end to end, plus the sweep helpers."""

from __future__ import annotations

import multiprocessing
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl import from_polygons
from livemod.dlfl.io import WRITERS
from livemod.runner import cli
from livemod.runner.batch import (
    SerialExecutor,
    _worker_started,
    _Workers,
    make_variants,
    output_name,
    parse_param,
    run_batch,
    sweep,
)

from .meshes import CUBE_FACES, CUBE_POSITIONS
from .runner_scripts.support import script_path, write_by_rename

RING = script_path("ring.py")
# the extensions an output may have, as the refusal lists them
WRITTEN = ", ".join(f".{key}" for key in WRITERS)


def test_run_prints_summary_and_steps(capsys):
    assert cli.main(["run", script_path("cube_steps.py"), "--steps"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == cli.STEPS_HEADER
    assert lines[1].startswith("    0     11  cube                         8        12         6")
    assert any(" done " in line for line in lines[2:])
    assert "V=14 E=18 F=6 holes=0 components=1 genus=0" in lines


def test_steps_give_each_steps_own_time_beside_the_cumulative_one(capsys):
    from livemod.runner import StepRecord

    cli.print_steps([StepRecord(0, "cube", 3, (8, 12, 6), 0.25),
                     StepRecord(1, "subdivide", None, (26, 48, 24), 1.75)])
    assert capsys.readouterr().out == (
        " step   line  command                      V         E         F"
        "        time  cumulative\n"
        "    0      3  cube                         8        12         6"
        "    0.2500 s    0.2500 s\n"
        "    1      ?  subdivide                   26        48        24"
        "    1.5000 s    1.7500 s\n")


def test_summary_gives_genus_per_component_only_for_several(tmp_path, capsys):
    script = tmp_path / "two.py"
    script.write_text("load('cube')\nload('torus')\n")  # two objects, the second current
    assert cli.main(["run", str(script)]) == 0
    assert "components=1 genus=1\n" in capsys.readouterr().out
    two = from_polygons(np.vstack([CUBE_POSITIONS, CUBE_POSITIONS + 5.0]),
                        CUBE_FACES + [[i + 8 for i in f] for f in CUBE_FACES])
    cli.print_summary("two cubes", two, 0, 0.0)
    assert "components=2 genus=0 (per component: 0, 0)" in capsys.readouterr().out


def test_run_failure_exits_non_zero_with_file_and_line(capsys):
    assert cli.main(["run", script_path("error_at_line_7.py")]) == 1
    err = capsys.readouterr().err
    assert f"{script_path('error_at_line_7.py')}:7: UnknownIdError: edge 12345" in err


def test_a_missing_script_exits_1_and_an_output_no_writer_takes_2(capsys, tmp_path):
    missing = tmp_path / "nope.py"
    assert cli.main(["run", str(missing)]) == 1
    assert capsys.readouterr().err == (f"livemod: error: cannot read {missing}: "
                                       "No such file or directory\n")
    assert cli.main(["run", RING, "-o", str(tmp_path / "x.txt")]) == 2
    assert capsys.readouterr().err == (f"livemod: error: output {tmp_path / 'x.txt'} must "
                                       f"end with one of {WRITTEN}\n")


def test_run_with_params_seed_and_output(tmp_path, capsys):
    out = tmp_path / "ring.obj"
    code = cli.main(["run", RING, "--param", "count=5", "--param", "radius=2",
                     "--seed", "3", "-o", str(out)])
    assert code == 0, capsys.readouterr().err
    assert "V=5 E=5 F=2" in capsys.readouterr().out
    assert out.exists() and out.read_text().count("\nv ") + out.read_text().startswith("v ") == 5


RIND = "load('cube')\nrind(faces(True), False, 0.1)\n"


def test_run_select_is_what_faces_true_returns(tmp_path, capsys):
    script = tmp_path / "crust.py"
    script.write_text(RIND)
    crust = tmp_path / "crust.stl"
    assert cli.main(["run", str(script), "--select", "faces=0", "-o", str(crust)]) == 0
    captured = capsys.readouterr()
    # one face opened: a single crust of 14 quads (without it, two closed shells)
    assert "V=16 E=28 F=14 holes=0 components=1 genus=0" in captured.out
    assert captured.err == "" and crust.exists()
    assert cli.main(["run", str(script)]) == 0
    assert "F=12 holes=0 components=2" in capsys.readouterr().out


def test_run_warns_of_picks_the_mesh_did_not_have(tmp_path, capsys):
    script = tmp_path / "crust.py"
    script.write_text(RIND)
    assert cli.main(["run", str(script), "--select", "faces=0,99", "--select", "corners=7"]) == 0
    err = capsys.readouterr().err
    # corners(True) is never called, so corner 7 goes unremarked
    assert err == ("livemod: warning: the mesh had no faces 99 when the script asked for "
                   "the selection; those picks were left out\n")


def test_run_notes_a_selection_asked_for_with_nothing_selected(tmp_path, capsys):
    script = tmp_path / "crust.py"
    script.write_text("load('cube')\nprint(len(edges(True)), len(verts(True)))\n"
                      "rind(faces(True), False, 0.1)\n")
    assert cli.main(["run", str(script)]) == 0
    out, err = capsys.readouterr()
    assert "0 0\n" in out and "components=2" in out  # a closed double shell
    assert err == ("livemod: note: faces(True) and edges(True) and verts(True) found nothing "
                   "selected, so the script got none; give --select faces=ID,... --select "
                   "edges=ID,... --select verts=ID,..., or pick in `livemod view`\n")
    assert cli.main(["run", str(script), "--select", "faces=0", "--select", "edges=0",
                     "--select", "vertices=0"]) == 0
    assert capsys.readouterr().err == ""


def test_a_bad_select_stops_before_running(tmp_path, capsys):
    script = tmp_path / "crust.py"
    script.write_text(RIND)
    with pytest.raises(SystemExit) as stopped:
        cli.main(["run", str(script), "--select", "fcae=0"])
    assert stopped.value.code == 2
    assert "--select 'fcae=0': the kind must be one of" in capsys.readouterr().err


def test_batch_variants_start_with_the_selection(tmp_path, capsys):
    script = tmp_path / "crusts.py"
    script.write_text("t = param('t', 0.1)\nload('cube')\nrind(faces(True), False, t)\n")
    code = cli.main(["batch", str(script), "--param", "t=0.1:0.2:2", "--select", "faces=0,1",
                     "-o", str(tmp_path / "c_{index}.obj"), "-j", "1"])
    assert code == 0, capsys.readouterr().err
    # faces 0 and 1 share an edge, so one hole of six edges: four outer and four
    # inner quads and six rim quads (without the selection: two shells of six)
    for index in (0, 1):
        assert (tmp_path / f"c_{index}.obj").read_text().count("\nf ") == 4 + 4 + 6


def test_params_and_set_of_a_script_that_is_not_utf8_say_so_in_one_line(tmp_path, capsys):
    script = tmp_path / "latin.py"
    script.write_bytes(b"n = param('n', 3)\n# caf\xe9\n")
    # the script's fault, not the command line's: 1, as when it runs (without --set)
    assert cli.main(["params", str(script)]) == 1
    assert cli.main(["run", str(script), "--set", "n=4"]) == 1
    err = capsys.readouterr().err.splitlines()
    assert err == [f"livemod: error: {script}:2: byte 0xe9 on line 2 is not UTF-8 text: "
                   "save the file as UTF-8, or declare its encoding on the first line "
                   "(# -*- coding: latin-1 -*-)"] * 2


def test_a_syntax_error_is_the_scripts_fault_with_or_without_set(tmp_path, capsys):
    script = tmp_path / "broken.py"
    script.write_text("n = param('n', 3)\nif n\n")
    assert cli.main(["run", str(script), "--set", "n=4"]) == 1
    assert capsys.readouterr().err == (f"livemod: error: {script}:2: syntax error: "
                                       "expected ':'\n")
    assert cli.main(["run", str(script)]) == 1
    assert capsys.readouterr().err.endswith(f"livemod: error: {script}:2: SyntaxError: "
                                            "expected ':'\n")


def test_run_makes_the_output_folder_and_says_when_there_is_nothing_to_write(tmp_path, capsys):
    out = tmp_path / "new" / "folder" / "ring.obj"
    assert cli.main(["run", RING, "-o", str(out)]) == 0 and out.exists()
    empty = tmp_path / "empty.py"
    empty.write_text("x = 1\n")
    stale = tmp_path / "old.obj"
    stale.write_text("v 0 0 0\n")
    capsys.readouterr()
    assert cli.main(["run", str(empty), "-o", str(stale)]) == 1
    assert capsys.readouterr().err == (f"livemod: error: the script left no mesh; {stale} "
                                       "was not written\n")
    assert stale.read_text() == "v 0 0 0\n"


@pytest.mark.parametrize(("argv", "message"), [
    (["batch", RING, "--param", "count=3", "-j", "0"], "jobs must be a whole number >= 1, not '0'"),
    (["run", RING, "--seed", "abc"], "the seed must be a whole number or 'none', not 'abc'"),
])
def test_bad_jobs_and_seeds_are_one_line_errors(argv, message, capsys):
    with pytest.raises(SystemExit) as stopped:
        cli.main(argv)
    assert stopped.value.code == 2 and message in capsys.readouterr().err


def test_livemod_entry_point_runs_a_script():
    done = subprocess.run([sys.executable, "-m", "livemod.runner.cli", "run", RING,
                           "--param", "count=4", "--param", "radius=1"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "V=4 E=4 F=2" in done.stdout


def _marking_script(tmp_path) -> tuple[str, object]:
    """A script that leaves a marker file when it runs (and a cube), and the marker."""
    marker = tmp_path / "ran"
    script = tmp_path / "marks.py"
    script.write_text(f"n = param('n', 0)\nopen({str(marker)!r}, 'w').close()\nload('cube')\n")
    return str(script), marker


def test_an_output_that_cannot_be_written_fails_before_the_script_runs(tmp_path, capsys):
    script, marker = _marking_script(tmp_path)
    (tmp_path / "folder.obj").mkdir()
    (tmp_path / "file.obj").write_text("")
    for target, reason in ((tmp_path / "folder.obj", "Is a directory"),
                           (tmp_path / "file.obj" / "x.obj",
                            f"{tmp_path / 'file.obj'} is a file, not a folder"),
                           (tmp_path / "file.obj" / "deeper" / "x.obj",
                            f"{tmp_path / 'file.obj'} is a file, not a folder")):
        assert cli.main(["run", script, "-o", str(target)]) == 1
        assert capsys.readouterr().err == f"livemod: error: cannot write {target}: {reason}\n"
        assert cli.main(["run", "--watch", script, "-o", str(target)]) == 1
        assert capsys.readouterr().err == f"livemod: error: cannot write {target}: {reason}\n"
    assert not marker.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file.obj", "folder.obj", "marks.py"]


def test_a_folder_that_takes_no_new_file_fails_before_the_script_runs(tmp_path, capsys):
    script, marker = _marking_script(tmp_path)
    if os.geteuid() == 0:  # root writes into any folder a mode forbids: /sys takes none
        locked = Path("/sys")
    else:
        locked = tmp_path / "locked"
        locked.mkdir(mode=0o555)
    target = locked / "new" / "x.obj"
    assert cli.main(["run", script, "-o", str(target)]) == 1
    message = capsys.readouterr().err
    assert message in (f"livemod: error: cannot write {target}: Permission denied\n",
                       f"livemod: error: cannot write {target}: Read-only file system\n")
    assert not marker.exists()


def test_batch_checks_every_output_and_the_index_before_any_variant_runs(tmp_path, capsys):
    script, marker = _marking_script(tmp_path)
    (tmp_path / "file").write_text("")
    pattern = str(tmp_path / "out" / "{n}.txt")
    assert cli.main(["batch", script, "--param", "n=0:1:2", "-o", pattern, "-j", "1"]) == 2
    assert capsys.readouterr().err == (f"livemod: error: output {tmp_path / 'out' / '0.txt'} "
                                       f"must end with one of {WRITTEN}\n")
    into_a_file = str(tmp_path / "file" / "{n}.obj")
    assert cli.main(["batch", script, "--param", "n=0:1:2", "-o", into_a_file]) == 1
    assert capsys.readouterr().err == (f"livemod: error: cannot write {tmp_path / 'file' / '0.obj'}"
                                       f": {tmp_path / 'file'} is a file, not a folder\n")
    index = tmp_path / "file" / "index.json"
    assert cli.main(["batch", script, "--param", "n=0:1:2", "--index", str(index)]) == 1
    assert capsys.readouterr().err == (f"livemod: error: cannot write {index}: "
                                       f"{tmp_path / 'file'} is a file, not a folder\n")
    assert not marker.exists() and not (tmp_path / "out").exists()


def test_run_writes_its_output_even_when_the_reader_of_its_summary_left(tmp_path):
    """``livemod run S -o OUT | head -1``: the pipe closes before the summary is
    printed (here: before anything is), and OUT must still be written."""
    out = tmp_path / "ring.obj"
    proc = subprocess.Popen([sys.executable, "-m", "livemod.runner.cli", "run", RING,
                             "--param", "count=4", "--param", "radius=1", "-o", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()  # the reader is gone before the run prints its first line
    with proc.stderr:
        error = proc.stderr.read().decode()
    assert proc.wait(timeout=60) != 0 and "Traceback" not in error
    assert out.exists() and out.read_bytes().count(b"\nf ") == 2


def test_ctrl_c_stops_a_batch_at_once_and_indexes_what_finished(tmp_path):
    """Ctrl-C (SIGINT to the process group, as a terminal sends it) ends the running
    variants and drops the queued ones, and the index lists those that finished."""
    import json

    script = tmp_path / "slow.py"
    script.write_text(
        "import pathlib, time\n"
        "n = param('n', 0)\n"
        "pathlib.Path(__file__).with_name(f'{n}.started').touch()\n"
        "load('cube')\n"
        "while n >= 2:  # variants 0 and 1 finish, the others would run for ever\n"
        "    time.sleep(0.01)\n")
    proc = subprocess.Popen([sys.executable, "-m", "livemod.runner.cli", "batch", str(script),
                             "--param", "n=0:7:8", "-o", str(tmp_path / "out" / "{n}.obj"),
                             "-j", "2"], start_new_session=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stderr is not None
    progress = [proc.stderr.readline() for _ in range(2)]  # one line per result off a tty
    assert progress[1].startswith("batch [") and " 2/8" in progress[1], progress
    os.killpg(proc.pid, signal.SIGINT)
    # variants 2 and 3 never end: waiting for them would time out here (how soon it
    # stops is bench/bench_responsiveness.py's to time)
    out, error = proc.communicate(timeout=30)
    assert proc.returncode == 130
    assert "Traceback" not in error and "(interrupted)" in error
    assert out == (f"interrupted: 2/8 variants finished, 2 ok\n"
                   f"wrote {tmp_path / 'out' / 'index.json'}\n")
    index = json.loads((tmp_path / "out" / "index.json").read_text())
    assert index["interrupted"] is True and index["planned"] == 8
    assert [(v["index"], v["status"]) for v in index["variants"]] == [(0, "ok"), (1, "ok")]
    assert len(list(tmp_path.glob("*.started"))) <= 4  # no queued variant began
    # no half-written mesh (nor its temporary file) of the two ended variants
    assert sorted(os.listdir(tmp_path / "out")) == ["0.obj", "1.obj", "index.json"]


@pytest.mark.timeout(60)
def test_ctrl_c_ends_run_watch_with_130(tmp_path):
    script = tmp_path / "w.py"
    script.write_text("load('cube')\n")
    proc = subprocess.Popen([sys.executable, "-m", "livemod", "run", "--watch", str(script)],
                            start_new_session=True, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    assert proc.stdout is not None
    assert proc.stdout.readline().startswith("run 1: ok")
    os.killpg(proc.pid, signal.SIGINT)
    out, error = proc.communicate(timeout=30)
    assert proc.returncode == 130 and "Traceback" not in error


def test_parse_param_sweep_and_output_names():
    assert parse_param("n=3:6:4") == ("n", [3, 4, 5, 6])
    assert parse_param("r=0:1:3") == ("r", [0.0, 0.5, 1.0])
    assert parse_param("r=2.5") == ("r", [2.5])
    for bad in ("n", "n=1:2", "n=1:2:0", "n=a:2:3", "1n=1:2:3"):
        with pytest.raises(ValueError):
            parse_param(bad)
    with pytest.raises(ValueError, match="--param a given more than once"):
        sweep([("a", [1]), ("b", [2]), ("a", [3])])
    combos = sweep([("a", [1, 2]), ("b", [0.5])])
    assert combos == [{"a": 1, "b": 0.5}, {"a": 2, "b": 0.5}]
    assert output_name("out/{a}_{b:.2f}_{index:03d}.obj", combos[1], 1) == "out/2_0.50_001.obj"
    with pytest.raises(ValueError):
        output_name("{missing}.obj", combos[0], 0)


def test_serial_batch_writes_each_variant(tmp_path):
    variants = make_variants(RING, sweep([parse_param("count=3:5:3"), parse_param("radius=1")]),
                             str(tmp_path / "ring_{count}.obj"))
    results = run_batch(variants, SerialExecutor(), quiet=True)
    assert [r.counts for r in results] == [(3, 3, 2), (4, 4, 2), (5, 5, 2)]
    assert sorted(os.listdir(tmp_path)) == ["ring_3.obj", "ring_4.obj", "ring_5.obj"]


@pytest.mark.timeout(120)
def test_batch_in_two_processes_end_to_end(tmp_path, capsys):
    pattern = str(tmp_path / "out" / "ring_{count}_{radius}_{index}.obj")
    code = cli.main(["batch", RING, "--param", "count=3:6:4", "--param", "radius=1:2:2",
                     "-o", pattern, "-j", "2"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "8/8 variants ok" in captured.out and "8/8" in captured.err  # progress bar
    names = sorted(os.listdir(tmp_path / "out"))
    assert len(names) == 9 and "ring_6_2.0_7.obj" in names and "index.json" in names


def test_batch_refuses_outputs_that_two_variants_would_share(tmp_path, capsys):
    same = str(tmp_path / "same.obj")
    assert cli.main(["batch", RING, "--param", "count=3:4:2", "--param", "radius=1",
                     "-o", same]) == 2
    assert (f"names one file, {same}, for variants 0 {{'count': 3, 'radius': 1.0}} and 1 "
            f"{{'count': 4, 'radius': 1.0}}; put {{index}} or the swept parameters in it"
            in capsys.readouterr().err)
    rounded = str(tmp_path / "r_{radius:.0f}.obj")  # 1.0 and 1.5 both print as 1 (or 2)
    assert cli.main(["batch", RING, "--param", "count=3", "--param", "radius=1:2:3",
                     "-o", rounded]) == 2
    assert os.listdir(tmp_path) == []


def test_batch_writes_glb_as_one_binary_file(tmp_path):
    assert cli.main(["batch", RING, "--param", "count=3:4:2", "-o",
                     str(tmp_path / "r_{count}.glb")]) == 0
    assert sorted(os.listdir(tmp_path)) == ["index.json", "r_3.glb", "r_4.glb"]
    assert (tmp_path / "r_3.glb").read_bytes()[:4] == b"glTF"


def test_a_parameter_named_index_clashes_with_the_pattern_field():
    with pytest.raises(ValueError, match="a parameter named 'index' clashes"):
        output_name("out/{index}.obj", {"index": 2}, 0)
    with pytest.raises(ValueError, match="cannot format"):
        output_name("out/{name:.2f}.obj", {"name": "abc"}, 0)


@pytest.mark.timeout(120)
@pytest.mark.parametrize(("ending", "said"), [
    ("os.kill(os.getpid(), 9)", "its worker process died"),
    # a script's os._exit ends its run, not its worker
    ("os._exit(5)", "dies.py:4: ProcessExit: os._exit(5) ends the run here, not livemod"),
], ids=["killed", "os._exit"])
def test_a_variant_that_kills_its_worker_fails_alone(tmp_path, capsys, ending, said):
    script = tmp_path / "dies.py"
    script.write_text(f"import os\nn = param('n', 0)\nif n == 1:\n    {ending}\n"
                      "createVertex((n, 0, 0))\n")
    code = cli.main(["batch", str(script), "--param", "n=0:3:4", "-o",
                     str(tmp_path / "out" / "{n}.obj"), "-j", "2"])
    captured = capsys.readouterr()
    assert code == 1 and "3/4 variants ok" in captured.out
    assert "variant 1 {'n': 1}: " in captured.err and said in captured.err
    assert sorted(os.listdir(tmp_path / "out")) == ["0.obj", "2.obj", "3.obj", "index.json"]


def test_a_variant_that_leaves_no_mesh_fails_and_writes_nothing(tmp_path):
    script = tmp_path / "maybe.py"
    script.write_text('n = param("n", 0, min=0, max=1)\nif n:\n    load("cube")\n')
    out = tmp_path / "out" / "v{n}.obj"
    results = run_batch(make_variants(str(script), [{"n": 0}, {"n": 1}], str(out)))
    assert [r.status for r in results] == ["error", "ok"]
    written = tmp_path / "out" / "v0.obj"
    assert results[0].error == f"the script left no mesh; {written} was not written"
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == ["v1.obj"]


def test_batch_reports_failing_variants(tmp_path, capsys):
    code = cli.main(["batch", RING, "--param", "count=1:3:3", "--param", "radius=1", "-j", "1"])
    assert code == 1
    assert "variant 0" in capsys.readouterr().err


@pytest.mark.timeout(60)
def test_run_watch_rewrites_the_output_on_save(tmp_path, capsys):
    script, out = tmp_path / "w.py", tmp_path / "w.obj"
    script.write_text("createVertex((0, 0, 0))\n")

    def save_later() -> None:
        deadline = time.monotonic() + 10
        while not out.exists() and time.monotonic() < deadline:
            time.sleep(0.02)
        time.sleep(0.3)
        write_by_rename(str(script), "createFace([(0, 0, 0), (1, 0, 0), (0, 1, 0)])\n")

    saver = threading.Thread(target=save_later)
    saver.start()
    code = cli.main(["run", "--watch", str(script), "-o", str(out), "--max-runs", "2"])
    saver.join()
    assert code == 0
    lines = [line for line in capsys.readouterr().out.splitlines() if line.startswith("run ")]
    assert len(lines) == 2 and "V=3 E=3 F=2" in lines[1]
    assert out.read_text().count("f ") == 2


@pytest.mark.parametrize(("suffix", "counts"), [
    ("obj", "V=5 E=5 F=2"), ("dlfl", "V=5 E=5 F=2"), ("ply", "V=5 E=5 F=2"),
    ("stl", "V=5 E=6 F=3"),  # STL holds the quad as two triangles
])
def test_run_starts_from_the_mesh_given_with_mesh(tmp_path, capsys, suffix, counts):
    from livemod.dlfl import from_polygons
    from livemod.dlfl.io import save_mesh

    base = tmp_path / f"quad.{suffix}"
    save_mesh(from_polygons([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2, 3)]),
              str(base))
    script = tmp_path / "grow.py"
    script.write_text("subdivideEdge(edges()[0])\n")
    assert cli.main(["run", str(script), "--mesh", str(base), "--steps"]) == 0
    out = capsys.readouterr().out
    assert counts in out and "subdivideEdge" in out


def test_the_top_level_livemod_command_has_run_and_batch(capsys):
    from livemod import cli as top

    assert top.main(["run", RING, "--param", "count=3", "--param", "radius=1"]) == 0
    assert "V=3 E=3 F=2" in capsys.readouterr().out


def test_any_futures_executor_can_run_a_batch(tmp_path):
    from concurrent.futures import ThreadPoolExecutor

    from livemod.runner.batch import FuturesVariantExecutor

    variants = make_variants(RING, sweep([parse_param("count=3:4:2"), parse_param("radius=1")]),
                             None)
    with ThreadPoolExecutor(1) as pool:  # stands in for a Dask client's executor
        results = run_batch(variants, FuturesVariantExecutor(pool), quiet=True)
    assert [r.counts for r in results] == [(3, 3, 2), (4, 4, 2)]


def _slow_failure(variant):
    time.sleep(0.2)
    raise RuntimeError(f"variant {variant.index} lost in transit")


def test_a_variant_whose_future_fails_reports_the_time_it_took(tmp_path):
    from livemod.runner.batch import ProcessPoolVariantExecutor

    variants = make_variants(RING, [{"count": 3}], None)
    [result] = ProcessPoolVariantExecutor(1).map_unordered(_slow_failure, variants)
    assert result.status == "error" and result.error == "RuntimeError: variant 0 lost in transit"
    assert result.elapsed >= 0.2  # it was 0: the clock started when the failure came back


def test_watch_reports_no_write_when_a_run_left_no_mesh(capsys):
    from types import SimpleNamespace

    empty = SimpleNamespace(run_id=3, error=None, arrays=None, status="ok", steps=(),
                            elapsed=0.01)
    cli._report(empty, "out.obj")
    assert capsys.readouterr().out == ("run 3: ok, 0 steps, V=0 E=0 F=0, 0.010 s, "
                                       "no mesh to write\n")


def test_run_says_which_object_of_several_it_counted_and_wrote(tmp_path, capsys):
    script = tmp_path / "two.py"
    script.write_text("load('cube')\nload('tetrahedron')\n")
    assert cli.main(["run", str(script), "-o", str(tmp_path / "out.obj")]) == 0
    out = capsys.readouterr().out
    assert "V=4 E=6 F=4" in out
    assert ("objects: 2 in the scene; the counts above and -o are the current one's "
            "(object 1; --all-objects takes them all)") in out
    single = tmp_path / "one.py"
    single.write_text("load('cube')\n")
    assert cli.main(["run", str(single)]) == 0
    assert "objects:" not in capsys.readouterr().out


def test_all_objects_joins_the_scene_for_run_watch_and_batch(tmp_path, capsys):
    from livemod.dlfl.analysis import component_genera
    from livemod.dlfl.io import load_mesh
    from livemod.runner.batch import make_variants, run_variant

    script = tmp_path / "two.py"
    script.write_text("n = param('n', 2)\nload('cube')\nfor i in range(n):\n    load('torus')\n"
                      "    translate(5 * (i + 1), 0, 0)\n")
    out = tmp_path / "all.obj"
    assert cli.main(["run", str(script), "--all-objects", "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "objects: 3, joined into one mesh for the counts above and -o" in printed
    assert sorted(component_genera(load_mesh(out))) == [0, 1, 1]
    watched = tmp_path / "watched.obj"
    assert cli.main(["run", "--watch", str(script), "--all-objects", "-o", str(watched),
                     "--max-runs", "1"]) == 0
    assert load_mesh(watched).counts() == load_mesh(out).counts()
    variant, = make_variants(str(script), [{"n": 1}], str(tmp_path / "v.obj"),
                             all_objects=True)
    result = run_variant(variant)
    assert result.status == "ok" and result.counts == load_mesh(tmp_path / "v.obj").counts()
    assert sorted(component_genera(load_mesh(tmp_path / "v.obj"))) == [0, 1]


def test_all_objects_keeps_each_object_apart_in_gltf_and_3mf(tmp_path, capsys):
    import pygltflib
    import trimesh

    from livemod.runner.batch import make_variants, run_variant
    from tests.test_io_threemf import lib3mf_model

    script = tmp_path / "two.py"
    script.write_text("load('cube')\nload('soccerball')\ntranslate(5, 0, 0)\n")
    out = tmp_path / "scene.glb"
    assert cli.main(["run", str(script), "--all-objects", "-o", str(out)]) == 0
    assert "objects: 2, joined into one mesh for the counts above; -o keeps them apart" \
        in capsys.readouterr().out
    document = pygltflib.GLTF2().load(str(out))
    assert [node.name for node in document.nodes] == ["cube", "soccerball"]
    assert document.scenes[0].nodes == [0, 1]
    read = trimesh.load(out, process=False)  # a trimesh Scene of the two
    faces = {name: len(geometry.faces) for name, geometry in read.geometry.items()}
    assert sorted(faces.values()) == [12, 116]  # the ball: 12 pentagons, 20 hexagons
    assert read.geometry[document.meshes[1].name].bounds[0][0] > 3.0  # moved apart
    watched = tmp_path / "watched.3mf"
    assert cli.main(["run", "--watch", str(script), "--all-objects", "-o", str(watched),
                     "--max-runs", "1"]) == 0
    _, parts = lib3mf_model(watched)
    assert [(p.GetName(), p.GetTriangleCount()) for p in parts] == \
        [("cube", 12), ("soccerball", 116)]
    assert all(p.IsManifoldAndOriented() for p in parts)
    variant, = make_variants(str(script), [{}], str(tmp_path / "v.3mf"), all_objects=True)
    assert run_variant(variant).status == "ok"
    assert [p.GetName() for p in lib3mf_model(tmp_path / "v.3mf")[1]] == ["cube", "soccerball"]
    alone = tmp_path / "alone.glb"
    assert cli.main(["run", str(script), "-o", str(alone)]) == 0
    assert [node.name for node in pygltflib.GLTF2().load(str(alone)).nodes] == ["soccerball"]


@pytest.mark.parametrize("stopping", [False, True])
def test_a_worker_starting_while_its_pool_is_ended_exits_before_taking_a_variant(stopping):
    # the gap terminate() cannot signal: a worker still in its initializer
    context = multiprocessing.get_context("fork")
    workers = _Workers(context)
    if stopping:
        workers.terminate()  # nothing reported yet: it only raises the flag
    worker = context.Process(target=_worker_started, args=(workers.started, workers.stopping))
    worker.start()
    worker.join(timeout=30)
    assert workers.started.get() == worker.pid
    assert worker.exitcode == (128 + signal.SIGTERM if stopping else 0)
    workers.close()
