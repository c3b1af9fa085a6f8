"""The ``livemod`` command line: view | run | batch | render | info | convert.

This module only parses arguments and dispatches. ``info`` and ``convert`` live
here; the runner and the viewer add their own subcommands through an
``add_commands(subparsers)`` function in ``livemod/runner/cli.py`` and
``livemod/viewer/cli.py`` (which must not import GL at parse time).
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, TextIO

from livemod import __version__

if TYPE_CHECKING:
    from livemod.dlfl import MeshArrays

SUBCOMMAND_MODULES = ("livemod.runner.cli", "livemod.viewer.cli")


def build_parser() -> argparse.ArgumentParser:
    """The top-level parser with every subcommand registered."""
    from livemod.commandline import EXIT_CODES_HELP, Parser

    parser = Parser(
        prog="livemod",
        description="Procedural manifold mesh modeling: run, watch, view and render "
        "DLFL scripts.",
        epilog=f"{EXIT_CODES_HELP}. Errors are one line: livemod: error: <what>: <why>.",
    )
    parser.add_argument("--version", action="version", version=f"livemod {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    _add_info(sub)
    _add_convert(sub)
    for name in SUBCOMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name != name:
                raise
            continue
        module.add_commands(sub)
    for command in sub.choices.values():  # each `livemod COMMAND --help` says them too
        command.epilog = command.epilog or f"{EXIT_CODES_HELP}."
    return parser


def _add_info(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("info", help="print counts, genus per component and face sizes of a mesh")
    p.add_argument("file", help="a .obj, .dlfl, .stl, .ply or .off file, or a built-in shape name")
    p.set_defaults(handler=_info)


def _add_convert(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("convert", help="convert between .obj, .dlfl, .stl, .ply and .off, or to .glb, .gltf or .3mf")
    p.add_argument("input", help="a .obj, .dlfl, .stl, .ply or .off file")
    p.add_argument("output", help="a .obj, .dlfl, .stl, .ply, .off, .glb, .gltf or .3mf file (written atomically)")
    p.set_defaults(handler=_convert)


def _info(args: argparse.Namespace) -> int:
    from livemod.dlfl import DLFLError, mesh_arrays, summarize, validate
    from livemod.dlfl.io import open_mesh

    mesh = open_mesh(args.file)
    arrays = mesh_arrays(mesh)
    summary = summarize(arrays)
    # a missing cube.obj is TopMod's built-in cube: say so, lest it pass for the file
    built_in = "" if os.path.exists(args.file) else " (no such file: the built-in shape)"
    print(f"{args.file}{built_in}")
    print(f"Number of vertices : {summary.vertices}")
    print(f"Number of faces : {summary.faces - summary.holes}")
    print(f"Number of edges : {summary.edges}")
    print(f"Genus : {summary.genus}")
    genera = ", ".join(str(g) for g in summary.component_genera)
    print(f"Components : {summary.components} (genus per component: {genera})")
    sizes = ", ".join(f"{count}x{size}" for size, count in summary.face_sizes.items())
    print(f"Face sizes : {sizes or 'none'}")
    print(f"Holes : {summary.holes}   Point-spheres : {summary.point_spheres}")
    for line in _geometry_lines(arrays):
        print(line)
    for note in mesh.notes:
        print(f"Note : {note}")
    try:
        validate(mesh)
    except DLFLError as exc:
        print(f"Valid : no ({exc})")
        return 1
    print("Valid : yes")
    return 0


def _geometry_lines(arrays: MeshArrays) -> list[str]:
    """``livemod info``'s size, area and volume lines."""
    from livemod.dlfl import bounds, enclosed_volume, surface_area

    low, high = bounds(arrays)
    size = " x ".join(f"{v:.6g}" for v in high - low)
    corners = f"from {', '.join(f'{v:.6g}' for v in low)} to {', '.join(f'{v:.6g}' for v in high)}"
    volume, holes = enclosed_volume(arrays), int(arrays.face_hole.sum())
    if volume is None:
        said = f"none (open: {holes} hole{'s' if holes != 1 else ''})"
    elif volume < 0:
        said = f"{volume:.6g} (inside out: the faces point inward)"
    else:
        said = f"{volume:.6g}"
    return [f"Size : {size} ({corners})", f"Area : {surface_area(arrays):.6g}",
            f"Volume : {said}"]


