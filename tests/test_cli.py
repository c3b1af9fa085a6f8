"""The livemod command line: info and convert (run/batch/view/render are tested with
their subsystems)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from livemod.cli import build_parser, main
from livemod.dlfl.io import WRITERS

# the extensions an output may have, as the refusal lists them
WRITTEN = ", ".join(f".{key}" for key in WRITERS)


def test_info_prints_counts_genus_and_sizes_of_a_shape(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", "cube"]) == 0
    out = capsys.readouterr().out
    assert "Number of vertices : 8" in out
    assert "Number of faces : 6" in out
    assert "Number of edges : 12" in out
    assert "Genus : 0" in out
    assert "Components : 1 (genus per component: 0)" in out
    assert "Face sizes : 6x4" in out
    assert "Size : 2 x 2 x 2 (from -1, -1, -1 to 1, 1, 1)" in out
    assert "Area : 24\n" in out and "Volume : 8\n" in out
    assert "Valid : yes" in out


def test_info_says_what_volume_an_open_or_inside_out_mesh_has(tmp_path: Path, capsys) -> None:
    corners = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    quads = ["1 4 3 2", "5 6 7 8", "1 2 6 5", "2 3 7 6", "3 4 8 7", "4 1 5 8"]
    opened, flipped = tmp_path / "open.obj", tmp_path / "flipped.obj"
    opened.write_text(corners + "".join(f"f {q}\n" for q in quads[1:]))
    flipped.write_text(corners + "".join(f"f {' '.join(q.split()[::-1])}\n" for q in quads))
    assert main(["info", str(opened)]) == 0
    assert "Volume : none (open: 1 hole)" in capsys.readouterr().out
    assert main(["info", str(flipped)]) == 0
    assert "Volume : -1 (inside out: the faces point inward)" in capsys.readouterr().out


def test_info_reports_genus_of_a_sample_torus(
        topmod_samples: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", str(topmod_samples / "donuthexa1.obj")]) == 0
    out = capsys.readouterr().out
    assert "Number of vertices : 100" in out
    assert "Genus : 1" in out


def test_info_says_a_missing_file_named_as_a_shape_is_the_built_in_one(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)
    assert main(["info", "cube.obj"]) == 0
    assert capsys.readouterr().out.startswith("cube.obj (no such file: the built-in shape)\n")
    (tmp_path / "cube.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    assert main(["info", "cube.obj"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("cube.obj\n") and "Number of vertices : 3" in out


def test_info_of_a_missing_file_is_one_clear_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", "no-such-mesh.obj"]) == 1
    err = capsys.readouterr().err
    # a name with an extension is meant as a file: the folder, and no list of shapes
    assert err == f"livemod: error: no file no-such-mesh.obj in {os.getcwd()}\n"
    assert err.count("\n") == 1


@pytest.mark.parametrize("command", [
    ["run", "{missing}"], ["run", "--watch", "{missing}"], ["params", "{missing}"],
    ["batch", "{missing}", "--param", "n=1"], ["render", "{missing}", "-o", "{tmp}/x.png"],
    ["view", "{missing}"], ["run", "{script}", "--mesh", "{missing}"],
    ["batch", "{script}", "--param", "n=1", "--mesh", "{missing}"],
    ["render", "{script}", "--mesh", "{missing}", "-o", "{tmp}/x.png"],
])
def test_every_command_says_a_missing_input_the_same_way(command, tmp_path, capsys) -> None:
    script, missing = tmp_path / "s.py", tmp_path / "gone.py"
    script.write_text(f"n = param('n', 0)\nopen({str(tmp_path / 'ran')!r}, 'w').close()\n")
    argv = [a.format(missing=missing, script=script, tmp=tmp_path) for a in command]
    assert main(argv) == 1
    assert capsys.readouterr().err == (f"livemod: error: cannot read {missing}: "
                                       "No such file or directory\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.py"]  # nothing ran, nothing written


def test_help_states_the_exit_codes(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["--help"])
    assert stop.value.code == 0
    assert " ".join(capsys.readouterr().out.split()).endswith(
        "exit codes: 0 done; 1 the script, a file or a variant failed; 2 the command line is "
        "wrong; 130 interrupted (Ctrl-C); 141 the reader of the output left (| head). Errors "
        "are one line: livemod: error: <what>: <why>.")


def test_convert_round_trips_through_dlfl(
        tmp_path: Path, topmod_samples: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "cube.dlfl"
    assert main(["convert", str(topmod_samples / "cube.obj"), str(out)]) == 0
    assert "8 vertices, 12 edges, 6 faces" in capsys.readouterr().out
    assert main(["info", str(out)]) == 0
    assert "Number of faces : 6" in capsys.readouterr().out


def test_convert_counts_faces_as_info_does(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    triangle = tmp_path / "tri.obj"
    triangle.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")  # open: one face, one hole
    assert main(["convert", str(triangle), str(tmp_path / "tri.dlfl")]) == 0
    assert capsys.readouterr().out.endswith("(3 vertices, 3 edges, 1 faces, 1 holes)\n")


def test_convert_checks_the_output_before_reading_and_makes_its_folder(tmp_path, capsys) -> None:
    (tmp_path / "file").write_text("")
    target = tmp_path / "file" / "c.obj"
    # the input is missing too: the output is checked first (a large input takes a while)
    assert main(["convert", str(tmp_path / "gone.obj"), str(target)]) == 1
    assert capsys.readouterr().err == (f"livemod: error: cannot write {target}: "
                                       f"{tmp_path / 'file'} is a file, not a folder\n")
    assert main(["convert", "cube", str(tmp_path / "c.txt")]) == 2
    assert capsys.readouterr().err == (f"livemod: error: output {tmp_path / 'c.txt'} must end "
                                       f"with one of {WRITTEN}\n")
    assert main(["convert", "cube", str(tmp_path / "new" / "c.stl")]) == 0
    assert (tmp_path / "new" / "c.stl").exists()


def test_a_write_into_a_missing_folder_names_the_target(tmp_path: Path) -> None:
    from livemod.dlfl.io import save_mesh
    from livemod.dlfl.shapes import cube

    target = tmp_path / "missing" / "c.obj"
    with pytest.raises(FileNotFoundError, match=f"cannot write {target}: No such file"):
        save_mesh(cube(), target)


def test_every_subcommand_is_registered() -> None:
    parser = build_parser()
    choices = parser._subparsers._group_actions[0].choices  # type: ignore[union-attr]
    assert {"info", "convert", "run", "batch", "view", "render"} <= set(choices)


@pytest.mark.parametrize("command", [["run"], ["view"], ["render", "-o", "x.png"],
                                     ["batch", "--param", "n=1"]])
def test_every_command_that_runs_a_script_takes_a_selection(command: list[str]) -> None:
    args = build_parser().parse_args(
        [command[0], "s.py", *command[1:], "--select", "faces=1,2", "--select", "corners=3"])
    assert args.select == ["faces=1,2", "corners=3"]


def _first_line_then_close(args: list[str]) -> tuple[str, str, int]:
    """Run ``livemod *args``, read one line of its output and close the pipe, as
    ``| head -1`` does: ``(that line, all of stderr, exit code)``."""
    with subprocess.Popen([sys.executable, "-m", "livemod", *args],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE) as proc:
        assert proc.stdout is not None and proc.stderr is not None
        line = proc.stdout.readline().decode()
        proc.stdout.close()
        errors = proc.stderr.read().decode()
        return line, errors, proc.wait(timeout=60)


def test_a_closed_pipe_ends_the_command_quietly(tmp_path: Path) -> None:
    # `livemod run --steps script | head -1`: the reader leaves after one line
    script = tmp_path / "many.py"
    script.write_text("for i in range(20000):\n    createVertex((i, 0.0, 0.0))\n")
    assert _first_line_then_close(["run", str(script), "--steps"])[1:] == ("", 141)


def test_a_closed_pipe_ends_a_printing_script_quietly(tmp_path: Path) -> None:
    # `livemod run script | head -1` where the script itself prints
    script = tmp_path / "chatty.py"
    script.write_text("for i in range(200000):\n    print(i)\n")
    assert _first_line_then_close(["run", str(script)]) == ("0\n", "", 141)


def test_a_scripts_own_broken_pipe_is_still_its_error(tmp_path: Path) -> None:
    script = tmp_path / "sock.py"
    script.write_text("print('hello')\nraise BrokenPipeError(32, 'its own socket')\n")
    done = subprocess.run([sys.executable, "-m", "livemod", "run", str(script)],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 1 and done.stdout == "hello\n"
    assert "sock.py:2: BrokenPipeError: [Errno 32] its own socket" in done.stderr


@pytest.mark.parametrize(("option", "message"), [
    (["--turntable", "-3"], "the frame count must be a whole number >= 0, not '-3'"),
    (["--turntable", "2.5"], "the frame count must be a whole number >= 0, not '2.5'"),
    (["--elevation", "nan"], "strictly between -90 and 90, not 'nan'"),
    (["--elevation", "90"], "strictly between -90 and 90, not '90'"),
    (["--elevation", "up"], "strictly between -90 and 90, not 'up'"),
])
def test_render_refuses_frame_counts_and_elevations_it_cannot_draw(option, message, capsys):
    with pytest.raises(SystemExit) as stop:
        build_parser().parse_args(["render", "cube", "-o", "x.png", *option])
    assert stop.value.code == 2 and message in capsys.readouterr().err
    args = build_parser().parse_args(["render", "cube", "-o", "x.png", "--elevation", "-89.5"])
    assert args.elevation == -89.5 and args.turntable == 0


def test_render_checks_its_output_before_the_script_runs(tmp_path, capsys):
    script = tmp_path / "marks.py"
    script.write_text(f"open({str(tmp_path / 'ran')!r}, 'w').close()\nload('cube')\n")
    (tmp_path / "file").write_text("")
    for out, frames in ((tmp_path / "file" / "x.png", "0"), (tmp_path / "file" / "t.gif", "2"),
                        (tmp_path / "file" / "seq" / "f_{frame}.png", "2")):
        assert main(["render", str(script), "-o", str(out), "--turntable", frames]) == 1
        first = str(out).format(frame=0)
        assert capsys.readouterr().err == (f"livemod: error: cannot write {first}: "
                                           f"{tmp_path / 'file'} is a file, not a folder\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file", "marks.py"]


def test_a_repair_while_loading_is_one_note_not_a_python_warning(tmp_path: Path, capsys) -> None:
    import warnings

    from tests.meshes import CUBE_FACES, CUBE_POSITIONS

    flipped = [CUBE_FACES[0][::-1], *CUBE_FACES[1:]]
    lines = [f"v {x} {y} {z}" for x, y, z in CUBE_POSITIONS]
    lines += ["f " + " ".join(str(v + 1) for v in face) for face in flipped]
    (tmp_path / "flip.obj").write_text("\n".join(lines) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("default")  # the suite turns warnings into errors
        assert main(["convert", str(tmp_path / "flip.obj"), str(tmp_path / "out.obj")]) == 0
    err = capsys.readouterr().err
    assert err.startswith("livemod: note: ") and "re-oriented 1 faces (line 9)" in err
    assert "DLFLRepairWarning" not in err and "livemod/" not in err.replace(str(tmp_path), "")


def _livemod(args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "livemod", *args], cwd=cwd,
                          capture_output=True, text=True, timeout=60, check=False)


SKIPPED_NOTE = "livemod: note: odd.obj: ignored 1 line not understood: line 4 'hello world'\n"


def test_info_convert_and_run_say_the_lines_a_reader_skipped(tmp_path: Path) -> None:
    (tmp_path / "odd.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nhello world\nf 1 2 3\n")
    (tmp_path / "pass.py").write_text("x = 1\n")
    (tmp_path / "loads.py").write_text("load('odd.obj')\n")
    info = _livemod(["info", "odd.obj"], tmp_path)
    assert info.returncode == 0 and info.stderr == SKIPPED_NOTE
    assert "Note : odd.obj: ignored 1 line not understood: line 4 'hello world'\n" in info.stdout
    convert = _livemod(["convert", "odd.obj", "out.ply"], tmp_path)
    assert convert.returncode == 0 and convert.stderr == SKIPPED_NOTE
    run = _livemod(["run", "pass.py", "--mesh", "odd.obj", "-o", "out.obj"], tmp_path)
    assert run.returncode == 0 and run.stderr == SKIPPED_NOTE
    loads = _livemod(["run", "loads.py"], tmp_path)
    assert loads.returncode == 0
    assert loads.stderr == SKIPPED_NOTE.replace("odd.obj", str(tmp_path / "odd.obj"))


def test_info_of_a_folder_says_it_is_a_folder(tmp_path: Path) -> None:
    (tmp_path / "meshes").mkdir()
    done = _livemod(["info", "meshes"], tmp_path)
    assert (done.returncode, done.stderr) == (1, "livemod: error: meshes: is a folder, not a mesh file\n")


def test_info_of_a_file_holding_no_geometry_names_the_line(tmp_path: Path) -> None:
    (tmp_path / "g.stl").write_text("solid x\nthis is garbage\nendsolid x\n")
    done = _livemod(["info", "g.stl"], tmp_path)
    assert done.returncode == 1
    assert done.stderr == ("livemod: error: g.stl:2: 'this' is not part of a facet (an ASCII "
                           "STL file is 'solid NAME', facets, 'endsolid NAME')\n")


def test_messages_quote_a_file_name_only_where_a_shell_needs_it(tmp_path: Path) -> None:
    (tmp_path / "my mesh.obj").write_text("v 0 0 0\nv 1 x 0\n")
    done = _livemod(["info", "my mesh.obj"], tmp_path)
    assert done.stderr == "livemod: error: 'my mesh.obj':2: bad number 'x'\n"
    done = _livemod(["info", "no such.obj"], tmp_path)
    assert done.stderr == f"livemod: error: no file 'no such.obj' in {tmp_path}\n"


@pytest.mark.parametrize(("argv", "said"), [
    (["rn", "x.py"], "argument COMMAND: invalid choice: 'rn'; did you mean 'run'? (choose from "
                     "'info', 'convert', 'run', "),
    (["render", "x.py", "--background", "drak"],
     "argument --background: invalid choice: 'drak'; did you mean 'dark'? (choose from 'dark', "
     "'light', 'transparent')"),
])
def test_a_misspelt_choice_gets_the_likely_one(argv, said, capsys) -> None:
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    assert said in capsys.readouterr().err


def test_a_script_error_shows_its_message_once(tmp_path: Path, capsys) -> None:
    script = tmp_path / "typo.py"
    script.write_text("load('cube')\nsubdivide('catmul-clark')\n")
    assert main(["run", str(script)]) == 1
    err = capsys.readouterr().err
    assert err.count("valid schemes:") == 1 and err.count("InvalidArgumentError") == 1
    assert err.splitlines()[-1].startswith(
        f"livemod: error: {script}:2: InvalidArgumentError: unknown subdivision scheme "
        "'catmul-clark'; did you mean 'catmull-clark'? valid schemes: 12.6.4, ")
    assert "    subdivide('catmul-clark')" in err  # the traceback's line of the script
