"""The ``view`` and ``render`` subcommands (no GL is imported at parse time).

``livemod.cli`` calls :func:`add_commands`; :func:`main` parses only these two
subcommands, for tests and ``python -m``-free use.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from livemod.commandline import (
    DONE,
    FAILED,
    UsageError,
    check_readable,
    check_writable,
    describe,
    error,
    note,
    usage_errors,
    warning,
)
from livemod.dlfl.io import open_mesh
from livemod.dlfl.scene import Selection
from livemod.runner.cli import (
    add_all_objects_option,
    add_face_budget_option,
    add_seed_option,
    add_select_option,
    check_run_files,
    script_values,
    selection_of,
    whole_number_option,
)
from livemod.viewer.script_session import SCRIPT_SUFFIXES


def parse_size(text: str) -> tuple[int, int]:
    """``"800x600"`` -> ``(800, 600)``; raises ArgumentTypeError otherwise."""
    try:
        width, height = (int(part) for part in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size must look like 800x600, not {text!r}") from None
    if width <= 0 or height <= 0:
        raise argparse.ArgumentTypeError(f"size must be positive, not {text!r}")
    return width, height


parse_frames = whole_number_option("the frame count", 0)  # ``--turntable``
parse_step = whole_number_option("the step", 0)  # ``--step``, 0-based as run --steps counts


def _float_or_nan(text: str) -> float:
    """``text`` as a float, or NaN when it is not a number (the callers refuse NaN
    with a message of their own)."""
    try:
        return float(text)
    except ValueError:
        return math.nan


def parse_elevation(text: str) -> float:
    """``--elevation`` in degrees, strictly between -90 and 90 (the camera looks
    straight down or up at the poles, where its turn is undefined).

    Raises:
        argparse.ArgumentTypeError: not a number in that range (argparse shows it).
    """
    degrees = _float_or_nan(text)
    if not -90.0 < degrees < 90.0:
        raise argparse.ArgumentTypeError(f"the elevation must be a number of degrees "
                                         f"strictly between -90 and 90, not {text!r}")
    return degrees


def parse_yaw(text: str, what: str = "the yaw") -> float:
    """``--yaw`` in degrees around the up axis (any finite number; 0 looks from +z).

    Raises:
        argparse.ArgumentTypeError: not a finite number.
    """
    degrees = _float_or_nan(text)
    if not math.isfinite(degrees):
        raise argparse.ArgumentTypeError(f"{what} must be a number of degrees, not {text!r}")
    return degrees


def parse_margin(text: str) -> float:
    """``--margin``: the empty border at each side, a share of the frame from 0 to
    below 0.5, or a percentage such as ``10%``.

    Raises:
        argparse.ArgumentTypeError: not a number in that range.
    """
    share = _share(text)
    if not 0.0 <= share < 0.5:
        raise argparse.ArgumentTypeError(f"the margin is a share of the frame from 0 to "
                                         f"below 0.5 (or 0% to below 50%), not {text!r}")
    return share


def parse_zoom(text: str) -> float:
    """``--zoom``: a factor above 0 (2 draws the mesh twice as large).

    Raises:
        argparse.ArgumentTypeError: not a finite number above 0.
    """
    factor = _float_or_nan(text)
    if not (math.isfinite(factor) and factor > 0.0):
        raise argparse.ArgumentTypeError(f"the zoom must be a number above 0 (2 draws the "
                                         f"mesh twice as large), not {text!r}")
    return factor


def _share(text: str) -> float:
    """``0.02`` or ``2%`` as 0.02; NaN when it is neither."""
    given = text.strip()
    return _float_or_nan(given[:-1]) / 100 if given.endswith("%") else _float_or_nan(given)


def parse_turn(text: str) -> float:
    """``--turn``: degrees the camera turns around the up axis from one frame of a
    film to the next (any finite number). Raises ArgumentTypeError otherwise."""
    return parse_yaw(text, "the turn")


def parse_threshold(text: str) -> float:
    """``--threshold``: a share of pixels from 0 to 1, or a percentage such as ``2%``.

    Raises:
        argparse.ArgumentTypeError: not a number, or outside 0 to 1 (0% to 100%).
    """
    share = _share(text)
    if not 0.0 <= share <= 1.0:
        raise argparse.ArgumentTypeError(f"the threshold is a share of the pixels from 0 to "
                                         f"1 (or 0% to 100%), not {text!r}")
    return share


def parse_section(text: str) -> tuple[int, float | None]:
    """``--section`` as ``(axis, at)``: ``x=0.25`` cuts away what lies beyond x = 0.25,
    a bare ``y`` cuts through the middle of the scene (``at`` None).

    Raises:
        argparse.ArgumentTypeError: no axis x, y or z, or a coordinate that is not
            a finite number.
    """
    name, _, value = text.partition("=")
    axis = "xyz".find(name.strip().lower())
    at = _float_or_nan(value) if value.strip() else None
    if len(name.strip()) != 1 or axis < 0 or (at is not None and not math.isfinite(at)):
        raise argparse.ArgumentTypeError(f"--section takes x, y or z, optionally =COORDINATE "
                                         f"(as in y=0.5), not {text!r}")
    return axis, at


def section_through(section: tuple[int, float | None] | None,
                    parts: Sequence[Any]) -> tuple[int, float] | None:
    """A :attr:`Style.section` from a parsed ``--section``: a bare axis cuts through
    the middle of the ``parts`` drawn (MeshArrays or None; the origin if none)."""
    if section is None or section[1] is not None:
        return section  # type: ignore[return-value]
    points = [part.positions for part in parts if part is not None and len(part.positions)]
    if not points:
        return section[0], 0.0
    coordinates = np.concatenate(points)[:, section[0]]
    return section[0], float(coordinates.min() + coordinates.max()) / 2


def add_commands(subparsers: Any) -> None:
    """Register ``view`` and ``render`` on the ``livemod`` subparsers."""
    view = subparsers.add_parser("view", help="open the live window on a script")
    view.add_argument("script", help="the Python script to watch and run")
    view.add_argument("--mesh", help="mesh every run starts from (.obj .dlfl .stl .ply)")
    add_seed_option(view)
    add_face_budget_option(view)
    view.add_argument("--size", type=parse_size, default=(1280, 800), help="WxH window size")
    view.add_argument("--poll", action="store_true",
                      help="poll for changes (for file systems that send no events)")
    view.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                      help="a declared script parameter to start with, repeatable")
    view.add_argument("-o", "--output", metavar="OUT",
                      help="write the result here after every successful run "
                           "(.obj .dlfl .stl .ply)")
    add_all_objects_option(view)
    add_select_option(view)
    view.set_defaults(handler=_view)
    _add_render(subparsers)


def _add_render(subparsers: Any) -> None:
    render = subparsers.add_parser(
        "render", help="render a script's result or a mesh to PNG, a PNG sequence, a GIF, "
                       "an animated WebP or an MP4")
    render.add_argument("input", help="a script (.py) or a mesh file or shape name")
    render.add_argument("-o", "--output", required=True,
                        help="out.png, out.gif, out.webp, out.mp4 (needs livemod[video]), a "
                             "folder, or a pattern with {frame} / %%03d")
    render.add_argument("--mesh", help="mesh a script starts from")
    add_seed_option(render)
    render.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a declared script parameter, repeatable")
    add_select_option(render)
    render.add_argument("--size", type=parse_size, default=(800, 600), help="WxH pixels")
    render.add_argument("--turntable", type=parse_frames, default=0, metavar="N",
                        help="N frames evenly spaced around the up axis")
    render.add_argument("--fps", type=float, default=25.0,
                        help="frames per second of a GIF, WebP or MP4 (default: 25)")
    render.add_argument("--elevation", type=parse_elevation, default=25.0, metavar="DEG",
                        help="camera height above the horizon in degrees")
    render.add_argument("--yaw", type=parse_yaw, default=30.0, metavar="DEG",
                        help="camera turn around the up axis in degrees (0 looks from +z; "
                             "default 30); a turntable starts there")
    render.add_argument("--margin", type=parse_margin, default=None, metavar="SHARE",
                        help="empty border at each side, a share of the frame where the "
                             "view is tightest, e.g. 0.1 or 10%% (0 fills the frame; "
                             "default: a thin border)")
    render.add_argument("--zoom", type=parse_zoom, default=1.0, metavar="FACTOR",
                        help="draw the mesh FACTOR times as large as framed (what falls "
                             "outside is cut)")
    render.add_argument("--refit", action="store_true",
                        help="with --turntable: frame each frame at its own angle, so the "
                             "mesh fills every one (default: one framing for the orbit)")
    _add_render_steps(render)
    _add_render_style(render)
    render.add_argument("--reference", metavar="IMAGE",
                        help="compare the picture with this one: exit 1 and write "
                             "OUTPUT.diff.png when they differ (golden-image tests)")
    render.add_argument("--threshold", type=parse_threshold, default=None, metavar="SHARE",
                        help="with --reference: the share of pixels that may differ "
                             "(by more than 10%% in a channel), e.g. 0.02 or 2%% "
                             "(default: 1%%)")
    render.set_defaults(handler=_render)


def _add_render_steps(render: argparse.ArgumentParser) -> None:
    """``livemod render``'s options that film a script's steps."""
    render.add_argument("--steps", action="store_true",
                        help="film the build: one frame per modeling step of the script "
                             "(a GIF, WebP, MP4, folder or PNG pattern)")
    render.add_argument("--step", type=parse_step, default=None, metavar="K",
                        help="draw the scene as step K left it (0-based, as run --steps "
                             "numbers the steps)")
    render.add_argument("--turn", type=parse_turn, default=0.0, metavar="DEG",
                        help="with --steps: turn the camera DEG degrees each frame")
    render.add_argument("--captions", action="store_true",
                        help="with --steps or --step: draw each step's number, label and "
                             "script line into its frame")


def _add_render_style(render: argparse.ArgumentParser) -> None:
    """``livemod render``'s options of what is drawn and how."""
    render.add_argument("--preview", action="store_true",
                        help="draw TopMod's patch preview of every object")
    render.add_argument("--labels", nargs="?", const="faces,edges,vertices", default="",
                        help="id labels: comma list of faces, edges, vertices (all if bare)")
    render.add_argument("--ortho", action="store_true", help="orthographic projection")
    render.add_argument("--vertices", action="store_true", help="draw vertices")
    render.add_argument("--no-edges", action="store_true", help="hide the edges")
    render.add_argument("--grid", action="store_true",
                        help="draw a ground grid and the x, y, z axes")
    render.add_argument("--background", choices=("dark", "light", "transparent"),
                        default="dark", help="background (default: dark; transparent: "
                                             "PNG with alpha)")
    render.add_argument("--smooth", action="store_true",
                        help="smooth shading instead of flat faces (edges between faces "
                             "over 45 degrees apart stay sharp)")
    render.add_argument("--no-colors", action="store_true",
                        help="every face in the modelling colour, not in its own colour")
    render.add_argument("--section", type=parse_section, default=None, metavar="AXIS[=AT]",
                        help="cut the meshes at a plane and cap the cut solids: x=0.5 cuts "
                             "away what lies beyond x = 0.5; a bare x, y or z cuts "
                             "through the middle")
    render.add_argument("--samples", type=int, default=None,
                        help="MSAA samples; default 4 for one frame, 0 for a turntable "
                        "(edges are anti-aliased in the shader; MSAA triples the cost "
                        "on software GL)")