def _convert(args: argparse.Namespace) -> int:
    """``livemod convert``: the output is checked before the input is read (a large
    mesh takes a while), and its folder made if missing, as ``run -o`` does.

    Raises:
        UsageError: an output suffix no writer takes.
        OSError, DLFLError: the input cannot be read, or the output written.
    """
    from livemod.commandline import check_writable
    from livemod.dlfl import summarize
    from livemod.dlfl.io import open_mesh, save_mesh
    from livemod.dlfl.io.source import show_path
    from livemod.runner.cli import check_mesh_output

    check_mesh_output(args.output)
    check_writable([args.output])
    mesh = open_mesh(args.input)
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    save_mesh(mesh, args.output)
    summary = summarize(mesh)  # faces as `livemod info` counts them: holes apart
    holes = f", {summary.holes} holes" if summary.holes else ""
    print(f"wrote {show_path(args.output)} ({summary.vertices} vertices, {summary.edges} edges, "
          f"{summary.faces - summary.holes} faces{holes})")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``livemod`` command line; returns the process exit code.

    What a subcommand raises becomes one line ``livemod: error: <what>: <why>``,
    never a Python traceback: a :class:`~livemod.commandline.UsageError` exits 2
    (as argparse's own errors do), an OSError or DLFLError (a missing file, a
    malformed mesh, a script error) 1, Ctrl-C 130 (see :mod:`livemod.commandline`).
    """
    from livemod.commandline import FAILED, INTERRUPTED, USAGE, UsageError, describe, error
    from livemod.dlfl.errors import DLFLError

    parser = build_parser()
    args = parser.parse_args(argv)
    _say_repairs_as_notes()
    try:
        return int(args.handler(args) or 0)
    except BrokenPipeError:
        return _reader_went_away()
    except UsageError as exc:
        error(describe(exc))
        return USAGE
    except (DLFLError, OSError) as exc:
        error(describe(exc))
        return FAILED
    except KeyboardInterrupt:
        return INTERRUPTED


def _say_repairs_as_notes() -> None:
    """Print a loader's repair (:class:`~livemod.dlfl.errors.DLFLRepairWarning`) or
    the lines it skipped (:class:`~livemod.dlfl.errors.DLFLSkippedLinesWarning`) as
    one ``livemod: note: ...`` line on standard error, not as a Python warning that
    shows livemod's own source line; other warnings are shown as Python shows them.
    So ``info``, ``convert`` and ``run`` (``--mesh`` and a script's ``load()``) say them."""
    from livemod.commandline import note
    from livemod.dlfl.errors import DLFLRepairWarning, DLFLSkippedLinesWarning

    python_shows = warnings.showwarning

    def show(message: Warning | str, category: type[Warning], filename: str, lineno: int,
             file: TextIO | None = None, line: str | None = None) -> None:
        if issubclass(category, DLFLRepairWarning | DLFLSkippedLinesWarning):
            note(str(message), file)
        else:
            python_shows(message, category, filename, lineno, file, line)

    warnings.showwarning = show


def _reader_went_away() -> int:
    """Exit quietly when whoever reads our output (``| head``) has closed the pipe.

    Standard output is pointed at the null device, so that the interpreter's
    last flush does not fail again; returns 128 + SIGPIPE, as a shell tool
    killed by the signal would.
    """
    from livemod.commandline import READER_LEFT

    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)
    return READER_LEFT


if __name__ == "__main__":
    raise SystemExit(main())