def _view(args: argparse.Namespace) -> int:
    """``livemod view``: the window's exit code.

    Raises:
        UsageError, OSError, DLFLError: a bad ``-o`` or ``--set``, or a file that
            cannot be read or written (see
            :func:`~livemod.runner.cli.check_run_files`); before the window opens.
    """
    from .window import ViewOptions, view

    check_run_files(args.script, args.mesh, args.output)
    values = _given_values(args.script, args.set)
    return view(ViewOptions(args.script, mesh_path=args.mesh, seed=args.seed,
                            size=args.size, poll=args.poll,
                            parameters=values, selection=selection_of(args),
                            output=args.output, all_objects=args.all_objects))


def _given_values(script: str, texts: list[str]) -> dict[str, Any]:
    """The ``--set`` values checked against the script's declarations.

    Raises:
        UsageError: a name the script does not declare, a value that does not
            fit, or ``--set`` for a mesh file.
        DLFLError, OSError: the script's own fault, or it cannot be read (see
            :func:`~livemod.runner.cli.script_values`).
    """
    if texts and Path(script).suffix.lower() not in SCRIPT_SUFFIXES:
        raise UsageError(f"--set needs a script, not {script!r}")
    return script_values(script, texts)


def _render(args: argparse.Namespace) -> int:
    """``livemod render``: 0 when written (and matching ``--reference``), 1 when
    the input, the GL or the comparison fails.

    Raises:
        UsageError, OSError, DLFLError: a bad argument or file (see
            :func:`_render_inputs`, :func:`_reference_of`), all before the script
            runs: a long run must not end in a bad argument.
    """
    from .headless import NoOffscreenGL, Offscreen

    inputs = _render_inputs(args)
    reference = _reference_of(args)
    try:
        with usage_errors():  # a size or MSAA level this GL cannot make
            offscreen = Offscreen(args.size, samples=_samples(args))
    except NoOffscreenGL as exc:
        error(str(exc))
        return FAILED
    try:
        paths = _render_to(args, offscreen, *inputs)
    finally:
        offscreen.release()
    print(f"wrote {paths[0]}" if len(paths) == 1 else f"wrote {len(paths)} frames: "
          f"{paths[0]} .. {paths[-1]}")
    if reference is None:
        return DONE
    return _check_against(reference, args.reference, paths[0], args.threshold)


def _reference_of(args: argparse.Namespace) -> np.ndarray | None:
    """The ``--reference`` picture, checked against the render it is for (None without).

    Raises:
        UsageError: no such picture, one of another size, a turntable, an MP4
            output, or ``--threshold`` without ``--reference``: exit 2, as ``cmp`` exits when
            it cannot compare (1 says that the pictures differ).
    """
    from .compare import read_picture

    if args.reference is None:
        if args.threshold is not None:
            raise UsageError("--threshold needs --reference")
        return None
    if args.turntable > 1:
        raise UsageError("--reference compares one picture: leave out --turntable")
    if Path(args.output).suffix.lower() == ".mp4":  # no picture reader takes it back
        raise UsageError(f"--reference compares a PNG, GIF or WebP picture, not "
                         f"{Path(args.output).name} (H.264 is lossy too)")
    if Path(args.reference).resolve() == Path(args.output).resolve():
        raise UsageError(f"-o would write over the reference {args.reference}: render to "
                         "another file (copy it over the reference to update it)")
    try:
        check_readable(args.reference)
    except OSError as exc:
        raise UsageError(f"the reference picture: {describe(exc)}") from None
    with usage_errors():
        reference = read_picture(args.reference, "reference picture")
    if reference.shape[1::-1] != tuple(args.size):
        raise UsageError(f"the reference {args.reference} is {reference.shape[1]}x"
                         f"{reference.shape[0]} pixels and the render "
                         f"{args.size[0]}x{args.size[1]} (give --size)")
    return reference


def _check_against(reference: np.ndarray, reference_path: str, rendered: Path,
                   threshold: float | None) -> int:
    """Compare the picture written at ``rendered`` with ``reference``; 0 when they
    match, else 1 with ``OUTPUT.diff.png`` written (the differing pixels in red)."""
    from .compare import THRESHOLD, difference_picture, image_difference, read_picture
    from .imagefiles import save_png

    limit = THRESHOLD if threshold is None else threshold
    difference = image_difference(read_picture(rendered), reference)
    summary = difference.summary(reference_path, limit)
    if difference.matches(limit):
        print(f"matches: {summary}")
        return DONE
    diff_path = rendered.with_name(f"{rendered.stem}.diff.png")
    save_png(diff_path, difference_picture(reference, difference))
    error(f"{rendered} differs: {summary}; see {diff_path}")
    return FAILED


def _render_to(args: argparse.Namespace, offscreen: Any, values: dict[str, Any],
               labels: frozenset[str], selection: Selection | None) -> list[Path]:
    """Run or load ``livemod render``'s input and draw it into ``offscreen``."""
    from livemod.progress import ProgressBar

    from .headless import Framing, render_arrays

    if args.steps or args.step is not None:
        return _film_to(args, offscreen, values, _render_style(args, labels, None, None),
                        selection)
    arrays, preview, others = _load_input(args.input, args.mesh, args.preview, values,
                                          selection, args.seed)
    if arrays is None and others is None:
        warning(f"{args.input} left no mesh; the picture shows an empty scene")
    elif args.preview and preview is None:
        warning("no patch preview available; drawing the mesh")
    style = _render_style(args, labels, arrays, others)
    progress = ProgressBar("rendering") if args.turntable > 1 else None
    return render_arrays(arrays, args.output, turntable=args.turntable,
                         elevation=args.elevation, yaw=args.yaw, style=style, preview=preview,
                         progress=progress, ortho=args.ortho, offscreen=offscreen,
                         others=others, fps=args.fps,
                         framing=Framing(args.margin, args.zoom, args.refit))


def _render_style(args: argparse.Namespace, labels: frozenset[str], arrays: Any,
                  others: Any) -> Any:
    """The :class:`~.renderer.Style` of ``livemod render``'s options (a bare
    ``--section`` cuts through the middle of ``arrays`` and ``others``)."""
    from .renderer import BACKGROUNDS, Style

    return Style(edges=not args.no_edges, vertices=args.vertices, preview=args.preview,
                 labels=labels, grid=args.grid, background=BACKGROUNDS[args.background],
                 smooth=args.smooth, section=section_through(args.section, (arrays, others)),
                 colors=not args.no_colors)


def _film_to(args: argparse.Namespace, offscreen: Any, values: dict[str, Any], style: Any,
             selection: Selection | None) -> list[Path]:
    """``render --steps`` (a frame per step) or ``--step K`` (one): run the script,
    draw the shots into ``offscreen`` and write them.

    Raises:
        DLFLError: the script failed, or has no step K (or none at all).
    """
    from livemod.progress import ProgressBar
    from livemod.runner.headless import report_selection

    from .film import render_film, script_shots
    from .headless import Framing
    from .imagefiles import write_images
    from .pictures import View

    shots = script_shots(args.input, which=None if args.steps else {args.step},
                         mesh_path=args.mesh, seed=args.seed, parameters=values,
                         selection=selection)
    report_selection(shots.outcome.run)
    view = View(offscreen.size, args.elevation, args.yaw, style, args.ortho,
                Framing(args.margin, args.zoom))
    frames = render_film(offscreen, shots, view, turn=args.turn, captions=args.captions,
                         progress=ProgressBar("rendering") if args.steps else None)
    return write_images(args.output, frames, args.fps)


def _check_film(args: argparse.Namespace, is_script: bool) -> None:
    """Refuse film options that do not go together (see :func:`_render_inputs`)."""
    filming = args.steps or args.step is not None
    if args.steps and args.step is not None:
        raise UsageError("--steps films every step and --step K draws one: give one of them")
    if filming and not is_script:
        raise UsageError(f"--steps and --step need a script, not {args.input!r}")
    if filming and (args.turntable or args.preview):
        raise UsageError("--steps and --step draw the steps as they are: leave out "
                         "--turntable and --preview (--turn DEG turns the camera per frame)")
    if args.steps and args.reference is not None:
        raise UsageError("--reference compares one picture: give --step K, not --steps")
    output = args.output
    if args.steps and Path(output).suffix.lower() == ".png" and not ("{" in output
                                                                      or "%" in output):
        raise UsageError(f"--steps films a frame per step: write a .gif, .webp or .mp4, a "
                         f"folder, or a name with {{frame}}, not one PNG ({output})")
    if args.turn and not args.steps:
        raise UsageError("--turn turns the camera from frame to frame of --steps")
    if args.captions and not filming:
        raise UsageError("--captions needs --steps or --step")


def _render_inputs(args: argparse.Namespace,
                   ) -> tuple[dict[str, Any], frozenset[str], Selection | None]:
    """``livemod render``'s parameter values, label kinds and selection, with the
    files it reads and writes checked; a GIF asked for faster than GIFs play gets
    a note (it is written at the fastest rate that plays, see
    :func:`~livemod.viewer.imagefiles.write_images`).

    Raises:
        UsageError: a bad ``--set``, ``-o``, ``--fps``, ``--labels``,
            ``--refit`` without a turntable, film options that do not go together
            (``--steps`` with ``--step``, ``--turntable``, ``--preview`` or
            ``--reference``; ``--turn`` or ``--captions`` alone), or ``--select``,
            ``--mesh``, ``--steps`` or ``--step`` for a mesh input (the message says
            which).
        OSError: a script or ``--mesh`` that cannot be read, or an output that
            cannot be written.
        DLFLError: the script's own fault found while checking ``--set``.
    """
    from .imagefiles import check_output, gif_rate_note
    from .renderer import LABEL_KINDS

    is_script = Path(args.input).suffix.lower() in SCRIPT_SUFFIXES
    if args.refit and args.turntable < 2:
        raise UsageError("--refit frames each turntable frame at its own angle: give "
                         "--turntable N (a single frame is framed at its angle already)")
    _check_film(args, is_script)
    frames = 2 if args.steps else max(args.turntable, 1)  # a film: several, count unknown
    with usage_errors():
        paths = check_output(args.output, frames, args.size,
                             transparent=args.background == "transparent", fps=args.fps)
    if is_script:
        check_run_files(args.input, args.mesh, None)
    elif args.mesh is not None:  # it would be ignored: the input is the mesh drawn
        raise UsageError(f"--mesh needs a script (it is the mesh the script starts "
                         f"from), not {args.input!r}")
    check_writable(paths)
    values = _given_values(args.input, args.set)
    labels = frozenset(k.strip() for k in args.labels.split(",") if k.strip())
    if labels - set(LABEL_KINDS):
        raise UsageError(f"unknown label kinds: {sorted(labels - set(LABEL_KINDS))}")
    selection = selection_of(args)
    if selection is not None and not is_script:
        raise UsageError(f"--select needs a script, not {args.input!r}")
    slower = gif_rate_note(paths, args.fps)  # written at the rate it plays at
    if slower is not None:
        note(slower)
    return values, labels, selection


def _samples(args: argparse.Namespace) -> int:
    """The MSAA level: as given, or 4 for one frame and 0 for turntable and film frames."""
    if args.samples is not None:
        return int(args.samples)
    return 0 if args.turntable > 1 or args.steps else 4


def _load_input(path: str, mesh_path: str | None, want_preview: bool,
                values: dict[str, Any] | None = None,
                selection: Selection | None = None,
                seed: int | None = 0) -> tuple[Any, Any, Any]:
    """``(arrays, preview or None, other objects or None)`` of a script's result (run
    with the parameter ``values``, ``selection`` and ``seed``) or of a mesh file."""

    if Path(path).suffix.lower() in SCRIPT_SUFFIXES:
        return _run_for_render(path, mesh_path, want_preview, values, selection, seed)
    from livemod.dlfl import mesh_arrays

    arrays = mesh_arrays(open_mesh(path))
    return arrays, _patch_preview(arrays, None) if want_preview else None, None


def _patch_preview(arrays: Any, others: Any) -> Any:
    """The patch preview of ``arrays`` and the ``others`` (a picture has no frame
    time to keep: a GPU's triangle budget)."""
    from livemod.runner.preview import (
        GPU_TRIANGLE_BUDGET,
        PreviewRequest,
        PreviewSettings,
        make_preview,
    )

    objects = (arrays,) if others is None else (arrays, others)
    return make_preview(PreviewRequest(objects, PreviewSettings(budget=GPU_TRIANGLE_BUDGET)))


def _run_for_render(path: str, mesh_path: str | None, want_preview: bool,
                    values: dict[str, Any] | None = None,
                    selection: Selection | None = None,
                    seed: int | None = 0) -> tuple[Any, Any, Any]:
    """Run a script headless (with the parameter ``values``, ``selection`` and ``seed``);
    ``(arrays, preview, others)`` of the mesh it leaves and its other objects.

    Raises:
        ScriptFailedError: the script failed (the message names file and line).
        InvalidArgumentError: ``values`` names a parameter the run did not declare.
    """
    from livemod.dlfl import mesh_arrays
    from livemod.runner import run_outcome
    from livemod.runner.headless import check_outcome, report_selection
    from livemod.runner.results import current_mesh, snapshot_others

    outcome = run_outcome(path, mesh_path=mesh_path, parameters=values, selection=selection,
                          seed=seed)
    report_selection(outcome.run)
    check_outcome(outcome, values)
    mesh, others = current_mesh(outcome.scene), snapshot_others(outcome.scene)
    if mesh is None:
        return None, None, others
    arrays = mesh_arrays(mesh)
    return arrays, _patch_preview(arrays, others) if want_preview else None, others


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``livemod view`` or ``livemod render`` (the ``livemod`` command line)."""
    from livemod.cli import main as livemod_main

    return livemod_main(argv)
